//! The accessibility audit on hand-made floors: door statuses with reasons, reachability from
//! the entrances or a named start, the door named when narrowing it cuts rooms off, the
//! required-rooms check, storeys joined by stairs and lifts, and the written report.

mod support;

use glam::DVec2;
use poinav_nav::audit::{audit, write_report, AuditOptions, ProfileAudit};
use poinav_nav::building::{ConnectionKind, Landing, VerticalConnection};
use poinav_nav::Building;
use poinav_poi::{AccessibilityStatus, RobotProfile};
use support::{demo, demo_floor, office_floor};

fn from(start: &str) -> AuditOptions {
    AuditOptions {
        start: Some(start.into()),
        ..Default::default()
    }
}

fn space<'a>(p: &'a ProfileAudit, name: &str) -> &'a poinav_nav::audit::SpaceAudit {
    p.spaces
        .iter()
        .find(|s| s.name.as_deref() == Some(name))
        .unwrap()
}

fn small_robot() -> RobotProfile {
    let mut p = RobotProfile::paper();
    p.name = "small-robot".into();
    p.width_m = 0.45;
    p.length_m = 0.5;
    p.clearance_margin_m = 0.05;
    p.min_clearance_width_m = Some(0.55);
    p
}

#[test]
fn demo_building_from_the_corridor() {
    let building = Building::single(demo());
    let report = audit(&building, &[RobotProfile::paper()], &from("Corridor")).unwrap();
    let p = &report.profiles[0];
    assert_eq!(p.door_counts(), [5, 1, 0, 0]);
    assert_eq!(p.space_counts(), (7, 0));
    let d2 = p
        .doors
        .iter()
        .find(|d| d.name.as_deref() == Some("Door Room 2"))
        .unwrap();
    assert_eq!(d2.status, AccessibilityStatus::Restricted);
    assert_eq!(
        d2.reason,
        "clear width 0.800 m < required 0.900 m, >= robot width 0.700 m"
    );
    assert!(d2.grid_passable);
    assert_eq!(d2.zones, ["Room 2", "Corridor"]);
    assert!(space(p, "Room 2").restricted_only);
    assert!(!space(p, "Room 1").restricted_only);
    let d1 = p
        .doors
        .iter()
        .find(|d| d.name.as_deref() == Some("Door Room 1"))
        .unwrap();
    assert_eq!(d1.reason, "clear width 1.000 m >= required 0.900 m");
}

#[test]
fn no_entrance_and_no_start_says_so() {
    let building = Building::single(demo());
    let report = audit(
        &building,
        &[RobotProfile::paper()],
        &AuditOptions::default(),
    )
    .unwrap();
    let p = &report.profiles[0];
    assert!(p.starts.is_empty());
    assert_eq!(p.space_counts(), (0, 7));
    assert!(space(p, "Room 1").reason.contains("no entrance"));
}

#[test]
fn narrowing_room_2_door_cuts_room_2_off_and_names_the_door() {
    let building = Building::single(demo_floor(&poinav_author::DemoBuilding {
        room2_door_width_m: 0.6,
        ..Default::default()
    }));
    let report = audit(
        &building,
        &[RobotProfile::paper(), small_robot()],
        &from("Room 1"),
    )
    .unwrap();
    let paper = &report.profiles[0];
    let r2 = space(paper, "Room 2");
    assert!(!r2.reachable);
    assert_eq!(r2.blocked_by.len(), 1);
    assert_eq!(r2.blocked_by[0].name.as_deref(), Some("Door Room 2"));
    assert_eq!(r2.blocked_by[0].status, AccessibilityStatus::Blocked);
    assert_eq!(
        r2.reason,
        "blocked by Door Room 2 (BLOCKED: clear width 0.600 m < robot width 0.700 m)"
    );
    assert_eq!(paper.space_counts(), (6, 1));
    let d2 = paper
        .doors
        .iter()
        .find(|d| d.name.as_deref() == Some("Door Room 2"))
        .unwrap();
    assert_eq!(
        (d2.status, d2.grid_passable),
        (AccessibilityStatus::Blocked, false)
    );
    // The small robot fits through 0.60 m.
    let small = &report.profiles[1];
    assert!(space(small, "Room 2").reachable);
    assert_eq!(small.door_counts(), [6, 0, 0, 0]);
    // --require-reachable.
    let fails = report
        .unreachable_required(&building, &["Room 2".into(), "Room 3".into()])
        .unwrap();
    assert_eq!(fails.len(), 1, "{fails:?}");
    assert!(fails[0].starts_with("paper-robot: Room 2 is unreachable: blocked by Door Room 2"));
    assert!(report
        .unreachable_required(&building, &["Room 3".into(), "Room 6@Ground floor".into()])
        .unwrap()
        .is_empty());
    let missing = report
        .unreachable_required(&building, &["Room 9".into()])
        .unwrap_err();
    assert_eq!(missing.to_string(), "no space named `Room 9`");
}

#[test]
fn office_from_its_entrances() {
    let building = Building::single(office_floor());
    let report = audit(
        &building,
        &[RobotProfile::paper()],
        &AuditOptions::default(),
    )
    .unwrap();
    let p = &report.profiles[0];
    assert_eq!(
        p.starts,
        [
            "Office level door Entrance West into Corridor A",
            "Office level door Entrance East into Corridor B"
        ]
    );
    assert_eq!(p.door_counts(), [85, 14, 1, 0]);
    assert!(p
        .doors
        .iter()
        .all(|d| d.grid_passable == (d.status != AccessibilityStatus::Blocked)));
    assert_eq!(p.space_counts(), (100, 1));
    let o50 = space(p, "Office 50");
    assert!(o50.reason.contains("Door Office 50"), "{}", o50.reason);
    assert_eq!(p.spaces.iter().filter(|s| s.restricted_only).count(), 14);
}

fn two_storeys(lift: bool) -> Building {
    let mut first = demo();
    first.name = "First floor".into();
    first.elevation_m = 3.5;
    let landing = |floor, x| Landing {
        floor,
        point: DVec2::new(x, 5.4),
    };
    let mut connections = vec![VerticalConnection {
        id: "stair".into(),
        name: Some("Stair A".into()),
        kind: ConnectionKind::Stair,
        landings: vec![landing(0, 0.8), landing(1, 0.8)],
        clear_width_m: Some(1.2),
        slope_deg: None,
        travel_time_s: None,
    }];
    if lift {
        connections.push(VerticalConnection {
            id: "lift".into(),
            name: Some("Lift 1".into()),
            kind: ConnectionKind::Lift,
            landings: vec![landing(0, 11.6), landing(1, 11.6)],
            clear_width_m: Some(0.8),
            slope_deg: None,
            travel_time_s: None,
        });
    }
    Building {
        floors: vec![demo(), first],
        connections,
        levels: vec![],
    }
}

#[test]
fn storeys_joined_by_stairs_and_lifts() {
    let options = from("Room 1@Ground floor");
    let report = audit(&two_storeys(false), &[RobotProfile::paper()], &options).unwrap();
    let p = &report.profiles[0];
    assert_eq!(p.transitions[0].status, AccessibilityStatus::Blocked);
    assert_eq!(
        p.transitions[0].reason,
        "stairs are not passable for a wheeled robot"
    );
    let up: Vec<_> = p.spaces.iter().filter(|s| s.floor == 1).collect();
    assert_eq!(up.len(), 7);
    assert!(up
        .iter()
        .all(|s| !s.reachable && s.blocked_by.iter().any(|b| b.label() == "Stair A")));
    // With a lift (0.80 m door: RESTRICTED) the first floor is reachable, through it only.
    let report = audit(&two_storeys(true), &[RobotProfile::paper()], &options).unwrap();
    let p = &report.profiles[0];
    assert_eq!(p.transitions[1].status, AccessibilityStatus::Restricted);
    assert_eq!(p.space_counts(), (14, 0));
    assert!(p
        .spaces
        .iter()
        .filter(|s| s.floor == 1)
        .all(|s| s.restricted_only));
}

#[test]
fn report_files() {
    let building = two_storeys(true);
    let report = audit(
        &building,
        &[RobotProfile::paper(), small_robot()],
        &from("Room 1@Ground floor"),
    )
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let files = write_report(&report, &building, dir.path()).unwrap();
    let names: Vec<String> = files
        .iter()
        .map(|f| f.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        [
            "audit.json",
            "paper-robot-00-ground-floor.svg",
            "paper-robot-01-first-floor.svg",
            "small-robot-00-ground-floor.svg",
            "small-robot-01-first-floor.svg",
            "report.html"
        ]
    );
    for f in &files[1..5] {
        let text = std::fs::read_to_string(f).unwrap();
        let doc = roxmltree::Document::parse(&text).unwrap();
        let doors = doc
            .descendants()
            .filter(|n| {
                n.has_tag_name("path")
                    && n.parent()
                        .is_some_and(|p| p.attribute("id") == Some("doors"))
            })
            .count();
        assert_eq!(doors, 6);
        // Room 2's door is drawn RESTRICTED (amber) for the paper robot.
        if f.to_string_lossy().contains("paper-robot-00") {
            let d = doc
                .descendants()
                .find(|n| n.attribute("data-global-id") == Some("door-room-2"))
                .unwrap();
            assert_eq!(d.attribute("fill"), Some("#e8a400"));
        }
    }
    let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    assert_eq!(html.matches("<svg ").count(), 4);
    assert!(html.contains("Door Room 2"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("audit.json")).unwrap())
            .unwrap();
    assert_eq!(json["profiles"][0]["profile"], "paper-robot");
    // Deterministic: the same report twice gives the same bytes.
    let dir2 = tempfile::tempdir().unwrap();
    write_report(&report, &building, dir2.path()).unwrap();
    for n in &names {
        assert_eq!(
            std::fs::read(dir.path().join(n)).unwrap(),
            std::fs::read(dir2.path().join(n)).unwrap(),
            "{n}"
        );
    }
}
