//! Hand-made floors for the tests and the benchmark: the paper's test building from
//! `poinav_author::DemoBuilding::layout()` (walls as rectangles with gaps for the doors) and a
//! large office storey (60 x 40 m, 98 rooms) standing in for office-a.ifc until the IFC ->
//! Floor converter lands.

#![allow(dead_code)]

use glam::DVec2;
use poinav_author::DemoBuilding;
use poinav_nav::building::width_status;
use poinav_nav::building::{ConnectionKind, Landing, VerticalConnection};
pub use poinav_nav::polygon::rect;
use poinav_nav::{Building, Floor, FloorDoor, FloorObstacle, FloorZone, ObstacleKind, Ring};
use poinav_poi::{AccessibilityStatus, CoordinationProtocol, RobotProfile, Role};

pub fn wall(id: &str, rings: Vec<Ring>) -> FloorObstacle {
    FloorObstacle {
        id: id.into(),
        class: "IfcWall".into(),
        kind: ObstacleKind::Structure,
        rings,
        roles: vec![Role::Avoidance, Role::PathGuidance],
    }
}

/// A door in the ring `ring` as the enrichment would classify it for the paper robot.
pub fn door(id: &str, name: &str, ring: Ring, clear_width_m: f64) -> FloorDoor {
    let profile = RobotProfile::paper();
    let (status, _) = width_status(clear_width_m, &profile);
    let mut roles = vec![Role::Transition];
    if status != AccessibilityStatus::FullAccess {
        roles.push(Role::Narrow);
    }
    let center = ring.iter().copied().sum::<DVec2>() / ring.len() as f64;
    FloorDoor {
        id: id.into(),
        name: Some(name.into()),
        ring,
        center,
        clear_width_m,
        classified_width_m: Some(clear_width_m),
        blocked: None,
        roles,
        spaces: None,
        doorless: false,
        terrain: false,
    }
}

pub fn room(id: &str, name: &str, ring: Ring) -> FloorZone {
    FloorZone {
        id: id.into(),
        name: Some(name.into()),
        long_name: None,
        ring,
        roles: vec![Role::Destination],
        coordination: None,
    }
}

pub fn corridor(id: &str, name: &str, ring: Ring) -> FloorZone {
    FloorZone {
        id: id.into(),
        name: Some(name.into()),
        long_name: None,
        ring,
        roles: vec![Role::PathGuidance, Role::MultiRobotZone],
        coordination: Some((2.0, CoordinationProtocol::SpeedReduction)),
    }
}

/// Walls along one line (`horizontal` at `at`..`at + t`, or vertical) from `from` to `to`
/// with gaps `(centre, width)`.
fn wall_with_gaps(
    horizontal: bool,
    at: f64,
    t: f64,
    from: f64,
    to: f64,
    gaps: &[(f64, f64)],
) -> Vec<Ring> {
    let mut gaps: Vec<(f64, f64)> = gaps
        .iter()
        .map(|(c, w)| (c - w / 2.0, c + w / 2.0))
        .collect();
    gaps.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut rings = Vec::new();
    let mut x = from;
    for (g0, g1) in gaps.into_iter().chain([(to, to)]) {
        if g0 > x + 1e-9 {
            rings.push(if horizontal {
                rect(x, at, g0, at + t)
            } else {
                rect(at, x, at + t, g0)
            });
        }
        x = g1;
    }
    rings
}

/// The paper's test building (one storey) built from `spec`'s layout.
pub fn demo_floor(spec: &DemoBuilding) -> Floor {
    let layout = spec.layout();
    let t = spec.wall_thickness_m;
    let (lx, ly) = (spec.length_m(), spec.depth_m());
    let (c0, c1) = (layout.corridor_min[1], layout.corridor_max[1]);
    let mut obstacles = vec![
        wall("wall-ext-s", vec![rect(-t, -t, lx + t, 0.0)]),
        wall("wall-ext-n", vec![rect(-t, ly, lx + t, ly + t)]),
        wall("wall-ext-w", vec![rect(-t, 0.0, 0.0, ly)]),
        wall("wall-ext-e", vec![rect(lx, 0.0, lx + t, ly)]),
    ];
    let mut doors = Vec::new();
    for (id, side, y0) in [("wall-cor-s", -1.0, c0 - t), ("wall-cor-n", 1.0, c1)] {
        let mut gaps = Vec::new();
        for r in layout.rooms.iter().filter(|r| r.door.side == side) {
            let (cx, w) = (r.door.center[0], r.door.width_m);
            gaps.push((cx, w));
            doors.push(door(
                &format!("door-{}", r.name.to_lowercase().replace(' ', "-")),
                &r.door.name,
                rect(cx - w / 2.0, y0, cx + w / 2.0, y0 + t),
                w,
            ));
        }
        obstacles.push(wall(id, wall_with_gaps(true, y0, t, 0.0, lx, &gaps)));
    }
    for i in 1..spec.rooms_per_side {
        let x = i as f64 * (spec.room_width_m + t) - t;
        obstacles.push(wall(
            &format!("wall-part-s{i}"),
            vec![rect(x, 0.0, x + t, spec.room_depth_m)],
        ));
        obstacles.push(wall(
            &format!("wall-part-n{i}"),
            vec![rect(x, c1 + t, x + t, c1 + t + spec.room_depth_m)],
        ));
    }
    let mut zones: Vec<FloorZone> = layout
        .rooms
        .iter()
        .map(|r| {
            room(
                &format!("space-{}", r.name.to_lowercase().replace(' ', "-")),
                &r.name,
                rect(r.min[0], r.min[1], r.max[0], r.max[1]),
            )
        })
        .collect();
    zones.push(corridor(
        "space-corridor",
        "Corridor",
        rect(
            layout.corridor_min[0],
            layout.corridor_min[1],
            layout.corridor_max[0],
            layout.corridor_max[1],
        ),
    ));
    Floor {
        name: "Ground floor".into(),
        elevation_m: 0.0,
        obstacles,
        doors,
        zones,
    }
}

/// The default test building.
pub fn demo() -> Floor {
    demo_floor(&DemoBuilding::default())
}

/// Every coordinate turned by `angle` radians about the origin.
pub fn rotated(floor: &Floor, angle: f64) -> Floor {
    let r = DVec2::from_angle(angle);
    let turn = |ring: &Ring| ring.iter().map(|p| r.rotate(*p)).collect::<Ring>();
    let mut f = floor.clone();
    for o in &mut f.obstacles {
        o.rings = o.rings.iter().map(turn).collect();
    }
    for d in &mut f.doors {
        d.ring = turn(&d.ring);
        d.center = r.rotate(d.center);
    }
    for z in &mut f.zones {
        z.ring = turn(&z.ring);
    }
    f
}

/// Rooms along `[x0, x1]` at pitch about `pitch` (walls `t` between them).
fn split(x0: f64, x1: f64, pitch: f64, t: f64) -> Vec<(f64, f64)> {
    let n = (((x1 - x0) + t) / pitch).floor().max(1.0) as usize;
    let w = ((x1 - x0) - (n as f64 - 1.0) * t) / n as f64;
    (0..n)
        .map(|i| {
            let a = x0 + i as f64 * (w + t);
            (a, a + w)
        })
        .collect()
}

/// A large office storey, 60 x 40 m inside: two east-west corridors (2.4 m) joined by a
/// north-south hall in the middle, 98 rooms of about 2.2 x 8.5 m with a desk each, 1.0 m
/// doors (every 7th 0.80 m, RESTRICTED; room 50's 0.60 m, BLOCKED), every 10th room a hazard
/// (B-1), and two entrances (1.8 m) at the corridors' west and east ends.
pub fn office_floor() -> Floor {
    let t = 0.2;
    let te = 0.25;
    let (lx, ly) = (60.0, 40.0);
    let (a0, a1) = (9.0, 11.4); // corridor A
    let (b0, b1) = (28.6, 31.0); // corridor B
    let (h0, h1) = (28.8, 31.2); // hall between them
    let mid = 20.0; // wall between bands 2 and 3: [mid - t/2, mid + t/2]
    let mut obstacles = Vec::new();
    let mut doors = Vec::new();
    let mut zones = Vec::new();
    // Exterior walls with the two entrances.
    obstacles.push(wall("ext-s", vec![rect(-te, -te, lx + te, 0.0)]));
    obstacles.push(wall("ext-n", vec![rect(-te, ly, lx + te, ly + te)]));
    let ea = ((a0 + a1) / 2.0, 1.8);
    let eb = ((b0 + b1) / 2.0, 1.8);
    obstacles.push(wall(
        "ext-w",
        wall_with_gaps(false, -te, te, 0.0, ly, &[ea]),
    ));
    obstacles.push(wall("ext-e", wall_with_gaps(false, lx, te, 0.0, ly, &[eb])));
    doors.push(door(
        "entrance-w",
        "Entrance West",
        rect(-te, ea.0 - 0.9, 0.0, ea.0 + 0.9),
        1.8,
    ));
    doors.push(door(
        "entrance-e",
        "Entrance East",
        rect(lx, eb.0 - 0.9, lx + te, eb.0 + 0.9),
        1.8,
    ));
    zones.push(corridor("corridor-a", "Corridor A", rect(0.0, a0, lx, a1)));
    zones.push(corridor("corridor-b", "Corridor B", rect(0.0, b0, lx, b1)));
    zones.push(corridor("hall", "Hall", rect(h0, a1, h1, b0)));
    // Bands: (y0, y1, door wall y, door wall is below the band?)
    struct Band {
        y0: f64,
        y1: f64,
        spans: Vec<(f64, f64)>,
        door_wall: f64,
    }
    let bands = [
        Band {
            y0: 0.0,
            y1: a0 - t,
            spans: vec![(0.0, lx)],
            door_wall: a0 - t,
        },
        Band {
            y0: a1 + t,
            y1: mid - t / 2.0,
            spans: vec![(0.0, h0 - t), (h1 + t, lx)],
            door_wall: a1,
        },
        Band {
            y0: mid + t / 2.0,
            y1: b0 - t,
            spans: vec![(0.0, h0 - t), (h1 + t, lx)],
            door_wall: b0 - t,
        },
        Band {
            y0: b1 + t,
            y1: ly,
            spans: vec![(0.0, lx)],
            door_wall: b1,
        },
    ];
    let mut number = 0;
    for (bi, band) in bands.iter().enumerate() {
        let mut gaps = Vec::new();
        for &(s0, s1) in &band.spans {
            let rooms = split(s0, s1, 2.4, t);
            for (ri, &(x0, x1)) in rooms.iter().enumerate() {
                number += 1;
                let name = format!("Office {number}");
                let width = if number == 50 {
                    0.6
                } else if number % 7 == 0 {
                    0.8
                } else {
                    1.0
                };
                let cx = (x0 + x1) / 2.0;
                gaps.push((cx, width));
                doors.push(door(
                    &format!("door-{number}"),
                    &format!("Door {name}"),
                    rect(
                        cx - width / 2.0,
                        band.door_wall,
                        cx + width / 2.0,
                        band.door_wall + t,
                    ),
                    width,
                ));
                let mut z = room(
                    &format!("office-{number}"),
                    &name,
                    rect(x0, band.y0, x1, band.y1),
                );
                if number % 10 == 0 {
                    z.roles.push(Role::Hazard);
                }
                zones.push(z);
                // A desk at the far end of the room.
                let far = if band.door_wall > band.y0 {
                    band.y0 + 0.3
                } else {
                    band.y1 - 1.0
                };
                obstacles.push(FloorObstacle {
                    id: format!("desk-{number}").into(),
                    class: "IfcFurniture".into(),
                    kind: ObstacleKind::Furniture,
                    rings: vec![rect(x0 + 0.3, far, x0 + 1.7, far + 0.7)],
                    roles: vec![Role::Avoidance],
                });
                if ri + 1 < rooms.len() {
                    obstacles.push(wall(
                        &format!("part-{bi}-{number}"),
                        vec![rect(x1, band.y0, x1 + t, band.y1)],
                    ));
                }
            }
        }
        obstacles.push(wall(
            &format!("corridor-wall-{bi}"),
            wall_with_gaps(true, band.door_wall, t, 0.0, lx, &gaps),
        ));
    }
    // Walls between bands 2 and 3, and along the hall.
    obstacles.push(wall(
        "mid",
        vec![
            rect(0.0, mid - t / 2.0, h0 - t, mid + t / 2.0),
            rect(h1 + t, mid - t / 2.0, lx, mid + t / 2.0),
        ],
    ));
    obstacles.push(wall("hall-w", vec![rect(h0 - t, a1 + t, h0, b0 - t)]));
    obstacles.push(wall("hall-e", vec![rect(h1, a1 + t, h1 + t, b0 - t)]));
    // Cut the corridor walls where the hall opens onto the corridors.
    for o in obstacles
        .iter_mut()
        .filter(|o| o.id == "corridor-wall-1" || o.id == "corridor-wall-2")
    {
        let mut rings = Vec::new();
        for r in &o.rings {
            let (x0, x1) = (r[0].x, r[1].x);
            let (y0, y1) = (r[0].y, r[2].y);
            if x1 <= h0 || x0 >= h1 {
                rings.push(r.clone());
                continue;
            }
            if x0 < h0 {
                rings.push(rect(x0, y0, h0, y1));
            }
            if x1 > h1 {
                rings.push(rect(h1, y0, x1, y1));
            }
        }
        o.rings = rings;
    }
    Floor {
        name: "Office level".into(),
        elevation_m: 0.0,
        obstacles,
        doors,
        zones,
    }
}

/// The demo floor twice (ground, first floor 3.5 m up) joined by a stair near Room 1 and, if
/// `with_lift`, a lift near Room 6 (no travel times given: estimated from the heights).
pub fn two_storeys(with_lift: bool) -> Building {
    let ground = demo();
    let mut first = demo();
    first.name = "First floor".into();
    first.elevation_m = 3.5;
    let mut connections = vec![VerticalConnection {
        id: "stair-1".into(),
        name: Some("Stair".into()),
        kind: ConnectionKind::Stair,
        landings: vec![
            Landing {
                floor: 0,
                point: DVec2::new(0.8, 5.4),
            },
            Landing {
                floor: 1,
                point: DVec2::new(0.8, 5.4),
            },
        ],
        clear_width_m: Some(1.2),
        slope_deg: None,
        travel_time_s: None,
    }];
    if with_lift {
        connections.push(VerticalConnection {
            id: "lift-1".into(),
            name: Some("Lift".into()),
            kind: ConnectionKind::Lift,
            landings: vec![
                Landing {
                    floor: 0,
                    point: DVec2::new(11.6, 5.4),
                },
                Landing {
                    floor: 1,
                    point: DVec2::new(11.6, 5.4),
                },
            ],
            clear_width_m: Some(1.1),
            slope_deg: None,
            travel_time_s: None,
        });
    }
    Building {
        floors: vec![ground, first],
        connections,
        levels: vec![],
    }
}
