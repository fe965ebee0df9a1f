//! Mapping rules as data: a TOML rule file (the defaults ship in `rules/default.toml`) that
//! assigns POI category, type, roles, conditional roles and property values to elements.
//!
//! Precedence: of all rules that match an element, the one with the highest `priority` wins;
//! among equal priorities the rule defined last wins, so a user file loaded after the defaults
//! overrides them. Only the winning rule applies (its roles are not merged with others').

use std::path::Path;

use regex::Regex;
use serde::Deserialize;

use crate::condition::Condition;
use crate::error::PoiError;
use crate::facts::{FactValue, Facts};
use poinav_roles::{Category, Coordination, PoiType, RobotProfile, Role};

/// How AccessibilityStatus is decided for the elements of a rule.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AccessibilityKind {
    /// No Pset_RobotAccessibility.
    None,
    /// Clear width against the profile: FULL_ACCESS, RESTRICTED (wider than the robot) or BLOCKED.
    ClearWidth,
    /// Always BLOCKED for ground robots (windows).
    Blocked,
    /// BLOCKED unless the profile climbs stairs.
    Stairs,
    /// Slope against the profile's max slope.
    Slope,
    /// Spaces: from the statuses of their doors.
    Space,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConditional {
    role: Role,
    when: String,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawProperty {
    name: String,
    #[serde(default)]
    equals: Option<toml::Value>,
    #[serde(default)]
    matches: Option<String>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRule {
    id: String,
    #[serde(default)]
    function: String,
    classes: Vec<String>,
    #[serde(default)]
    exclude_classes: Vec<String>,
    #[serde(default)]
    predefined_types: Vec<String>,
    #[serde(default)]
    names: Vec<String>,
    #[serde(default)]
    property: Vec<RawProperty>,
    #[serde(default)]
    when: Vec<String>,
    #[serde(default)]
    when_any: Vec<String>,
    #[serde(default)]
    priority: i64,
    #[serde(default)]
    skip: bool,
    category: Option<Category>,
    #[serde(rename = "type")]
    poi_type: Option<PoiType>,
    #[serde(default)]
    roles: Vec<Role>,
    #[serde(default)]
    conditional: Vec<RawConditional>,
    #[serde(default = "no_access")]
    accessibility: AccessibilityKind,
    #[serde(default)]
    coordination: Option<Coordination>,
}

fn no_access() -> AccessibilityKind {
    AccessibilityKind::None
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
enum Mode {
    Extend,
    Replace,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    version: u32,
    #[serde(default = "extend")]
    mode: Mode,
    #[serde(default, rename = "rule")]
    rules: Vec<RawRule>,
}

fn extend() -> Mode {
    Mode::Extend
}

/// A property predicate: `Pset.Property` equal to a value, or matching a regex.
#[derive(Debug, Clone)]
pub enum PropertyTest {
    /// Equal to a boolean.
    Bool(String, bool),
    /// Equal to a number.
    Number(String, f64),
    /// Equal to a text (case-insensitive).
    Text(String, String),
    /// Text (or any list item) matches the regex.
    Matches(String, Regex),
}

impl PropertyTest {
    fn holds(&self, facts: &Facts) -> bool {
        let get = |k: &str| facts.properties.get(k);
        match self {
            PropertyTest::Bool(k, b) => matches!(get(k), Some(FactValue::Bool(v)) if v == b),
            PropertyTest::Number(k, n) => {
                matches!(get(k), Some(FactValue::Number(v)) if (v - n).abs() < 1e-9)
            }
            PropertyTest::Text(k, t) => get(k).is_some_and(|v| v.text().eq_ignore_ascii_case(t)),
            PropertyTest::Matches(k, re) => match get(k) {
                Some(FactValue::List(items)) => items.iter().any(|i| re.is_match(i)),
                Some(v) => re.is_match(&v.text()),
                None => false,
            },
        }
    }
}

/// A conditional role: added when its condition holds at enrichment time.
#[derive(Debug, Clone)]
pub struct ConditionalRole {
    /// The role added.
    pub role: Role,
    /// When.
    pub when: Condition,
}

/// One compiled rule.
#[derive(Debug, Clone)]
pub struct Rule {
    /// Rule id (`R1`, `R3-corridor-name`).
    pub id: String,
    /// The functional condition in words.
    pub function: String,
    /// Classes it applies to (subtypes included).
    pub classes: Vec<String>,
    /// Classes excluded (subtypes included).
    pub exclude_classes: Vec<String>,
    /// PredefinedType values it applies to (any, when empty).
    pub predefined_types: Vec<String>,
    /// Name/LongName/ObjectType patterns (any, when empty).
    pub names: Vec<Regex>,
    /// Property predicates (all must hold).
    pub properties: Vec<PropertyTest>,
    /// Conditions that must all hold.
    pub when: Vec<Condition>,
    /// Conditions of which one must hold (ignored when empty).
    pub when_any: Vec<Condition>,
    /// Higher wins.
    pub priority: i64,
    /// Matching elements get no POI data at all.
    pub skip: bool,
    /// POI_Category.
    pub category: Option<Category>,
    /// POI_Type.
    pub poi_type: Option<PoiType>,
    /// POI_PrimaryRoles.
    pub roles: Vec<Role>,
    /// Conditional roles evaluated at enrichment.
    pub conditional: Vec<ConditionalRole>,
    /// How AccessibilityStatus is decided.
    pub accessibility: AccessibilityKind,
    /// Pset_RobotCoordination values.
    pub coordination: Option<Coordination>,
    /// Where the rule was defined.
    pub origin: String,
}

impl Rule {
    /// True when the rule's class and predicates match `e` with `facts`.
    pub fn matches(
        &self,
        e: &poinav_ifc::Entity<'_>,
        facts: &Facts,
        profile: &RobotProfile,
    ) -> bool {
        if !self.classes.iter().any(|c| e.is_a(c)) || self.exclude_classes.iter().any(|c| e.is_a(c))
        {
            return false;
        }
        if !self.predefined_types.is_empty()
            && !facts.predefined_type.as_deref().is_some_and(|p| {
                self.predefined_types
                    .iter()
                    .any(|t| t.eq_ignore_ascii_case(p))
            })
        {
            return false;
        }
        if !self.names.is_empty() {
            let texts = [&facts.name, &facts.long_name, &facts.object_type];
            if !self.names.iter().any(|re| {
                texts
                    .iter()
                    .any(|t| t.as_deref().is_some_and(|t| re.is_match(t)))
            }) {
                return false;
            }
        }
        self.properties.iter().all(|p| p.holds(facts))
            && self.when.iter().all(|c| c.holds(facts, profile))
            && (self.when_any.is_empty() || self.when_any.iter().any(|c| c.holds(facts, profile)))
    }
}

/// An ordered set of rules.
#[derive(Debug, Clone)]
pub struct RuleSet {
    rules: Vec<Rule>,
}

const DEFAULT_RULES: &str = include_str!("../rules/default.toml");

impl RuleSet {
    /// The default rules (R1-R4 and the floor-slab rule; R5 is the simulator's), shipped in
    /// `rules/default.toml`.
    pub fn defaults() -> RuleSet {
        RuleSet::from_toml(DEFAULT_RULES, "rules/default.toml")
            .expect("shipped rules are valid")
            .0
    }

    /// The default rules file's text (for `poinav rules --print-defaults`).
    pub fn default_text() -> &'static str {
        DEFAULT_RULES
    }

    /// Parses a rule file; returns the rules and whether the file replaces (true) or extends the defaults.
    pub fn from_toml(text: &str, origin: &str) -> Result<(RuleSet, bool), PoiError> {
        let raw: RawFile = toml::from_str(text).map_err(|source| PoiError::Toml {
            file: origin.into(),
            source: Box::new(source),
        })?;
        if raw.version != 1 {
            return Err(PoiError::Invalid {
                file: origin.into(),
                message: format!(
                    "rule file version {} is not supported (expected 1)",
                    raw.version
                ),
            });
        }
        let mut rules = Vec::with_capacity(raw.rules.len());
        for r in raw.rules {
            rules.push(compile(r, origin)?);
        }
        Ok((RuleSet { rules }, raw.mode == Mode::Replace))
    }

    /// The defaults extended (or replaced, with `mode = "replace"`) by the rule file at `path`.
    pub fn with_user_file(path: &Path) -> Result<RuleSet, PoiError> {
        let text = std::fs::read_to_string(path).map_err(|source| PoiError::Io {
            file: path.display().to_string(),
            source,
        })?;
        let (user, replace) = RuleSet::from_toml(&text, &path.display().to_string())?;
        if replace {
            return Ok(user);
        }
        let mut all = RuleSet::defaults();
        all.rules.extend(user.rules);
        Ok(all)
    }

    /// The rules in definition order.
    pub fn rules(&self) -> &[Rule] {
        &self.rules
    }

    /// Class names any rule mentions (for choosing candidates cheaply).
    pub fn classes(&self) -> Vec<&str> {
        let mut c: Vec<&str> = self
            .rules
            .iter()
            .flat_map(|r| r.classes.iter().map(String::as_str))
            .collect();
        c.sort_unstable();
        c.dedup();
        c
    }

    /// True when a rule that may apply to `e` tests property values (directly, or through the
    /// `is_external` and `slope_deg` measures, which come from property sets).
    pub fn needs_properties(&self, e: &poinav_ifc::Entity<'_>) -> bool {
        let from_psets = |c: &Condition| {
            [&c.lhs, &c.rhs].iter().any(|o| matches!(o, crate::condition::Operand::Measure(m) if m == "is_external" || m == "slope_deg"))
        };
        self.rules.iter().any(|r| {
            r.classes.iter().any(|c| e.is_a(c))
                && (!r.properties.is_empty()
                    || r.accessibility == AccessibilityKind::Slope
                    || r.when.iter().chain(&r.when_any).any(from_psets)
                    || r.conditional.iter().any(|c| from_psets(&c.when)))
        })
    }

    /// The winning rule for `e`: highest priority, then the last defined.
    pub fn winner(
        &self,
        e: &poinav_ifc::Entity<'_>,
        facts: &Facts,
        profile: &RobotProfile,
    ) -> Option<&Rule> {
        let mut best: Option<&Rule> = None;
        for r in &self.rules {
            if r.matches(e, facts, profile) && best.is_none_or(|b| r.priority >= b.priority) {
                best = Some(r);
            }
        }
        best
    }
}

fn compile(r: RawRule, origin: &str) -> Result<Rule, PoiError> {
    let err = |message: String| PoiError::Rule {
        file: origin.into(),
        rule: r.id.clone(),
        message,
    };
    let cond_err = |text: &str, source| PoiError::Condition {
        file: origin.into(),
        rule: r.id.clone(),
        condition: text.trim().to_string(),
        source,
    };
    if r.classes.is_empty() {
        return Err(err("`classes` must name at least one IFC class".into()));
    }
    for c in r.classes.iter().chain(&r.exclude_classes) {
        if !poinav_ifc::Schema::ALL
            .iter()
            .any(|s| s.type_by_name(c).is_some())
        {
            return Err(err(format!(
                "`{c}` is not an entity of IFC2X3, IFC4 or IFC4X3_ADD2"
            )));
        }
    }
    if !r.skip && (r.category.is_none() || r.poi_type.is_none() || r.roles.is_empty()) {
        return Err(err(
            "a rule needs `category`, `type` and at least one role (or `skip = true`)".into(),
        ));
    }
    let names = r
        .names
        .iter()
        .map(|p| Regex::new(p).map_err(|e| err(format!("bad name pattern `{p}`: {e}"))))
        .collect::<Result<_, _>>()?;
    let conds = |list: &[String]| {
        list.iter()
            .map(|c| Condition::parse(c).map_err(|e| cond_err(c, e)))
            .collect::<Result<Vec<_>, _>>()
    };
    let mut properties = Vec::new();
    for p in &r.property {
        if !p.name.contains('.') {
            return Err(err(format!(
                "property `{}` must be written `Pset_Name.Property`",
                p.name
            )));
        }
        let test = match (&p.equals, &p.matches) {
            (Some(toml::Value::Boolean(b)), None) => PropertyTest::Bool(p.name.clone(), *b),
            (Some(toml::Value::Integer(i)), None) => {
                PropertyTest::Number(p.name.clone(), *i as f64)
            }
            (Some(toml::Value::Float(f)), None) => PropertyTest::Number(p.name.clone(), *f),
            (Some(toml::Value::String(s)), None) => PropertyTest::Text(p.name.clone(), s.clone()),
            (None, Some(re)) => PropertyTest::Matches(
                p.name.clone(),
                Regex::new(re).map_err(|e| err(format!("bad pattern `{re}`: {e}")))?,
            ),
            _ => {
                return Err(err(format!(
                "property `{}` needs exactly one of `equals` (bool, number or text) or `matches`",
                p.name
            )))
            }
        };
        properties.push(test);
    }
    let conditional = r
        .conditional
        .iter()
        .map(|c| {
            Ok(ConditionalRole {
                role: c.role,
                when: Condition::parse(&c.when).map_err(|e| cond_err(&c.when, e))?,
            })
        })
        .collect::<Result<Vec<_>, PoiError>>()?;
    Ok(Rule {
        when: conds(&r.when)?,
        when_any: conds(&r.when_any)?,
        id: r.id.clone(),
        function: r.function.clone(),
        classes: r.classes.clone(),
        exclude_classes: r.exclude_classes.clone(),
        predefined_types: r.predefined_types.clone(),
        names,
        properties,
        priority: r.priority,
        skip: r.skip,
        category: r.category,
        poi_type: r.poi_type,
        roles: r.roles.clone(),
        conditional,
        accessibility: r.accessibility,
        coordination: r.coordination.clone(),
        origin: origin.into(),
    })
}
