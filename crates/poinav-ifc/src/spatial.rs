//! The spatial hierarchy: project, sites, buildings, storeys (by elevation) and spaces, and
//! where each element sits in it (containment, aggregation, or the wall a door fills).

use crate::entity::Entity;
use crate::model::Model;
use crate::units::LengthUnit;
use crate::EntityId;

/// How far up the hierarchy a walk goes before it gives up (guards damaged, cyclic files).
const MAX_DEPTH: usize = 32;

/// A building storey.
#[derive(Debug, Clone, PartialEq)]
pub struct Storey {
    /// The storey instance.
    pub id: EntityId,
    /// Its GlobalId.
    pub global_id: Option<String>,
    /// Its Name.
    pub name: Option<String>,
    /// Elevation in metres, when given.
    pub elevation_m: Option<f64>,
}

impl Storey {
    /// What to call the storey: its Name, else its GlobalId, else `Storey #id`.
    pub fn label(&self) -> String {
        storey_label(self.name.as_deref(), self.global_id.as_deref(), self.id)
    }
}

/// What to call storey `e` (see [`Storey::label`]).
pub fn label_of(e: Entity<'_>) -> String {
    storey_label(e.name().as_deref(), e.global_id().as_deref(), e.id())
}

fn storey_label(name: Option<&str>, global_id: Option<&str>, id: EntityId) -> String {
    match (name, global_id) {
        (Some(n), _) if !n.trim().is_empty() => n.to_string(),
        (_, Some(g)) if !g.is_empty() => g.to_string(),
        _ => format!("Storey {id}"),
    }
}

/// A space (room, corridor, ...).
#[derive(Debug, Clone, PartialEq)]
pub struct Space {
    /// The space instance.
    pub id: EntityId,
    /// Its GlobalId.
    pub global_id: Option<String>,
    /// Its Name (often a number).
    pub name: Option<String>,
    /// Its LongName (often the room's function).
    pub long_name: Option<String>,
    /// The storey it belongs to, if any.
    pub storey: Option<EntityId>,
}

/// The spatial structure of a model.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SpatialStructure {
    /// The IfcProject, if present.
    pub project: Option<EntityId>,
    /// IfcSite instances.
    pub sites: Vec<EntityId>,
    /// IfcBuilding instances.
    pub buildings: Vec<EntityId>,
    /// Storeys sorted by elevation (storeys without one last), then name.
    pub storeys: Vec<Storey>,
    /// Spaces in file order.
    pub spaces: Vec<Space>,
}

/// One step up: the spatial container, the aggregate whole, or the element whose opening this fills.
pub fn parent_of<'m>(e: Entity<'m>) -> Option<Entity<'m>> {
    if let Some(p) = e
        .inverse("ContainedInStructure")
        .iter()
        .find_map(|r| r.get_ref("RelatingStructure"))
    {
        return Some(p);
    }
    if let Some(p) = e
        .inverse("Decomposes")
        .iter()
        .find_map(|r| r.get_ref("RelatingObject"))
    {
        return Some(p);
    }
    if let Some(p) = e
        .inverse("Nests")
        .iter()
        .find_map(|r| r.get_ref("RelatingObject"))
    {
        return Some(p);
    }
    if let Some(opening) = e
        .inverse("FillsVoids")
        .iter()
        .find_map(|r| r.get_ref("RelatingOpeningElement"))
    {
        return opening
            .inverse("VoidsElements")
            .iter()
            .find_map(|r| r.get_ref("RelatingBuildingElement"));
    }
    if e.is_a("IfcOpeningElement") {
        return e
            .inverse("VoidsElements")
            .iter()
            .find_map(|r| r.get_ref("RelatingBuildingElement"));
    }
    None
}

/// The storey `e` belongs to, walking up containment and aggregation; when the walk ends at a
/// whole whose own place is not given (a stair in no storey whose flights are), the lowest
/// storey of that whole's parts.
pub fn storey_of<'m>(e: Entity<'m>) -> Option<Entity<'m>> {
    let (found, top) = walk_up(e);
    found.or_else(|| {
        top.inverse("IsDecomposedBy")
            .iter()
            .flat_map(|r| r.get_refs("RelatedObjects"))
            .filter_map(|part| walk_up(part).0)
            .min_by(|a, b| {
                let z = |s: &Entity<'m>| s.get_f64("Elevation").unwrap_or(f64::INFINITY);
                z(a).total_cmp(&z(b)).then(a.id().cmp(&b.id()))
            })
    })
}

/// The first storey up from `e`, and the last element the walk reached.
fn walk_up<'m>(e: Entity<'m>) -> (Option<Entity<'m>>, Entity<'m>) {
    let mut cur = e;
    for _ in 0..MAX_DEPTH {
        match parent_of(cur) {
            Some(p) if p.is_a("IfcBuildingStorey") => return (Some(p), p),
            Some(p) => cur = p,
            None => break,
        }
    }
    (None, cur)
}

/// Reads the spatial structure; `unit` converts storey elevations to metres.
pub fn spatial_structure(model: &Model, unit: &LengthUnit) -> SpatialStructure {
    let ids = |name: &str| {
        model
            .instances_of(name)
            .iter()
            .map(Entity::id)
            .collect::<Vec<_>>()
    };
    let mut storeys: Vec<Storey> = model
        .instances_of("IfcBuildingStorey")
        .into_iter()
        .map(|s| Storey {
            id: s.id(),
            global_id: s.global_id(),
            name: s.name(),
            elevation_m: s.get_f64("Elevation").map(|v| unit.to_metres(v)),
        })
        .collect();
    storeys.sort_by(|a, b| {
        let ka = a.elevation_m.unwrap_or(f64::INFINITY);
        let kb = b.elevation_m.unwrap_or(f64::INFINITY);
        ka.total_cmp(&kb)
            .then_with(|| a.name.cmp(&b.name))
            .then_with(|| a.id.cmp(&b.id))
    });
    let spaces = model
        .instances_of("IfcSpace")
        .into_iter()
        .map(|s| Space {
            id: s.id(),
            global_id: s.global_id(),
            name: s.name(),
            long_name: s.get_str("LongName"),
            storey: storey_of(s).map(|st| st.id()),
        })
        .collect();
    SpatialStructure {
        project: model.instances_of("IfcProject").first().map(Entity::id),
        sites: ids("IfcSite"),
        buildings: ids("IfcBuilding"),
        storeys,
        spaces,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model(data: &str) -> Model {
        let text = format!(
            "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n{data}\nENDSEC;END-ISO-10303-21;"
        );
        Model::from_bytes("spatial.ifc", text.into_bytes()).unwrap()
    }

    #[test]
    fn a_stair_placed_only_through_its_flights_takes_their_lowest_storey() {
        // #10 "Upper" at 3 m, #11 unnamed at 0 m; the stair #20 is in no storey, its flights
        // #21 (upper) and #22 (ground) are; the railing #30 is in the stair.
        let m = model(
            "#10=IFCBUILDINGSTOREY('0000000000000000000010',$,'Upper',$,$,$,$,$,.ELEMENT.,3.);\
             #11=IFCBUILDINGSTOREY('0000000000000000000011',$,$,$,$,$,$,$,.ELEMENT.,0.);\
             #20=IFCSTAIR('0000000000000000000020',$,'Stair',$,$,$,$,$,$);\
             #21=IFCSTAIRFLIGHT('0000000000000000000021',$,'F1',$,$,$,$,$,$,$,$,$,$);\
             #22=IFCSTAIRFLIGHT('0000000000000000000022',$,'F2',$,$,$,$,$,$,$,$,$,$);\
             #23=IFCRELAGGREGATES('0000000000000000000023',$,$,$,#20,(#21,#22));\
             #24=IFCRELCONTAINEDINSPATIALSTRUCTURE('0000000000000000000024',$,$,$,(#21),#10);\
             #25=IFCRELCONTAINEDINSPATIALSTRUCTURE('0000000000000000000025',$,$,$,(#22),#11);\
             #30=IFCRAILING('0000000000000000000030',$,'Rail',$,$,$,$,$,$);\
             #31=IFCRELAGGREGATES('0000000000000000000031',$,$,$,#20,(#30));",
        );
        let e = |id: u64| m.entity(EntityId(id)).unwrap();
        assert_eq!(storey_of(e(21)).map(|s| s.id()), Some(EntityId(10)));
        assert_eq!(storey_of(e(20)).map(|s| s.id()), Some(EntityId(11)));
        // The railing is part of the stair: the stair's storey.
        assert_eq!(storey_of(e(30)).map(|s| s.id()), Some(EntityId(11)));
        assert_eq!(label_of(e(10)), "Upper");
        assert_eq!(label_of(e(11)), "0000000000000000000011");
    }
}
