//! Storey floor plans: for each storey, the 2D regions (world XY metres) of everything it
//! contains that a robot meets within a height band above the storey's floor, tagged with
//! GlobalId, class and [`PlanItemKind`]. The input of navigation maps, the simulator and the
//! SVG drawing.
//!
//! How each product is drawn:
//! - its mesh ([`crate::mesh_model`], openings already cut) is cut by the band
//!   ([`crate::section::mesh_section`], exact for solids; surfaces crossing the band, such as
//!   fences modelled as open profiles, are lines [`crate::section_lines::LINE_WIDTH_M`] wide);
//! - a section that reaches a bound ([`SectionBounds`]) is drawn as its conservative outline
//!   ([`PlanSource::Outline`], unknown space to navigation) and listed in
//!   [`FloorPlan::problems`];
//! - stairs and ramps are drawn with their whole shadow ([`crate::section::mesh_shadow`]):
//!   a wheeled robot must not enter a flight even where it passes high above the band;
//! - a product whose mesh could not be made falls back on its footprint
//!   ([`crate::footprint_of`]) when its z-range meets the band, less the footprints of its
//!   openings that span its part of the band; the failure is listed in [`FloorPlan::problems`];
//! - a door gives up to three items: its body's section inside the clear width
//!   ([`PlanItemKind::DoorLeaf`]), outside it ([`PlanItemKind::DoorFrame`]), and its clear
//!   passage ([`PlanItemKind::DoorOpening`], see [`DoorPassage`]).
//!
//! A product belongs to the storey [`poinav_ifc::spatial::storey_of`] finds; a model without
//! storeys gets one plan for everything, unless it has no building either (IFC4X3
//! infrastructure): then each spatial element containing products (a railway part, a facility,
//! a site) gets a plan of everything it contains over its whole height (shadows; products of
//! at least [`crate::part_hulls::DENSE_TRIANGLES`] triangles by the convex hull of theirs,
//! [`PlanSource::PartHulls`]). Products that have no storey in a model with storeys
//! go to the storey they stand on (the highest one at or below their lowest point).

use glam::DVec2;
use poinav_ifc::{spatial, Entity, EntityId, Model};
use rayon::prelude::*;
use rustc_hash::FxHashMap;
use serde::{Deserialize, Serialize};

use crate::door_passage::{
    door_passage, opening_passage, unfilled_openings, DoorPassage, MIN_OPENING_PASSAGE_M,
};
use crate::element_mesh::{meshed_products, openings_of};
use crate::error::GeomError;
use crate::floor_level::{floor_voids, is_floor_slab, walking_level, LevelFrom};
use crate::footprint::footprint_of;
use crate::mesh::ElementMesh;
use crate::placement::PlacementCache;
use crate::plan_kind::{plan_kind, PlanItemKind};
use crate::region::{self, Region};
use crate::section::{mesh_section_within, mesh_shadow_within, CutOff, SectionBounds};
use crate::{mesh_model, ModelMeshes};

/// The height band of a plan, relative to the storey's elevation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PlanOptions {
    /// Bottom of the band above the storey's floor, metres (0.05: above floor finishes and
    /// thresholds).
    pub band_min_m: f64,
    /// Top of the band, metres: the robot's height (1.0 by default, which also shows desks and
    /// tables; pass the robot profile's height for its navigation map).
    pub band_max_m: f64,
    /// How much work one product's section may take.
    #[serde(default)]
    pub section: SectionBounds,
}

impl Default for PlanOptions {
    fn default() -> Self {
        PlanOptions {
            band_min_m: 0.05,
            band_max_m: 1.0,
            section: SectionBounds::default(),
        }
    }
}

/// Where an item's regions come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PlanSource {
    /// The section of its mesh by the band.
    Section,
    /// The projection of its whole mesh (stairs, ramps, spaces modelled as open surfaces).
    Shadow,
    /// Its footprint (its mesh could not be made).
    Footprint,
    /// Its door passage (door openings).
    Passage,
    /// The convex hull of what it has in the band: its section (or shadow) reached a bound
    /// ([`SectionBounds`]). It holds the product, but what is free inside it is not known:
    /// navigation draws it as unknown space.
    Outline,
    /// The union of its connected parts' convex hulls in the band: a dense furnishing (at least
    /// [`crate::part_hulls::DENSE_TRIANGLES`] triangles), drawn conservatively
    /// ([`crate::part_hulls`]); it holds the exact section.
    PartHulls,
    /// The holes of a floor slab at the storey's walking level (a stairwell, a shaft): a drop.
    Void,
}

/// One product's regions of one kind.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanItem {
    /// The product.
    pub product: EntityId,
    /// Its GlobalId.
    pub global_id: String,
    /// Its IFC class, schema spelling.
    pub class: String,
    /// Its Name.
    pub name: Option<String>,
    /// Its LongName (spaces).
    pub long_name: Option<String>,
    /// What it is in the plan.
    pub kind: PlanItemKind,
    /// Its regions, world XY metres.
    pub regions: Vec<Region>,
    /// Where they come from.
    pub source: PlanSource,
}

impl PlanItem {
    /// Total area, square metres.
    pub fn area(&self) -> f64 {
        region::total_area(&self.regions)
    }
}

/// A product that could not be drawn as well as it should be.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanProblem {
    /// The product.
    pub product: EntityId,
    /// Its GlobalId.
    pub global_id: String,
    /// Its class.
    pub class: String,
    /// What went wrong.
    pub error: GeomError,
    /// True when it is drawn anyway, from its footprint.
    pub fell_back: bool,
}

/// The plan of one storey.
#[derive(Debug, Clone, PartialEq)]
pub struct FloorPlan {
    /// The storey (the building, or the project, in a model without storeys).
    pub storey: EntityId,
    /// Its Name.
    pub storey_name: Option<String>,
    /// Its GlobalId.
    pub storey_global_id: Option<String>,
    /// The z of its floor, world metres: its walking level ([`crate::floor_level`]), which is
    /// the storey's elevation unless its floor slabs (or spaces) say otherwise.
    pub elevation_m: f64,
    /// The storey's elevation as the model gives it: its placement, else its Elevation.
    pub storey_elevation_m: f64,
    /// Where `elevation_m` comes from.
    pub level_from: LevelFrom,
    /// The band cut, world z metres.
    pub band: (f64, f64),
    /// Items in file order of their products (a door's frame, leaf and opening together).
    pub items: Vec<PlanItem>,
    /// The passages of its doors, in file order.
    pub doors: Vec<DoorPassage>,
    /// The passages through wall openings that no door or window fills (doorways), in file
    /// order of their walls: openings at least [`MIN_OPENING_PASSAGE_M`] wide that cut the
    /// wall through the whole band. `door` is the `IfcOpeningElement`.
    pub openings: Vec<DoorPassage>,
    /// Products drawn from their footprint or not at all, and doors without a passage.
    pub problems: Vec<PlanProblem>,
    /// The box around every item (min, max); `None` for an empty plan.
    pub bounds: Option<(DVec2, DVec2)>,
}

impl FloorPlan {
    /// Items of `kind`.
    pub fn items_of(&self, kind: PlanItemKind) -> impl Iterator<Item = &PlanItem> {
        self.items.iter().filter(move |i| i.kind == kind)
    }

    /// Every obstacle region ([`PlanItemKind::is_obstacle`]).
    pub fn obstacles(&self) -> impl Iterator<Item = &Region> {
        self.items
            .iter()
            .filter(|i| i.kind.is_obstacle())
            .flat_map(|i| i.regions.iter())
    }

    /// The free width through a door at its centre line: the length of the free stretch of
    /// the line along the door through its centre, between the nearest obstacle regions either
    /// side, searched up to `reach` metres out. What the walls and frames leave open.
    pub fn free_width_at(&self, door: &DoorPassage, reach: f64) -> f64 {
        let mut left = reach;
        let mut right = reach;
        for r in self.obstacles() {
            for ring in r.rings() {
                let n = ring.len();
                for i in 0..n {
                    let (a, b) = (ring[i], ring[(i + 1) % n]);
                    if let Some(t) = line_hit(door.center, door.along, a, b) {
                        if t >= 0.0 {
                            right = right.min(t);
                        }
                        if t <= 0.0 {
                            left = left.min(-t);
                        }
                    }
                }
            }
            if r.contains(door.center) {
                return 0.0;
            }
        }
        left + right
    }
}

/// Where the line `o + t * d` meets the segment `a`-`b`: `t`, if it does.
fn line_hit(o: DVec2, d: DVec2, a: DVec2, b: DVec2) -> Option<f64> {
    let e = b - a;
    let denom = d.perp_dot(e);
    if denom.abs() < 1e-15 {
        return None;
    }
    let w = a - o;
    let t = w.perp_dot(e) / denom;
    let s = w.perp_dot(d) / denom;
    (0.0..=1.0).contains(&s).then_some(t)
}

/// The floor plans of `model`, one per storey sorted by elevation; meshes every product first
/// ([`mesh_model`]). Use [`floor_plans_with_meshes`] when the meshes are at hand.
pub fn floor_plans(model: &Model, options: &PlanOptions) -> Vec<FloorPlan> {
    floor_plans_with_meshes(model, &mesh_model(model), options)
}

/// The floor plans of `model` from its meshes (from [`mesh_model`]).
pub fn floor_plans_with_meshes(
    model: &Model,
    meshes: &ModelMeshes,
    options: &PlanOptions,
) -> Vec<FloorPlan> {
    floor_plans_with_progress(model, meshes, options, &crate::progress::none)
}

/// [`floor_plans_with_meshes`], reporting each product drawn to `progress`.
pub fn floor_plans_with_progress(
    model: &Model,
    meshes: &ModelMeshes,
    options: &PlanOptions,
    progress: crate::progress::Progress<'_>,
) -> Vec<FloorPlan> {
    let mut cache = PlacementCache::new(model);
    let metres = cache.metres_per_unit();
    let storeys = spatial::spatial_structure(model, &poinav_ifc::units::length_unit(model)).storeys;
    let by_id: FxHashMap<EntityId, &ElementMesh> = meshes
        .elements
        .iter()
        .chain(meshes.spaces.iter())
        .map(|m| (m.product, m))
        .collect();
    let failures: FxHashMap<EntityId, &GeomError> =
        meshes.failures.iter().map(|(id, e)| (*id, e)).collect();
    let products = meshed_products(model);

    // The storeys, with the z of their floors.
    let mut levels: Vec<(Entity<'_>, f64)> = storeys
        .iter()
        .filter_map(|s| model.entity(s.id))
        .map(|s| {
            let z = cache
                .product(s)
                .map(|t| t.translation.z)
                .ok()
                .or_else(|| s.get_f64("Elevation").map(|e| e * metres))
                .unwrap_or(0.0);
            (s, z)
        })
        .collect();
    let mut members: Vec<Vec<Entity<'_>>> = vec![Vec::new(); levels.len().max(1)];
    // Bands that replace the storey's (facility parts: their whole height).
    let mut bands: Vec<Option<(f64, f64)>> = Vec::new();
    let facility = levels.is_empty() && model.instances_of("IfcBuilding").is_empty();
    let parts = if facility {
        facility_parts(&products, &by_id)
    } else {
        Vec::new()
    };
    if !parts.is_empty() {
        members.clear();
        for (part, group, (low, high)) in parts {
            levels.push((part, low));
            bands.push(Some((low - 0.01, high + 0.01)));
            members.push(group);
        }
    } else if levels.is_empty() {
        let whole = model
            .instances_of("IfcBuilding")
            .into_iter()
            .next()
            .or_else(|| model.instances_of("IfcProject").into_iter().next());
        let z = whole
            .and_then(|b| cache.product(b).ok())
            .map_or(0.0, |t| t.translation.z);
        if let Some(w) = whole {
            levels.push((w, z));
        }
        members[0] = products.clone();
    } else {
        let index: FxHashMap<EntityId, usize> = levels
            .iter()
            .enumerate()
            .map(|(i, (s, _))| (s.id(), i))
            .collect();
        for p in &products {
            let at = spatial::storey_of(*p)
                .and_then(|s| index.get(&s.id()).copied())
                .or_else(|| {
                    let low = by_id.get(&p.id())?.mesh.bounds()?.0.z;
                    standing_on(&levels, low)
                });
            if let Some(i) = at {
                members[i].push(*p);
            }
        }
    }
    let ticker = crate::progress::Ticker::new(members.iter().map(Vec::len).sum(), progress);
    // Each storey's walking level, and the floor slabs whose holes are drops on the storeys
    // above the lowest.
    let walking: Vec<(f64, LevelFrom)> = levels
        .iter()
        .zip(&members)
        .map(|((_, elevation), products)| {
            walking_level(
                *elevation,
                products
                    .iter()
                    .filter_map(|p| by_id.get(&p.id()).map(|m| (*p, *m))),
            )
        })
        .collect();
    let lowest = walking
        .iter()
        .map(|(z, _)| *z)
        .fold(f64::INFINITY, f64::min);
    let floor_slabs: Vec<(Entity<'_>, &ElementMesh)> = meshes
        .elements
        .iter()
        .filter_map(|m| model.entity(m.product).map(|e| (e, m)))
        .filter(|(e, _)| is_floor_slab(*e))
        .collect();
    // From here on a storey's z is its walking level.
    let storey_z: Vec<(EntityId, f64, LevelFrom)> = levels
        .iter()
        .zip(&walking)
        .map(|((s, z), (_, from))| (s.id(), *z, *from))
        .collect();
    for (l, (z, _)) in levels.iter_mut().zip(&walking) {
        l.1 = *z;
    }
    levels
        .iter()
        .zip(members)
        .enumerate()
        .map(|(i, (&(storey, elevation), products))| {
            let facility_plan = bands.get(i).copied().flatten().is_some();
            let band = bands.get(i).copied().flatten().unwrap_or((
                elevation + options.band_min_m,
                elevation + options.band_max_m,
            ));
            let drawn: Vec<Drawn> = products
                .par_iter()
                .with_min_len(4)
                .map_init(
                    || PlacementCache::new(model),
                    |cache, &p| {
                        let d = draw(
                            cache,
                            p,
                            band,
                            &options.section,
                            &by_id,
                            &failures,
                            facility_plan,
                        );
                        ticker.tick();
                        d
                    },
                )
                .collect();
            let (_, storey_elevation, level_from) = storey_z
                .iter()
                .copied()
                .find(|(id, _, _)| *id == storey.id())
                .unwrap_or((storey.id(), elevation, LevelFrom::StoreyElevation));
            let mut plan = FloorPlan {
                storey: storey.id(),
                storey_name: storey.name(),
                storey_global_id: storey.global_id(),
                elevation_m: elevation,
                storey_elevation_m: storey_elevation,
                level_from,
                band,
                items: Vec::new(),
                doors: Vec::new(),
                openings: Vec::new(),
                problems: Vec::new(),
                bounds: None,
            };
            for d in drawn {
                plan.items.extend(d.items);
                plan.doors.extend(d.door);
                plan.openings.extend(d.openings);
                plan.problems.extend(d.problems);
            }
            void_items(&mut plan, elevation > lowest + 1.0, &floor_slabs);
            plan.bounds = region::bounds_of(plan.items.iter().flat_map(|i| i.regions.iter()));
            plan
        })
        .collect()
}

/// Adds the holes in the floor at `plan`'s level (stairwells, shafts: drops) as obstacle items
/// of the slabs around them, on a storey `above` the lowest.
fn void_items<'m>(
    plan: &mut FloorPlan,
    above: bool,
    floor_slabs: &[(Entity<'m>, &'m ElementMesh)],
) {
    if !above {
        return;
    }
    for (slab, voids) in floor_voids(plan.elevation_m, floor_slabs.iter().copied()) {
        plan.items.push(PlanItem {
            product: slab.id(),
            global_id: slab.global_id().unwrap_or_default(),
            class: slab.type_name().to_string(),
            name: slab.name(),
            long_name: None,
            kind: PlanItemKind::Obstacle,
            regions: voids,
            source: PlanSource::Void,
        });
    }
}

/// A model without storeys or buildings (IFC4X3 infrastructure: a railway, a road): its
/// products grouped by the spatial element containing them (an `IfcRailwayPart`, a facility,
/// a site; those in none under the first site, else the project), each group with the height
/// range of its meshes. Groups without a mesh are left out; in file order of the element.
fn facility_parts<'m>(
    products: &[Entity<'m>],
    by_id: &FxHashMap<EntityId, &ElementMesh>,
) -> Vec<(Entity<'m>, Vec<Entity<'m>>, (f64, f64))> {
    let mut groups: Vec<(Entity<'m>, Vec<Entity<'m>>, (f64, f64))> = Vec::new();
    let fallback = products.first().and_then(|p| {
        let model = p.model();
        model
            .instances_of("IfcSite")
            .into_iter()
            .next()
            .or_else(|| model.instances_of("IfcProject").into_iter().next())
    });
    for p in products {
        let Some((lo, hi)) = by_id.get(&p.id()).and_then(|m| m.mesh.bounds()) else {
            continue;
        };
        let mut container = spatial::parent_of(*p);
        for _ in 0..64 {
            match container {
                Some(c) if !c.is_a("IfcSpatialStructureElement") && !c.is_a("IfcProject") => {
                    container = spatial::parent_of(c);
                }
                _ => break,
            }
        }
        let Some(c) = container.or(fallback) else {
            continue;
        };
        match groups.iter_mut().find(|(e, _, _)| e.id() == c.id()) {
            Some((_, g, range)) => {
                g.push(*p);
                *range = (range.0.min(lo.z), range.1.max(hi.z));
            }
            None => groups.push((c, vec![*p], (lo.z, hi.z))),
        }
    }
    groups.sort_by_key(|(e, _, _)| e.position());
    groups
}

/// The highest storey whose floor is at or below `z` (1 cm tolerance), else the lowest.
fn standing_on(levels: &[(Entity<'_>, f64)], z: f64) -> Option<usize> {
    let below = levels
        .iter()
        .enumerate()
        .filter(|(_, (_, e))| *e <= z + 0.01)
        .max_by(|a, b| a.1 .1.total_cmp(&b.1 .1))
        .map(|(i, _)| i);
    below.or_else(|| {
        levels
            .iter()
            .enumerate()
            .min_by(|a, b| a.1 .1.total_cmp(&b.1 .1))
            .map(|(i, _)| i)
    })
}

/// What one product adds to a plan.
#[derive(Debug, Default)]
struct Drawn {
    items: Vec<PlanItem>,
    door: Option<DoorPassage>,
    openings: Vec<DoorPassage>,
    problems: Vec<PlanProblem>,
}

fn draw<'m>(
    cache: &mut PlacementCache<'m>,
    product: Entity<'m>,
    band: (f64, f64),
    bounds: &SectionBounds,
    meshes: &FxHashMap<EntityId, &ElementMesh>,
    failures: &FxHashMap<EntityId, &GeomError>,
    hull_dense: bool,
) -> Drawn {
    let mut out = Drawn::default();
    let Some(kind) = plan_kind(product) else {
        return out;
    };
    let problem = |error: GeomError, fell_back: bool| PlanProblem {
        product: product.id(),
        global_id: product.global_id().unwrap_or_default(),
        class: product.type_name().to_string(),
        error,
        fell_back,
    };
    let cut = |r: Result<Vec<Region>, CutOff>, source: PlanSource| match r {
        Ok(regions) => (regions, source, None),
        Err(c) => (c.outline, PlanSource::Outline, Some(c.limit)),
    };
    let (regions, source, limit) = match meshes.get(&product.id()) {
        Some(m) if matches!(kind, PlanItemKind::Stair | PlanItemKind::Ramp) => {
            cut(mesh_shadow_within(&m.mesh, bounds), PlanSource::Shadow)
        }
        // A space modelled as an open surface (walls and floor, no ceiling: duplex-apartment's
        // hallways) has no inside to cut: the air it bounds is its shadow, where it reaches
        // into the band.
        Some(m)
            if kind == PlanItemKind::Space
                && !crate::section::is_closed(&m.mesh)
                && m.mesh
                    .bounds()
                    .is_some_and(|(lo, hi)| lo.z <= band.1 && hi.z >= band.0) =>
        {
            cut(mesh_shadow_within(&m.mesh, bounds), PlanSource::Shadow)
        }
        // Dense furniture (thousands of triangles, as Revit and ArchiCAD export it): each part's
        // hull, linear in triangles, instead of the exact section's boolean.
        Some(m)
            if kind == PlanItemKind::Furniture
                && m.mesh.triangles.len() >= crate::part_hulls::DENSE_TRIANGLES =>
        {
            (
                crate::part_hulls::part_hulls(&m.mesh, band.0, band.1),
                PlanSource::PartHulls,
                None,
            )
        }
        // In a facility part's plan (its whole height) a dense product (a sleeper with its
        // fastenings) is drawn by the hull of its shadow: exact sections of thousands of
        // overlapping parts would cost seconds each, and the hull holds them.
        Some(m) if hull_dense && m.mesh.triangles.len() >= crate::part_hulls::DENSE_TRIANGLES => {
            let points: Vec<DVec2> = m.mesh.positions.iter().map(|p| p.truncate()).collect();
            let hull = crate::polygon::convex_hull(&points);
            (
                Region::from_ring(hull).into_iter().collect(),
                PlanSource::PartHulls,
                None,
            )
        }
        Some(m) => cut(
            mesh_section_within(&m.mesh, band.0, band.1, bounds),
            PlanSource::Section,
        ),
        None => {
            let why = failures.get(&product.id()).map(|e| (*e).clone());
            match footprint_regions(cache, product, band, kind) {
                Ok(r) => {
                    if let Some(e) = why {
                        out.problems.push(problem(e, true));
                    }
                    (r, PlanSource::Footprint, None)
                }
                Err(e) => {
                    out.problems.push(problem(why.unwrap_or(e), false));
                    (Vec::new(), PlanSource::Footprint, None)
                }
            }
        }
    };
    // A section given up on: its hull stands in for an obstacle (unknown space), but a space
    // (free space) is left out rather than grown.
    let (regions, source) = match limit {
        None => (regions, source),
        Some(limit) => {
            let error = GeomError::SectionLimit {
                id: product.id(),
                class: product.type_name().to_string(),
                limit,
            };
            if kind == PlanItemKind::Space {
                out.problems.push(problem(error, false));
                return out;
            }
            out.problems.push(problem(error, !regions.is_empty()));
            (regions, source)
        }
    };
    let item = |kind: PlanItemKind, regions: Vec<Region>, source: PlanSource| PlanItem {
        product: product.id(),
        global_id: product.global_id().unwrap_or_default(),
        class: product.type_name().to_string(),
        name: product.name(),
        long_name: product.get_str("LongName"),
        kind,
        regions,
        source,
    };
    if product.is_a("IfcDoor") {
        match door_passage(cache, product) {
            Ok(passage) => {
                let reach = (passage.depth_m / 2.0).max(passage.clear_width_m) + 0.5;
                let strip: Vec<Region> = passage.strip(reach).into_iter().collect();
                let frame = region::difference(&regions, &strip);
                let leaf = region::intersection(&regions, &strip);
                if !frame.is_empty() {
                    out.items.push(item(PlanItemKind::DoorFrame, frame, source));
                }
                if !leaf.is_empty() {
                    out.items.push(item(PlanItemKind::DoorLeaf, leaf, source));
                }
                let opening: Vec<Region> = passage.passage().into_iter().collect();
                // Openings that do not reach into the band (a hatch) are no passage here.
                let (z0, z1) = passage.z_range;
                if !opening.is_empty() && z0 <= band.1 && z1 >= band.0 {
                    out.items.push(item(
                        PlanItemKind::DoorOpening,
                        opening,
                        PlanSource::Passage,
                    ));
                    out.door = Some(passage);
                }
            }
            Err(e) => {
                out.problems.push(problem(e, !regions.is_empty()));
                if !regions.is_empty() {
                    out.items
                        .push(item(PlanItemKind::DoorLeaf, regions, source));
                }
            }
        }
        return out;
    }
    if !regions.is_empty() {
        out.items.push(item(kind, regions, source));
        // A wall that is drawn has a gap at each of its doorways; one that is not (its geometry
        // failed, or its openings took all of it) has none to speak of.
        if kind == PlanItemKind::Wall {
            doorways(cache, product, band, &mut out);
        }
    }
    out
}

/// Adds the doorways of `wall`: its openings that no door or window fills, at least
/// [`MIN_OPENING_PASSAGE_M`] wide, cutting it from the band's bottom to its top (1 cm
/// tolerance), so that its plan has a gap there.
fn doorways<'m>(
    cache: &mut PlacementCache<'m>,
    wall: Entity<'m>,
    band: (f64, f64),
    out: &mut Drawn,
) {
    for opening in unfilled_openings(wall) {
        match opening_passage(cache, opening, wall) {
            Ok(passage) => {
                let (z0, z1) = passage.z_range;
                if passage.clear_width_m < MIN_OPENING_PASSAGE_M
                    || z0 > band.0 + 0.01
                    || z1 < band.1 - 0.01
                {
                    continue;
                }
                let regions: Vec<Region> = passage.passage().into_iter().collect();
                if regions.is_empty() {
                    continue;
                }
                out.items.push(PlanItem {
                    product: opening.id(),
                    global_id: opening.global_id().unwrap_or_default(),
                    class: opening.type_name().to_string(),
                    name: opening.name(),
                    long_name: None,
                    kind: PlanItemKind::DoorOpening,
                    regions,
                    source: PlanSource::Passage,
                });
                out.openings.push(passage);
            }
            Err(error) => out.problems.push(PlanProblem {
                product: opening.id(),
                global_id: opening.global_id().unwrap_or_default(),
                class: opening.type_name().to_string(),
                error,
                fell_back: false,
            }),
        }
    }
}

/// The footprint of a product as plan regions when its z-range meets the band (stairs and
/// ramps whatever their height), less the footprints of its openings that span the heights
/// at which the product is inside the band.
fn footprint_regions<'m>(
    cache: &mut PlacementCache<'m>,
    product: Entity<'m>,
    band: (f64, f64),
    kind: PlanItemKind,
) -> Result<Vec<Region>, GeomError> {
    let f = footprint_of(cache, product)?.footprint;
    let whole = matches!(kind, PlanItemKind::Stair | PlanItemKind::Ramp);
    if !whole && (f.z_max < band.0 || f.z_min > band.1) {
        return Ok(Vec::new());
    }
    let Some(outline) = Region::from_ring(f.polygon) else {
        return Ok(Vec::new());
    };
    // An opening cuts where it spans the heights at which the product is inside the band.
    let (lo, hi) = (band.0.max(f.z_min), band.1.min(f.z_max));
    let mut cut = Vec::new();
    for opening in openings_of(product) {
        if let Ok(o) = footprint_of(cache, opening) {
            let o = o.footprint;
            if o.z_min <= lo + 1e-6 && o.z_max >= hi - 1e-6 {
                cut.extend(Region::from_ring(o.polygon));
            }
        }
    }
    Ok(region::difference(&[outline], &cut))
}
