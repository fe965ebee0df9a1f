//! The default rules R1-R5 and the floor-slab rule on small hand-made IFC models, precedence and
//! user rule files, and door statuses on real buildings against their door widths.

use poinav_ifc::Model;
use poinav_poi::runtime::{self, Observation};
use poinav_poi::{
    classify, AccessibilityStatus as S, Category, Classification, PoiType, RobotProfile, Role,
    RuleSet, ValidationMethod,
};

/// An IFC4 model in metres with the given instances (ids from #100).
fn model(instances: &str) -> Model {
    let text = format!(
        "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n\
         #1=IFCPROJECT('0YvctVUKr0kugbFTf53O9L',$,'P',$,$,$,$,$,#2);\n\
         #2=IFCUNITASSIGNMENT((#3));#3=IFCSIUNIT(*,.LENGTHUNIT.,$,.METRE.);\n{instances}\nENDSEC;END-ISO-10303-21;"
    );
    Model::from_bytes("snippet.ifc", text.into_bytes()).unwrap()
}

fn run(instances: &str) -> Classification {
    classify(
        &model(instances),
        &RuleSet::defaults(),
        &RobotProfile::paper(),
    )
}

fn guid(n: u32) -> String {
    format!("'{n:0>22}'")
}

fn space(id: u32, name: &str, long_name: &str) -> String {
    format!(
        "#{id}=IFCSPACE({},$,'{name}',$,$,$,$,'{long_name}',.ELEMENT.,.INTERNAL.,$);",
        guid(id)
    )
}

fn door(id: u32, width: f64) -> String {
    format!(
        "#{id}=IFCDOOR({},$,'D{id}',$,$,$,$,$,2.1,{width:?},.DOOR.,$,$);",
        guid(id)
    )
}

fn status(c: &Classification, i: usize) -> S {
    c.elements[i].accessibility.as_ref().unwrap().status
}

#[test]
fn r1_boundary_elements_avoid_and_guide() {
    let c = run(&format!(
        "#100=IFCWALLSTANDARDCASE({},$,'W',$,$,$,$,$,$);#101=IFCCOLUMN({},$,'C',$,$,$,$,$,$);#102=IFCRAILING({},$,'R',$,$,$,$,$,$);",
        guid(100),
        guid(101),
        guid(102)
    ));
    assert_eq!(c.elements.len(), 3);
    for e in &c.elements {
        assert_eq!(
            (e.rule.as_str(), e.category, e.poi_type),
            ("R1", Category::Structural, PoiType::BoundaryElement)
        );
        assert_eq!(e.primary, [Role::Avoidance, Role::PathGuidance]);
        assert!(e.conditional.is_empty() && e.accessibility.is_none());
    }
}

#[test]
fn r2_doors_are_checked_by_clear_width() {
    // 1.00 m: FULL_ACCESS; 0.80 m: RESTRICTED + B-2 (the paper's door); 0.60 m: BLOCKED (narrower than the 0.70 m robot).
    let c = run(&format!(
        "{}{}{}",
        door(100, 1.0),
        door(101, 0.8),
        door(102, 0.6)
    ));
    assert_eq!(
        [status(&c, 0), status(&c, 1), status(&c, 2)],
        [S::FullAccess, S::Restricted, S::Blocked]
    );
    assert_eq!(c.elements[0].conditional, []);
    assert_eq!(c.elements[1].conditional, [Role::Narrow]);
    assert_eq!(c.elements[2].conditional, [Role::Narrow]);
    for e in &c.elements {
        assert_eq!(
            (e.category, e.poi_type, e.primary.as_slice()),
            (
                Category::Structural,
                PoiType::TransitionElement,
                &[Role::Transition][..]
            )
        );
        let a = e.accessibility.as_ref().unwrap();
        assert_eq!(
            (a.min_clearance_width_m, a.method),
            (0.90, ValidationMethod::GeometricAnalysis)
        );
    }
    // Exactly at the requirement is enough.
    assert_eq!(status(&run(&door(100, 0.9)), 0), S::FullAccess);
}

#[test]
fn r2_clear_width_comes_from_the_lining() {
    // 1.00 m door with 0.06 m linings: 0.88 m clear, so RESTRICTED.
    let c = run(&format!(
        "{}#101=IFCDOORLININGPROPERTIES({},$,'L',$,0.1,0.06,$,$,$,$,$,$,$,$,$,$,$);#102=IFCRELDEFINESBYPROPERTIES({},$,$,$,(#100),#101);",
        door(100, 1.0),
        guid(101),
        guid(102)
    ));
    assert!((c.elements[0].facts.clear_width_m.unwrap() - 0.88).abs() < 1e-12);
    assert_eq!(c.elements[0].facts.clear_width_source, Some("lining"));
    assert_eq!(status(&c, 0), S::Restricted);
}

#[test]
fn r2_windows_stairs_and_ramps_follow_the_profile() {
    let c = run(&format!(
        "#100=IFCWINDOW({},$,'Win',$,$,$,$,$,1.2,1.5,$,$,$);#101=IFCSTAIR({},$,'St',$,$,$,$,$,$);\
         #102=IFCRAMP({},$,'Gentle',$,$,$,$,$,$);#103=IFCPROPERTYSINGLEVALUE('Slope',$,IFCPLANEANGLEMEASURE(0.05),$);\
         #104=IFCPROPERTYSET({},$,'Pset_RampFlightCommon',$,(#103));#105=IFCRELDEFINESBYPROPERTIES({},$,$,$,(#102),#104);\
         #106=IFCRAMP({},$,'Steep',$,$,$,$,$,$);#107=IFCPROPERTYSINGLEVALUE('Slope',$,IFCPLANEANGLEMEASURE(0.2),$);\
         #108=IFCPROPERTYSET({},$,'Pset_RampFlightCommon',$,(#107));#109=IFCRELDEFINESBYPROPERTIES({},$,$,$,(#106),#108);",
        guid(100),
        guid(101),
        guid(102),
        guid(104),
        guid(105),
        guid(106),
        guid(108),
        guid(109)
    ));
    let by_name = |n: &str| {
        c.elements
            .iter()
            .find(|e| e.name.as_deref() == Some(n))
            .unwrap()
    };
    assert_eq!(
        by_name("Win").accessibility.as_ref().unwrap().status,
        S::Blocked
    );
    assert_eq!(
        by_name("St").accessibility.as_ref().unwrap().status,
        S::Blocked,
        "wheeled robots do not climb stairs"
    );
    // 0.05 rad = 2.9 deg <= 6 deg; 0.2 rad = 11.5 deg > 6 deg.
    assert_eq!(
        by_name("Gentle").accessibility.as_ref().unwrap().status,
        S::FullAccess
    );
    assert_eq!(
        by_name("Steep").accessibility.as_ref().unwrap().status,
        S::Blocked
    );
    assert_eq!(by_name("Steep").conditional, [Role::Narrow]);
    let mut legged = RobotProfile::paper();
    legged.locomotion = poinav_poi::Locomotion::Legged;
    let m = model(&format!("#101=IFCSTAIR({},$,'St',$,$,$,$,$,$);", guid(101)));
    assert_eq!(
        classify(&m, &RuleSet::defaults(), &legged).elements[0]
            .accessibility
            .as_ref()
            .unwrap()
            .status,
        S::FullAccess
    );
}

#[test]
fn r3_corridors_are_found_in_several_languages_and_rooms_are_destinations() {
    let names = [
        ("101", "CORRIDOR", true),
        ("A201", "Hallway", true),
        ("1", "Flur", true),
        ("2", "Gang", true),
        ("3", "Korridor", true),
        ("4", "Couloir", true),
        ("5", "廊下", true),
        ("6", "Pasillo", true),
        ("7", "Besprechungsraum", false),
        ("8", "Office", false),
        ("9", "Ganglion lab", false),
        // "Hall" alone or as a house's hall is circulation; a banquet or sports hall is not.
        ("10", "Hall", true),
        ("11", "Hall 2", true),
        ("12", "Stair hall", true),
        ("13", "Banquet Hall", false),
        ("14", "Sports hall", false),
        ("15", "Lecture Hall 1", false),
        ("16", "Entrance Hall", true),
        // Cyrillic names, as Russian and Ukrainian houses write them.
        ("17", "Коридор", true),
        ("18", "коридор 2", true),
        ("19", "Прихожая", true),
        ("20", "Холл", true),
        ("21", "Спальня", false),
    ];
    let text: String = names
        .iter()
        .enumerate()
        .map(|(i, (n, l, _))| space(100 + i as u32, n, l))
        .collect();
    let c = run(&text);
    assert_eq!(c.elements.len(), names.len());
    for (e, (name, long, corridor)) in c.elements.iter().zip(names) {
        assert_eq!(
            (e.category, e.poi_type),
            (Category::Functional, PoiType::SpaceType)
        );
        if corridor {
            assert_eq!(
                e.primary,
                [Role::PathGuidance, Role::MultiRobotZone],
                "{name} {long}"
            );
            let k = e.coordination.as_ref().unwrap();
            assert_eq!(
                (k.min_separation_m, k.protocol),
                (2.0, poinav_poi::CoordinationProtocol::SpeedReduction)
            );
        } else {
            assert_eq!(e.primary, [Role::Destination], "{name} {long}");
            assert!(e.coordination.is_none());
        }
    }
}

#[test]
fn r3_corridor_from_space_common_category_and_hazard_spaces() {
    let c = run(&format!(
        "{}#101=IFCPROPERTYSINGLEVALUE('Category',$,IFCLABEL('Circulation'),$);#102=IFCPROPERTYSET({},$,'Pset_SpaceCommon',$,(#101));\
         #103=IFCRELDEFINESBYPROPERTIES({},$,$,$,(#100),#102);{}{}{}",
        space(100, "0.12", "Zone 12"),
        guid(102),
        guid(103),
        space(104, "B01", "Electrical Room"),
        space(105, "B02", "Technikraum"),
        space(106, "B03", "Лестничная клетка"),
    ));
    assert_eq!(c.elements[0].rule, "R3-corridor-property");
    for e in &c.elements[1..] {
        assert_eq!(e.primary, [Role::Hazard, Role::Destination], "{:?}", e.name);
    }
}

#[test]
fn a_banquet_hall_category_is_not_circulation() {
    let c = run(&format!(
        "{}#101=IFCPROPERTYSINGLEVALUE('Category',$,IFCLABEL('Banquet Hall'),$);#102=IFCPROPERTYSET({},$,'Pset_SpaceCommon',$,(#101));\
         #103=IFCRELDEFINESBYPROPERTIES({},$,$,$,(#100),#102);",
        space(100, "0.12", "Zone 12"),
        guid(102),
        guid(103),
    ));
    assert_eq!(c.elements[0].rule, "R3-room");
    assert_eq!(c.elements[0].primary, [Role::Destination]);
}

#[test]
fn r3_geometric_fallback_needs_a_long_narrow_space_with_doors() {
    let rules = RuleSet::defaults();
    let m = model(&space(100, "X", "Zone"));
    let profile = RobotProfile::paper();
    let e = m.entity(poinav_ifc::EntityId(100)).unwrap();
    let mut facts = poinav_poi::FactContext::new(&m).facts(e);
    assert_eq!(rules.winner(&e, &facts, &profile).unwrap().id, "R3-room");
    facts.elongation = Some(5.0);
    facts.footprint_width_m = Some(2.0);
    facts.door_count = Some(4.0);
    assert_eq!(
        rules.winner(&e, &facts, &profile).unwrap().id,
        "R3-corridor-geometry"
    );
    facts.door_count = Some(2.0);
    assert_eq!(
        rules.winner(&e, &facts, &profile).unwrap().id,
        "R3-room",
        "too few doors"
    );
    facts.door_count = Some(4.0);
    facts.footprint_width_m = Some(6.0);
    assert_eq!(
        rules.winner(&e, &facts, &profile).unwrap().id,
        "R3-room",
        "an open office is elongated but wide"
    );
}

#[test]
fn r4_furniture_and_equipment_are_fixed_objects_to_avoid() {
    let c = run(&format!(
        "#100=IFCFURNITURE({},$,'Desk',$,$,$,$,$,$);#101=IFCFLOWTERMINAL({},$,'Sink',$,$,$,$,$);",
        guid(100),
        guid(101)
    ));
    for e in &c.elements {
        assert_eq!(
            (e.rule.as_str(), e.category, e.poi_type),
            ("R4", Category::ObjectBased, PoiType::FixedObject)
        );
        assert_eq!(e.primary, [Role::Avoidance]);
    }
    assert_eq!(c.elements.len(), 2);
}

#[test]
fn floor_slabs_guide_and_roofs_are_not_enriched() {
    let c = run(&format!(
        "#100=IFCSLAB({},$,'Floor',$,$,$,$,$,.FLOOR.);#101=IFCSLAB({},$,'Roof',$,$,$,$,$,.ROOF.);#102=IFCSLAB({},$,'Base',$,$,$,$,$,.BASESLAB.);",
        guid(100),
        guid(101),
        guid(102)
    ));
    let names: Vec<_> = c.elements.iter().map(|e| e.name.clone().unwrap()).collect();
    assert_eq!(names, ["Floor", "Base"]);
    for e in &c.elements {
        assert_eq!(
            (e.rule.as_str(), e.poi_type, e.primary.as_slice()),
            ("R-floor", PoiType::FloorSurface, &[Role::PathGuidance][..])
        );
    }
}

#[test]
fn r5_sensor_feedback_adds_and_removes_conditional_roles() {
    let mut c = run(&format!(
        "{}{}",
        door(100, 1.0),
        space(101, "121", "CORRIDOR")
    ));
    let door = &mut c.elements[0];
    assert_eq!(door.accessibility.as_ref().unwrap().status, S::FullAccess);
    let ch = runtime::apply(
        door,
        Observation::Clearance {
            measured_width_m: 0.82,
        },
    );
    assert_eq!(
        (ch.added.as_slice(), ch.status),
        (&[Role::Narrow][..], Some((S::FullAccess, S::Restricted)))
    );
    assert_eq!(
        door.accessibility.as_ref().unwrap().method,
        ValidationMethod::SensorBased
    );
    let ch = runtime::apply(
        door,
        Observation::Clearance {
            measured_width_m: 1.18,
        },
    );
    assert_eq!(
        (ch.removed.as_slice(), door.conditional.as_slice()),
        (&[Role::Narrow][..], &[][..])
    );
    let corridor = &mut c.elements[1];
    assert!(runtime::apply(corridor, Observation::RobotDistance { distance_m: 2.5 }).is_empty());
    assert_eq!(
        runtime::apply(corridor, Observation::RobotDistance { distance_m: 1.9 }).added,
        [Role::RobotInteraction]
    );
    assert_eq!(corridor.conditional, [Role::RobotInteraction]);
    // A wall has no A-2 or C-1: R5 leaves it alone.
    let mut w = run(&format!("#100=IFCWALL({},$,'W',$,$,$,$,$,$);", guid(100)));
    assert!(runtime::apply(
        &mut w.elements[0],
        Observation::Clearance {
            measured_width_m: 0.1
        }
    )
    .is_empty());
}

#[test]
fn user_rules_extend_or_replace_and_later_rules_win_ties() {
    let dir = tempfile::tempdir().unwrap();
    let extend = dir.path().join("extend.toml");
    std::fs::write(
        &extend,
        "version = 1\n[[rule]]\nid = \"my-walls\"\nclasses = [\"IfcWall\"]\nnames = ['(?i)glass']\ncategory = \"Structural\"\ntype = \"Boundary Element\"\nroles = [\"A-1\"]\n",
    )
    .unwrap();
    let rules = RuleSet::with_user_file(&extend).unwrap();
    let m = model(&format!(
        "#100=IFCWALL({},$,'Glass wall',$,$,$,$,$,$);#101=IFCWALL({},$,'Brick',$,$,$,$,$,$);",
        guid(100),
        guid(101)
    ));
    let c = classify(&m, &rules, &RobotProfile::paper());
    assert_eq!(
        (
            c.elements[0].rule.as_str(),
            c.elements[0].primary.as_slice()
        ),
        ("my-walls", &[Role::Avoidance][..])
    );
    assert_eq!(c.elements[1].rule, "R1");
    let replace = dir.path().join("replace.toml");
    std::fs::write(
        &replace,
        std::fs::read_to_string(&extend)
            .unwrap()
            .replace("version = 1", "version = 1\nmode = \"replace\""),
    )
    .unwrap();
    let c = classify(
        &m,
        &RuleSet::with_user_file(&replace).unwrap(),
        &RobotProfile::paper(),
    );
    assert_eq!(
        c.elements.len(),
        1,
        "defaults dropped: the brick wall is not enriched"
    );
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "version = 1\n[[rule]]\nid = \"x\"\nclasses = [\"IfcWal\"]\ncategory = \"Structural\"\ntype = \"Boundary Element\"\nroles = [\"A-1\"]\n").unwrap();
    let err = RuleSet::with_user_file(&bad).unwrap_err().to_string();
    assert!(
        err.contains("bad.toml") && err.contains("rule `x`") && err.contains("IfcWal"),
        "{err}"
    );
    std::fs::write(&bad, "version = 1\n[[rule]]\nid = \"y\"\nclasses = [\"IfcWall\"]\nwhen = [\"width > 3\"]\nskip = true\n").unwrap();
    let err = RuleSet::with_user_file(&bad).unwrap_err();
    assert!(
        err.to_string()
            .ends_with("bad.toml: rule `y`: condition `width > 3`"),
        "{err}"
    );
    let source = std::error::Error::source(&err).expect("the condition's error as source");
    assert!(
        source
            .to_string()
            .starts_with("unknown measure `width` (known: "),
        "{source}"
    );
}

#[test]
fn door_statuses_of_real_buildings_follow_their_widths() {
    for (file, full, restricted, min_w, max_w) in [
        ("office-a.ifc", 97, 5, 0.813, 1.830),
        ("duplex-apartment.ifc", 2, 12, 0.762, 1.250),
    ] {
        let m = Model::open(poinav_testkit::corpus_file(file)).unwrap();
        let c = classify(&m, &RuleSet::defaults(), &RobotProfile::paper());
        let doors: Vec<_> = c.elements.iter().filter(|e| e.class == "IfcDoor").collect();
        let widths: Vec<f64> = doors
            .iter()
            .map(|d| d.facts.clear_width_m.unwrap())
            .collect();
        let lo = widths.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = widths.iter().copied().fold(0.0, f64::max);
        assert!(
            (lo - min_w).abs() < 5e-4 && (hi - max_w).abs() < 5e-4,
            "{file}: widths {lo}..{hi}"
        );
        for d in &doors {
            let w = d.facts.clear_width_m.unwrap();
            let want = if w >= 0.9 {
                S::FullAccess
            } else if w >= 0.7 {
                S::Restricted
            } else {
                S::Blocked
            };
            assert_eq!(
                d.accessibility.as_ref().unwrap().status,
                want,
                "{file} {} {w}",
                d.global_id
            );
            assert_eq!(d.conditional.contains(&Role::Narrow), w < 0.9);
        }
        let count = |s| {
            doors
                .iter()
                .filter(|d| d.accessibility.as_ref().unwrap().status == s)
                .count()
        };
        assert_eq!(
            (
                count(S::FullAccess),
                count(S::Restricted),
                count(S::Blocked)
            ),
            (full, restricted, 0),
            "{file}"
        );
    }
}

#[test]
fn r3_geometric_facts_come_from_space_footprints_and_door_positions() {
    // A 12 x 2 m corridor (extruded rectangle) with three doors along its side, no space boundaries.
    let mut text = String::from(
        "#10=IFCCARTESIANPOINT((0.,0.,0.));#11=IFCAXIS2PLACEMENT3D(#10,$,$);#12=IFCLOCALPLACEMENT($,#11);\
         #13=IFCCARTESIANPOINT((6.,1.));#14=IFCAXIS2PLACEMENT2D(#13,$);#15=IFCRECTANGLEPROFILEDEF(.AREA.,$,#14,12.,2.);\
         #16=IFCDIRECTION((0.,0.,1.));#17=IFCEXTRUDEDAREASOLID(#15,#11,#16,3.);\
         #18=IFCGEOMETRICREPRESENTATIONCONTEXT($,'Model',3,1.E-5,#11,$);\
         #19=IFCSHAPEREPRESENTATION(#18,'Body','SweptSolid',(#17));#20=IFCPRODUCTDEFINITIONSHAPE($,$,(#19));\
         #100=IFCSPACE('0000000000000000000100',$,'S1',$,$,#12,#20,'Zone',.ELEMENT.,.INTERNAL.,$);",
    );
    for (i, x) in [2.0, 6.0, 10.0].iter().enumerate() {
        let id = 200 + 10 * i;
        text.push_str(&format!(
            "#{}=IFCCARTESIANPOINT(({x:?},2.1,0.));#{}=IFCAXIS2PLACEMENT3D(#{},$,$);#{}=IFCLOCALPLACEMENT($,#{});\
             #{id}=IFCDOOR('{id:0>22}',$,'D',$,$,#{},$,$,2.1,1.0,$,$,$);",
            id + 1,
            id + 2,
            id + 1,
            id + 3,
            id + 2,
            id + 3
        ));
    }
    let c = run(&text);
    let space = c.elements.iter().find(|e| e.class == "IfcSpace").unwrap();
    assert!((space.facts.elongation.unwrap() - 6.0).abs() < 1e-9);
    assert!((space.facts.footprint_width_m.unwrap() - 2.0).abs() < 1e-9);
    assert!(
        (space.facts.area_m2.unwrap() - 24.0).abs() < 1e-9,
        "area from the footprint when no quantity is given"
    );
    assert_eq!(space.facts.door_count, Some(3.0));
    assert_eq!(space.rule, "R3-corridor-geometry");
    assert_eq!(
        space.accessibility.as_ref().unwrap().status,
        S::FullAccess,
        "its doors are 1.0 m wide"
    );
}

#[test]
fn r2_clear_width_falls_back_to_the_opening_geometry() {
    // A door without OverallWidth in a 0.85 m wide opening (a box 0.85 x 0.3 x 2.1 m).
    let text = "#10=IFCCARTESIANPOINT((0.,0.,0.));#11=IFCAXIS2PLACEMENT3D(#10,$,$);#12=IFCLOCALPLACEMENT($,#11);\
        #13=IFCCARTESIANPOINT((0.,0.));#14=IFCAXIS2PLACEMENT2D(#13,$);#15=IFCRECTANGLEPROFILEDEF(.AREA.,$,#14,0.85,0.3);\
        #16=IFCDIRECTION((0.,0.,1.));#17=IFCEXTRUDEDAREASOLID(#15,#11,#16,2.1);\
        #18=IFCGEOMETRICREPRESENTATIONCONTEXT($,'Model',3,1.E-5,#11,$);\
        #19=IFCSHAPEREPRESENTATION(#18,'Body','SweptSolid',(#17));#20=IFCPRODUCTDEFINITIONSHAPE($,$,(#19));\
        #30=IFCOPENINGELEMENT('0000000000000000000030',$,'O',$,$,#12,#20,$,.OPENING.);\
        #31=IFCRELFILLSELEMENT('0000000000000000000031',$,$,$,#30,#100);\
        #100=IFCDOOR('0000000000000000000100',$,'D',$,$,#12,$,$,$,$,.DOOR.,$,$);";
    let c = run(text);
    let door = c.elements.iter().find(|e| e.class == "IfcDoor").unwrap();
    assert_eq!(door.facts.clear_width_source, Some("opening geometry"));
    assert!((door.facts.clear_width_m.unwrap() - 0.85).abs() < 1e-9);
    assert_eq!(door.accessibility.as_ref().unwrap().status, S::Restricted);
}

#[test]
fn enriching_an_ifc2x3_file_without_owner_history_is_idempotent() {
    // Found by the enrichment fuzz target: the owner history poinav creates must be recognised
    // and replaced on the next run.
    let text = "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC2X3'));ENDSEC;DATA;\n\
        #1=IFCDOOR('0000000000000000000001',$,'D',$,$,$,$,$,2.1,0.8);\nENDSEC;END-ISO-10303-21;\n";
    let opts = poinav_poi::WriteOptions {
        prefix: "Pset_".into(),
        timestamp: "2026-01-01T00:00:00".into(),
    };
    let enrich = |bytes: Vec<u8>| {
        let m = Model::from_bytes("x.ifc", bytes).unwrap();
        let c = classify(&m, &RuleSet::defaults(), &RobotProfile::paper());
        poinav_poi::write_enrichment(&m, &c, &opts)
            .unwrap()
            .to_bytes()
    };
    let once = enrich(text.as_bytes().to_vec());
    assert!(
        String::from_utf8_lossy(&once).contains("IFCOWNERHISTORY("),
        "IFC2X3 needs an owner history"
    );
    assert_eq!(enrich(once.clone()), once);
    // An element added later that uses poinav's owner history keeps it alive.
    let mut edited = String::from_utf8(once).unwrap();
    let history = edited
        .lines()
        .find(|l| l.contains("IFCOWNERHISTORY("))
        .unwrap()
        .split('=')
        .next()
        .unwrap()
        .to_string();
    edited = edited.replace(
        "ENDSEC;END",
        &format!("#9000=IFCWALL('0000000000000000000900',{history},'W',$,$,$,$,$);\nENDSEC;END"),
    );
    let again = enrich(edited.into_bytes());
    let reread = Model::from_bytes("again.ifc", again).unwrap();
    assert!(
        reread.diagnostics().is_empty(),
        "{:?}",
        reread.diagnostics()
    );
}

#[test]
fn a_ramp_without_a_slope_takes_the_steepest_of_its_flights() {
    // The ramp itself has no slope property; its two flights have 0.05 and 0.08 rad.
    let flights = |gentle: f64, steep: f64| {
        format!(
            "#100=IFCRAMP({},$,'Ramp',$,$,$,$,$,$);\
             #101=IFCRAMPFLIGHT({},$,'F1',$,$,$,$,$,$);#102=IFCRAMPFLIGHT({},$,'F2',$,$,$,$,$,$);\
             #103=IFCRELAGGREGATES({},$,$,$,#100,(#101,#102));\
             #110=IFCPROPERTYSINGLEVALUE('Slope',$,IFCPLANEANGLEMEASURE({gentle:?}),$);\
             #111=IFCPROPERTYSET({},$,'Pset_RampFlightCommon',$,(#110));#112=IFCRELDEFINESBYPROPERTIES({},$,$,$,(#101),#111);\
             #120=IFCPROPERTYSINGLEVALUE('Slope',$,IFCPLANEANGLEMEASURE({steep:?}),$);\
             #121=IFCPROPERTYSET({},$,'Pset_RampFlightCommon',$,(#120));#122=IFCRELDEFINESBYPROPERTIES({},$,$,$,(#102),#121);",
            guid(100),
            guid(101),
            guid(102),
            guid(103),
            guid(111),
            guid(112),
            guid(121),
            guid(122)
        )
    };
    let ramp = |c: &Classification| {
        c.elements
            .iter()
            .find(|e| e.name.as_deref() == Some("Ramp"))
            .unwrap()
            .accessibility
            .clone()
            .unwrap()
    };
    let ok = ramp(&run(&flights(0.05, 0.08)));
    assert_eq!(ok.status, S::FullAccess);
    assert_eq!(
        ok.reason,
        "slope 4.6 deg <= max 6.0 deg (from its flights' properties)"
    );
    let steep = ramp(&run(&flights(0.05, 0.12)));
    assert_eq!(steep.status, S::Blocked);
    assert!(
        steep.reason.starts_with("slope 6.9 deg > max"),
        "{}",
        steep.reason
    );
}

#[test]
fn ramps_without_slope_properties_are_measured_like_ifcopenshell_measures_them() {
    // ramps-extract.ifc: three IfcRamps, no slope in any property set. Their slope comes from
    // the steepest walking surface of their meshes; IfcOpenShell's meshes give the same.
    let file = poinav_testkit::corpus_file("ramps-extract.ifc");
    let py = poinav_testkit::python("ifcopenshell, numpy");
    let reference = poinav_testkit::ifcos_with(&py, "ramp_slopes.py", &[file.as_os_str()]);
    let model = Model::open(&file).unwrap();
    let ctx = poinav_poi::FactContext::new(&model);
    let ramps = model.instances_of("IfcRamp");
    assert_eq!(ramps.len(), 3);
    for r in ramps {
        let facts = ctx.facts(r);
        let want = reference[r.global_id().unwrap().as_str()].as_f64().unwrap();
        let got = facts.slope_deg.unwrap();
        assert_eq!(facts.slope_source, Some("geometry"));
        assert!((got - want).abs() <= 0.1, "{}: {got} vs {want}", r.id());
    }
}
