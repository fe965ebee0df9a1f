//! Typed indices into a floor's lists ([`ZoneIdx`] into `Floor::zones`, [`DoorIdx`] into
//! `Floor::doors`, [`ObstacleIdx`] into `Floor::obstacles`), serialised as the plain index:
//! `Option<ZoneIdx>` says "no zone" where a bare `u32` needed a sentinel, and takes the same 4
//! bytes (the index is stored plus one in a `NonZeroU32`, so `None` is the niche), which
//! matters where a grid holds one per cell.

use std::fmt;
use std::num::NonZeroU32;

macro_rules! index_type {
    ($(#[$doc:meta])* $name:ident, $list:literal) => {
        $(#[$doc])*
        #[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub struct $name(NonZeroU32);

        impl $name {
            /// The index `i`; panics when `i` is `u32::MAX - 1` or more (grids and floors
            /// are bounded far below that).
            #[inline]
            pub fn new(i: usize) -> $name {
                u32::try_from(i)
                    .ok()
                    .and_then(|i| i.checked_add(1))
                    .and_then(NonZeroU32::new)
                    .map($name)
                    .unwrap_or_else(|| panic!("{} index {i} out of range", $list))
            }

            /// The index.
            #[inline]
            pub fn get(self) -> usize {
                (self.0.get() - 1) as usize
            }
        }

        impl fmt::Debug for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "{}({})", stringify!($name), self.get())
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "{}", self.get())
            }
        }

        /// Serialised as the plain index, as a `usize` is.
        impl serde::Serialize for $name {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_u64(self.get() as u64)
            }
        }
    };
}

index_type!(
    /// An index into `Floor::zones`.
    ZoneIdx,
    "zone"
);
index_type!(
    /// An index into `Floor::doors`.
    DoorIdx,
    "door"
);
index_type!(
    /// An index into `Floor::obstacles`.
    ObstacleIdx,
    "obstacle"
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn options_of_indices_take_four_bytes_and_keep_the_order() {
        assert_eq!(std::mem::size_of::<Option<ZoneIdx>>(), 4);
        assert_eq!(std::mem::size_of::<Option<DoorIdx>>(), 4);
        assert_eq!(ZoneIdx::new(0).get(), 0);
        assert_eq!(DoorIdx::new(41).get(), 41);
        assert_eq!(
            ZoneIdx::new(u32::MAX as usize - 1).get(),
            u32::MAX as usize - 1
        );
        assert!(ZoneIdx::new(3) < ZoneIdx::new(4));
        assert_eq!(
            format!("{:?} {}", DoorIdx::new(7), ZoneIdx::new(2)),
            "DoorIdx(7) 2"
        );
        assert_eq!(std::mem::size_of::<Option<ObstacleIdx>>(), 4);
        // Serialised as a usize is: the index itself.
        assert_eq!(
            serde_json::to_string(&[Some(ZoneIdx::new(0)), None]).unwrap(),
            serde_json::to_string(&[Some(0usize), None]).unwrap()
        );
        assert_eq!(serde_json::to_string(&DoorIdx::new(12)).unwrap(), "12");
    }

    #[test]
    #[should_panic(expected = "zone index")]
    fn an_index_past_u32_is_refused() {
        ZoneIdx::new(u32::MAX as usize);
    }
}
