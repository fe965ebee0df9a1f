//! Pathological geometry is cut off, not waited for: a wall with thousands of openings that
//! would take long to cut is left out with a `TimeLimit` failure naming it, once its time
//! limit passes; the model's other elements are meshed as usual.

use std::time::{Duration, Instant};

use poinav_geom::{mesh_model_within, GeomError};
use poinav_ifc::{EntityId, Model};

/// Wall #100 (`openings` openings cut through it, 0.2 x 0.2 m, 0.3 m apart) and wall #200
/// without openings.
fn model(openings: usize) -> Model {
    let mut data = String::from(
        "#1=IFCCARTESIANPOINT((0.,0.,0.));#2=IFCAXIS2PLACEMENT3D(#1,$,$);#3=IFCLOCALPLACEMENT($,#2);
#4=IFCDIRECTION((0.,0.,1.));
#10=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,1000.,0.3);#5=IFCCARTESIANPOINT((500.,0.15,0.));
#6=IFCAXIS2PLACEMENT3D(#5,$,$);#11=IFCEXTRUDEDAREASOLID(#10,#6,#4,3.);
#12=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#11));#13=IFCPRODUCTDEFINITIONSHAPE($,$,(#12));
#100=IFCWALL('0YvctVUKr0kugbFTf53O90',$,'Wall with many openings',$,$,#3,#13,$,$);
#200=IFCWALL('0YvctVUKr0kugbFTf53O91',$,'Plain wall',$,$,#3,#13,$,$);
#20=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,0.2,0.5);#21=IFCCARTESIANPOINT((0.1,0.15,0.));
#22=IFCAXIS2PLACEMENT3D(#21,$,$);#23=IFCEXTRUDEDAREASOLID(#20,#22,#4,0.2);
#24=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#23));#25=IFCPRODUCTDEFINITIONSHAPE($,$,(#24));
",
    );
    for k in 0..openings {
        let id = 1000 + 4 * k;
        let x = 0.1 + 0.3 * k as f64;
        data.push_str(&format!(
            "#{}=IFCCARTESIANPOINT(({x:.3},0.,1.));#{}=IFCAXIS2PLACEMENT3D(#{},$,$);#{}=IFCLOCALPLACEMENT(#3,#{});\
             #{}=IFCOPENINGELEMENT('{}',$,$,$,$,#{},#25,$,.OPENING.);\
             #{}=IFCRELVOIDSELEMENT('{}',$,$,$,#100,#{});\n",
            id,
            id + 1,
            id,
            id + 2,
            id + 1,
            id + 3,
            poinav_ifc::GlobalId::from_name("opening", &k.to_string()),
            id + 2,
            900_000 + k,
            poinav_ifc::GlobalId::from_name("voids", &k.to_string()),
            id + 3,
        ));
    }
    let text = format!(
        "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;{data}ENDSEC;END-ISO-10303-21;"
    );
    Model::from_bytes("openings.ifc", text.into_bytes()).unwrap()
}

#[test]
fn a_wall_with_thousands_of_openings_is_cut_off_and_named() {
    let m = model(3000);
    assert!(m.diagnostics().is_empty(), "{:?}", m.diagnostics());
    let limit = Duration::from_millis(100);
    let started = Instant::now();
    let meshes = mesh_model_within(&m, limit);
    let took = started.elapsed();
    assert_eq!(meshes.failures.len(), 1, "{:?}", meshes.failures);
    let (id, e) = &meshes.failures[0];
    assert_eq!(*id, EntityId(100));
    assert!(
        matches!(e, GeomError::TimeLimit { id: EntityId(100), class, seconds } if class == "IfcWall" && *seconds == 0.1),
        "{e:?}"
    );
    assert_eq!(
        e.to_string(),
        "#100: IfcWall took longer than 0.1 s to mesh (pathological geometry); left out"
    );
    let plain: Vec<_> = meshes.elements.iter().map(|e| e.product).collect();
    assert_eq!(plain, [EntityId(200)]);
    // Cut off soon after the limit: one boolean operation past it at most.
    assert!(took < Duration::from_secs(5), "took {took:?}");
}

#[test]
fn within_the_limit_the_same_wall_is_cut_by_every_opening() {
    let m = model(20);
    let meshes = mesh_model_within(&m, Duration::from_secs(600));
    assert!(meshes.failures.is_empty(), "{:?}", meshes.failures);
    let wall = meshes
        .elements
        .iter()
        .find(|e| e.product == EntityId(100))
        .unwrap();
    let plain = meshes
        .elements
        .iter()
        .find(|e| e.product == EntityId(200))
        .unwrap();
    // 20 holes through the wall: more triangles than the plain box's 12.
    assert_eq!(plain.mesh.triangles.len(), 12);
    assert!(
        wall.mesh.triangles.len() > 12 + 20 * 8,
        "{}",
        wall.mesh.triangles.len()
    );
}
