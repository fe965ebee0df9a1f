//! `Diagnostic`: a damaged part of an otherwise readable model, named by line and `#id`.

use std::fmt;

use crate::EntityId;

/// The kind of damage found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum DiagnosticKind {
    /// A `#ref` points to an instance that does not exist.
    DanglingReference,
    /// Two instances share one `#id`; the first is kept.
    DuplicateId,
    /// An instance has more or fewer attributes than its schema declares (or a header entry
    /// more or fewer parameters than ISO 10303-21 declares).
    WrongAttributeCount,
    /// An instance names an entity its schema does not declare.
    UnknownEntity,
    /// Text breaks the STEP syntax: an entry that could not be parsed and was skipped, an empty
    /// value (`,,`), a stray `;`, the instance name `#0`.
    Syntax,
    /// Placements refer to each other in a loop.
    CyclicPlacement,
    /// Aggregation (decomposition) refers back to itself.
    CyclicAggregation,
    /// A string holds bytes that are not UTF-8 (kept as they are, read as ISO 8859-1).
    NonUtf8,
    /// The schema identifier is a tolerated variant, not the exact release.
    SchemaVariant,
    /// No length unit is declared; metres are assumed.
    MissingUnit,
    /// An attribute value has the wrong form for its use (e.g. text where a number belongs).
    BadValue,
    /// More diagnostics of one kind than are kept; the rest are counted.
    Truncated,
}

impl DiagnosticKind {
    /// A short stable name (`dangling-reference`), used in JSON output.
    pub fn code(self) -> &'static str {
        match self {
            DiagnosticKind::DanglingReference => "dangling-reference",
            DiagnosticKind::DuplicateId => "duplicate-id",
            DiagnosticKind::WrongAttributeCount => "wrong-attribute-count",
            DiagnosticKind::UnknownEntity => "unknown-entity",
            DiagnosticKind::Syntax => "syntax",
            DiagnosticKind::CyclicPlacement => "cyclic-placement",
            DiagnosticKind::CyclicAggregation => "cyclic-aggregation",
            DiagnosticKind::NonUtf8 => "non-utf8",
            DiagnosticKind::SchemaVariant => "schema-variant",
            DiagnosticKind::MissingUnit => "missing-unit",
            DiagnosticKind::BadValue => "bad-value",
            DiagnosticKind::Truncated => "truncated",
        }
    }
}

/// One damaged part of a model. The rest of the model is still read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnostic {
    /// What kind of damage.
    pub kind: DiagnosticKind,
    /// The instance concerned, when there is one.
    pub id: Option<EntityId>,
    /// 1-based line in the file, when known.
    pub line: Option<usize>,
    /// Human-readable explanation.
    pub message: String,
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(line) = self.line {
            write!(f, "line {line}: ")?;
        }
        if let Some(id) = self.id {
            write!(f, "{id}: ")?;
        }
        write!(f, "{} ({})", self.message, self.kind.code())
    }
}
