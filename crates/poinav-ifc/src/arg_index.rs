//! `ArgIndex`: where each instance's top-level attribute values lie, found once while the
//! model is read (in `check.rs`'s parallel walk), so reading one attribute parses that value
//! alone instead of splitting the whole argument list again on every access.

/// Per instance, the offsets (relative to the `(` that opens its arguments) of the opening
/// `(`, of every top-level `,` and of the closing `)`: value `k` lies between separators `k`
/// and `k + 1`. An argument list holding no value (`()`) keeps only its `(`; an instance whose
/// list could not be walked (unbalanced parentheses) keeps nothing and is split on access.
#[derive(Debug, Default)]
pub(crate) struct ArgIndex {
    /// All instances' separators, in instance order.
    separators: Vec<u32>,
    /// Instance `i`'s separators are `separators[starts[i]..starts[i + 1]]`.
    starts: Vec<u32>,
}

impl ArgIndex {
    /// Builds the index from each instance's separators, in instance order (`None`: not
    /// indexed). Fails (returns `None`) only when the offsets do not fit in `u32`, which a
    /// file under 4 GiB cannot reach.
    pub(crate) fn from_parts<'a>(
        parts: impl IntoIterator<Item = Option<&'a [u32]>>,
        instances: usize,
        total: usize,
    ) -> Option<ArgIndex> {
        let mut index = ArgIndex {
            separators: Vec::with_capacity(total),
            starts: Vec::with_capacity(instances + 1),
        };
        index.starts.push(0);
        for p in parts {
            index.separators.extend_from_slice(p.unwrap_or(&[]));
            index
                .starts
                .push(u32::try_from(index.separators.len()).ok()?);
        }
        index.separators.shrink_to_fit();
        index.starts.shrink_to_fit();
        Some(index)
    }

    /// The separators of the instance at `position`, or `None` when it is not indexed.
    pub(crate) fn separators(&self, position: usize) -> Option<&[u32]> {
        let from = *self.starts.get(position)? as usize;
        let to = *self.starts.get(position + 1)? as usize;
        (to > from).then(|| &self.separators[from..to])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn separators_per_instance_and_unindexed_instances() {
        let a: &[u32] = &[0, 3, 7];
        let b: &[u32] = &[0];
        let ix = ArgIndex::from_parts([Some(a), None, Some(b)], 3, 4).unwrap();
        assert_eq!(ix.separators(0), Some(a));
        assert_eq!(ix.separators(1), None);
        assert_eq!(ix.separators(2), Some(b));
        assert_eq!(ix.separators(3), None);
        assert_eq!(ArgIndex::default().separators(0), None);
    }
}
