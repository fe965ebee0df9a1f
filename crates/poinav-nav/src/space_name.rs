//! Which space a user's words select: a GlobalId, or a Name or LongName, optionally on one
//! storey (`Name@Storey`). A name that fits several spaces is an error listing every
//! candidate with its storey, its GlobalId and a selector that picks exactly it; never a guess.

use std::fmt;

use crate::building::Building;
use crate::floor::FloorZone;
use crate::{NavError, ZoneIdx};
use poinav_floor::ElementId;

/// A space of a [`Building`]: storey index and zone index on it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct SpaceRef {
    /// Index in [`Building::floors`].
    pub floor: usize,
    /// Index in that floor's [`crate::Floor::zones`].
    pub zone: ZoneIdx,
}

/// One of the spaces an ambiguous name fits.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Candidate {
    /// The space.
    pub space: SpaceRef,
    /// What to type to select exactly this space: its Name or LongName when no other space
    /// has it, else `Name@Storey` when unique on its storey, else its GlobalId.
    pub selector: String,
    /// Name.
    pub name: Option<String>,
    /// LongName.
    pub long_name: Option<String>,
    /// Storey name.
    pub storey: String,
    /// GlobalId.
    pub global_id: ElementId,
}

/// A name that fits several spaces.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Ambiguous {
    /// The name as given (with `@Storey` when given).
    pub name: String,
    /// Every space it fits, in storey and file order.
    pub candidates: Vec<Candidate>,
}

impl fmt::Display for Ambiguous {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "`{}` is ambiguous: {} spaces have that Name or LongName; name one of them as shown (a Name or LongName no other space has, `Name@Storey`, or the GlobalId):",
            self.name,
            self.candidates.len()
        )?;
        for c in &self.candidates {
            write!(
                f,
                "\n  {}  (Name {}, LongName {}, storey `{}`, GlobalId {})",
                c.selector,
                c.name.as_deref().unwrap_or("-"),
                c.long_name.as_deref().unwrap_or("-"),
                c.storey,
                c.global_id
            )?;
        }
        Ok(())
    }
}

fn named(z: &FloorZone, name: &str) -> bool {
    z.name.as_deref() == Some(name) || z.long_name.as_deref() == Some(name)
}

/// Selecting spaces and storeys of a [`Building`] by the names users type.
pub trait SpaceNames {
    /// Every space, in storey and file order.
    fn spaces(&self) -> impl Iterator<Item = (SpaceRef, &FloorZone)>;

    /// The space `s`.
    fn space(&self, s: SpaceRef) -> &FloorZone;

    /// The spaces `name` fits on storey `floor` (every storey when `None`): the one whose
    /// GlobalId it is, else every space with that Name or LongName.
    fn spaces_named(&self, name: &str, floor: Option<usize>) -> Vec<SpaceRef>;

    /// What to type to select exactly space `s` (see [`Candidate::selector`]).
    fn space_selector(&self, s: SpaceRef) -> String;

    /// The index of the storey named `name`; [`NavError::NotFound`] listing the storeys when
    /// none has that name.
    fn find_storey(&self, name: &str) -> Result<usize, NavError>;

    /// The one space `text` selects: a GlobalId, Name or LongName, optionally `@Storey`
    /// (see [`SpaceNames::find_space`]).
    fn select_space(&self, text: &str) -> Result<SpaceRef, NavError>;

    /// The one space `name` selects on storey `floor` (any storey when `None`; `storey` is the
    /// storey's name as given, for messages): a GlobalId, or a Name or LongName that exactly
    /// one space there has. [`NavError::NotFound`] when none fits (naming spaces whose names
    /// differ only in case), [`NavError::Ambiguous`] listing the candidates when several do.
    fn find_space(
        &self,
        name: &str,
        floor: Option<usize>,
        storey: Option<&str>,
    ) -> Result<SpaceRef, NavError>;
}

impl SpaceNames for Building {
    fn spaces(&self) -> impl Iterator<Item = (SpaceRef, &FloorZone)> {
        self.floors.iter().enumerate().flat_map(|(floor, f)| {
            f.zones.iter().enumerate().map(move |(zone, z)| {
                let zone = ZoneIdx::new(zone);
                (SpaceRef { floor, zone }, z)
            })
        })
    }

    fn space(&self, s: SpaceRef) -> &FloorZone {
        &self.floors[s.floor].zones[s.zone.get()]
    }

    fn spaces_named(&self, name: &str, floor: Option<usize>) -> Vec<SpaceRef> {
        let on = |s: &SpaceRef| floor.is_none_or(|f| f == s.floor);
        let by_id: Vec<SpaceRef> = self
            .spaces()
            .filter(|(s, z)| on(s) && z.id == name)
            .map(|(s, _)| s)
            .collect();
        if !by_id.is_empty() {
            return by_id;
        }
        self.spaces()
            .filter(|(s, z)| on(s) && named(z, name))
            .map(|(s, _)| s)
            .collect()
    }

    fn space_selector(&self, s: SpaceRef) -> String {
        let z = self.space(s);
        let storey = &self.floors[s.floor].name;
        let unique_storey = self.floors.iter().filter(|f| &f.name == storey).count() == 1;
        for n in [&z.name, &z.long_name].into_iter().flatten() {
            if self.spaces_named(n, None) == [s] {
                return n.clone();
            }
        }
        if unique_storey {
            for n in [&z.name, &z.long_name].into_iter().flatten() {
                if self.spaces_named(n, Some(s.floor)) == [s] {
                    return format!("{n}@{storey}");
                }
            }
        }
        z.id.to_string()
    }

    fn find_storey(&self, name: &str) -> Result<usize, NavError> {
        self.floor_index(name).ok_or_else(|| {
            let all: Vec<&str> = self.floors.iter().map(|f| f.name.as_str()).collect();
            NavError::NotFound(format!(
                "no storey named `{name}`; storeys: {}",
                all.join(", ")
            ))
        })
    }

    fn select_space(&self, text: &str) -> Result<SpaceRef, NavError> {
        let (name, storey) = match text.rsplit_once('@') {
            Some((n, s)) => (n.trim(), Some(s.trim())),
            None => (text.trim(), None),
        };
        let floor = storey.map(|s| self.find_storey(s)).transpose()?;
        self.find_space(name, floor, storey)
    }

    fn find_space(
        &self,
        name: &str,
        floor: Option<usize>,
        storey: Option<&str>,
    ) -> Result<SpaceRef, NavError> {
        let hits = self.spaces_named(name, floor);
        let given = match storey {
            Some(s) => format!("{name}@{s}"),
            None => name.to_string(),
        };
        match hits.as_slice() {
            [one] => Ok(*one),
            [] => {
                let on = |s: &SpaceRef| floor.is_none_or(|f| f == s.floor);
                let spaces = self.spaces().filter(|(s, _)| on(s)).count();
                let mut near: Vec<String> = self
                    .spaces()
                    .filter(|(s, _)| on(s))
                    .flat_map(|(_, z)| [&z.name, &z.long_name])
                    .flatten()
                    .filter(|n| n.eq_ignore_ascii_case(name))
                    .cloned()
                    .collect();
                near.sort();
                near.dedup();
                let hint = if spaces == 0 {
                    " (the model has no spaces there: give a point, `x,y@Storey`)".to_string()
                } else if !near.is_empty() {
                    format!(
                        " (names are case-sensitive: {})",
                        near.iter()
                            .map(|n| format!("`{n}`"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    )
                } else {
                    String::new()
                };
                Err(NavError::NotFound(format!(
                    "no space named `{name}`{}{hint}",
                    match storey {
                        Some(s) => format!(" on storey `{s}`"),
                        None => String::new(),
                    }
                )))
            }
            many => Err(NavError::Ambiguous(Box::new(Ambiguous {
                name: given,
                candidates: many
                    .iter()
                    .map(|&s| {
                        let z = self.space(s);
                        Candidate {
                            space: s,
                            selector: self.space_selector(s),
                            name: z.name.clone(),
                            long_name: z.long_name.clone(),
                            storey: self.floors[s.floor].name.clone(),
                            global_id: z.id.clone(),
                        }
                    })
                    .collect(),
            }))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floor::Floor;

    fn zone(id: &str, name: &str, long: &str) -> FloorZone {
        FloorZone {
            id: id.into(),
            name: Some(name.into()),
            long_name: Some(long.into()),
            ring: Default::default(),
            roles: Vec::new(),
            coordination: None,
        }
    }

    fn building() -> Building {
        let floor = |name: &str, zones| Floor {
            name: name.into(),
            zones,
            ..Floor::default()
        };
        Building {
            floors: vec![
                floor(
                    "Level 1",
                    vec![
                        zone("g1", "101", "OFFICE"),
                        zone("g2", "102", "SERVER RM"),
                        zone("g3", "103", "SERVER RM"),
                        zone("g4", "104", "CORRIDOR"),
                    ],
                ),
                floor(
                    "Level 2",
                    vec![zone("g5", "201", "CORRIDOR"), zone("g6", "101", "STORE")],
                ),
            ],
            connections: Vec::new(),
            levels: Vec::new(),
        }
    }

    #[test]
    fn a_unique_name_a_global_id_or_name_at_storey_selects_one_space() {
        let b = building();
        let at = |floor, zone| SpaceRef {
            floor,
            zone: ZoneIdx::new(zone),
        };
        assert_eq!(b.find_space("OFFICE", None, None).unwrap(), at(0, 0));
        assert_eq!(b.find_space("g3", None, None).unwrap(), at(0, 2));
        assert_eq!(
            b.find_space("CORRIDOR", Some(1), Some("Level 2")).unwrap(),
            at(1, 0)
        );
        assert_eq!(
            b.find_space("101", Some(1), Some("Level 2")).unwrap(),
            at(1, 1)
        );
        assert_eq!(b.select_space("101@Level 2").unwrap(), at(1, 1));
        assert_eq!(
            b.select_space("101@Level 3").unwrap_err().to_string(),
            "no storey named `Level 3`; storeys: Level 1, Level 2"
        );
        // The selector each candidate shows selects it.
        let sel: Vec<String> = b.spaces().map(|(s, _)| b.space_selector(s)).collect();
        assert_eq!(
            sel,
            ["OFFICE", "102", "103", "104", "201", "STORE"],
            "a unique Name or LongName first"
        );
    }

    #[test]
    fn an_ambiguous_name_lists_every_candidate_with_storey_and_global_id() {
        let b = building();
        let Err(NavError::Ambiguous(a)) = b.find_space("SERVER RM", None, None) else {
            panic!("ambiguous");
        };
        assert_eq!(
            a.to_string(),
            "`SERVER RM` is ambiguous: 2 spaces have that Name or LongName; name one of them as shown (a Name or LongName no other space has, `Name@Storey`, or the GlobalId):\n  102  (Name 102, LongName SERVER RM, storey `Level 1`, GlobalId g2)\n  103  (Name 103, LongName SERVER RM, storey `Level 1`, GlobalId g3)"
        );
        let Err(NavError::Ambiguous(a)) = b.find_space("101", None, None) else {
            panic!("ambiguous");
        };
        let sel: Vec<&str> = a.candidates.iter().map(|c| c.selector.as_str()).collect();
        assert_eq!(sel, ["OFFICE", "STORE"]);
        // Two spaces with the same names on one storey: only the GlobalId tells them apart.
        let mut twins = building();
        twins.floors[0].zones.push(zone("g7", "104", "CORRIDOR"));
        let Err(NavError::Ambiguous(a)) = twins.find_space("104", Some(0), Some("Level 1")) else {
            panic!("ambiguous");
        };
        assert_eq!(a.name, "104@Level 1");
        let sel: Vec<&str> = a.candidates.iter().map(|c| c.selector.as_str()).collect();
        assert_eq!(sel, ["g4", "g7"]);
    }

    #[test]
    fn an_unknown_name_says_so_and_names_spaces_differing_in_case() {
        let b = building();
        let e = b.find_space("corridor", None, None).unwrap_err();
        assert!(matches!(e, NavError::NotFound(_)));
        assert_eq!(
            e.to_string(),
            "no space named `corridor` (names are case-sensitive: `CORRIDOR`)"
        );
        assert_eq!(
            b.find_space("OFFICE", Some(1), Some("Level 2"))
                .unwrap_err()
                .to_string(),
            "no space named `OFFICE` on storey `Level 2`"
        );
    }
}
