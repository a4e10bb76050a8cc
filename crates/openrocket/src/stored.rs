//! OpenRocket's stored flights: the `reference.json` of a design folder (the layout of
//! `fixtures/openrocket`: a subfolder holding `design.ork` and the flights OpenRocket stored in
//! it, extracted by `fixtures/openrocket/extract.py`), read as the figures a comparison takes:
//! the summary values, the ascent rows (time, Mach, total Cd, thrust), the rod-exit CP row,
//! the flow's roll angle there, and the stage separations. Pure data: nothing here flies.

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::{Design, ImportOptions, Problem, SimulationResult, import, read_document};

/// One simulation OpenRocket stored with a design (an element of `reference.json`'s
/// `simulations`): its launch conditions and the figures of its main branch.
#[derive(Debug, Clone, PartialEq)]
pub struct StoredFlight {
    record: Value,
}

/// The ascent rows of a stored flight's main branch, column by column (a missing or
/// non-numeric value is `NaN`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Ascent {
    /// Time (s).
    pub time_s: Vec<f64>,
    /// Mach number.
    pub mach: Vec<f64>,
    /// OpenRocket's total drag coefficient.
    pub cd: Vec<f64>,
    /// Thrust (N).
    pub thrust_n: Vec<f64>,
}

/// OpenRocket's first stored CP of a flight (rod exit): each value `NaN` when absent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RodExit {
    /// Time (s).
    pub time_s: f64,
    /// Angle of attack (rad).
    pub aoa_rad: f64,
    /// Mach number.
    pub mach: f64,
    /// Centre of pressure from the nose tip (m).
    pub cp_m: f64,
    /// Stability margin (calibers).
    pub stability_cal: f64,
}

impl StoredFlight {
    /// The simulation's name (empty when the record has none).
    #[must_use]
    pub fn name(&self) -> &str {
        self.record["name"].as_str().unwrap_or("")
    }

    /// The number of simulation extensions OpenRocket's flight runs (roll control, air
    /// start): a flight with any is not the plain flight of the design.
    #[must_use]
    pub fn extensions(&self) -> usize {
        self.record["extensions"].as_array().map_or(0, Vec::len)
    }

    /// A value of OpenRocket's summary (`maxaltitude`, `maxvelocity`, `flighttime`,
    /// `groundhitvelocity`, ...), `NaN` when absent.
    #[must_use]
    pub fn summary(&self, key: &str) -> f64 {
        self.record["summary"][key].as_f64().unwrap_or(f64::NAN)
    }

    fn branch(&self) -> &Value {
        &self.record["branches"][0]
    }

    /// The main branch's ascent rows.
    #[must_use]
    pub fn ascent(&self) -> Ascent {
        let ascent = &self.branch()["ascent"];
        Ascent {
            time_s: column(ascent, "time_s"),
            mach: column(ascent, "mach"),
            cd: column(ascent, "cd"),
            thrust_n: column(ascent, "thrust_n"),
        }
    }

    /// The time of rod exit (s), OpenRocket's first stored CP; 0 when absent.
    #[must_use]
    pub fn rod_exit_time(&self) -> f64 {
        self.branch()["launch"]["first_finite_cp"]["time_s"]
            .as_f64()
            .unwrap_or(0.0)
    }

    /// The rod-exit row: OpenRocket's first stored CP, with the angle of attack and Mach it
    /// was taken at.
    #[must_use]
    pub fn rod_exit(&self) -> RodExit {
        let launch = &self.branch()["launch"]["first_finite_cp"];
        let at = |key: &str| launch[key].as_f64().unwrap_or(f64::NAN);
        RodExit {
            time_s: at("time_s"),
            aoa_rad: at("aoa_rad"),
            mach: at("mach"),
            cp_m: at("cp_m"),
            stability_cal: at("stability_cal"),
        }
    }

    /// The flow's roll angle in the body frame at rod exit (rad), from the simulation's
    /// launch conditions (see `rod_exit_roll` in the source for the derivation).
    #[must_use]
    pub fn rod_exit_roll(&self) -> f64 {
        rod_exit_roll(&self.record["conditions"])
    }

    /// The times of the main branch's stage-separation events (s), in stored order.
    #[must_use]
    pub fn separations(&self) -> Vec<f64> {
        self.branch()["events"]
            .as_array()
            .into_iter()
            .flatten()
            .filter(|e| e["type"].as_str() == Some("stageseparation"))
            .filter_map(|e| e["time_s"].as_f64())
            .collect()
    }

    /// The time of the main branch's apogee (s), infinite when absent.
    #[must_use]
    pub fn apogee_time(&self) -> f64 {
        self.branch()["time_to_optimum_altitude_s"]
            .as_f64()
            .unwrap_or(f64::INFINITY)
    }
}

impl Ascent {
    /// The worst relative error of `drag(powered, mach)` against the total Cd of the rows
    /// from `from` (s) on with a finite Cd (powered: thrust above 0), below Mach 0.8 and at
    /// or above it (`NaN` without such rows).
    #[must_use]
    pub fn cd_errors(&self, from: f64, drag: impl Fn(bool, f64) -> f64) -> (f64, f64) {
        let (t, mach, cd, thrust) = (&self.time_s, &self.mach, &self.cd, &self.thrust_n);
        let (mut sub, mut sup) = (0.0_f64, f64::NAN);
        for i in 0..t.len() {
            if t[i] < from || !cd[i].is_finite() {
                continue;
            }
            let ours = drag(thrust[i] > 0.0, mach[i]);
            let e = (ours - cd[i]).abs() / cd[i];
            if mach[i] < 0.8 {
                sub = sub.max(e);
            } else {
                sup = if sup.is_nan() { e } else { sup.max(e) };
            }
        }
        (sub, sup)
    }

    /// The worst relative error of `drag(powered, mach)` against the total Cd of the rows in
    /// `[from, to)` (s) with a finite Cd; 0 without such rows.
    #[must_use]
    pub fn worst_cd_error(&self, from: f64, to: f64, drag: impl Fn(bool, f64) -> f64) -> f64 {
        let (t, mach, cd, thrust) = (&self.time_s, &self.mach, &self.cd, &self.thrust_n);
        (0..t.len())
            .filter(|&i| t[i] >= from && t[i] < to && cd[i].is_finite())
            .map(|i| (drag(thrust[i] > 0.0, mach[i]) - cd[i]).abs() / cd[i])
            .fold(0.0, f64::max)
    }
}

fn column(ascent: &Value, name: &str) -> Vec<f64> {
    ascent[name]
        .as_array()
        .map(|a| a.iter().map(|v| v.as_f64().unwrap_or(f64::NAN)).collect())
        .unwrap_or_default()
}

/// The roll angle of the flow in the body frame (rad) at rod exit of OpenRocket's flight
/// with the simulation `conditions` (`reference.json`). OpenRocket starts the rocket at the
/// orientation `R_z(π/2 − d) R_y(a) R_z(−θ₀ − (π/2 − d))` (rod angle `a`, rod direction `d`,
/// the wind's direction when launched into the wind) and takes the flow's roll angle as the
/// azimuth of the air velocity in the body frame. Its code means `θ₀` to be the worst roll
/// angle, but OpenRocket 24.12 (`SimulationStatus`'s constructor) reads it from a new
/// `FlightConditions`, whose roll angle is 0, and never runs the worst-CP search there: the
/// rocket starts unrolled, `θ₀ = 0`, which is what the stored CPs show (a design whose CP
/// depends on the roll angle, `pods_airframes_and_winglets` with its wings and single fins,
/// has OpenRocket's rod-exit CP at `θ = 0`, not at the worst angle 90°). On the rod the
/// rocket's own velocity is along its axis, so the lateral flow is the wind's, from
/// direction `d_w`: with `γ = d − d_w`, the angle is `π/2 − d + atan2(sin γ, cos a cos γ)`;
/// with no wind OpenRocket takes 0. The fins' `sin²` makes the sign of the flow irrelevant.
fn rod_exit_roll(conditions: &Value) -> f64 {
    let wind = &conditions["wind"];
    let speed = wind["average_speed_m_s"].as_f64().unwrap_or(0.0);
    let wind_direction = wind["direction_rad"].as_f64().unwrap_or(0.0);
    if speed <= 0.0 {
        return 0.0;
    }
    let into_wind = conditions["launch_into_wind"].as_bool().unwrap_or(false);
    let rod_direction = if into_wind {
        wind_direction
    } else {
        conditions["launch_rod_direction_deg"]
            .as_f64()
            .unwrap_or(0.0)
            .to_radians()
    };
    let rod_angle = conditions["launch_rod_angle_deg"]
        .as_f64()
        .unwrap_or(0.0)
        .to_radians();
    let gamma = rod_direction - wind_direction;
    let lateral = gamma.sin().atan2(rod_angle.cos() * gamma.cos());
    std::f64::consts::FRAC_PI_2 - rod_direction + lateral
}

/// The stored flights of `design_dir/reference.json`, in stored order.
///
/// # Errors
/// [`Problem::Failed`] when `reference.json` cannot be read or is not JSON.
pub fn stored_flights(design_dir: &Path) -> Result<Vec<StoredFlight>, Problem> {
    let path = design_dir.join("reference.json");
    let text = std::fs::read_to_string(&path)
        .map_err(|e| Problem::Failed(format!("{}: {e}", path.display())))?;
    let reference: Value = serde_json::from_str(&text)
        .map_err(|e| Problem::Failed(format!("{}: {e}", path.display())))?;
    Ok(reference["simulations"]
        .as_array()
        .into_iter()
        .flatten()
        .map(|record| StoredFlight {
            record: record.clone(),
        })
        .collect())
}

/// Reads `design_dir/reference.json` and, for each stored simulation, imports
/// `design_dir/design.ork` for it and hands `compare` the stored flight and the imported
/// mission's text; a simulation that flies simulation extensions is skipped, one the import
/// refuses is [`Problem::Refused`], and an error of `compare` is [`Problem::Failed`].
///
/// # Errors
/// [`Problem::Failed`] when `reference.json` cannot be read.
pub fn each_imported_simulation<T>(
    design_dir: &Path,
    mut compare: impl FnMut(&StoredFlight, String) -> Result<T, String>,
) -> Result<Vec<SimulationResult<T>>, Problem> {
    let design = design_dir.join("design.ork");
    let mut out = Vec::new();
    for flight in stored_flights(design_dir)? {
        let simulation = flight.name().to_owned();
        let extensions = flight.extensions();
        let outcome = if extensions > 0 {
            Err(Problem::Skipped(format!(
                "OpenRocket's flight runs {extensions} simulation extension(s)"
            )))
        } else {
            let options = ImportOptions {
                simulation: Some(simulation.clone()),
                motors: Vec::new(),
                output_dir: Some(design_dir.to_owned()),
            };
            match import(&design, &options) {
                Err(e) => Err(Problem::Refused(e.to_string())),
                Ok(imported) => compare(&flight, imported.mission).map_err(Problem::Failed),
            }
        };
        out.push(SimulationResult {
            simulation,
            outcome,
        });
    }
    Ok(out)
}

/// The design folders of `dir`: its subfolders holding both `design.ork` and
/// `reference.json` (the layout of `fixtures/openrocket`), by name.
///
/// # Errors
/// `dir` cannot be listed, or holds no design folder.
pub fn design_folders(dir: &Path) -> Result<Vec<PathBuf>, String> {
    let entries = std::fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut out = Vec::new();
    for entry in entries {
        let path = entry.map_err(|e| format!("{}: {e}", dir.display()))?.path();
        if path.join("design.ork").is_file() && path.join("reference.json").is_file() {
            out.push(path);
        }
    }
    if out.is_empty() {
        return Err(format!(
            "{}: no design folder (a subfolder holding design.ork and reference.json)",
            dir.display()
        ));
    }
    out.sort();
    Ok(out)
}

/// The number of axial stages of `design_dir/design.ork` (OpenRocket's stages; pods and
/// boosters are components of a stage).
///
/// # Errors
/// [`Problem::Refused`] when the design cannot be read or parsed (its error).
pub fn stage_count(design_dir: &Path) -> Result<usize, Problem> {
    let file = design_dir.join("design.ork");
    let text = read_document(&file).map_err(|e| Problem::Refused(e.to_string()))?;
    let design = Design::parse(&file, &text).map_err(|e| Problem::Refused(e.to_string()))?;
    Ok(design.stages.len())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn conditions(into_wind: bool, rod_deg: [f64; 2], wind: [f64; 2]) -> Value {
        serde_json::json!({
            "launch_into_wind": into_wind,
            "launch_rod_angle_deg": rod_deg[0],
            "launch_rod_direction_deg": rod_deg[1],
            "wind": {"average_speed_m_s": wind[0], "direction_rad": wind[1]},
        })
    }

    #[test]
    fn the_rod_exit_roll_angle_follows_openrockets_initial_orientation() {
        // Into the wind on a vertical rod: the flow comes at roll angle 0.
        let into = conditions(true, [0.0, 0.0], [2.0, FRAC_PI_2]);
        assert!(rod_exit_roll(&into).abs() < 1e-15);
        // A vertical rod pointing east with a north wind: the flow comes at 90°.
        let north = conditions(false, [0.0, 90.0], [2.0, 0.0]);
        assert!((rod_exit_roll(&north) - FRAC_PI_2).abs() < 1e-15);
        // No wind: OpenRocket's 0.
        assert!(rod_exit_roll(&conditions(true, [5.0, 0.0], [0.0, 1.0])) == 0.0);
    }
}
