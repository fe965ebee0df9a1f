//! Doors above ground level that open onto the terrain are entrances (issue 22, point 1: "at
//! ground level or reached from the terrain"), on a hillside house written by IfcOpenShell
//! (`tests/ifcos/author_hillside.py`) with its terrain modelled three ways: an
//! IfcGeographicElement TERRAIN, the IfcSite's body, an IfcBuildingElementProxy named
//! "Gelände". Its upper floor is reached only through the hillside door (no stair); the
//! balcony door above low terrain stays no entrance, and so does the hillside door where a
//! roof of the ground floor lies under the terrain behind it.

use std::path::Path;

use glam::DVec2;
use poinav_bridge::terrain::{terrain_of, top_at, PROBE_M};
use poinav_bridge::DroppedKind;
use poinav_geom::{floor_plans_with_meshes, mesh_model, PlanOptions};
use poinav_ifc::Model;
use poinav_nav::audit::audit_profile;
use poinav_nav::route::Place;
use poinav_nav::{Building, CellState, Entrance, NavOptions, Navigator};
use poinav_poi::{classify, RobotProfile, RuleSet};

fn building(file: &Path, profile: &RobotProfile) -> Building {
    let model = Model::open(file).unwrap();
    let c = classify(&model, &RuleSet::defaults(), profile);
    poinav_bridge::building(&model, &c, &poinav_bridge::Stages::of(&model)).building
}

/// Per door with a side outside: (name, how it is entered), in the topology's order.
fn entrances(nav: &Navigator<'_>) -> Vec<(String, Option<Entrance>)> {
    nav.topology
        .doors
        .iter()
        .filter(|d| d.zones.iter().filter(|z| z.is_none()).count() == 1)
        .map(|d| {
            let name = nav.building.floors[d.floor].doors[d.door.get()]
                .name
                .clone();
            (name.unwrap_or_default(), d.entrance())
        })
        .collect()
}

fn reachable(nav: &Navigator<'_>) -> Vec<(String, bool)> {
    audit_profile(nav, None)
        .unwrap()
        .spaces
        .iter()
        .map(|s| (s.name.clone().unwrap_or_default(), s.reachable))
        .collect()
}

#[test]
fn a_hillside_door_is_an_entrance_from_the_terrain() {
    let dir = tempfile::tempdir().unwrap();
    let py = poinav_testkit::python("ifcopenshell");
    let info = poinav_testkit::ifcos_with(&py, "author_hillside.py", &[dir.path().as_os_str()]);
    let paper = RobotProfile::paper();
    for variant in ["geographic", "site", "proxy"] {
        let file = dir.path().join(info["files"][variant].as_str().unwrap());
        let label = |what: &str| format!("{variant}: {what}");

        // The terrain as read agrees with IfcOpenShell's mesh of it, and its top 0.6 m beyond
        // the hillside door (x 2-3 in the north wall, y 7.8-8.0) is at 3.0 + 0.4 * 0.6 / 12.
        let model = Model::open(&file).unwrap();
        let meshes = mesh_model(&model);
        let terrain = terrain_of(&model, &meshes);
        assert!(terrain.failures.is_empty(), "{:?}", terrain.failures);
        assert_eq!(
            terrain.surfaces.len(),
            1,
            "{}",
            label("one terrain surface")
        );
        let (_, mesh) = &terrain.surfaces[0];
        let ios = &info["terrain"][variant];
        assert_eq!(
            mesh.triangles.len() as u64,
            ios["triangles"].as_u64().unwrap()
        );
        let (lo, hi) = mesh.bounds().unwrap();
        assert!((lo.z - ios["zmin"].as_f64().unwrap()).abs() < 1e-9, "{lo}");
        assert!((hi.z - ios["zmax"].as_f64().unwrap()).abs() < 1e-9, "{hi}");
        assert!((mesh.area() - ios["area"].as_f64().unwrap()).abs() < 1e-6);
        let probe = DVec2::new(2.5, 8.0 + PROBE_M);
        let top = top_at(terrain.surfaces.iter().map(|(_, m)| m), probe).unwrap();
        assert!((top - 3.02).abs() < 1e-9, "{}: {top}", label("top"));
        let balcony = top_at([mesh], DVec2::new(2.5, -PROBE_M)).unwrap();
        assert!(balcony.abs() < 1e-9, "{balcony}");
        // Nothing of the terrain is under the house, so the storeys' plans are unchanged.
        let plans = floor_plans_with_meshes(&model, &meshes, &PlanOptions::default());
        assert_eq!(plans.len(), 2);
        assert_eq!(top_at([mesh], DVec2::new(5.0, 4.0)), None);

        let b = building(&file, &paper);
        assert_eq!(b.levels.len(), 2);
        assert!(
            b.levels[0].at_ground && !b.levels[1].at_ground,
            "{:?}",
            b.levels
        );
        assert!((b.levels[1].walking_level_m - 3.0).abs() < 1e-9);
        let terrain_doors: Vec<&str> = b
            .floors
            .iter()
            .flat_map(|f| f.doors.iter().filter(|d| d.terrain))
            .map(|d| d.name.as_deref().unwrap_or("?"))
            .collect();
        assert_eq!(
            terrain_doors,
            ["Hillside door"],
            "{}",
            label("terrain doors")
        );

        // Entrances: the front door from the ground, the hillside door from the terrain; the
        // balcony door (terrain 3 m below) none.
        let nav = Navigator::new(&b, &paper, &NavOptions::default()).unwrap();
        assert_eq!(
            entrances(&nav),
            [
                ("Front door".to_string(), Some(Entrance::Ground)),
                ("Hillside door".to_string(), Some(Entrance::Terrain)),
                ("Balcony door".to_string(), None),
            ],
            "{}",
            label("entrances")
        );
        // The paper robot reaches every space from outside, the upper ones only through the
        // hillside door.
        let all = [
            ("Hall".to_string(), true),
            ("Upper hall".to_string(), true),
            ("Upper room".to_string(), true),
        ];
        assert_eq!(reachable(&nav), all, "{}", label("reachable"));
        let route = nav
            .route(
                &"outside".parse::<Place>().unwrap(),
                &Place::zone("Upper room"),
            )
            .unwrap();
        let passed: Vec<&str> = route
            .doors
            .iter()
            .map(|d| d.name.as_deref().unwrap_or("?"))
            .collect();
        assert_eq!(
            passed,
            ["Hillside door", "Upper room door"],
            "{}",
            label("route")
        );
        // The hillside door has its free apron outside; the balcony door none.
        let g = &nav.floors[1].grid.occupancy;
        let cell = |x: f64, y: f64| g.cells[g.cell_of(DVec2::new(x, y)).unwrap()];
        assert_eq!(cell(2.5, 8.5), CellState::Free);
        assert_eq!(cell(2.5, -0.5), CellState::Unknown);

        // The audit says so: JSON `entrance` per door, and the start's label.
        let audit = audit_profile(&nav, None).unwrap();
        let json = serde_json::to_value(&audit).unwrap();
        let kinds: Vec<(String, serde_json::Value)> = json["doors"]
            .as_array()
            .unwrap()
            .iter()
            .map(|d| {
                (
                    d["name"].as_str().unwrap().to_string(),
                    d["entrance"].clone(),
                )
            })
            .collect();
        assert_eq!(
            kinds,
            [
                ("Front door".to_string(), "ground".into()),
                ("Hillside door".to_string(), "terrain".into()),
                ("Balcony door".to_string(), serde_json::Value::Null),
                ("Upper room door".to_string(), serde_json::Value::Null),
            ]
        );
        assert_eq!(
            audit.starts,
            [
                "Ground floor door Front door into Hall Hall",
                "Upper floor door Hillside door into Upper hall Upper hall, from the terrain",
            ]
        );
        let topo = nav.topology.to_json(&b, &paper);
        let node = topo["nodes"]
            .as_array()
            .unwrap()
            .iter()
            .find(|n| n["name"] == "Hillside door")
            .unwrap();
        assert_eq!(node["entrance"], "terrain");

        // Before terrain doors (the same building without them): the upper floor is cut off.
        let mut before = b.clone();
        for d in before.floors.iter_mut().flat_map(|f| f.doors.iter_mut()) {
            d.terrain = false;
        }
        let nav = Navigator::new(&before, &paper, &NavOptions::default()).unwrap();
        assert_eq!(
            entrances(&nav).iter().filter(|(_, e)| e.is_some()).count(),
            1
        );
        assert_eq!(
            reachable(&nav),
            [
                ("Hall".to_string(), true),
                ("Upper hall".to_string(), false),
                ("Upper room".to_string(), false),
            ],
            "{}",
            label("before")
        );
    }

    // A site body that cannot be meshed (a list inserted into its face set's attributes): the
    // building leaves the terrain out and says so; no door opens onto it.
    let site = dir.path().join(info["files"]["site"].as_str().unwrap());
    let text = std::fs::read_to_string(&site).unwrap();
    let at = text.find("IFCTRIANGULATEDFACESET(").unwrap();
    let list = at + text[at..].find(",((").unwrap();
    let damaged = format!("{}((1,2,999),{}", &text[..list + 3], &text[list + 3..]);
    let model = Model::from_bytes("damaged-site.ifc", damaged.into_bytes()).unwrap();
    let c = classify(&model, &RuleSet::defaults(), &paper);
    let made = poinav_bridge::building(&model, &c, &poinav_bridge::Stages::of(&model));
    let dropped: Vec<(DroppedKind, Option<&str>)> = made
        .dropped
        .iter()
        .map(|d| (d.kind, d.name.as_deref()))
        .collect();
    assert_eq!(dropped, [(DroppedKind::Terrain, Some("Site"))]);
    let d = &made.dropped[0];
    assert_eq!(
        Some(d.id.clone()),
        model.instances_of("IfcSite")[0].global_id()
    );
    assert!(
        d.reason
            .ends_with(": IfcTriangulatedFaceSet has no usable `Coordinates`"),
        "{}",
        d.reason
    );
    assert!(d.message().starts_with("terrain Site ("), "{}", d.message());
    let floors = &made.building.floors;
    assert!(floors.iter().flat_map(|f| &f.doors).all(|d| !d.terrain));

    // Terrain at the upper storey's level beyond the hillside door, but over the ground
    // floor's roof slab there (a roof terrace, inside the building's footprint): no entrance.
    let file = dir.path().join(info["files"]["covered"].as_str().unwrap());
    let b = building(&file, &paper);
    assert!(b.floors.iter().flat_map(|f| &f.doors).all(|d| !d.terrain));
    let nav = Navigator::new(&b, &paper, &NavOptions::default()).unwrap();
    let hillside = entrances(&nav)
        .into_iter()
        .find(|(n, _)| n == "Hillside door")
        .unwrap();
    assert_eq!(hillside.1, None);
    assert_eq!(
        reachable(&nav),
        [
            ("Hall".to_string(), true),
            ("Upper hall".to_string(), false),
            ("Upper room".to_string(), false),
        ]
    );
}
