//! Vertical connections from IFC: the stairs and ramps (`IfcStair`, `IfcStairFlight`,
//! `IfcRamp`, `IfcRampFlight`, flights and landings aggregated into their whole) and lifts
//! (`IfcTransportElement` of type ELEVATOR, spaces named like lifts, stacked or spanning
//! storeys) that join storeys, as [`VerticalConnection`]s with one landing per storey served.
//!
//! - The storeys a stair or ramp connects come from its meshes' lowest and highest z against
//!   the storeys' elevations ([`STOREY_TOLERANCE_M`]; railings may rise above the top storey);
//!   one rising through several storeys also stops at each storey in between where it has a
//!   part at that floor's level.
//! - A landing is the XY of its vertices at that storey's floor, pushed out of its footprint
//!   into free space: inside some zone of that storey and clear of its obstacles, else moved
//!   around the footprint, else the connection is [`Dropped`] with the reason.
//! - A lift serves every storey its spaces' (or elements') z-ranges reach with headroom; its
//!   landing is in front of a door at its footprint, else beside it, else its centroid.
//!
//! Statuses per profile come from [`VerticalConnection::status`].

use std::collections::BTreeMap;
use std::sync::OnceLock;

use glam::{DVec2, DVec3};
use poinav_geom::region::{self, Region};
use poinav_geom::{polygon, ElementMesh, Footprint, ModelMeshes};
use poinav_ifc::{Entity, EntityId, Model};
use poinav_nav::{
    ConnectionKind, Floor, FloorObstacle, Landing, ObstacleKind, Ring, VerticalConnection,
};
use regex::Regex;

use crate::dropped::{Dropped, DroppedKind};

/// How far a stair's or ramp's lowest point may be from a storey's floor (metres).
pub const STOREY_TOLERANCE_M: f64 = 0.35;
/// How far above the top storey's floor a stair may reach (its railings), metres.
pub const RAILING_ALLOWANCE_M: f64 = 1.3;
/// The headroom a lift space needs above a storey's floor for a stop there, metres.
pub const LIFT_HEADROOM_M: f64 = 1.5;
/// How far a landing stays outside the footprint of its stair, ramp or lift, metres.
pub const FOOTPRINT_MARGIN_M: f64 = 0.3;
/// How far a landing is searched beyond that margin, metres.
pub const SEARCH_REACH_M: f64 = 2.0;
/// How much further than the clearance a stair's or ramp's landing stays from obstacles, so
/// that it is traversable in the inflated grid whatever the cells, metres.
pub const LANDING_SLACK_M: f64 = 0.1;

/// The vertical connections of a model and the candidates left out.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Vertical {
    /// Stairs and ramps in file order of their wholes, then lifts in file order.
    pub connections: Vec<VerticalConnection>,
    /// Stairs, ramps and lifts that connect nothing, with why.
    pub dropped: Vec<Dropped>,
    /// The shadow of each stair and ramp on the storeys it rises to (every landing's storey
    /// but its foot's): an obstacle there, where it stands in the stairwell (by storey index).
    pub shadows: Vec<(usize, FloorObstacle)>,
}

/// True for a lift's name: `elevator`, `elev`, `lift`, Aufzug, Fahrstuhl, ascenseur, ascensor,
/// ascensore; not the rooms around one (`ELEV EQ RM`, `lift lobby`, machine rooms).
pub fn is_lift_name(name: &str) -> bool {
    static LIFT: OnceLock<(Regex, Regex)> = OnceLock::new();
    let (yes, no) = LIFT.get_or_init(|| {
        (
            Regex::new(r"(?i)\b(elev(ator)?|lifts?)\b|(?i)(aufzug|fahrstuhl|ascenseur|ascensor)")
                .unwrap_or_else(|_| Regex::new("$^").expect("empty regex")),
            Regex::new(
                r"(?i)\b(eq|equip(ment)?|machine|mach|mech(anical)?|motor|lobby|hall|rm|room|vestibule|control)\b|(?i)(raum|vorraum|maschinen)",
            )
            .unwrap_or_else(|_| Regex::new("$^").expect("empty regex")),
        )
    });
    yes.is_match(name) && !no.is_match(name)
}

/// Finds the vertical connections of `model` from its meshes, with landings on `floors` (the
/// model's storeys as floors, sorted by elevation); `clearance_m` is how far a landing stays
/// from obstacles (half the robot's width).
pub fn vertical_connections(
    model: &Model,
    meshes: &ModelMeshes,
    floors: &[Floor],
    clearance_m: f64,
) -> Vertical {
    let mut out = Vertical::default();
    stairs_and_ramps(model, meshes, floors, clearance_m, &mut out);
    lifts(model, meshes, floors, clearance_m, &mut out);
    out
}

/// The stair or ramp an element belongs to: its outermost `IfcStair`/`IfcRamp` whole, else
/// itself when it is a stair, ramp or flight; `None` for anything else.
fn transition_root(e: Entity<'_>) -> Option<(Entity<'_>, ConnectionKind)> {
    let kind_of = |x: &Entity<'_>| {
        if x.is_a("IfcStair") || x.is_a("IfcStairFlight") {
            Some(ConnectionKind::Stair)
        } else if x.is_a("IfcRamp") || x.is_a("IfcRampFlight") {
            Some(ConnectionKind::Ramp)
        } else {
            None
        }
    };
    if e.is_a("IfcRailing") {
        return None;
    }
    let mut found = kind_of(&e).map(|k| (e, k));
    let mut current = e;
    for _ in 0..8 {
        let Some(whole) = current
            .inverse("Decomposes")
            .into_iter()
            .filter(|r| r.is_a("IfcRelAggregates"))
            .find_map(|r| r.get_ref("RelatingObject"))
        else {
            break;
        };
        if let Some(k) = kind_of(&whole) {
            found = Some((whole, k));
        }
        current = whole;
    }
    found
}

/// The item of enumeration attribute `name` (`.ELEVATOR.` is `ELEVATOR`).
fn enum_attr<'m>(e: Entity<'m>, name: &str) -> Option<&'m str> {
    e.get(name).and_then(|v| v.as_enum())
}

struct Group<'a> {
    root: EntityId,
    class: String,
    id: String,
    name: Option<String>,
    kind: ConnectionKind,
    multi_run: bool,
    members: Vec<&'a ElementMesh>,
    flights: Vec<&'a ElementMesh>,
}

fn stairs_and_ramps(
    model: &Model,
    meshes: &ModelMeshes,
    floors: &[Floor],
    clearance_m: f64,
    out: &mut Vertical,
) {
    let mut groups: BTreeMap<usize, Group<'_>> = BTreeMap::new();
    for m in &meshes.elements {
        let Some(e) = model.entity(m.product) else {
            continue;
        };
        let Some((root, kind)) = transition_root(e) else {
            continue;
        };
        let g = groups.entry(root.position()).or_insert_with(|| Group {
            root: root.id(),
            class: root.type_name().to_string(),
            id: root
                .global_id()
                .unwrap_or_else(|| format!("#{}", root.id())),
            name: root.name(),
            kind,
            multi_run: enum_attr(root, "PredefinedType")
                .or_else(|| enum_attr(root, "ShapeType"))
                .is_some_and(|t| {
                    t.contains("TURN") || t.starts_with("TWO_") || t.contains("WINDING")
                }),
            members: Vec::new(),
            flights: Vec::new(),
        });
        g.members.push(m);
        if (e.is_a("IfcStairFlight") || e.is_a("IfcRampFlight")) && e.id() != g.root {
            g.flights.push(m);
        }
    }
    for g in groups.into_values() {
        match stair_or_ramp(&g, floors, clearance_m) {
            Ok(c) => {
                let shadow: Vec<Region> = region::union(
                    &g.members
                        .iter()
                        .flat_map(|m| poinav_geom::section::mesh_shadow(&m.mesh))
                        .collect::<Vec<_>>(),
                );
                let rings: Vec<Ring> = shadow.into_iter().map(|r| Ring::from(r.outer)).collect();
                if !rings.is_empty() {
                    for l in c.landings.iter().skip(1) {
                        out.shadows.push((
                            l.floor,
                            FloorObstacle {
                                id: g.id.as_str().into(),
                                class: g.class.clone(),
                                kind: ObstacleKind::Transition,
                                rings: rings.clone(),
                                roles: Vec::new(),
                            },
                        ));
                    }
                }
                out.connections.push(c)
            }
            Err(reason) => out.dropped.push(Dropped {
                id: g.id.clone(),
                name: g.name.clone(),
                kind: DroppedKind::Connection(g.kind),
                reason,
            }),
        }
    }
}

fn points_of<'a>(meshes: impl IntoIterator<Item = &'a ElementMesh>) -> Vec<DVec3> {
    meshes
        .into_iter()
        .flat_map(|m| m.mesh.positions.iter().copied())
        .filter(|p| p.is_finite())
        .collect()
}

/// The storey whose floor is nearest `z`, within [`STOREY_TOLERANCE_M`].
fn storey_at(floors: &[Floor], z: f64) -> Option<usize> {
    floors
        .iter()
        .enumerate()
        .map(|(i, f)| ((f.elevation_m - z).abs(), i))
        .filter(|(d, _)| *d <= STOREY_TOLERANCE_M)
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, i)| i)
}

fn stair_or_ramp(
    g: &Group<'_>,
    floors: &[Floor],
    clearance_m: f64,
) -> Result<VerticalConnection, String> {
    let points = points_of(g.members.iter().copied());
    let hull = Footprint::convex_hull_of(&points)
        .ok_or_else(|| "its meshes have no footprint".to_string())?;
    let (z0, z1) = (hull.z_min, hull.z_max);
    let bottom = storey_at(floors, z0).ok_or_else(|| {
        format!(
            "its lowest point (z = {z0:.2} m) is at no storey's floor (tolerance {STOREY_TOLERANCE_M} m)"
        )
    })?;
    let e0 = floors[bottom].elevation_m;
    let top = floors
        .iter()
        .enumerate()
        .filter(|(_, f)| {
            f.elevation_m > e0 + 1.0
                && f.elevation_m <= z1 + STOREY_TOLERANCE_M
                && f.elevation_m >= z1 - RAILING_ALLOWANCE_M
        })
        .max_by(|a, b| a.1.elevation_m.total_cmp(&b.1.elevation_m))
        .map(|(i, _)| i)
        .ok_or_else(|| {
            format!(
                "it rises from storey `{}` to z = {z1:.2} m, no other storey's floor",
                floors[bottom].name
            )
        })?;
    let e1 = floors[top].elevation_m;
    let near = |e: f64, lo: f64, hi: f64| -> Option<DVec2> {
        let pts: Vec<DVec2> = points
            .iter()
            .filter(|p| p.z >= e + lo && p.z <= e + hi)
            .map(|p| p.truncate())
            .collect();
        (!pts.is_empty()).then(|| pts.iter().copied().sum::<DVec2>() / pts.len() as f64)
    };
    // The way up at each end (the gradient of z over the first and last metre of rise), the
    // end step's front edge and the way off: down the first steps at the foot, on along the
    // last ones at the top.
    // (Not the points on the floor: the bottoms of steps modelled as blocks from the floor.)
    let foot_end = end_step(&points, e0 + 0.02, e0 + 1.0, false);
    let top_end = end_step(&points, e1 - 1.0, e1 + 0.05, true);
    let foot = foot_end
        .map(|(p, _)| p)
        .or_else(|| near(e0, -0.3, 0.3))
        .or_else(|| near(z0, 0.0, 0.3))
        .unwrap_or(hull.centroid());
    let head = top_end
        .map(|(p, _)| p)
        .or_else(|| near(e1, -0.3, 0.05))
        .or_else(|| near(z1, -0.3, 0.0))
        .unwrap_or(hull.centroid());
    let off_foot = foot_end.map(|(_, up)| -up);
    let off_top = top_end.map(|(_, up)| up);
    let what = g.kind.label();
    let mut landings = Vec::new();
    for (floor, at, off, end) in [
        (bottom, foot, off_foot, "foot"),
        (top, head, off_top, "top"),
    ] {
        let point = landing_off(&floors[floor], &hull.polygon, at, off, clearance_m)
            .ok_or_else(|| {
                format!(
                    "no free spot in a zone of storey `{}` within {SEARCH_REACH_M} m of the {what}'s {end} ({:.2}, {:.2})",
                    floors[floor].name, at.x, at.y
                )
            })?;
        landings.push(Landing { floor, point });
    }
    // A stair or ramp rising through several storeys stops at each storey in between where it
    // has a part at that floor's level (a landing there) with free space beside it.
    let top_landing = landings.pop();
    for (floor, f) in floors.iter().enumerate() {
        let e = f.elevation_m;
        if floor == bottom || floor == top || e <= e0 + 1.0 || e >= e1 - 1.0 {
            continue;
        }
        let Some(at) = near(e, -0.3, 0.3) else {
            continue;
        };
        if let Some(point) = landing_beside(f, &hull.polygon, at, clearance_m, &[]) {
            landings.push(Landing { floor, point });
        }
    }
    landings.extend(top_landing);
    let rects: Vec<_> = if g.flights.is_empty() {
        vec![hull.min_area_rectangle()]
    } else {
        g.flights
            .iter()
            .map(|f| {
                Footprint::convex_hull_of(&f.mesh.positions).and_then(|h| h.min_area_rectangle())
            })
            .collect()
    };
    let rects: Vec<_> = rects.into_iter().flatten().collect();
    let mut width = rects.iter().map(|r| r.width).fold(f64::INFINITY, f64::min);
    if g.flights.is_empty() && g.multi_run {
        width /= 2.0;
    }
    let run: f64 = rects.iter().map(|r| r.length).sum();
    let slope = (g.kind == ConnectionKind::Ramp && run > 0.0)
        .then(|| ((e1 - e0) / run).atan().to_degrees());
    Ok(VerticalConnection {
        id: g.id.as_str().into(),
        name: g.name.clone(),
        kind: g.kind,
        landings,
        clear_width_m: width.is_finite().then_some(width),
        slope_deg: slope,
        travel_time_s: None,
    })
}

/// One end of a flight from its points with `lo <= z <= hi`: the front edge of its end step
/// (the centre of the points furthest down the slope, or up it for the `top`, within 5 cm)
/// and the unit way up there (the least-squares gradient of z over XY); `None` when the
/// points do not rise in plan.
fn end_step(points: &[DVec3], lo: f64, hi: f64, top: bool) -> Option<(DVec2, DVec2)> {
    let pts: Vec<DVec3> = points
        .iter()
        .copied()
        .filter(|p| p.z >= lo && p.z <= hi)
        .collect();
    if pts.len() < 3 {
        return None;
    }
    let n = pts.len() as f64;
    let mean = pts.iter().copied().sum::<DVec3>() / n;
    let (mut cxx, mut cxy, mut cyy, mut rx, mut ry) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for p in &pts {
        let d = *p - mean;
        cxx += d.x * d.x;
        cxy += d.x * d.y;
        cyy += d.y * d.y;
        rx += d.x * d.z;
        ry += d.y * d.z;
    }
    let det = cxx * cyy - cxy * cxy;
    if det.abs() < 1e-12 {
        return None;
    }
    let grad = DVec2::new(cyy * rx - cxy * ry, cxx * ry - cxy * rx) / det;
    // A flight rises at least 10 cm per metre.
    if grad.length() < 0.1 {
        return None;
    }
    let up = grad.normalize();
    let key = |p: &DVec3| p.truncate().dot(up) * if top { -1.0 } else { 1.0 };
    let edge = pts.iter().map(key).fold(f64::INFINITY, f64::min);
    let front: Vec<DVec2> = pts
        .iter()
        .filter(|p| key(p) <= edge + 0.05)
        .map(|p| p.truncate())
        .collect();
    let at = front.iter().copied().sum::<DVec2>() / front.len() as f64;
    Some((at, up))
}

/// True when `p` is inside a zone of `floor` (other than the zones `except`) and at least
/// `clearance_m` from every obstacle.
fn free(floor: &Floor, p: DVec2, clearance_m: f64, except: &[&str]) -> bool {
    let in_zone = floor
        .zones
        .iter()
        .any(|z| !except.contains(&z.id.as_str()) && polygon::contains_closed(&z.ring, p));
    in_zone
        && floor.obstacles.iter().all(|o| {
            o.rings.iter().all(|r| {
                let Some((lo, hi)) = polygon::bounds(r) else {
                    return true;
                };
                let c = DVec2::splat(clearance_m);
                if p.cmplt(lo - c).any() || p.cmpgt(hi + c).any() {
                    return true;
                }
                !polygon::contains_closed(r, p) && polygon::boundary_distance(r, p) >= clearance_m
            })
        })
}

/// The landing at one end of a stair or ramp: a free spot on the walkable side of its end
/// step at `from`, reached from the footprint's edge in a straight line that crosses no wall
/// or other structure (so in the zone the stair opens onto, never behind its own wall): first
/// straight along `off` (the way off the stair), then turning up to 75 degrees either side;
/// without a way off known, or none free that way, in any direction from the footprint's
/// centre as [`landing_beside`] searches, with the same straight-line rule.
fn landing_off(
    floor: &Floor,
    footprint: &[DVec2],
    from: DVec2,
    off: Option<DVec2>,
    clearance_m: f64,
) -> Option<DVec2> {
    let clearance_m = clearance_m + LANDING_SLACK_M;
    if let Some(off) = off {
        let mut turns = vec![0.0];
        for k in 1..=5 {
            let a = (15.0 * k as f64).to_radians();
            turns.extend([a, -a]);
        }
        if let Some(p) = search_out(floor, footprint, from, off, &turns, clearance_m, &[], true) {
            return Some(p);
        }
    }
    let base = (from - polygon::centroid(footprint).unwrap_or_default())
        .try_normalize()
        .unwrap_or(DVec2::X);
    search_out(
        floor,
        footprint,
        from,
        base,
        &all_turns(),
        clearance_m,
        &[],
        true,
    )
}

/// True when the segment `a`-`b` passes through no structure (walls, columns, door frames,
/// holes in the floor) of `floor`, sampled every 2.5 cm.
fn unobstructed(floor: &Floor, a: DVec2, b: DVec2) -> bool {
    let n = ((b - a).length() / 0.025).ceil().max(1.0) as usize;
    (0..=n).all(|k| {
        let p = a.lerp(b, k as f64 / n as f64);
        floor
            .obstacles
            .iter()
            .filter(|o| o.kind == ObstacleKind::Structure)
            .all(|o| o.rings.iter().all(|r| !polygon::contains_closed(r, p)))
    })
}

/// Turns of 0, +-15, ... +-165 and 180 degrees.
fn all_turns() -> Vec<f64> {
    let mut turns = vec![0.0];
    for k in 1..=12 {
        let a = (15.0 * k as f64).to_radians();
        turns.push(a);
        if k < 12 {
            turns.push(-a);
        }
    }
    turns
}

/// The first free spot going out of `footprint` from `from` along `base` turned by each of
/// `turns` in turn (radians), at most [`SEARCH_REACH_M`] beyond [`FOOTPRINT_MARGIN_M`];
/// with `straight`, only spots the way from the footprint's edge to which is
/// [`unobstructed`].
#[allow(clippy::too_many_arguments)]
fn search_out(
    floor: &Floor,
    footprint: &[DVec2],
    from: DVec2,
    base: DVec2,
    turns: &[f64],
    clearance_m: f64,
    except: &[&str],
    straight: bool,
) -> Option<DVec2> {
    let outside = |p: DVec2| {
        !polygon::contains_closed(footprint, p)
            && polygon::boundary_distance(footprint, p) >= FOOTPRINT_MARGIN_M
    };
    for &a in turns {
        let d = DVec2::from_angle(a).rotate(base);
        let mut r = 0.0;
        while r < 20.0 && !outside(from + d * r) {
            r += 0.05;
        }
        let edge = from + d * r;
        let mut s = 0.0;
        while s <= SEARCH_REACH_M + 1e-9 {
            let p = edge + d * s;
            if free(floor, p, clearance_m, except) {
                if !straight || unobstructed(floor, edge, p) {
                    return Some(p);
                }
                break;
            }
            s += 0.1;
        }
    }
    None
}

/// A free spot outside `footprint` near `from`: first along the direction from the
/// footprint's centroid to `from`, then turning away from it in 15 degree steps; `None` when
/// there is none within [`SEARCH_REACH_M`] beyond [`FOOTPRINT_MARGIN_M`].
fn landing_beside(
    floor: &Floor,
    footprint: &[DVec2],
    from: DVec2,
    clearance_m: f64,
    except: &[&str],
) -> Option<DVec2> {
    let c = polygon::centroid(footprint).unwrap_or_default();
    let base = (from - c).try_normalize().unwrap_or(DVec2::X);
    search_out(
        floor,
        footprint,
        from,
        base,
        &all_turns(),
        clearance_m,
        except,
        false,
    )
}

struct LiftUnit {
    id: String,
    name: Option<String>,
    position: usize,
    hull: Footprint,
}

fn lifts(
    model: &Model,
    meshes: &ModelMeshes,
    floors: &[Floor],
    clearance_m: f64,
    out: &mut Vertical,
) {
    let mut units: Vec<LiftUnit> = Vec::new();
    for m in meshes.elements.iter().chain(&meshes.spaces) {
        let Some(e) = model.entity(m.product) else {
            continue;
        };
        let is_lift = if e.is_a("IfcSpace") {
            let long = e.get_str("LongName");
            let named = [m.name.as_deref(), long.as_deref()]
                .into_iter()
                .flatten()
                .any(is_lift_name);
            named
        } else {
            e.is_a("IfcTransportElement")
                && ["PredefinedType", "OperationType"]
                    .iter()
                    .any(|a| enum_attr(e, a) == Some("ELEVATOR"))
        };
        if !is_lift {
            continue;
        }
        let Some(hull) = Footprint::convex_hull_of(&m.mesh.positions) else {
            continue;
        };
        let long = e.get_str("LongName").filter(|s| !s.is_empty());
        units.push(LiftUnit {
            id: m.global_id.clone(),
            name: match (&m.name, long) {
                (Some(n), Some(l)) if *n != l => Some(format!("{l} {n}")),
                (n, l) => l.or_else(|| n.clone()),
            },
            position: e.position(),
            hull,
        });
    }
    units.sort_by_key(|u| u.position);
    // Stacks: units whose footprints overlap by 30 % of the smaller one.
    let regions: Vec<Vec<Region>> = units
        .iter()
        .map(|u| {
            Region::from_ring(u.hull.polygon.clone())
                .into_iter()
                .collect()
        })
        .collect();
    let mut stack: Vec<usize> = (0..units.len()).collect();
    for i in 0..units.len() {
        for j in 0..i {
            let common = region::total_area(&region::intersection(&regions[i], &regions[j]));
            if common >= 0.3 * units[i].hull.area().min(units[j].hull.area()) {
                let (a, b) = (root(&stack, i), root(&stack, j));
                stack[a.max(b)] = a.min(b);
            }
        }
    }
    let mut stacks: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for i in 0..units.len() {
        stacks.entry(root(&stack, i)).or_default().push(i);
    }
    for members in stacks.into_values() {
        let first = &units[members[0]];
        let mut stops: BTreeMap<usize, &LiftUnit> = BTreeMap::new();
        for &i in &members {
            let u = &units[i];
            for (k, f) in floors.iter().enumerate() {
                if f.elevation_m >= u.hull.z_min - STOREY_TOLERANCE_M
                    && f.elevation_m <= u.hull.z_max - LIFT_HEADROOM_M
                {
                    stops.entry(k).or_insert(u);
                }
            }
        }
        let mut landings = Vec::new();
        let mut widths = Vec::new();
        let mut missing = Vec::new();
        for (&k, u) in &stops {
            match lift_landing(&floors[k], u, clearance_m) {
                Some((point, width)) => {
                    landings.push(Landing { floor: k, point });
                    widths.extend(width);
                }
                None => missing.push(floors[k].name.clone()),
            }
        }
        if landings.len() < 2 {
            let reason = if stops.len() < 2 {
                format!(
                    "it serves {} storey(s) (z {:.2}..{:.2} m)",
                    stops.len(),
                    first.hull.z_min,
                    first.hull.z_max
                )
            } else {
                format!(
                    "no free spot in a zone beside it on storey(s) {}",
                    missing.join(", ")
                )
            };
            out.dropped.push(Dropped {
                id: first.id.clone(),
                name: first.name.clone(),
                kind: DroppedKind::Connection(ConnectionKind::Lift),
                reason,
            });
            continue;
        }
        out.connections.push(VerticalConnection {
            id: first.id.as_str().into(),
            name: first.name.clone(),
            kind: ConnectionKind::Lift,
            landings,
            clear_width_m: widths.into_iter().reduce(f64::min),
            slope_deg: None,
            travel_time_s: None,
        });
    }
}

fn root(parent: &[usize], mut i: usize) -> usize {
    while parent[i] != i {
        i = parent[i];
    }
    i
}

/// The landing of lift `u` on `floor`: in front of the door nearest its footprint (with the
/// door's clear width), else a free spot beside it (its own zone, a shaft without a modelled
/// door, is left out), else its centroid.
fn lift_landing(floor: &Floor, u: &LiftUnit, clearance_m: f64) -> Option<(DVec2, Option<f64>)> {
    let ring = &u.hull.polygon;
    let c = polygon::centroid(ring).unwrap_or_default();
    let door = floor
        .doors
        .iter()
        .map(|d| {
            let dist = if polygon::contains_closed(ring, d.center) {
                0.0
            } else {
                polygon::boundary_distance(ring, d.center)
            };
            (dist, d)
        })
        .filter(|(dist, _)| *dist <= 0.75)
        .min_by(|a, b| a.0.total_cmp(&b.0));
    if let Some((_, d)) = door {
        if let Some(p) = landing_beside(floor, ring, d.center, clearance_m, &[u.id.as_str()]) {
            return Some((
                p,
                Some(d.clear_width_m).filter(|w| w.is_finite() && *w > 0.0),
            ));
        }
    }
    // Beside it: of the first free spots in each direction, the one in the zone with the most
    // doors (a corridor or lobby rather than a closed room beside the shaft).
    let doors_of = |p: DVec2| {
        floor
            .zones
            .iter()
            .filter(|z| z.id != u.id && polygon::contains_closed(&z.ring, p))
            .map(|z| {
                floor
                    .doors
                    .iter()
                    .filter(|d| {
                        polygon::contains_closed(&z.ring, d.center)
                            || polygon::boundary_distance(&z.ring, d.center) <= 0.5
                    })
                    .count()
            })
            .max()
            .unwrap_or(0)
    };
    let mut best: Option<(usize, DVec2)> = None;
    for k in 0..24 {
        let d = DVec2::from_angle((15.0 * k as f64).to_radians());
        if let Some(p) = landing_beside(floor, ring, c + d * 0.01, clearance_m, &[u.id.as_str()]) {
            let n = doors_of(p);
            if best.is_none_or(|(m, _)| n > m) {
                best = Some((n, p));
            }
        }
    }
    best.map(|(_, p)| (p, None))
        .or_else(|| free(floor, c, clearance_m, &[]).then_some((c, None)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lift_names_but_not_the_rooms_around_lifts() {
        for yes in [
            "ELEV",
            "Elevator 2",
            "Lift",
            "Aufzug",
            "Personenaufzug",
            "ascenseur",
        ] {
            assert!(is_lift_name(yes), "{yes}");
        }
        for no in [
            "ELEV EQ RM",
            "Lift lobby",
            "Aufzugsmaschinenraum",
            "Elevation",
            "Stair",
        ] {
            assert!(!is_lift_name(no), "{no}");
        }
    }

    /// Three storeys 3 m apart, each one open zone.
    fn three_storeys(elevations: &[f64]) -> Vec<Floor> {
        elevations
            .iter()
            .enumerate()
            .map(|(i, &e)| Floor {
                name: format!("L{i}"),
                elevation_m: e,
                zones: vec![poinav_nav::FloorZone {
                    id: format!("z{i}").into(),
                    name: None,
                    long_name: None,
                    ring: polygon::rect(-5.0, -5.0, 20.0, 10.0),
                    roles: vec![],
                    coordination: None,
                }],
                ..Floor::default()
            })
            .collect()
    }

    #[test]
    fn a_stair_rising_through_a_storey_lands_on_it_too() {
        // One straight flight, 1.2 m wide, rising 6 m over 12 m: it passes the middle
        // storey's floor at x = 6.
        let positions: Vec<DVec3> = (0..=12)
            .flat_map(|k| [0.0, 1.2].map(|y| DVec3::new(k as f64, y, k as f64 / 2.0)))
            .collect();
        let mesh = ElementMesh {
            product: EntityId(1),
            global_id: "stair".into(),
            class: "IfcStair".into(),
            name: Some("Stair".into()),
            storey: None,
            mesh: poinav_geom::Mesh {
                positions,
                triangles: vec![],
            },
            color: None,
        };
        let group = Group {
            root: EntityId(1),
            id: "stair".into(),
            name: Some("Stair".into()),
            kind: ConnectionKind::Stair,
            class: "IfcStair".into(),
            multi_run: false,
            members: vec![&mesh],
            flights: vec![],
        };
        let floors = three_storeys(&[0.0, 3.0, 6.0]);
        let c = stair_or_ramp(&group, &floors, 0.4).unwrap();
        let on: Vec<usize> = c.landings.iter().map(|l| l.floor).collect();
        assert_eq!(on, [0, 1, 2], "bottom, the storey passed, top: {c:?}");
        for l in &c.landings {
            let p = l.point;
            let in_footprint = (0.0..=12.0).contains(&p.x) && (0.0..=1.2).contains(&p.y);
            assert!(
                !in_footprint && free(&floors[l.floor], p, 0.4, &[]),
                "{l:?}"
            );
        }
        assert!(
            c.landings[0].point.x < 0.0 && c.landings[2].point.x > 12.0,
            "{c:?}"
        );
        assert!((c.clear_width_m.unwrap() - 1.2).abs() < 1e-9, "{c:?}");
        // A storey less than a metre above the foot (a mezzanine step) gets no landing.
        let floors = three_storeys(&[0.0, 0.8, 6.0]);
        let c = stair_or_ramp(&group, &floors, 0.4).unwrap();
        let on: Vec<usize> = c.landings.iter().map(|l| l.floor).collect();
        assert_eq!(on, [0, 2], "{c:?}");
    }
}
