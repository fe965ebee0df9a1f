//! `IfcObjectPlacement`: the world transform of a product, resolved through `IfcLocalPlacement`
//! chains and `IfcLinearPlacement`s along alignments ([`crate::linear_placement`]), memoised per
//! placement `#id` (basis curves per curve `#id`), safe against cycles, translations in metres.

use std::collections::HashMap;
use std::sync::Arc;

use glam::DAffine3;
use poinav_ifc::{Entity, EntityId, Model};

pub use crate::axis2_placement::{axis2placement, axis2placement_2d, axis2placement_3d};
use crate::error::{missing, unsupported, GeomError};
use crate::gradient_curve::BasisCurve;
use crate::linear_placement::axis2placement_linear;
use crate::representation_mesh::MappedMeshes;
use crate::unit_assignment::Units;

/// Longest `PlacementRelTo` chain followed; longer chains (and cycles) are errors.
pub const MAX_DEPTH: usize = 64;

/// A resolved placement: the world transform (grid placements taken as the identity) and the
/// first grid placement met on the way, if any.
type Resolved = Result<(DAffine3, Option<EntityId>), GeomError>;

/// World transforms of placements and products of one model, in metres, computed once per
/// placement `#id`.
///
/// A transform maps a point in the placement's local coordinates, already converted to
/// metres, to world coordinates in metres: its rotation is as written, its translation is the
/// file's coordinates times the model's `metres_per_unit`.
#[derive(Debug)]
pub struct PlacementCache<'m> {
    model: &'m Model,
    units: Units,
    resolved: HashMap<EntityId, Resolved>,
    curves: HashMap<EntityId, Result<Arc<BasisCurve>, GeomError>>,
    /// Mapped representations meshed and directrices read for earlier products (kept here
    /// so that one cache per thread serves every product [`crate::mesh_model`] gives it).
    pub(crate) mapped_meshes: MappedMeshes,
}

impl<'m> PlacementCache<'m> {
    /// A cache for `model`, using its declared units.
    pub fn new(model: &'m Model) -> PlacementCache<'m> {
        PlacementCache::with_units(model, Units::of(model))
    }

    /// A cache for `model` that converts lengths and angles with `units`.
    pub fn with_units(model: &'m Model, units: Units) -> PlacementCache<'m> {
        PlacementCache {
            model,
            units,
            resolved: HashMap::new(),
            curves: HashMap::new(),
            mapped_meshes: MappedMeshes::default(),
        }
    }

    /// The model.
    pub fn model(&self) -> &'m Model {
        self.model
    }

    /// The units lengths and angles are converted with.
    pub fn units(&self) -> Units {
        self.units
    }

    /// Metres per file length unit.
    pub fn metres_per_unit(&self) -> f64 {
        self.units.metres_per_unit
    }

    /// The world transform of `product`'s `ObjectPlacement` (the identity when it has none,
    /// as in IfcOpenShell). An `IfcGridPlacement` anywhere in the chain is
    /// [`GeomError::GridPlacement`].
    pub fn product(&mut self, product: Entity<'m>) -> Result<DAffine3, GeomError> {
        match product.get("ObjectPlacement") {
            None => Ok(DAffine3::IDENTITY),
            Some(_) => self.placement(
                product
                    .get_ref("ObjectPlacement")
                    .ok_or_else(|| missing(&product, "ObjectPlacement"))?,
            ),
        }
    }

    /// Like [`PlacementCache::product`], but an `IfcGridPlacement` counts as the identity; the
    /// second value then says so. Other errors are still errors.
    pub fn product_or_identity(
        &mut self,
        product: Entity<'m>,
    ) -> Result<(DAffine3, Option<GeomError>), GeomError> {
        match product.get("ObjectPlacement") {
            None => Ok((DAffine3::IDENTITY, None)),
            Some(_) => {
                let p = product
                    .get_ref("ObjectPlacement")
                    .ok_or_else(|| missing(&product, "ObjectPlacement"))?;
                let (t, grid) = self.resolve(p)?;
                Ok((t, grid.map(|id| GeomError::GridPlacement { id })))
            }
        }
    }

    /// The basis curve `curve` (an alignment's `IfcGradientCurve`, ...), read once per `#id`.
    pub fn basis_curve(&mut self, curve: Entity<'m>) -> Result<Arc<BasisCurve>, GeomError> {
        let units = self.units;
        self.curves
            .entry(curve.id())
            .or_insert_with(|| BasisCurve::read(curve, &units).map(Arc::new))
            .clone()
    }

    /// The world transform of an `IfcObjectPlacement`.
    pub fn placement(&mut self, placement: Entity<'m>) -> Result<DAffine3, GeomError> {
        match self.resolve(placement)? {
            (_, Some(id)) => Err(GeomError::GridPlacement { id }),
            (t, None) => Ok(t),
        }
    }

    /// Walks up `PlacementRelTo` to a resolved or root placement, then composes downwards,
    /// remembering every level.
    fn resolve(&mut self, placement: Entity<'m>) -> Resolved {
        let mut chain: Vec<Entity<'m>> = Vec::new();
        let mut current = Some(placement);
        let mut parent: Resolved = Ok((DAffine3::IDENTITY, None));
        while let Some(p) = current {
            if let Some(r) = self.resolved.get(&p.id()) {
                parent = r.clone();
                break;
            }
            if chain.len() >= MAX_DEPTH || chain.iter().any(|c| c.id() == p.id()) {
                parent = Err(GeomError::PlacementChain {
                    id: p.id(),
                    depth: MAX_DEPTH,
                });
                break;
            }
            chain.push(p);
            current = match relative_to(p) {
                Ok(next) => next,
                Err(e) => {
                    parent = Err(e);
                    break;
                }
            };
        }
        // `chain` runs from `placement` up; compose from the top down.
        let mut result = parent;
        while let Some(p) = chain.pop() {
            result = result.and_then(|(world, grid)| {
                let (local, is_grid) = self.local(p)?;
                Ok((world * local, grid.or(is_grid.then(|| p.id()))))
            });
            self.resolved.insert(p.id(), result.clone());
        }
        result
    }

    /// The transform of one placement relative to its parent (metres), and whether it is a
    /// grid placement taken as the identity.
    fn local(&mut self, p: Entity<'m>) -> Result<(DAffine3, bool), GeomError> {
        if p.is_a("IfcLocalPlacement") {
            let rel = p
                .get_ref("RelativePlacement")
                .ok_or_else(|| missing(&p, "RelativePlacement"))?;
            Ok((axis2placement(rel, self.units.metres_per_unit)?, false))
        } else if p.is_a("IfcGridPlacement") {
            Ok((DAffine3::IDENTITY, true))
        } else if p.is_a("IfcLinearPlacement") {
            let rel = p
                .get_ref("RelativePlacement")
                .ok_or_else(|| missing(&p, "RelativePlacement"))?;
            let units = self.units;
            let t = axis2placement_linear(rel, &units, &mut |c| self.basis_curve(c))?;
            Ok((t, false))
        } else {
            Err(unsupported(&p, "object placement"))
        }
    }
}

/// The placement `p` is relative to (`PlacementRelTo`), `None` for a root.
fn relative_to<'m>(p: Entity<'m>) -> Result<Option<Entity<'m>>, GeomError> {
    if !p.is_a("IfcObjectPlacement") {
        return Err(unsupported(&p, "expected an IfcObjectPlacement"));
    }
    if p.is_a("IfcLinearPlacement") {
        // The basis curve's coordinates are the world's (as in IfcOpenShell).
        return Ok(None);
    }
    if p.is_a("IfcGridPlacement") && p.attr_index("PlacementRelTo").is_err() {
        // IFC2X3 grid placements have no PlacementRelTo.
        return Ok(None);
    }
    match p.get("PlacementRelTo") {
        None => Ok(None),
        Some(_) => p
            .get_ref("PlacementRelTo")
            .map(Some)
            .ok_or_else(|| missing(&p, "PlacementRelTo")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn model(data: &str) -> Model {
        crate::test_model::ifc4(data)
    }

    const AXES: &str = "#1=IFCCARTESIANPOINT((0.,0.,0.));#2=IFCDIRECTION((0.,0.,1.));\
        #3=IFCDIRECTION((1.,0.,0.));#4=IFCAXIS2PLACEMENT3D(#1,#2,#3);\
        #5=IFCLOCALPLACEMENT($,#4);";

    #[test]
    fn chains_compose_and_translations_are_scaled() {
        let m = model(&format!(
            "{AXES}#6=IFCCARTESIANPOINT((1000.,0.,0.));#7=IFCDIRECTION((0.,1.,0.));\
             #8=IFCAXIS2PLACEMENT3D(#6,$,#7);#9=IFCLOCALPLACEMENT(#5,#8);\
             #10=IFCCARTESIANPOINT((500.,0.));#11=IFCAXIS2PLACEMENT2D(#10,$);\
             #12=IFCLOCALPLACEMENT(#9,#11);"
        ));
        let mut cache = PlacementCache::with_units(
            &m,
            Units {
                metres_per_unit: 0.001,
                radians_per_unit: 1.0,
            },
        );
        let t = cache.placement(m.entity(EntityId(12)).unwrap()).unwrap();
        // #9 is at x = 1 m with local x along world y; #12 is 0.5 m along that.
        assert!((t.translation - DVec3::new(1.0, 0.5, 0.0)).length() < 1e-12);
        assert!((t.matrix3.x_axis - DVec3::Y).length() < 1e-12);
        assert!((t.matrix3.y_axis - -DVec3::X).length() < 1e-12);
        assert_eq!(cache.resolved.len(), 3);
    }

    #[test]
    fn non_orthogonal_axes_are_made_orthonormal() {
        let m = model(
            "#1=IFCCARTESIANPOINT((0.,0.,0.));#2=IFCDIRECTION((0.,0.,2.));\
             #3=IFCDIRECTION((1.,0.,1.));#4=IFCAXIS2PLACEMENT3D(#1,#2,#3);#5=IFCLOCALPLACEMENT($,#4);",
        );
        let t = PlacementCache::with_units(&m, Units::SI)
            .placement(m.entity(EntityId(5)).unwrap())
            .unwrap();
        assert!((t.matrix3.x_axis - DVec3::X).length() < 1e-12);
        assert!((t.matrix3.determinant() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn cycles_damage_and_grids_are_errors_not_panics() {
        let m = model(&format!(
            "{AXES}#20=IFCLOCALPLACEMENT(#21,#4);#21=IFCLOCALPLACEMENT(#20,#4);\
             #22=IFCLOCALPLACEMENT(#5,#99);#23=IFCDIRECTION((0.,0.,0.));\
             #24=IFCAXIS2PLACEMENT3D(#1,#23,$);#25=IFCLOCALPLACEMENT($,#24);\
             #26=IFCGRIDPLACEMENT($,$,$);#27=IFCLOCALPLACEMENT(#26,#4);"
        ));
        let mut cache = PlacementCache::with_units(&m, Units::SI);
        let mut get = |id| cache.placement(m.entity(EntityId(id)).unwrap());
        assert!(matches!(get(20), Err(GeomError::PlacementChain { .. })));
        assert!(matches!(
            get(22),
            Err(GeomError::Missing {
                id: EntityId(22),
                ..
            })
        ));
        assert!(matches!(
            get(25),
            Err(GeomError::Degenerate {
                id: EntityId(23),
                ..
            })
        ));
        assert_eq!(get(27), Err(GeomError::GridPlacement { id: EntityId(26) }));
        assert!(get(5).is_ok());
    }
}
