//! Classification: apply the rules and a robot profile to every candidate element of a model,
//! giving its POI category, type, roles, accessibility and coordination values.

use poinav_ifc::{spatial, Entity, EntityId, Model};
use poinav_roles::{
    clear_width_status, slope_status, stairs_status, Accessibility, AccessibilityStatus, Category,
    Coordination, PoiType, RobotProfile, Role, ValidationMethod,
};
use rayon::prelude::*;

use crate::facts::{FactContext, Facts};
use crate::rules::{AccessibilityKind, RuleSet};

/// One classified element.
#[derive(Debug, Clone, PartialEq)]
pub struct Classified {
    /// The element.
    pub id: EntityId,
    /// Its GlobalId.
    pub global_id: String,
    /// Its class (`IfcDoor`).
    pub class: String,
    /// Its Name.
    pub name: Option<String>,
    /// Its storey's name.
    pub storey: Option<String>,
    /// The winning rule's id.
    pub rule: String,
    /// POI_Category.
    pub category: Category,
    /// POI_Type.
    pub poi_type: PoiType,
    /// POI_PrimaryRoles.
    pub primary: Vec<Role>,
    /// POI_ConditionalRoles.
    pub conditional: Vec<Role>,
    /// How the winning rule decides AccessibilityStatus (what `accessibility` was made from,
    /// besides the facts and the profile).
    pub accessibility_kind: AccessibilityKind,
    /// Pset_RobotAccessibility, when the rule asks for it.
    pub accessibility: Option<Accessibility>,
    /// Pset_RobotCoordination, when the rule gives it.
    pub coordination: Option<Coordination>,
    /// What the rules saw.
    pub facts: Facts,
}

/// The classification of a model for one profile.
#[derive(Debug, Clone)]
pub struct Classification {
    /// The profile used.
    pub profile: RobotProfile,
    /// Classified elements in file order.
    pub elements: Vec<Classified>,
}

impl Classified {
    /// What rule R5 reads and changes of this element ([`crate::runtime::apply`]).
    pub fn roles_mut(&mut self) -> poinav_roles::runtime::RolesMut<'_> {
        poinav_roles::runtime::RolesMut {
            primary: &self.primary,
            conditional: &mut self.conditional,
            accessibility: self.accessibility.as_mut(),
            coordination: self.coordination.as_ref(),
        }
    }
}

impl Classification {
    /// The element `id`, if it was classified.
    pub fn get(&self, id: EntityId) -> Option<&Classified> {
        self.elements
            .binary_search_by_key(&id, |c| c.id)
            .ok()
            .map(|i| &self.elements[i])
            .or_else(|| self.elements.iter().find(|c| c.id == id))
    }
}

fn element_access(
    kind: AccessibilityKind,
    facts: &Facts,
    profile: &RobotProfile,
) -> Option<(AccessibilityStatus, String)> {
    Some(match kind {
        AccessibilityKind::None | AccessibilityKind::Space => return None,
        AccessibilityKind::Blocked => (
            AccessibilityStatus::Blocked,
            format!("{} is not passable by a ground robot", facts.class),
        ),
        AccessibilityKind::Stairs => stairs_status(profile),
        AccessibilityKind::Slope => {
            let (status, reason) = slope_status(facts.slope_deg, profile);
            match facts.slope_source.filter(|s| *s != "property") {
                Some(source) => (status, format!("{reason} (from its {source})")),
                None => (status, reason),
            }
        }
        AccessibilityKind::ClearWidth => clear_width_status(
            facts.clear_width_m,
            Some(facts.clear_width_source.unwrap_or("unknown")),
            profile,
        ),
    })
}

/// Classifies every element of `model` that a rule matches, for `profile`.
pub fn classify(model: &Model, rules: &RuleSet, profile: &RobotProfile) -> Classification {
    let ctx = FactContext::new(model);
    let mut candidates: Vec<Entity<'_>> = rules
        .classes()
        .iter()
        .flat_map(|c| model.instances_of(c))
        .collect();
    candidates.sort_by_key(|e| e.position());
    candidates.dedup_by_key(|e| e.position());
    let mut elements: Vec<Classified> = candidates
        .par_iter()
        .filter_map(|&e| {
            let facts = ctx.facts_with(e, rules.needs_properties(&e));
            let rule = rules.winner(&e, &facts, profile)?;
            if rule.skip {
                return None;
            }
            let mut conditional: Vec<Role> = rule
                .conditional
                .iter()
                .filter(|c| c.when.holds(&facts, profile))
                .map(|c| c.role)
                .collect();
            conditional.dedup();
            let accessibility =
                element_access(rule.accessibility, &facts, profile).map(|(status, reason)| {
                    Accessibility {
                        min_clearance_width_m: profile.min_clearance_width(),
                        min_clearance_height_m: profile.min_clearance_height(),
                        status,
                        method: ValidationMethod::GeometricAnalysis,
                        reason,
                    }
                });
            let needs_space_access = rule.accessibility == AccessibilityKind::Space;
            let mut c = Classified {
                id: e.id(),
                global_id: e.global_id().unwrap_or_default(),
                class: e.type_name().to_string(),
                name: e.name(),
                storey: spatial::storey_of(e).map(spatial::label_of),
                rule: rule.id.clone(),
                category: rule.category.expect("compiled rules have a category"),
                poi_type: rule.poi_type.expect("compiled rules have a type"),
                primary: rule.roles.clone(),
                conditional,
                accessibility_kind: rule.accessibility,
                accessibility,
                coordination: rule.coordination.clone(),
                facts,
            };
            if needs_space_access {
                // Filled in below, once every door has its status.
                c.accessibility = Some(Accessibility {
                    min_clearance_width_m: profile.min_clearance_width(),
                    min_clearance_height_m: profile.min_clearance_height(),
                    status: AccessibilityStatus::PendingValidation,
                    method: ValidationMethod::GeometricAnalysis,
                    reason: String::new(),
                });
            }
            Some(c)
        })
        .collect();
    elements.sort_by_key(|c| c.id);
    let mut result = Classification {
        profile: profile.clone(),
        elements,
    };
    space_access(&ctx, &mut result);
    result
        .elements
        .sort_by_key(|c| model.entity(c.id).map(|e| e.position()));
    result
}

/// A space's status from its doors: FULL_ACCESS if one door is, else RESTRICTED if one is,
/// else BLOCKED; PENDING_VALIDATION when no door is known.
fn space_access(ctx: &FactContext<'_>, result: &mut Classification) {
    use AccessibilityStatus::*;
    let mut updates = Vec::new();
    for (i, c) in result.elements.iter().enumerate() {
        if c.class != "IfcSpace" || c.accessibility.is_none() {
            continue;
        }
        let doors = ctx.doors_of_space(c.id);
        let statuses: Vec<AccessibilityStatus> = doors
            .iter()
            .filter_map(|d| result.elements.binary_search_by_key(d, |x| x.id).ok())
            .filter_map(|k| result.elements[k].accessibility.as_ref().map(|a| a.status))
            .collect();
        let count = |s| statuses.iter().filter(|&&x| x == s).count();
        let (status, reason) = if statuses.is_empty() {
            (
                PendingValidation,
                "no door on the space boundary is known".to_string(),
            )
        } else if count(FullAccess) > 0 {
            (
                FullAccess,
                format!(
                    "{} of {} doors FULL_ACCESS",
                    count(FullAccess),
                    statuses.len()
                ),
            )
        } else if count(Restricted) > 0 {
            (
                Restricted,
                format!(
                    "no door FULL_ACCESS, {} of {} RESTRICTED",
                    count(Restricted),
                    statuses.len()
                ),
            )
        } else {
            (
                Blocked,
                format!("all {} doors BLOCKED or unknown", statuses.len()),
            )
        };
        updates.push((i, status, reason));
    }
    for (i, status, reason) in updates {
        if let Some(a) = result.elements[i].accessibility.as_mut() {
            a.status = status;
            a.reason = reason;
        }
    }
}
