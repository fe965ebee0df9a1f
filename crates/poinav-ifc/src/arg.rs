//! `Arg`: a value to write into a STEP instance, encoded exactly as ISO 10303-21 requires.

use std::fmt::Write as _;

use crate::string;
use crate::EntityId;

/// A value that has no STEP form.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ArgError {
    /// A real that is NaN or infinite.
    #[error("{0} is not a finite number")]
    NotFinite(f64),
    /// An enumeration item with characters STEP does not allow, or none.
    #[error("`{0}` is not a valid enumeration item")]
    BadEnum(String),
    /// A type name with characters STEP does not allow, or none.
    #[error("`{0}` is not a valid type name")]
    BadTypeName(String),
}

/// A value for a new or changed attribute.
#[derive(Debug, Clone, PartialEq)]
pub enum Arg {
    /// `$`
    Null,
    /// `*`
    Derived,
    /// `#id`
    Ref(EntityId),
    /// An integer.
    Integer(i64),
    /// A real; must be finite.
    Real(f64),
    /// A string, encoded with STEP escapes.
    Text(String),
    /// An enumeration item, written `.ITEM.`.
    Enum(String),
    /// A boolean, written `.T.` / `.F.`.
    Bool(bool),
    /// A typed value such as `IFCLABEL('x')`; the type name is written upper-case.
    Typed(String, Box<Arg>),
    /// A list `( ... )`.
    List(Vec<Arg>),
}

impl Arg {
    /// `IFCLABEL('text')`.
    pub fn label(text: &str) -> Arg {
        Arg::typed("IfcLabel", Arg::Text(text.into()))
    }

    /// A typed value, e.g. `Arg::typed("IfcPositiveLengthMeasure", Arg::Real(0.9))`.
    pub fn typed(ty: &str, value: Arg) -> Arg {
        Arg::Typed(ty.to_ascii_uppercase(), Box::new(value))
    }

    /// Appends the STEP form to `out`; fails on a non-finite real or an invalid enum or type name.
    pub fn write_step(&self, out: &mut String) -> Result<(), ArgError> {
        match self {
            Arg::Null => out.push('$'),
            Arg::Derived => out.push('*'),
            Arg::Ref(id) => write!(out, "#{}", id.0).expect("write to String"),
            Arg::Integer(i) => write!(out, "{i}").expect("write to String"),
            Arg::Real(r) => out.push_str(&format_real(*r).ok_or(ArgError::NotFinite(*r))?),
            Arg::Text(s) => {
                out.push('\'');
                out.push_str(&string::encode(s));
                out.push('\'');
            }
            Arg::Enum(e) => {
                if e.is_empty() || !e.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_') {
                    return Err(ArgError::BadEnum(e.clone()));
                }
                write!(out, ".{}.", e.to_ascii_uppercase()).expect("write to String");
            }
            Arg::Bool(b) => out.push_str(if *b { ".T." } else { ".F." }),
            Arg::Typed(t, v) => {
                if t.is_empty() || !t.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_') {
                    return Err(ArgError::BadTypeName(t.clone()));
                }
                out.push_str(&t.to_ascii_uppercase());
                out.push('(');
                v.write_step(out)?;
                out.push(')');
            }
            Arg::List(items) => {
                out.push('(');
                for (i, a) in items.iter().enumerate() {
                    if i > 0 {
                        out.push(',');
                    }
                    a.write_step(out)?;
                }
                out.push(')');
            }
        }
        Ok(())
    }
}

/// A finite real in STEP form: always with a decimal point (`900.`, `0.9`, `1.5E-05`);
/// shortest representation that reads back to the same `f64`.
pub fn format_real(r: f64) -> Option<String> {
    if !r.is_finite() {
        return None;
    }
    let s = format!("{r:?}");
    let (mantissa, exponent) = match s.find(['e', 'E']) {
        Some(p) => (&s[..p], Some(&s[p + 1..])),
        None => (s.as_str(), None),
    };
    let mut out = mantissa.to_string();
    if !out.contains('.') {
        out.push('.');
    }
    if let Some(e) = exponent {
        out.push('E');
        out.push_str(e);
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn writes_step_forms() {
        let a = Arg::List(vec![
            Arg::label("It's"),
            Arg::Real(900.0),
            Arg::Real(1e-5),
            Arg::Enum("full_access".into()),
            Arg::Ref(EntityId(7)),
            Arg::Null,
            Arg::Bool(true),
        ]);
        let mut s = String::new();
        a.write_step(&mut s).unwrap();
        assert_eq!(s, "(IFCLABEL('It''s'),900.0,1.E-5,.FULL_ACCESS.,#7,$,.T.)");
        assert!(Arg::Real(f64::NAN).write_step(&mut String::new()).is_err());
        assert!(Arg::Enum("a b".into())
            .write_step(&mut String::new())
            .is_err());
    }

    proptest! {
        #[test]
        fn reals_read_back_exactly(r in any::<f64>().prop_filter("finite", |r| r.is_finite())) {
            let s = format_real(r).unwrap();
            let args = format!("({s})");
            let v = crate::value::parse_args(args.as_bytes()).unwrap();
            prop_assert_eq!(v[0].as_f64().unwrap(), r);
        }
    }
}
