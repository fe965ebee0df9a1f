//! Geometry of IFC products for robots, read with [`poinav_ifc`]: world placements
//! ([`placement`]), profiles ([`profile`]), footprints of spaces and other products
//! ([`footprint`]), door frames ([`door`]) and element meshes in world coordinates with
//! openings cut ([`element_mesh`]: [`mesh_model`], [`mesh_product`]), and storey floor plans
//! ([`floor_plan`]: [`floor_plans`]). All lengths are metres, all numbers `f64`; a part of a
//! model that cannot be read gives a [`GeomError`] naming its `#id`, for that part only.
//!
//! ```
//! use poinav_geom::{footprint_of, PlacementCache};
//! use poinav_ifc::Model;
//!
//! // A 4 m x 3 m room, 2.5 m high, placed at (10 m, 20 m) in a millimetre model.
//! let text = "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n\
//!     #1=IFCPROJECT('0YvctVUKr0kugbFTf53O9L',$,'P',$,$,$,$,$,#2);\n\
//!     #2=IFCUNITASSIGNMENT((#3));#3=IFCSIUNIT(*,.LENGTHUNIT.,.MILLI.,.METRE.);\n\
//!     #10=IFCCARTESIANPOINT((10000.,20000.,0.));#11=IFCAXIS2PLACEMENT3D(#10,$,$);\n\
//!     #12=IFCLOCALPLACEMENT($,#11);\n\
//!     #20=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,4000.,3000.);#21=IFCDIRECTION((0.,0.,1.));\n\
//!     #22=IFCCARTESIANPOINT((0.,0.,0.));#23=IFCAXIS2PLACEMENT3D(#22,$,$);\n\
//!     #24=IFCEXTRUDEDAREASOLID(#20,#23,#21,2500.);\n\
//!     #25=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#24));\n\
//!     #26=IFCPRODUCTDEFINITIONSHAPE($,$,(#25));\n\
//!     #30=IFCSPACE('1YvctVUKr0kugbFTf53O9L',$,'101',$,$,#12,#26,$,.ELEMENT.,$,$);\n\
//!     ENDSEC;END-ISO-10303-21;";
//! let model = Model::from_bytes("room.ifc", text.as_bytes().to_vec()).unwrap();
//! let mut cache = PlacementCache::new(&model);
//! let space = model.instances_of("IfcSpace")[0];
//! assert_eq!(cache.product(space).unwrap().translation.x, 10.0);
//! let f = footprint_of(&mut cache, space).unwrap().footprint;
//! assert!((f.area() - 12.0).abs() < 1e-9);
//! assert_eq!((f.z_min, f.z_max), (0.0, 2.5));
//! assert!(f.contains(glam::DVec2::new(11.9, 21.4)));
//! assert!((f.elongation() - 4.0 / 3.0).abs() < 1e-9);
//! ```

pub mod advanced_brep;
pub mod alignment_curve;
mod axis2_placement;
pub mod boolean;
pub mod brep;
pub mod bspline;
pub mod cartesian_point;
pub mod cartesian_transformation_operator;
pub mod chord_rule;
pub mod csg_primitive;
pub mod curve;
pub mod curve3d;
pub mod curve_bounded_plane;
pub mod direction;
pub mod door;
pub mod door_passage;
pub mod edge_curve;
pub mod element_mesh;
mod error;
pub mod extrusion;
pub mod face_set;
pub mod floor_level;
pub mod floor_plan;
pub mod footprint;
pub mod gradient_curve;
pub mod half_space;
pub mod linear_placement;
pub mod loft;
pub mod mesh;
pub mod open_profile;
mod parameterized_profile;
pub mod part_hulls;
pub mod placement;
pub mod plan_kind;
/// Plane geometry on rings: `poinav-plane`, under the name the geometry has always used.
pub use poinav_plane as polygon;
pub mod profile;
pub mod progress;
pub mod region;
pub mod representation;
pub mod representation_mesh;
pub mod revolve;
pub mod section;
pub mod section_lines;
pub mod sectioned_solid;
pub mod self_crossing;
pub mod surface;
pub mod surface_style;
pub mod sweep;
pub mod swept_area;
pub mod swept_disk;
pub mod tapered_extrusion;
#[cfg(test)]
mod test_model;
pub mod triangulation;
mod unit_assignment;
pub mod uv_mesh;
pub mod walking_slope;
pub mod winding_chain;

pub use door::{door_geometry, DoorGeometry};
pub use door_passage::{door_passage, DoorPassage};
pub use element_mesh::{
    mesh_model, mesh_model_with_progress, mesh_model_within, mesh_product, mesh_product_noting,
    mesh_product_within, without_representation, ModelMeshes, PRODUCT_TIME_LIMIT,
};
pub use error::GeomError;
pub use floor_plan::{
    floor_plans, floor_plans_with_meshes, floor_plans_with_progress, FloorPlan, PlanItem,
    PlanOptions, PlanProblem, PlanSource,
};
pub use footprint::{footprint_of, Footprint, FootprintMethod, ProductFootprint};
pub use mesh::{ElementMesh, Mesh};
pub use placement::{axis2placement_3d, PlacementCache};
pub use plan_kind::PlanItemKind;
pub use representation::Approximation;
pub use unit_assignment::{plane_angle_unit, Units};
pub use walking_slope::walking_slope_deg;
