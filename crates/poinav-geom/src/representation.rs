//! `IfcShapeRepresentation` and its `IfcRepresentationItem`s evaluated to world points in
//! metres: extrusions (with their exact outline when vertical), swept disks, areas swept along
//! a directrix and open-profile extrusions (the vertices of their meshes), faceted breps, face
//! sets, surface models, bounding boxes, boolean results (first operand) and mapped items.

use std::collections::HashSet;

use glam::{DAffine3, DVec2, DVec3};
use poinav_ifc::{Entity, EntityId, Value};

use crate::axis2_placement::axis2placement;
use crate::cartesian_point::{point3, point_list};
use crate::cartesian_transformation_operator::transformation;
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::gradient_curve::BasisCurve;
use crate::open_profile::is_open_profile_extrusion;
use crate::polygon;
use crate::profile;
use crate::representation_mesh::ItemMesher;
use crate::sectioned_solid::sectioned_solid_horizontal;
use crate::swept_area::is_directrix_swept_area_solid;
use crate::unit_assignment::Units;

/// Deepest nesting of mapped items followed.
pub const MAX_DEPTH: usize = 16;

/// Longest chain of boolean results (each the first operand of the next) followed.
pub const MAX_BOOLEAN_CHAIN: usize = 4096;

/// Cosine tolerance under which an extrusion counts as vertical (about 0.08 degrees).
const VERTICAL: f64 = 1.0 - 1e-6;

/// Where a result is less exact than the geometry in the file, and why.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Approximation {
    /// A grid placement was taken as the identity.
    #[error("{0}")]
    GridPlacement(GeomError),
    /// A non-vertical extrusion of a concave profile: its footprint is the convex hull of the
    /// swept profile, larger than the real one. (Convex profiles are exact.)
    #[error("{id}: extrusion of a concave profile is not vertical; its footprint is the convex hull of the swept profile")]
    NonVerticalExtrusion {
        /// The IfcExtrudedAreaSolid.
        id: EntityId,
    },
    /// A boolean result (or chain of them) of which only the first operands were used: the
    /// clipping is ignored, so the solid may be taller or larger than in the file.
    #[error("{id}: boolean result: only the first operand is used, clipping is ignored")]
    BooleanOperandIgnored {
        /// The IfcBooleanResult.
        id: EntityId,
    },
    /// A representation item that could not be read and was left out.
    #[error("item left out: {0}")]
    ItemSkipped(GeomError),
}

/// The geometry of one representation item, in world coordinates (metres).
#[derive(Debug, Clone, PartialEq)]
pub struct ItemGeometry {
    /// The item (an IfcExtrudedAreaSolid, IfcFacetedBrep, ...).
    pub id: EntityId,
    /// The exact horizontal outline (counter-clockwise) when the item is a vertical extrusion.
    pub outline: Option<Vec<DVec2>>,
    /// Its vertices: for an extrusion the profile at both ends.
    pub points: Vec<DVec3>,
}

/// What the items of a representation gave.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RepresentationGeometry {
    /// One entry per leaf item read (mapped items and boolean results are looked through).
    pub items: Vec<ItemGeometry>,
    /// Where the result is approximate.
    pub approximations: Vec<Approximation>,
}

/// The representation used for geometry: the `IfcShapeRepresentation` identified `Body`,
/// else the first one.
pub fn body_representation<'m>(product: Entity<'m>) -> Result<Entity<'m>, GeomError> {
    let no_geometry = || GeomError::NoGeometry {
        id: product.id(),
        class: product.type_name().to_string(),
    };
    let shape = product.get_ref("Representation").ok_or_else(no_geometry)?;
    let reps: Vec<Entity<'m>> = shape
        .get_refs("Representations")
        .into_iter()
        .filter(|r| r.is_a("IfcShapeRepresentation"))
        .collect();
    reps.iter()
        .find(|r| r.get_str("RepresentationIdentifier").as_deref() == Some("Body"))
        .or(reps.first())
        .copied()
        .ok_or_else(no_geometry)
}

/// Evaluates every item of `representation`, mapping local coordinates (metres) to world
/// coordinates with `transform`. Items that cannot be read are left out and reported; the
/// result is an error only when no item could be read.
pub fn evaluate(
    representation: Entity<'_>,
    transform: DAffine3,
    units: &Units,
) -> Result<RepresentationGeometry, GeomError> {
    let mut out = RepresentationGeometry::default();
    let mut first_error = None;
    let items = representation.get_refs("Items");
    for item in items {
        if let Err(e) = evaluate_item(item, transform, units, 0, &mut out) {
            first_error.get_or_insert(e.clone());
            out.approximations.push(Approximation::ItemSkipped(e));
        }
    }
    if out.items.is_empty() {
        return Err(first_error.unwrap_or(GeomError::NoGeometry {
            id: representation.id(),
            class: representation.type_name().to_string(),
        }));
    }
    Ok(out)
}

fn evaluate_item(
    item: Entity<'_>,
    t: DAffine3,
    units: &Units,
    depth: usize,
    out: &mut RepresentationGeometry,
) -> Result<(), GeomError> {
    if depth > MAX_DEPTH {
        return Err(degenerate(
            &item,
            "mapped items or booleans nested too deeply",
        ));
    }
    let s = units.metres_per_unit;
    let leaf = |points: Vec<DVec3>| -> Result<ItemGeometry, GeomError> {
        if points.is_empty() {
            return Err(degenerate(&item, "no vertices"));
        }
        Ok(ItemGeometry {
            id: item.id(),
            outline: None,
            points: points
                .into_iter()
                .map(|p| t.transform_point3(p * s))
                .collect(),
        })
    };
    if item.is_a("IfcMappedItem") {
        let source = required_ref(&item, "MappingSource", "IfcRepresentationMap")?;
        let origin = source
            .get_ref("MappingOrigin")
            .ok_or_else(|| missing(&source, "MappingOrigin"))?;
        let origin = axis2placement(origin, s)?;
        let target = required_ref(&item, "MappingTarget", "IfcCartesianTransformationOperator")?;
        let inner = t * transformation(target, s)? * origin;
        let rep = required_ref(&source, "MappedRepresentation", "IfcRepresentation")?;
        let (items_before, notes_before) = (out.items.len(), out.approximations.len());
        let mut first_error = None;
        for sub in rep.get_refs("Items") {
            if let Err(e) = evaluate_item(sub, inner, units, depth + 1, out) {
                first_error.get_or_insert(e.clone());
                out.approximations.push(Approximation::ItemSkipped(e));
            }
        }
        if out.items.len() == items_before {
            // Nothing read: the mapped item fails as a whole, with its first error.
            out.approximations.truncate(notes_before);
            return Err(first_error.unwrap_or_else(|| degenerate(&rep, "no items")));
        }
        Ok(())
    } else if item.is_a("IfcBooleanResult") {
        // Clipping chains (A - H1) - H2 - ... can be long: follow first operands in a loop.
        let mut current = item;
        let mut clipped = false;
        for _ in 0..MAX_BOOLEAN_CHAIN {
            if !current.is_a("IfcBooleanResult") {
                evaluate_item(current, t, units, depth + 1, out)?;
                if clipped {
                    out.approximations
                        .push(Approximation::BooleanOperandIgnored { id: item.id() });
                }
                return Ok(());
            }
            let first = current
                .get_ref("FirstOperand")
                .ok_or_else(|| missing(&current, "FirstOperand"))?;
            if current.get("Operator").and_then(|v| v.as_enum()) == Some("UNION") {
                let second = current
                    .get_ref("SecondOperand")
                    .ok_or_else(|| missing(&current, "SecondOperand"))?;
                evaluate_item(second, t, units, depth + 1, out)?;
            } else {
                clipped = true;
            }
            current = first;
        }
        Err(degenerate(&item, "boolean results nested too deeply"))
    } else if item.is_a("IfcSweptDiskSolid") || is_directrix_swept_area_solid(&item) {
        mesh_vertices(item, t, units, depth, out)
    } else if item.is_a("IfcExtrudedAreaSolid") {
        let (geometry, concave) = match extrusion(item, t, units) {
            Ok(g) => g,
            Err(_) if is_open_profile_extrusion(&item) => {
                return mesh_vertices(item, t, units, depth, out)
            }
            Err(e) => return Err(e),
        };
        if geometry.outline.is_none() && concave {
            out.approximations
                .push(Approximation::NonVerticalExtrusion { id: item.id() });
        }
        out.items.push(geometry);
        Ok(())
    } else if item.is_a("IfcFacetedBrep") {
        let shell = item
            .get_ref("Outer")
            .ok_or_else(|| missing(&item, "Outer"))?;
        let g = leaf(face_points(&shell_faces(shell)?)?)?;
        out.items.push(g);
        Ok(())
    } else if (item.is_a("IfcFaceBasedSurfaceModel") || item.is_a("IfcShellBasedSurfaceModel"))
        && crate::advanced_brep::has_face_surfaces(item)
    {
        // Faces on surfaces or bounded by edge loops: the vertices of their mesh.
        mesh_vertices(item, t, units, depth, out)
    } else if item.is_a("IfcFaceBasedSurfaceModel") {
        let mut faces = Vec::new();
        for set in item.get_refs("FbsmFaces") {
            faces.extend(shell_faces(set)?);
        }
        let g = leaf(face_points(&faces)?)?;
        out.items.push(g);
        Ok(())
    } else if item.is_a("IfcShellBasedSurfaceModel") {
        let mut faces = Vec::new();
        for shell in item.get_refs("SbsmBoundary") {
            faces.extend(shell_faces(shell)?);
        }
        let g = leaf(face_points(&faces)?)?;
        out.items.push(g);
        Ok(())
    } else if item.is_a("IfcSectionedSolidHorizontal") {
        let directrix = required_ref(&item, "Directrix", "IfcCurve")?;
        let curve = BasisCurve::read(directrix, units)?;
        let mesh = sectioned_solid_horizontal(item, units, &curve)?;
        out.items.push(ItemGeometry {
            id: item.id(),
            outline: None,
            points: mesh
                .positions
                .iter()
                .map(|p| t.transform_point3(*p))
                .collect(),
        });
        Ok(())
    } else if item.is_a("IfcTessellatedFaceSet") {
        let list = required_ref(&item, "Coordinates", "IfcCartesianPointList3D")?;
        let g = leaf(point_list(list)?)?;
        out.items.push(g);
        Ok(())
    } else if item.is_a("IfcBoundingBox") {
        let corner = point3(required_ref(&item, "Corner", "IfcCartesianPoint")?)?;
        let d = DVec3::new(
            item.get_f64("XDim").ok_or_else(|| missing(&item, "XDim"))?,
            item.get_f64("YDim").ok_or_else(|| missing(&item, "YDim"))?,
            item.get_f64("ZDim").ok_or_else(|| missing(&item, "ZDim"))?,
        );
        let corners = (0..8)
            .map(|i| {
                corner
                    + d * DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64)
            })
            .collect();
        let g = leaf(corners)?;
        out.items.push(g);
        Ok(())
    } else {
        Err(unsupported(&item, "representation item"))
    }
}

/// An item swept along a curve (or an open surface) as the world vertices of its mesh.
fn mesh_vertices(
    item: Entity<'_>,
    t: DAffine3,
    units: &Units,
    depth: usize,
    out: &mut RepresentationGeometry,
) -> Result<(), GeomError> {
    let parts = ItemMesher::new(*units).item(item, depth)?;
    let points: Vec<DVec3> = parts
        .iter()
        .flat_map(|p| p.mesh.positions.iter())
        .map(|p| t.transform_point3(*p))
        .collect();
    if points.is_empty() {
        return Err(degenerate(&item, "no vertices"));
    }
    out.items.push(ItemGeometry {
        id: item.id(),
        outline: None,
        points,
    });
    Ok(())
}

/// An `IfcExtrudedAreaSolid` in world coordinates, with its exact outline (the projected
/// profile) when it is extruded vertically; true when its profile is concave (then the
/// convex hull of a non-vertical extrusion is larger than its real footprint).
fn extrusion(
    item: Entity<'_>,
    t: DAffine3,
    units: &Units,
) -> Result<(ItemGeometry, bool), GeomError> {
    let profile = required_ref(&item, "SweptArea", "IfcProfileDef")?;
    let outline = profile::outline(profile, units)?;
    let (position, sweep) = crate::extrusion::extrusion_frame(item, units)?;
    let m = t * position;
    let base: Vec<DVec3> = outline
        .iter()
        .map(|p| m.transform_point3(p.extend(0.0)))
        .collect();
    let top: Vec<DVec3> = outline
        .iter()
        .map(|p| m.transform_point3(p.extend(0.0) + sweep))
        .collect();
    let world_sweep = m.transform_vector3(sweep);
    let vertical = world_sweep.normalize_or_zero().z.abs() >= VERTICAL;
    let projected = vertical
        .then(|| polygon::clean(base.iter().map(|p| p.truncate()).collect()))
        .flatten();
    let area = polygon::signed_area(&outline);
    let hull_area = polygon::signed_area(&polygon::convex_hull(&outline));
    let concave = hull_area - area > 1e-9 * hull_area;
    let mut points = base;
    points.extend(top);
    Ok((
        ItemGeometry {
            id: item.id(),
            outline: projected,
            points,
        },
        concave,
    ))
}

/// The faces (`CfsFaces`) of an `IfcConnectedFaceSet` (open or closed shell).
fn shell_faces(shell: Entity<'_>) -> Result<Vec<Entity<'_>>, GeomError> {
    if !shell.is_a("IfcConnectedFaceSet") {
        return Err(unsupported(
            &shell,
            "shell (expected an IfcConnectedFaceSet)",
        ));
    }
    let faces = shell.get_refs("CfsFaces");
    if faces.is_empty() {
        return Err(missing(&shell, "CfsFaces"));
    }
    Ok(faces)
}

/// The distinct vertices of faces bounded by `IfcPolyLoop`s, in file units.
fn face_points(faces: &[Entity<'_>]) -> Result<Vec<DVec3>, GeomError> {
    let mut seen: HashSet<EntityId> = HashSet::new();
    let mut points = Vec::new();
    for face in faces {
        for bound in face.get_refs("Bounds") {
            let lp = bound
                .get_ref("Bound")
                .ok_or_else(|| missing(&bound, "Bound"))?;
            if !lp.is_a("IfcPolyLoop") {
                return Err(unsupported(&lp, "face loop (only IfcPolyLoop)"));
            }
            let ids = lp
                .get("Polygon")
                .map(|v: Value<'_>| v.refs())
                .unwrap_or_default();
            if ids.is_empty() {
                return Err(missing(&lp, "Polygon"));
            }
            for id in ids {
                if seen.insert(id) {
                    let p = lp
                        .model()
                        .entity(id)
                        .ok_or_else(|| missing(&lp, "Polygon"))?;
                    points.push(point3(p)?);
                }
            }
        }
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;
    use poinav_ifc::Model;

    fn model(data: &str) -> Model {
        crate::test_model::ifc4(data)
    }

    #[test]
    fn mapped_face_set_is_moved_scaled_and_clipping_is_reported() {
        // A unit tetrahedron-ish face set mapped with origin (1,0,0), target scale 2 and
        // translation (10,0,0): x' = 10 + 2 (x + 1).
        let m = model(
            "#1=IFCCARTESIANPOINTLIST3D(((0.,0.,0.),(1.,0.,0.),(0.,1.,0.),(0.,0.,1.)),$);\
             #2=IFCTRIANGULATEDFACESET(#1,$,$,((1,2,3),(1,2,4),(1,3,4),(2,3,4)),$);\
             #3=IFCSHAPEREPRESENTATION($,'Body','Tessellation',(#2));\
             #4=IFCCARTESIANPOINT((1.,0.,0.));#5=IFCAXIS2PLACEMENT3D(#4,$,$);\
             #6=IFCREPRESENTATIONMAP(#5,#3);#7=IFCCARTESIANPOINT((10.,0.,0.));\
             #8=IFCCARTESIANTRANSFORMATIONOPERATOR3D($,$,#7,2.,$);#9=IFCMAPPEDITEM(#6,#8);\
             #10=IFCPLANE(#5);#11=IFCHALFSPACESOLID(#10,.F.);\
             #12=IFCBOOLEANCLIPPINGRESULT(.DIFFERENCE.,#9,#11);\
             #13=IFCSHAPEREPRESENTATION($,'Body','Clipping',(#12));",
        );
        let rep = m.entity(EntityId(13)).unwrap();
        let g = evaluate(rep, DAffine3::IDENTITY, &Units::SI).unwrap();
        assert_eq!(g.items.len(), 1);
        let xs: Vec<f64> = g.items[0].points.iter().map(|p| p.x).collect();
        assert_eq!(xs, vec![12.0, 14.0, 12.0, 12.0]);
        assert_eq!(g.items[0].points[3].z, 2.0);
        assert_eq!(
            g.approximations,
            vec![Approximation::BooleanOperandIgnored { id: EntityId(12) }]
        );
    }
}
