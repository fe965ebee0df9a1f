//! Damaged parts of a model give an error naming their `#id` for that element only; the
//! other elements of the same model are still read (footprints, door frames and meshes).

use poinav_geom::{door_geometry, footprint_of, GeomError, PlacementCache};
use poinav_ifc::{EntityId, Model};

const DATA: &str = "
#1=IFCCARTESIANPOINT((0.,0.,0.));#2=IFCAXIS2PLACEMENT3D(#1,$,$);#3=IFCLOCALPLACEMENT($,#2);
#4=IFCDIRECTION((0.,0.,1.));
#10=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,2.,3.);#11=IFCEXTRUDEDAREASOLID(#10,#2,#4,2.5);
#12=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#11));#13=IFCPRODUCTDEFINITIONSHAPE($,$,(#12));
#20=IFCSPACE('0YvctVUKr0kugbFTf53O90',$,'good',$,$,#3,#13,$,.ELEMENT.,$,$);
#30=IFCLOCALPLACEMENT(#31,#2);#31=IFCLOCALPLACEMENT(#30,#2);
#32=IFCSPACE('0YvctVUKr0kugbFTf53O91',$,'cyclic placement',$,$,#30,#13,$,.ELEMENT.,$,$);
#40=IFCCENTERLINEPROFILEDEF(.AREA.,$,#45,0.);#45=IFCPOLYLINE((#46,#47));
#46=IFCCARTESIANPOINT((0.,0.));#47=IFCCARTESIANPOINT((1.,0.));#41=IFCEXTRUDEDAREASOLID(#40,#2,#4,2.5);
#42=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#41));#43=IFCPRODUCTDEFINITIONSHAPE($,$,(#42));
#44=IFCSPACE('0YvctVUKr0kugbFTf53O92',$,'zero thickness profile',$,$,#3,#43,$,.ELEMENT.,$,$);
#50=IFCDIRECTION((0.,0.,0.));#51=IFCEXTRUDEDAREASOLID(#10,#2,#50,2.5);
#52=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#51,#99));#53=IFCPRODUCTDEFINITIONSHAPE($,$,(#52));
#54=IFCSPACE('0YvctVUKr0kugbFTf53O93',$,'zero direction',$,$,#3,#53,$,.ELEMENT.,$,$);
#60=IFCSPACE('0YvctVUKr0kugbFTf53O94',$,'no representation',$,$,#3,$,$,.ELEMENT.,$,$);
#70=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#11,#41));#71=IFCPRODUCTDEFINITIONSHAPE($,$,(#70));
#72=IFCSPACE('0YvctVUKr0kugbFTf53O95',$,'one bad item',$,$,#3,#71,$,.ELEMENT.,$,$);
#80=IFCDOOR('0YvctVUKr0kugbFTf53O96',$,'door',$,$,#3,#43,$,2.1,0.9,$,$,$);
";

#[test]
fn damaged_elements_fail_alone() {
    let text = format!(
        "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;{DATA}ENDSEC;END-ISO-10303-21;"
    );
    let model = Model::from_bytes("damaged.ifc", text.into_bytes()).unwrap();
    let mut cache = PlacementCache::new(&model);
    let mut fp = |id| footprint_of(&mut cache, model.entity(EntityId(id)).unwrap());
    let good = fp(20).unwrap();
    assert!((good.footprint.area() - 6.0).abs() < 1e-12);
    assert!(matches!(fp(32), Err(GeomError::PlacementChain { .. })));
    let e = fp(44).unwrap_err();
    assert_eq!(e.id(), EntityId(40));
    assert!(e.to_string().contains("Thickness"), "{e}");
    assert!(matches!(
        fp(54),
        Err(GeomError::Degenerate {
            id: EntityId(50),
            ..
        })
    ));
    assert!(matches!(
        fp(60),
        Err(GeomError::NoGeometry {
            id: EntityId(60),
            ..
        })
    ));
    let partial = fp(72).unwrap();
    assert_eq!(
        partial.approximations.len(),
        1,
        "{:?}",
        partial.approximations
    );
    assert!((partial.footprint.area() - 6.0).abs() < 1e-12);
    // A door without an opening and without a readable body keeps its frame.
    let door = door_geometry(&mut cache, model.entity(EntityId(80)).unwrap()).unwrap();
    assert!(door.footprint.is_none());
    assert_eq!(door.center, door.placement.translation);
    assert_eq!(door.problems.len(), 1);
}

mod fuzz {
    use super::*;
    use proptest::prelude::*;

    /// Numbers as they may appear in damaged files: zero, negative, tiny, huge.
    fn number() -> impl Strategy<Value = f64> {
        prop_oneof![
            Just(0.0),
            Just(-1.0),
            Just(1e-300),
            Just(1e300),
            Just(-1e300),
            -1e4f64..1e4,
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        #[test]
        fn any_numbers_give_a_result_or_an_error_never_a_panic(
            n in proptest::collection::vec(number(), 14),
            swap in 0usize..6,
        ) {
            let f = |x: f64| format!("{x:.17E}");
            // Sometimes a reference points at the wrong kind of instance.
            let (profile, axis) = match swap {
                0 => ("#4", "#2"),
                1 => ("#10", "#4"),
                _ => ("#10", "#2"),
            };
            let data = format!(
                "#1=IFCCARTESIANPOINT(({},{},{}));#4=IFCDIRECTION(({},{},{}));#5=IFCDIRECTION(({},{},{}));\
                 #2=IFCAXIS2PLACEMENT3D(#1,#4,#5);#3=IFCLOCALPLACEMENT($,{axis});\
                 #6=IFCCARTESIANPOINT(({},{}));#7=IFCAXIS2PLACEMENT2D(#6,$);\
                 #10=IFCRECTANGLEPROFILEDEF(.AREA.,$,#7,{},{});#11=IFCEXTRUDEDAREASOLID({profile},#2,#5,{});\
                 #12=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#11));#13=IFCPRODUCTDEFINITIONSHAPE($,$,(#12));\
                 #20=IFCDOOR('0YvctVUKr0kugbFTf53O90',$,'d',$,$,#3,#13,$,2.1,0.9,$,$,$);",
                f(n[0]), f(n[1]), f(n[2]), f(n[3]), f(n[4]), f(n[5]), f(n[6]), f(n[7]), f(n[8]),
                f(n[9]), f(n[10]), f(n[11]), f(n[12]), f(n[13]),
            );
            let text = format!(
                "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n{data}\nENDSEC;END-ISO-10303-21;"
            );
            let model = Model::from_bytes("fuzz.ifc", text.into_bytes()).unwrap();
            let mut cache = PlacementCache::new(&model);
            let door = model.entity(EntityId(20)).unwrap();
            if let Ok(fp) = footprint_of(&mut cache, door) {
                let f = &fp.footprint;
                prop_assert!(f.polygon.len() >= 3);
                prop_assert!(f.polygon.iter().all(|p| p.is_finite()));
                prop_assert!(f.z_min.is_finite() && f.z_max.is_finite() && f.z_min <= f.z_max);
                prop_assert!(f.area() > 0.0);
            }
            let _ = door_geometry(&mut cache, door);
            if let Ok(m) = poinav_geom::mesh_product(&mut cache, door) {
                prop_assert!(!m.mesh.is_empty() && m.mesh.is_finite());
            }
        }
    }
}
