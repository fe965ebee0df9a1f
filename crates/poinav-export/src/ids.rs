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
//!   `cardinality="prohibited"`: the property has no value. A list with extra codes is not
//!   caught (IDS 1.0 cannot say "exactly these items").
//! - A model with nothing classified gets one prohibited specification (no object carries
//!   `<prefix>POI_Classification`), since an IDS needs at least one specification.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::path::Path;

use poinav_ifc::{EntityId, Model, Schema};
use poinav_io::xml;
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
    let mut summary = format!(
        "{}, {}, {}",
        e.category.label(),
        e.poi_type.label(),
        roles(&e.primary)
    );
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

/// Appends `<ids:{tag}>` holding `value` (nothing for [`Value::Any`]).
fn write_value(out: &mut String, indent: &str, tag: &str, value: &Value) {
    match value {
        Value::Any => {}
        Value::Simple(v) => {
            let v = xml::text(v);
            let _ = writeln!(
                out,
                "{indent}<ids:{tag}><ids:simpleValue>{v}</ids:simpleValue></ids:{tag}>"
            );
        }
        Value::Enumeration(values) => {
            let _ = writeln!(out, "{indent}<ids:{tag}>");
            let _ = writeln!(out, "{indent}  <xs:restriction base=\"xs:string\">");
            for v in values {
                let v = xml::attr(v);
                let _ = writeln!(out, "{indent}    <xs:enumeration value=\"{v}\"/>");
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
    let ok = digits(0..4) && b[4] == b'-' && digits(5..7) && b[7] == b'-' && digits(8..10);
    ok.then_some(d)
}

/// Appends `<ids:info>`.
fn write_info(out: &mut String, file: &str, description: &str, timestamp: &str) {
    let version = env!("CARGO_PKG_VERSION");
    let title = format!("Robot POI enrichment of {file} (poinav {version})");
    out.push_str("  <ids:info>\n");
    let _ = writeln!(out, "    <ids:title>{}</ids:title>", xml::text(&title));
    let _ = writeln!(out, "    <ids:version>poinav {version}</ids:version>");
    let _ = writeln!(
        out,
        "    <ids:description>{}</ids:description>",
        xml::text(description)
    );
    if let Some(date) = date_of(timestamp) {
        let _ = writeln!(out, "    <ids:date>{date}</ids:date>");
    }
    out.push_str("    <ids:purpose>Check the robot Point-of-Interest property sets");
    out.push_str(" of the enriched model</ids:purpose>\n");
    out.push_str("  </ids:info>\n");
}

/// Appends the opening `<ids:specification ...>` tag.
fn open_spec(out: &mut String, name: &str, schema: Schema, identifier: &str, description: &str) {
    let _ = writeln!(
        out,
        "    <ids:specification name=\"{}\" ifcVersion=\"{}\" identifier=\"{}\" description=\"{}\">",
        xml::attr(name),
        schema.name(),
        xml::attr(identifier),
        xml::attr(description)
    );
}

/// Appends one requirement's `<ids:property>`.
fn write_property(out: &mut String, pset: &str, p: &PropertyReq) {
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
        let _ = write!(out, " instructions=\"{}\"", xml::attr(i));
    }
    out.push_str(">\n");
    let pset = xml::text(pset);
    let base = xml::text(p.base_name);
    let _ = writeln!(
        out,
        "          <ids:propertySet><ids:simpleValue>{pset}</ids:simpleValue></ids:propertySet>"
    );
    let _ = writeln!(
        out,
        "          <ids:baseName><ids:simpleValue>{base}</ids:simpleValue></ids:baseName>"
    );
    write_value(out, "          ", "value", &p.value);
    out.push_str("        </ids:property>\n");
}

/// Appends the specification of one group.
fn write_group(
    out: &mut String,
    n: usize,
    key: &GroupKey,
    elements: &[&Classified],
    ctx: &Context<'_>,
) {
    let pset = set_name(key.set, ctx.prefix);
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
    open_spec(
        out,
        &name,
        ctx.schema,
        &format!("poinav-{n:03}"),
        &description,
    );
    out.push_str("      <ids:applicability minOccurs=\"1\" maxOccurs=\"unbounded\">\n");
    let class = xml::text(&key.class.to_ascii_uppercase());
    let _ = writeln!(out, "        <ids:entity><ids:name><ids:simpleValue>{class}</ids:simpleValue></ids:name></ids:entity>");
    let ids: BTreeSet<EntityId> = elements.iter().map(|e| e.id).collect();
    if entity_facet_matches(ctx.model, &key.class) != ids {
        let guids: BTreeSet<&str> = elements
            .iter()
            .map(|e| e.global_id.as_str())
            .filter(|g| !g.is_empty())
            .collect();
        out.push_str("        <ids:attribute>\n");
        out.push_str(
            "          <ids:name><ids:simpleValue>GlobalId</ids:simpleValue></ids:name>\n",
        );
        let guids = Value::Enumeration(guids.into_iter().map(str::to_string).collect());
        write_value(out, "          ", "value", &guids);
        out.push_str("        </ids:attribute>\n");
    }
    out.push_str("      </ids:applicability>\n");
    out.push_str("      <ids:requirements>\n");
    for p in &key.props {
        write_property(out, &pset, p);
    }
    out.push_str("      </ids:requirements>\n");
    out.push_str("    </ids:specification>\n");
}

/// IDS needs at least one specification: when nothing was classified, state that no object
/// carries the classification set.
fn write_nothing_enriched(out: &mut String, ctx: &Context<'_>) {
    let pset = set_name(SetKind::Classification, ctx.prefix);
    let name = format!("No element carries {pset}");
    open_spec(
        out,
        &name,
        ctx.schema,
        "poinav-000",
        "poinav classified no element of this model",
    );
    out.push_str("      <ids:applicability minOccurs=\"0\" maxOccurs=\"0\">\n");
    out.push_str("        <ids:property>\n");
    let pset = xml::text(&pset);
    let _ = writeln!(
        out,
        "          <ids:propertySet><ids:simpleValue>{pset}</ids:simpleValue></ids:propertySet>"
    );
    out.push_str(
        "          <ids:baseName><ids:simpleValue>POI_Category</ids:simpleValue></ids:baseName>\n",
    );
    out.push_str("        </ids:property>\n");
    out.push_str("      </ids:applicability>\n");
    out.push_str("    </ids:specification>\n");
}

struct Context<'m> {
    model: &'m Model,
    schema: Schema,
    prefix: &'m str,
}

/// Renders the IDS of the enrichment `c` of `model`, as written with `opts`. Same input, same
/// bytes: specifications are sorted by class, set and values; GlobalIds are sorted.
pub fn to_ids(model: &Model, c: &Classification, opts: &WriteOptions) -> String {
    let ctx = Context {
        model,
        schema: model.schema(),
        prefix: &opts.prefix,
    };
    let mut groups: BTreeMap<GroupKey, Vec<&Classified>> = BTreeMap::new();
    for e in &c.elements {
        groups.entry(classification_key(e)).or_default().push(e);
        if let Some(k) = accessibility_key(e, ctx.schema, &opts.timestamp) {
            groups.entry(k).or_default().push(e);
        }
        if let Some(k) = coordination_key(e) {
            groups.entry(k).or_default().push(e);
        }
    }
    let file = match model.file().file_name() {
        Some(f) => f.to_string_lossy().into_owned(),
        None => model.file().display().to_string(),
    };
    let description = format!(
        "Property sets {}*, written by poinav {} for robot profile {} into {} file {file}: \
         {} classified elements, {} specifications. Lengths in metres.",
        opts.prefix,
        env!("CARGO_PKG_VERSION"),
        c.profile.name,
        ctx.schema.name(),
        c.elements.len(),
        groups.len().max(1)
    );

    let mut out = String::new();
    out.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        out,
        "<ids:ids xmlns:ids=\"{IDS_NAMESPACE}\" xmlns:xs=\"http://www.w3.org/2001/XMLSchema\" \
         xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" \
         xsi:schemaLocation=\"{IDS_NAMESPACE} {IDS_SCHEMA_LOCATION}\">"
    );
    write_info(&mut out, &file, &description, &opts.timestamp);
    out.push_str("  <ids:specifications>\n");
    for (n, (key, elements)) in groups.iter().enumerate() {
        write_group(&mut out, n + 1, key, elements, &ctx);
    }
    if groups.is_empty() {
        write_nothing_enriched(&mut out, &ctx);
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
    poinav_io::write_atomic(path, to_ids(model, c, opts).as_bytes()).map_err(|e| {
        ExportError::Write {
            path: path.display().to_string(),
            message: e.to_string(),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use poinav_poi::{classify, RobotProfile, RuleSet};

    fn model(schema: &str, data: &str) -> Model {
        let text = format!(
            "ISO-10303-21;HEADER;FILE_SCHEMA(('{schema}'));ENDSEC;DATA;\n{data}ENDSEC;END-ISO-10303-21;"
        );
        Model::from_bytes("a & b.ifc", text.into_bytes()).unwrap()
    }

    fn ids_of(m: &Model, prefix: &str) -> String {
        let c = classify(m, &RuleSet::defaults(), &RobotProfile::paper());
        let opts = WriteOptions {
            prefix: prefix.into(),
            timestamp: "2026-11-22T02:30:00".into(),
        };
        to_ids(m, &c, &opts)
    }

    fn specs(ids: &str) -> Vec<&str> {
        ids.split("<ids:specification ").skip(1).collect()
    }

    #[test]
    fn dates_come_from_iso_timestamps_only() {
        assert_eq!(date_of("2026-11-22T02:30:00"), Some("2026-11-22"));
        assert_eq!(date_of("2026-11-22"), Some("2026-11-22"));
        assert_eq!(date_of("yesterday at noon"), None);
        assert_eq!(date_of("2026-1-2"), None);
        assert_eq!(date_of("éééééééééé"), None);
    }

    #[test]
    fn doors_get_one_specification_per_set_and_values() {
        // Two doors: 0.80 m (RESTRICTED, conditional B-2) and 1.00 m (FULL_ACCESS).
        let m = model(
            "IFC4",
            "#1=IFCDOOR('1YvctVUKr0kugbFTf53O9L',$,'Door',$,$,$,$,$,2.1,0.8,$,$,$);\n\
             #2=IFCDOOR('2YvctVUKr0kugbFTf53O9L',$,'Wide',$,$,$,$,$,2.1,1.0,$,$,$);\n",
        );
        let ids = ids_of(&m, "POINAV_");
        assert_eq!(ids, ids_of(&m, "POINAV_"), "deterministic");
        assert!(ids.contains("<ids:title>Robot POI enrichment of a &amp; b.ifc (poinav "));
        assert!(ids.contains("<ids:date>2026-11-22</ids:date>"));
        let specs = specs(&ids);
        assert_eq!(specs.len(), 4, "{ids}");
        for s in &specs {
            assert!(s.contains("ifcVersion=\"IFC4\""));
            assert!(s.contains("<ids:simpleValue>IFCDOOR</ids:simpleValue>"));
            // Each group is one of the two doors: GlobalId restricts it to that door.
            assert!(
                s.contains("<ids:simpleValue>GlobalId</ids:simpleValue>"),
                "{s}"
            );
            assert_eq!(s.matches("YvctVUKr0kugbFTf53O9L\"/>").count(), 1, "{s}");
        }
        let restricted = specs
            .iter()
            .find(|s| s.contains("value=\"RESTRICTED\""))
            .unwrap();
        assert!(restricted.contains("value=\"1YvctVUKr0kugbFTf53O9L\""));
        assert!(restricted.contains("dataType=\"IFCDATETIME\""));
        assert!(restricted.contains("<ids:simpleValue>2026-11-22T02:30:00</ids:simpleValue>"));
        assert!(restricted.contains("dataType=\"IFCPOSITIVELENGTHMEASURE\""));
        let narrow = specs.iter().find(|s| s.contains("A-2 + B-2")).unwrap();
        assert!(narrow.contains("<ids:simpleValue>B-2</ids:simpleValue>"));
        assert!(!narrow.contains("prohibited"));
        let wide = specs
            .iter()
            .find(|s| s.contains("Classification: Structural, Transition Element, A-2\""))
            .unwrap();
        assert!(wide.contains("cardinality=\"prohibited\""));
        assert!(wide.contains("value=\"2YvctVUKr0kugbFTf53O9L\""));
    }

    #[test]
    fn ifc2x3_dates_are_labels_and_whole_classes_need_no_global_ids() {
        let m = model(
            "IFC2X3",
            "#1=IFCDOOR('1YvctVUKr0kugbFTf53O9L',$,'A',$,$,$,$,$,2100.,1000.);\n\
             #2=IFCDOOR('2YvctVUKr0kugbFTf53O9L',$,'B',$,$,$,$,$,2100.,1000.);\n",
        );
        let ids = ids_of(&m, "Pset_");
        assert!(!ids.contains("GlobalId"), "{ids}");
        assert!(!ids.contains("IFCDATETIME"));
        assert_eq!(specs(&ids).len(), 2);
        let access = specs(&ids)
            .into_iter()
            .find(|s| s.contains("Pset_RobotAccessibility"))
            .unwrap();
        assert!(access.contains(
            "<ids:property dataType=\"IFCLABEL\" cardinality=\"required\">\n          \
             <ids:propertySet><ids:simpleValue>Pset_RobotAccessibility</ids:simpleValue></ids:propertySet>\n          \
             <ids:baseName><ids:simpleValue>LastValidated</ids:simpleValue></ids:baseName>"
        ));
    }

    #[test]
    fn a_model_with_nothing_classified_still_gives_a_valid_ids() {
        let m = model("IFC4X3_ADD2", "#1=IFCPERSON($,$,'x',$,$,$,$,$);\n");
        let ids = ids_of(&m, "A&B_");
        let specs = specs(&ids);
        assert_eq!(specs.len(), 1);
        assert!(specs[0].contains("minOccurs=\"0\" maxOccurs=\"0\""));
        assert!(specs[0].contains("<ids:simpleValue>A&amp;B_POI_Classification</ids:simpleValue>"));
        assert!(specs[0].contains("ifcVersion=\"IFC4X3_ADD2\""));
    }
}
