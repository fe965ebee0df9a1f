//! `ElementId`: the id of an element of the building (obstacle, door, zone, vertical
//! connection), in IFC its GlobalId, on hand-built floors any text. A type of its own so an id
//! is not mistaken for a name; it serialises as the plain string, and maps keyed by it look up
//! by `&str`.

use std::borrow::Borrow;
use std::fmt;
use std::ops::Deref;

use serde::{Deserialize, Serialize};

/// The id of an element of the building: its IFC GlobalId (the bridge converts
/// `poinav_ifc`'s), or a made-up one on hand-built floors. Not checked here: this crate knows
/// no IFC.
#[derive(Debug, Clone, Default, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(transparent)]
pub struct ElementId(String);

impl ElementId {
    /// The id `id`.
    pub fn new(id: impl Into<String>) -> ElementId {
        ElementId(id.into())
    }

    /// The id as text.
    pub fn as_str(&self) -> &str {
        &self.0
    }

    /// The id as an owned `String`.
    pub fn into_string(self) -> String {
        self.0
    }
}

impl fmt::Display for ElementId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl Deref for ElementId {
    type Target = str;

    fn deref(&self) -> &str {
        &self.0
    }
}

impl Borrow<str> for ElementId {
    fn borrow(&self) -> &str {
        &self.0
    }
}

impl AsRef<str> for ElementId {
    fn as_ref(&self) -> &str {
        &self.0
    }
}

impl From<String> for ElementId {
    fn from(id: String) -> ElementId {
        ElementId(id)
    }
}

impl From<&str> for ElementId {
    fn from(id: &str) -> ElementId {
        ElementId(id.to_string())
    }
}

impl From<&String> for ElementId {
    fn from(id: &String) -> ElementId {
        ElementId(id.clone())
    }
}

impl From<ElementId> for String {
    fn from(id: ElementId) -> String {
        id.0
    }
}

impl PartialEq<str> for ElementId {
    fn eq(&self, other: &str) -> bool {
        self.0 == other
    }
}

impl PartialEq<&str> for ElementId {
    fn eq(&self, other: &&str) -> bool {
        self.0 == *other
    }
}

impl PartialEq<String> for ElementId {
    fn eq(&self, other: &String) -> bool {
        &self.0 == other
    }
}

impl PartialEq<ElementId> for str {
    fn eq(&self, other: &ElementId) -> bool {
        self == other.0
    }
}

impl PartialEq<ElementId> for &str {
    fn eq(&self, other: &ElementId) -> bool {
        *self == other.0
    }
}

impl PartialEq<ElementId> for String {
    fn eq(&self, other: &ElementId) -> bool {
        *self == other.0
    }
}

#[cfg(test)]
mod tests {
    use std::collections::{BTreeMap, HashMap};

    use super::*;

    #[test]
    fn an_id_is_its_text_in_json_display_and_map_lookups() {
        let id = ElementId::from("2O2Fr$t4X7Zf8NOew3FLOH");
        assert_eq!(
            serde_json::to_string(&id).unwrap(),
            "\"2O2Fr$t4X7Zf8NOew3FLOH\""
        );
        let back: ElementId = serde_json::from_str("\"2O2Fr$t4X7Zf8NOew3FLOH\"").unwrap();
        assert_eq!(back, id);
        assert_eq!(id.to_string(), "2O2Fr$t4X7Zf8NOew3FLOH");
        assert_eq!(id.as_str().len(), 22);
        assert_eq!(id, "2O2Fr$t4X7Zf8NOew3FLOH");
        assert_eq!("2O2Fr$t4X7Zf8NOew3FLOH", id);
        assert_ne!(id, "2O2Fr$t4X7Zf8NOew3FLOh");
        let by_id: BTreeMap<ElementId, u32> = [(id.clone(), 7), ("a".into(), 1)].into();
        assert_eq!(by_id.get("2O2Fr$t4X7Zf8NOew3FLOH"), Some(&7));
        let hashed: HashMap<ElementId, u32> = [(id.clone(), 7)].into();
        assert_eq!(hashed.get("2O2Fr$t4X7Zf8NOew3FLOH"), Some(&7));
        assert_eq!(hashed.get("other"), None);
        // Ordered as its text is.
        let mut ids: Vec<ElementId> = ["b", "a", "B"].map(ElementId::from).into();
        ids.sort();
        assert_eq!(ids, ["B", "a", "b"]);
    }
}
