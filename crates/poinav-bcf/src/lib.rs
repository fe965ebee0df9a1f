//! BCF issues from poinav's accessibility audit, for designers to fix in their BIM tools
//! (Bonsai, BIMcollab, Revit and Archicad plugins).
//!
//! One topic per door passage, stair, ramp or lift that is BLOCKED or RESTRICTED for a robot
//! profile and per space the profile cannot reach ([`issue`]): a title and a description with
//! the widths, the profile and the reason, labels (profile, status, kind), and one viewpoint
//! with the element's IfcGuid selected and coloured in its status colour, a perspective camera
//! at eye height in front of it ([`camera`]) and a snapshot of the plan around it
//! ([`snapshot`]). BCF 3.0 by default, 2.1 on request ([`BcfVersion`]).
//!
//! The output is deterministic: topic and viewpoint GUIDs are UUID v5 of profile, element
//! GlobalId and kind ([`guid`]), so a second run updates the same topics; the creation date and
//! every zip entry's time come from [`BcfOptions::created_s`]; entries are written in a fixed
//! order ([`archive`]). Reads the audit and the plain building model, never IFC.

pub mod archive;
pub mod camera;
mod error;
pub mod guid;
pub mod issue;
pub mod snapshot;
pub mod xml;

use std::collections::BTreeMap;
use std::path::Path;

use poinav_nav::grid::{GridOptions, OccupancyGrid};
use poinav_nav::{AuditReport, Building};
use poinav_poi::RobotProfile;

pub use error::BcfError;
pub use issue::{Focus, Issue, IssueKind};

/// Which BCF version to write.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BcfVersion {
    /// BCF 3.0 (default).
    #[default]
    V3_0,
    /// BCF 2.1.
    V2_1,
}

impl BcfVersion {
    /// `3.0` or `2.1`.
    pub fn label(self) -> &'static str {
        match self {
            BcfVersion::V3_0 => "3.0",
            BcfVersion::V2_1 => "2.1",
        }
    }
}

/// How to write the BCF.
#[derive(Debug, Clone, PartialEq)]
pub struct BcfOptions {
    /// BCF version.
    pub version: BcfVersion,
    /// How the audit rasterised storeys (the snapshots draw the same grids; the storey's
    /// ground level is set per storey from the building).
    pub grid: GridOptions,
    /// The IFC file's name, for each topic's header and the project's name.
    pub model: Option<String>,
    /// Creation date of the topics and time of the zip entries, seconds since 1970 (UTC).
    pub created_s: i64,
}

/// The BCF archive's bytes for `report` (an audit of `building` for `profiles`, in the same
/// order), and the topics in it.
pub fn bcf_bytes(
    report: &AuditReport,
    building: &Building,
    profiles: &[RobotProfile],
    options: &BcfOptions,
) -> Result<(Vec<u8>, Vec<Issue>), BcfError> {
    if profiles.len() != report.profiles.len() {
        return Err(BcfError::Profiles {
            audited: report.profiles.len(),
            given: profiles.len(),
        });
    }
    let v = options.version;
    let issues = issue::issues(report, building);
    let date = format!("{}Z", poinav_ifc::timestamp::iso8601_utc(options.created_s));
    let mut zip = archive::Archive::new(options.created_s);
    zip.add("bcf.version", xml::version(v).as_bytes())?;
    let name = options.model.as_deref().unwrap_or("poinav audit");
    zip.add(
        "project.bcfp",
        xml::project(v, &guid::project_guid(name), name).as_bytes(),
    )?;
    if v == BcfVersion::V3_0 {
        zip.add("extensions.xml", xml::extensions(&issues).as_bytes())?;
    }
    let mut grids: BTreeMap<(usize, usize), OccupancyGrid> = BTreeMap::new();
    let aspect = f64::from(snapshot::WIDTH) / f64::from(snapshot::HEIGHT);
    for i in &issues {
        let seen = match (i.floor, &i.focus) {
            (Some(fi), Some(focus)) => Some((fi, focus)),
            _ => None,
        };
        let viewpoint = seen.map(|_| guid::viewpoint_guid(&i.guid));
        let markup = xml::markup(
            v,
            i,
            options.model.as_deref(),
            &date,
            viewpoint.as_deref(),
            seen.is_some(),
        );
        zip.add(&format!("{}/markup.bcf", i.guid), markup.as_bytes())?;
        let (Some((fi, focus)), Some(vg)) = (seen, viewpoint) else {
            continue;
        };
        let floor = &building.floors[fi];
        let camera = camera::camera(floor, focus);
        let ifc_guid = poinav_ifc::GlobalId::parse(&i.element)
            .ok()
            .map(|_| i.element.as_str());
        let colour = if i.status == "RESTRICTED" {
            "E8A400"
        } else {
            "D93025"
        };
        let visinfo = xml::viewpoint(
            v,
            &vg,
            ifc_guid,
            colour,
            i.kind == IssueKind::Space,
            &camera,
            aspect,
        );
        zip.add(
            &format!("{}/{}", i.guid, xml::VIEWPOINT_FILE),
            visinfo.as_bytes(),
        )?;
        let grid = match grids.entry((i.profile, fi)) {
            std::collections::btree_map::Entry::Occupied(e) => e.into_mut(),
            std::collections::btree_map::Entry::Vacant(e) => {
                let grid_options = GridOptions {
                    at_ground: building.at_ground(fi),
                    ..options.grid.clone()
                };
                // The storey as the audit rasterised it: cropped to its own extent.
                let cropped = poinav_nav::extent::for_grid(floor, &grid_options);
                let g = OccupancyGrid::build(&cropped, &profiles[i.profile], &grid_options)
                    .map_err(|source| BcfError::Grid {
                        floor: floor.name.clone(),
                        profile: i.profile_name.clone(),
                        source,
                    })?;
                e.insert(g)
            }
        };
        let eye = camera.position.truncate();
        let look = camera.direction.truncate();
        let pixels = snapshot::render(grid, focus, i.status, Some((eye, look)));
        let entry = format!("{}/{}", i.guid, xml::SNAPSHOT_FILE);
        zip.add(&entry, &snapshot::png(&pixels, &entry)?)?;
    }
    Ok((zip.finish()?, issues))
}

/// Writes the BCF of [`bcf_bytes`] to `path` atomically; returns the topics.
pub fn write_bcf(
    path: &Path,
    report: &AuditReport,
    building: &Building,
    profiles: &[RobotProfile],
    options: &BcfOptions,
) -> Result<Vec<Issue>, BcfError> {
    let (bytes, issues) = bcf_bytes(report, building, profiles, options)?;
    poinav_io::write_atomic(path, &bytes).map_err(|source| BcfError::Write {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(issues)
}
