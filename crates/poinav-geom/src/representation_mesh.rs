//! The items of an `IfcShapeRepresentation` as triangle meshes in the representation's
//! coordinates (metres): extrusions (tapered too; of open profiles: surfaces), revolutions,
//! swept disks and areas swept along a directrix, sectioned solids and surfaces along
//! alignments, faceted and advanced breps, surface models, tessellated face sets, boxes and
//! CSG primitives, boolean results (clipping by half-spaces, differences, unions and
//! intersections of solids; an operand that cannot be made is left out with a warning, as
//! IfcOpenShell leaves it out) and mapped items (nested, with any
//! `IfcCartesianTransformationOperator`, mirrored or non-uniformly scaled).
//!
//! Work is bounded: at most [`MAX_ITEMS`] items and [`MAX_TRIANGLES`] triangles per
//! representation, mapped items nested at most [`MAX_DEPTH`] deep, boolean chains at most
//! [`MAX_BOOLEAN_CHAIN`] long; past that the representation is an error.

use std::collections::HashMap;
use std::sync::Arc;
use std::time::Instant;

use glam::{DAffine3, DVec2, DVec3};
use poinav_ifc::{Entity, EntityId};

use crate::advanced_brep::advanced_brep;
use crate::axis2_placement::{axis2placement, axis2placement_3d};
use crate::boolean::{boxes_overlap, clip, Solid};
use crate::brep::face_mesh;
use crate::cartesian_point::point3;
use crate::cartesian_transformation_operator::transformation;
use crate::csg_primitive::csg_primitive;
use crate::curve_bounded_plane::curve_bounded_plane;
use crate::error::{degenerate, left_uncut, missing, required_ref, unsupported, GeomError};
use crate::extrusion::{extrude, extruded_area_solid};
use crate::face_set::face_set_mesh;
use crate::gradient_curve::BasisCurve;
use crate::half_space::{half_space, HalfSpace};
use crate::mesh::Mesh;
use crate::open_profile::{extruded_open_profile, is_open_profile_extrusion};
use crate::parameterized_profile::ellipse;
use crate::profile::ProfileArea;
use crate::revolve::revolved_area_solid;
use crate::sectioned_solid::{sectioned_solid_horizontal, sectioned_surface};
use crate::surface_style::item_colour;
use crate::swept_area::{directrix_swept_area_solid, is_directrix_swept_area_solid};
use crate::swept_disk::swept_disk_solid;
use crate::tapered_extrusion::tapered_extrusion;
use crate::unit_assignment::Units;

/// Deepest nesting of mapped items, CSG trees and boolean operands followed.
pub const MAX_DEPTH: usize = 16;

/// Longest chain of boolean results (each the first operand of the next) followed.
pub const MAX_BOOLEAN_CHAIN: usize = 4096;

/// Most representation items evaluated for one representation (mapped items count once per
/// use).
pub const MAX_ITEMS: usize = 100_000;

/// Most triangles one representation may produce.
pub const MAX_TRIANGLES: usize = 4_000_000;

/// One piece of geometry: a mesh, and whether it encloses a volume (booleans apply to those).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Part {
    /// The triangles.
    pub mesh: Mesh,
    /// True for solids (extrusions, breps, closed face sets, boolean results).
    pub closed: bool,
}

impl Part {
    fn transformed(mut self, t: &DAffine3) -> Part {
        self.mesh.transform(t);
        self
    }
}

/// Evaluates representation items into [`Part`]s, within the limits, noting the first
/// surface colour met.
#[derive(Debug)]
pub struct ItemMesher {
    units: Units,
    deadline: Option<Instant>,
    items: usize,
    triangles: usize,
    /// The colour of the first styled item met outside boolean second operands.
    pub colour: Option<[f32; 4]>,
    /// Boolean operands left out ([`GeomError::LeftUncut`]): the first operand was kept.
    pub warnings: Vec<GeomError>,
    look_for_colour: bool,
    maps: MappedMeshes,
}

/// One mapped representation meshed: its parts, the colour its items give, its item count,
/// the operands its booleans left out.
type MappedMesh = (Vec<Part>, Option<[f32; 4]>, usize, Vec<GeomError>);

/// What meshing one product leaves for the next ones of the same model: mapped
/// representations already meshed (by `#id`: their parts in the map's coordinates, the
/// colour their items give and how many items they hold) and directrices read.
#[derive(Debug, Default)]
pub struct MappedMeshes {
    maps: HashMap<EntityId, MappedMesh>,
    curves: HashMap<EntityId, Arc<BasisCurve>>,
}

impl ItemMesher {
    /// A mesher converting lengths with `units`.
    pub fn new(units: Units) -> ItemMesher {
        ItemMesher::with_deadline(units, None)
    }

    /// A mesher that gives up with [`GeomError::TimeLimit`] (naming the item it was at) once
    /// `deadline` has passed; checked at every item and before every boolean operation.
    pub fn with_deadline(units: Units, deadline: Option<Instant>) -> ItemMesher {
        ItemMesher {
            units,
            deadline,
            items: 0,
            triangles: 0,
            colour: None,
            warnings: Vec::new(),
            look_for_colour: true,
            maps: MappedMeshes::default(),
        }
    }

    /// The parts of every item of `representation`. Items without surfaces (curves, points,
    /// text) are passed over; an item that cannot be meshed is an error for the whole.
    pub fn representation(&mut self, representation: Entity<'_>) -> Result<Vec<Part>, GeomError> {
        let mut out = Vec::new();
        for item in representation.get_refs("Items") {
            out.extend(self.item(item, 0)?);
        }
        Ok(out)
    }

    fn count(&mut self, e: &Entity<'_>, triangles: usize) -> Result<(), GeomError> {
        self.triangles += triangles;
        if self.triangles > MAX_TRIANGLES {
            return Err(degenerate(e, "more triangles than one product may have"));
        }
        Ok(())
    }

    fn leaf(&mut self, e: &Entity<'_>, mesh: Mesh, closed: bool) -> Result<Vec<Part>, GeomError> {
        self.count(e, mesh.triangles.len())?;
        if !mesh.is_finite() {
            return Err(degenerate(e, "coordinates overflow"));
        }
        Ok(vec![Part { mesh, closed }])
    }

    /// The parts of one item, in the coordinates of the representation holding it.
    pub fn item(&mut self, item: Entity<'_>, depth: usize) -> Result<Vec<Part>, GeomError> {
        if depth > MAX_DEPTH {
            return Err(degenerate(
                &item,
                "mapped items or booleans nested too deeply",
            ));
        }
        if past(self.deadline) {
            return Err(time_limit(&item));
        }
        self.items += 1;
        if self.items > MAX_ITEMS {
            return Err(degenerate(&item, "more items than one product may have"));
        }
        if self.look_for_colour && self.colour.is_none() {
            self.colour = item_colour(item);
        }
        let s = self.units.metres_per_unit;
        if item.is_a("IfcMappedItem") {
            let source = required_ref(&item, "MappingSource", "IfcRepresentationMap")?;
            let origin = source
                .get_ref("MappingOrigin")
                .ok_or_else(|| missing(&source, "MappingOrigin"))?;
            let origin = axis2placement(origin, s)?;
            let target =
                required_ref(&item, "MappingTarget", "IfcCartesianTransformationOperator")?;
            let t = transformation(target, s)? * origin;
            let rep = required_ref(&source, "MappedRepresentation", "IfcRepresentation")?;
            let parts = self.mapped(rep, depth)?;
            Ok(parts.into_iter().map(|p| p.transformed(&t)).collect())
        } else if item.is_a("IfcBooleanResult") {
            self.boolean(item, depth)
        } else if item.is_a("IfcCsgSolid") {
            let root = item
                .get_ref("TreeRootExpression")
                .ok_or_else(|| missing(&item, "TreeRootExpression"))?;
            self.item(root, depth + 1)
        } else if item.is_a("IfcExtrudedAreaSolid") {
            if item.is_a("IfcExtrudedAreaSolidTapered") {
                let mesh = tapered_extrusion(item, &self.units)?;
                return self.leaf(&item, mesh, true);
            }
            match extruded_area_solid(item, &self.units) {
                Ok(mesh) => self.leaf(&item, mesh, true),
                // An open profile bounds no area: extruded, it is a surface (an open part).
                Err(_) if is_open_profile_extrusion(&item) => {
                    let mesh = extruded_open_profile(item, &self.units)?;
                    self.leaf(&item, mesh, false)
                }
                Err(e) => Err(e),
            }
        } else if item.is_a("IfcRevolvedAreaSolid") {
            let mesh = revolved_area_solid(item, &self.units)?;
            self.leaf(&item, mesh, true)
        } else if item.is_a("IfcSweptDiskSolid") {
            let mesh = swept_disk_solid(item, &self.units)?;
            self.leaf(&item, mesh, true)
        } else if is_directrix_swept_area_solid(&item) {
            let mesh = directrix_swept_area_solid(item, &self.units)?;
            self.leaf(&item, mesh, true)
        } else if item.is_a("IfcAdvancedBrep") {
            let mesh = advanced_brep(item, &self.units)?;
            self.leaf(&item, mesh, true)
        } else if item.is_a("IfcSectionedSolidHorizontal") || item.is_a("IfcSectionedSurface") {
            let directrix = required_ref(&item, "Directrix", "IfcCurve")?;
            let curve = match self.maps.curves.get(&directrix.id()) {
                Some(c) => c.clone(),
                None => Arc::new(BasisCurve::read(directrix, &self.units)?),
            };
            self.maps.curves.insert(directrix.id(), curve.clone());
            if item.is_a("IfcSectionedSurface") {
                let mesh = sectioned_surface(item, &self.units, &curve)?;
                return self.leaf(&item, mesh, false);
            }
            let mesh = sectioned_solid_horizontal(item, &self.units, &curve)?;
            self.leaf(&item, mesh, true)
        } else if item.is_a("IfcManifoldSolidBrep")
            || item.is_a("IfcFaceBasedSurfaceModel")
            || item.is_a("IfcShellBasedSurfaceModel")
        {
            let (mesh, solid) = face_mesh(item, &self.units)?;
            self.leaf(&item, mesh, solid)
        } else if item.is_a("IfcTessellatedFaceSet") {
            let (mesh, closed) = face_set_mesh(item, s)?;
            self.leaf(&item, mesh, closed)
        } else if item.is_a("IfcBoundingBox") {
            let corner = point3(required_ref(&item, "Corner", "IfcCartesianPoint")?)? * s;
            let size = self.size(&item, ["XDim", "YDim", "ZDim"])?;
            let mesh = cuboid(corner, size);
            self.leaf(&item, mesh, true)
        } else if item.is_a("IfcBlock") {
            let size = self.size(&item, ["XLength", "YLength", "ZLength"])?;
            let mut mesh = cuboid(DVec3::ZERO, size);
            mesh.transform(&self.position(&item)?);
            self.leaf(&item, mesh, true)
        } else if item.is_a("IfcRightCircularCylinder") {
            let [h, r] = self.lengths(&item, ["Height", "Radius"])?;
            let area = ProfileArea {
                outer: ellipse(r, r),
                holes: Vec::new(),
            };
            let mut mesh = extrude(&[area], DVec3::Z * h)
                .ok_or_else(|| degenerate(&item, "cylinder cannot be meshed"))?;
            mesh.transform(&self.position(&item)?);
            self.leaf(&item, mesh, true)
        } else if item.is_a("IfcSphere")
            || item.is_a("IfcRightCircularCone")
            || item.is_a("IfcRectangularPyramid")
        {
            let mut mesh = csg_primitive(item, s)?;
            mesh.transform(&self.position(&item)?);
            self.leaf(&item, mesh, true)
        } else if item.is_a("IfcCurveBoundedPlane") {
            let mesh = curve_bounded_plane(item, &self.units)?;
            self.leaf(&item, mesh, false)
        } else if item.is_a("IfcCurve")
            || item.is_a("IfcPoint")
            || item.is_a("IfcGeometricSet")
            || item.is_a("IfcAnnotationFillArea")
            || item.is_a("IfcTextLiteral")
            || item.is_a("IfcPlacement")
            || item.is_a("IfcVector")
            || item.is_a("IfcDirection")
            || item.is_a("IfcCartesianPointList")
        {
            Ok(Vec::new())
        } else {
            Err(unsupported(&item, "representation item"))
        }
    }

    /// The parts of a mapped representation in its own coordinates, meshed once per
    /// [`MappedMeshes`] (a model's thousand sleepers share one map); the colour its items give
    /// is remembered with them, and so are the operands left out (warned about again at
    /// every use).
    fn mapped(&mut self, rep: Entity<'_>, depth: usize) -> Result<Vec<Part>, GeomError> {
        if let Some((parts, colour, items, warnings)) = self.maps.maps.get(&rep.id()) {
            let (parts, colour) = (parts.clone(), *colour);
            self.warnings.extend(warnings.iter().cloned());
            // The items count as if evaluated again, so the bounds hold as without the cache.
            self.items += items;
            if self.items > MAX_ITEMS {
                return Err(degenerate(&rep, "more items than one product may have"));
            }
            self.count(&rep, parts.iter().map(|p| p.mesh.triangles.len()).sum())?;
            if self.look_for_colour && self.colour.is_none() {
                self.colour = colour;
            }
            return Ok(parts);
        }
        let saved = (
            self.colour.take(),
            std::mem::replace(&mut self.look_for_colour, true),
        );
        let items_before = self.items;
        let warnings_before = self.warnings.len();
        let mut result = Ok(Vec::new());
        for sub in rep.get_refs("Items") {
            match (self.item(sub, depth + 1), &mut result) {
                (Ok(p), Ok(out)) => out.extend(p),
                (Err(e), _) => {
                    result = Err(e);
                    break;
                }
                _ => {}
            }
        }
        let found = std::mem::replace(&mut self.colour, saved.0);
        self.look_for_colour = saved.1;
        let parts = result?;
        if self.look_for_colour && self.colour.is_none() {
            self.colour = found;
        }
        let items = self.items - items_before;
        let warnings = self.warnings[warnings_before..].to_vec();
        self.maps
            .maps
            .insert(rep.id(), (parts.clone(), found, items, warnings));
        Ok(parts)
    }

    /// Takes over `maps` (mapped representations meshed for earlier products of the model).
    pub fn with_maps(mut self, maps: MappedMeshes) -> ItemMesher {
        self.maps = maps;
        self
    }

    /// The mapped representations meshed so far, for the next product's mesher.
    pub fn into_maps(self) -> MappedMeshes {
        self.maps
    }

    fn lengths<const N: usize>(
        &self,
        e: &Entity<'_>,
        names: [&'static str; N],
    ) -> Result<[f64; N], GeomError> {
        let mut out = [0.0; N];
        for (o, name) in out.iter_mut().zip(names) {
            let v = e.get_f64(name).ok_or_else(|| missing(e, name))?;
            if !(v.is_finite() && v > 0.0) {
                return Err(degenerate(e, "dimension is not a positive number"));
            }
            *o = v * self.units.metres_per_unit;
        }
        Ok(out)
    }

    fn size(&self, e: &Entity<'_>, names: [&'static str; 3]) -> Result<DVec3, GeomError> {
        Ok(DVec3::from_array(self.lengths(e, names)?))
    }

    /// The `Position` of a CSG primitive (the identity when `$`).
    fn position(&self, e: &Entity<'_>) -> Result<DAffine3, GeomError> {
        match e.get("Position") {
            None => Ok(DAffine3::IDENTITY),
            Some(_) => axis2placement_3d(
                e.get_ref("Position")
                    .ok_or_else(|| missing(e, "Position"))?,
                self.units.metres_per_unit,
            ),
        }
    }

    /// An operand's parts without looking for colours (cutters do not colour the result).
    fn operand(&mut self, e: Entity<'_>, depth: usize) -> Result<Vec<Part>, GeomError> {
        let look = std::mem::replace(&mut self.look_for_colour, false);
        let r = self.item(e, depth);
        self.look_for_colour = look;
        r
    }

    /// A boolean result; chains `((A op B) op C) ...` are followed in a loop.
    fn boolean(&mut self, item: Entity<'_>, depth: usize) -> Result<Vec<Part>, GeomError> {
        let mut chain = Vec::new();
        let mut current = item;
        while current.is_a("IfcBooleanResult") {
            if chain.len() >= MAX_BOOLEAN_CHAIN {
                return Err(degenerate(&item, "boolean results nested too deeply"));
            }
            chain.push(current);
            current = current
                .get_ref("FirstOperand")
                .ok_or_else(|| missing(&current, "FirstOperand"))?;
        }
        let innermost = *chain.last().expect("item is a boolean result");
        let (mut parts, done) = if current.is_a("IfcHalfSpaceSolid") {
            self.without_first(&chain, Some(current), depth)?
        } else {
            match self.item(current, depth + 1) {
                Ok(parts) if !parts.is_empty() => (parts, chain.len()),
                first => {
                    let cause = match first {
                        Ok(_) => GeomError::Empty {
                            id: current.id(),
                            class: current.type_name().to_string(),
                            reason: "a first operand with no solid",
                        },
                        Err(e) => e,
                    };
                    // Kept only to be checked: the first operand is left out either way.
                    self.left_out(&innermost, &current, cause, Vec::new())?;
                    self.without_first(&chain, None, depth)?
                }
            }
        };
        for b in chain[..done].iter().copied().rev() {
            let second = b
                .get_ref("SecondOperand")
                .ok_or_else(|| missing(&b, "SecondOperand"))?;
            parts = self.apply(b, second, parts, depth)?;
            let n = parts.iter().map(|p| p.mesh.triangles.len()).sum();
            self.count(&b, n)?;
        }
        Ok(parts)
    }

    /// IfcOpenShell 0.9's result when the first operand of the innermost boolean of `chain`
    /// (outermost first) could not be made or holds no solid, or is the half-space `lead`:
    /// that operand is left out and the operands that follow it in IfcOpenShell's list take
    /// its place. A run of differences ending at the innermost result is one list (the
    /// first operand, then the second operands from the outside in: see
    /// [`flattened_from`]); its first operand that can be made is cut by the others. A union
    /// or intersection leaves its second operand alone. When the list begins with a
    /// half-space, what the solids after it have in the half-space's material is kept (a
    /// second half-space leaves nothing). When nothing of the list can be made, the result
    /// fails as a whole, as the first operand of the next result out. Returns the parts and
    /// how many results of `chain` (from the outside) remain to be applied.
    fn without_first(
        &mut self,
        chain: &[Entity<'_>],
        lead: Option<Entity<'_>>,
        depth: usize,
    ) -> Result<(Vec<Part>, usize), GeomError> {
        let mut n = chain.len();
        let mut lead = lead.map(|hs| (chain[n - 1], hs));
        while n > 0 {
            let k = flattened_from(&chain[..n]);
            let mut list: Vec<(Entity<'_>, Entity<'_>)> = lead.take().into_iter().collect();
            for &b in &chain[k..n] {
                let second = b
                    .get_ref("SecondOperand")
                    .ok_or_else(|| missing(&b, "SecondOperand"))?;
                list.push((b, second));
            }
            if let Some(parts) = self.remaining(list, depth)? {
                return Ok((parts, k));
            }
            n = k;
        }
        Ok((Vec::new(), 0))
    }

    /// The parts of one of IfcOpenShell's operand lists without its first operand (see
    /// [`ItemMesher::without_first`]): each operand with the boolean result it belongs to.
    /// `None` when no operand can be made.
    fn remaining(
        &mut self,
        list: Vec<(Entity<'_>, Entity<'_>)>,
        depth: usize,
    ) -> Result<Option<Vec<Part>>, GeomError> {
        let mut base: Option<Vec<Part>> = None;
        let mut lead: Option<HalfSpace> = None;
        let mut kept = Vec::new();
        for (b, operand) in list {
            if let Some(parts) = base.take() {
                base = Some(self.apply(b, operand, parts, depth)?);
                continue;
            }
            if operand.is_a("IfcHalfSpaceSolid") {
                match half_space(operand, &self.units) {
                    // A second half-space after the first leaves nothing, as in IfcOpenShell.
                    Ok(_) if lead.is_some() => return Ok(Some(Vec::new())),
                    Ok(hs) => lead = Some(hs),
                    Err(e) => {
                        self.left_out(&b, &operand, e, Vec::new())?;
                    }
                }
                continue;
            }
            match self.operand(operand, depth + 1) {
                Ok(parts) if !parts.is_empty() => match lead {
                    Some(_) => kept.extend(parts),
                    None => base = Some(parts),
                },
                Ok(_) => {
                    let why = GeomError::Empty {
                        id: operand.id(),
                        class: operand.type_name().to_string(),
                        reason: "a first operand with no solid",
                    };
                    self.left_out(&b, &operand, why, Vec::new())?;
                }
                Err(e) => {
                    self.left_out(&b, &operand, e, Vec::new())?;
                }
            }
        }
        let Some(mut hs) = lead else {
            return Ok(base);
        };
        if hs.prism.is_some() {
            return Ok(Some(Vec::new()));
        }
        // Kept: the material side of the half-space.
        hs.outward = -hs.outward;
        let mut out = Vec::with_capacity(kept.len());
        for p in kept {
            let mesh = clip(&p.mesh, &hs).unwrap_or(p.mesh);
            out.push(Part {
                mesh,
                closed: p.closed,
            });
        }
        Ok(Some(out))
    }

    /// The boolean result `b` of `parts` (its first operand) and `second`. What cannot be
    /// read or applied of `second` is left out with a [`GeomError::LeftUncut`] warning (as
    /// IfcOpenShell keeps the first operand); only the time limit and the bounds on items and
    /// triangles are errors.
    fn apply(
        &mut self,
        b: Entity<'_>,
        second: Entity<'_>,
        parts: Vec<Part>,
        depth: usize,
    ) -> Result<Vec<Part>, GeomError> {
        let op = b.get("Operator").and_then(|v| v.as_enum()).unwrap_or("");
        if second.is_a("IfcHalfSpaceSolid") {
            let hs = half_space(second, &self.units).and_then(|mut hs| match op {
                "DIFFERENCE" => Ok(hs),
                "INTERSECTION" if hs.prism.is_none() => {
                    hs.outward = -hs.outward;
                    Ok(hs)
                }
                _ => Err(unsupported(&b, "this operation with a half-space")),
            });
            let hs = match hs {
                Ok(hs) => hs,
                Err(e) => return self.left_out(&b, &second, e, parts),
            };
            let (mut out, mut failed) = (Vec::with_capacity(parts.len()), false);
            for p in parts {
                match clip(&p.mesh, &hs) {
                    Some(mesh) => {
                        self.count(&b, mesh.triangles.len())?;
                        out.push(Part {
                            mesh,
                            closed: p.closed,
                        });
                    }
                    None => {
                        failed = true;
                        out.push(p);
                    }
                }
            }
            if failed {
                let why = degenerate(&b, "clipping by a half-space failed");
                self.warnings.push(left_uncut(&b, &second, why));
            }
            return Ok(out);
        }
        let others = match self.operand(second, depth + 1) {
            Ok(others) => others,
            Err(e) => return self.left_out(&b, &second, e, parts),
        };
        match op {
            "DIFFERENCE" => {
                let cut = subtract(parts, &others, self.deadline)
                    .map_err(|Cut::TimeLimit| time_limit(&b))?;
                if !cut.failed.is_empty() {
                    let why = degenerate(&b, "boolean difference failed");
                    self.warnings.push(left_uncut(&b, &second, why));
                }
                Ok(cut.parts)
            }
            "UNION" => Ok(unite(parts, others)),
            "INTERSECTION" => match intersect(&parts, &others) {
                Some(common) => Ok(common),
                None => {
                    let why = degenerate(&b, "boolean intersection failed");
                    self.left_out(&b, &second, why, parts)
                }
            },
            _ => self.left_out(&b, &second, missing(&b, "Operator"), parts),
        }
    }

    /// `parts` as they are, with a warning that `b` is meshed without `second` because of
    /// `e`; or `e` itself when it is the time limit or a bound on the whole was reached.
    fn left_out(
        &mut self,
        b: &Entity<'_>,
        second: &Entity<'_>,
        e: GeomError,
        parts: Vec<Part>,
    ) -> Result<Vec<Part>, GeomError> {
        if matches!(e, GeomError::TimeLimit { .. })
            || self.items > MAX_ITEMS
            || self.triangles > MAX_TRIANGLES
        {
            return Err(e);
        }
        self.warnings.push(left_uncut(b, second, e));
        Ok(parts)
    }
}

/// Where IfcOpenShell 0.9 begins the operand list of the innermost result of `chain`
/// (outermost first): the outermost result from which every result in is a difference, with
/// at most 8 half-spaces among the second operands below it (more are not read as one
/// list); a union or intersection innermost is a list of its own.
fn flattened_from(chain: &[Entity<'_>]) -> usize {
    let n = chain.len();
    let difference =
        |b: &Entity<'_>| b.get("Operator").and_then(|v| v.as_enum()) == Some("DIFFERENCE");
    let half_space_second = |b: &Entity<'_>| {
        b.get_ref("SecondOperand")
            .is_some_and(|s| s.is_a("IfcHalfSpaceSolid"))
    };
    let mut k = n - 1;
    if !difference(&chain[k]) {
        return k;
    }
    let mut half_spaces = 0;
    while k > 0 && difference(&chain[k - 1]) {
        half_spaces += usize::from(half_space_second(&chain[k]));
        if half_spaces > 8 {
            break;
        }
        k -= 1;
    }
    k
}

/// How far cutters are grown on every side before they are subtracted, metres (10 µm).
pub const CUTTER_MARGIN: f64 = 1e-5;

/// `mesh` scaled about the centre of its box so that the box grows by `margin` on every side.
fn grow(mesh: &Mesh, margin: f64) -> Option<Mesh> {
    let (lo, hi) = mesh.bounds()?;
    let centre = (lo + hi) / 2.0;
    let half = ((hi - lo) / 2.0).max(DVec3::splat(margin));
    let scale = (half + margin) / half;
    let t = DAffine3::from_translation(centre)
        * DAffine3::from_scale(scale)
        * DAffine3::from_translation(-centre);
    let mut m = mesh.clone();
    m.transform(&t);
    Some(m)
}

/// Why [`subtract`] gave up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cut {
    /// The deadline passed.
    TimeLimit,
}

/// What [`subtract`] made.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Subtracted {
    /// The parts, cut.
    pub parts: Vec<Part>,
    /// The cutters (indices into [`subtract`]'s `cutters`, ascending) that could not be made
    /// solids or subtracted: the parts are cut by the others only.
    pub failed: Vec<usize>,
}

/// True once `deadline` (if any) has passed.
pub(crate) fn past(deadline: Option<Instant>) -> bool {
    deadline.is_some_and(|d| Instant::now() > d)
}

/// A [`GeomError::TimeLimit`] at instance `e` (the caller names the product and the limit).
fn time_limit(e: &Entity<'_>) -> GeomError {
    GeomError::TimeLimit {
        id: e.id(),
        class: e.type_name().to_string(),
        seconds: 0.0,
    }
}

/// Every closed part of `parts` less every closed part of `cutters` that can touch it; open
/// parts are kept as they are. A cutter the boolean library cannot take (not a solid, or
/// the difference fails) is passed over and listed in [`Subtracted::failed`], as
/// IfcOpenShell passes over an opening it cannot apply. Fails only when `deadline` passes
/// (checked before every difference).
///
/// Each cutter is first grown by [`CUTTER_MARGIN`] on every side (scaled about the centre of
/// its box), so that faces of a cutter lying exactly in faces of the part (an opening as deep
/// as its wall is thick, a door opening flush with the wall's foot) cut through cleanly
/// instead of leaving zero-thickness skins.
pub fn subtract(
    parts: Vec<Part>,
    cutters: &[Part],
    deadline: Option<Instant>,
) -> Result<Subtracted, Cut> {
    let cutters: Vec<(usize, Mesh, (DVec3, DVec3))> = cutters
        .iter()
        .enumerate()
        .filter(|(_, c)| c.closed)
        .filter_map(|(i, c)| {
            let grown = grow(&c.mesh, CUTTER_MARGIN)?;
            let bounds = grown.bounds()?;
            Some((i, grown, bounds))
        })
        .collect();
    let mut solids: Vec<Option<Option<Solid>>> = vec![None; cutters.len()];
    let mut failed = Vec::new();
    let mut out = Vec::with_capacity(parts.len());
    for part in parts {
        let Some(bounds) = part.mesh.bounds() else {
            continue;
        };
        let margin = 1e-9 * (bounds.1 - bounds.0).length().max(1.0);
        let touching: Vec<usize> = (0..cutters.len())
            .filter(|&i| boxes_overlap(bounds, cutters[i].2, margin))
            .collect();
        if !part.closed || touching.is_empty() {
            out.push(part);
            continue;
        }
        let Some(mut solid) = Solid::new(&part.mesh) else {
            out.push(part);
            continue;
        };
        for i in touching {
            if past(deadline) {
                return Err(Cut::TimeLimit);
            }
            let cutter = solids[i].get_or_insert_with(|| Solid::new(&cutters[i].1));
            match cutter.as_ref().and_then(|c| solid.difference(c)) {
                Some(cut) => solid = cut,
                None => failed.push(cutters[i].0),
            }
        }
        if !solid.is_empty() {
            out.push(Part {
                mesh: solid.mesh(),
                closed: true,
            });
        }
    }
    failed.sort_unstable();
    failed.dedup();
    Ok(Subtracted { parts: out, failed })
}

/// `parts` and `others` together, as a union of solids is: their closed parts fused into one
/// solid, so that where they overlap counts once (as IfcOpenShell fuses them), and their open
/// parts as they are. When the boolean library cannot take a closed part or fails, every part
/// is kept as it is, side by side (the same space taken, overlaps counted twice).
fn unite(parts: Vec<Part>, others: Vec<Part>) -> Vec<Part> {
    let all: Vec<Part> = parts.into_iter().chain(others).collect();
    if all.iter().filter(|p| p.closed).count() < 2 {
        return all;
    }
    let mut fused: Option<Solid> = None;
    for p in all.iter().filter(|p| p.closed) {
        let Some(s) = Solid::new(&p.mesh) else {
            return all;
        };
        fused = match fused {
            None => Some(s),
            Some(u) => match u.union(&s) {
                Some(u) => Some(u),
                None => return all,
            },
        };
    }
    let mut out: Vec<Part> = all.into_iter().filter(|p| !p.closed).collect();
    if let Some(fused) = fused.filter(|f| !f.is_empty()) {
        out.push(Part {
            mesh: fused.mesh(),
            closed: true,
        });
    }
    out
}

/// What the closed parts of `parts` share with the union of the closed parts of `others`.
fn intersect(parts: &[Part], others: &[Part]) -> Option<Vec<Part>> {
    let mut union: Option<Solid> = None;
    for o in others.iter().filter(|o| o.closed) {
        let s = Solid::new(&o.mesh)?;
        union = Some(match union {
            None => s,
            Some(u) => u.union(&s)?,
        });
    }
    let Some(union) = union else {
        return Some(Vec::new());
    };
    let mut out = Vec::new();
    for p in parts.iter().filter(|p| p.closed) {
        let r = Solid::new(&p.mesh)?.intersection(&union)?;
        if !r.is_empty() {
            out.push(Part {
                mesh: r.mesh(),
                closed: true,
            });
        }
    }
    Some(out)
}

/// A box from `corner` spanning `size`, triangles facing out.
fn cuboid(corner: DVec3, size: DVec3) -> Mesh {
    let area = ProfileArea {
        outer: vec![
            DVec2::ZERO,
            DVec2::new(size.x, 0.0),
            DVec2::new(size.x, size.y),
            DVec2::new(0.0, size.y),
        ],
        holes: Vec::new(),
    };
    let mut m = extrude(&[area], DVec3::Z * size.z).unwrap_or_default();
    m.transform(&DAffine3::from_translation(corner));
    m
}
