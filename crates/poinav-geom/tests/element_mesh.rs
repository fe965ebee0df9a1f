//! Element meshes of small hand-written models with known answers: an extrusion with a hole,
//! a scaled and mirrored mapped item, a wall less a door opening and a window opening,
//! clipping by plain and polygon-bounded half-spaces, and hostile input that must end in an
//! error naming its `#id` rather than a panic or a hang.

use glam::DVec3;
use poinav_geom::{mesh_model, mesh_product, ElementMesh, GeomError, PlacementCache};
use poinav_ifc::{EntityId, Model};

/// Shared header: metres, a world placement #3 and the usual directions.
const COMMON: &str = "
#1=IFCCARTESIANPOINT((0.,0.,0.));#2=IFCAXIS2PLACEMENT3D(#1,$,$);#3=IFCLOCALPLACEMENT($,#2);
#4=IFCDIRECTION((0.,0.,1.));#5=IFCDIRECTION((1.,0.,0.));#6=IFCDIRECTION((0.,1.,0.));
#7=IFCDIRECTION((0.,-1.,0.));
";

fn model(data: &str) -> Model {
    let text = format!(
        "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;{COMMON}{data}\nENDSEC;END-ISO-10303-21;"
    );
    Model::from_bytes("t.ifc", text.into_bytes()).unwrap()
}

fn mesh(m: &Model, id: u64) -> Result<ElementMesh, GeomError> {
    let mut cache = PlacementCache::new(m);
    mesh_product(&mut cache, m.entity(EntityId(id)).unwrap())
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-4 * b.abs().max(1.0)
}

fn assert_box(e: &ElementMesh, lo: [f64; 3], hi: [f64; 3]) {
    let (l, h) = e.mesh.bounds().unwrap();
    assert!(
        (l - DVec3::from(lo)).length() < 1e-6 && (h - DVec3::from(hi)).length() < 1e-6,
        "bounds {l} {h}"
    );
}

#[test]
fn extruded_rectangle_with_a_hole() {
    // A 4 x 3 profile with a 1 x 1 hole, 2 m deep: area 2 (12 - 1) + 2 (14 + 4) = 58.
    let m = model(
        "#10=IFCCARTESIANPOINT((0.,0.));#11=IFCCARTESIANPOINT((4.,0.));#12=IFCCARTESIANPOINT((4.,3.));
         #13=IFCCARTESIANPOINT((0.,3.));#14=IFCPOLYLINE((#10,#11,#12,#13,#10));
         #15=IFCCARTESIANPOINT((1.,1.));#16=IFCCARTESIANPOINT((2.,1.));#17=IFCCARTESIANPOINT((2.,2.));
         #18=IFCCARTESIANPOINT((1.,2.));#19=IFCPOLYLINE((#15,#16,#17,#18,#15));
         #20=IFCARBITRARYPROFILEDEFWITHVOIDS(.AREA.,$,#14,(#19));
         #21=IFCEXTRUDEDAREASOLID(#20,#2,#4,2.);
         #22=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#21));#23=IFCPRODUCTDEFINITIONSHAPE($,$,(#22));
         #24=IFCSLAB('0YvctVUKr0kugbFTf53O90',$,'slab',$,$,#3,#23,$,.FLOOR.);
         #30=IFCRECTANGLEHOLLOWPROFILEDEF(.AREA.,$,$,0.2,0.1,0.01,$,$);
         #31=IFCEXTRUDEDAREASOLID(#30,#2,#4,3.);
         #32=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#31));#33=IFCPRODUCTDEFINITIONSHAPE($,$,(#32));
         #34=IFCCOLUMN('0YvctVUKr0kugbFTf53O91',$,'tube',$,$,#3,#33,$,$);",
    );
    let slab = mesh(&m, 24).unwrap();
    assert!(close(slab.mesh.area(), 58.0), "{}", slab.mesh.area());
    assert!(close(slab.mesh.volume(), 22.0), "{}", slab.mesh.volume());
    assert_box(&slab, [0.0, 0.0, 0.0], [4.0, 3.0, 2.0]);
    // A 200 x 100 tube, 10 mm wall, 3 m long: sides 3 (0.6 + 0.52), ends 2 (0.02 - 0.0144).
    let tube = mesh(&m, 34).unwrap();
    assert!(
        close(tube.mesh.area(), 3.0 * 1.12 + 2.0 * 0.0056),
        "{}",
        tube.mesh.area()
    );
}

#[test]
fn mapped_item_with_non_uniform_scale_and_mirror() {
    // A unit cube mapped with scales (2, 3, 0.5) and its y axis flipped, placed at x = 10.
    let m = model(
        "#10=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,1.,1.);#11=IFCEXTRUDEDAREASOLID(#10,#2,#4,1.);
         #12=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#11));#13=IFCREPRESENTATIONMAP(#2,#12);
         #14=IFCCARTESIANPOINT((10.,0.,0.));
         #15=IFCCARTESIANTRANSFORMATIONOPERATOR3DNONUNIFORM(#5,#7,#14,2.,#4,3.,0.5);
         #16=IFCMAPPEDITEM(#13,#15);
         #17=IFCSHAPEREPRESENTATION($,'Body','MappedRepresentation',(#16));
         #18=IFCPRODUCTDEFINITIONSHAPE($,$,(#17));
         #19=IFCFURNITURE('0YvctVUKr0kugbFTf53O92',$,'box',$,$,#3,#18,$,$);",
    );
    let e = mesh(&m, 19).unwrap();
    assert_box(&e, [9.0, -1.5, 0.0], [11.0, 1.5, 0.5]);
    assert!(
        close(e.mesh.area(), 2.0 * (6.0 + 1.0 + 1.5)),
        "{}",
        e.mesh.area()
    );
    // Mirroring keeps the triangles facing outwards: the volume stays positive.
    assert!(close(e.mesh.volume(), 3.0), "{}", e.mesh.volume());
}

/// A 4 m x 0.2 m x 3 m wall (#40) with openings, each given as (x, z, width, height, depth
/// centred on the wall).
fn wall_with_openings(openings: &[(f64, f64, f64, f64, f64)]) -> Model {
    let mut data = String::from(
        "#30=IFCCARTESIANPOINT((2.,0.));#31=IFCAXIS2PLACEMENT2D(#30,$);
         #32=IFCRECTANGLEPROFILEDEF(.AREA.,$,#31,4.,0.2);#33=IFCEXTRUDEDAREASOLID(#32,#2,#4,3.);
         #34=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#33));#35=IFCPRODUCTDEFINITIONSHAPE($,$,(#34));
         #36=IFCCARTESIANPOINT((100.,50.,10.));#37=IFCAXIS2PLACEMENT3D(#36,$,$);
         #38=IFCLOCALPLACEMENT(#3,#37);
         #40=IFCWALL('0YvctVUKr0kugbFTf53O93',$,'wall',$,$,#38,#35,$,$);",
    );
    for (i, &(x, z, w, h, d)) in openings.iter().enumerate() {
        let b = 100 + 20 * i;
        // Extruded along -y from y = d / 2, like Revit's openings.
        data.push_str(&format!(
            "#{p}=IFCCARTESIANPOINT(({x},{y},{z}));#{a}=IFCAXIS2PLACEMENT3D(#{p},$,$);
             #{l}=IFCLOCALPLACEMENT(#38,#{a});
             #{c}=IFCCARTESIANPOINT(({cx},{cz}));#{a2}=IFCAXIS2PLACEMENT2D(#{c},$);
             #{r}=IFCRECTANGLEPROFILEDEF(.AREA.,$,#{a2},{w},{h});
             #{ap}=IFCAXIS2PLACEMENT3D(#1,#7,#5);
             #{s}=IFCEXTRUDEDAREASOLID(#{r},#{ap},#4,{d});
             #{sr}=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#{s}));
             #{ps}=IFCPRODUCTDEFINITIONSHAPE($,$,(#{sr}));
             #{o}=IFCOPENINGELEMENT('0YvctVUKr0kugbFTf53P{i:02}',$,$,$,$,#{l},#{ps},$,.OPENING.);
             #{v}=IFCRELVOIDSELEMENT('0YvctVUKr0kugbFTf53Q{i:02}',$,$,$,#40,#{o});",
            p = b,
            a = b + 1,
            l = b + 2,
            c = b + 3,
            a2 = b + 4,
            r = b + 5,
            ap = b + 6,
            s = b + 7,
            sr = b + 8,
            ps = b + 9,
            o = b + 10,
            v = b + 11,
            y = d / 2.0,
            cx = w / 2.0,
            cz = h / 2.0,
        ));
    }
    model(&data)
}

#[test]
fn box_minus_a_door_opening_as_deep_as_the_wall() {
    // A 1 m x 2 m door opening at the wall's foot, exactly as deep as the wall is thick: the
    // wall becomes a U-shaped prism, 23.6 m2 (26.8 - 2 x 2 - 0.2 + reveals 0.8 + 0.2), 28
    // triangles (two 8-point caps of 6 triangles, 8 quads).
    let m = wall_with_openings(&[(1.5, 0.0, 1.0, 2.0, 0.2)]);
    let wall = mesh(&m, 40).unwrap();
    assert!(close(wall.mesh.area(), 23.6), "{}", wall.mesh.area());
    assert!(
        close(wall.mesh.volume(), 2.4 - 0.4),
        "{}",
        wall.mesh.volume()
    );
    assert_eq!(wall.mesh.triangles.len(), 28);
    assert_box(&wall, [100.0, 49.9, 10.0], [104.0, 50.1, 13.0]);
    // Openings are not elements of their own.
    let all = mesh_model(&m);
    assert_eq!(all.elements.len(), 1);
    assert_eq!(all.elements[0], wall);
    assert!(all.failures.is_empty());
}

#[test]
fn box_minus_a_window_opening_deeper_than_the_wall() {
    // A 1 m x 1 m window opening through the middle, 0.5 m deep: a hole in both faces.
    let m = wall_with_openings(&[(1.5, 1.0, 1.0, 1.0, 0.5), (3.5, 1.0, 1.0, 3.0, 0.5)]);
    let wall = mesh(&m, 40).unwrap();
    // The second opening reaches past the top and the end: it cuts the corner x > 3.5,
    // z > 1 away. Area: faces 2 (12 - 1 - 1) = 20, ends 0.6 + 0.2, top 0.7, bottom 0.8,
    // hole reveals 4 x 0.2 = 0.8, corner reveals (0.5 + 2) x 0.2 = 0.5.
    let expected = 20.0 + 0.6 + 0.2 + 0.7 + 0.8 + 0.8 + 0.5;
    assert!(close(wall.mesh.area(), expected), "{}", wall.mesh.area());
    assert!(
        close(wall.mesh.volume(), 0.2 * 10.0),
        "{}",
        wall.mesh.volume()
    );
}

#[test]
fn half_space_clips() {
    // A 2 x 2 x 2 box; #50 removes z > 1.5 (normal up, agreement false: the material is on
    // the normal's side); #60 removes the part x > 1 within a polygon covering y < 1 only.
    let m = model(
        "#10=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,2.,2.);#11=IFCEXTRUDEDAREASOLID(#10,#2,#4,2.);
         #41=IFCCARTESIANPOINT((0.,0.,1.5));#42=IFCAXIS2PLACEMENT3D(#41,#4,#5);#43=IFCPLANE(#42);
         #44=IFCHALFSPACESOLID(#43,.F.);
         #50=IFCBOOLEANCLIPPINGRESULT(.DIFFERENCE.,#11,#44);
         #51=IFCSHAPEREPRESENTATION($,'Body','Clipping',(#50));#52=IFCPRODUCTDEFINITIONSHAPE($,$,(#51));
         #53=IFCWALL('0YvctVUKr0kugbFTf53O94',$,'clipped',$,$,#3,#52,$,$);
         #61=IFCCARTESIANPOINT((1.,0.,0.));#62=IFCDIRECTION((-1.,0.,0.));
         #63=IFCAXIS2PLACEMENT3D(#61,#62,#6);#64=IFCPLANE(#63);
         #65=IFCAXIS2PLACEMENT3D(#1,#4,#5);
         #66=IFCCARTESIANPOINT((-5.,-5.));#67=IFCCARTESIANPOINT((5.,-5.));#68=IFCCARTESIANPOINT((5.,0.));
         #69=IFCCARTESIANPOINT((-5.,0.));#70=IFCPOLYLINE((#66,#67,#68,#69,#66));
         #71=IFCPOLYGONALBOUNDEDHALFSPACE(#64,.T.,#65,#70);
         #72=IFCBOOLEANCLIPPINGRESULT(.DIFFERENCE.,#50,#71);
         #73=IFCSHAPEREPRESENTATION($,'Body','Clipping',(#72));#74=IFCPRODUCTDEFINITIONSHAPE($,$,(#73));
         #75=IFCWALL('0YvctVUKr0kugbFTf53O95',$,'clipped twice',$,$,#3,#74,$,$);",
    );
    let once = mesh(&m, 53).unwrap();
    assert_box(&once, [-1.0, -1.0, 0.0], [1.0, 1.0, 1.5]);
    assert!(
        close(once.mesh.area(), 2.0 * 4.0 + 4.0 * 3.0),
        "{}",
        once.mesh.area()
    );
    assert!(close(once.mesh.volume(), 6.0), "{}", once.mesh.volume());
    // The normal of #64 is -x, agreement true: its material is x > 1, outside the box, so a
    // second clipping in the chain changes nothing.
    let twice = mesh(&m, 75).unwrap();
    assert!(close(twice.mesh.volume(), 6.0), "{}", twice.mesh.volume());
}

#[test]
fn polygon_bounded_half_space_removes_a_notch() {
    // A 2 x 2 x 2 box less the half-space x > 0 bounded to the prism y < 0: a quarter of
    // the footprint goes, full height (the prism extends along z both ways).
    let m = model(
        "#10=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,2.,2.);#11=IFCEXTRUDEDAREASOLID(#10,#2,#4,2.);
         #62=IFCDIRECTION((-1.,0.,0.));#63=IFCAXIS2PLACEMENT3D(#1,#62,#6);#64=IFCPLANE(#63);
         #66=IFCCARTESIANPOINT((-5.,-5.));#67=IFCCARTESIANPOINT((5.,-5.));#68=IFCCARTESIANPOINT((5.,0.));
         #69=IFCCARTESIANPOINT((-5.,0.));#70=IFCPOLYLINE((#66,#67,#68,#69,#66));
         #71=IFCPOLYGONALBOUNDEDHALFSPACE(#64,.T.,#2,#70);
         #72=IFCBOOLEANCLIPPINGRESULT(.DIFFERENCE.,#11,#71);
         #73=IFCSHAPEREPRESENTATION($,'Body','Clipping',(#72));#74=IFCPRODUCTDEFINITIONSHAPE($,$,(#73));
         #75=IFCWALL('0YvctVUKr0kugbFTf53O95',$,'notched',$,$,#3,#74,$,$);",
    );
    let e = mesh(&m, 75).unwrap();
    assert!(close(e.mesh.volume(), 6.0), "{}", e.mesh.volume());
    // An L-shaped prism: caps 2 x 3, sides 8 x 2.
    assert!(close(e.mesh.area(), 6.0 + 16.0), "{}", e.mesh.area());
    assert_box(&e, [-1.0, -1.0, 0.0], [1.0, 1.0, 2.0]);
}

#[test]
fn colours_come_from_styled_items_else_from_the_material() {
    let m = model(
        "#10=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,1.,1.);#11=IFCEXTRUDEDAREASOLID(#10,#2,#4,1.);
         #12=IFCCOLOURRGB($,1.,0.5,0.);#13=IFCSURFACESTYLESHADING(#12,0.25);
         #14=IFCSURFACESTYLE($,.BOTH.,(#13));#15=IFCSTYLEDITEM(#11,(#14),$);
         #16=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#11));#17=IFCPRODUCTDEFINITIONSHAPE($,$,(#16));
         #18=IFCWALL('0YvctVUKr0kugbFTf53O96',$,'styled',$,$,#3,#17,$,$);
         #20=IFCEXTRUDEDAREASOLID(#10,#2,#4,2.);
         #21=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#20));#22=IFCPRODUCTDEFINITIONSHAPE($,$,(#21));
         #23=IFCWALL('0YvctVUKr0kugbFTf53O97',$,'material',$,$,#3,#22,$,$);
         #24=IFCMATERIAL('brick',$,$);#25=IFCCOLOURRGB($,0.,0.,1.);
         #26=IFCSURFACESTYLERENDERING(#25,$,$,$,$,$,$,$,.NOTDEFINED.);
         #27=IFCSURFACESTYLE($,.BOTH.,(#26));#28=IFCSTYLEDITEM($,(#27),$);
         #29=IFCSTYLEDREPRESENTATION($,$,$,(#28));#30=IFCMATERIALDEFINITIONREPRESENTATION($,$,(#29),#24);
         #31=IFCMATERIALLAYER(#24,0.2,$,$,$,$,$);#32=IFCMATERIALLAYERSET((#31),$,$);
         #33=IFCMATERIALLAYERSETUSAGE(#32,.AXIS2.,.POSITIVE.,0.,$);
         #34=IFCRELASSOCIATESMATERIAL('0YvctVUKr0kugbFTf53O98',$,$,$,(#23),#33);
         #40=IFCEXTRUDEDAREASOLID(#10,#2,#4,3.);
         #41=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#40));#42=IFCPRODUCTDEFINITIONSHAPE($,$,(#41));
         #43=IFCWALL('0YvctVUKr0kugbFTf53O99',$,'plain',$,$,#3,#42,$,$);",
    );
    assert_eq!(mesh(&m, 18).unwrap().color, Some([1.0, 0.5, 0.0, 0.75]));
    assert_eq!(mesh(&m, 23).unwrap().color, Some([0.0, 0.0, 1.0, 1.0]));
    assert_eq!(mesh(&m, 43).unwrap().color, None);
}

#[test]
fn triangulated_face_set_pn_index_flat_or_first_release_normal_index() {
    // One unit tetrahedron (volume 1/6, bounds 0..1) three ways: straight indices; through a
    // flat PnIndex over a point list with a decoy first point; and with IFC4's first-release
    // NormalIndex (a list of index triples, as buildingSMART's texture examples write it) in
    // PnIndex's place, which is not a point mapping and must be ignored, not make every
    // index "outside the point list".
    let m = model(
        "#40=IFCCARTESIANPOINTLIST3D(((0.,0.,0.),(1.,0.,0.),(0.,1.,0.),(0.,0.,1.)));
         #41=IFCTRIANGULATEDFACESET(#40,$,.T.,((1,3,2),(1,2,4),(1,4,3),(2,3,4)),$);
         #42=IFCCARTESIANPOINTLIST3D(((9.,9.,9.),(0.,0.,0.),(1.,0.,0.),(0.,1.,0.),(0.,0.,1.)));
         #43=IFCTRIANGULATEDFACESET(#42,$,.T.,((1,3,2),(1,2,4),(1,4,3),(2,3,4)),(2,3,4,5));
         #44=IFCTRIANGULATEDFACESET(#40,((0.,0.,-1.),(0.,-1.,0.),(-1.,0.,0.),(0.577,0.577,0.577)),
             .T.,((1,3,2),(1,2,4),(1,4,3),(2,3,4)),((1,1,1),(2,2,2),(3,3,3),(4,4,4)));
         #50=IFCSHAPEREPRESENTATION($,'Body','Tessellation',(#41));#51=IFCPRODUCTDEFINITIONSHAPE($,$,(#50));
         #52=IFCBUILDINGELEMENTPROXY('0YvctVUKr0kugbFTf53O9P',$,'plain',$,$,#3,#51,$,$);
         #53=IFCSHAPEREPRESENTATION($,'Body','Tessellation',(#43));#54=IFCPRODUCTDEFINITIONSHAPE($,$,(#53));
         #55=IFCBUILDINGELEMENTPROXY('0YvctVUKr0kugbFTf53O9Q',$,'pn',$,$,#3,#54,$,$);
         #56=IFCSHAPEREPRESENTATION($,'Body','Tessellation',(#44));#57=IFCPRODUCTDEFINITIONSHAPE($,$,(#56));
         #58=IFCBUILDINGELEMENTPROXY('0YvctVUKr0kugbFTf53O9R',$,'normal index',$,$,#3,#57,$,$);",
    );
    for id in [52, 55, 58] {
        let e = mesh(&m, id).unwrap_or_else(|err| panic!("#{id}: {err}"));
        assert_eq!(e.mesh.triangles.len(), 4, "#{id}");
        assert!(
            close(e.mesh.volume(), 1.0 / 6.0),
            "#{id}: {}",
            e.mesh.volume()
        );
        assert_box(&e, [0.0; 3], [1.0; 3]);
    }
}

#[test]
fn hostile_input_is_an_error_naming_its_id() {
    // A mapped-item bomb: each level maps the level below 10 times (10^7 cubes), a NaN
    // coordinate, a depth that overflows when scaled, a boolean chain longer than the limit
    // and a mapped item that maps itself.
    let mut data = String::from(
        "#10=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,1.,1.);#11=IFCEXTRUDEDAREASOLID(#10,#2,#4,1.);
         #12=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#11));#13=IFCREPRESENTATIONMAP(#2,#12);
         #14=IFCCARTESIANTRANSFORMATIONOPERATOR3D($,$,#1,$,$);",
    );
    let mut map = 13;
    for level in 0..7 {
        let base = 1000 + 100 * level;
        let items: Vec<String> = (0..10).map(|i| format!("#{}", base + i)).collect();
        for i in 0..10 {
            data.push_str(&format!("#{}=IFCMAPPEDITEM(#{map},#14);", base + i));
        }
        data.push_str(&format!(
            "#{r}=IFCSHAPEREPRESENTATION($,'Body','MappedRepresentation',({}));#{m}=IFCREPRESENTATIONMAP(#2,#{r});",
            items.join(","),
            r = base + 50,
            m = base + 51
        ));
        map = base + 51;
    }
    data.push_str(&format!(
        "#20=IFCMAPPEDITEM(#{map},#14);#21=IFCSHAPEREPRESENTATION($,'Body','MappedRepresentation',(#20));
         #22=IFCPRODUCTDEFINITIONSHAPE($,$,(#21));#23=IFCWALL('0YvctVUKr0kugbFTf53O9A',$,'bomb',$,$,#3,#22,$,$);
         #30=IFCCARTESIANPOINT((0.,NaN));"
    ));
    // NaN is not STEP: write a huge exponent that parses to infinity instead.
    data = data.replace("NaN", "1.E999");
    data.push_str(
        "#31=IFCCARTESIANPOINT((1.,0.));#32=IFCCARTESIANPOINT((1.,1.));
         #33=IFCPOLYLINE((#30,#31,#32,#30));#34=IFCARBITRARYCLOSEDPROFILEDEF(.AREA.,$,#33);
         #35=IFCEXTRUDEDAREASOLID(#34,#2,#4,1.);#36=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#35));
         #37=IFCPRODUCTDEFINITIONSHAPE($,$,(#36));#38=IFCWALL('0YvctVUKr0kugbFTf53O9B',$,'infinite',$,$,#3,#37,$,$);
         #40=IFCEXTRUDEDAREASOLID(#10,#2,#4,1.E300);#41=IFCCARTESIANTRANSFORMATIONOPERATOR3D($,$,#1,1.E300,$);
         #42=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#40));#43=IFCREPRESENTATIONMAP(#2,#42);
         #44=IFCMAPPEDITEM(#43,#41);#45=IFCSHAPEREPRESENTATION($,'Body','MappedRepresentation',(#44));
         #46=IFCPRODUCTDEFINITIONSHAPE($,$,(#45));#47=IFCWALL('0YvctVUKr0kugbFTf53O9C',$,'overflow',$,$,#3,#46,$,$);
         #50=IFCMAPPEDITEM(#52,#14);#51=IFCSHAPEREPRESENTATION($,'Body','MappedRepresentation',(#50));
         #52=IFCREPRESENTATIONMAP(#2,#51);#53=IFCPRODUCTDEFINITIONSHAPE($,$,(#51));
         #54=IFCWALL('0YvctVUKr0kugbFTf53O9D',$,'cycle',$,$,#3,#53,$,$);
         #60=IFCCARTESIANPOINT((0.,0.,0.5));#61=IFCAXIS2PLACEMENT3D(#60,$,$);#62=IFCPLANE(#61);
         #63=IFCHALFSPACESOLID(#62,.F.);",
    );
    let chain = 5000;
    for i in 0..chain {
        let first = if i == 0 { 11 } else { 10_000 + i - 1 };
        data.push_str(&format!(
            "#{}=IFCBOOLEANCLIPPINGRESULT(.DIFFERENCE.,#{first},#63);",
            10_000 + i
        ));
    }
    data.push_str(&format!(
        "#70=IFCSHAPEREPRESENTATION($,'Body','Clipping',(#{}));#71=IFCPRODUCTDEFINITIONSHAPE($,$,(#70));
         #72=IFCWALL('0YvctVUKr0kugbFTf53O9E',$,'long chain',$,$,#3,#71,$,$);",
        10_000 + chain - 1
    ));
    let m = model(&data);
    let start = std::time::Instant::now();
    let all = mesh_model(&m);
    assert!(all.elements.is_empty(), "{:?}", all.elements);
    let failed: Vec<u64> = all.failures.iter().map(|(id, _)| id.0).collect();
    assert_eq!(failed, vec![23, 38, 47, 54, 72]);
    for (_, e) in &all.failures {
        let msg = e.to_string();
        assert!(msg.starts_with(&e.id().to_string()), "{msg}");
    }
    let reason = |i: usize| all.failures[i].1.to_string();
    assert!(reason(0).contains("more items"), "{}", reason(0));
    assert_eq!(all.failures[1].1.id(), EntityId(30), "{}", reason(1));
    assert!(reason(2).contains("overflow"), "{}", reason(2));
    assert!(reason(3).contains("nested too deeply"), "{}", reason(3));
    assert!(reason(4).contains("nested too deeply"), "{}", reason(4));
    assert!(start.elapsed().as_secs() < 60, "took {:?}", start.elapsed());
}
