//! Warnings on standard error, summarised: one line per (class, reason) with a count and the
//! first `#id`s, so a model with ten thousand unreadable elements prints a screenful, not ten
//! thousand lines. `--verbose` lists every warning, `--quiet` none; `--json` outputs carry the
//! full list ([`to_json`]). Every command prints its warnings through [`print()`].

use serde::Serialize;

/// Most summary lines printed; the rest are counted on one line.
pub const MAX_LINES: usize = 20;
/// `#id`s shown per summary line.
pub const SHOWN_IDS: usize = 5;
/// Groups of up to this many warnings print each one in full.
pub const IN_FULL: usize = 3;

/// One warning: what it is about and why.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Warning {
    /// The instance it is about (`#123` or a GlobalId), if one.
    pub id: Option<String>,
    /// Its IFC class (or kind: `stair`, `storey`), if known.
    pub class: Option<String>,
    /// The whole message, as `--verbose` prints it (after `id: `).
    pub message: String,
    /// What warnings are grouped by besides the class: the message without instance ids.
    #[serde(skip)]
    pub reason: String,
}

impl Warning {
    /// A warning about instance `id` of `class`; grouped by `message` without its `#id`s.
    pub fn of(
        id: impl std::fmt::Display,
        class: Option<String>,
        message: impl Into<String>,
    ) -> Warning {
        let id = id.to_string();
        let message = message.into();
        Warning {
            reason: without_ids(message.strip_prefix(&format!("{id}: ")).unwrap_or(&message)),
            id: Some(id),
            class,
            message,
        }
    }

    /// A warning about no instance in particular.
    pub fn plain(message: impl Into<String>) -> Warning {
        let message = message.into();
        Warning {
            reason: without_ids(&message),
            id: None,
            class: None,
            message,
        }
    }

    /// Groups this warning with others of its class by `reason` instead of its message.
    pub fn grouped_by(mut self, reason: impl Into<String>) -> Warning {
        self.reason = reason.into();
        self
    }

    /// The line `--verbose` prints (without `warning: `): the message, after the id unless
    /// the message names it.
    pub fn line(&self) -> String {
        match &self.id {
            Some(id) if !self.message.contains(id.as_str()) => crate::with_id(id, &self.message),
            _ => self.message.clone(),
        }
    }
}

/// `text` with every `#123` written `#…`, so messages differing only in ids group together,
/// and without a leading `#123: `.
fn without_ids(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        out.push(c);
        if c == '#' && chars.peek().is_some_and(char::is_ascii_digit) {
            while chars.peek().is_some_and(char::is_ascii_digit) {
                chars.next();
            }
            out.push('…');
        }
    }
    match out.strip_prefix("#…: ") {
        Some(rest) => rest.to_string(),
        None => out,
    }
}

/// Warnings of one class and reason.
#[derive(Debug, Clone, PartialEq)]
pub struct Group<'w> {
    /// The first warning of the group.
    pub first: &'w Warning,
    /// How many.
    pub count: usize,
    /// The first [`SHOWN_IDS`].
    pub members: Vec<&'w Warning>,
}

/// `warnings` grouped by (class, reason), in the order each group first appears.
pub fn groups(warnings: &[Warning]) -> Vec<Group<'_>> {
    let mut index: std::collections::HashMap<(Option<&str>, &str), usize> =
        std::collections::HashMap::new();
    let mut out: Vec<Group<'_>> = Vec::new();
    for w in warnings {
        let key = (w.class.as_deref(), w.reason.as_str());
        let g = *index.entry(key).or_insert_with(|| {
            out.push(Group {
                first: w,
                count: 0,
                members: Vec::new(),
            });
            out.len() - 1
        });
        let g = &mut out[g];
        g.count += 1;
        if g.members.len() < SHOWN_IDS {
            g.members.push(w);
        }
    }
    out
}

/// The summary lines of `warnings` (each starting `warning: ` or `note: `): a group of up to
/// [`IN_FULL`] warnings in full, a larger one on one line with its count and first ids.
pub fn summary(warnings: &[Warning]) -> Vec<String> {
    let groups = groups(warnings);
    let mut lines: Vec<String> = Vec::new();
    let mut shown = 0;
    for g in &groups {
        let group_lines = group_lines(g);
        if lines.len() + group_lines.len() > MAX_LINES {
            break;
        }
        lines.extend(group_lines);
        shown += 1;
    }
    if shown < groups.len() {
        let rest: usize = groups[shown..].iter().map(|g| g.count).sum();
        lines.push(format!(
            "warning: ... and {} more warnings of {} other kinds",
            thousands(rest),
            groups.len() - shown
        ));
    }
    if warnings.len() > lines.len() {
        lines.push(format!(
            "note: {} warnings summarised in {} lines; --verbose lists each one",
            thousands(warnings.len()),
            lines.len()
        ));
    }
    lines
}

fn group_lines(g: &Group<'_>) -> Vec<String> {
    if g.count <= IN_FULL {
        return g
            .members
            .iter()
            .map(|w| format!("warning: {}", w.line()))
            .collect();
    }
    let ids: Vec<&str> = g.members.iter().filter_map(|w| w.id.as_deref()).collect();
    let ids = if ids.is_empty() {
        String::new()
    } else {
        let more = match g.count - ids.len() {
            0 => String::new(),
            n => format!(" and {} more", thousands(n)),
        };
        format!(": {}{more}", ids.join(", "))
    };
    vec![match &g.first.class {
        Some(class) => format!(
            "warning: {} {class}: {}{ids}",
            thousands(g.count),
            g.first.reason
        ),
        None => format!(
            "warning: {} ({} times){ids}",
            g.first.reason,
            thousands(g.count)
        ),
    }]
}

/// Prints `warnings` on standard error: summarised, each (`--verbose`) or none (`--quiet`).
pub fn print(warnings: &[Warning]) {
    let flags = crate::flags();
    if flags.quiet || warnings.is_empty() {
        return;
    }
    crate::progress::suspend(|| {
        if flags.verbose {
            for w in warnings {
                errln!("warning: {}", w.line());
            }
        } else {
            for line in summary(warnings) {
                errln!("{line}");
            }
        }
    });
}

/// The elements navigation gave up on ([`poinav_nav::bounds`]) as warnings, one per element,
/// grouped by class, stage, kind of bound and outcome.
pub fn gave_up(list: &[poinav_nav::GaveUp]) -> Vec<Warning> {
    list.iter()
        .map(|g| Warning::of(&g.element, Some(g.class.clone()), g.message()).grouped_by(g.reason()))
        .collect()
}

/// The elements meshed without an opening or boolean operand that could not be made
/// ([`poinav_geom::ModelMeshes::uncut`]), as warnings: every command that meshes a model
/// prints them.
pub fn uncut(model: &poinav_ifc::Model, meshes: &poinav_geom::ModelMeshes) -> Vec<Warning> {
    uncut_of(model, &meshes.uncut)
}

/// [`uncut`] from the list alone (a prepared scenario keeps it, not the meshes).
pub fn uncut_of(
    model: &poinav_ifc::Model,
    uncut: &[(poinav_ifc::EntityId, poinav_geom::GeomError)],
) -> Vec<Warning> {
    uncut
        .iter()
        .map(|(id, e)| {
            let class = model.entity(*id).map(|e| e.type_name().to_string());
            Warning::of(id, class, e.to_string())
        })
        .collect()
}

/// What making a building left out (grouped like the plan's), then the elements meshed uncut
/// and the building's own diagnostics: route, audit, export nav2 and simulate print the same.
pub fn of_building(
    model: &poinav_ifc::Model,
    dropped: &[poinav_bridge::Dropped],
    uncut: &[(poinav_ifc::EntityId, poinav_geom::GeomError)],
    building: &poinav_nav::Building,
) -> Vec<Warning> {
    let mut warnings: Vec<Warning> = dropped
        .iter()
        .map(|d| {
            Warning::of(&d.id, Some(d.kind.label().to_string()), d.message()).grouped_by(d.group())
        })
        .collect();
    warnings.extend(uncut_of(model, uncut));
    warnings.extend(building.diagnostics().into_iter().map(Warning::plain));
    warnings
}

/// The full list for `--json` outputs: `[{"id", "class", "message"}]`.
pub fn to_json(warnings: &[Warning]) -> serde_json::Value {
    serde_json::to_value(warnings).unwrap_or_default()
}

/// `12345` as `12,345`.
pub fn thousands(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn failed(id: u64, item: u64) -> Warning {
        Warning::of(
            format!("#{id}"),
            Some("IfcRailwayPart".into()),
            format!("#{item}: IfcLinearPlacement is not supported (placement) (left out)"),
        )
    }

    #[test]
    fn warnings_differing_only_in_ids_are_one_line_with_the_count_and_first_ids() {
        let mut w: Vec<Warning> = (0..1234).map(|i| failed(10 + i, 5000 + i)).collect();
        w.push(Warning::plain("storey Roof has no spaces"));
        let lines = summary(&w);
        assert_eq!(
            lines,
            [
                "warning: 1,234 IfcRailwayPart: IfcLinearPlacement is not supported (placement) (left out): #10, #11, #12, #13, #14 and 1,229 more",
                "warning: storey Roof has no spaces",
                "note: 1,235 warnings summarised in 2 lines; --verbose lists each one",
            ]
        );
    }

    #[test]
    fn few_distinct_warnings_print_as_they_are_without_a_note() {
        let w = vec![failed(1, 2), Warning::plain("a"), Warning::plain("b")];
        let lines = summary(&w);
        assert_eq!(lines.len(), 3);
        assert_eq!(
            lines[0],
            "warning: #1: #2: IfcLinearPlacement is not supported (placement) (left out)"
        );
    }

    #[test]
    fn more_kinds_than_lines_are_counted_on_one_line() {
        let w: Vec<Warning> = (0..30)
            .flat_map(|k| (0..5).map(move |_| Warning::plain(format!("kind {k}"))))
            .collect();
        let lines = summary(&w);
        assert_eq!(lines.len(), MAX_LINES + 2);
        assert_eq!(lines[0], "warning: kind 0 (5 times)");
        assert_eq!(
            lines[MAX_LINES],
            "warning: ... and 50 more warnings of 10 other kinds"
        );
        assert_eq!(
            lines[MAX_LINES + 1],
            "note: 150 warnings summarised in 21 lines; --verbose lists each one"
        );
    }

    #[test]
    fn small_groups_are_printed_in_full() {
        let w = vec![failed(1, 2), failed(3, 4), Warning::plain("a")];
        assert_eq!(
            summary(&w),
            [
                "warning: #1: #2: IfcLinearPlacement is not supported (placement) (left out)",
                "warning: #3: #4: IfcLinearPlacement is not supported (placement) (left out)",
                "warning: a",
            ]
        );
    }

    #[test]
    fn thousands_are_separated() {
        assert_eq!(thousands(0), "0");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(9937), "9,937");
        assert_eq!(thousands(1_234_567), "1,234,567");
    }
}
