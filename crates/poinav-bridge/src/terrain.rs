//! Doors that open onto the terrain: on a storey that is not at ground level, a door whose
//! side outside every space meets the terrain at that storey's walking level (the upper
//! storey of a hillside house) is an entrance all the same ([`poinav_nav::FloorDoor::terrain`]).
//!
//! What is terrain ([`is_terrain`]): the body of every `IfcSite`; an `IfcGeographicElement`
//! (IFC4 and later) of PredefinedType TERRAIN, or USERDEFINED / NOTDEFINED / unset with a
//! terrain-like Name or ObjectType; an `IfcBuildingElementProxy` with such a name (how IFC2X3
//! exporters write terrain). Terrain-like: `terrain`, `Gelände` / `Gelaende` (not `Geländer`,
//! a railing), `topography`, `DGM`, `DTM`, `ground surface`.
//!
//! The test ([`mark_terrain_doors`]): [`PROBE_M`] beyond the door's outer face, on its centre
//! line, the top of the terrain (the highest terrain triangle over that point) is within
//! [`LEVEL_TOLERANCE_M`] of the storey's walking level, and the point is outside the
//! building: in no space of that storey or of a lower one, and over no slab or roof of
//! another storey near that level (a roof terrace over a lower storey is not the terrain).
//! A door over terrain far below (a balcony) stays no entrance.

use std::sync::OnceLock;

use glam::{DVec2, DVec3};
use poinav_geom::element_mesh::mesh_product;
use poinav_geom::{FloorPlan, GeomError, Mesh, ModelMeshes, PlacementCache};
use poinav_ifc::{Entity, EntityId, Model};
use poinav_nav::graph::{door_zones, zone_at};
use poinav_nav::{DoorFrame, Floor, FloorLevel};
use regex::Regex;

/// How far beyond a door's outer face the terrain is sampled, metres.
pub const PROBE_M: f64 = 0.6;
/// How far the terrain's top may be from the storey's walking level there, metres.
pub const LEVEL_TOLERANCE_M: f64 = 0.3;
/// How far below the walking level (or the terrain's top, if lower) and above the walking
/// level a slab or roof of another storey at the probe puts it inside the building, metres.
pub const COVER_BAND_M: f64 = 0.5;

/// The terrain surfaces of a model, in world metres.
#[derive(Debug, Clone, Default)]
pub struct Terrain {
    /// One mesh per terrain product (the sites' bodies first, then elements in file order),
    /// with the product's GlobalId.
    pub surfaces: Vec<(String, Mesh)>,
    /// Sites whose body could not be meshed, with why (elements' failures are in
    /// [`ModelMeshes::failures`] already).
    pub failures: Vec<(EntityId, GeomError)>,
}

fn terrain_name() -> &'static Regex {
    static RE: OnceLock<Regex> = OnceLock::new();
    RE.get_or_init(|| {
        Regex::new(r"(?i)\b(terrain|gel(ä|ae|a)nde|topograph\w*|dgm|dtm|ground\s+surface)\b")
            .unwrap_or_else(|_| Regex::new("$^").expect("empty regex"))
    })
}

/// True for a product whose body is terrain (see the module's rule).
pub fn is_terrain(product: Entity<'_>) -> bool {
    if product.is_a("IfcSite") {
        return true;
    }
    let named = || {
        ["Name", "ObjectType"]
            .iter()
            .filter_map(|a| product.get_str(a))
            .any(|n| terrain_name().is_match(&n))
    };
    if product.is_a("IfcGeographicElement") {
        let predefined = product
            .get("PredefinedType")
            .and_then(|v| v.as_enum().map(str::to_string));
        return match predefined.as_deref() {
            Some("TERRAIN") => true,
            None | Some("USERDEFINED" | "NOTDEFINED") => named(),
            Some(_) => false,
        };
    }
    product.is_a("IfcBuildingElementProxy") && named()
}

/// The terrain of `model`: each `IfcSite`'s body (meshed here; a site without a body is
/// none) and the terrain elements among `meshes` ([`is_terrain`]).
pub fn terrain_of(model: &Model, meshes: &ModelMeshes) -> Terrain {
    let mut out = Terrain::default();
    let mut cache = PlacementCache::new(model);
    for site in model.instances_of("IfcSite") {
        if site.get("Representation").is_none() {
            continue;
        }
        match mesh_product(&mut cache, site) {
            Ok(m) => out.surfaces.push((m.global_id, m.mesh)),
            // A site with a footprint or annotation only has no terrain to offer.
            Err(GeomError::NoGeometry { .. }) => {}
            Err(e) => out.failures.push((site.id(), e)),
        }
    }
    for m in &meshes.elements {
        if model.entity(m.product).is_some_and(is_terrain) {
            out.surfaces.push((m.global_id.clone(), m.mesh.clone()));
        }
    }
    out
}

/// The z of the highest triangle of `meshes` over `p` (a vertical ray's highest hit); `None`
/// when none is over it. Vertical triangles are skipped.
pub fn top_at<'a>(meshes: impl IntoIterator<Item = &'a Mesh>, p: DVec2) -> Option<f64> {
    let mut top: Option<f64> = None;
    for m in meshes {
        let Some((lo, hi)) = m.bounds() else {
            continue;
        };
        if p.x < lo.x || p.y < lo.y || p.x > hi.x || p.y > hi.y {
            continue;
        }
        for t in &m.triangles {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            if let Some(z) = z_over(a, b, c, p) {
                top = Some(top.map_or(z, |t| t.max(z)));
            }
        }
    }
    top
}

/// The z of triangle `a b c` over `p` (edges included), `None` when `p` is not under it or
/// the triangle is vertical.
fn z_over(a: DVec3, b: DVec3, c: DVec3, p: DVec2) -> Option<f64> {
    let cross = |u: DVec2, v: DVec2| u.x * v.y - u.y * v.x;
    let (a2, b2, c2) = (a.truncate(), b.truncate(), c.truncate());
    let area = cross(b2 - a2, c2 - a2);
    if area.abs() < 1e-12 {
        return None;
    }
    let wa = cross(b2 - p, c2 - p) / area;
    let wb = cross(c2 - p, a2 - p) / area;
    let wc = 1.0 - wa - wb;
    let eps = -1e-9;
    (wa >= eps && wb >= eps && wc >= eps).then_some(wa * a.z + wb * b.z + wc * c.z)
}

/// The slabs and roofs of `meshes` (what covers or carries a storey), each with the index of
/// the storey it belongs to in `plans` (`None`: no storey).
fn covers<'m>(
    model: &Model,
    meshes: &'m ModelMeshes,
    plans: &[FloorPlan],
) -> Vec<(Option<usize>, &'m Mesh)> {
    meshes
        .elements
        .iter()
        .filter(|m| {
            model
                .entity(m.product)
                .is_some_and(|e| e.is_a("IfcSlab") || e.is_a("IfcRoof"))
        })
        .map(|m| {
            let floor = m
                .storey
                .and_then(|s| plans.iter().position(|p| p.storey == s));
            (floor, &m.mesh)
        })
        .collect()
}

/// Sets [`poinav_nav::FloorDoor::terrain`] on every door of `floors` (as `plans`, with their
/// `levels`) on a storey not at ground level whose side outside every space opens onto
/// `terrain` at the storey's walking level (see the module's test); returns how many.
pub fn mark_terrain_doors(
    model: &Model,
    meshes: &ModelMeshes,
    plans: &[FloorPlan],
    floors: &mut [Floor],
    levels: &[FloorLevel],
    terrain: &Terrain,
) -> usize {
    if terrain.surfaces.is_empty() {
        return 0;
    }
    let covers = covers(model, meshes, plans);
    let surfaces = || terrain.surfaces.iter().map(|(_, m)| m);
    let mut found = Vec::new();
    for (fi, floor) in floors.iter().enumerate() {
        let Some(level) = levels.get(fi).filter(|l| !l.at_ground) else {
            continue;
        };
        let walk = level.walking_level_m;
        for (k, d) in floor.doors.iter().enumerate() {
            if d.doorless {
                continue;
            }
            let side = match door_zones(floor, k) {
                [None, Some(_)] => -1.0,
                [Some(_), None] => 1.0,
                _ => continue,
            };
            let Some(f) = floor.door_frame(k) else {
                continue;
            };
            let p = f.center + f.normal * side * (f.half_depth + PROBE_M);
            let Some(top) = top_at(surfaces(), p) else {
                continue;
            };
            if (top - walk).abs() > LEVEL_TOLERANCE_M {
                continue;
            }
            // Outside the building: in no space of this storey or a lower one ...
            let in_space = floors.iter().zip(levels).any(|(g, l)| {
                l.walking_level_m <= walk + LEVEL_TOLERANCE_M && zone_at(g, p).is_some()
            });
            // ... and over no slab or roof of another storey near this level.
            let (lo, hi) = (top.min(walk) - COVER_BAND_M, walk + COVER_BAND_M);
            let covered = covers.iter().any(|(g, m)| {
                *g != Some(fi) && top_at([*m], p).is_some_and(|z| z >= lo && z <= hi)
            });
            if !in_space && !covered {
                found.push((fi, k));
            }
        }
    }
    for &(fi, k) in &found {
        floors[fi].doors[k].terrain = true;
    }
    found.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_top_is_the_highest_triangle_over_the_point() {
        // Two sloped triangles over the unit square, one 1 m above the other.
        let tri = |dz: f64| Mesh {
            positions: vec![
                DVec3::new(0.0, 0.0, dz),
                DVec3::new(1.0, 0.0, dz + 1.0),
                DVec3::new(0.0, 1.0, dz),
            ],
            triangles: vec![[0, 1, 2]],
        };
        let (low, high) = (tri(0.0), tri(1.0));
        let z = top_at([&low, &high], DVec2::new(0.5, 0.25)).unwrap();
        assert!((z - 1.5).abs() < 1e-12, "{z}");
        assert_eq!(top_at([&low], DVec2::new(0.8, 0.8)), None);
        // A vertical triangle is never hit.
        let wall = Mesh {
            positions: vec![
                DVec3::new(0.0, 0.5, 0.0),
                DVec3::new(1.0, 0.5, 0.0),
                DVec3::new(0.0, 0.5, 5.0),
            ],
            triangles: vec![[0, 1, 2]],
        };
        assert_eq!(top_at([&wall], DVec2::new(0.2, 0.5)), None);
    }

    #[test]
    fn terrain_names() {
        let re = terrain_name();
        for yes in [
            "Terrain",
            "Gelände",
            "Gelaende 0815",
            "DGM Grundstück",
            "Topography",
        ] {
            assert!(re.is_match(yes), "{yes}");
        }
        for no in ["Geländer", "Gelaender", "Terrace", "Wall"] {
            assert!(!re.is_match(no), "{no}");
        }
    }
}
