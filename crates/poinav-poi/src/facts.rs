//! `Facts`: what the rules can test about one element: class, names, property values and
//! derived measures (clear width, area, door count, ...), all lengths in metres.

use std::collections::BTreeMap;

use poinav_ifc::property::{self, PropertyValue, Scalar};
use poinav_ifc::{spatial, Entity, EntityId, Model};
use rustc_hash::FxHashMap;

/// Measures a rule condition may use, all in metres, square metres or degrees.
pub const MEASURES: &[&str] = &[
    "overall_width_m",
    "overall_height_m",
    "clear_width_m",
    "clear_height_m",
    "area_m2",
    "elongation",
    "footprint_width_m",
    "footprint_length_m",
    "door_count",
    "slope_deg",
    "is_external",
    "storey_elevation_m",
];

/// A property value reduced to what rules compare.
#[derive(Debug, Clone, PartialEq)]
pub enum FactValue {
    /// Text, labels and enumeration items.
    Text(String),
    /// Numbers (lengths not converted: property values are in the file's units).
    Number(f64),
    /// Booleans and logicals.
    Bool(bool),
    /// Lists and enumerated values (as text).
    List(Vec<String>),
}

impl FactValue {
    /// The value as text (lists joined by `,`).
    pub fn text(&self) -> String {
        match self {
            FactValue::Text(t) => t.clone(),
            FactValue::Number(n) => n.to_string(),
            FactValue::Bool(b) => b.to_string(),
            FactValue::List(l) => l.join(","),
        }
    }
}

/// Everything rules can test about one element.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Facts {
    /// IFC class in schema spelling (`IfcWallStandardCase`).
    pub class: String,
    /// PredefinedType (or ObjectType when it is USERDEFINED).
    pub predefined_type: Option<String>,
    /// Name.
    pub name: Option<String>,
    /// LongName (spaces, storeys).
    pub long_name: Option<String>,
    /// ObjectType.
    pub object_type: Option<String>,
    /// `Pset.Property` -> value, type properties merged under the occurrence's.
    pub properties: BTreeMap<String, FactValue>,
    /// OverallWidth in metres (doors, windows).
    pub overall_width_m: Option<f64>,
    /// OverallHeight in metres.
    pub overall_height_m: Option<f64>,
    /// Clear passage width in metres.
    pub clear_width_m: Option<f64>,
    /// Clear passage height in metres.
    pub clear_height_m: Option<f64>,
    /// Floor area in square metres.
    pub area_m2: Option<f64>,
    /// Long side / short side of the footprint's minimum bounding rectangle.
    pub elongation: Option<f64>,
    /// Short side of the footprint's minimum bounding rectangle, metres.
    pub footprint_width_m: Option<f64>,
    /// Long side of the footprint's minimum bounding rectangle, metres.
    pub footprint_length_m: Option<f64>,
    /// Number of distinct doors on the boundary of a space.
    pub door_count: Option<f64>,
    /// Slope in degrees (ramps).
    pub slope_deg: Option<f64>,
    /// IsExternal of the class's common property set.
    pub is_external: Option<bool>,
    /// Elevation of the element's storey in metres.
    pub storey_elevation_m: Option<f64>,
    /// Where the clear width came from (`lining`, `overall width`, `geometry`).
    pub clear_width_source: Option<&'static str>,
    /// Where the slope came from (`property`, `flights' properties`, `geometry`).
    pub slope_source: Option<&'static str>,
}

impl Facts {
    /// A measure by name (see [`MEASURES`]); booleans are 1 or 0.
    pub fn measure(&self, name: &str) -> Option<f64> {
        match name {
            "overall_width_m" => self.overall_width_m,
            "overall_height_m" => self.overall_height_m,
            "clear_width_m" => self.clear_width_m,
            "clear_height_m" => self.clear_height_m,
            "area_m2" => self.area_m2,
            "elongation" => self.elongation,
            "footprint_width_m" => self.footprint_width_m,
            "footprint_length_m" => self.footprint_length_m,
            "door_count" => self.door_count,
            "slope_deg" => self.slope_deg,
            "is_external" => self.is_external.map(|b| if b { 1.0 } else { 0.0 }),
            "storey_elevation_m" => self.storey_elevation_m,
            _ => None,
        }
    }
}

/// How far (metres) a door's centre may lie outside a space's footprint and still open into it:
/// the door sits in the middle of the wall, half a wall's thickness from the room.
pub const DOOR_REACH_M: f64 = 0.4;

/// Model-wide context for computing facts: units, space footprints and the space/door adjacency.
#[derive(Debug)]
pub struct FactContext<'m> {
    model: &'m Model,
    metres: f64,
    square_metres: f64,
    radians: f64,
    /// Space -> doors on its boundary (IfcRelSpaceBoundary, else geometry).
    space_doors: FxHashMap<EntityId, Vec<EntityId>>,
    /// Where the adjacency came from.
    doors_from_boundaries: bool,
    /// Space footprints in world metres.
    footprints: FxHashMap<EntityId, poinav_geom::Footprint>,
}

impl<'m> FactContext<'m> {
    /// Prepares units and the space-boundary index of `model`.
    pub fn new(model: &'m Model) -> FactContext<'m> {
        let mut cache = poinav_geom::PlacementCache::new(model);
        let footprints: FxHashMap<EntityId, poinav_geom::Footprint> = model
            .instances_of("IfcSpace")
            .into_iter()
            .filter_map(|s| {
                poinav_geom::footprint_of(&mut cache, s)
                    .ok()
                    .map(|f| (s.id(), f.footprint))
            })
            .collect();
        let mut space_doors: FxHashMap<EntityId, Vec<EntityId>> = FxHashMap::default();
        for b in model.instances_of("IfcRelSpaceBoundary") {
            let (Some(space), Some(element)) = (
                b.get_ref("RelatingSpace"),
                b.get_ref("RelatedBuildingElement"),
            ) else {
                continue;
            };
            if element.is_a("IfcDoor") {
                let doors = space_doors.entry(space.id()).or_default();
                if !doors.contains(&element.id()) {
                    doors.push(element.id());
                }
            }
        }
        let doors_from_boundaries = !space_doors.is_empty();
        if !doors_from_boundaries && !footprints.is_empty() {
            // No space boundaries: a door opens into every space its centre is near.
            for door in model.instances_of("IfcDoor") {
                let Ok(g) = poinav_geom::door_geometry(&mut cache, door) else {
                    continue;
                };
                let mut ids: Vec<&EntityId> = footprints.keys().collect();
                ids.sort();
                for id in ids {
                    let f = &footprints[id];
                    let z_overlap = g.center.z >= f.z_min - 0.5 && g.center.z <= f.z_max + 0.5;
                    if z_overlap && f.distance_to(g.center.truncate()) <= DOOR_REACH_M {
                        space_doors.entry(*id).or_default().push(door.id());
                    }
                }
            }
        }
        FactContext {
            model,
            metres: poinav_ifc::units::length_unit(model).metres_per_unit,
            square_metres: poinav_ifc::units::area_scale(model),
            radians: poinav_ifc::units::angle_scale(model),
            space_doors,
            doors_from_boundaries,
            footprints,
        }
    }

    /// True when the space/door adjacency comes from IfcRelSpaceBoundary (else from geometry).
    pub fn doors_from_space_boundaries(&self) -> bool {
        self.doors_from_boundaries
    }

    /// The footprint of a space, in world metres.
    pub fn footprint(&self, space: EntityId) -> Option<&poinav_geom::Footprint> {
        self.footprints.get(&space)
    }

    /// The model.
    pub fn model(&self) -> &'m Model {
        self.model
    }

    /// Metres per length unit of the file.
    pub fn metres_per_unit(&self) -> f64 {
        self.metres
    }

    /// Doors on the boundary of `space`: from IfcRelSpaceBoundary, else every door whose centre
    /// is within `DOOR_REACH_M` (0.4 m) of the space's footprint.
    pub fn doors_of_space(&self, space: EntityId) -> &[EntityId] {
        self.space_doors.get(&space).map_or(&[], Vec::as_slice)
    }

    /// True when door counts are meaningful: the model has space boundaries, or space footprints.
    pub fn knows_doors(&self) -> bool {
        self.doors_from_boundaries || !self.footprints.is_empty()
    }

    /// Computes the facts of `e`, property values included.
    pub fn facts(&self, e: Entity<'m>) -> Facts {
        self.facts_with(e, true)
    }

    /// Computes the facts of `e`; property sets (the costly part) are read only when
    /// `with_properties` is set (`properties`, `is_external` and `slope_deg` stay empty otherwise).
    pub fn facts_with(&self, e: Entity<'m>, with_properties: bool) -> Facts {
        let mut f = Facts {
            class: e.type_name().to_string(),
            name: e.name(),
            long_name: e.get_str("LongName"),
            object_type: e.get_str("ObjectType"),
            ..Facts::default()
        };
        f.predefined_type = e
            .get("PredefinedType")
            .and_then(|v| v.as_enum().map(str::to_string));
        if f.predefined_type.as_deref() == Some("USERDEFINED") {
            f.predefined_type = f.object_type.clone().or(f.predefined_type);
        }
        if with_properties {
            f.properties = properties_of(e);
        }
        f.is_external = f.properties.iter().find_map(|(k, v)| match v {
            FactValue::Bool(b) if k.ends_with("Common.IsExternal") => Some(*b),
            _ => None,
        });
        f.overall_width_m = e.get_f64("OverallWidth").map(|w| w * self.metres);
        f.overall_height_m = e.get_f64("OverallHeight").map(|h| h * self.metres);
        if e.is_a("IfcDoor") || e.is_a("IfcWindow") {
            let lining = lining_thickness(e).map(|t| t * self.metres);
            match (f.overall_width_m, lining) {
                (Some(w), Some(t)) if t > 0.0 && w > 2.0 * t => {
                    f.clear_width_m = Some(w - 2.0 * t);
                    f.clear_height_m = f.overall_height_m.map(|h| h - t);
                    f.clear_width_source = Some("lining");
                }
                (Some(w), _) => {
                    f.clear_width_m = Some(w);
                    f.clear_height_m = f.overall_height_m;
                    f.clear_width_source = Some("overall width");
                }
                (None, _) => {
                    // No OverallWidth: the long side of the opening's (or the door's) footprint.
                    let mut cache = poinav_geom::PlacementCache::new(self.model);
                    let g = poinav_geom::door_geometry(&mut cache, e).ok();
                    if let Some(r) = g
                        .as_ref()
                        .and_then(|g| g.footprint.as_ref())
                        .and_then(|p| p.min_area_rectangle())
                    {
                        f.clear_width_m = Some(r.length);
                        f.clear_height_m = g
                            .as_ref()
                            .and_then(|g| g.footprint.as_ref())
                            .map(|p| p.height());
                        f.clear_width_source = Some("opening geometry");
                    }
                }
            }
        }
        if e.is_a("IfcSpace") {
            let footprint = self.footprints.get(&e.id());
            f.area_m2 = space_area(e)
                .map(|a| a * self.square_metres)
                .or_else(|| footprint.map(|p| p.area()));
            f.elongation = footprint.map(|p| p.elongation()).filter(|e| e.is_finite());
            let rect = footprint.and_then(|p| p.min_area_rectangle());
            f.footprint_width_m = rect.as_ref().map(|r| r.width);
            f.footprint_length_m = rect.as_ref().map(|r| r.length);
            if self.doors_from_boundaries || footprint.is_some() {
                f.door_count = Some(self.doors_of_space(e.id()).len() as f64);
            }
        }
        if with_properties && (e.is_a("IfcRamp") || e.is_a("IfcRampFlight")) {
            (f.slope_deg, f.slope_source) = self.ramp_slope(e, &f.properties);
        }
        f.storey_elevation_m = spatial::storey_of(e)
            .and_then(|s| s.get_f64("Elevation"))
            .map(|z| z * self.metres);
        f
    }
}

/// Slope properties of ramps and ramp flights, in the order they are trusted.
const SLOPE_PROPERTIES: [&str; 3] = [
    "Pset_RampFlightCommon.Slope",
    "Pset_RampCommon.RequiredSlope",
    "Pset_RampFlightCommon.RequiredSlope",
];

impl<'m> FactContext<'m> {
    /// The slope of ramp or flight `e` in degrees and where it came from: its own property set,
    /// else (a ramp) the steepest of its flights' properties, else the steepest walking surface
    /// of its mesh (or its flights' meshes) ([`poinav_geom::walking_slope_deg`]).
    fn ramp_slope(
        &self,
        e: Entity<'m>,
        properties: &BTreeMap<String, FactValue>,
    ) -> (Option<f64>, Option<&'static str>) {
        let from_props = |props: &BTreeMap<String, FactValue>| {
            SLOPE_PROPERTIES.iter().find_map(|k| match props.get(*k) {
                Some(FactValue::Number(a)) => Some((a * self.radians).to_degrees()),
                _ => None,
            })
        };
        if let Some(s) = from_props(properties) {
            return (Some(s), Some("property"));
        }
        let flights: Vec<Entity<'m>> = e
            .inverse("IsDecomposedBy")
            .iter()
            .flat_map(|r| r.get_refs("RelatedObjects"))
            .filter(|p| p.is_a("IfcRampFlight"))
            .collect();
        let by_flights = flights
            .iter()
            .filter_map(|fl| from_props(&properties_of(*fl)))
            .reduce(f64::max);
        if by_flights.is_some() {
            return (by_flights, Some("flights' properties"));
        }
        let mut cache = poinav_geom::PlacementCache::new(self.model);
        let mut slope_of = |p: Entity<'m>| {
            poinav_geom::mesh_product(&mut cache, p)
                .ok()
                .and_then(|m| poinav_geom::walking_slope_deg(&m.mesh))
        };
        let by_geometry = slope_of(e).or_else(|| {
            flights
                .iter()
                .filter_map(|fl| slope_of(*fl))
                .reduce(f64::max)
        });
        (by_geometry, by_geometry.map(|_| "geometry"))
    }
}

/// Every property of `e` with a value, keyed `Pset.Property`.
fn properties_of(e: Entity<'_>) -> BTreeMap<String, FactValue> {
    let mut out = BTreeMap::new();
    for set in property::property_sets(e) {
        for p in set.properties {
            if let Some(v) = fact_value(&p.value) {
                out.insert(format!("{}.{}", set.name, p.name), v);
            }
        }
    }
    out
}

fn fact_value(v: &PropertyValue) -> Option<FactValue> {
    let text = |s: &poinav_ifc::property::TypedScalar| match &s.value {
        Scalar::Text(t) | Scalar::Enum(t) => t.clone(),
        Scalar::Real(r) => r.to_string(),
        Scalar::Integer(i) => i.to_string(),
        Scalar::Bool(b) => b.to_string(),
        Scalar::Logical(l) => l.map_or("UNKNOWN".into(), |b| b.to_string()),
        Scalar::Ref(id) => id.to_string(),
    };
    match v {
        PropertyValue::Single(Some(s)) => Some(match &s.value {
            Scalar::Text(t) | Scalar::Enum(t) => FactValue::Text(t.clone()),
            Scalar::Real(r) => FactValue::Number(*r),
            Scalar::Integer(i) => FactValue::Number(*i as f64),
            Scalar::Bool(b) => FactValue::Bool(*b),
            Scalar::Logical(Some(b)) => FactValue::Bool(*b),
            Scalar::Logical(None) | Scalar::Ref(_) => return None,
        }),
        PropertyValue::Enumerated(items) | PropertyValue::List(items) => {
            Some(FactValue::List(items.iter().map(text).collect()))
        }
        _ => None,
    }
}

/// LiningThickness from an IfcDoorLiningProperties / IfcWindowLiningProperties of the
/// occurrence or its type, in file units.
fn lining_thickness(e: Entity<'_>) -> Option<f64> {
    let defs = property::own_definitions(e)
        .into_iter()
        .chain(property::type_definitions(e));
    defs.filter(|d| d.is_a("IfcDoorLiningProperties") || d.is_a("IfcWindowLiningProperties"))
        .find_map(|d| d.get_f64("LiningThickness"))
}

/// Floor area of a space from its quantities (NetFloorArea, else GrossFloorArea), file units.
fn space_area(space: Entity<'_>) -> Option<f64> {
    let mut gross = None;
    for def in property::own_definitions(space) {
        if !def.is_a("IfcElementQuantity") {
            continue;
        }
        for q in def.get_refs("Quantities") {
            if !q.is_a("IfcQuantityArea") {
                continue;
            }
            match q.name().as_deref() {
                Some("NetFloorArea") => return q.get_f64("AreaValue"),
                Some("GrossFloorArea") => gross = gross.or(q.get_f64("AreaValue")),
                _ => {}
            }
        }
    }
    gross
}
