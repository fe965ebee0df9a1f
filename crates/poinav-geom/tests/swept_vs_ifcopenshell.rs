//! Swept solids and open profiles agree with IfcOpenShell's meshes (run live:
//! `tests/ifcos/author_swept.py` writes one element per case with IfcOpenShell's API, meshes
//! them in world coordinates and prints their boxes and volumes): every case is meshed here,
//! its bounding box within 1 cm and, for closed solids, its volume within 1 %. Where
//! IfcOpenShell 0.9 does not follow the schema (it ignores StartParam/EndParam and the
//! Thickness of centre line profiles, fails on FilletRadius, parameterises trimmed
//! polylines by length and draws Bezier curves as their chords) the script writes a reference
//! element with the geometry the schema defines written out, and the case is compared with
//! that. A directrix may be a surface curve (its Curve3D is swept); an IFC2X3 crane rail
//! profile and a profile bounded by an IFC2X3 Bezier curve are extruded, and so are rolled
//! I, L and U profiles with root fillets and edge radii, a cold-formed C with rounded
//! bends and trapezia whose top line reaches past the bottom one. Also: a swept-disk
//! railing is an obstacle in its storey's floor plan and has a footprint, and a directrix of
//! an unsupported kind is an error naming its `#id`.

mod common;

use std::collections::BTreeMap;

use glam::DVec2;
use poinav_geom::{
    floor_plans, footprint_of, mesh_model, GeomError, PlacementCache, PlanOptions, PlanSource,
};
use poinav_ifc::{EntityId, Model};

/// Bounding boxes agree when every coordinate of both corners is this close (metres).
const BOX_TOLERANCE: f64 = 0.01;

/// Volumes of closed solids agree within this fraction.
const VOLUME_TOLERANCE: f64 = 0.01;

/// Cases that are surfaces, not solids (no volume to compare).
const OPEN: [&str; 2] = ["open_profile", "open_profile_reference"];

#[test]
fn swept_solids_match_ifcopenshell() {
    let python = common::python();
    let dir = tempfile::tempdir().unwrap();
    let reference =
        poinav_testkit::ifcos_with(&python, "author_swept.py", &[dir.path().as_os_str()]);
    let reference = reference.as_object().unwrap();
    let mut ours = BTreeMap::new();
    let mut models = BTreeMap::new();
    for file in ["swept-ifc4.ifc", "swept-ifc4x3.ifc", "swept-ifc2x3.ifc"] {
        let model = Model::open(dir.path().join(file)).unwrap();
        let meshes = mesh_model(&model);
        assert!(meshes.failures.is_empty(), "{file}: {:?}", meshes.failures);
        for e in meshes.elements {
            ours.insert(e.name.clone().unwrap(), e);
        }
        models.insert(file, model);
    }
    let mut problems = Vec::new();
    let mut compared = 0;
    for (name, r) in reference {
        let theirs = match r.get("reference") {
            Some(other) => &reference[other.as_str().unwrap()],
            None => r,
        };
        let Some(e) = ours.get(name) else {
            problems.push(format!("{name}: not meshed"));
            continue;
        };
        let (lo, hi) = e.mesh.bounds().unwrap();
        let reference = common::ReferenceBox::of(theirs, name);
        let box_err = reference.error((lo, hi));
        let (rlo, rhi) = (reference.lo, reference.hi);
        // IfcOpenShell turns some meshes inside out (a circle trimmed against its sense).
        let their_volume = theirs["volume"].as_f64().unwrap().abs();
        let volume = e.mesh.volume();
        let closed = !OPEN.contains(&name.as_str());
        eprintln!(
            "{name:28} {:26} box within {box_err:.1e} m, volume {volume:.6} vs {their_volume:.6} m3",
            e.class
        );
        compared += 1;
        if box_err > BOX_TOLERANCE {
            problems.push(format!(
                "{name}: box {lo}..{hi}, IfcOpenShell {rlo:?}..{rhi:?}"
            ));
        }
        if closed && (volume / their_volume - 1.0).abs() > VOLUME_TOLERANCE {
            problems.push(format!(
                "{name}: volume {volume} m3, IfcOpenShell {their_volume} m3"
            ));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    assert_eq!(compared, 30, "cases compared");

    // The railing (posts at x = 0 and x = 3 up to a handrail 1 m up) is an obstacle in the
    // ground floor's plan: the band 0.05..1.0 m cuts both posts.
    let plans = floor_plans(&models["swept-ifc4.ifc"], &PlanOptions::default());
    let railing = plans
        .iter()
        .flat_map(|p| &p.items)
        .find(|i| i.name.as_deref() == Some("disk_polyline"))
        .expect("the railing is in a plan");
    assert!(railing.kind.is_obstacle(), "{:?}", railing.kind);
    assert_eq!(railing.source, PlanSource::Section);
    for post in [DVec2::new(0.0, 0.0), DVec2::new(3.0, 0.0)] {
        assert!(
            railing.regions.iter().any(|r| r.contains(post)),
            "post at {post} not in the plan"
        );
    }
    // Its footprint: the hull of its mesh, from the floor to the handrail's top.
    let model = &models["swept-ifc4.ifc"];
    let mut cache = PlacementCache::new(model);
    let f = footprint_of(&mut cache, model.entity(railing.product).unwrap())
        .unwrap()
        .footprint;
    assert!(
        f.z_min.abs() < 1e-9 && (f.z_max - 1.025).abs() < 0.001,
        "{f:?}"
    );
    let (lo, hi) = poinav_geom::polygon::bounds(&f.polygon).unwrap();
    assert!(
        (lo.x + 0.025).abs() < 0.001 && (hi.x - 3.025).abs() < 0.001,
        "{lo} {hi}"
    );
    // And the open profile's (a surface on a trimmed polyline, 2 m high).
    let open = ours["open_profile"].product;
    let f = footprint_of(&mut cache, model.entity(open).unwrap())
        .unwrap()
        .footprint;
    assert_eq!((f.z_min, f.z_max), (0.0, 2.0));
    let (lo, hi) = poinav_geom::polygon::bounds(&f.polygon).unwrap();
    assert!(lo.distance(DVec2::new(1.0, 30.0)) < 1e-9, "{lo}");
    assert!(hi.distance(DVec2::new(2.5, 32.0)) < 1e-9, "{hi}");
}

#[test]
fn unsupported_directrix_names_its_id() {
    let text = "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n\
        #1=IFCCARTESIANPOINT((0.,0.,0.));#2=IFCAXIS2PLACEMENT3D(#1,$,$);#3=IFCLOCALPLACEMENT($,#2);\
        #4=IFCCARTESIANPOINT((4.,0.,0.));#5=IFCPOLYLINE((#1,#4));#6=IFCDIRECTION((0.,0.,1.));\
        #7=IFCOFFSETCURVE3D(#5,0.5,.F.,#6);#8=IFCSWEPTDISKSOLID(#7,0.05,$,$,$);\
        #9=IFCSHAPEREPRESENTATION($,'Body','AdvancedSweptSolid',(#8));\
        #10=IFCPRODUCTDEFINITIONSHAPE($,$,(#9));\
        #11=IFCPIPESEGMENT('0YvctVUKr0kugbFTf53O9L',$,'pipe',$,$,#3,#10,$,$);\n\
        ENDSEC;END-ISO-10303-21;";
    let model = Model::from_bytes("t.ifc", text.as_bytes().to_vec()).unwrap();
    let meshes = mesh_model(&model);
    assert!(meshes.elements.is_empty());
    let [(product, err)] = &meshes.failures[..] else {
        panic!("{:?}", meshes.failures)
    };
    assert_eq!(*product, EntityId(11));
    assert!(
        matches!(err, GeomError::Unsupported { id, class, .. } if *id == EntityId(7) && class == "IfcOffsetCurve3D"),
        "{err}"
    );
}
