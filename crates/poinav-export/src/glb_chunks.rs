//! The GLB of a building split per storey: one self-contained GLB ([`crate::glb`]'s layout,
//! one storey node) per storey that has elements, and one ([`NO_STOREY`](crate::scene::NO_STOREY)
//! node) for the elements without a listed storey, so a viewer can draw one storey before the
//! others have arrived.

use poinav_geom::ElementMesh;
use poinav_ifc::spatial::Storey;
use poinav_poi::Classification;

use crate::glb::{to_glb_with, GlbOptions};
use crate::scene::SceneInput;

/// One storey's GLB.
#[derive(Debug, Clone, PartialEq)]
pub struct StoreyGlb {
    /// Index of the storey in the list given to [`to_glb_per_storey`]; `None` for the
    /// elements without a listed storey.
    pub storey: Option<usize>,
    /// Element nodes in it.
    pub elements: usize,
    /// The GLB bytes.
    pub glb: Vec<u8>,
}

/// One GLB per storey of `storeys` that has elements, in the list's order, then one for the
/// elements without a storey of the list (when there are any). Every element is in exactly
/// one GLB, in input order within it; copies of a mapped item share a mesh only within a GLB.
/// Reorders `elements` (stably, by storey) so each GLB's elements are one run of the slice.
pub fn to_glb_per_storey(
    storeys: &[Storey],
    elements: &mut [ElementMesh],
    poi: Option<&Classification>,
    options: GlbOptions,
) -> Vec<StoreyGlb> {
    let group = |e: &ElementMesh| -> usize {
        e.storey
            .and_then(|id| storeys.iter().position(|s| s.id == id))
            .unwrap_or(usize::MAX)
    };
    elements.sort_by_cached_key(group);
    let mut out = Vec::new();
    let mut start = 0;
    while start < elements.len() {
        let g = group(&elements[start]);
        let len = elements[start..]
            .iter()
            .position(|e| group(e) != g)
            .unwrap_or(elements.len() - start);
        let run = &elements[start..start + len];
        let storey = (g != usize::MAX).then_some(g);
        let glb = to_glb_with(
            &SceneInput {
                storeys: storey.map_or(&[][..], |g| &storeys[g..=g]),
                elements: run,
                poi,
            },
            options,
        );
        out.push(StoreyGlb {
            storey,
            elements: len,
            glb,
        });
        start += len;
    }
    out
}
