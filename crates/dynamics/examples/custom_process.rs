//! Flies an analytic vehicle with a custom sampled process: an exponential atmosphere, a
//! 10 kg rocket with a 2 s constant-thrust burn and two surfaces, and an accelerometer
//! sampled at 100 Hz that publishes the vertical acceleration it reads on the dense output
//! and records the largest one.
//!
//! Run with `cargo run -p karman-dynamics --example custom_process`.

use karman_dynamics::{
    Action, AtmosphereModel, BodyFlow, Configuration, Cursor, Flight, FlightSettings, Loads,
    LocalFlow, MAX_CONTROLS, MassFlowLaw, MassSample, Probe, RailButtonGeometry, SampledProcess,
    SurfaceModel, VehicleModel, VehicleSetup, simulate_with,
};

/// An isothermal atmosphere: density and pressure fall off with a scale height of 8.5 km.
struct Isothermal;

const SCALE_HEIGHT: f64 = 8500.0;

impl AtmosphereModel for Isothermal {
    fn elevation(&self) -> f64 {
        0.0
    }
    fn pressure(&self, z: f64) -> f64 {
        101_325.0 * (-z / SCALE_HEIGHT).exp()
    }
    fn density(&self, z: f64) -> f64 {
        1.225 * (-z / SCALE_HEIGHT).exp()
    }
    fn speed_of_sound(&self, _z: f64) -> f64 {
        340.0
    }
    fn dynamic_viscosity(&self, _z: f64) -> f64 {
        1.8e-5
    }
    fn wind(&self, _z: f64) -> [f64; 2] {
        [3.0, 0.0]
    }
    fn uniform_wind(&self) -> Option<[f64; 2]> {
        Some([3.0, 0.0])
    }
    fn gravity(&self, _z: f64) -> f64 {
        9.80665
    }
    fn earth_rotation_enu(&self) -> [f64; 3] {
        [0.0; 3]
    }
    fn barometric_height(&self, pressure: f64) -> f64 {
        -SCALE_HEIGHT * (pressure / 101_325.0).ln()
    }
}

/// A lifting surface at `z` m from the centre of dry mass with a normal-force slope.
struct Surface {
    z: f64,
    cn_alpha: f64,
}

/// Reference area of the 10 cm body, m².
const AREA: f64 = std::f64::consts::PI * 0.05 * 0.05;

impl SurfaceModel for Surface {
    fn cp_body(&self) -> [f64; 3] {
        [0.0, 0.0, self.z]
    }
    fn loads(&self, flow: &LocalFlow) -> Loads {
        Loads::normal_force(flow, AREA, self.cn_alpha, self.z)
    }
}

/// 10 kg dry, 1 kg of propellant burnt at a constant rate in 2 s under 800 N.
struct Rocket {
    surfaces: [Surface; 2],
}

impl Rocket {
    fn mass(t: f64) -> (f64, f64) {
        if (0.0..2.0).contains(&t) {
            (11.0 - 0.5 * t, -0.5)
        } else {
            (if t < 0.0 { 11.0 } else { 10.0 }, 0.0)
        }
    }
}

impl VehicleModel for Rocket {
    type Surface = Surface;
    fn setup(&self) -> VehicleSetup {
        VehicleSetup {
            csys: 1.0,
            burn_start: 0.0,
            burn_out: 2.0,
            thrust_knots: vec![0.0, 2.0],
            rail_buttons: Some(RailButtonGeometry {
                upper_position: 0.2,
                lower_position: -0.5,
                angular_position_rad: 0.0,
            }),
            parachutes: Vec::new(),
            dry_mass: 10.0,
            nozzle_position: -1.0,
            nozzle_to_cdm: 1.0,
            nozzle_gyration: [0.25, 0.25, 0.0005],
            static_margins: [0.0; 2],
            initial_controls: [0.0; MAX_CONTROLS],
            off_axis: karman_model::OffAxis::default(),
        }
    }
    fn surfaces(&self) -> &[Surface] {
        &self.surfaces
    }
    fn mass(&self, t: f64, _law: MassFlowLaw, _cursors: &mut [Cursor; 2]) -> MassSample {
        let (m, md) = Self::mass(t);
        MassSample {
            total_mass: m,
            mass_flow_rate: md,
            mass_flow_rate_derivative: 0.0,
            com_to_cdm: 0.0,
            com_to_cdm_rate: 0.0,
            com_to_cdm_accel: 0.0,
            inertia: [m * 0.25, m * 0.25, m * 0.0025, 0.0, 0.0, 0.0],
            inertia_rate: [md * 0.25, md * 0.25, md * 0.0025, 0.0, 0.0, 0.0],
        }
    }
    fn total_mass(&self, t: f64, _cursor: &mut Cursor) -> f64 {
        Self::mass(t).0
    }
    fn thrust(&self, t: f64, _ambient_pressure: f64, _cursor: &mut Cursor) -> f64 {
        if (0.0..2.0).contains(&t) { 800.0 } else { 0.0 }
    }
    fn axial_load(&self, flow: &BodyFlow, _c: &Configuration, _cursor: &mut Cursor) -> f64 {
        -0.5 * flow.density * flow.speed * flow.speed * AREA * 0.5
    }
}

/// The custom process: a vertical accelerometer at 100 Hz. It publishes its reading as the
/// signal `"accelerometer.z"` (other processes may read it) and records each new maximum on
/// channel 0.
struct Accelerometer {
    max: f64,
}

impl SampledProcess for Accelerometer {
    fn rate(&self) -> f64 {
        100.0
    }
    fn on_rail(&self) -> bool {
        true
    }
    fn outputs(&self) -> &[&str] {
        &["accelerometer.z"]
    }
    fn sample(&mut self, probe: &mut Probe<'_>) -> Option<Action> {
        let a_z = probe.acceleration()[2];
        probe.publish(0, a_z);
        (a_z > self.max).then(|| {
            self.max = a_z;
            Action::Record {
                channel: 0,
                value: a_z,
            }
        })
    }
}

/// Flies the rocket from a 3 m rail at 85° with the accelerometer.
pub fn fly() -> Flight {
    let rocket = Rocket {
        surfaces: [
            Surface {
                z: 0.8,
                cn_alpha: 2.0,
            },
            Surface {
                z: -0.9,
                cn_alpha: 6.0,
            },
        ],
    };
    let mut settings = FlightSettings::new(3.0);
    settings.inclination_deg = 85.0;
    let accelerometer = Box::new(Accelerometer {
        max: f64::NEG_INFINITY,
    });
    simulate_with(&Isothermal, &rocket, &settings, vec![accelerometer])
        .expect("the analytic rocket flies")
}

#[allow(dead_code)] // `fly` is also run by the crate's tests.
fn main() {
    let flight = fly();
    let (t_apogee, apogee) = flight.apogee.expect("an apogee");
    let peak = flight.records.last().expect("a reading");
    println!(
        "apogee {:.1} m at {t_apogee:.2} s; largest vertical acceleration {:.1} m/s² at {:.2} s",
        apogee[2], peak.value, peak.t
    );
}
