//! Door sides in the topology: from geometry (the zones beyond the passage's faces), and from
//! the spaces a door bounds when the floor model has them (IfcRelSpaceBoundary in IFC), which
//! settle doors whose geometry is ambiguous.

mod support;

use poinav_nav::graph::{door_zones, Topology};
use poinav_nav::{Building, Floor};
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

fn names(floor: &Floor, sides: [Option<usize>; 2]) -> Vec<&str> {
    let mut v: Vec<&str> = sides
        .iter()
        .map(|z| z.map_or("outside", |z| floor.zones[z].name.as_deref().unwrap()))
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
