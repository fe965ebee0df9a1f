//! `Model`: one IFC file read into memory and indexed by `#id` and entity type.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

use rustc_hash::FxHashMap;

use crate::arg_index::ArgIndex;
use crate::check;
use crate::diagnostic::{Diagnostic, DiagnosticKind};
use crate::entity::Entity;
use crate::error::{ReadError, ReadErrorKind};
use crate::header::{self, Header};
use crate::lines::{line_of, LineTable};
use crate::scan::{self, Instance};
use crate::schema::TypeId;
use crate::{EntityId, Schema};

/// At most this many diagnostics of one kind are kept; the rest are counted in one more.
pub const MAX_DIAGNOSTICS_PER_KIND: usize = 1000;

/// `#id` to instance position.
#[derive(Debug)]
enum IdIndex {
    /// Ids are mostly dense: a table indexed by id.
    Dense(Vec<u32>),
    /// Ids are sparse (or hostile): a hash map.
    Sparse(FxHashMap<u64, u32>),
}

const NONE: u32 = u32::MAX;

impl IdIndex {
    fn get(&self, id: EntityId) -> Option<u32> {
        match self {
            IdIndex::Dense(v) => v
                .get(usize::try_from(id.0).ok()?)
                .copied()
                .filter(|&i| i != NONE),
            IdIndex::Sparse(m) => m.get(&id.0).copied(),
        }
    }
}

/// Reverse references for one (relating type, attribute): target -> relating instances.
pub(crate) type InverseIndex = FxHashMap<EntityId, Vec<u32>>;

/// An IFC file in memory. Instances are decoded lazily on access; the bytes are kept as read,
/// so unchanged instances can be written back byte for byte.
#[derive(Debug)]
pub struct Model {
    file: PathBuf,
    bytes: Vec<u8>,
    header: Header,
    pub(crate) instances: Vec<Instance>,
    ids: IdIndex,
    diagnostics: Vec<Diagnostic>,
    data_end: usize,
    /// Where each instance's attribute values lie.
    args: ArgIndex,
    /// The largest `#id` any instance defines or mentions (found by the structure check).
    max_id_used: u64,
    lines: OnceLock<LineTable>,
    by_type: OnceLock<Vec<Vec<u32>>>,
    inverses: Mutex<FxHashMap<(TypeId, usize), Arc<InverseIndex>>>,
}

impl Model {
    /// Reads and indexes the file at `path`. The file is only ever opened for reading.
    pub fn open(path: impl AsRef<Path>) -> Result<Model, ReadError> {
        let path = path.as_ref();
        let bytes = std::fs::read(path).map_err(|e| ReadError {
            file: path.to_path_buf(),
            line: None,
            id: None,
            kind: ReadErrorKind::Io(e.to_string()),
        })?;
        Model::from_bytes(path, bytes)
    }

    /// Indexes a file already in memory; `file` names it in errors and diagnostics.
    pub fn from_bytes(file: impl Into<PathBuf>, bytes: Vec<u8>) -> Result<Model, ReadError> {
        let file = file.into();
        let fail = |kind, offset: usize, id| ReadError {
            file: file.clone(),
            line: Some(line_of(&bytes, offset)),
            id,
            kind,
        };
        let (header, header_problems) = header::parse(&bytes).map_err(|(k, o)| fail(k, o, None))?;
        let schema = header.schema;
        let scanned =
            scan::scan(&bytes, header.end, schema).map_err(|(k, o, id)| fail(k, o, id))?;

        let mut diagnostics = Vec::new();
        if Schema::from_identifier(&header.schema_identifier).is_some_and(|(_, exact)| !exact) {
            diagnostics.push((
                DiagnosticKind::SchemaVariant,
                None,
                0,
                format!(
                    "schema `{}` is read as {}",
                    header.schema_identifier,
                    schema.name()
                ),
            ));
        }
        diagnostics.extend(header_problems);
        diagnostics.extend(scanned.problems);
        let mut instances = scanned.instances;
        let (mut ids, duplicates) = build_id_index(&instances);
        if !duplicates.is_empty() {
            for &i in &duplicates {
                let inst = &instances[i as usize];
                diagnostics.push((
                    DiagnosticKind::DuplicateId,
                    Some(inst.id),
                    inst.start,
                    format!(
                        "{} is defined more than once; the first definition is used, this one is ignored (and kept in written copies)",
                        inst.id
                    ),
                ));
            }
            // Later definitions leave the index; their bytes stay in the file.
            let dropped: rustc_hash::FxHashSet<u32> = duplicates.iter().copied().collect();
            let mut k = 0u32;
            instances.retain(|_| {
                k += 1;
                !dropped.contains(&(k - 1))
            });
            ids = build_id_index(&instances).0;
        }
        if let Some(p) = ids.get(EntityId(0)) {
            let inst = &instances[p as usize];
            diagnostics.push((
                DiagnosticKind::Syntax,
                Some(inst.id),
                inst.start,
                "`#0` is not a valid instance name (STEP numbers instances from #1); the instance is kept".into(),
            ));
        }
        let mut model = Model {
            file,
            bytes,
            header,
            instances,
            ids,
            diagnostics: Vec::new(),
            data_end: scanned.data_end,
            args: ArgIndex::default(),
            max_id_used: 0,
            lines: OnceLock::new(),
            by_type: OnceLock::new(),
            inverses: Mutex::new(FxHashMap::default()),
        };
        let (problems, structure) = check::structure(&model);
        diagnostics.extend(problems);
        model.args = structure.args;
        model.max_id_used = structure.max_id_used;
        diagnostics.extend(check::non_utf8(&model));
        diagnostics.extend(check::cycles(&model));
        model.diagnostics = model.finish_diagnostics(diagnostics);
        Ok(model)
    }

    fn finish_diagnostics(
        &self,
        mut raw: Vec<(DiagnosticKind, Option<EntityId>, usize, String)>,
    ) -> Vec<Diagnostic> {
        raw.sort_by_key(|p| (p.2, p.0));
        let mut per_kind: BTreeMap<DiagnosticKind, usize> = BTreeMap::new();
        let mut out = Vec::new();
        for (kind, id, offset, message) in raw {
            let n = per_kind.entry(kind).or_default();
            *n += 1;
            if *n <= MAX_DIAGNOSTICS_PER_KIND {
                out.push(Diagnostic {
                    kind,
                    id,
                    line: Some(self.line_at(offset)),
                    message,
                });
            }
        }
        for (kind, n) in per_kind {
            if n > MAX_DIAGNOSTICS_PER_KIND {
                out.push(Diagnostic {
                    kind: DiagnosticKind::Truncated,
                    id: None,
                    line: None,
                    message: format!(
                        "{} more `{}` diagnostics not shown",
                        n - MAX_DIAGNOSTICS_PER_KIND,
                        kind.code()
                    ),
                });
            }
        }
        out
    }

    /// The file name given when reading.
    pub fn file(&self) -> &Path {
        &self.file
    }

    /// The schema the file is read with.
    pub fn schema(&self) -> Schema {
        self.header.schema
    }

    /// The header: schema identifier as written, and spans for editing.
    pub fn header(&self) -> &Header {
        &self.header
    }

    /// The file's bytes exactly as read.
    pub fn bytes(&self) -> &[u8] {
        &self.bytes
    }

    /// Offset of the `ENDSEC` closing the last DATA section (new instances go before it).
    pub(crate) fn data_end(&self) -> usize {
        self.data_end
    }

    /// Damaged parts found while reading, in file order.
    pub fn diagnostics(&self) -> &[Diagnostic] {
        &self.diagnostics
    }

    /// Number of instances.
    pub fn len(&self) -> usize {
        self.instances.len()
    }

    /// True when the DATA section holds no instance.
    pub fn is_empty(&self) -> bool {
        self.instances.is_empty()
    }

    /// The largest `#id` in the file (0 for an empty model).
    pub fn max_id(&self) -> EntityId {
        EntityId(self.instances.iter().map(|i| i.id.0).max().unwrap_or(0))
    }

    /// The largest `#id` any instance defines or mentions, dangling or not (0 for an empty
    /// model): an editor's first new id is above it.
    pub(crate) fn max_id_used(&self) -> u64 {
        self.max_id_used
    }

    /// The largest `#id` the instance at `position` defines or mentions (read from its
    /// arguments each time: only an editor's first new id asks, and keeping it per instance
    /// cost 8 bytes an instance for the model's whole life).
    pub(crate) fn max_id_used_at(&self, position: usize) -> u64 {
        let inst = &self.instances[position];
        let args = &self.bytes[inst.args()..inst.end() - 1];
        inst.id.0.max(crate::check::max_ref(args))
    }

    /// The top-level separators of the argument list of the instance at `position` (see
    /// [`ArgIndex`]), or `None` when they were not recorded.
    pub(crate) fn arg_separators(&self, position: usize) -> Option<&[u32]> {
        self.args.separators(position)
    }

    /// The instance `#id`, if it exists.
    pub fn entity(&self, id: EntityId) -> Option<Entity<'_>> {
        self.ids.get(id).map(|i| Entity::new(self, i))
    }

    /// Every instance, in file order.
    pub fn entities(&self) -> impl ExactSizeIterator<Item = Entity<'_>> + '_ {
        (0..self.instances.len() as u32).map(move |i| Entity::new(self, i))
    }

    /// Instance positions grouped by exact type.
    pub(crate) fn by_type(&self) -> &[Vec<u32>] {
        self.by_type.get_or_init(|| {
            let mut buckets = vec![Vec::new(); self.schema().entity_count()];
            for (i, inst) in self.instances.iter().enumerate() {
                if let Some(t) = inst.type_id() {
                    buckets[t.index()].push(i as u32);
                }
            }
            buckets
        })
    }

    /// Positions of all instances of `ty` or a subtype, in file order.
    pub(crate) fn positions_of(&self, ty: TypeId) -> Vec<u32> {
        let schema = self.schema();
        let buckets = self.by_type();
        let mut out: Vec<u32> = Vec::new();
        let mut parts = 0;
        for (t, bucket) in buckets.iter().enumerate() {
            if !bucket.is_empty() && schema.is_subtype_of(TypeId(t as u16), ty) {
                out.extend_from_slice(bucket);
                parts += 1;
            }
        }
        if parts > 1 {
            out.sort_unstable();
        }
        out
    }

    /// All instances of the entity `name` and its subtypes, in file order, like IfcOpenShell's
    /// `by_type`. A name the schema does not know gives an empty list.
    pub fn instances_of(&self, name: &str) -> Vec<Entity<'_>> {
        match self.schema().type_by_name(name) {
            Some(t) => self
                .positions_of(t)
                .into_iter()
                .map(|i| Entity::new(self, i))
                .collect(),
            None => Vec::new(),
        }
    }

    /// Number of instances of `name` and its subtypes.
    pub fn count_of(&self, name: &str) -> usize {
        let Some(ty) = self.schema().type_by_name(name) else {
            return 0;
        };
        let schema = self.schema();
        self.by_type()
            .iter()
            .enumerate()
            .filter(|(t, b)| !b.is_empty() && schema.is_subtype_of(TypeId(*t as u16), ty))
            .map(|(_, b)| b.len())
            .sum()
    }

    /// For every entity type with at least one instance of itself or a subtype: that count.
    pub fn type_counts(&self) -> BTreeMap<&'static str, usize> {
        let schema = self.schema();
        let mut counts = BTreeMap::new();
        for (t, bucket) in self.by_type().iter().enumerate() {
            if bucket.is_empty() {
                continue;
            }
            for a in schema.ancestors(TypeId(t as u16)) {
                *counts.entry(schema.entity(a).name).or_insert(0) += bucket.len();
            }
        }
        counts
    }

    /// Every instance whose arguments refer to `id` (a scan of the whole file: for edits, not
    /// for hot paths).
    pub fn referrers(&self, id: EntityId) -> Vec<Entity<'_>> {
        let needle = format!("#{}", id.0);
        let finder = memchr::memmem::Finder::new(needle.as_bytes());
        self.entities()
            .filter(|e| {
                let args = e.raw_args();
                finder
                    .find_iter(args)
                    .any(|at| !args.get(at + needle.len()).is_some_and(u8::is_ascii_digit))
            })
            .collect()
    }

    /// 1-based line of a byte offset.
    pub(crate) fn line_at(&self, offset: usize) -> usize {
        self.lines
            .get_or_init(|| LineTable::new(&self.bytes))
            .line(offset)
    }

    /// The reverse-reference index of attribute `attr` of `rel` (and subtypes), built once.
    pub(crate) fn inverse_index(&self, rel: TypeId, attr: usize) -> Arc<InverseIndex> {
        if let Some(ix) = self
            .inverses
            .lock()
            .expect("inverse cache")
            .get(&(rel, attr))
        {
            return ix.clone();
        }
        let mut index: InverseIndex = FxHashMap::default();
        for pos in self.positions_of(rel) {
            let e = Entity::new(self, pos);
            if let Ok(Some(v)) = e.attr_at(attr) {
                for target in v.refs() {
                    let list = index.entry(target).or_default();
                    if list.last() != Some(&pos) {
                        list.push(pos);
                    }
                }
            }
        }
        let index = Arc::new(index);
        self.inverses
            .lock()
            .expect("inverse cache")
            .insert((rel, attr), index.clone());
        index
    }
}

/// Builds the id index; returns it with the positions of duplicate definitions.
fn build_id_index(instances: &[Instance]) -> (IdIndex, Vec<u32>) {
    let max = instances.iter().map(|i| i.id.0).max().unwrap_or(0);
    let mut duplicates = Vec::new();
    let dense_limit = (instances.len() as u64)
        .saturating_mul(4)
        .saturating_add(1024);
    if max <= dense_limit {
        let mut table = vec![NONE; max as usize + 1];
        for (i, inst) in instances.iter().enumerate() {
            let slot = &mut table[inst.id.0 as usize];
            if *slot == NONE {
                *slot = i as u32;
            } else {
                duplicates.push(i as u32);
            }
        }
        (IdIndex::Dense(table), duplicates)
    } else {
        let mut map = FxHashMap::default();
        for (i, inst) in instances.iter().enumerate() {
            match map.entry(inst.id.0) {
                std::collections::hash_map::Entry::Occupied(_) => duplicates.push(i as u32),
                std::collections::hash_map::Entry::Vacant(e) => {
                    e.insert(i as u32);
                }
            }
        }
        (IdIndex::Sparse(map), duplicates)
    }
}
