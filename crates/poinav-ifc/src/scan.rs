//! First pass over the DATA section: finds every instance's `#id`, entity type and byte span.
//!
//! The scan jumps between `'`, `;` and `/` with memchr, so it touches little more than the
//! bytes of string literals; attribute contents are checked later, in parallel (`check.rs`).

use rustc_hash::FxHashMap;

use crate::diagnostic::DiagnosticKind;
use crate::error::ReadErrorKind;
use crate::schema::TypeId;
use crate::{EntityId, Schema};

/// Marks an instance whose entity name the schema does not declare.
pub(crate) const UNKNOWN_TYPE: u16 = u16::MAX;

/// One instance line: `#id = TYPE ( args ) ;`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Instance {
    pub(crate) id: EntityId,
    /// Offset of the `#`.
    pub(crate) start: usize,
    /// Bytes from the `#` through the closing `;` (24 bytes an instance, not 40: on a furnished
    /// model of 880,000 short lines this index is as large as a third of the file).
    len: u32,
    /// Bytes from the `#` to the `(` that opens the arguments.
    head: u16,
    pub(crate) ty: u16,
}

impl Instance {
    /// The instance from `start` (`#`) through `end` (just after `;`) whose arguments open at
    /// `args`; `None` when it is 4 GiB long or more, or its `#id = TYPE` head 64 KiB or more.
    pub(crate) fn new(
        id: EntityId,
        start: usize,
        args: usize,
        end: usize,
        ty: u16,
    ) -> Option<Instance> {
        Some(Instance {
            id,
            start,
            len: u32::try_from(end - start).ok()?,
            head: u16::try_from(args - start).ok()?,
            ty,
        })
    }

    /// Offset of the `(` that opens the arguments.
    pub(crate) fn args(&self) -> usize {
        self.start + usize::from(self.head)
    }

    /// Offset just after the closing `;`.
    pub(crate) fn end(&self) -> usize {
        self.start + self.len as usize
    }

    pub(crate) fn type_id(&self) -> Option<TypeId> {
        (self.ty != UNKNOWN_TYPE).then_some(TypeId(self.ty))
    }
}

/// What the scan found.
#[derive(Debug, Default)]
pub(crate) struct Scan {
    pub(crate) instances: Vec<Instance>,
    /// Syntax and unknown-entity problems, with byte offsets (lines are added by the model).
    pub(crate) problems: Vec<(DiagnosticKind, Option<EntityId>, usize, String)>,
    /// Offset of the `ENDSEC` that closes the last DATA section.
    pub(crate) data_end: usize,
}

/// A fatal scan failure: what and at which byte offset, and the instance being read.
pub(crate) type ScanError = (ReadErrorKind, usize, Option<EntityId>);

/// Skips white space and `/* */` comments from `pos`.
pub(crate) fn skip_ws_and_comments(
    bytes: &[u8],
    mut pos: usize,
) -> Result<usize, (ReadErrorKind, usize)> {
    loop {
        while pos < bytes.len() && matches!(bytes[pos], b' ' | b'\t' | b'\r' | b'\n' | b'\x0c') {
            pos += 1;
        }
        if bytes[pos.min(bytes.len())..].starts_with(b"/*") {
            match memchr::memmem::find(&bytes[pos + 2..], b"*/") {
                Some(e) => pos += e + 4,
                None => return Err((ReadErrorKind::UnterminatedComment, pos)),
            }
        } else {
            return Ok(pos);
        }
    }
}

/// Offset of the `;` that ends the record starting at or before `pos`, skipping strings and comments.
pub(crate) fn find_record_end(
    bytes: &[u8],
    mut pos: usize,
) -> Result<usize, (ReadErrorKind, usize)> {
    loop {
        let Some(k) = memchr::memchr3(b'\'', b';', b'/', &bytes[pos.min(bytes.len())..]) else {
            return Err((
                ReadErrorKind::Truncated("the file ends inside an entry (no closing `;`)".into()),
                bytes.len(),
            ));
        };
        let k = pos + k;
        match bytes[k] {
            b';' => return Ok(k),
            b'\'' => match crate::string::literal_end(bytes, k) {
                Some(q) => pos = q + 1,
                None => return Err((ReadErrorKind::UnterminatedString, k)),
            },
            _ => {
                if bytes.get(k + 1) == Some(&b'*') {
                    match memchr::memmem::find(&bytes[k + 2..], b"*/") {
                        Some(e) => pos = k + e + 4,
                        None => return Err((ReadErrorKind::UnterminatedComment, k)),
                    }
                } else {
                    pos = k + 1;
                }
            }
        }
    }
}

fn is_name_byte(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

/// Scans every DATA section after the header ends at `pos`.
pub(crate) fn scan(bytes: &[u8], mut pos: usize, schema: Schema) -> Result<Scan, ScanError> {
    let mut out = Scan {
        instances: Vec::with_capacity(bytes.len() / 80),
        ..Scan::default()
    };
    let mut type_cache: FxHashMap<&[u8], u16> = FxHashMap::default();
    let mut sections = 0;
    let lift = |(k, o): (ReadErrorKind, usize)| (k, o, None);
    loop {
        pos = skip_ws_and_comments(bytes, pos).map_err(lift)?;
        let rest = &bytes[pos..];
        if rest.starts_with(b"DATA") {
            pos = find_record_end(bytes, pos + 4).map_err(lift)? + 1;
            scan_section(bytes, &mut pos, schema, &mut out, &mut type_cache)?;
            sections += 1;
        } else if rest.starts_with(b"END-ISO-10303-21") {
            if sections == 0 {
                return Err((
                    ReadErrorKind::Syntax(
                        "the file has no DATA section: `END-ISO-10303-21;` follows the header"
                            .into(),
                    ),
                    pos,
                    None,
                ));
            }
            break;
        } else if rest.is_empty() && sections > 0 {
            out.problems.push((
                DiagnosticKind::Truncated,
                None,
                pos,
                "the file does not end with `END-ISO-10303-21;`: it may have been cut short after its DATA section".into(),
            ));
            break;
        } else if rest.is_empty() {
            return Err((
                ReadErrorKind::Truncated("the file ends before its DATA section".into()),
                pos,
                None,
            ));
        } else if sections == 0 {
            return Err((
                ReadErrorKind::Syntax("expected `DATA;` after the HEADER section".into()),
                pos,
                None,
            ));
        } else {
            // Trailing junk after the data: report it and stop reading.
            out.problems.push((
                DiagnosticKind::Syntax,
                None,
                pos,
                "unexpected text after the DATA section".into(),
            ));
            break;
        }
    }
    // The capacity guessed from the file size may be up to twice what was used.
    out.instances.shrink_to_fit();
    Ok(out)
}

fn scan_section<'b>(
    bytes: &'b [u8],
    pos: &mut usize,
    schema: Schema,
    out: &mut Scan,
    type_cache: &mut FxHashMap<&'b [u8], u16>,
) -> Result<(), ScanError> {
    let mut upper = Vec::new();
    loop {
        let last_id = out.instances.last().map(|i| i.id);
        let p = skip_ws_and_comments(bytes, *pos).map_err(|(k, o)| (k, o, last_id))?;
        if p >= bytes.len() {
            return Err((
                ReadErrorKind::Truncated("the DATA section is not closed by `ENDSEC;`".into()),
                p,
                last_id,
            ));
        }
        if bytes[p] != b'#' {
            let end = find_record_end(bytes, p).map_err(|(k, o)| (k, o, last_id))?;
            if bytes[p..].starts_with(b"ENDSEC") {
                out.data_end = p;
                *pos = end + 1;
                return Ok(());
            }
            out.problems.push(not_an_instance(p, end, last_id));
            *pos = end + 1;
            continue;
        }
        let start = p;
        let mut i = p + 1;
        let digits_start = i;
        while i < bytes.len() && bytes[i].is_ascii_digit() {
            i += 1;
        }
        let id = std::str::from_utf8(&bytes[digits_start..i])
            .ok()
            .and_then(|s| s.parse::<u64>().ok());
        let id_for_errors = id.map(EntityId).or(last_id);
        let end = match find_record_end(bytes, i) {
            Ok(end) => end,
            // A string that never closes damages its own instance only: it ends at the last
            // `;` before the next line that starts an instance (the check reports it).
            Err((ReadErrorKind::UnterminatedString, k)) => end_of_damaged_record(bytes, start)
                .ok_or((ReadErrorKind::UnterminatedString, k, id_for_errors))?,
            Err((k, o)) => return Err((k, o, id_for_errors)),
        };
        *pos = end + 1;
        let Some(id) = id else {
            out.problems.push((
                DiagnosticKind::Syntax,
                None,
                start,
                "instance id is missing or out of range; instance skipped".into(),
            ));
            continue;
        };
        let id = EntityId(id);
        i = skip_ws(bytes, i);
        if bytes.get(i) != Some(&b'=') {
            out.problems.push((
                DiagnosticKind::Syntax,
                Some(id),
                start,
                "expected `=` after the instance id; instance skipped".into(),
            ));
            continue;
        }
        i = skip_ws(bytes, i + 1);
        let name_start = i;
        while i < end && is_name_byte(bytes[i]) {
            i += 1;
        }
        let name = &bytes[name_start..i];
        i = skip_ws(bytes, i);
        if bytes.get(i) != Some(&b'(') {
            out.problems.push((
                DiagnosticKind::Syntax,
                Some(id),
                start,
                "expected `TYPE(` after `=`; instance skipped".into(),
            ));
            continue;
        }
        let ty = if name.is_empty() {
            // A complex (multi-leaf) instance `#1=(A()B());`: kept as bytes, not typed.
            out.problems.push((
                DiagnosticKind::UnknownEntity,
                Some(id),
                start,
                "complex entity instance is kept but not interpreted".into(),
            ));
            UNKNOWN_TYPE
        } else if let Some(&t) = type_cache.get(name) {
            t
        } else {
            upper.clear();
            upper.extend(name.iter().map(u8::to_ascii_uppercase));
            let t = schema.type_by_upper(&upper).map_or(UNKNOWN_TYPE, |t| t.0);
            type_cache.insert(name, t);
            t
        };
        if ty == UNKNOWN_TYPE && !name.is_empty() {
            out.problems.push((
                DiagnosticKind::UnknownEntity,
                Some(id),
                start,
                format!(
                    "entity `{}` is not part of {}; instance kept but not interpreted",
                    String::from_utf8_lossy(name),
                    schema.name()
                ),
            ));
        }
        match Instance::new(id, start, i, end + 1, ty) {
            Some(instance) => out.instances.push(instance),
            None => out.problems.push((
                DiagnosticKind::Syntax,
                Some(id),
                start,
                "the instance is 4 GiB long or more, or its `#id = TYPE` 64 KiB or more; instance skipped".into(),
            )),
        }
    }
}

/// The problem of an entry at `p` (through the `;` at `end`) that does not start with `#`: an
/// empty entry (a second `;` after `last`), or text that is no instance.
#[cold]
fn not_an_instance(
    p: usize,
    end: usize,
    last: Option<EntityId>,
) -> (DiagnosticKind, Option<EntityId>, usize, String) {
    if end != p {
        let message = "expected `#id=` at the start of an instance; skipped to the next `;`";
        return (DiagnosticKind::Syntax, None, p, message.into());
    }
    let message = match last {
        Some(id) => format!("a second `;` (an empty entry) follows {id}; ignored"),
        None => "a `;` with nothing before it (an empty entry); ignored".into(),
    };
    (DiagnosticKind::Syntax, last, p, message)
}

/// For the record starting at `open` in which a string never closes: the last `;` before the
/// next line that starts with `#<digits>=` or `ENDSEC`, when there is one after `open`.
fn end_of_damaged_record(bytes: &[u8], open: usize) -> Option<usize> {
    let mut from = open;
    while let Some(nl) = memchr::memchr(b'\n', &bytes[from..]) {
        let line = skip_ws(bytes, from + nl + 1);
        from = line;
        let starts_record = if bytes[line..].starts_with(b"ENDSEC") {
            true
        } else if bytes.get(line) == Some(&b'#') {
            let digits = bytes[line + 1..]
                .iter()
                .take_while(|c| c.is_ascii_digit())
                .count();
            digits > 0 && bytes.get(skip_ws(bytes, line + 1 + digits)) == Some(&b'=')
        } else {
            false
        };
        if starts_record {
            return memchr::memrchr(b';', &bytes[open..line]).map(|p| open + p);
        }
    }
    None
}

fn skip_ws(bytes: &[u8], mut i: usize) -> usize {
    while i < bytes.len() && matches!(bytes[i], b' ' | b'\t' | b'\r' | b'\n') {
        i += 1;
    }
    i
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_instance_takes_24_bytes_and_a_too_long_head_is_skipped() {
        assert_eq!(std::mem::size_of::<Instance>(), 24);
        let i = Instance::new(EntityId(7), 100, 110, 150, 3).unwrap();
        assert_eq!((i.start, i.args(), i.end()), (100, 110, 150));
        assert!(Instance::new(EntityId(7), 0, 70_000, 70_010, 3).is_none());
        let mut data = b"DATA;\n#1=".to_vec();
        data.extend(std::iter::repeat_n(b' ', 70_000));
        data.extend_from_slice(b"IFCWALL($);\n#2=IFCDOOR($);\nENDSEC;\nEND-ISO-10303-21;");
        let s = scan(&data, 0, Schema::Ifc4).unwrap();
        assert_eq!(s.instances.len(), 1);
        assert_eq!(s.instances[0].id, EntityId(2));
        assert_eq!(s.problems.len(), 1, "{:?}", s.problems);
        assert_eq!(s.problems[0].1, Some(EntityId(1)));
    }

    #[test]
    fn finds_instances_across_strings_comments_and_lines() {
        let data = b"DATA;\n#1=IFCWALL('a;b''c',$);\r\n/* note; 'x */ #2 = IFCDOOR\n('x',\n#1);#3=IFCFOOBAR();\nENDSEC;\nEND-ISO-10303-21;";
        let s = scan(data, 0, Schema::Ifc4).unwrap();
        let ids: Vec<u64> = s.instances.iter().map(|i| i.id.0).collect();
        assert_eq!(ids, [1, 2, 3]);
        assert_eq!(
            &data[s.instances[1].args()..s.instances[1].end()],
            b"('x',\n#1);"
        );
        assert_eq!(s.instances[2].ty, UNKNOWN_TYPE);
        assert_eq!(s.problems.len(), 1);
        assert!(data[s.data_end..].starts_with(b"ENDSEC"));
    }

    #[test]
    fn fatal_scan_errors_name_the_instance() {
        let (kind, _, id) = scan(b"DATA;#1=IFCWALL('abc);", 0, Schema::Ifc4).unwrap_err();
        assert_eq!(
            (kind, id),
            (ReadErrorKind::UnterminatedString, Some(EntityId(1)))
        );
        let (kind, _, id) =
            scan(b"DATA;#1=IFCWALL('abc');#2=IFCWALL(", 0, Schema::Ifc4).unwrap_err();
        assert!(matches!(kind, ReadErrorKind::Truncated(_)));
        assert_eq!(id, Some(EntityId(2)));
        let (kind, _, _) = scan(b"DATA;#1=IFCWALL('abc');", 0, Schema::Ifc4).unwrap_err();
        assert!(matches!(kind, ReadErrorKind::Truncated(_)));
    }

    #[test]
    fn a_string_that_never_closes_damages_its_own_instance_only() {
        let data = b"DATA;\n#1=IFCWALL('abc,$);\n#2=IFCWALL('x',$);\n  #3 = IFCDOOR('y');\nENDSEC;\nEND-ISO-10303-21;";
        let s = scan(data, 0, Schema::Ifc4).unwrap();
        // `#1`'s string would run to the end of the file; it ends at the last `;` before the
        // next line that starts an instance, and the others read as usual.
        let ids: Vec<u64> = s.instances.iter().map(|i| i.id.0).collect();
        assert_eq!(ids, [1, 2, 3]);
        assert_eq!(
            &data[s.instances[0].start..s.instances[0].end()],
            b"#1=IFCWALL('abc,$);"
        );
        assert_eq!(
            &data[s.instances[1].start..s.instances[1].end()],
            b"#2=IFCWALL('x',$);"
        );
        // A `\\S\\'` that would end the string before junk does not: the escape wins.
        let data =
            b"DATA;#1=IFCWALL('a\\S\\'\\X\\91',$);#2=IFCWALL('C:\\S\\',$);ENDSEC;END-ISO-10303-21;";
        let s = scan(data, 0, Schema::Ifc4).unwrap();
        assert_eq!(s.instances.len(), 2);
        assert!(s.problems.is_empty());
    }

    #[test]
    fn damaged_instances_are_skipped_with_a_problem() {
        let s = scan(
            b"DATA;#1 IFCWALL();garbage;#=X();#2=IFCWALL();ENDSEC;END-ISO-10303-21;",
            0,
            Schema::Ifc4,
        )
        .unwrap();
        assert_eq!(s.instances.len(), 1);
        assert_eq!(s.problems.len(), 3);
    }

    #[test]
    fn a_file_without_a_data_section_is_an_error() {
        // Found by fuzzing enrichment: such a file read as an empty model whose DATA section
        // had no position, and the editor's insertion point was out of range.
        let (kind, _, _) = scan(b"END-ISO-10303-21;", 0, Schema::Ifc4).unwrap_err();
        assert!(matches!(kind, ReadErrorKind::Syntax(ref m) if m.contains("no DATA section")));
    }

    #[test]
    fn a_file_without_its_end_line_reads_with_a_truncation_problem() {
        let s = scan(b"DATA;#1=IFCWALL();ENDSEC;\n", 0, Schema::Ifc4).unwrap();
        assert_eq!(s.instances.len(), 1);
        assert_eq!(s.problems.len(), 1);
        assert_eq!(s.problems[0].0, DiagnosticKind::Truncated);
        let s = scan(
            b"DATA;#1=IFCWALL();ENDSEC;END-ISO-10303-21;",
            0,
            Schema::Ifc4,
        )
        .unwrap();
        assert!(s.problems.is_empty());
    }
}
