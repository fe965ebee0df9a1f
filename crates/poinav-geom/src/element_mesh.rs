//! Meshes of a model's products in world coordinates: every element with a body
//! representation, openings (`IfcRelVoidsElement`) subtracted from their hosts, and every
//! space; in parallel, in file order, failures reported per product.
//!
//! Openings themselves (`IfcFeatureElementSubtraction`) are not meshed as elements. An
//! element's openings are its own and those of the elements it is a part of
//! (`IfcRelAggregates`), as IfcOpenShell applies them.

use std::time::{Duration, Instant};

use glam::DAffine3;
use poinav_ifc::{spatial, Entity, EntityId, Model};
use rayon::prelude::*;

use crate::error::{degenerate, left_uncut, GeomError};
use crate::mesh::{ElementMesh, Mesh};
use crate::placement::PlacementCache;
use crate::representation_mesh::{past, subtract, Cut, ItemMesher, Part};
use crate::surface_style::material_colour;

/// Deepest aggregation whose openings are applied to its parts.
const MAX_AGGREGATE_DEPTH: usize = 8;

/// Most openings applied to one element.
pub const MAX_OPENINGS: usize = 10_000;

/// Longest time one product may take to mesh before it is left out with
/// [`GeomError::TimeLimit`]; no element of the corpus takes more than a few milliseconds.
pub const PRODUCT_TIME_LIMIT: Duration = Duration::from_secs(20);

/// The meshes of a model.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ModelMeshes {
    /// Every element (`IfcElement` but openings) with a body, in file order.
    pub elements: Vec<ElementMesh>,
    /// Every `IfcSpace` with a body, in file order.
    pub spaces: Vec<ElementMesh>,
    /// Products whose geometry could not be made, in file order, with why.
    pub failures: Vec<(EntityId, GeomError)>,
    /// Elements and spaces meshed without an opening or a boolean operand that could not be
    /// read or applied (their body kept uncut, as IfcOpenShell does), in file order, each
    /// with a [`GeomError::LeftUncut`] naming what was left out and why.
    pub uncut: Vec<(EntityId, GeomError)>,
    /// Elements with no `Representation` at all and no parts that could carry one (see
    /// [`without_representation`]): nothing to mesh, but a reader of the export should know.
    pub without_geometry: Vec<EntityId>,
}

/// Elements (not openings) with no `Representation` and not decomposed into parts, in file
/// order: a door or wall like this is invisible in any 3D export and absent from floor plans.
/// (An element assembly or a curtain wall without its own shape is drawn by its parts and is
/// not listed.)
pub fn without_representation(model: &Model) -> Vec<Entity<'_>> {
    let mut out: Vec<Entity<'_>> = model
        .instances_of("IfcElement")
        .into_iter()
        .filter(|p| !p.is_a("IfcFeatureElementSubtraction"))
        .filter(|p| p.get("Representation").is_none())
        .filter(|p| {
            p.inverse("IsDecomposedBy")
                .iter()
                .all(|r| r.get_refs("RelatedObjects").is_empty())
        })
        .collect();
    out.sort_by_key(|p| p.position());
    out
}

/// The products [`mesh_model`] meshes: elements other than openings, and spaces, that have a
/// representation; in file order.
pub fn meshed_products(model: &Model) -> Vec<Entity<'_>> {
    let mut products: Vec<Entity<'_>> = model
        .instances_of("IfcElement")
        .into_iter()
        .chain(model.instances_of("IfcSpace"))
        .filter(|p| !p.is_a("IfcFeatureElementSubtraction"))
        .filter(|p| p.get("Representation").is_some())
        .collect();
    products.sort_by_key(|p| p.position());
    products
}

/// Meshes every element and space of `model` (see [`meshed_products`]) in parallel on the
/// current rayon pool. The result is the same whatever the number of threads. A product that
/// takes longer than [`PRODUCT_TIME_LIMIT`] is a failure ([`GeomError::TimeLimit`]).
pub fn mesh_model(model: &Model) -> ModelMeshes {
    mesh_model_within(model, PRODUCT_TIME_LIMIT)
}

/// [`mesh_model`] with another time limit per product. Only pathological products reach a
/// limit, and only those depend on the machine's speed.
pub fn mesh_model_within(model: &Model, limit: Duration) -> ModelMeshes {
    mesh_model_with_progress(model, limit, &crate::progress::none)
}

/// [`mesh_model_within`], reporting each product meshed to `progress`.
pub fn mesh_model_with_progress(
    model: &Model,
    limit: Duration,
    progress: crate::progress::Progress<'_>,
) -> ModelMeshes {
    let products = meshed_products(model);
    let ticker = crate::progress::Ticker::new(products.len(), progress);
    let results: Vec<(Entity<'_>, Result<Meshed, GeomError>)> = products
        .par_iter()
        .with_min_len(4)
        .map_init(
            || PlacementCache::new(model),
            |cache, &p| {
                let r = mesh_product_noting(cache, p, limit);
                ticker.tick();
                (p, r)
            },
        )
        .collect();
    let mut out = ModelMeshes {
        without_geometry: without_representation(model)
            .iter()
            .map(Entity::id)
            .collect(),
        ..ModelMeshes::default()
    };
    for (p, r) in results {
        match r {
            Ok((m, warnings)) => {
                out.uncut.extend(warnings.into_iter().map(|w| (p.id(), w)));
                if p.is_a("IfcSpace") {
                    out.spaces.push(m);
                } else {
                    out.elements.push(m);
                }
            }
            Err(e) => out.failures.push((p.id(), e)),
        }
    }
    out
}

/// A product's mesh, and the openings and boolean operands it is meshed without
/// ([`GeomError::LeftUncut`]).
pub type Meshed = (ElementMesh, Vec<GeomError>);

/// The mesh of one product in world coordinates (metres), its openings subtracted, with its
/// colour and storey. Errors name the `#id` at fault: no body representation, an unreadable
/// placement, an item or opening that cannot be meshed, or a mesh with no triangles.
pub fn mesh_product<'m>(
    cache: &mut PlacementCache<'m>,
    product: Entity<'m>,
) -> Result<ElementMesh, GeomError> {
    mesh_product_within(cache, product, PRODUCT_TIME_LIMIT)
}

/// [`mesh_product`] giving up with [`GeomError::TimeLimit`] (naming the product) after
/// `limit`.
pub fn mesh_product_within<'m>(
    cache: &mut PlacementCache<'m>,
    product: Entity<'m>,
    limit: Duration,
) -> Result<ElementMesh, GeomError> {
    mesh_product_noting(cache, product, limit).map(|(m, _)| m)
}

/// [`mesh_product_within`], with the openings and boolean operands the product is meshed
/// without, each a [`GeomError::LeftUncut`].
pub fn mesh_product_noting<'m>(
    cache: &mut PlacementCache<'m>,
    product: Entity<'m>,
    limit: Duration,
) -> Result<Meshed, GeomError> {
    let deadline = Instant::now().checked_add(limit);
    let timed_out = || GeomError::TimeLimit {
        id: product.id(),
        class: product.type_name().to_string(),
        seconds: limit.as_secs_f64(),
    };
    match mesh_until(cache, product, deadline) {
        Err(GeomError::TimeLimit { .. }) => Err(timed_out()),
        other => other,
    }
}

fn mesh_until<'m>(
    cache: &mut PlacementCache<'m>,
    product: Entity<'m>,
    deadline: Option<Instant>,
) -> Result<Meshed, GeomError> {
    let placement = cache.product(product)?;
    let rep = body_representation(product)?;
    let mut mesher = ItemMesher::with_deadline(cache.units(), deadline)
        .with_maps(std::mem::take(&mut cache.mapped_meshes));
    let parts = mesher.representation(rep);
    let colour = mesher.colour;
    let mut warnings = std::mem::take(&mut mesher.warnings);
    cache.mapped_meshes = mesher.into_maps();
    let mut parts = parts?;
    let had_triangles = parts.iter().any(|p| !p.mesh.is_empty());
    let openings = openings_of(product);
    let timed_out = || GeomError::TimeLimit {
        id: product.id(),
        class: String::new(),
        seconds: 0.0,
    };
    if !openings.is_empty() && parts.iter().any(|p| p.closed) {
        if openings.len() > MAX_OPENINGS {
            return Err(degenerate(
                &product,
                "more openings than one element may have",
            ));
        }
        // Openings in the host's coordinates; one that cannot be read is left out.
        let to_host = placement.inverse();
        let mut cutters: Vec<Part> = Vec::new();
        let mut cut_by: Vec<Entity<'m>> = Vec::new();
        for opening in openings {
            if past(deadline) {
                return Err(timed_out());
            }
            match opening_parts(cache, opening, to_host, deadline) {
                Ok(parts) => {
                    cut_by.extend(parts.iter().map(|_| opening));
                    cutters.extend(parts);
                }
                Err(GeomError::TimeLimit { .. }) => return Err(timed_out()),
                Err(e) => warnings.push(left_uncut(&product, &opening, e)),
            }
        }
        let cut = subtract(parts, &cutters, deadline).map_err(|Cut::TimeLimit| timed_out())?;
        let mut failed: Vec<Entity<'m>> = cut.failed.iter().map(|&i| cut_by[i]).collect();
        failed.dedup();
        for opening in failed {
            let why = degenerate(&opening, "subtracting it from its host failed");
            warnings.push(left_uncut(&product, &opening, why));
        }
        parts = cut.parts;
    }
    let mut mesh = Mesh::default();
    for p in &parts {
        mesh.append(&p.mesh);
    }
    mesh.transform(&placement);
    if mesh.is_empty() {
        return Err(GeomError::Empty {
            id: product.id(),
            class: product.type_name().to_string(),
            reason: if had_triangles {
                "its openings or clippings remove all of its body"
            } else {
                "its body holds no surfaces"
            },
        });
    }
    if !mesh.is_finite() {
        return Err(degenerate(&rep, "coordinates overflow"));
    }
    let colour = colour.or_else(|| material_colour(product));
    let element = ElementMesh {
        product: product.id(),
        global_id: product.global_id().unwrap_or_default(),
        class: product.type_name().to_string(),
        name: product.name(),
        storey: spatial::storey_of(product).map(|s| s.id()),
        mesh,
        color: colour,
    };
    Ok((element, warnings))
}

/// The parts of `opening`'s body in its host's coordinates (`to_host` from world).
fn opening_parts<'m>(
    cache: &mut PlacementCache<'m>,
    opening: Entity<'m>,
    to_host: DAffine3,
    deadline: Option<Instant>,
) -> Result<Vec<Part>, GeomError> {
    let t: DAffine3 = to_host * cache.product(opening)?;
    let rep = body_representation(opening)?;
    let mut m = ItemMesher::with_deadline(cache.units(), deadline);
    let mut parts = m.representation(rep)?;
    for part in &mut parts {
        part.mesh.transform(&t);
    }
    Ok(parts)
}

/// Representation identifiers that never hold a body.
const NOT_BODY: [&str; 8] = [
    "Axis",
    "FootPrint",
    "Profile",
    "Box",
    "Annotation",
    "Clearance",
    "Reference",
    "Lighting",
];

/// The `IfcShapeRepresentation` meshed for `product`: the one identified `Body`, else
/// `Facetation`, else the first that is not identified as something else (axis, footprint,
/// bounding box, ...).
pub fn body_representation<'m>(product: Entity<'m>) -> Result<Entity<'m>, GeomError> {
    let no_geometry = || GeomError::NoGeometry {
        id: product.id(),
        class: product.type_name().to_string(),
    };
    let shape = product.get_ref("Representation").ok_or_else(no_geometry)?;
    let reps: Vec<(Entity<'m>, Option<String>)> = shape
        .get_refs("Representations")
        .into_iter()
        .filter(|r| r.is_a("IfcShapeRepresentation"))
        .map(|r| (r, r.get_str("RepresentationIdentifier")))
        .collect();
    let named = |name: &str| reps.iter().find(|(_, id)| id.as_deref() == Some(name));
    named("Body")
        .or_else(|| named("Facetation"))
        .or_else(|| {
            reps.iter()
                .find(|(_, id)| id.as_deref().is_none_or(|i| !NOT_BODY.contains(&i)))
        })
        .map(|(r, _)| *r)
        .ok_or_else(no_geometry)
}

/// The openings cut into `product`: its own and those of the elements it is part of.
pub fn openings_of<'m>(product: Entity<'m>) -> Vec<Entity<'m>> {
    let mut out = Vec::new();
    let mut current = Some(product);
    for _ in 0..MAX_AGGREGATE_DEPTH {
        let Some(e) = current else { break };
        out.extend(
            e.inverse("HasOpenings")
                .into_iter()
                .filter_map(|rel| rel.get_ref("RelatedOpeningElement")),
        );
        current = e
            .inverse("Decomposes")
            .into_iter()
            .filter(|r| r.is_a("IfcRelAggregates"))
            .find_map(|r| r.get_ref("RelatingObject"))
            .filter(|w| w.is_a("IfcElement"));
    }
    out.sort_by_key(|o| o.position());
    out.dedup();
    out
}
