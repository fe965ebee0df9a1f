//! What a product is in a floor plan ([`PlanItemKind`]): a geometric category (wall, column,
//! furniture, door parts, space, stair, ...), read from its IFC class, its predefined type and
//! the element it is a part of. Not a POI role: those come from the rules in `poinav-poi`.

use poinav_ifc::Entity;
use serde::{Deserialize, Serialize};

/// How far up an aggregation (`IfcRelAggregates`) a part looks for its whole.
const MAX_AGGREGATE_DEPTH: usize = 8;

/// The category of a plan item.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PlanItemKind {
    /// Walls and curtain walls (with their plates and members).
    Wall,
    /// Columns.
    Column,
    /// Any other built element reaching into the band: beams, members, railings, plates,
    /// coverings, slabs that are not floors, footings, building element parts, ...
    Obstacle,
    /// Furniture, equipment, distribution and transport elements, building element proxies
    /// (the classes of the default rules' R4, fixed objects).
    Furniture,
    /// What a door's body puts outside its clear width: linings and frames. Always in the way.
    DoorFrame,
    /// What a door's body puts inside its clear width: the leaf (closed as modelled). In the
    /// way or a passage, depending on the door's accessibility.
    DoorLeaf,
    /// A door's clear passage: its clear width across the depth of its opening.
    DoorOpening,
    /// Windows reaching into the band.
    Window,
    /// Spaces, as regions.
    Space,
    /// Stairs and their flights and landings: their whole projection.
    Stair,
    /// Ramps and their flights and landings: their whole projection.
    Ramp,
}

impl PlanItemKind {
    /// Every kind, in drawing order (regions first, obstacles over them, doors last).
    pub const ALL: [PlanItemKind; 11] = [
        PlanItemKind::Space,
        PlanItemKind::Stair,
        PlanItemKind::Ramp,
        PlanItemKind::Furniture,
        PlanItemKind::Obstacle,
        PlanItemKind::Column,
        PlanItemKind::Wall,
        PlanItemKind::Window,
        PlanItemKind::DoorOpening,
        PlanItemKind::DoorFrame,
        PlanItemKind::DoorLeaf,
    ];

    /// True for what a robot cannot pass whatever the doors' states: walls, columns, other
    /// obstacles, furniture, door frames and windows.
    pub fn is_obstacle(self) -> bool {
        matches!(
            self,
            PlanItemKind::Wall
                | PlanItemKind::Column
                | PlanItemKind::Obstacle
                | PlanItemKind::Furniture
                | PlanItemKind::DoorFrame
                | PlanItemKind::Window
        )
    }

    /// Kebab-case name, as serialised.
    pub fn label(self) -> &'static str {
        match self {
            PlanItemKind::Wall => "wall",
            PlanItemKind::Column => "column",
            PlanItemKind::Obstacle => "obstacle",
            PlanItemKind::Furniture => "furniture",
            PlanItemKind::DoorFrame => "door-frame",
            PlanItemKind::DoorLeaf => "door-leaf",
            PlanItemKind::DoorOpening => "door-opening",
            PlanItemKind::Window => "window",
            PlanItemKind::Space => "space",
            PlanItemKind::Stair => "stair",
            PlanItemKind::Ramp => "ramp",
        }
    }
}

/// What a product is drawn as, or `None` when it is left out of plans: openings, virtual
/// elements, floor slabs (`FLOOR`, `BASESLAB`) and floor coverings (`FLOORING`), which are
/// what the plan stands on. Doors are [`PlanItemKind::DoorLeaf`] here; the floor plan splits
/// them into frame, leaf and opening.
pub fn plan_kind(product: Entity<'_>) -> Option<PlanItemKind> {
    let is = |c: &str| product.is_a(c);
    if is("IfcSpace") {
        return Some(PlanItemKind::Space);
    }
    if is("IfcFeatureElement") || is("IfcVirtualElement") || !is("IfcElement") {
        return None;
    }
    // PredefinedType is an enumeration: read it as one (`get_str` is for strings).
    let predefined = product
        .get("PredefinedType")
        .and_then(|v| v.as_enum().map(str::to_string));
    if (is("IfcSlab") && matches!(predefined.as_deref(), Some("FLOOR" | "BASESLAB")))
        || (is("IfcCovering") && predefined.as_deref() == Some("FLOORING"))
    {
        return None;
    }
    if is("IfcDoor") {
        return Some(PlanItemKind::DoorLeaf);
    }
    if is("IfcWindow") {
        return Some(PlanItemKind::Window);
    }
    if is("IfcStair") || is("IfcStairFlight") {
        return Some(PlanItemKind::Stair);
    }
    if is("IfcRamp") || is("IfcRampFlight") {
        return Some(PlanItemKind::Ramp);
    }
    if is("IfcWall") || is("IfcCurtainWall") {
        return Some(PlanItemKind::Wall);
    }
    if is("IfcColumn") {
        return Some(PlanItemKind::Column);
    }
    let furniture = [
        "IfcFurnishingElement",
        "IfcEquipmentElement",
        "IfcDistributionElement",
        "IfcTransportElement",
        "IfcBuildingElementProxy",
    ];
    if furniture.iter().any(|c| is(c)) {
        return Some(PlanItemKind::Furniture);
    }
    // Parts take their whole's kind: a stair's landing slab, a curtain wall's plates. Railings
    // stay obstacles wherever they are.
    if !is("IfcRailing") {
        let mut current = product;
        for _ in 0..MAX_AGGREGATE_DEPTH {
            let Some(whole) = current
                .inverse("Decomposes")
                .into_iter()
                .filter(|r| r.is_a("IfcRelAggregates"))
                .find_map(|r| r.get_ref("RelatingObject"))
            else {
                break;
            };
            if whole.is_a("IfcStair") {
                return Some(PlanItemKind::Stair);
            }
            if whole.is_a("IfcRamp") {
                return Some(PlanItemKind::Ramp);
            }
            if whole.is_a("IfcWall") || whole.is_a("IfcCurtainWall") {
                return Some(PlanItemKind::Wall);
            }
            current = whole;
        }
    }
    if is("IfcSlab") && predefined.as_deref() == Some("LANDING") {
        return Some(PlanItemKind::Stair);
    }
    Some(PlanItemKind::Obstacle)
}
