//! The property sets of every product of a class, read on the rayon pool in chunks of
//! products (for `Model.psets`): each distinct IfcPropertySet read once, and each chunk
//! handed over as soon as it is read, so the caller makes one chunk's Python objects while
//! the pool reads the next.

use std::sync::OnceLock;

use poinav_ifc::property::{property_sets, read_set_untyped, set_definitions, PropertySet};
use poinav_ifc::{Entity, EntityId};
use rayon::prelude::*;
use rustc_hash::FxHashMap;

/// The products of one class in chunks, and each chunk's sets once it is read.
#[derive(Debug)]
pub struct Chunks<'m> {
    /// Every instance of the class (subtypes included), in the model's order.
    products: Vec<Entity<'m>>,
    /// Where each chunk ends in `products`.
    ends: Vec<usize>,
    /// Chunk `k`'s sets, set when it is read.
    read: Vec<OnceLock<Chunk>>,
}

/// One chunk of products, read.
#[derive(Debug, Default)]
pub struct Chunk {
    /// The sets first seen in this chunk (in the order of first use), each read once.
    pub sets: Vec<PropertySet>,
    /// The chunk's products with a GlobalId: the GlobalId and the product's sets.
    pub products: Vec<(String, ProductSets)>,
}

/// One product's property sets.
#[derive(Debug)]
pub enum ProductSets {
    /// Sets read once (`Chunks::set`), in the product's order (`property_sets`'s).
    Read(Vec<SetRef>),
    /// Sets of this product alone: a type's set and the product's own share a name, so
    /// `property_sets` merges them (rare).
    Merged(Vec<PropertySet>),
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
/// Every chunk costs two hand-offs to the pool's threads: a few of them (3 for fzk-haus's
/// 127 products, 7 for office-a's 1,090).
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
    /// The instances of `class` (subtypes included), none read yet.
    pub fn new(model: &'m poinav_ifc::Model, class: &str) -> Self {
        let products = model.instances_of(class);
        let ends = chunk_ends(products.len());
        let read = ends.iter().map(|_| OnceLock::new()).collect();
        Chunks {
            products,
            ends,
            read,
        }
    }

    /// The number of chunks.
    pub fn len(&self) -> usize {
        self.read.len()
    }

    /// Chunk `k`, once read.
    pub fn chunk(&self, k: usize) -> Option<&Chunk> {
        self.read.get(k).and_then(OnceLock::get)
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
        let mut seen: FxHashMap<EntityId, SetRef> = FxHashMap::default();
        let mut start = 0;
        for (k, &end) in self.ends.iter().enumerate() {
            self.read_chunk(k, &self.products[start..end], &mut seen);
            start = end;
            if !done(k) {
                return;
            }
        }
    }

    /// Reads chunk `k` (`products`), after the chunks before it.
    fn read_chunk(
        &self,
        k: usize,
        products: &[Entity<'m>],
        seen: &mut FxHashMap<EntityId, SetRef>,
    ) {
        let defs: Vec<(Entity<'m>, String, Vec<Entity<'m>>)> = products
            .par_iter()
            .filter_map(|e| {
                let g = e.global_id()?;
                Some((*e, g, set_definitions(*e).map(|(d, _)| d).collect()))
            })
            .collect();
        // Each product's sets as references to the distinct ones; those first seen here are
        // read in this chunk.
        let mut fresh: Vec<Entity<'m>> = Vec::new();
        let chunk = u32::try_from(k).expect("fewer than 2^32 chunks");
        let defs: Vec<(Entity<'m>, String, Vec<SetRef>)> = defs
            .into_iter()
            .map(|(e, g, d)| {
                let refs = d
                    .into_iter()
                    .map(|d| {
                        *seen.entry(d.id()).or_insert_with(|| {
                            fresh.push(d);
                            SetRef {
                                chunk,
                                index: u32::try_from(fresh.len() - 1).expect("< 2^32 sets"),
                            }
                        })
                    })
                    .collect();
                (e, g, refs)
            })
            .collect();
        let sets: Vec<PropertySet> = fresh
            .par_iter()
            .map(|d| read_set_untyped(*d, false))
            .collect();
        let name = |r: &SetRef| -> &str {
            if r.chunk == chunk {
                &sets[r.index as usize].name
            } else {
                &self.set(*r).name
            }
        };
        // Comparing names is little work: on this thread; merged sets are rare.
        let products = defs
            .into_iter()
            .map(|(e, g, d)| {
                let names_differ = d
                    .iter()
                    .enumerate()
                    .all(|(i, a)| d[..i].iter().all(|b| name(a) != name(b)));
                let sets = if names_differ {
                    ProductSets::Read(d)
                } else {
                    ProductSets::Merged(property_sets(e))
                };
                (g, sets)
            })
            .collect();
        self.read[k]
            .set(Chunk { sets, products })
            .expect("each chunk read once");
    }

    /// The chunks read, without the borrowed products (to free them elsewhere).
    pub fn into_read(self) -> Vec<OnceLock<Chunk>> {
        self.read
    }

    /// The number of property sets of all products read so far.
    pub fn set_count(&self) -> usize {
        (0..self.len())
            .filter_map(|k| self.chunk(k))
            .flat_map(|c| &c.products)
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
