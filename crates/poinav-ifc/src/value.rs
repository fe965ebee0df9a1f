//! `Value`: one decoded STEP attribute value, parsed lazily from an instance's argument bytes.

use std::borrow::Cow;

use crate::string;
use crate::EntityId;

/// Deepest list nesting the value parser follows before it reports an error.
pub const MAX_NESTING: usize = 64;

/// One attribute value as written in STEP, borrowing from the file's bytes.
#[derive(Debug, Clone, PartialEq)]
pub enum Value<'a> {
    /// `$`: no value.
    Null,
    /// `*`: value derived by the schema.
    Derived,
    /// An integer literal.
    Integer(i64),
    /// A real literal.
    Real(f64),
    /// A string literal, raw bytes between the quotes (decode with [`Value::as_str`]).
    String(&'a [u8]),
    /// A binary literal, raw hex digits between the double quotes.
    Binary(&'a [u8]),
    /// An enumeration or logical literal without its dots: `.T.` is `Enum("T")`.
    Enum(&'a str),
    /// A reference to another instance.
    Ref(EntityId),
    /// A list, set or array.
    List(Vec<Value<'a>>),
    /// A typed value for a SELECT, e.g. `IFCLENGTHMEASURE(0.9)`.
    Typed(&'a str, Box<Value<'a>>),
}

impl<'a> Value<'a> {
    /// True for `$`.
    pub fn is_null(&self) -> bool {
        matches!(self, Value::Null)
    }

    /// The number for integer and real values, looking through a typed wrapper.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Integer(i) => Some(*i as f64),
            Value::Real(r) => Some(*r),
            Value::Typed(_, v) => v.as_f64(),
            _ => None,
        }
    }

    /// The integer of an integer value, looking through a typed wrapper.
    pub fn as_i64(&self) -> Option<i64> {
        match self {
            Value::Integer(i) => Some(*i),
            Value::Typed(_, v) => v.as_i64(),
            _ => None,
        }
    }

    /// The decoded text of a string value (lossless for valid input; see [`string::decode_lossy`]).
    pub fn as_str(&self) -> Option<Cow<'a, str>> {
        match self {
            Value::String(raw) => Some(string::decode_lossy(raw)),
            Value::Typed(_, v) => v.as_str(),
            _ => None,
        }
    }

    /// The enumeration item of an enum value (`.METRE.` is `METRE`).
    pub fn as_enum(&self) -> Option<&'a str> {
        match self {
            Value::Enum(e) => Some(e),
            Value::Typed(_, v) => v.as_enum(),
            _ => None,
        }
    }

    /// The referenced id of a reference value.
    pub fn as_ref_id(&self) -> Option<EntityId> {
        match self {
            Value::Ref(id) => Some(*id),
            _ => None,
        }
    }

    /// The items of a list value.
    pub fn as_list(&self) -> Option<&[Value<'a>]> {
        match self {
            Value::List(items) => Some(items),
            _ => None,
        }
    }

    /// Every reference in this value, lists included, in order.
    pub fn refs(&self) -> Vec<EntityId> {
        let mut out = Vec::new();
        self.collect_refs(&mut out);
        out
    }

    fn collect_refs(&self, out: &mut Vec<EntityId>) {
        match self {
            Value::Ref(id) => out.push(*id),
            Value::List(items) => items.iter().for_each(|v| v.collect_refs(out)),
            Value::Typed(_, v) => v.collect_refs(out),
            _ => {}
        }
    }
}

/// Why an argument list could not be parsed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{message} at byte {offset} of the instance's arguments")]
pub struct ValueError {
    /// Offset within the argument bytes.
    pub offset: usize,
    /// What was expected.
    pub message: &'static str,
}

/// Parses the argument list `( ... )` of an instance into its top-level values.
pub fn parse_args(args: &[u8]) -> Result<Vec<Value<'_>>, ValueError> {
    let mut p = Parser { b: args, pos: 0 };
    p.ws();
    let v = p.list(0)?;
    match v {
        Value::List(items) => Ok(items),
        _ => unreachable!("list() returns lists"),
    }
}

/// Parses only the `index`-th top-level value of the argument list `( ... )`.
/// Returns `Ok(None)` when the list has fewer values.
pub fn parse_arg(args: &[u8], index: usize) -> Result<Option<Value<'_>>, ValueError> {
    let spans = split_args(args)?;
    match spans.get(index) {
        Some(r) => {
            let mut p = Parser {
                b: &args[..r.end],
                pos: r.start,
            };
            Ok(Some(p.value(1)?))
        }
        None => Ok(None),
    }
}

/// Parses the `index`-th top-level value of the argument list `args`, whose top-level
/// separators (`(`, each `,`, `)`) were found beforehand at the offsets `seps`: only that
/// value's bytes are read. `Ok(None)` when the list has fewer values.
pub(crate) fn parse_arg_between<'a>(
    args: &'a [u8],
    seps: &[u32],
    index: usize,
) -> Result<Option<Value<'a>>, ValueError> {
    let (Some(&from), Some(&to)) = (seps.get(index), seps.get(index + 1)) else {
        return Ok(None);
    };
    let (from, to) = (from as usize + 1, to as usize);
    if to > args.len() || from > to {
        return Err(ValueError {
            offset: from.min(args.len()),
            message: "argument list changed after it was indexed",
        });
    }
    let mut p = Parser {
        b: &args[..to],
        pos: from,
    };
    p.ws();
    let v = p.value(1)?;
    p.ws();
    if p.pos != to {
        return Err(p.err(p.pos, "expected `,` or `)`"));
    }
    Ok(Some(v))
}

/// Byte ranges (within `args`) of each top-level value of the argument list `( ... )`,
/// without surrounding white space. Used to rewrite one attribute and keep the others' bytes.
pub fn split_args(args: &[u8]) -> Result<Vec<std::ops::Range<usize>>, ValueError> {
    let mut p = Parser { b: args, pos: 0 };
    p.ws();
    p.expect(b'(')?;
    let mut spans = Vec::new();
    p.ws();
    if p.peek() == Some(b')') {
        return Ok(spans);
    }
    loop {
        p.ws();
        let start = p.pos;
        p.skip_value()?;
        spans.push(start..p.pos);
        p.ws();
        match p.next() {
            Some(b',') => continue,
            Some(b')') => return Ok(spans),
            _ => return Err(p.err(p.pos.saturating_sub(1), "expected `,` or `)`")),
        }
    }
}

struct Parser<'a> {
    b: &'a [u8],
    pos: usize,
}

impl<'a> Parser<'a> {
    fn peek(&self) -> Option<u8> {
        self.b.get(self.pos).copied()
    }

    fn next(&mut self) -> Option<u8> {
        let c = self.peek();
        self.pos += 1;
        c
    }

    fn err(&self, offset: usize, message: &'static str) -> ValueError {
        ValueError { offset, message }
    }

    fn expect(&mut self, c: u8) -> Result<(), ValueError> {
        if self.peek() == Some(c) {
            self.pos += 1;
            Ok(())
        } else {
            Err(self.err(
                self.pos,
                match c {
                    b'(' => "expected `(`",
                    b')' => "expected `)`",
                    _ => "unexpected character",
                },
            ))
        }
    }

    /// Skips white space and `/* */` comments.
    fn ws(&mut self) {
        loop {
            while matches!(self.peek(), Some(b' ' | b'\t' | b'\r' | b'\n')) {
                self.pos += 1;
            }
            if self.b[self.pos.min(self.b.len())..].starts_with(b"/*") {
                match memchr::memmem::find(&self.b[self.pos + 2..], b"*/") {
                    Some(e) => self.pos += e + 4,
                    None => self.pos = self.b.len(),
                }
            } else {
                return;
            }
        }
    }

    fn list(&mut self, depth: usize) -> Result<Value<'a>, ValueError> {
        if depth >= MAX_NESTING {
            return Err(self.err(self.pos, "lists nested too deeply"));
        }
        self.expect(b'(')?;
        let mut items = Vec::new();
        self.ws();
        if self.peek() == Some(b')') {
            self.pos += 1;
            return Ok(Value::List(items));
        }
        loop {
            self.ws();
            items.push(self.value(depth + 1)?);
            self.ws();
            match self.next() {
                Some(b',') => continue,
                Some(b')') => return Ok(Value::List(items)),
                _ => return Err(self.err(self.pos.saturating_sub(1), "expected `,` or `)`")),
            }
        }
    }

    fn string_end(&self, quote: u8) -> Result<usize, ValueError> {
        // The index of the closing quote (see `string::literal_end` for `''` and `\S\'`).
        let end = if quote == b'\'' {
            string::literal_end(self.b, self.pos)
        } else {
            memchr::memchr(quote, &self.b[self.pos + 1..]).map(|q| self.pos + 1 + q)
        };
        end.ok_or_else(|| self.err(self.pos, "unterminated string"))
    }

    fn value(&mut self, depth: usize) -> Result<Value<'a>, ValueError> {
        let start = self.pos;
        match self.peek() {
            Some(b'$') => {
                self.pos += 1;
                Ok(Value::Null)
            }
            Some(b'*') => {
                self.pos += 1;
                Ok(Value::Derived)
            }
            Some(q @ (b'\'' | b'"')) => {
                let end = self.string_end(q)?;
                let raw = &self.b[start + 1..end];
                self.pos = end + 1;
                Ok(if q == b'\'' {
                    Value::String(raw)
                } else {
                    Value::Binary(raw)
                })
            }
            Some(b'.') => {
                let end = memchr::memchr(b'.', &self.b[start + 1..])
                    .ok_or_else(|| self.err(start, "unterminated enumeration"))?;
                let item = &self.b[start + 1..start + 1 + end];
                if !item.iter().all(|c| c.is_ascii_alphanumeric() || *c == b'_') {
                    return Err(self.err(start, "invalid enumeration"));
                }
                self.pos = start + end + 2;
                Ok(Value::Enum(
                    std::str::from_utf8(item).expect("checked ASCII"),
                ))
            }
            Some(b'#') => {
                self.pos += 1;
                let n = self.digits();
                if n == 0 {
                    return Err(self.err(start, "expected digits after `#`"));
                }
                let text = std::str::from_utf8(&self.b[start + 1..self.pos]).expect("digits");
                text.parse()
                    .map(|id| Value::Ref(EntityId(id)))
                    .map_err(|_| self.err(start, "instance id out of range"))
            }
            Some(b'(') => self.list(depth),
            Some(c) if c.is_ascii_alphabetic() => {
                while matches!(self.peek(), Some(c) if c.is_ascii_alphanumeric() || c == b'_') {
                    self.pos += 1;
                }
                let name = std::str::from_utf8(&self.b[start..self.pos]).expect("checked ASCII");
                self.ws();
                self.expect(b'(')?;
                self.ws();
                let inner = self.value(depth + 1)?;
                self.ws();
                self.expect(b')')?;
                Ok(Value::Typed(name, Box::new(inner)))
            }
            Some(b'+' | b'-' | b'0'..=b'9') => self.number(),
            _ => Err(self.err(start, "expected a value")),
        }
    }

    fn digits(&mut self) -> usize {
        let s = self.pos;
        while matches!(self.peek(), Some(b'0'..=b'9')) {
            self.pos += 1;
        }
        self.pos - s
    }

    fn number(&mut self) -> Result<Value<'a>, ValueError> {
        let start = self.pos;
        if matches!(self.peek(), Some(b'+' | b'-')) {
            self.pos += 1;
        }
        let int_digits = self.digits();
        let mut real = false;
        if self.peek() == Some(b'.') {
            real = true;
            self.pos += 1;
            self.digits();
        }
        if matches!(self.peek(), Some(b'E' | b'e')) {
            real = true;
            self.pos += 1;
            if matches!(self.peek(), Some(b'+' | b'-')) {
                self.pos += 1;
            }
            if self.digits() == 0 {
                return Err(self.err(start, "expected exponent digits"));
            }
        }
        if int_digits == 0 {
            return Err(self.err(start, "expected digits"));
        }
        let text = std::str::from_utf8(&self.b[start..self.pos]).expect("checked ASCII");
        if real {
            // `1.` and `1.E3` are valid STEP reals; Rust's parser accepts both forms.
            text.parse()
                .map(Value::Real)
                .map_err(|_| self.err(start, "invalid real"))
        } else {
            match text.parse() {
                Ok(i) => Ok(Value::Integer(i)),
                Err(_) => text
                    .parse()
                    .map(Value::Real)
                    .map_err(|_| self.err(start, "invalid integer")),
            }
        }
    }

    /// Skips one value without building it (for [`split_args`]). Lists are skipped by counting
    /// parentheses, without recursion, so a deeply nested attribute cannot hide its neighbours.
    fn skip_value(&mut self) -> Result<(), ValueError> {
        match self.peek() {
            Some(q @ (b'\'' | b'"')) => {
                self.pos = self.string_end(q)? + 1;
                Ok(())
            }
            Some(b'(') => self.skip_balanced(),
            Some(c) if c.is_ascii_alphabetic() => {
                while matches!(self.peek(), Some(c) if c.is_ascii_alphanumeric() || c == b'_') {
                    self.pos += 1;
                }
                self.ws();
                if self.peek() != Some(b'(') {
                    return Err(self.err(self.pos, "expected `(`"));
                }
                self.skip_balanced()
            }
            _ => self.value(0).map(|_| ()),
        }
    }

    fn skip_balanced(&mut self) -> Result<(), ValueError> {
        let start = self.pos;
        let mut depth = 0usize;
        loop {
            match self.peek() {
                None => return Err(self.err(start, "unbalanced parentheses")),
                Some(q @ (b'\'' | b'"')) => {
                    self.pos = self.string_end(q)? + 1;
                    continue;
                }
                Some(b'(') => depth += 1,
                Some(b')') => {
                    depth -= 1;
                    if depth == 0 {
                        self.pos += 1;
                        return Ok(());
                    }
                }
                _ => {}
            }
            self.pos += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_every_value_form() {
        let args =
            b"('2N3o',#1,'It''s',$,*,.T.,(#2,#3),IFCLENGTHMEASURE(0.9),2.134,-5,1.E-3,\"0FF\",())";
        let v = parse_args(args).unwrap();
        assert_eq!(v.len(), 13);
        assert_eq!(v[0].as_str().unwrap(), "2N3o");
        assert_eq!(v[1], Value::Ref(EntityId(1)));
        assert_eq!(v[2].as_str().unwrap(), "It's");
        assert!(v[3].is_null());
        assert_eq!(v[4], Value::Derived);
        assert_eq!(v[5].as_enum(), Some("T"));
        assert_eq!(v[6].refs(), vec![EntityId(2), EntityId(3)]);
        assert_eq!(
            v[7],
            Value::Typed("IFCLENGTHMEASURE", Box::new(Value::Real(0.9)))
        );
        assert_eq!(v[8].as_f64(), Some(2.134));
        assert_eq!(v[9].as_i64(), Some(-5));
        assert_eq!(v[10].as_f64(), Some(0.001));
        assert_eq!(v[11], Value::Binary(b"0FF"));
        assert_eq!(v[12], Value::List(vec![]));
    }

    #[test]
    fn single_argument_and_spans_skip_strings_with_separators() {
        let args = b"( 'a,b)' , #7 ,(1,(2,3)) )";
        assert_eq!(parse_arg(args, 1).unwrap(), Some(Value::Ref(EntityId(7))));
        assert_eq!(parse_arg(args, 3).unwrap(), None);
        let spans = split_args(args).unwrap();
        let texts: Vec<&[u8]> = spans.iter().map(|r| &args[r.clone()]).collect();
        assert_eq!(texts, vec![&b"'a,b)'"[..], b"#7", b"(1,(2,3))"]);
    }

    #[test]
    fn malformed_arguments_are_errors_not_panics() {
        for bad in [
            &b"(1,"[..],
            b"('abc)",
            b"(#)",
            b"(1 2)",
            b"(.X)",
            b"(IFCLABEL('a')",
            b"",
            b"(1.E)",
        ] {
            assert!(
                parse_args(bad).is_err(),
                "{:?}",
                String::from_utf8_lossy(bad)
            );
        }
        let deep = format!("(1,{}{},2)", "(".repeat(100_000), ")".repeat(100_000));
        assert!(parse_args(deep.as_bytes()).is_err());
        // Splitting does not recurse: the neighbours of a too-deep attribute stay readable.
        assert_eq!(split_args(deep.as_bytes()).unwrap().len(), 3);
        assert_eq!(
            parse_arg(deep.as_bytes(), 2).unwrap(),
            Some(Value::Integer(2))
        );
        assert!(parse_arg(deep.as_bytes(), 1).is_err());
    }
}
