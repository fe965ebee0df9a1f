//! The IFC schemas poinav reads (IFC2X3, IFC4, IFC4X3_ADD2): entity lookup, subtype tests,
//! attribute positions and inverse relations, from tables generated out of `shared/schema`.

use std::sync::OnceLock;

use rustc_hash::FxHashMap;

#[rustfmt::skip]
mod ifc2x3;
#[rustfmt::skip]
mod ifc4;
#[rustfmt::skip]
mod ifc4x3_add2;

/// One explicit attribute of an entity, in STEP order.
#[derive(Debug)]
pub struct AttrDef {
    /// Attribute name as in the schema, e.g. `OverallWidth`.
    pub name: &'static str,
    /// Declared type name, e.g. `IfcPositiveLengthMeasure`.
    pub ty: &'static str,
    /// Whether `$` is allowed.
    pub optional: bool,
}

/// An inverse relation, e.g. `IsDefinedBy` = `IfcRelDefinesByProperties.RelatedObjects`.
#[derive(Debug)]
pub struct InverseDef {
    /// Inverse name, e.g. `IsDefinedBy`.
    pub name: &'static str,
    /// Index of the relating entity in the same schema table.
    pub(crate) entity: u16,
    /// The forward attribute of `entity` that points back.
    pub attribute: &'static str,
}

/// One entity declaration. Only the entity's own attributes and inverses are stored;
/// inherited ones come from the supertype chain.
#[derive(Debug)]
pub struct EntityDef {
    /// CamelCase name, e.g. `IfcWallStandardCase`.
    pub name: &'static str,
    /// Upper-case STEP name, e.g. `IFCWALLSTANDARDCASE`.
    pub upper: &'static str,
    pub(crate) supertype: Option<u16>,
    /// Abstract entities never appear as instances.
    pub is_abstract: bool,
    pub(crate) attr_offset: u16,
    pub(crate) attrs: &'static [AttrDef],
    pub(crate) derived: &'static [u16],
    pub(crate) inverses: &'static [InverseDef],
}

/// An entity type within one [`Schema`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TypeId(pub(crate) u16);

impl TypeId {
    /// Position in the schema's entity table (sorted by upper-case name).
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// The IFC schema versions poinav reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Schema {
    /// IFC2X3 TC1.
    Ifc2x3,
    /// IFC4 ADD2 TC1.
    Ifc4,
    /// IFC4.3 ADD2 (also used for IFC4X3 release candidates).
    Ifc4x3Add2,
}

impl Schema {
    /// All supported schemas.
    pub const ALL: [Schema; 3] = [Schema::Ifc2x3, Schema::Ifc4, Schema::Ifc4x3Add2];

    /// The canonical schema identifier as written in `FILE_SCHEMA`.
    pub fn name(self) -> &'static str {
        match self {
            Schema::Ifc2x3 => "IFC2X3",
            Schema::Ifc4 => "IFC4",
            Schema::Ifc4x3Add2 => "IFC4X3_ADD2",
        }
    }

    /// Maps a `FILE_SCHEMA` identifier to a schema. Returns the schema and whether the
    /// identifier was an exact match (`false` for tolerated variants such as `IFC4X3_RC2`).
    pub fn from_identifier(id: &str) -> Option<(Schema, bool)> {
        let up = id.trim().to_ascii_uppercase();
        // Some exporters append a version suffix in braces: `IFC4 {1 0 10303 ...}`.
        let up = up
            .split(|c: char| c.is_whitespace() || c == '{')
            .next()
            .unwrap_or("");
        match up {
            "IFC2X3" => Some((Schema::Ifc2x3, true)),
            "IFC2X3_TC1" => Some((Schema::Ifc2x3, false)),
            "IFC4" => Some((Schema::Ifc4, true)),
            "IFC4_ADD1" | "IFC4_ADD2" | "IFC4_ADD2_TC1" => Some((Schema::Ifc4, false)),
            // IFC4's release candidates (exporters of 2012-2013 wrote `IFC4RC4`): read as IFC4,
            // whose entities they mostly share; attribute-count differences become diagnostics.
            s if s.starts_with("IFC4RC") => Some((Schema::Ifc4, false)),
            "IFC4X3_ADD2" => Some((Schema::Ifc4x3Add2, true)),
            s if s.starts_with("IFC4X3") => Some((Schema::Ifc4x3Add2, false)),
            _ => None,
        }
    }

    pub(crate) fn entities(self) -> &'static [EntityDef] {
        match self {
            Schema::Ifc2x3 => ifc2x3::ENTITIES,
            Schema::Ifc4 => ifc4::ENTITIES,
            Schema::Ifc4x3Add2 => ifc4x3_add2::ENTITIES,
        }
    }

    /// Number of entity declarations.
    pub fn entity_count(self) -> usize {
        self.entities().len()
    }

    /// The declaration of `ty`.
    pub fn entity(self, ty: TypeId) -> &'static EntityDef {
        &self.entities()[ty.index()]
    }

    /// Looks up an entity by its upper-case STEP name (exact bytes, as in instance lines).
    pub fn type_by_upper(self, upper: &[u8]) -> Option<TypeId> {
        static MAPS: [OnceLock<FxHashMap<&'static [u8], u16>>; 3] =
            [OnceLock::new(), OnceLock::new(), OnceLock::new()];
        let map = MAPS[self as usize].get_or_init(|| {
            self.entities()
                .iter()
                .enumerate()
                .map(|(i, e)| (e.upper.as_bytes(), i as u16))
                .collect()
        });
        map.get(upper).map(|&i| TypeId(i))
    }

    /// Looks up an entity by name, ignoring case (`IfcWall`, `IFCWALL`, `ifcwall`).
    pub fn type_by_name(self, name: &str) -> Option<TypeId> {
        if name.bytes().any(|b| b.is_ascii_lowercase()) {
            self.type_by_upper(name.to_ascii_uppercase().as_bytes())
        } else {
            self.type_by_upper(name.as_bytes())
        }
    }

    /// The direct supertype of `ty`.
    pub fn supertype(self, ty: TypeId) -> Option<TypeId> {
        self.entity(ty).supertype.map(TypeId)
    }

    /// `ty` itself followed by all its supertypes up to the root.
    pub fn ancestors(self, ty: TypeId) -> impl Iterator<Item = TypeId> {
        std::iter::successors(Some(ty), move |&t| self.supertype(t))
    }

    /// True when `ty` is `ancestor` or one of its subtypes.
    pub fn is_subtype_of(self, ty: TypeId, ancestor: TypeId) -> bool {
        self.ancestors(ty).any(|t| t == ancestor)
    }

    /// A mask over all types, true for `ancestor` and its subtypes.
    pub fn subtype_mask(self, ancestor: TypeId) -> Vec<bool> {
        (0..self.entity_count())
            .map(|i| self.is_subtype_of(TypeId(i as u16), ancestor))
            .collect()
    }

    /// Number of attributes an instance of `ty` has in STEP (inherited included).
    pub fn attribute_count(self, ty: TypeId) -> usize {
        let e = self.entity(ty);
        e.attr_offset as usize + e.attrs.len()
    }

    /// The attribute at STEP position `index` of `ty`, and whether `ty` redefines it as derived (`*`).
    pub fn attribute(self, ty: TypeId, index: usize) -> Option<(&'static AttrDef, bool)> {
        let derived = self.entity(ty).derived.iter().any(|&d| d as usize == index);
        for t in self.ancestors(ty) {
            let e = self.entity(t);
            let off = e.attr_offset as usize;
            if index >= off {
                return e.attrs.get(index - off).map(|a| (a, derived));
            }
        }
        None
    }

    /// STEP position of the attribute called `name` (exact case) on `ty`.
    pub fn attribute_index(self, ty: TypeId, name: &str) -> Option<usize> {
        self.ancestors(ty).find_map(|t| {
            let e = self.entity(t);
            e.attrs
                .iter()
                .position(|a| a.name == name)
                .map(|p| e.attr_offset as usize + p)
        })
    }

    /// The inverse relation `name` declared on `ty` or a supertype, with the relating type.
    pub fn inverse(self, ty: TypeId, name: &str) -> Option<(&'static InverseDef, TypeId)> {
        self.ancestors(ty).find_map(|t| {
            self.entity(t)
                .inverses
                .iter()
                .find(|i| i.name == name)
                .map(|i| (i, TypeId(i.entity)))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_are_sorted_for_lookup() {
        for s in Schema::ALL {
            let e = s.entities();
            assert!(e.windows(2).all(|w| w[0].upper < w[1].upper), "{s:?}");
            assert!(e.len() > 600);
        }
    }

    #[test]
    fn subtype_tests_follow_the_schema() {
        let s = Schema::Ifc2x3;
        let wall = s.type_by_name("IfcWall").unwrap();
        let std = s.type_by_name("IFCWALLSTANDARDCASE").unwrap();
        let product = s.type_by_name("IfcProduct").unwrap();
        assert!(s.is_subtype_of(std, wall));
        assert!(s.is_subtype_of(std, product));
        assert!(!s.is_subtype_of(wall, std));
        assert_eq!(
            s.type_by_name("IfcFurniture"),
            None,
            "IfcFurniture is IFC4+"
        );
        assert!(Schema::Ifc4.type_by_name("IfcFurniture").is_some());
    }

    #[test]
    fn attribute_positions_match_step_order() {
        for s in Schema::ALL {
            let door = s.type_by_name("IfcDoor").unwrap();
            assert_eq!(s.attribute_index(door, "GlobalId"), Some(0));
            assert_eq!(s.attribute_index(door, "OverallHeight"), Some(8));
            assert_eq!(s.attribute_index(door, "OverallWidth"), Some(9));
            assert_eq!(s.attribute(door, 9).unwrap().0.name, "OverallWidth");
        }
        assert_eq!(
            Schema::Ifc2x3.attribute_count(Schema::Ifc2x3.type_by_name("IfcDoor").unwrap()),
            10
        );
        assert_eq!(
            Schema::Ifc4.attribute_count(Schema::Ifc4.type_by_name("IfcDoor").unwrap()),
            13
        );
        let si = Schema::Ifc4.type_by_name("IfcSIUnit").unwrap();
        assert_eq!(
            Schema::Ifc4.attribute(si, 0).map(|(a, d)| (a.name, d)),
            Some(("Dimensions", true))
        );
    }

    #[test]
    fn inverses_are_inherited() {
        let s = Schema::Ifc4;
        let door = s.type_by_name("IfcDoor").unwrap();
        let (inv, rel) = s.inverse(door, "IsDefinedBy").unwrap();
        assert_eq!(inv.attribute, "RelatedObjects");
        assert_eq!(s.entity(rel).name, "IfcRelDefinesByProperties");
        assert!(s.inverse(door, "FillsVoids").is_some());
    }

    #[test]
    fn schema_identifiers_tolerate_release_candidates() {
        assert_eq!(
            Schema::from_identifier("IFC4X3_RC2"),
            Some((Schema::Ifc4x3Add2, false))
        );
        assert_eq!(
            Schema::from_identifier("ifc2x3"),
            Some((Schema::Ifc2x3, true))
        );
        assert_eq!(
            Schema::from_identifier("IFC4RC4"),
            Some((Schema::Ifc4, false))
        );
        assert_eq!(Schema::from_identifier("IFC2X2_FINAL"), None);
        assert_eq!(Schema::from_identifier("IFC4X1"), None);
    }
}
