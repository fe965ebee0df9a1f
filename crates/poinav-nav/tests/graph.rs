//! Door sides in the topology: from geometry (the zones beyond the passage's faces), and from
//! the spaces a door bounds when the floor model has them (IfcRelSpaceBoundary in IFC), which
//! settle doors whose geometry is ambiguous.

mod support;

use glam::DVec2;
use poinav_nav::graph::{door_zones, zone_near, Topology};
use poinav_nav::zone_index::ZoneIndex;
use poinav_nav::{Building, DoorFrame, Floor, ZoneIdx};
use support::{door, rect, room};

/// A square 1 x 1 m passage (a door in a wall as thick as the door is wide) with the hall
/// north of it, a kitchen west and an office east, nothing south: an entrance whose ring alone
/// does not say which way it opens.
fn ambiguous_entrance() -> Floor {
    Floor {
        name: "Ground".into(),
        doors: vec![door("front", "Front door", rect(1.0, -1.0, 2.0, 0.0), 0.9)],
        zones: vec![
            room("hall", "Hall", rect(0.0, 0.0, 3.0, 3.0)),
            room("kitchen", "Kitchen", rect(-1.0, -1.0, 1.0, 0.0)),
            room("office", "Office", rect(2.0, -1.0, 4.0, 0.0)),
        ],
        ..Floor::default()
    }
}

fn names(floor: &Floor, sides: [Option<ZoneIdx>; 2]) -> Vec<&str> {
    let mut v: Vec<&str> = sides
        .iter()
        .map(|z| z.map_or("outside", |z| floor.zones[z.get()].name.as_deref().unwrap()))
        .collect();
    v.sort_unstable();
    v
}

#[test]
fn space_boundaries_decide_the_sides_of_an_ambiguous_door() {
    let mut floor = ambiguous_entrance();
    // Geometry alone: the orientation with zones beyond both faces wins.
    assert_eq!(names(&floor, door_zones(&floor, 0)), ["Kitchen", "Office"]);
    // The door bounds the hall only: an entrance from the hall.
    floor.doors[0].spaces = Some(vec!["hall".into()]);
    let sides = door_zones(&floor, 0);
    assert_eq!(names(&floor, sides), ["Hall", "outside"]);
    let frame = floor.door_frame(0).unwrap();
    assert!(frame.normal.x.abs() < 1e-9, "{frame:?}");
    let topology = Topology::build(&Building::single(floor.clone()));
    let d = &topology.doors[0];
    assert!(d.exterior() && d.from_spaces);
    assert_eq!(topology.entrances(), vec![d.node]);
    // Two spaces: those two, each on the side where geometry finds it.
    floor.doors[0].spaces = Some(vec!["hall".into(), "office".into()]);
    assert_eq!(names(&floor, door_zones(&floor, 0)), ["Hall", "Office"]);
    // Spaces that are not on this floor: geometry decides.
    floor.doors[0].spaces = Some(vec!["elsewhere".into()]);
    assert_eq!(names(&floor, door_zones(&floor, 0)), ["Kitchen", "Office"]);
    assert!(!Topology::build(&Building::single(floor)).doors[0].from_spaces);
}

/// A hall with an opening (no door) in its south wall into a shaft that has no space, and a
/// real door in its east wall to the outside.
fn hall_with_doorway() -> Floor {
    let mut doorway = door(
        "shaft-opening",
        "Doorway #7",
        rect(1.0, -0.2, 2.2, 0.0),
        1.2,
    );
    doorway.doorless = true;
    Floor {
        name: "Ground".into(),
        obstacles: vec![support::wall(
            "walls",
            vec![
                rect(-0.2, -0.2, 1.0, 0.0),
                rect(2.2, -0.2, 4.2, 0.0),
                rect(-0.2, 3.0, 4.2, 3.2),
                rect(-0.2, 0.0, 0.0, 3.0),
                rect(4.0, 0.0, 4.2, 1.0),
                rect(4.0, 2.0, 4.2, 3.0),
            ],
        )],
        doors: vec![
            doorway,
            door("east", "East door", rect(4.0, 1.0, 4.2, 2.0), 1.0),
        ],
        zones: vec![room("hall", "Hall", rect(0.0, 0.0, 4.0, 3.0))],
        ..Floor::default()
    }
}

#[test]
fn a_doorway_into_an_undescribed_room_is_no_entrance() {
    use poinav_nav::{CellState, NavOptions, Navigator};
    use poinav_poi::RobotProfile;
    let floor = hall_with_doorway();
    // Both have the hall on one side only; only the door is an entrance.
    assert_eq!(names(&floor, door_zones(&floor, 0)), ["Hall", "outside"]);
    let building = Building::single(floor);
    let topology = Topology::build(&building);
    let (doorway, east) = (&topology.doors[0], &topology.doors[1]);
    assert!(doorway.doorless && !doorway.exterior() && doorway.outside_side().is_none());
    assert!(east.exterior() && !east.doorless);
    assert_eq!(topology.entrances(), vec![east.node]);
    // The grid has an apron outside the door but none beyond the doorway (the shaft stays
    // unknown), so the doorway leads nowhere and the topology JSON says what it is.
    let nav = Navigator::new(&building, &RobotProfile::paper(), &NavOptions::default()).unwrap();
    let g = &nav.floors[0].grid.occupancy;
    let at = |x: f64, y: f64| g.cells[g.cell_of(glam::DVec2::new(x, y)).unwrap()];
    assert_eq!(at(4.7, 1.5), CellState::Free, "apron outside the east door");
    assert_eq!(
        at(1.6, -0.7),
        CellState::Unknown,
        "no apron beyond the doorway"
    );
    assert_eq!(at(1.6, -0.1), CellState::Free, "the doorway's passage");
    assert!(!nav.grid_passable[doorway.node]);
    let json = nav.topology_json();
    let node = &json["nodes"][doorway.node];
    assert_eq!(
        (node["doorless"].as_bool(), node["exterior"].as_bool()),
        (Some(true), Some(false))
    );
    assert_eq!(json["nodes"][east.node]["doorless"].as_bool(), Some(false));
}

/// A hall (4 x 3 m) with a front door in its east wall and a door in its north wall into a
/// walled-in closet (1 x 0.8 m) that has no space.
fn hall_with_closet() -> Floor {
    Floor {
        name: "Ground".into(),
        obstacles: vec![support::wall(
            "walls",
            vec![
                rect(-0.2, -0.2, 4.2, 0.0),
                rect(-0.2, 3.0, 1.0, 3.2),
                rect(2.0, 3.0, 4.2, 3.2),
                rect(-0.2, 0.0, 0.0, 3.0),
                rect(4.0, 0.0, 4.2, 1.0),
                rect(4.0, 2.0, 4.2, 3.0),
                // The closet north of the hall: 1.0 m wide inside, 0.8 m deep.
                rect(0.8, 3.2, 1.0, 4.2),
                rect(2.0, 3.2, 2.2, 4.2),
                rect(0.8, 4.0, 2.2, 4.2),
            ],
        )],
        doors: vec![
            door("closet", "Closet door", rect(1.0, 3.0, 2.0, 3.2), 0.95),
            door("front", "Front door", rect(4.0, 1.0, 4.2, 2.0), 1.0),
        ],
        zones: vec![room("hall", "Hall", rect(0.0, 0.0, 4.0, 3.0))],
        ..Floor::default()
    }
}

#[test]
fn a_door_into_a_walled_in_room_without_a_space_is_no_entrance() {
    use poinav_nav::{NavOptions, Navigator, Place};
    use poinav_poi::RobotProfile;
    let building = Building::single(hall_with_closet());
    // The topology alone cannot tell: both doors have the hall on one side only.
    let topology = Topology::build(&building);
    assert!(topology.doors.iter().all(|d| d.exterior()));
    // The grid can: the closet is walled in, the front door opens onto the outside.
    let nav = Navigator::new(&building, &RobotProfile::paper(), &NavOptions::default()).unwrap();
    let (closet, front) = (&nav.topology.doors[0], &nav.topology.doors[1]);
    assert!(closet.walled_in && !closet.exterior(), "{closet:?}");
    assert!(!front.walled_in && front.exterior(), "{front:?}");
    assert_eq!(nav.topology.entrances(), vec![front.node]);
    // Routes from outside come in by the front door.
    let outside: Place = "outside".parse().unwrap();
    let route = nav.route(&outside, &Place::zone("Hall")).unwrap();
    let doors: Vec<&str> = route
        .doors
        .iter()
        .map(|d| d.name.as_deref().unwrap())
        .collect();
    assert_eq!(doors, ["Front door"]);
    let json = nav.topology_json();
    assert_eq!(
        json["nodes"][closet.node]["exterior"].as_bool(),
        Some(false)
    );
    // The grid decides it and paints no apron for it: with a 1.5 m apron, one would reach
    // past the closet's back wall (y 4.0-4.2) into the outside.
    let mut options = NavOptions::default();
    options.grid.entrance_apron_m = 1.5;
    let nav = Navigator::new(&building, &RobotProfile::paper(), &options).unwrap();
    let g = &nav.floors[0].grid.occupancy;
    assert!(g.doors[0].walled_in && !g.doors[1].walled_in);
    let at = |x: f64, y: f64| g.cells[g.cell_of(glam::DVec2::new(x, y)).unwrap()];
    assert_eq!(
        at(1.5, 4.4),
        poinav_nav::CellState::Unknown,
        "outside behind the closet"
    );
    assert_eq!(
        at(5.0, 1.5),
        poinav_nav::CellState::Free,
        "the front door's apron"
    );
}

/// Rooms A, B, C in a row (doors A-B and B-C) above a corridor D (doors A-D and C-D): the
/// door path the simulator's robots plan with.
fn row_above_corridor() -> Floor {
    Floor {
        name: "Ground".into(),
        doors: vec![
            door("ab", "A-B", rect(3.0, 1.0, 3.2, 2.0), 0.9),
            door("bc", "B-C", rect(6.2, 1.0, 6.4, 2.0), 0.9),
            door("ad", "A-D", rect(1.0, -0.2, 2.0, 0.0), 0.9),
            door("cd", "C-D", rect(7.4, -0.2, 8.4, 0.0), 0.9),
        ],
        zones: vec![
            room("a", "A", rect(0.0, 0.0, 3.0, 3.0)),
            room("b", "B", rect(3.2, 0.0, 6.2, 3.0)),
            room("c", "C", rect(6.4, 0.0, 9.4, 3.0)),
            room("d", "D", rect(0.0, -2.2, 9.4, -0.2)),
        ],
        ..Floor::default()
    }
}

#[test]
fn door_paths_take_the_shortest_way_through_usable_doors() {
    let floor = row_above_corridor();
    let topology = Topology::build(&Building::single(floor.clone()));
    let all = |_: usize| true;
    // Zones and doors by their plain indices.
    let door_path = |floor: usize, from: usize, to: usize, usable: &dyn Fn(usize) -> bool| {
        let (from, to) = (ZoneIdx::new(from), ZoneIdx::new(to));
        topology
            .door_path(floor, from, to, |k| usable(k.get()))
            .map(|doors| doors.iter().map(|d| d.get()).collect::<Vec<_>>())
    };
    assert_eq!(door_path(0, 0, 0, &all), Some(vec![]));
    assert_eq!(door_path(0, 0, 1, &all), Some(vec![0]));
    // Through B (6.4 m between the zones' and doors' points) rather than the corridor (10.0 m).
    assert_eq!(door_path(0, 0, 2, &all), Some(vec![0, 1]));
    assert_eq!(door_path(0, 2, 0, &all), Some(vec![1, 0]));
    // B-C closed: round through the corridor.
    assert_eq!(door_path(0, 0, 2, &|k| k != 1), Some(vec![2, 3]));
    // C-D closed too: C cannot be reached; B still can.
    assert_eq!(door_path(0, 0, 2, &|k| k != 1 && k != 3), None);
    assert_eq!(door_path(0, 0, 1, &|k| k != 1 && k != 3), Some(vec![0]));
    // A storey or zone that does not exist.
    assert_eq!(door_path(1, 0, 2, &all), None);
    assert_eq!(door_path(0, 0, 9, &all), None);
    // Where a robot stands: inside a zone, else the nearest within 0.5 m.
    let index = ZoneIndex::new(&floor);
    assert_eq!(
        zone_near(&floor, &index, DVec2::new(1.0, 1.0)),
        Some(ZoneIdx::new(0))
    );
    assert_eq!(
        zone_near(&floor, &index, DVec2::new(3.15, 2.5)),
        Some(ZoneIdx::new(1))
    );
    assert_eq!(
        zone_near(&floor, &index, DVec2::new(4.0, 3.4)),
        Some(ZoneIdx::new(1))
    );
    assert_eq!(zone_near(&floor, &index, DVec2::new(4.0, 3.6)), None);
}
