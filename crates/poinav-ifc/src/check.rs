//! Second pass over a scanned model: dangling references, attribute counts, parenthesis
//! balance and empty values (in parallel), bytes that are not UTF-8, and cycles in placements
//! and aggregation.

use rayon::prelude::*;
use rustc_hash::{FxHashMap, FxHashSet};

use crate::arg_index::ArgIndex;
use crate::diagnostic::DiagnosticKind;
use crate::model::Model;
use crate::EntityId;

/// A diagnostic before its offset is turned into a line.
pub(crate) type Problem = (DiagnosticKind, Option<EntityId>, usize, String);

struct Shape {
    attrs: usize,
    balanced: bool,
    max_depth: usize,
    max_ref: u64,
    dangling: Vec<u64>,
    /// The first bare word standing as a value (`NaN`, `inf`, `T`): not STEP.
    bare: Option<(usize, usize)>,
    /// The first string holding an escape that is not a directive (read literally): where its
    /// content starts and the escape's offset in it.
    bad_escape: Option<(usize, usize)>,
    /// The opening quote of a string that is never closed.
    unclosed: Option<usize>,
    /// The first empty value (`,,`, `(,` or `,)`): the 1-based attribute it is in, and whether
    /// it is the attribute itself (not an item of a list inside it).
    empty: Option<(usize, bool)>,
}

/// Walks one argument list byte by byte; `exists` tells whether a referenced id is defined.
/// Appends the list's top-level separators to `seps` (see [`ArgIndex`]): the opening `(`,
/// each top-level `,` and the closing `)`; only the `(` for a list without values, nothing
/// for an unbalanced list.
fn shape(args: &[u8], exists: impl Fn(u64) -> bool, seps: &mut Vec<u32>) -> Shape {
    let mark = seps.len();
    let mut depth = 0usize;
    let mut max_depth = 0usize;
    let mut max_ref = 0u64;
    let mut commas = 0;
    let mut saw_value = false;
    let mut dangling = Vec::new();
    let mut i = 0;
    let mut closed_at = None;
    // At the start of a value (after `(` or `,`), where a bare word is not STEP.
    let mut fresh = false;
    let mut bare = None;
    // The first string with an escape that is not a directive: (content offset, offset in it).
    let mut bad_escape = None;
    // The opening quote of a string that never closes.
    let mut unclosed = None;
    let mut empty = None;
    while i < args.len() {
        let c = args[i];
        if fresh && !matches!(c, b' ' | b'\t' | b'\r' | b'\n') {
            fresh = false;
            if c.is_ascii_alphabetic() {
                let mut j = i;
                while j < args.len() && (args[j].is_ascii_alphanumeric() || args[j] == b'_') {
                    j += 1;
                }
                let mut k = j;
                while k < args.len() && args[k].is_ascii_whitespace() {
                    k += 1;
                }
                // A typed value (`IFCLABEL('x')`) is followed by `(`; anything else is bare.
                if args.get(k) != Some(&b'(') && bare.is_none() {
                    bare = Some((i, j));
                }
                saw_value = true;
                i = j;
                continue;
            }
            // Only white space since the last `(` or `,`: a `,` here, or a `)` after a `,`,
            // leaves a value empty (`()` is an empty list).
            if matches!(c, b',' | b')') && empty.is_none() && (c == b',' || follows_comma(args, i))
            {
                empty = Some((commas + 1, depth == 1));
            }
        }
        match c {
            b'\'' => {
                saw_value = true;
                match crate::string::literal_end(args, i) {
                    Some(q) => {
                        let raw = &args[i + 1..q];
                        if bad_escape.is_none() && memchr::memchr(b'\\', raw).is_some() {
                            if let Err(crate::string::StringError::BadEscape(at)) =
                                crate::string::check_escapes(raw)
                            {
                                bad_escape = Some((i + 1, at));
                            }
                        }
                        i = q + 1;
                    }
                    None => {
                        unclosed = Some(i);
                        i = args.len();
                    }
                }
                continue;
            }
            b'"' => {
                saw_value = true;
                i = memchr::memchr(b'"', &args[i + 1..]).map_or(args.len(), |q| i + q + 2);
                continue;
            }
            b'(' => {
                if depth >= 1 {
                    saw_value = true;
                } else {
                    seps.push(i as u32);
                }
                depth += 1;
                max_depth = max_depth.max(depth);
                fresh = true;
            }
            b')' => {
                if depth == 0 {
                    closed_at = None;
                    break;
                }
                depth -= 1;
                if depth == 0 {
                    seps.push(i as u32);
                    closed_at = Some(i);
                    break;
                }
            }
            b',' => {
                if depth == 1 {
                    commas += 1;
                    seps.push(i as u32);
                }
                fresh = true;
            }
            b'#' => {
                saw_value = true;
                let s = i + 1;
                let mut j = s;
                while j < args.len() && args[j].is_ascii_digit() {
                    j += 1;
                }
                let id = std::str::from_utf8(&args[s..j])
                    .ok()
                    .and_then(|t| t.parse::<u64>().ok());
                if let Some(id) = id {
                    max_ref = max_ref.max(id);
                }
                match id {
                    Some(id) if exists(id) => {}
                    Some(id) => dangling.push(id),
                    None => {}
                }
                i = j;
                continue;
            }
            b'/' if args.get(i + 1) == Some(&b'*') => {
                i = memchr::memmem::find(&args[i + 2..], b"*/").map_or(args.len(), |e| i + e + 4);
                continue;
            }
            b' ' | b'\t' | b'\r' | b'\n' => {}
            _ => {
                if depth >= 1 {
                    saw_value = true;
                }
            }
        }
        i += 1;
    }
    let balanced = closed_at.is_some_and(|c| args[c + 1..].iter().all(u8::is_ascii_whitespace));
    if !balanced || u32::try_from(args.len()).is_err() {
        seps.truncate(mark);
    } else if !saw_value {
        seps.truncate(mark + 1);
    }
    Shape {
        attrs: if saw_value { commas + 1 } else { 0 },
        balanced,
        max_depth,
        max_ref,
        dangling,
        bare,
        bad_escape,
        unclosed,
        empty,
    }
}

/// Whether the last byte before `i` that is not white space is a `,`.
fn follows_comma(args: &[u8], i: usize) -> bool {
    args[..i]
        .iter()
        .rfind(|c| !matches!(c, b' ' | b'\t' | b'\r' | b'\n'))
        == Some(&b',')
}

/// The largest `#id` the argument list `args` mentions (0 for none), dangling or not.
pub(crate) fn max_ref(args: &[u8]) -> u64 {
    shape(args, |_| true, &mut Vec::new()).max_ref
}

/// What [`structure`] finds besides problems.
pub(crate) struct Structure {
    /// Where each instance's attribute values lie.
    pub(crate) args: ArgIndex,
    /// The largest `#id` any instance defines or mentions (dangling or not; 0 for none).
    pub(crate) max_id_used: u64,
}

/// One chunk's results: problems, separators, each instance's separator count and the
/// largest `#id` the chunk defines or mentions.
type ChunkResult = (Vec<Problem>, Vec<u32>, Vec<u32>, u64);

/// Dangling references, wrong attribute counts and unbalanced argument lists, checked in
/// parallel; the same walk records what [`Structure`] holds.
pub(crate) fn structure(model: &Model) -> (Vec<Problem>, Structure) {
    let schema = model.schema();
    let bytes = model.bytes();
    let parts: Vec<ChunkResult> = model
        .instances
        .par_chunks(4096)
        .map(|chunk| {
            let mut out = Vec::new();
            let mut seps = Vec::with_capacity(chunk.len() * 8);
            let mut counts = Vec::with_capacity(chunk.len());
            let mut max_id = 0u64;
            for inst in chunk {
                let args = &bytes[inst.args()..inst.end() - 1];
                let before = seps.len();
                let s = shape(args, |id| model.entity(EntityId(id)).is_some(), &mut seps);
                counts.push((seps.len() - before) as u32);
                max_id = max_id.max(inst.id.0).max(s.max_ref);
                if let Some(at) = s.unclosed {
                    out.push((
                        DiagnosticKind::Syntax,
                        Some(inst.id),
                        inst.start,
                        format!(
                            "the string opened at byte {at} of the arguments is never closed; the instance is read up to the next `;`, and its attributes cannot be read"
                        ),
                    ));
                    continue;
                }
                if !s.balanced {
                    out.push((
                        DiagnosticKind::Syntax,
                        Some(inst.id),
                        inst.start,
                        "unbalanced parentheses in the argument list".to_string(),
                    ));
                    continue;
                }
                if let Some((content, at)) = s.bad_escape {
                    let rest = &args[content + at..];
                    let len = rest.iter().take(6).take_while(|&&c| c != b'\'').count();
                    let shown = &rest[..len];
                    out.push((
                        DiagnosticKind::BadValue,
                        Some(inst.id),
                        inst.start,
                        format!(
                            "a string holds `{}`, which is not a STEP escape; it is read as written",
                            String::from_utf8_lossy(shown)
                        ),
                    ));
                }
                if let Some((n, whole)) = s.empty {
                    let name = inst
                        .type_id()
                        .and_then(|t| schema.attribute(t, n - 1))
                        .map_or(String::new(), |(a, _)| format!(" ({})", a.name));
                    out.push((
                        DiagnosticKind::Syntax,
                        Some(inst.id),
                        inst.start,
                        format!(
                            "{} (nothing between two separators, as in `,,`): STEP writes `$` for an unset value; that attribute cannot be read, the others can",
                            if whole {
                                format!("attribute {n}{name} is empty")
                            } else {
                                format!("a list in attribute {n}{name} has an empty item")
                            }
                        ),
                    ));
                }
                if s.max_depth > crate::value::MAX_NESTING {
                    out.push((
                        DiagnosticKind::BadValue,
                        Some(inst.id),
                        inst.start,
                        format!(
                            "an attribute nests lists {} deep (limit {}); that attribute cannot be read, the others can",
                            s.max_depth - 1,
                            crate::value::MAX_NESTING
                        ),
                    ));
                }
                if let Some((a, b)) = s.bare {
                    out.push((
                        DiagnosticKind::BadValue,
                        Some(inst.id),
                        inst.start,
                        format!(
                            "`{}` is not a STEP value (numbers are written like 1.5E3, enumerations like .T.); that attribute cannot be read, the others can",
                            String::from_utf8_lossy(&args[a..b])
                        ),
                    ));
                }
                if let Some(t) = inst.type_id() {
                    let want = schema.attribute_count(t);
                    if s.attrs != want {
                        out.push((
                            DiagnosticKind::WrongAttributeCount,
                            Some(inst.id),
                            inst.start,
                            format!(
                                "{} has {} attributes, {} declares {}",
                                schema.entity(t).upper,
                                s.attrs,
                                schema.name(),
                                want
                            ),
                        ));
                    }
                }
                if !s.dangling.is_empty() {
                    let shown: Vec<String> = s
                        .dangling
                        .iter()
                        .take(5)
                        .map(|id| format!("#{id}"))
                        .collect();
                    out.push((
                        DiagnosticKind::DanglingReference,
                        Some(inst.id),
                        inst.start,
                        format!(
                            "refers to {} which {} not exist{}",
                            shown.join(", "),
                            if s.dangling.len() == 1 { "does" } else { "do" },
                            if s.dangling.len() > 5 {
                                format!(" (and {} more)", s.dangling.len() - 5)
                            } else {
                                String::new()
                            }
                        ),
                    ));
                }
            }
            (out, seps, counts, max_id)
        })
        .collect();
    let mut problems = Vec::new();
    let total = parts.iter().map(|p| p.1.len()).sum();
    for (p, _, _, _) in &parts {
        problems.extend_from_slice(p);
    }
    let max_id_used = parts.iter().map(|p| p.3).max().unwrap_or(0);
    let per_instance = parts.iter().flat_map(|(_, seps, counts, _)| {
        let mut at = 0usize;
        counts.iter().map(move |&n| {
            let s = &seps[at..at + n as usize];
            at += n as usize;
            (n > 0).then_some(s)
        })
    });
    let args = ArgIndex::from_parts(per_instance, model.instances.len(), total).unwrap_or_default();
    (problems, Structure { args, max_id_used })
}

/// One diagnostic per instance whose bytes are not valid UTF-8.
pub(crate) fn non_utf8(model: &Model) -> Vec<Problem> {
    let bytes = model.bytes();
    let mut out = Vec::new();
    let mut seen = FxHashSet::default();
    let mut pos = 0;
    while pos < bytes.len() {
        match std::str::from_utf8(&bytes[pos..]) {
            Ok(_) => break,
            Err(e) => {
                let bad = pos + e.valid_up_to();
                let at = model.instances.partition_point(|i| i.start <= bad);
                let inst = at
                    .checked_sub(1)
                    .map(|k| &model.instances[k])
                    .filter(|i| bad < i.end());
                if seen.insert(inst.map(|i| i.id)) {
                    out.push((
                        DiagnosticKind::NonUtf8,
                        inst.map(|i| i.id),
                        bad,
                        "bytes that are not UTF-8 (kept unchanged, read as ISO 8859-1)".to_string(),
                    ));
                }
                pos = bad + e.error_len().unwrap_or(1);
            }
        }
    }
    out
}

/// Child -> parent edges: finds every cycle once, as positions in walk order.
fn find_cycles(parent: &FxHashMap<u32, u32>) -> Vec<Vec<u32>> {
    // 0 = unvisited, 1 = on the current walk, 2 = done.
    let mut state: FxHashMap<u32, u8> = FxHashMap::default();
    let mut keys: Vec<u32> = parent.keys().copied().collect();
    keys.sort_unstable();
    let mut cycles = Vec::new();
    for start in keys {
        if state.get(&start).copied().unwrap_or(0) != 0 {
            continue;
        }
        let mut walk = Vec::new();
        let mut cur = start;
        loop {
            match state.get(&cur).copied().unwrap_or(0) {
                0 => {
                    state.insert(cur, 1);
                    walk.push(cur);
                    match parent.get(&cur) {
                        Some(&p) => cur = p,
                        None => break,
                    }
                }
                1 => {
                    let from = walk.iter().position(|&w| w == cur).expect("on walk");
                    cycles.push(walk[from..].to_vec());
                    break;
                }
                _ => break,
            }
        }
        for w in walk {
            state.insert(w, 2);
        }
    }
    cycles
}

fn cycle_problems(
    model: &Model,
    parent: &FxHashMap<u32, u32>,
    kind: DiagnosticKind,
    what: &str,
) -> Vec<Problem> {
    find_cycles(parent)
        .into_iter()
        .map(|cycle| {
            let first = *cycle.iter().min().expect("non-empty cycle");
            let ids: Vec<String> = cycle
                .iter()
                .map(|&p| model.instances[p as usize].id.to_string())
                .collect();
            let inst = &model.instances[first as usize];
            (
                kind,
                Some(inst.id),
                inst.start,
                format!("{what} form a cycle: {}", ids.join(" -> ")),
            )
        })
        .collect()
}

/// Cycles through `IfcLocalPlacement.PlacementRelTo` and through aggregation.
pub(crate) fn cycles(model: &Model) -> Vec<Problem> {
    let mut out = Vec::new();
    let schema = model.schema();
    let pos_of = |id: EntityId| model.entity(id).map(|e| e.position() as u32);

    if let Some(t) = schema.type_by_name("IfcObjectPlacement") {
        let mut parent = FxHashMap::default();
        for p in model.positions_of(t) {
            let e = crate::Entity::new(model, p);
            if let Some(rel) = e
                .attr_index("PlacementRelTo")
                .ok()
                .and_then(|i| e.attr_at(i).ok().flatten())
            {
                if let Some(target) = rel.as_ref_id().and_then(pos_of) {
                    parent.insert(p, target);
                }
            }
        }
        out.extend(cycle_problems(
            model,
            &parent,
            DiagnosticKind::CyclicPlacement,
            "placements",
        ));
    }
    if let Some(t) = schema.type_by_name("IfcRelAggregates") {
        let mut parent = FxHashMap::default();
        for p in model.positions_of(t) {
            let rel = crate::Entity::new(model, p);
            let Some(whole) = rel
                .get("RelatingObject")
                .and_then(|v| v.as_ref_id())
                .and_then(pos_of)
            else {
                continue;
            };
            for part in rel
                .get("RelatedObjects")
                .map(|v| v.refs())
                .unwrap_or_default()
            {
                if let Some(part) = pos_of(part) {
                    parent.entry(part).or_insert(whole);
                }
            }
        }
        out.extend(cycle_problems(
            model,
            &parent,
            DiagnosticKind::CyclicAggregation,
            "aggregations (IfcRelAggregates)",
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_counts_top_level_attributes_and_dangling_refs() {
        let mut seps = Vec::new();
        let s = shape(b"('a,b',(#1,#2),$,#9)", |id| id < 5, &mut seps);
        assert_eq!((s.attrs, s.balanced, s.dangling), (4, true, vec![9]));
        assert_eq!(seps, [0, 6, 14, 16, 19]);
        seps.clear();
        let s = shape(b"( ) ", |_| true, &mut seps);
        assert_eq!((s.attrs, s.balanced), (0, true));
        assert_eq!(seps, [0], "a list without values keeps only its `(`");
        seps.clear();
        assert!(!shape(b"((1,2)", |_| true, &mut seps).balanced);
        assert!(!shape(b"(1))", |_| true, &mut seps).balanced);
        assert!(seps.is_empty(), "unbalanced lists keep no separators");
        let s = shape(
            b"( 'x/*,*/' /* a, comment */ ,\"0,\",IFCLABEL('a,b'))",
            |_| true,
            &mut seps,
        );
        assert_eq!(s.attrs, 3);
        assert_eq!(seps, [0, 28, 33, 49]);
    }

    #[test]
    fn shape_finds_the_first_empty_value_and_only_empty_ones() {
        let empty = |args: &[u8]| shape(args, |_| true, &mut Vec::new()).empty;
        assert_eq!(
            empty(b"(',,',(),( ),IFCLABEL('a,'),/*,,*/$,\",,\",.T.,-1.E-3,#4,*)"),
            None
        );
        assert_eq!(empty(b"($,,$)"), Some((2, true)));
        assert_eq!(empty(b"(,$)"), Some((1, true)));
        assert_eq!(empty(b"($ ,\n )"), Some((2, true)));
        assert_eq!(empty(b"($,(1.,2.),(#1, ,#2),,)"), Some((3, false)));
        assert_eq!(empty(b"((1.,2.,))"), Some((1, false)));
    }

    #[test]
    fn cycles_are_found_once() {
        let parent: FxHashMap<u32, u32> = [(1, 2), (2, 3), (3, 1), (4, 1), (5, 6)]
            .into_iter()
            .collect();
        let c = find_cycles(&parent);
        assert_eq!(c.len(), 1);
        assert_eq!(c[0].len(), 3);
    }
}
