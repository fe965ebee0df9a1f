//! The BCF XML documents, for BCF 3.0 and 2.1: `bcf.version`, `project.bcfp`,
//! `extensions.xml` (3.0), and per topic `markup.bcf` and `viewpoint.bcfv`. Element order and
//! names follow buildingSMART's XSDs of each version (`tests/bcf/xsd/`).

use std::fmt::Write as _;

use glam::DVec3;

use crate::camera::Camera;
use crate::issue::Issue;
use crate::BcfVersion;

/// Who creates the topics.
pub const AUTHOR: &str = "poinav";
/// Topic type of every topic.
pub const TOPIC_TYPE: &str = "Issue";
/// Topic status of every topic.
pub const TOPIC_STATUS: &str = "Open";
/// File name of each topic's viewpoint.
pub const VIEWPOINT_FILE: &str = "viewpoint.bcfv";
/// File name of each topic's snapshot.
pub const SNAPSHOT_FILE: &str = "snapshot.png";

const HEAD: &str = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";

/// Text for XML content or a double-quoted attribute ([`poinav_io::xml::attr`]).
pub fn text(s: &str) -> String {
    poinav_io::xml::attr(s)
}

/// `bcf.version`.
pub fn version(v: BcfVersion) -> String {
    match v {
        BcfVersion::V3_0 => format!("{HEAD}<Version VersionId=\"3.0\"/>\n"),
        BcfVersion::V2_1 => format!(
            "{HEAD}<Version VersionId=\"2.1\">\n  <DetailedVersion>2.1</DetailedVersion>\n</Version>\n"
        ),
    }
}

/// `project.bcfp`: the project's GUID and name.
pub fn project(v: BcfVersion, guid: &str, name: &str) -> String {
    let project = format!(
        "  <Project ProjectId=\"{guid}\">\n    <Name>{}</Name>\n  </Project>\n",
        text(name)
    );
    match v {
        BcfVersion::V3_0 => format!("{HEAD}<ProjectInfo>\n{project}</ProjectInfo>\n"),
        BcfVersion::V2_1 => format!(
            "{HEAD}<ProjectExtension>\n{project}  <ExtensionSchema></ExtensionSchema>\n</ProjectExtension>\n"
        ),
    }
}

/// `extensions.xml` (BCF 3.0): the topic types, statuses, priorities, labels and users used.
pub fn extensions(issues: &[Issue]) -> String {
    let mut labels: Vec<&str> = issues
        .iter()
        .flat_map(|i| i.labels.iter().map(String::as_str))
        .collect();
    labels.sort_unstable();
    labels.dedup();
    let mut priorities: Vec<&str> = issues.iter().map(|i| i.priority).collect();
    priorities.sort_unstable();
    priorities.dedup();
    let list = |outer: &str, inner: &str, items: &[&str]| {
        if items.is_empty() {
            return format!("  <{outer}/>\n");
        }
        let mut s = format!("  <{outer}>\n");
        for i in items {
            let _ = writeln!(s, "    <{inner}>{}</{inner}>", text(i));
        }
        let _ = writeln!(s, "  </{outer}>");
        s
    };
    let mut s = format!("{HEAD}<Extensions>\n");
    s.push_str(&list("TopicTypes", "TopicType", &[TOPIC_TYPE]));
    s.push_str(&list(
        "TopicStatuses",
        "TopicStatus",
        &[TOPIC_STATUS, "Closed"],
    ));
    s.push_str(&list("Priorities", "Priority", &priorities));
    s.push_str(&list("TopicLabels", "TopicLabel", &labels));
    s.push_str(&list("Users", "User", &[AUTHOR]));
    s.push_str(&list("SnippetTypes", "SnippetType", &[]));
    s.push_str(&list("Stages", "Stage", &[]));
    s.push_str("</Extensions>\n");
    s
}

/// A topic's `markup.bcf`. `model` is the IFC file's name for the header; `date` an
/// `xs:dateTime`; `viewpoint` the viewpoint's GUID when the topic has one (with
/// `snapshot` when it has a picture).
pub fn markup(
    v: BcfVersion,
    issue: &Issue,
    model: Option<&str>,
    date: &str,
    viewpoint: Option<&str>,
    snapshot: bool,
) -> String {
    let mut s = format!("{HEAD}<Markup>\n");
    if let Some(m) = model {
        let file = |indent: &str| {
            format!(
                "{indent}<File>\n{indent}  <Filename>{}</Filename>\n{indent}</File>\n",
                text(m)
            )
        };
        match v {
            BcfVersion::V3_0 => {
                let _ = write!(
                    s,
                    "  <Header>\n    <Files>\n{}    </Files>\n  </Header>\n",
                    file("      ")
                );
            }
            BcfVersion::V2_1 => {
                let _ = write!(s, "  <Header>\n{}  </Header>\n", file("    "));
            }
        }
    }
    let _ = writeln!(
        s,
        "  <Topic Guid=\"{}\" TopicType=\"{TOPIC_TYPE}\" TopicStatus=\"{TOPIC_STATUS}\">",
        issue.guid
    );
    let _ = writeln!(s, "    <Title>{}</Title>", text(&issue.title));
    let _ = writeln!(s, "    <Priority>{}</Priority>", issue.priority);
    match v {
        BcfVersion::V3_0 => {
            s.push_str("    <Labels>\n");
            for l in &issue.labels {
                let _ = writeln!(s, "      <Label>{}</Label>", text(l));
            }
            s.push_str("    </Labels>\n");
        }
        BcfVersion::V2_1 => {
            for l in &issue.labels {
                let _ = writeln!(s, "    <Labels>{}</Labels>", text(l));
            }
        }
    }
    let _ = writeln!(s, "    <CreationDate>{date}</CreationDate>");
    let _ = writeln!(s, "    <CreationAuthor>{AUTHOR}</CreationAuthor>");
    let _ = writeln!(
        s,
        "    <Description>{}</Description>",
        text(&issue.description)
    );
    let files = |indent: &str| {
        let mut f = format!("{indent}<Viewpoint>{VIEWPOINT_FILE}</Viewpoint>\n");
        if snapshot {
            let _ = writeln!(f, "{indent}<Snapshot>{SNAPSHOT_FILE}</Snapshot>");
        }
        f
    };
    match (v, viewpoint) {
        (BcfVersion::V3_0, Some(g)) => {
            let _ = write!(
                s,
                "    <Viewpoints>\n      <ViewPoint Guid=\"{g}\">\n{}      </ViewPoint>\n    </Viewpoints>\n",
                files("        ")
            );
            s.push_str("  </Topic>\n");
        }
        (BcfVersion::V2_1, Some(g)) => {
            s.push_str("  </Topic>\n");
            let _ = write!(
                s,
                "  <Viewpoints Guid=\"{g}\">\n{}  </Viewpoints>\n",
                files("    ")
            );
        }
        (_, None) => s.push_str("  </Topic>\n"),
    }
    s.push_str("</Markup>\n");
    s
}

/// A topic's `viewpoint.bcfv`: the element (when it has an IFC GlobalId) selected and
/// coloured `colour` (`RRGGBB`), everything else visible, spaces shown for a space topic, and
/// the perspective camera; `aspect` is the snapshot's width over height.
pub fn viewpoint(
    v: BcfVersion,
    guid: &str,
    ifc_guid: Option<&str>,
    colour: &str,
    show_spaces: bool,
    camera: &Camera,
    aspect: f64,
) -> String {
    let mut s = format!("{HEAD}<VisualizationInfo Guid=\"{guid}\">\n");
    if let Some(id) = ifc_guid {
        let component = format!("<Component IfcGuid=\"{}\"/>", text(id));
        let hints = format!(
            "<ViewSetupHints SpacesVisible=\"{show_spaces}\" SpaceBoundariesVisible=\"false\" OpeningsVisible=\"false\"/>"
        );
        let _ = writeln!(s, "  <Components>");
        // 2.1 puts the hints first among the components, 3.0 inside the visibility.
        if v == BcfVersion::V2_1 {
            let _ = writeln!(s, "    {hints}");
        }
        let _ = writeln!(s, "    <Selection>\n      {component}\n    </Selection>");
        match v {
            BcfVersion::V3_0 => {
                let _ = writeln!(
                    s,
                    "    <Visibility DefaultVisibility=\"true\">\n      {hints}\n    </Visibility>"
                );
            }
            BcfVersion::V2_1 => {
                let _ = writeln!(s, "    <Visibility DefaultVisibility=\"true\"/>");
            }
        }
        match v {
            BcfVersion::V3_0 => {
                let _ = writeln!(
                    s,
                    "    <Coloring>\n      <Color Color=\"{colour}\">\n        <Components>\n          {component}\n        </Components>\n      </Color>\n    </Coloring>"
                );
            }
            BcfVersion::V2_1 => {
                let _ = writeln!(
                    s,
                    "    <Coloring>\n      <Color Color=\"{colour}\">\n        {component}\n      </Color>\n    </Coloring>"
                );
            }
        }
        let _ = writeln!(s, "  </Components>");
    }
    s.push_str("  <PerspectiveCamera>\n");
    point(&mut s, "CameraViewPoint", camera.position);
    point(&mut s, "CameraDirection", camera.direction);
    point(&mut s, "CameraUpVector", camera.up);
    let _ = writeln!(
        s,
        "    <FieldOfView>{}</FieldOfView>",
        number(camera.field_of_view_deg)
    );
    if v == BcfVersion::V3_0 {
        let _ = writeln!(s, "    <AspectRatio>{}</AspectRatio>", number(aspect));
    }
    s.push_str("  </PerspectiveCamera>\n</VisualizationInfo>\n");
    s
}

fn point(s: &mut String, tag: &str, p: DVec3) {
    let _ = writeln!(
        s,
        "    <{tag}>\n      <X>{}</X>\n      <Y>{}</Y>\n      <Z>{}</Z>\n    </{tag}>",
        number(p.x),
        number(p.y),
        number(p.z)
    );
}

/// A number with six decimals (micrometres), never `-0`.
fn number(x: f64) -> String {
    let s = format!("{x:.6}");
    if s.trim_start_matches('-')
        .bytes()
        .all(|b| b == b'0' || b == b'.')
    {
        "0.000000".into()
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_escapes_markup_and_drops_illegal_characters() {
        assert_eq!(
            text("a<b & \"c\"\u{1}"),
            "a&lt;b &amp; &quot;c&quot;\u{FFFD}"
        );
        assert_eq!(number(-0.0000001), "0.000000");
        assert_eq!(number(1.5), "1.500000");
    }
}
