//! An OpenRocket design imported (karman-openrocket) and flown, against the flight OpenRocket
//! stored in it (the `reference.json` of `fixtures/openrocket`, see its README): apogee, maximum
//! speed, total drag coefficient row by row, centre of pressure and stability margin; for the
//! multi-stage designs the top stage's apogee, the maximum speed and the time of every stage
//! separation.
//!
//! [`compare_folder`] runs the comparison on every design of a folder laid out as
//! `fixtures/openrocket` (a subfolder holding `design.ork` and `reference.json`): a design of
//! one axial stage is held to issue 20's acceptance, one of several to issue 21's, and a
//! design karman refuses is a miss unless it is one of [`KNOWN_REFUSALS`]. The stored flights,
//! the comparison records and the acceptance are karman-openrocket's ([`StoredFlight`],
//! [`DesignResult`]); this module flies the imported missions.
//!
//! Notes on the designs of `fixtures/openrocket`: `simulation_scripting`'s two canards form a
//! fin set of two, whose normal force OpenRocket takes at the flow's roll angle θ
//! (`2 C_Nα1 sin²(θ − φ)`, [`karman_airframe::FinAerodynamics::roll_factor`]) where the
//! flight model averages it to `C_Nα1`: the compared CP is taken at OpenRocket's roll angle
//! at rod exit ([`StoredFlight::rod_exit_roll`]). `clustered_motors` flies its four motors as one cluster
//! (`[motor] cluster_count`). `pods_airframes_and_winglets` has two pod sets
//! (`[rocket.pods]`: wing pods, and a radius-0 "phantom" pod carrying the horizontal
//! stabiliser), wings of two fins and single fins, whose CP depends on the roll angle.
//! `deployable_payload`'s upper "stage"
//! is a payload without a motor, ejected by the booster's ejection charge: the import flies it
//! on the booster as one body, so its apogee and speed are compared and its separation is not
//! flown (the booster's parachute, ejected with the payload, opens at that time on the one
//! body). `simulation_extensions` and `simulation_scripting` store, beside a plain flight,
//! flights altered by simulation extensions (roll control, air start): those are not compared.

use std::path::Path;

use karman_openrocket::{
    Compared, DesignResult, OpenRocketComparison, Problem, SimulationResult, StagedComparison,
    design_folders, each_imported_simulation, stage_count,
};
#[cfg(doc)]
use karman_openrocket::{KNOWN_REFUSALS, StoredFlight};

use crate::assemble::flight::simulate;
use crate::assemble::stages::simulate_staged;
use crate::report::rocket::AngleStability;

/// Imports `design_dir/design.ork` (a single-stage design) for each stored simulation, flies
/// it and compares it with `design_dir/reference.json`.
///
/// # Errors
/// [`Problem::Failed`] when `reference.json` cannot be read.
pub fn compare_design(
    design_dir: &Path,
) -> Result<Vec<SimulationResult<OpenRocketComparison>>, Problem> {
    each_imported_simulation(design_dir, |sim, imported| {
        let mission = crate::parse(&imported, &design_dir.join("imported.toml"), &[])
            .map_err(|e| e.to_string())?;
        let run = simulate(&mission).map_err(|e| e.to_string())?;
        let summary = run.summary();
        let rocket = &run.rocket;

        let stored = |key: &str| sim.summary(key);
        let (sub, sup) = sim
            .ascent()
            .cd_errors(sim.rod_exit_time(), |powered, mach| {
                rocket.drag_coefficient(powered, mach)
            });
        // OpenRocket's CP at rod exit (its first stored CP), at the angle of attack and Mach
        // it stored there: Barrowman's terms with its body lift (karman's flight keeps the
        // linear CP of RocketPy; the estimate reports this one).
        let launch = sim.rod_exit();
        let (cp_time, cp_alpha, cp_mach) = (launch.time_s, launch.aoa_rad, launch.mach);
        if !(cp_time.is_finite() && cp_alpha.is_finite() && cp_mach.is_finite()) {
            return Err("no rod-exit CP row in reference.json".to_owned());
        }
        let stability = AngleStability::new(&mission, rocket, cp_time, cp_alpha, cp_mach, |_| {
            sim.rod_exit_roll()
        })
        .map_err(|e| e.to_string())?;
        let body_length = mission
            .spec
            .rocket
            .drag_estimate
            .as_ref()
            .and_then(|d| d.body_length)
            .unwrap_or(f64::NAN);
        Ok(OpenRocketComparison {
            simulation: sim.name().to_owned(),
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
            cp: (stability.cp_m, launch.cp_m),
            body_length,
            margin: (stability.margin_cal, launch.stability_cal),
            cp_time,
            cp_alpha,
            cp_roll: stability.roll_rad,
        })
    })
}

/// Imports `design_dir/design.ork` (a multi-stage design) for each stored simulation, flies
/// it and compares it with `design_dir/reference.json`.
///
/// # Errors
/// [`Problem::Failed`] when `reference.json` cannot be read.
pub fn compare_staged_design(
    design_dir: &Path,
) -> Result<Vec<SimulationResult<StagedComparison>>, Problem> {
    each_imported_simulation(design_dir, |sim, imported| {
        // The ascent is compared: every body's flight ends at its apogee.
        let text = imported.replacen(
            "\n[flight]\n",
            "\n[flight]\nterminate_on_apogee = true\n",
            1,
        );
        let mission = crate::parse(&text, &design_dir.join("imported.toml"), &[])
            .map_err(|e| e.to_string())?;
        let one_body = mission.spec.stages.is_empty();
        let ascent = sim.ascent();
        let rod = sim.rod_exit_time();
        // Worst Cd error of `rocket` over the rows in [from, to) after rod exit.
        let worst = |rocket: &karman_airframe::Rocket, from: f64, to: f64| {
            ascent.worst_cd_error(rod.max(from), to, |powered, mach| {
                rocket.drag_coefficient(powered, mach)
            })
        };
        let reference_separations = sim.separations();
        // OpenRocket's vehicle changes at its separations: the rows strictly between two of
        // them (a stored step away) belong to one vehicle.
        let window = |k: usize| {
            let from = if k == 0 {
                0.0
            } else {
                reference_separations[k - 1] + 2e-3
            };
            let to = reference_separations
                .get(k)
                .map_or(f64::INFINITY, |t| t - 2e-3);
            (from, to)
        };
        let (summary, separations, cd_errors) = if one_body {
            let run = simulate(&mission).map_err(|e| e.to_string())?;
            let (from, to) = window(0);
            (
                run.summary(),
                Vec::new(),
                vec![worst(&run.rocket, from, to)],
            )
        } else {
            let run = simulate_staged(&mission, 0).map_err(|e| e.to_string())?;
            let times = run.separations.iter().map(|s| s.time_s).collect();
            let errors = run.bodies[0]
                .segments
                .iter()
                .enumerate()
                .map(|(k, &segment)| {
                    let (from, to) = window(k);
                    worst(&run.segments[segment].rocket, from, to)
                })
                .collect();
            (run.summary(0), times, errors)
        };
        let apogee_time = sim.apogee_time();
        let reference_separations = reference_separations
            .into_iter()
            .filter(|t| one_body || *t <= apogee_time)
            .collect();
        Ok(StagedComparison {
            simulation: sim.name().to_owned(),
            apogee: (
                summary.apogee_agl_m.unwrap_or(f64::NAN),
                sim.summary("maxaltitude"),
            ),
            max_speed: (summary.max_speed_mps, sim.summary("maxvelocity")),
            separations,
            reference_separations,
            one_body,
            cd: cd_errors,
        })
    })
}

/// Compares one design folder: single-stage ([`compare_design`]) or multi-stage
/// ([`compare_staged_design`]) by the number of axial stages of its design.
#[must_use]
pub fn compare(design_dir: &Path) -> DesignResult {
    let design = design_dir.file_name().map_or_else(
        || design_dir.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let outcome = stage_count(design_dir).and_then(|stages| {
        if stages > 1 {
            compare_staged_design(design_dir).map(Compared::Staged)
        } else {
            compare_design(design_dir).map(Compared::Single)
        }
    });
    DesignResult { design, outcome }
}

/// Compares every design folder of `dir` ([`design_folders`], [`compare`]).
///
/// # Errors
/// As [`design_folders`].
pub fn compare_folder(dir: &Path) -> Result<Vec<DesignResult>, String> {
    Ok(design_folders(dir)?.iter().map(|d| compare(d)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn design_folders_hold_a_design_and_its_reference() {
        let dir = std::env::temp_dir().join(format!("karman-or-folders-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        for (name, files) in [
            ("b_design", &["design.ork", "reference.json"][..]),
            ("a_design", &["design.ork", "reference.json", "X.eng"][..]),
            ("no_reference", &["design.ork"][..]),
        ] {
            std::fs::create_dir_all(dir.join(name)).expect("a folder");
            for f in files {
                std::fs::write(dir.join(name).join(f), "").expect("a file");
            }
        }
        std::fs::write(dir.join("design.ork"), "").expect("a file");
        let found = design_folders(&dir).expect("two designs");
        assert_eq!(found, vec![dir.join("a_design"), dir.join("b_design")]);
        // A design that is not OpenRocket's is refused, not a failure to read.
        let refused = compare(&dir.join("a_design"));
        assert!(
            matches!(&refused.outcome, Err(Problem::Refused(m)) if m.contains("design.ork")),
            "{refused:?}"
        );
        assert_eq!(refused.failures().len(), 1);
        let e = design_folders(&dir.join("no_reference")).expect_err("no design folder");
        assert!(e.contains("no design folder"), "{e}");
        std::fs::remove_dir_all(&dir).expect("clean up");
    }
}
