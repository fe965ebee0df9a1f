//! What the viewer shows: the building (one GLB per storey), what a click on an element reveals, every storey
//! as a floor with the robots that drive on it, and which storey is shown first.

use std::collections::BTreeMap;

use poinav_nav::Floor;
use poinav_sim::{RobotSetup, SimOptions};
use serde::Serialize;

/// One element as a click shows it.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct ElementInfo {
    /// GlobalId.
    #[serde(rename = "GlobalId")]
    pub global_id: String,
    /// IFC class.
    #[serde(rename = "Class")]
    pub class: String,
    /// Name.
    #[serde(rename = "Name")]
    pub name: Option<String>,
    /// Storey name.
    #[serde(rename = "Storey")]
    pub storey: Option<String>,
    /// POI category, type, roles and accessibility status (as in the GLB's `extras`).
    #[serde(rename = "POI")]
    pub poi: BTreeMap<String, String>,
    /// Property sets by name: property name -> value as text.
    #[serde(rename = "PropertySets")]
    pub property_sets: BTreeMap<String, BTreeMap<String, String>>,
}

/// Everything a viewer serves.
#[derive(Debug, Clone)]
pub struct Viewer {
    /// Page title (the file name).
    pub title: String,
    /// The building, one binary glTF per storey (`poinav_export::glb_chunks`: Y up, one node
    /// per element with `extras` carrying GlobalId, class and POI data), served in this order
    /// at `/api/model/<k>.glb`.
    pub model: Vec<ModelChunk>,
    /// Click-to-inspect data by GlobalId.
    pub elements: BTreeMap<String, ElementInfo>,
    /// Every storey a page can switch to, lowest first.
    pub storeys: Vec<ViewStorey>,
    /// The index in `storeys` of the storey the robots drive on when the server starts.
    pub current: usize,
    /// Simulation settings (fixed step; `record` is turned off for a live run).
    pub options: SimOptions,
    /// Where the robots came from, in words (shown on the page).
    pub source: String,
}

/// One part of the building: the elements of one storey (or those without a storey) as a GLB.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelChunk {
    /// The index in [`Viewer::storeys`] of the storey it belongs to, when that storey is one.
    pub storey: Option<usize>,
    /// The storey's name (`No storey` for the elements without one).
    pub name: String,
    /// The storey's elevation, metres (0 without a storey).
    pub elevation_m: f64,
    /// Element nodes in it.
    pub elements: usize,
    /// The GLB bytes.
    pub glb: Vec<u8>,
}

/// One storey of the viewer: its floor and the robots that drive on it when it is chosen.
#[derive(Debug, Clone)]
pub struct ViewStorey {
    /// The storey as a floor.
    pub floor: Floor,
    /// The robots (index 0 is driven by the arrow keys, index 1 by W A S D); empty when they
    /// could not be placed.
    pub robots: Vec<RobotSetup>,
    /// Why there are no robots on this storey (it cannot then be chosen).
    pub unplaced: Option<String>,
}

impl ViewStorey {
    /// A storey with its robots.
    pub fn new(floor: Floor, robots: Vec<RobotSetup>) -> ViewStorey {
        ViewStorey {
            floor,
            robots,
            unplaced: None,
        }
    }

    /// A storey where no robot could be placed, and why.
    pub fn unplaced(floor: Floor, reason: String) -> ViewStorey {
        ViewStorey {
            floor,
            robots: Vec::new(),
            unplaced: Some(reason),
        }
    }
}
