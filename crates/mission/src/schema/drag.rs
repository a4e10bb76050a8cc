//! `[rocket.drag_estimate]`: the geometry the drag build-up needs beyond the surfaces, for
//! `power_off_drag = "estimate"` / `power_on_drag = "estimate"` (karman-airframe `drag`,
//! Niskanen 2009 §3.4).

use indexmap::IndexMap;
use serde::{Deserialize, Serialize};

use super::names::{FinCrossSection, SurfaceFinish};

fn default_finish() -> SurfaceFinish {
    SurfaceFinish::Normal
}

/// `[rocket.drag_estimate]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DragEstimateSpec {
    /// Body length from the nose tip to the aft end, m; absent: to the aftmost end of a
    /// surface (tail or fin root chord).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body_length: Option<f64>,
    /// Surface finish of the whole rocket; OpenRocket's default `"normal"` (regular paint).
    #[serde(default = "default_finish")]
    pub finish: SurfaceFinish,
    /// Sand roughness, m, instead of a named finish.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub roughness: Option<f64>,
    /// `[rocket.drag_estimate.fins.<surface>]`: thickness and edges of each fin set, keyed by
    /// the name of its `[rocket.surfaces.<surface>]` table.
    #[serde(default, skip_serializing_if = "IndexMap::is_empty")]
    pub fins: IndexMap<String, FinDragSpec>,
    /// `[rocket.drag_estimate.launch_lugs.<name>]`.
    #[serde(default, skip_serializing_if = "IndexMap::is_empty")]
    pub launch_lugs: IndexMap<String, LaunchLugSpec>,
    /// `[rocket.drag_estimate.overrides]`: surface name (a nose or tail) → a drag coefficient
    /// on the reference area that replaces that part's estimated drag (OpenRocket's CD
    /// override).
    #[serde(default, skip_serializing_if = "IndexMap::is_empty")]
    pub overrides: IndexMap<String, f64>,
    /// `[rocket.drag_estimate.rail_buttons]`: the size of the buttons of
    /// `[rocket.rail_buttons]`; absent: the buttons add no drag.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rail_buttons: Option<RailButtonSizeSpec>,
}

/// `[rocket.drag_estimate.fins.<surface>]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FinDragSpec {
    /// Fin thickness, m.
    pub thickness: f64,
    /// Edge profile; OpenRocket's default `"square"`.
    #[serde(default = "default_cross_section")]
    pub cross_section: FinCrossSection,
    /// Finish of this fin set; absent: the rocket's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub finish: Option<SurfaceFinish>,
}

fn default_cross_section() -> FinCrossSection {
    FinCrossSection::Square
}

fn one() -> u32 {
    1
}

/// `[rocket.drag_estimate.launch_lugs.<name>]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LaunchLugSpec {
    /// Outer radius, m.
    pub outer_radius: f64,
    /// Inner radius, m (0: a solid rail guide).
    pub inner_radius: f64,
    /// Length, m.
    pub length: f64,
    /// Number of lugs of this size; default 1.
    #[serde(default = "one")]
    pub count: u32,
}

/// `[rocket.drag_estimate.rail_buttons]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RailButtonSizeSpec {
    /// Outer diameter, m.
    pub outer_diameter: f64,
    /// Diameter of the notch, m.
    pub inner_diameter: f64,
    /// Height above the body, m.
    pub height: f64,
    /// Height of the notch, m.
    pub inner_height: f64,
}
