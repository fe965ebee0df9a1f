//! `GeomError`: why the geometry of one instance could not be read; always names its `#id`.

use poinav_ifc::EntityId;

/// Why a placement, profile, curve or representation could not be turned into geometry.
///
/// Every variant carries the `#id` of the instance at fault, so a damaged part of a model is
/// reported for that part only; the rest of the model is still read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GeomError {
    /// A required attribute is `$`, missing, unreadable or a dangling reference.
    #[error("{id}: {class} has no usable `{attribute}`")]
    Missing {
        /// The instance whose attribute is missing.
        id: EntityId,
        /// Its class.
        class: String,
        /// The attribute (schema spelling).
        attribute: &'static str,
    },
    /// An attribute refers to an instance of a class that cannot stand there.
    #[error("{id}: `{attribute}` refers to {found_id}={found}, expected {expected}")]
    WrongType {
        /// The referring instance.
        id: EntityId,
        /// The attribute (schema spelling).
        attribute: &'static str,
        /// The instance referred to.
        found_id: EntityId,
        /// Its class.
        found: String,
        /// What the attribute should hold.
        expected: &'static str,
    },
    /// A kind of geometry this crate does not (yet) evaluate.
    #[error("{id}: {class} is not supported ({what})")]
    Unsupported {
        /// The instance.
        id: EntityId,
        /// Its class.
        class: String,
        /// What it was needed for.
        what: &'static str,
    },
    /// An `IfcGridPlacement` (placement on a design grid), which is not evaluated; callers
    /// that need a transform anyway may use the identity.
    #[error("{id}: IfcGridPlacement is not supported; the identity would be an approximation")]
    GridPlacement {
        /// The grid placement.
        id: EntityId,
    },
    /// A placement chain that loops back on itself or is deeper than [`crate::placement::MAX_DEPTH`].
    #[error("{id}: placement chain is cyclic or deeper than {depth} levels")]
    PlacementChain {
        /// The placement where the walk gave up.
        id: EntityId,
        /// The depth limit.
        depth: usize,
    },
    /// Numbers that do not make geometry: a zero direction, a polygon with no area, NaN.
    #[error("{id}: degenerate geometry: {reason}")]
    Degenerate {
        /// The instance.
        id: EntityId,
        /// What is wrong.
        reason: &'static str,
    },
    /// Geometry that was read but left nothing to show: every part was cut away by openings
    /// or clipping, or the body holds only curves and points.
    #[error("{id}: {class} has no surface left: {reason}")]
    Empty {
        /// The product (or item) instance.
        id: EntityId,
        /// Its class.
        class: String,
        /// Why nothing is left.
        reason: &'static str,
    },
    /// Meshing the product took longer than its time limit (pathological geometry: thousands
    /// of openings or boolean operands); it is left out instead of holding up the model.
    #[error(
        "{id}: {class} took longer than {seconds} s to mesh (pathological geometry); left out"
    )]
    TimeLimit {
        /// The product.
        id: EntityId,
        /// Its class.
        class: String,
        /// The limit, seconds.
        seconds: f64,
    },
    /// Sectioning the product's mesh for a floor plan reached a bound
    /// ([`crate::section::SectionBounds`]); its conservative outline is drawn instead, as
    /// unknown space.
    #[error("{id}: {class}'s section {limit}; its convex hull is drawn as unknown space")]
    SectionLimit {
        /// The product.
        id: EntityId,
        /// Its class.
        class: String,
        /// The bound reached.
        limit: crate::section::SectionLimit,
    },
    /// An opening of an element, or the second operand of a boolean result, that could not be
    /// read or applied: the element is meshed without it (its uncut body, or the first
    /// operand as it is), as IfcOpenShell does. A warning, not a failure.
    #[error("{id}: {class} is meshed without {operand} ({operand_class}): {cause}")]
    LeftUncut {
        /// The element, or the boolean result.
        id: EntityId,
        /// Its class.
        class: String,
        /// The opening element or the operand left out.
        operand: EntityId,
        /// Its class.
        operand_class: String,
        /// Why it could not be applied.
        #[source]
        cause: Box<GeomError>,
    },
    /// A product without a representation from which a footprint can be made.
    #[error("{id}: {class} has no shape representation with geometry")]
    NoGeometry {
        /// The product (or representation) instance.
        id: EntityId,
        /// Its class.
        class: String,
    },
}

impl GeomError {
    /// The `#id` of the instance the error is about.
    pub fn id(&self) -> EntityId {
        match self {
            GeomError::Missing { id, .. }
            | GeomError::WrongType { id, .. }
            | GeomError::Unsupported { id, .. }
            | GeomError::GridPlacement { id }
            | GeomError::PlacementChain { id, .. }
            | GeomError::Degenerate { id, .. }
            | GeomError::Empty { id, .. }
            | GeomError::TimeLimit { id, .. }
            | GeomError::SectionLimit { id, .. }
            | GeomError::LeftUncut { id, .. }
            | GeomError::NoGeometry { id, .. } => *id,
        }
    }
}

/// Shorthand for [`GeomError::Missing`] on entity `e`.
pub(crate) fn missing(e: &poinav_ifc::Entity<'_>, attribute: &'static str) -> GeomError {
    GeomError::Missing {
        id: e.id(),
        class: e.type_name().to_string(),
        attribute,
    }
}

/// [`GeomError::LeftUncut`]: `e` is meshed without `operand`, which failed with `cause`.
pub(crate) fn left_uncut(
    e: &poinav_ifc::Entity<'_>,
    operand: &poinav_ifc::Entity<'_>,
    cause: GeomError,
) -> GeomError {
    GeomError::LeftUncut {
        id: e.id(),
        class: e.type_name().to_string(),
        operand: operand.id(),
        operand_class: operand.type_name().to_string(),
        cause: Box::new(cause),
    }
}

/// Shorthand for [`GeomError::Unsupported`] on entity `e`.
pub(crate) fn unsupported(e: &poinav_ifc::Entity<'_>, what: &'static str) -> GeomError {
    GeomError::Unsupported {
        id: e.id(),
        class: e.type_name().to_string(),
        what,
    }
}

/// Shorthand for [`GeomError::Degenerate`] on entity `e`.
pub(crate) fn degenerate(e: &poinav_ifc::Entity<'_>, reason: &'static str) -> GeomError {
    GeomError::Degenerate { id: e.id(), reason }
}

/// The instance `e.attribute` refers to, which must be of class `expected` (or a subtype).
pub(crate) fn required_ref<'m>(
    e: &poinav_ifc::Entity<'m>,
    attribute: &'static str,
    expected: &'static str,
) -> Result<poinav_ifc::Entity<'m>, GeomError> {
    let target = e.get_ref(attribute).ok_or_else(|| missing(e, attribute))?;
    if target.is_a(expected) {
        Ok(target)
    } else {
        Err(GeomError::WrongType {
            id: e.id(),
            attribute,
            found_id: target.id(),
            found: target.type_name().to_string(),
            expected,
        })
    }
}
