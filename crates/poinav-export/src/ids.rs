//! IDS (buildingSMART Information Delivery Specification 1.0) of an enriched model: one
//! `<specification>` per group of classified elements with the same exact IFC class, the same
//! property set and the same values, stating exactly what `poinav_poi::write_enrichment` wrote.
//!
//! The IDS is checkable by any IDS 1.0 tool (tested with IfcOpenShell's ifctester):
//!
//! - Applicability: an entity facet with the upper-case class (IDS matches the exact class, not
//!   subtypes; in IFC2X3 also occurrences whose type object is `<class>Type`/`<class>Style`) and,
//!   unless the group is every instance so matched, an attribute facet restricting `GlobalId` to
//!   the group's GlobalIds. Each specification is required (`minOccurs="1"`).
//! - Requirements: one property facet per written property, with its IFC data type
//!   (`IFCLABEL`, `IFCPOSITIVELENGTHMEASURE`, `IFCINTEGER`, `IFCDATETIME`; `LastValidated` is an
//!   `IFCLABEL` in IFC2X3) and its value. Enumerated properties carry an `xs:enumeration`;
//!   lengths are in metres (IDS compares measures in SI units, converting the file's unit).
//! - Role lists: IDS 1.0 matches a single value against a list property when *any* list item
//!   equals it, so `POI_PrimaryRoles` gets one facet per role code (each code must be present).
//!   An empty `POI_ConditionalRoles` (left out in IFC2X3, `$` in IFC4+) is stated as
//!   `cardinality="prohibited"`: the property has no value.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::path::Path;

use poinav_ifc::{EntityId, Model, Schema};
use poinav_poi::{pset_names, Classification, Classified, Role, WriteOptions};

use crate::ExportError;

/// The IDS 1.0 namespace.
pub const IDS_NAMESPACE: &str = "http://standards.buildingsmart.org/IDS";
/// Where the IDS 1.0 XSD is published.
pub const IDS_SCHEMA_LOCATION: &str = "http://standards.buildingsmart.org/IDS/1.0/ids.xsd";

/// Which of the three property sets a specification is about (declaration order = output order).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum SetKind {
    Classification,
    Accessibility,
    Coordination,
}

/// How a property facet constrains the value.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
enum Value {
    /// Any non-empty value.
    Any,
    /// `<simpleValue>`.
    Simple(String),
    /// `<xs:restriction base="xs:string">` with these `xs:enumeration`s.
    Enumeration(Vec<String>),
}

/// `required`, or `prohibited` (the property has no value).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Cardinality {
    Required,
    Prohibited,
}

/// One property facet of the requirements.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
struct PropertyReq {
    base_name: &'static str,
    data_type: &'static str,
    value: Value,
    cardinality: Cardinality,
    instructions: Option<&'static str>,
}

impl PropertyReq {
    fn required(base_name: &'static str, data_type: &'static str, value: Value) -> PropertyReq {
        PropertyReq {
            base_name,
            data_type,
            value,
            cardinality: Cardinality::Required,
            instructions: None,
        }
    }
}

/// What groups elements into one specification.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
struct GroupKey {
    class: String,
    set: SetKind,
    summary: String,
    props: Vec<PropertyReq>,
}

const IFCLABEL: &str = "IFCLABEL";
const LENGTH: &str = "IFCPOSITIVELENGTHMEASURE";

fn enumeration(label: &str) -> Value {
    Value::Enumeration(vec![label.to_string()])
}

/// A length in metres as IDS writes measures (SI units, shortest round-trip form).
fn metres(v: f64) -> Value {
    Value::Simple(format!("{v}"))
}

fn roles(r: &[Role]) -> String {
    r.iter().map(|r| r.label()).collect::<Vec<_>>().join(" ")
}

fn role_facets(props: &mut Vec<PropertyReq>, base_name: &'static str, list: &[Role]) {
    let mut seen = BTreeSet::new();
    for r in list {
        if seen.insert(r.label()) {
            props.push(PropertyReq::required(
                base_name,
                IFCLABEL,
                Value::Simple(r.label().to_string()),
            ));
        }
    }
}

fn classification_key(e: &Classified) -> GroupKey {
    let mut props = vec![
        PropertyReq::required("POI_Category", IFCLABEL, enumeration(e.category.label())),
        PropertyReq::required("POI_Type", IFCLABEL, enumeration(e.poi_type.label())),
    ];
    role_facets(&mut props, "POI_PrimaryRoles", &e.primary);
    if e.conditional.is_empty() {
        props.push(PropertyReq {
            base_name: "POI_ConditionalRoles",
            data_type: IFCLABEL,
            value: Value::Any,
            cardinality: Cardinality::Prohibited,
            instructions: Some(
                "no conditional role applies: the list is empty (IFC4+) or left out (IFC2X3)",
            ),
        });
    } else {
        role_facets(&mut props, "POI_ConditionalRoles", &e.conditional);
    }
    let mut summary = format!("{}, {}", e.poi_type.label(), roles(&e.primary));
    if !e.conditional.is_empty() {
        let _ = write!(summary, " + {}", roles(&e.conditional));
    }
    GroupKey {
        class: e.class.clone(),
        set: SetKind::Classification,
        summary,
        props,
    }
}

fn accessibility_key(e: &Classified, schema: Schema, timestamp: &str) -> Option<GroupKey> {
    let a = e.accessibility.as_ref()?;
    let date_type = if schema == Schema::Ifc2x3 {
        IFCLABEL
    } else {
        "IFCDATETIME"
    };
    Some(GroupKey {
        class: e.class.clone(),
        set: SetKind::Accessibility,
        summary: format!("{}, {}", a.status.label(), a.method.label()),
        props: vec![
            PropertyReq::required("MinClearanceWidth", LENGTH, metres(a.min_clearance_width_m)),
            PropertyReq::required(
                "MinClearanceHeight",
                LENGTH,
                metres(a.min_clearance_height_m),
            ),
            PropertyReq::required(
                "AccessibilityStatus",
                IFCLABEL,
                enumeration(a.status.label()),
            ),
            PropertyReq::required("ValidationMethod", IFCLABEL, enumeration(a.method.label())),
            PropertyReq::required(
                "LastValidated",
                date_type,
                Value::Simple(timestamp.to_string()),
            ),
        ],
    })
}

fn coordination_key(e: &Classified) -> Option<GroupKey> {
    let k = e.coordination.as_ref()?;
    Some(GroupKey {
        class: e.class.clone(),
        set: SetKind::Coordination,
        summary: format!(
            "{}, {}, at most {}",
            k.protocol.label(),
            k.applies_to.label(),
            k.max_robots
        ),
        props: vec![
            PropertyReq::required(
                "MaxSimultaneousRobots",
                "IFCINTEGER",
                Value::Simple(k.max_robots.to_string()),
            ),
            PropertyReq::required(
                "MinInterRobotSeparation",
                LENGTH,
                metres(k.min_separation_m),
            ),
            PropertyReq::required(
                "CoordinationProtocol",
                IFCLABEL,
                enumeration(k.protocol.label()),
            ),
            PropertyReq::required("AppliesTo", IFCLABEL, enumeration(k.applies_to.label())),
        ],
    })
}

/// The instances an IDS entity facet naming `class` applies to: the exact class, and in IFC2X3
/// also objects typed by `<class>Type` or `<class>Style` (IDS 1.0's rule for IFC2X3, where many
/// occurrence classes were only distinguished by their type).
fn entity_facet_matches(model: &Model, class: &str) -> BTreeSet<EntityId> {
    let mut out: BTreeSet<EntityId> = model
        .instances_of(class)
        .into_iter()
        .filter(|e| e.type_name() == class)
        .map(|e| e.id())
        .collect();
    if model.schema() == Schema::Ifc2x3 {
        let upper = class.to_ascii_uppercase();
        for rel in model.instances_of("IfcRelDefinesByType") {
            let Some(ty) = rel.get_ref("RelatingType") else {
                continue;
            };
            let derived = ty.type_name().to_ascii_uppercase();
            let derived = derived
                .strip_suffix("TYPE")
                .or_else(|| derived.strip_suffix("STYLE"))
                .unwrap_or(&derived);
            if derived == upper {
                out.extend(rel.get_refs("RelatedObjects").iter().map(|o| o.id()));
            }
        }
    }
    out
}

/// Escapes text for XML content (`attr == false`) or a double-quoted attribute (`attr == true`).
/// Characters XML 1.0 cannot carry at all (most C0 controls, U+FFFE/U+FFFF) become U+FFFD.
fn escape(s: &str, attr: bool) -> String {
    let mut out = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' if attr => out.push_str("&quot;"),
            '\'' if attr => out.push_str("&apos;"),
            '\t' | '\n' | '\r' if attr => {
                let _ = write!(out, "&#{};", ch as u32);
            }
            '\r' => out.push_str("&#13;"),
            '\t' | '\n' => out.push(ch),
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => out.push('\u{FFFD}'),
            c => out.push(c),
        }
    }
    out
}

fn write_value(out: &mut String, indent: &str, tag: &str, value: &Value) {
    match value {
        Value::Any => {}
        Value::Simple(v) => {
            let _ = writeln!(
                out,
                "{indent}<ids:{tag}><ids:simpleValue>{}</ids:simpleValue></ids:{tag}>",
                escape(v, false)
            );
        }
        Value::Enumeration(values) => {
            let _ = writeln!(out, "{indent}<ids:{tag}>");
            let _ = writeln!(out, "{indent}  <xs:restriction base=\"xs:string\">");
            for v in values {
                let _ = writeln!(
                    out,
                    "{indent}    <xs:enumeration value=\"{}\"/>",
                    escape(v, true)
                );
            }
            let _ = writeln!(out, "{indent}  </xs:restriction>");
            let _ = writeln!(out, "{indent}</ids:{tag}>");
        }
    }
}

fn set_name(kind: SetKind, prefix: &str) -> String {
    let names = pset_names(prefix);
    match kind {
        SetKind::Classification => names.classification,
        SetKind::Accessibility => names.accessibility,
        SetKind::Coordination => names.coordination,
    }
}

/// The `xs:date` part of an ISO 8601 timestamp, if it has one.
fn date_of(timestamp: &str) -> Option<&str> {
    let d = timestamp.get(..10)?;
    let b = d.as_bytes();
    let digits = |r: std::ops::Range<usize>| b[r].iter().all(u8::is_ascii_digit);
    (digits(0..4) && b[4] == b'-' && digits(5..7) && b[7] == b'-' && digits(8..10)).then_some(d)
}

/// Renders the IDS of the enrichment `c` of `model`, as written with `opts`.
pub fn to_ids(model: &Model, c: &Classification, opts: &WriteOptions) -> String {
    let schema = model.schema();
    let mut groups: BTreeMap<GroupKey, Vec<&Classified>> = BTreeMap::new();
    for e in &c.elements {
        groups.entry(classification_key(e)).or_default().push(e);
        if let Some(k) = accessibility_key(e, schema, &opts.timestamp) {
            groups.entry(k).or_default().push(e);
        }
        if let Some(k) = coordination_key(e) {
            groups.entry(k).or_default().push(e);
        }
    }
    let mut matches: BTreeMap<&str, BTreeSet<EntityId>> = BTreeMap::new();

    let file = model
        .file()
        .file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_else(|| model.file().display().to_string());
    let version = env!("CARGO_PKG_VERSION");
    let mut out = String::new();
    out.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        out,
        "<ids:ids xmlns:ids=\"{IDS_NAMESPACE}\" xmlns:xs=\"http://www.w3.org/2001/XMLSchema\" \
         xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" xsi:schemaLocation=\"{IDS_NAMESPACE} {IDS_SCHEMA_LOCATION}\">"
    );
    out.push_str("  <ids:info>\n");
    let _ = writeln!(
        out,
        "    <ids:title>{}</ids:title>",
        escape(
            &format!("Robot POI enrichment of {file} (poinav {version})"),
            false
        )
    );
    let _ = writeln!(
        out,
        "    <ids:version>{}</ids:version>",
        escape(&format!("poinav {version}"), false)
    );
    let description = format!(
        "Property sets {}*, written by poinav {version} for robot profile {} into {} {file}: {} classified elements, {} specifications. Lengths in metres.",
        opts.prefix,
        c.profile.name,
        schema.name(),
        c.elements.len(),
        groups.len()
    );
    let _ = writeln!(
        out,
        "    <ids:description>{}</ids:description>",
        escape(&description, false)
    );
    if let Some(date) = date_of(&opts.timestamp) {
        let _ = writeln!(out, "    <ids:date>{date}</ids:date>");
    }
    out.push_str("    <ids:purpose>Verify the robot Point-of-Interest property sets of the enriched model</ids:purpose>\n");
    out.push_str("  </ids:info>\n");
    out.push_str("  <ids:specifications>\n");

    for (n, (key, elements)) in groups.iter().enumerate() {
        let pset = set_name(key.set, &opts.prefix);
        let class_upper = key.class.to_ascii_uppercase();
        let mut rules: Vec<&str> = elements.iter().map(|e| e.rule.as_str()).collect();
        rules.sort_unstable();
        rules.dedup();
        let name = format!("{} {pset}: {}", key.class, key.summary);
        let description = format!(
            "{} {} element(s) classified by rule(s) {} carry {pset} with these values",
            elements.len(),
            key.class,
            rules.join(", ")
        );
        let _ = writeln!(
            out,
            "    <ids:specification name=\"{}\" ifcVersion=\"{}\" identifier=\"{}\" description=\"{}\">",
            escape(&name, true),
            schema.name(),
            escape(&format!("poinav-{:03}", n + 1), true),
            escape(&description, true)
        );
        out.push_str("      <ids:applicability minOccurs=\"1\" maxOccurs=\"unbounded\">\n");
        let _ = writeln!(out, "        <ids:entity><ids:name><ids:simpleValue>{}</ids:simpleValue></ids:name></ids:entity>", escape(&class_upper, false));
        let group_ids: BTreeSet<EntityId> = elements.iter().map(|e| e.id).collect();
        let all = matches
            .entry(key.class.as_str())
            .or_insert_with(|| entity_facet_matches(model, &key.class));
        if *all != group_ids {
            let guids: BTreeSet<&str> = elements
                .iter()
                .map(|e| e.global_id.as_str())
                .filter(|g| !g.is_empty())
                .collect();
            out.push_str("        <ids:attribute>\n");
            out.push_str(
                "          <ids:name><ids:simpleValue>GlobalId</ids:simpleValue></ids:name>\n",
            );
            write_value(
                &mut out,
                "          ",
                "value",
                &Value::Enumeration(guids.into_iter().map(str::to_string).collect()),
            );
            out.push_str("        </ids:attribute>\n");
        }
        out.push_str("      </ids:applicability>\n");
        out.push_str("      <ids:requirements>\n");
        for p in &key.props {
            let cardinality = match p.cardinality {
                Cardinality::Required => "required",
                Cardinality::Prohibited => "prohibited",
            };
            let _ = write!(
                out,
                "        <ids:property dataType=\"{}\" cardinality=\"{cardinality}\"",
                p.data_type
            );
            if let Some(i) = p.instructions {
                let _ = write!(out, " instructions=\"{}\"", escape(i, true));
            }
            out.push_str(">\n");
            let _ = writeln!(out, "          <ids:propertySet><ids:simpleValue>{}</ids:simpleValue></ids:propertySet>", escape(&pset, false));
            let _ = writeln!(
                out,
                "          <ids:baseName><ids:simpleValue>{}</ids:simpleValue></ids:baseName>",
                escape(p.base_name, false)
            );
            write_value(&mut out, "          ", "value", &p.value);
            out.push_str("        </ids:property>\n");
        }
        out.push_str("      </ids:requirements>\n");
        out.push_str("    </ids:specification>\n");
    }
    if groups.is_empty() {
        // IDS needs at least one specification: state that no object carries the set.
        let pset = escape(&set_name(SetKind::Classification, &opts.prefix), false);
        let _ = writeln!(
            out,
            "    <ids:specification name=\"No element carries {pset}\" ifcVersion=\"{}\" identifier=\"poinav-000\" \
             description=\"poinav classified no element of this model\">",
            schema.name()
        );
        out.push_str("      <ids:applicability minOccurs=\"0\" maxOccurs=\"0\">\n");
        out.push_str("        <ids:property>\n");
        let _ = writeln!(out, "          <ids:propertySet><ids:simpleValue>{pset}</ids:simpleValue></ids:propertySet>");
        out.push_str("          <ids:baseName><ids:simpleValue>POI_Category</ids:simpleValue></ids:baseName>\n");
        out.push_str("        </ids:property>\n");
        out.push_str("      </ids:applicability>\n");
        out.push_str("    </ids:specification>\n");
    }
    out.push_str("  </ids:specifications>\n");
    out.push_str("</ids:ids>\n");
    out
}

/// Writes the IDS for `c` to `path` atomically.
pub fn write_ids(
    path: &Path,
    model: &Model,
    c: &Classification,
    opts: &WriteOptions,
) -> Result<(), ExportError> {
    poinav_ifc::output::write_atomic(path, to_ids(model, c, opts).as_bytes()).map_err(|e| {
        ExportError::Write {
            path: path.display().to_string(),
            message: e.to_string(),
        }
    })
}
