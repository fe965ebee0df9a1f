//! The property sets of every product of a class, read on the rayon pool in chunks of
//! products (for `Model.psets`): each distinct IfcPropertySet read once, and each chunk
//! handed over as soon as it is read, so the caller makes one chunk's Python objects while
//! the pool reads the next.

use std::sync::OnceLock;

use poinav_ifc::property::{property_sets, read_set_untyped, set_definitions, PropertySet};
use poinav_ifc::{Entity, EntityId};
use rayon::prelude::*;
use rustc_hash::FxHashMap;

/// The products of one class in chunks: which sets each has (found before any is read, by
/// `read_all`), and each chunk's sets once they are read.
#[derive(Debug)]
pub struct Chunks<'m> {
    /// Every instance of the class (subtypes included), in the model's order.
    all: Vec<Entity<'m>>,
    /// Where each chunk ends in `all`.
    ends: Vec<usize>,
    /// Per chunk: its products with a GlobalId, in the model's order (set by `find`).
    products: OnceLock<Vec<Vec<Product>>>,
    /// Per chunk: the entities of `products`, and the sets first seen in it (set by `find`).
    plan: OnceLock<Vec<(Vec<Entity<'m>>, Vec<Entity<'m>>)>>,
    /// Per chunk: its sets, set when read.
    read: Vec<OnceLock<Chunk>>,
}

/// One product with a GlobalId.
#[derive(Debug)]
pub struct Product {
    /// Its GlobalId.
    global_id: String,
    /// Its sets in `property_sets`'s order, each read once (`Chunks::set`).
    sets: Vec<SetRef>,
}

/// One chunk's sets, read.
#[derive(Debug, Default)]
pub struct Chunk {
    /// The sets first seen in this chunk (in the order of first use), each read once.
    sets: Vec<PropertySet>,
    /// By position in the chunk: the sets of a product where a type's set and the product's
    /// own share a name, so that `property_sets` merges them (rare), read for it alone.
    merged: FxHashMap<usize, Vec<PropertySet>>,
}

/// One product's property sets.
#[derive(Debug)]
pub enum ProductSets<'c> {
    /// Sets read once (`Chunks::set`), in the product's order (`property_sets`'s).
    Read(&'c [SetRef]),
    /// Sets of this product alone, merged.
    Merged(&'c [PropertySet]),
}

/// Where a set read once is: chunk and position in its `Chunk::sets`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SetRef {
    chunk: u32,
    index: u32,
}

/// The smallest chunk (but for a model with fewer products).
const MIN_CHUNK: usize = 16;

/// Where the chunks of `n` products end: each chunk half of the products left (the last
/// fewer than twice `MIN_CHUNK`), so the first is read while the caller waits anyway, and
/// what the caller converts after the last one is read (one core then idle) is a small part.
/// Every chunk costs a parallel pass (a hand-off between the pool's threads) and a hand-off
/// to the caller: a few of them (3 for fzk-haus's 127 products, 7 for office-a's 1,090).
fn chunk_ends(n: usize) -> Vec<usize> {
    let mut ends = Vec::new();
    let mut start = 0;
    while start < n {
        let left = n - start;
        start += if left < 2 * MIN_CHUNK {
            left
        } else {
            left.div_ceil(2)
        };
        ends.push(start);
    }
    ends
}

impl<'m> Chunks<'m> {
    /// The instances of `class` (subtypes included) in chunks; nothing read yet.
    pub fn new(model: &'m poinav_ifc::Model, class: &str) -> Self {
        let all = model.instances_of(class);
        let ends = chunk_ends(all.len());
        let read = ends.iter().map(|_| OnceLock::new()).collect();
        Chunks {
            all,
            ends,
            products: OnceLock::new(),
            plan: OnceLock::new(),
            read,
        }
    }

    /// Finds the sets of every product (in parallel), numbered in the order of first use,
    /// chunk by chunk: what `read_all` does first, on the pool as the rest.
    fn find(&self) {
        let defs: Vec<Option<(String, Vec<Entity<'m>>)>> = self
            .all
            .par_iter()
            .map(|e| {
                let g = e.global_id()?;
                Some((g, set_definitions(*e).map(|(d, _)| d).collect()))
            })
            .collect();
        let mut seen: FxHashMap<EntityId, SetRef> = FxHashMap::default();
        let mut products = Vec::new();
        let mut plan = Vec::new();
        let mut start = 0;
        let mut defs = defs.into_iter();
        for (k, &end) in self.ends.iter().enumerate() {
            let chunk = u32::try_from(k).expect("fewer than 2^32 chunks");
            let mut fresh: Vec<Entity<'m>> = Vec::new();
            let mut entities = Vec::new();
            let mut these = Vec::new();
            for (e, d) in self.all[start..end].iter().zip(defs.by_ref()) {
                let Some((global_id, d)) = d else { continue };
                let sets = d
                    .into_iter()
                    .map(|d| {
                        *seen.entry(d.id()).or_insert_with(|| {
                            fresh.push(d);
                            let index = u32::try_from(fresh.len() - 1).expect("< 2^32 sets");
                            SetRef { chunk, index }
                        })
                    })
                    .collect();
                entities.push(*e);
                these.push(Product { global_id, sets });
            }
            products.push(these);
            plan.push((entities, fresh));
            start = end;
        }
        self.products.set(products).expect("found once");
        self.plan.set(plan).expect("found once");
    }

    /// The number of chunks.
    pub fn len(&self) -> usize {
        self.read.len()
    }

    /// The products of chunk `k` with their sets, once it is read.
    pub fn products(&self, k: usize) -> Option<impl Iterator<Item = (&str, ProductSets<'_>)>> {
        let chunk = self.read.get(k)?.get()?;
        let products = &self.products.get()?[k];
        Some(products.iter().enumerate().map(|(i, p)| {
            let sets = match chunk.merged.get(&i) {
                Some(merged) => ProductSets::Merged(merged),
                None => ProductSets::Read(&p.sets),
            };
            (p.global_id.as_str(), sets)
        }))
    }

    /// The set at `r` (of a chunk already read).
    pub fn set(&self, r: SetRef) -> &PropertySet {
        let chunk = self.read[r.chunk as usize]
            .get()
            .expect("a chunk read before");
        &chunk.sets[r.index as usize]
    }

    /// Reads the chunks in order, each in parallel, calling `done(k)` after chunk `k`;
    /// stops when `done` returns false. Every distinct set is read once, as
    /// `read_set_untyped` gives it (without the values' IFC type names and `from_type`,
    /// which the dicts do not give).
    ///
    /// A set related to many products (and a type's sets, which every occurrence of the
    /// type gets) would otherwise be read, decoded and freed again for every product: 39 %
    /// of office-a's 8,494 sets are repeats.
    pub fn read_all(&self, mut done: impl FnMut(usize) -> bool) {
        if self.len() > 0 {
            self.find();
        }
        for k in 0..self.len() {
            self.read_chunk(k);
            if !done(k) {
                return;
            }
        }
    }

    /// Reads chunk `k`, after the chunks before it.
    fn read_chunk(&self, k: usize) {
        let (entities, fresh) = &self.plan.get().expect("found before")[k];
        let sets: Vec<PropertySet> = fresh
            .par_iter()
            .map(|d| read_set_untyped(*d, false))
            .collect();
        let name = |r: &SetRef| -> &str {
            if r.chunk as usize == k {
                &sets[r.index as usize].name
            } else {
                &self.set(*r).name
            }
        };
        // Comparing names is little work: on this thread; merged sets are rare.
        let merged = self.products.get().expect("found before")[k]
            .iter()
            .zip(entities)
            .enumerate()
            .filter(|(_, (p, _))| {
                let d = &p.sets;
                !d.iter()
                    .enumerate()
                    .all(|(i, a)| d[..i].iter().all(|b| name(a) != name(b)))
            })
            .map(|(i, (_, e))| (i, property_sets(*e)))
            .collect();
        self.read[k]
            .set(Chunk { sets, merged })
            .expect("each chunk read once");
    }

    /// What the chunks own, without the borrowed entities (to free it elsewhere).
    pub fn into_owned(self) -> (Option<Vec<Vec<Product>>>, Vec<OnceLock<Chunk>>) {
        (self.products.into_inner(), self.read)
    }

    /// The number of property sets of all products read so far.
    pub fn set_count(&self) -> usize {
        (0..self.len())
            .filter_map(|k| self.products(k))
            .flatten()
            .map(|(_, s)| match s {
                ProductSets::Read(sets) => sets.len(),
                ProductSets::Merged(sets) => sets.len(),
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::chunk_ends;

    #[test]
    fn chunks_halve_down_to_16_to_31_products() {
        assert_eq!(chunk_ends(0), Vec::<usize>::new());
        assert_eq!(chunk_ends(20), [20]);
        assert_eq!(chunk_ends(32), [16, 32]);
        assert_eq!(chunk_ends(127), [64, 96, 127]);
        assert_eq!(chunk_ends(295), [148, 222, 259, 277, 295]);
        assert_eq!(chunk_ends(1090), [545, 818, 954, 1022, 1056, 1073, 1090]);
    }
}
