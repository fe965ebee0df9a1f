//! The BCF of a hand-built storey: three rooms in a row joined by a 0.8 m door (RESTRICTED for
//! the paper robot, which needs 0.9 m) and a 0.6 m door (BLOCKED: narrower than the robot), so
//! the last room is unreachable. Checks the archive's entries, the XML read back with
//! roxmltree, the cameras and that the bytes do not change from run to run.

use std::io::{Cursor, Read};

use glam::DVec2;
use poinav_bcf::{bcf_bytes, guid, BcfOptions, BcfVersion, IssueKind};
use poinav_nav::polygon::rect;
use poinav_nav::{
    audit, AuditOptions, AuditReport, Building, Floor, FloorDoor, FloorObstacle, FloorZone,
    NavOptions, ObstacleKind,
};
use poinav_poi::RobotProfile;

/// A 22-character GlobalId-like id.
fn gid(tag: &str) -> String {
    format!("{tag:0<22}")
}

fn door(tag: &str, x: f64, width: f64) -> FloorDoor {
    FloorDoor {
        id: gid(tag).into(),
        name: Some(tag.into()),
        ring: rect(x, 2.0 - width / 2.0, x + 0.2, 2.0 + width / 2.0),
        center: DVec2::new(x + 0.1, 2.0),
        clear_width_m: width,
        classified_width_m: Some(width),
        blocked: None,
        roles: vec![],
        spaces: None,
        doorless: false,
        terrain: false,
    }
}

fn building() -> Building {
    let zone = |tag: &str, x0: f64, x1: f64| FloorZone {
        id: gid(tag).into(),
        name: Some(tag.into()),
        long_name: None,
        ring: rect(x0, 0.0, x1, 4.0),
        roles: vec![],
        coordination: None,
    };
    let wall = |tag: &str, rings| FloorObstacle {
        id: gid(tag).into(),
        class: "IfcWall".into(),
        kind: ObstacleKind::Structure,
        rings,
        roles: vec![],
    };
    let gap = |x: f64, w: f64| {
        vec![
            rect(x, 0.0, x + 0.2, 2.0 - w / 2.0),
            rect(x, 2.0 + w / 2.0, x + 0.2, 4.0),
        ]
    };
    let mut inner = gap(4.0, 0.8);
    inner.extend(gap(8.2, 0.6));
    Building::single(Floor {
        name: "Level 1".into(),
        elevation_m: 3.0,
        obstacles: vec![
            wall(
                "0Outer",
                vec![
                    rect(-0.2, -0.2, 10.6, 0.0),
                    rect(-0.2, 4.0, 10.6, 4.2),
                    rect(-0.2, 0.0, 0.0, 4.0),
                    rect(10.4, 0.0, 10.6, 4.0),
                ],
            ),
            wall("0Inner", inner),
        ],
        doors: vec![door("0Narrow", 4.0, 0.8), door("0Tiny", 8.2, 0.6)],
        zones: vec![
            zone("0West", 0.0, 4.0),
            zone("0East", 4.2, 8.2),
            zone("0Closet", 8.4, 10.4),
        ],
    })
}

fn report(b: &Building) -> AuditReport {
    audit(
        b,
        &[RobotProfile::paper()],
        &AuditOptions {
            nav: NavOptions::default(),
            start: Some("0West".into()),
        },
    )
    .unwrap()
}

fn options(version: BcfVersion) -> BcfOptions {
    BcfOptions {
        version,
        grid: NavOptions::default().grid,
        model: Some("rooms & doors.ifc".into()),
        created_s: 1_795_314_600,
    }
}

fn entries(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    let mut z = zip::ZipArchive::new(Cursor::new(bytes)).unwrap();
    (0..z.len())
        .map(|i| {
            let mut f = z.by_index(i).unwrap();
            let mut data = Vec::new();
            f.read_to_end(&mut data).unwrap();
            (f.name().to_string(), data)
        })
        .collect()
}

fn entry<'a>(all: &'a [(String, Vec<u8>)], name: &str) -> &'a str {
    let (_, data) = all
        .iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no entry {name}"));
    std::str::from_utf8(data).unwrap()
}

fn child_text(node: roxmltree::Node<'_, '_>, path: &[&str]) -> Option<String> {
    let mut n = node;
    for p in path {
        n = n.children().find(|c| c.has_tag_name(*p))?;
    }
    n.text().map(str::to_string)
}

#[test]
fn three_topics_with_guids_labels_cameras_and_snapshots_in_bcf_3() {
    let b = building();
    let r = report(&b);
    let profiles = [RobotProfile::paper()];
    let (bytes, issues) = bcf_bytes(&r, &b, &profiles, &options(BcfVersion::V3_0)).unwrap();
    let kinds: Vec<(IssueKind, &str, &str)> = issues
        .iter()
        .map(|i| (i.kind, i.element.as_str(), i.status))
        .collect();
    assert_eq!(
        kinds,
        [
            (IssueKind::Door, gid("0Narrow").as_str(), "RESTRICTED"),
            (IssueKind::Door, gid("0Tiny").as_str(), "BLOCKED"),
            (IssueKind::Space, gid("0Closet").as_str(), "UNREACHABLE"),
        ]
    );
    let all = entries(&bytes);
    assert_eq!(
        all.len(),
        3 + 3 * 3,
        "{:?}",
        all.iter().map(|e| &e.0).collect::<Vec<_>>()
    );
    assert_eq!(all[0].0, "bcf.version");
    assert!(entry(&all, "bcf.version").contains("VersionId=\"3.0\""));

    // The narrow door's topic.
    let narrow = guid::topic_guid("paper-robot", &gid("0Narrow"), "door");
    assert_eq!(issues[0].guid, narrow);
    let markup = entry(&all, &format!("{narrow}/markup.bcf"));
    let doc = roxmltree::Document::parse(markup).unwrap();
    let topic = doc
        .root_element()
        .children()
        .find(|n| n.has_tag_name("Topic"))
        .unwrap();
    assert_eq!(topic.attribute("Guid"), Some(narrow.as_str()));
    assert_eq!(topic.attribute("TopicType"), Some("Issue"));
    let labels: Vec<&str> = topic
        .descendants()
        .filter(|n| n.has_tag_name("Label"))
        .filter_map(|n| n.text())
        .collect();
    assert_eq!(labels, ["paper-robot", "RESTRICTED", "door"]);
    let title = child_text(topic, &["Title"]).unwrap();
    assert!(title.contains("0.80 m clear, needs 0.90 m"), "{title}");
    assert_eq!(
        child_text(topic, &["CreationDate"]).as_deref(),
        Some("2026-11-22T02:30:00Z")
    );
    // The model's name, escaped and read back.
    assert!(markup.contains("rooms &amp; doors.ifc"));
    assert_eq!(
        child_text(doc.root_element(), &["Header", "Files", "File", "Filename"]).as_deref(),
        Some("rooms & doors.ifc")
    );

    let vp = entry(&all, &format!("{narrow}/viewpoint.bcfv"));
    let doc = roxmltree::Document::parse(vp).unwrap();
    let v = doc.root_element();
    assert_eq!(
        v.attribute("Guid"),
        Some(guid::viewpoint_guid(&narrow).as_str())
    );
    let selected: Vec<&str> = v
        .descendants()
        .filter(|n| n.has_tag_name("Component"))
        .filter_map(|n| n.attribute("IfcGuid"))
        .collect();
    assert_eq!(
        selected,
        [gid("0Narrow"), gid("0Narrow")],
        "selected and coloured"
    );
    let num = |path: &[&str]| -> f64 { child_text(v, path).unwrap().parse().unwrap() };
    // In the larger room (West, x 0-4 against East's 4.2-8.2: both allow 2.5 m, so the
    // positive normal's side), 1.6 m above the storey at 3.0 m.
    let z = num(&["PerspectiveCamera", "CameraViewPoint", "Z"]);
    assert!((z - 4.6).abs() < 1e-6, "{z}");
    let x = num(&["PerspectiveCamera", "CameraViewPoint", "X"]);
    assert!((x - 1.6).abs() < 1e-6 || (x - 6.6).abs() < 1e-6, "{x}");
    let dx = num(&["PerspectiveCamera", "CameraDirection", "X"]);
    assert!(
        dx.abs() > 0.9 && (x < 4.1) == (dx > 0.0),
        "looks at the door: {x} {dx}"
    );
    assert_eq!(num(&["PerspectiveCamera", "FieldOfView"]), 60.0);
    assert!((num(&["PerspectiveCamera", "AspectRatio"]) - 4.0 / 3.0).abs() < 1e-6);
    let png = all
        .iter()
        .find(|(n, _)| *n == format!("{narrow}/snapshot.png"))
        .unwrap();
    assert_eq!(&png.1[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(&png.1[16..24], &[0, 0, 2, 128, 0, 0, 1, 224], "640 x 480");

    // The unreachable closet: spaces shown, the camera above it.
    let closet = guid::topic_guid("paper-robot", &gid("0Closet"), "space");
    let vp = entry(&all, &format!("{closet}/viewpoint.bcfv"));
    assert!(vp.contains("SpacesVisible=\"true\""));
    assert!(vp.contains("Color=\"D93025\""));
    let markup = entry(&all, &format!("{closet}/markup.bcf"));
    assert!(markup.contains("blocked by"), "{markup}");

    // The extensions list every label used.
    let ext = entry(&all, "extensions.xml");
    for l in [
        "paper-robot",
        "RESTRICTED",
        "BLOCKED",
        "UNREACHABLE",
        "door",
        "space",
    ] {
        assert!(
            ext.contains(&format!("<TopicLabel>{l}</TopicLabel>")),
            "{l}"
        );
    }

    // Same input, same bytes.
    let (again, _) = bcf_bytes(&r, &b, &profiles, &options(BcfVersion::V3_0)).unwrap();
    assert_eq!(bytes, again);
}

#[test]
fn bcf_2_1_keeps_the_guids_and_puts_viewpoints_beside_the_topic() {
    let b = building();
    let r = report(&b);
    let (bytes, issues) =
        bcf_bytes(&r, &b, &[RobotProfile::paper()], &options(BcfVersion::V2_1)).unwrap();
    let all = entries(&bytes);
    // No extensions.xml in 2.1.
    assert_eq!(all.len(), 2 + 3 * 3);
    let version = entry(&all, "bcf.version");
    assert!(version.contains("<DetailedVersion>2.1</DetailedVersion>"));
    let g = &issues[0].guid;
    assert_eq!(g, &guid::topic_guid("paper-robot", &gid("0Narrow"), "door"));
    let markup = entry(&all, &format!("{g}/markup.bcf"));
    let doc = roxmltree::Document::parse(markup).unwrap();
    let tags: Vec<&str> = doc
        .root_element()
        .children()
        .filter(|n| n.is_element())
        .map(|n| n.tag_name().name())
        .collect();
    assert_eq!(tags, ["Header", "Topic", "Viewpoints"]);
    let labels: Vec<&str> = doc
        .descendants()
        .filter(|n| n.has_tag_name("Labels"))
        .filter_map(|n| n.text())
        .collect();
    assert_eq!(labels, ["paper-robot", "RESTRICTED", "door"]);
    let vp = entry(&all, &format!("{g}/viewpoint.bcfv"));
    assert!(!vp.contains("AspectRatio"));
    let doc = roxmltree::Document::parse(vp).unwrap();
    let components: Vec<&str> = doc
        .root_element()
        .children()
        .find(|n| n.has_tag_name("Components"))
        .unwrap()
        .children()
        .filter(|n| n.is_element())
        .map(|n| n.tag_name().name())
        .collect();
    assert_eq!(
        components,
        ["ViewSetupHints", "Selection", "Visibility", "Coloring"]
    );
}

#[test]
fn a_report_for_other_profiles_is_refused() {
    let b = building();
    let r = report(&b);
    let err = bcf_bytes(&r, &b, &[], &options(BcfVersion::V3_0)).unwrap_err();
    assert_eq!(err.to_string(), "the audit has 1 profiles but 0 were given");
}
