//! Rule conditions: `measure op value` comparisons such as `clear_width_m < profile.min_clearance_width_m`.

use std::fmt;

use crate::facts::{Facts, MEASURES};
use poinav_roles::RobotProfile;

/// A comparison operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `==`
    Eq,
    /// `!=`
    Ne,
}

/// One side of a comparison.
#[derive(Debug, Clone, PartialEq)]
pub enum Operand {
    /// A literal number.
    Number(f64),
    /// A measure of the element (see [`MEASURES`]).
    Measure(String),
    /// A variable of the robot profile (`profile.min_clearance_width_m`).
    Profile(String),
}

/// A parsed condition.
#[derive(Debug, Clone, PartialEq)]
pub struct Condition {
    /// Left side.
    pub lhs: Operand,
    /// Operator.
    pub op: Op,
    /// Right side.
    pub rhs: Operand,
    text: String,
}

/// Why a condition's text could not be read.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ConditionError {
    /// A side of the comparison is empty.
    #[error("missing operand")]
    MissingOperand,
    /// `profile.<name>` names no variable of a robot profile.
    #[error("unknown profile variable `{name}` (known: {})", RobotProfile::VARIABLES.join(", "))]
    UnknownProfileVariable {
        /// The name after `profile.`.
        name: String,
    },
    /// A side is neither a number, a measure nor a profile variable.
    #[error("unknown measure `{name}` (known: {})", MEASURES.join(", "))]
    UnknownMeasure {
        /// The text of that side.
        name: String,
    },
    /// No comparison operator in the text.
    #[error("`{text}` is not a comparison (use <, <=, >, >=, ==, !=)")]
    NotAComparison {
        /// The condition's text.
        text: String,
    },
}

impl fmt::Display for Condition {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.text)
    }
}

fn operand(s: &str) -> Result<Operand, ConditionError> {
    let s = s.trim();
    if s.is_empty() {
        return Err(ConditionError::MissingOperand);
    }
    if let Ok(n) = s.parse::<f64>() {
        return Ok(Operand::Number(n));
    }
    if let Some(var) = s.strip_prefix("profile.") {
        if RobotProfile::VARIABLES.contains(&var) {
            return Ok(Operand::Profile(var.to_string()));
        }
        return Err(ConditionError::UnknownProfileVariable {
            name: var.to_string(),
        });
    }
    if MEASURES.contains(&s) {
        return Ok(Operand::Measure(s.to_string()));
    }
    Err(ConditionError::UnknownMeasure {
        name: s.to_string(),
    })
}

impl Condition {
    /// Parses `lhs op rhs`.
    pub fn parse(text: &str) -> Result<Condition, ConditionError> {
        for (tok, op) in [
            ("<=", Op::Le),
            (">=", Op::Ge),
            ("==", Op::Eq),
            ("!=", Op::Ne),
            ("<", Op::Lt),
            (">", Op::Gt),
        ] {
            if let Some((l, r)) = text.split_once(tok) {
                return Ok(Condition {
                    lhs: operand(l)?,
                    op,
                    rhs: operand(r)?,
                    text: text.trim().to_string(),
                });
            }
        }
        Err(ConditionError::NotAComparison {
            text: text.trim().to_string(),
        })
    }

    fn value(o: &Operand, facts: &Facts, profile: &RobotProfile) -> Option<f64> {
        match o {
            Operand::Number(n) => Some(*n),
            Operand::Measure(m) => facts.measure(m),
            Operand::Profile(p) => profile.variable(p),
        }
    }

    /// True when both sides are known and the comparison holds.
    pub fn holds(&self, facts: &Facts, profile: &RobotProfile) -> bool {
        let (Some(a), Some(b)) = (
            Self::value(&self.lhs, facts, profile),
            Self::value(&self.rhs, facts, profile),
        ) else {
            return false;
        };
        match self.op {
            Op::Lt => a < b,
            Op::Le => a <= b,
            Op::Gt => a > b,
            Op::Ge => a >= b,
            Op::Eq => (a - b).abs() < 1e-9,
            Op::Ne => (a - b).abs() >= 1e-9,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_evaluates_against_facts_and_profile() {
        let c = Condition::parse("clear_width_m < profile.min_clearance_width_m").unwrap();
        let p = RobotProfile::paper();
        let mut f = Facts::default();
        assert!(!c.holds(&f, &p), "unknown measures never hold");
        f.clear_width_m = Some(0.80);
        assert!(c.holds(&f, &p));
        f.clear_width_m = Some(0.90);
        assert!(!c.holds(&f, &p));
        assert!(Condition::parse("door_count >= 2").is_ok());
        assert_eq!(
            Condition::parse("doors >= 2").unwrap_err(),
            ConditionError::UnknownMeasure {
                name: "doors".into()
            }
        );
        assert!(Condition::parse("doors >= 2")
            .unwrap_err()
            .to_string()
            .starts_with("unknown measure `doors` (known: "));
        assert_eq!(
            Condition::parse("profile.wings > 1").unwrap_err(),
            ConditionError::UnknownProfileVariable {
                name: "wings".into()
            }
        );
        assert_eq!(
            Condition::parse(" area_m2 ").unwrap_err(),
            ConditionError::NotAComparison {
                text: "area_m2".into()
            }
        );
        assert_eq!(
            Condition::parse("< 2").unwrap_err(),
            ConditionError::MissingOperand
        );
    }
}
