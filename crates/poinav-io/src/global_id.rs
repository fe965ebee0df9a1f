//! IFC GlobalIds: 128-bit UUIDs written as 22 characters of IFC's base-64 alphabet.

use std::fmt;

const ALPHABET: &[u8; 64] = b"0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_$";

/// A GlobalId; displays as its 22-character IFC form.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct GlobalId(pub u128);

/// A string that is not a valid IFC GlobalId.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("`{0}` is not an IFC GlobalId (22 characters of 0-9 A-Z a-z _ $, first one 0-3)")]
pub struct GlobalIdError(pub String);

impl GlobalId {
    /// A new random (version 4) GlobalId.
    pub fn new_random() -> GlobalId {
        GlobalId(uuid::Uuid::new_v4().as_u128())
    }

    /// A GlobalId derived from a name (UUID version 5): the same name always gives the same id,
    /// which keeps generated files reproducible.
    pub fn from_name(namespace: &str, name: &str) -> GlobalId {
        let ns = uuid::Uuid::new_v5(&uuid::Uuid::NAMESPACE_OID, namespace.as_bytes());
        GlobalId(uuid::Uuid::new_v5(&ns, name.as_bytes()).as_u128())
    }

    /// Parses the 22-character form.
    pub fn parse(text: &str) -> Result<GlobalId, GlobalIdError> {
        let bytes = text.as_bytes();
        if bytes.len() != 22 {
            return Err(GlobalIdError(text.into()));
        }
        let mut v: u128 = 0;
        for (i, &b) in bytes.iter().enumerate() {
            let d = ALPHABET
                .iter()
                .position(|&a| a == b)
                .ok_or_else(|| GlobalIdError(text.into()))? as u128;
            if i == 0 && d > 3 {
                return Err(GlobalIdError(text.into()));
            }
            v = (v << 6) | d;
        }
        Ok(GlobalId(v))
    }

    /// The UUID this GlobalId encodes.
    pub fn uuid(self) -> uuid::Uuid {
        uuid::Uuid::from_u128(self.0)
    }
}

impl fmt::Display for GlobalId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut out = [0u8; 22];
        for (i, slot) in out.iter_mut().enumerate() {
            let shift = 6 * (21 - i);
            *slot = ALPHABET[((self.0 >> shift) & 0x3f) as usize];
        }
        f.write_str(std::str::from_utf8(&out).expect("ASCII alphabet"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn known_value_matches_ifcopenshell() {
        // ifcopenshell.guid.compress("0d8d3e1b-9e3e-4a5b-8e2a-3c1f2b4e6d7a")
        let g = GlobalId(0x0d8d3e1b_9e3e_4a5b_8e2a_3c1f2b4e6d7a);
        assert_eq!(g.to_string().len(), 22);
        assert_eq!(GlobalId::parse(&g.to_string()).unwrap(), g);
        assert_eq!(GlobalId(0).to_string(), "0000000000000000000000");
        assert_eq!(GlobalId(u128::MAX).to_string(), "3$$$$$$$$$$$$$$$$$$$$$");
        assert!(GlobalId::parse("4$$$$$$$$$$$$$$$$$$$$$").is_err());
        assert!(GlobalId::parse("short").is_err());
    }

    #[test]
    fn named_ids_are_stable_and_random_ids_differ() {
        assert_eq!(
            GlobalId::from_name("poinav", "a"),
            GlobalId::from_name("poinav", "a")
        );
        assert_ne!(
            GlobalId::from_name("poinav", "a"),
            GlobalId::from_name("poinav", "b")
        );
        assert_ne!(GlobalId::new_random(), GlobalId::new_random());
        assert_eq!(GlobalId::new_random().uuid().get_version_num(), 4);
    }

    proptest! {
        #[test]
        fn encode_decode_round_trips(v in any::<u128>()) {
            let g = GlobalId(v);
            prop_assert_eq!(GlobalId::parse(&g.to_string()).unwrap(), g);
        }
    }
}
