//! An air-brake controller written in Rust: the proportional apogee controller of
//! `fixtures/airbrakes/apogee_controller.rhai`, line by line, flown on Calisto with air brakes
//! (`fixtures/airbrakes/calisto_apogee.toml`) in place of the mission's Rhai script. The
//! engine calls it where it calls the script (100 times a second, in every phase), so the two
//! give the same flight, bit for bit. Run with
//! `cargo run --release -p karman-mission --example rust_controller`.
//!
//! After burn-out, while the rocket climbs, the controller predicts the apogee of a vertical
//! coast with quadratic drag from the height `h` and the vertical speed `v_z`,
//! `apogee = h + ln(1 + k v_z² / g) / (2k)` with `k = ρ A C_D0 / (2m)`, and opens the brakes
//! in proportion to the predicted overshoot of its target.

use std::path::{Path, PathBuf};

use karman_mission::assemble::flight::PreparedFlight;
use karman_mission::load;
use karman_mission::script::{AirBrakeController, AirBrakesControl, ControlInputs};

/// The mission the example flies.
pub fn example_mission() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/airbrakes/calisto_apogee.toml")
}

/// The apogee controller, its constants those of the Rhai script.
pub struct ApogeeController {
    /// Target apogee above ground, m.
    pub target: f64,
    /// Level per metre of predicted overshoot.
    pub gain: f64,
    /// The rocket's own drag coefficient, as the controller assumes it.
    pub cd0: f64,
    /// The rocket after burn-out, kg.
    pub mass: f64,
    /// The number of calls, for the report.
    pub calls: usize,
}

impl Default for ApogeeController {
    fn default() -> Self {
        ApogeeController {
            target: 3000.0,
            gain: 0.004,
            cd0: 0.45,
            mass: 16.241,
            calls: 0,
        }
    }
}

impl AirBrakeController for ApogeeController {
    fn control(
        &mut self,
        inputs: &ControlInputs<'_>,
        air_brakes: &mut AirBrakesControl<'_>,
    ) -> Result<(), String> {
        self.calls += 1;
        if inputs.time < inputs.burn_out_time {
            return Ok(());
        }
        let env = inputs.environment;
        let (z, vz) = (inputs.state[2], inputs.state[5]);
        if vz <= 0.0 {
            air_brakes.set_deployment_level(0.0);
            return Ok(());
        }
        // The same operations in the same order as the script (Rhai's `**` is `powf`).
        let k = 0.5 * env.density(z) * air_brakes.reference_area() * self.cd0 / self.mass;
        let g = env.gravity(z);
        let predicted = z - env.elevation() + (1.0 + k * vz.powf(2.0) / g).ln() / (2.0 * k);
        air_brakes.set_deployment_level(self.gain * (predicted - self.target));
        Ok(())
    }
}

/// Flies `mission` with the Rust controller; returns the apogee above ground (m) and the
/// number of controller calls.
///
/// # Errors
/// The mission's errors, and the flight's.
pub fn run(mission: &Path) -> Result<(f64, usize), Box<dyn std::error::Error>> {
    let mission = load(mission, &[])?;
    let prepared = PreparedFlight::new(&mission)?;
    let mut controller = ApogeeController::default();
    let run = prepared.fly_with_controller(&mission, 0, &mut controller)?;
    let apogee = run
        .summary()
        .apogee_agl_m
        .ok_or("the flight has no apogee")?;
    Ok((apogee, controller.calls))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args_os()
        .nth(1)
        .map_or_else(example_mission, PathBuf::from);
    let (apogee, calls) = run(&path)?;
    println!("apogee {apogee:.1} m above ground, {calls} controller calls");
    Ok(())
}
