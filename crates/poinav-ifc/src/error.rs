//! `ReadError`: why a file could not be read at all, with file, line and `#id`.

use std::fmt;
use std::path::PathBuf;

use crate::EntityId;

/// What made a file unreadable.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ReadErrorKind {
    /// The operating system refused to read the file.
    Io(String),
    /// The file has no bytes (or only white space).
    Empty,
    /// The file does not start with `ISO-10303-21;`.
    NotStep,
    /// The HEADER section is missing or malformed.
    BadHeader(String),
    /// `FILE_SCHEMA` names a schema poinav does not read.
    UnknownSchema(String),
    /// A string literal has no closing quote.
    UnterminatedString,
    /// A comment has no closing `*/`.
    UnterminatedComment,
    /// The file ends before the DATA section is closed by `ENDSEC;`.
    Truncated(String),
    /// Text that belongs to no section where a section keyword is required.
    Syntax(String),
}

impl fmt::Display for ReadErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReadErrorKind::Io(e) => write!(f, "cannot read file: {e}"),
            ReadErrorKind::Empty => f.write_str("file is empty"),
            ReadErrorKind::NotStep => {
                f.write_str("not an IFC/STEP file: it must start with `ISO-10303-21;`")
            }
            ReadErrorKind::BadHeader(m) => write!(f, "malformed HEADER section: {m}"),
            ReadErrorKind::UnknownSchema(s) => write!(
                f,
                "unknown schema `{s}`: poinav reads IFC2X3, IFC4 and IFC4X3_ADD2 (and IFC4 and IFC4X3 release candidates)"
            ),
            ReadErrorKind::UnterminatedString => f.write_str("string literal is never closed"),
            ReadErrorKind::UnterminatedComment => f.write_str("comment is never closed"),
            ReadErrorKind::Truncated(m) => write!(f, "file is truncated: {m}"),
            ReadErrorKind::Syntax(m) => write!(f, "syntax error: {m}"),
        }
    }
}

/// A file could not be read. Displays as `file:line: #id: message`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub struct ReadError {
    /// The file as the caller named it.
    pub file: PathBuf,
    /// 1-based line where the problem was found, when known.
    pub line: Option<usize>,
    /// The instance being read, when known.
    pub id: Option<EntityId>,
    /// What went wrong.
    pub kind: ReadErrorKind,
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
        }
        if let Some(id) = self.id {
            write!(f, ": {id}")?;
        }
        write!(f, ": {}", self.kind)
    }
}
