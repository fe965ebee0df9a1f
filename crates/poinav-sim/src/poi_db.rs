//! The POI database Algorithm 1 queries (paper: `QueryDatabase(D, GUID)`): one
//! [`PoiRecord`] per obstacle, door and zone of the floor, found by GlobalId or by the index the
//! world reports, and changed at run time only through `poinav_roles::runtime::apply` (rule R5),
//! the same code the write-back uses.

use std::collections::BTreeMap;

use poinav_nav::door_status::classified_status;
use poinav_nav::{DoorIdx, Floor, ObstacleIdx, ObstacleKind, ZoneIdx};
use poinav_roles::runtime::{self, Observation, RuntimeChange};
use poinav_roles::{
    Accessibility, AccessibilityStatus, AppliesTo, Category, Coordination, PoiRecord, PoiType,
    RobotProfile, Role, ValidationMethod,
};

/// A set of roles as bits (index in `Role::ALL`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, PartialOrd, Ord, Hash)]
pub struct RoleSet(pub u16);

impl RoleSet {
    fn bit(r: Role) -> u16 {
        1 << Role::ALL.iter().position(|x| *x == r).expect("role in ALL")
    }

    /// The set of `roles`.
    pub fn of(roles: &[Role]) -> RoleSet {
        RoleSet(roles.iter().fold(0, |m, r| m | Self::bit(*r)))
    }

    /// True when `r` is in the set.
    #[inline]
    pub fn has(self, r: Role) -> bool {
        self.0 & Self::bit(r) != 0
    }

    /// Adds `r`.
    pub fn insert(&mut self, r: Role) {
        self.0 |= Self::bit(r);
    }

    /// The set without `r`.
    pub fn without(self, r: Role) -> RoleSet {
        RoleSet(self.0 & !Self::bit(r))
    }

    /// The union.
    pub fn union(self, o: RoleSet) -> RoleSet {
        RoleSet(self.0 | o.0)
    }

    /// The roles, in taxonomy order.
    pub fn roles(self) -> impl Iterator<Item = Role> {
        self.indices().map(|k| Role::ALL[k])
    }

    /// The roles' indices in `Role::ALL`, ascending (what a table per role is indexed by).
    pub fn indices(self) -> impl Iterator<Item = usize> {
        (0..Role::ALL.len()).filter(move |&k| self.0 & (1 << k) != 0)
    }
}

/// What kind of floor element a record describes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Element {
    /// A floor obstacle.
    Obstacle(ObstacleIdx),
    /// A floor door.
    Door(DoorIdx),
    /// A floor zone.
    Zone(ZoneIdx),
}

/// How the database starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Start {
    /// With the floor's roles and the enrichment's statuses (the classification's verdict on
    /// each door for the database's profile, [`classified_status`]).
    #[default]
    Keep,
    /// Without conditional roles, doors PENDING_VALIDATION: the sensors decide.
    Clear,
}

/// The records of one floor.
#[derive(Debug, Clone)]
pub struct PoiDb {
    records: Vec<PoiRecord>,
    roles: Vec<RoleSet>,
    by_id: BTreeMap<String, usize>,
    doors_at: usize,
    zones_at: usize,
}

fn split(roles: &[Role], start: Start) -> (Vec<Role>, Vec<Role>) {
    let conditional = |r: &Role| matches!(r, Role::Narrow | Role::RobotInteraction);
    let primary: Vec<Role> = roles.iter().copied().filter(|r| !conditional(r)).collect();
    let mut cond: Vec<Role> = match start {
        Start::Keep => roles.iter().copied().filter(conditional).collect(),
        Start::Clear => Vec::new(),
    };
    cond.sort();
    cond.dedup();
    (primary, cond)
}

fn record(
    global_id: &str,
    class: &str,
    name: Option<String>,
    category: Category,
    poi_type: PoiType,
    roles: (Vec<Role>, Vec<Role>),
) -> PoiRecord {
    PoiRecord {
        global_id: global_id.to_string(),
        class: class.to_string(),
        name,
        category,
        poi_type,
        primary: roles.0,
        conditional: roles.1,
        accessibility: None,
        coordination: None,
    }
}

impl PoiDb {
    /// Records for every obstacle, door and zone of `floor`, in that order; the doors'
    /// Pset_RobotAccessibility values are for `profile` (the enrichment's).
    pub fn new(floor: &Floor, start: Start, profile: &RobotProfile) -> PoiDb {
        let mut records = Vec::new();
        for o in &floor.obstacles {
            let (category, poi_type) = match o.kind {
                ObstacleKind::Structure => (Category::Structural, PoiType::BoundaryElement),
                ObstacleKind::Furniture | ObstacleKind::Unknown => {
                    (Category::ObjectBased, PoiType::FixedObject)
                }
                ObstacleKind::DoorLeaf | ObstacleKind::Transition => {
                    (Category::Structural, PoiType::TransitionElement)
                }
            };
            records.push(record(
                &o.id,
                &o.class,
                None,
                category,
                poi_type,
                split(&o.roles, start),
            ));
        }
        let doors_at = records.len();
        for d in &floor.doors {
            let mut r = record(
                &d.id,
                "IfcDoor",
                d.name.clone(),
                Category::Structural,
                PoiType::TransitionElement,
                split(&d.roles, start),
            );
            r.accessibility = Some(Accessibility {
                min_clearance_width_m: profile.min_clearance_width(),
                min_clearance_height_m: 0.0,
                status: match start {
                    Start::Keep => classified_status(d, profile).0,
                    Start::Clear => AccessibilityStatus::PendingValidation,
                },
                method: ValidationMethod::GeometricAnalysis,
                reason: String::new(),
            });
            records.push(r);
        }
        let zones_at = records.len();
        for z in &floor.zones {
            let mut r = record(
                &z.id,
                "IfcSpace",
                z.name.clone(),
                Category::Functional,
                PoiType::SpaceType,
                split(&z.roles, start),
            );
            r.coordination = z.coordination.map(|(sep, protocol)| Coordination {
                max_robots: 0,
                min_separation_m: sep,
                protocol,
                applies_to: AppliesTo::AllRobots,
            });
            records.push(r);
        }
        let roles = records
            .iter()
            .map(|r| RoleSet::of(&r.primary).union(RoleSet::of(&r.conditional)))
            .collect();
        let mut by_id = BTreeMap::new();
        for (i, r) in records.iter().enumerate() {
            by_id.entry(r.global_id.clone()).or_insert(i);
        }
        PoiDb {
            records,
            roles,
            by_id,
            doors_at,
            zones_at,
        }
    }

    /// The record index of a floor element.
    #[inline]
    pub fn index(&self, e: Element) -> usize {
        match e {
            Element::Obstacle(i) => i.get(),
            Element::Door(i) => self.doors_at + i.get(),
            Element::Zone(i) => self.zones_at + i.get(),
        }
    }

    /// The record with this GlobalId.
    pub fn find(&self, global_id: &str) -> Option<&PoiRecord> {
        self.by_id.get(global_id).map(|&i| &self.records[i])
    }

    /// Record `i`.
    pub fn get(&self, i: usize) -> &PoiRecord {
        &self.records[i]
    }

    /// Primary and conditional roles of record `i`.
    #[inline]
    pub fn roles(&self, i: usize) -> RoleSet {
        self.roles[i]
    }

    /// Applies rule R5 to record `i`.
    pub fn apply(&mut self, i: usize, observation: Observation) -> RuntimeChange {
        let change = runtime::apply(self.records[i].roles_mut(), observation);
        if !change.is_empty() {
            let r = &self.records[i];
            self.roles[i] = RoleSet::of(&r.primary).union(RoleSet::of(&r.conditional));
        }
        change
    }

    /// Every record.
    pub fn records(&self) -> &[PoiRecord] {
        &self.records
    }
}
