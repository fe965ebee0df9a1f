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

/// The storey `e` belongs to, walking up containment and aggregation.
pub fn storey_of<'m>(e: Entity<'m>) -> Option<Entity<'m>> {
    let mut cur = parent_of(e)?;
    for _ in 0..MAX_DEPTH {
        if cur.is_a("IfcBuildingStorey") {
            return Some(cur);
        }
        cur = parent_of(cur)?;
    }
    None
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
