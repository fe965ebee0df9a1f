//! An element whose floor-plan section reaches its bound is unknown space in the navigation
//! grid, never free: a dense piece of furniture cut off by a low edge bound is drawn as its
//! convex hull, an `Unknown` obstacle, and its cells are unknown where, within the default
//! bound, they are occupied.

use glam::DVec2;
use poinav_bridge::{building, Stages};
use poinav_geom::section::{SectionBounds, SectionLimit};
use poinav_geom::{
    floor_plans, floor_plans_with_meshes, GeomError, PlanItemKind, PlanOptions, PlanSource,
};
use poinav_ifc::{EntityId, Model};
use poinav_nav::{CellState, GridOptions, ObstacleKind, OccupancyGrid};
use poinav_poi::{classify, RobotProfile, RuleSet};

/// Segments around the furniture's cylinder.
const N: usize = 100;

/// A 4 m x 3 m room (#30) and, in it, a table (#40): a closed cylinder of radius 0.4 m from
/// 0.2 to 0.8 m centred at (2, 1.5), as a triangulated face set of 4 x `N` triangles.
fn model() -> Model {
    let mut points = Vec::new();
    for z in [0.2, 0.8] {
        points.push(format!("(2.,1.5,{z})"));
        for k in 0..N {
            let a = std::f64::consts::TAU * k as f64 / N as f64;
            points.push(format!(
                "({:.6},{:.6},{z})",
                2.0 + 0.4 * a.cos(),
                1.5 + 0.4 * a.sin()
            ));
        }
    }
    // 1-based: bottom centre 1, bottom ring 2..=N+1, top centre N+2, top ring N+3..
    let (bc, tc) = (1, N + 2);
    let b = |k: usize| 2 + k % N;
    let t = |k: usize| N + 3 + k % N;
    let mut faces = Vec::new();
    for k in 0..N {
        faces.push(format!("({bc},{},{})", b(k + 1), b(k)));
        faces.push(format!("({tc},{},{})", t(k), t(k + 1)));
        faces.push(format!("({},{},{})", b(k), b(k + 1), t(k + 1)));
        faces.push(format!("({},{},{})", b(k), t(k + 1), t(k)));
    }
    let text = format!(
        "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;
#1=IFCPROJECT('0YvctVUKr0kugbFTf53O9L',$,'P',$,$,$,$,$,#2);
#2=IFCUNITASSIGNMENT((#3));#3=IFCSIUNIT(*,.LENGTHUNIT.,$,.METRE.);
#10=IFCCARTESIANPOINT((0.,0.,0.));#11=IFCAXIS2PLACEMENT3D(#10,$,$);#12=IFCLOCALPLACEMENT($,#11);
#20=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,4.,3.);#21=IFCDIRECTION((0.,0.,1.));
#22=IFCCARTESIANPOINT((2.,1.5,0.));#23=IFCAXIS2PLACEMENT3D(#22,$,$);
#24=IFCEXTRUDEDAREASOLID(#20,#23,#21,2.5);
#25=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#24));
#26=IFCPRODUCTDEFINITIONSHAPE($,$,(#25));
#30=IFCSPACE('1YvctVUKr0kugbFTf53O9L',$,'101',$,$,#12,#26,$,.ELEMENT.,$,$);
#41=IFCCARTESIANPOINTLIST3D(({}));
#42=IFCTRIANGULATEDFACESET(#41,$,.T.,({}),$);
#43=IFCSHAPEREPRESENTATION($,'Body','Tessellation',(#42));
#44=IFCPRODUCTDEFINITIONSHAPE($,$,(#43));
#40=IFCFURNITURE('2YvctVUKr0kugbFTf53O9L',$,'Table',$,$,#12,#44,$,$);
ENDSEC;END-ISO-10303-21;",
        points.join(","),
        faces.join(",")
    );
    Model::from_bytes("table.ifc", text.into_bytes()).unwrap()
}

/// The state of the grid cell at `p` on the plan of `model` cut within `bounds`.
fn cell_states(model: &Model, bounds: SectionBounds, at: &[DVec2]) -> Vec<CellState> {
    let options = PlanOptions {
        section: bounds,
        ..PlanOptions::default()
    };
    let meshes = poinav_geom::mesh_model(model);
    let plans = floor_plans_with_meshes(model, &meshes, &options);
    assert_eq!(plans.len(), 1);
    let profile = RobotProfile::paper();
    let c = classify(model, &RuleSet::defaults(), &profile);
    let made = building(model, &c, &Stages { meshes, plans });
    let floor = &made.building.floors[0];
    let grid = OccupancyGrid::build(floor, &profile, &GridOptions::default()).unwrap();
    at.iter()
        .map(|p| grid.cells[grid.cell_of(*p).unwrap()])
        .collect()
}

#[test]
fn a_table_whose_section_is_cut_off_is_unknown_not_free() {
    let model = model();
    assert!(model.diagnostics().is_empty(), "{:?}", model.diagnostics());
    let low = SectionBounds {
        max_edges: 50,
        ..SectionBounds::default()
    };
    // The plan: the table is its hull, drawn as unknown, and named among the problems.
    let plans = floor_plans(
        &model,
        &PlanOptions {
            section: low,
            ..PlanOptions::default()
        },
    );
    let table = plans[0]
        .items
        .iter()
        .find(|i| i.product == EntityId(40))
        .unwrap();
    assert_eq!(table.kind, PlanItemKind::Furniture);
    assert_eq!(table.source, PlanSource::Outline);
    // The hull of a 100-gon of radius 0.4: the polygon itself.
    let polygon = 50.0 * 0.16 * (std::f64::consts::TAU / 100.0).sin();
    assert!((table.area() - polygon).abs() < 1e-4, "{}", table.area());
    let space = plans[0].items.iter().find(|i| i.product == EntityId(30));
    assert_eq!(space.unwrap().source, PlanSource::Section);
    assert_eq!(plans[0].problems.len(), 1);
    let p = &plans[0].problems[0];
    assert!(p.fell_back);
    assert!(
        matches!(
            &p.error,
            GeomError::SectionLimit { id: EntityId(40), class, limit: SectionLimit::Edges { edges: 200, limit: 50 } }
                if class == "IfcFurniture"
        ),
        "{:?}",
        p.error
    );
    assert_eq!(
        p.error.to_string(),
        "#40: IfcFurniture's section has an outline of 200 edges, more than 50; its convex hull \
         is drawn as unknown space"
    );
    let profile = RobotProfile::paper();
    let c = classify(&model, &RuleSet::defaults(), &profile);
    let stages = Stages {
        meshes: poinav_geom::mesh_model(&model),
        plans,
    };
    let made = building(&model, &c, &stages);
    let floor = &made.building.floors[0];
    let kinds: Vec<ObstacleKind> = floor.obstacles.iter().map(|o| o.kind).collect();
    assert_eq!(kinds, [ObstacleKind::Unknown]);

    // The grid: the table's centre and a point just inside its edge are unknown, a point
    // in the room away from it free; within the default bounds the table is occupied.
    let at = [
        DVec2::new(2.0, 1.5),
        DVec2::new(2.37, 1.5),
        DVec2::new(0.5, 0.5),
    ];
    assert_eq!(
        cell_states(&model, low, &at),
        [CellState::Unknown, CellState::Unknown, CellState::Free]
    );
    assert_eq!(
        cell_states(&model, SectionBounds::default(), &at),
        [CellState::Occupied, CellState::Occupied, CellState::Free]
    );
}
