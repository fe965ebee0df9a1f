//! Deterministic BCF GUIDs: UUID version 5 from what a topic is about, so running the audit
//! again gives the same topic the same GUID and BCF tools update it instead of adding a copy.

use uuid::Uuid;

/// poinav's namespace for BCF GUIDs: UUID v5 of `poinav:bcf` in the URL namespace.
fn namespace() -> Uuid {
    Uuid::new_v5(&Uuid::NAMESPACE_URL, b"poinav:bcf")
}

/// The GUID of the topic about element `element` (an IFC GlobalId) of kind `kind` (`door`,
/// `stair`, `ramp`, `lift`, `space`) for profile `profile`: lower-case, hyphenated, as BCF's
/// `Guid` type requires.
pub fn topic_guid(profile: &str, element: &str, kind: &str) -> String {
    let name = format!("topic\n{profile}\n{element}\n{kind}");
    Uuid::new_v5(&namespace(), name.as_bytes())
        .hyphenated()
        .to_string()
}

/// The GUID of a topic's viewpoint (one per topic).
pub fn viewpoint_guid(topic: &str) -> String {
    let name = format!("viewpoint\n{topic}");
    Uuid::new_v5(&namespace(), name.as_bytes())
        .hyphenated()
        .to_string()
}

/// The GUID of the BCF project of a model file name.
pub fn project_guid(model: &str) -> String {
    let name = format!("project\n{model}");
    Uuid::new_v5(&namespace(), name.as_bytes())
        .hyphenated()
        .to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn guids_are_stable_lower_case_and_distinct() {
        let a = topic_guid("paper-robot", "1giqnsgvr6uA16isIlsnHU", "door");
        assert_eq!(
            a,
            topic_guid("paper-robot", "1giqnsgvr6uA16isIlsnHU", "door")
        );
        assert_eq!(a.len(), 36);
        assert_eq!(a.as_bytes()[14], b'5', "version 5: {a}");
        assert!(a
            .chars()
            .all(|c| c == '-' || c.is_ascii_digit() || ('a'..='f').contains(&c)));
        assert_ne!(a, topic_guid("other", "1giqnsgvr6uA16isIlsnHU", "door"));
        assert_ne!(
            a,
            topic_guid("paper-robot", "1giqnsgvr6uA16isIlsnHU", "space")
        );
        assert_ne!(a, viewpoint_guid(&a));
    }
}
