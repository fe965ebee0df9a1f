//! The STEP HEADER section: `FILE_DESCRIPTION`, `FILE_NAME` and `FILE_SCHEMA`.

use std::ops::Range;

use crate::check::Problem;
use crate::diagnostic::DiagnosticKind;
use crate::error::ReadErrorKind;
use crate::scan::{find_record_end, skip_ws_and_comments};
use crate::value::{parse_args, Value};
use crate::Schema;

/// What the header says, with byte ranges into the file for lossless editing.
#[derive(Debug, Clone)]
pub struct Header {
    /// The schema identifier exactly as written, e.g. `IFC4X3_ADD2`.
    pub schema_identifier: String,
    /// The schema poinav reads the file with.
    pub schema: Schema,
    /// Byte range of the `FILE_NAME(...)` argument list, parentheses included.
    pub file_name_args: Option<Range<usize>>,
    /// Offset just after the header's `ENDSEC;`.
    pub end: usize,
}

/// A header failure: what and where (byte offset).
pub(crate) type HeaderError = (ReadErrorKind, usize);

/// The header entries ISO 10303-21 declares, with their parameter counts.
const ENTRIES: [(&[u8], usize); 3] = [
    (b"FILE_DESCRIPTION", 2),
    (b"FILE_NAME", 7),
    (b"FILE_SCHEMA", 1),
];

/// Reads the header; also returns its readable defects (a header entry whose parameters cannot
/// be read, or that has more or fewer than ISO 10303-21 declares) as problems at byte offsets.
pub(crate) fn parse(bytes: &[u8]) -> Result<(Header, Vec<Problem>), HeaderError> {
    let mut pos = 0;
    if bytes.starts_with(b"\xEF\xBB\xBF") {
        pos = 3;
    }
    pos = skip_ws_and_comments(bytes, pos)?;
    if pos >= bytes.len() {
        return Err((ReadErrorKind::Empty, 0));
    }
    if !bytes[pos..].starts_with(b"ISO-10303-21") {
        return Err((ReadErrorKind::NotStep, pos));
    }
    pos = skip_ws_and_comments(bytes, pos + 12)?;
    if bytes.get(pos) != Some(&b';') {
        return Err((ReadErrorKind::NotStep, pos));
    }
    pos = skip_ws_and_comments(bytes, pos + 1)?;
    if !bytes[pos..].starts_with(b"HEADER") {
        return Err((ReadErrorKind::BadHeader("expected `HEADER;`".into()), pos));
    }
    pos = skip_ws_and_comments(bytes, pos + 6)?;
    if bytes.get(pos) != Some(&b';') {
        return Err((
            ReadErrorKind::BadHeader("expected `;` after HEADER".into()),
            pos,
        ));
    }
    pos += 1;
    let mut schema_args = None;
    let mut file_name_args = None;
    let mut problems = Vec::new();
    loop {
        pos = skip_ws_and_comments(bytes, pos)?;
        if pos >= bytes.len() {
            return Err((
                ReadErrorKind::Truncated("the HEADER section is not closed by `ENDSEC;`".into()),
                pos,
            ));
        }
        let kw_start = pos;
        while pos < bytes.len()
            && (bytes[pos].is_ascii_alphanumeric() || bytes[pos] == b'_' || bytes[pos] == b'-')
        {
            pos += 1;
        }
        let keyword = &bytes[kw_start..pos];
        if keyword.is_empty() {
            return Err((
                ReadErrorKind::BadHeader("expected a header entry or `ENDSEC;`".into()),
                kw_start,
            ));
        }
        let end = find_record_end(bytes, pos)?;
        if keyword == b"ENDSEC" {
            pos = end + 1;
            break;
        }
        let args_start = skip_ws_and_comments(bytes, pos)?;
        let args = args_start..end;
        if let Some(&(name, want)) = ENTRIES.iter().find(|(k, _)| *k == keyword) {
            let name = std::str::from_utf8(name).expect("ASCII");
            let problem = match parse_args(&bytes[trim_end(bytes, args.clone())]) {
                Ok(values) if values.len() == want => None,
                Ok(values) => Some((
                    DiagnosticKind::WrongAttributeCount,
                    format!(
                        "header entry {name} has {} parameter{}, ISO 10303-21 declares {want}",
                        values.len(),
                        if values.len() == 1 { "" } else { "s" }
                    ),
                )),
                Err(e) => Some((
                    DiagnosticKind::Syntax,
                    format!(
                        "header entry {name} cannot be read: {} at byte {} of its parameters",
                        e.message, e.offset
                    ),
                )),
            };
            if let Some((kind, message)) = problem {
                problems.push((kind, None, kw_start, message));
            }
        }
        match keyword {
            b"FILE_SCHEMA" => schema_args = Some(args),
            b"FILE_NAME" => file_name_args = Some(trim_end(bytes, args)),
            _ => {}
        }
        pos = end + 1;
    }
    let Some(schema_args) = schema_args else {
        return Err((ReadErrorKind::BadHeader("no FILE_SCHEMA entry".into()), pos));
    };
    let values = parse_args(&bytes[trim_end(bytes, schema_args.clone())]).map_err(|e| {
        (
            ReadErrorKind::BadHeader(format!("FILE_SCHEMA: {e}")),
            schema_args.start,
        )
    })?;
    let identifier = match values.first() {
        Some(Value::List(items)) => items
            .first()
            .and_then(Value::as_str)
            .map(|s| s.into_owned()),
        _ => None,
    }
    .ok_or_else(|| {
        (
            ReadErrorKind::BadHeader("FILE_SCHEMA names no schema".into()),
            schema_args.start,
        )
    })?;
    let (schema, _) = Schema::from_identifier(&identifier).ok_or_else(|| {
        (
            ReadErrorKind::UnknownSchema(identifier.clone()),
            schema_args.start,
        )
    })?;
    let header = Header {
        schema_identifier: identifier,
        schema,
        file_name_args,
        end: pos,
    };
    Ok((header, problems))
}

fn trim_end(bytes: &[u8], r: Range<usize>) -> Range<usize> {
    let mut end = r.end;
    while end > r.start && bytes[end - 1].is_ascii_whitespace() {
        end -= 1;
    }
    r.start..end
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_schema_and_file_name_span() {
        let text = b"ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('x;y'),'2;1');\nFILE_NAME('a.ifc','2020-01-01T00:00:00',(''),(''),'','','');\nFILE_SCHEMA (('IFC4X3_ADD2'));\nENDSEC;\nDATA;";
        let (h, problems) = parse(text).unwrap();
        assert!(problems.is_empty(), "{problems:?}");
        assert_eq!(h.schema, Schema::Ifc4x3Add2);
        assert_eq!(h.schema_identifier, "IFC4X3_ADD2");
        assert!(text[h.file_name_args.unwrap()].starts_with(b"('a.ifc'"));
        assert!(text[h.end..].starts_with(b"\nDATA;"));
    }

    #[test]
    fn rejects_what_is_not_a_step_file() {
        assert_eq!(parse(b"  \n").unwrap_err().0, ReadErrorKind::Empty);
        assert_eq!(
            parse(b"\x00\x01garbage").unwrap_err().0,
            ReadErrorKind::NotStep
        );
        assert!(matches!(
            parse(b"ISO-10303-21;\nDATA;").unwrap_err().0,
            ReadErrorKind::BadHeader(_)
        ));
        assert!(matches!(
            parse(b"ISO-10303-21;HEADER;FILE_SCHEMA(('IFC2X2_FINAL'));ENDSEC;").unwrap_err().0,
            ReadErrorKind::UnknownSchema(s) if s == "IFC2X2_FINAL"
        ));
        assert!(matches!(
            parse(b"ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));")
                .unwrap_err()
                .0,
            ReadErrorKind::Truncated(_)
        ));
    }
}
