//! `Entity`: a view of one instance with schema-aware access by attribute name.

use std::fmt;

use crate::model::Model;
use crate::schema::TypeId;
use crate::value::{self, Value, ValueError};
use crate::EntityId;

/// Why an attribute could not be read.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum AttrError {
    /// The entity (or its schema) has no attribute of that name.
    #[error("{id}: {ty} has no attribute `{name}`")]
    UnknownAttribute {
        id: EntityId,
        ty: String,
        name: String,
    },
    /// The instance's entity type is not in the schema, so names cannot be resolved.
    #[error("{id}: entity `{ty}` is not in the schema")]
    UnknownType { id: EntityId, ty: String },
    /// The instance's arguments could not be parsed.
    #[error("line {line}: {id}: {error}")]
    Malformed {
        id: EntityId,
        line: usize,
        error: ValueError,
    },
}

/// One instance of a [`Model`]. Cheap to copy; decodes attributes on demand.
#[derive(Clone, Copy)]
pub struct Entity<'m> {
    model: &'m Model,
    pos: u32,
}

impl fmt::Debug for Entity<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}={}", self.id(), self.type_name())
    }
}

impl PartialEq for Entity<'_> {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self.model, other.model) && self.pos == other.pos
    }
}

impl Eq for Entity<'_> {}

impl<'m> Entity<'m> {
    pub(crate) fn new(model: &'m Model, pos: u32) -> Entity<'m> {
        Entity { model, pos }
    }

    fn inst(&self) -> &'m crate::scan::Instance {
        &self.model.instances[self.pos as usize]
    }

    /// The model this instance belongs to.
    pub fn model(&self) -> &'m Model {
        self.model
    }

    /// Position in file order.
    pub fn position(&self) -> usize {
        self.pos as usize
    }

    /// The instance's `#id`.
    pub fn id(&self) -> EntityId {
        self.inst().id
    }

    /// The schema type, or `None` for an entity the schema does not declare.
    pub fn type_id(&self) -> Option<TypeId> {
        self.inst().type_id()
    }

    /// The entity name in schema spelling (`IfcWallStandardCase`), or as written when unknown.
    pub fn type_name(&self) -> &'m str {
        match self.type_id() {
            Some(t) => self.model.schema().entity(t).name,
            None => {
                let inst = self.inst();
                let head = &self.model.bytes()[inst.start..inst.args()];
                let name = head.split(|&b| b == b'=').nth(1).unwrap_or(b"");
                std::str::from_utf8(name).unwrap_or("?").trim()
            }
        }
    }

    /// True when the instance is of entity `name` or a subtype (`IfcWallStandardCase` is an `IfcWall`).
    pub fn is_a(&self, name: &str) -> bool {
        let schema = self.model.schema();
        match (self.type_id(), schema.type_by_name(name)) {
            (Some(t), Some(a)) => schema.is_subtype_of(t, a),
            _ => false,
        }
    }

    /// The instance exactly as written, from `#` to `;`.
    pub fn raw(&self) -> &'m [u8] {
        let inst = self.inst();
        &self.model.bytes()[inst.start..inst.end()]
    }

    /// The argument list `( ... )` as written.
    pub fn raw_args(&self) -> &'m [u8] {
        let inst = self.inst();
        let b = &self.model.bytes()[inst.args()..inst.end() - 1];
        let trimmed = b
            .iter()
            .rposition(|c| !c.is_ascii_whitespace())
            .map_or(0, |p| p + 1);
        &b[..trimmed]
    }

    /// Byte offset of the instance in the file.
    pub fn offset(&self) -> usize {
        self.inst().start
    }

    /// 1-based line of the instance in the file.
    pub fn line(&self) -> usize {
        self.model.line_at(self.inst().start)
    }

    fn malformed(&self, error: ValueError) -> AttrError {
        AttrError::Malformed {
            id: self.id(),
            line: self.line(),
            error,
        }
    }

    /// All attribute values in STEP order.
    pub fn args(&self) -> Result<Vec<Value<'m>>, AttrError> {
        value::parse_args(self.raw_args()).map_err(|e| self.malformed(e))
    }

    /// The attribute at STEP position `index` (`Ok(None)` when the instance has fewer).
    pub fn attr_at(&self, index: usize) -> Result<Option<Value<'m>>, AttrError> {
        let args = self.raw_args();
        match self.model.arg_separators(self.position()) {
            Some(seps) => value::parse_arg_between(args, seps, index),
            None => value::parse_arg(args, index),
        }
        .map_err(|e| self.malformed(e))
    }

    /// STEP position of attribute `name` for this instance's type.
    pub fn attr_index(&self, name: &str) -> Result<usize, AttrError> {
        let Some(t) = self.type_id() else {
            return Err(AttrError::UnknownType {
                id: self.id(),
                ty: self.type_name().to_string(),
            });
        };
        self.model
            .schema()
            .attribute_index(t, name)
            .ok_or_else(|| AttrError::UnknownAttribute {
                id: self.id(),
                ty: self.type_name().to_string(),
                name: name.to_string(),
            })
    }

    /// The attribute called `name` (schema spelling, e.g. `OverallWidth`), with errors.
    /// A value missing from a short instance reads as [`Value::Null`].
    pub fn attr(&self, name: &str) -> Result<Value<'m>, AttrError> {
        let index = self.attr_index(name)?;
        Ok(self.attr_at(index)?.unwrap_or(Value::Null))
    }

    /// The attribute called `name`, or `None` when it is `$`, unknown or unreadable.
    pub fn get(&self, name: &str) -> Option<Value<'m>> {
        self.attr(name).ok().filter(|v| !v.is_null())
    }

    /// The referenced instance in attribute `name`.
    pub fn get_ref(&self, name: &str) -> Option<Entity<'m>> {
        self.get(name)
            .and_then(|v| v.as_ref_id())
            .and_then(|id| self.model.entity(id))
    }

    /// The referenced instances in list attribute `name` (dangling references are skipped).
    pub fn get_refs(&self, name: &str) -> Vec<Entity<'m>> {
        self.get(name)
            .map(|v| v.refs())
            .unwrap_or_default()
            .into_iter()
            .filter_map(|id| self.model.entity(id))
            .collect()
    }

    /// The decoded text of string attribute `name`.
    pub fn get_str(&self, name: &str) -> Option<String> {
        self.get(name)
            .and_then(|v| v.as_str().map(|s| s.into_owned()))
    }

    /// The number in attribute `name`.
    pub fn get_f64(&self, name: &str) -> Option<f64> {
        self.get(name).and_then(|v| v.as_f64())
    }

    /// `GlobalId`, for rooted entities.
    pub fn global_id(&self) -> Option<String> {
        self.get_str("GlobalId")
    }

    /// `Name`, where the entity has one.
    pub fn name(&self) -> Option<String> {
        self.get_str("Name")
    }

    /// The instances that refer to this one through the inverse relation `name`
    /// (e.g. `IsDefinedBy`, `ContainedInStructure`, `HasOpenings`), in file order.
    pub fn inverse(&self, name: &str) -> Vec<Entity<'m>> {
        let schema = self.model.schema();
        let Some(t) = self.type_id() else {
            return Vec::new();
        };
        let Some((def, rel)) = schema.inverse(t, name) else {
            return Vec::new();
        };
        let Some(attr) = schema.attribute_index(rel, def.attribute) else {
            return Vec::new();
        };
        let index = self.model.inverse_index(rel, attr);
        index
            .get(&self.id())
            .map(|v| v.iter().map(|&p| Entity::new(self.model, p)).collect())
            .unwrap_or_default()
    }
}
