//! Small analytic models implementing the engine's traits, for tests that must not depend on
//! the mission files: an exponential atmosphere and a constant-thrust rocket.

use karman_dynamics::{
    AtmosphereModel, ParachuteSpec, RailButtonGeometry, SurfaceModel, TriggerKind, VehicleModel,
};

/// Exponential atmosphere with constant speed of sound, gravity and wind.
#[derive(Debug, Clone)]
pub struct MockAtmosphere {
    /// Sea-level density, kg/m³ (0 for vacuum).
    pub rho0: f64,
    /// Constant gravity, m/s².
    pub g: f64,
    /// Constant wind (east, north), m/s.
    pub wind: [f64; 2],
    /// Launch elevation, m.
    pub elevation: f64,
}

/// Scale height of the mock atmosphere, m.
const SCALE_HEIGHT: f64 = 8500.0;
/// Sea-level pressure of the mock atmosphere, Pa.
const P0: f64 = 101_325.0;

impl Default for MockAtmosphere {
    fn default() -> Self {
        Self {
            rho0: 1.225,
            g: 9.80665,
            wind: [0.0, 0.0],
            elevation: 100.0,
        }
    }
}

impl AtmosphereModel for MockAtmosphere {
    fn elevation(&self) -> f64 {
        self.elevation
    }
    fn pressure(&self, z: f64) -> f64 {
        P0 * (-z / SCALE_HEIGHT).exp()
    }
    fn density(&self, z: f64) -> f64 {
        self.rho0 * (-z / SCALE_HEIGHT).exp()
    }
    fn speed_of_sound(&self, _z: f64) -> f64 {
        340.0
    }
    fn dynamic_viscosity(&self, _z: f64) -> f64 {
        1.8e-5
    }
    fn wind(&self, _z: f64) -> [f64; 2] {
        self.wind
    }
    fn gravity(&self, _z: f64) -> f64 {
        self.g
    }
    fn earth_rotation_enu(&self) -> [f64; 3] {
        [0.0; 3]
    }
    fn barometric_height(&self, pressure: f64) -> f64 {
        -SCALE_HEIGHT * (pressure / P0).ln()
    }
}

/// A surface with a constant normal-force slope.
#[derive(Debug, Clone)]
pub struct MockSurface {
    /// CP in body axes from the CDM, m.
    pub cp: [f64; 3],
    /// CNα, 1/rad.
    pub cn_alpha: f64,
}

impl SurfaceModel for MockSurface {
    fn cp_body(&self) -> [f64; 3] {
        self.cp
    }
    fn reference_area(&self) -> f64 {
        std::f64::consts::PI * 0.05 * 0.05
    }
    fn reference_length(&self) -> f64 {
        0.1
    }
    fn cn_alpha(&self, _mach: f64) -> f64 {
        self.cn_alpha
    }
    fn rolls(&self) -> bool {
        false
    }
    fn roll_forcing(&self, _mach: f64) -> f64 {
        0.0
    }
    fn roll_damping(&self, _mach: f64) -> f64 {
        0.0
    }
}

/// Constant-thrust rocket whose propellant sits at the CDM (so `c = 0`).
#[derive(Debug, Clone)]
pub struct MockRocket {
    /// Thrust during the burn, N.
    pub thrust: f64,
    /// Burn time, s.
    pub burn_time: f64,
    /// Dry mass, kg.
    pub dry_mass: f64,
    /// Initial propellant mass, kg.
    pub propellant: f64,
    /// Axial drag coefficient.
    pub cd: f64,
    /// Surfaces (nose ahead of the CDM, fins behind it for a stable rocket).
    pub surfaces: Vec<MockSurface>,
    /// Parachutes.
    pub parachutes: Vec<ParachuteSpec>,
}

impl MockRocket {
    /// A stable 10 kg rocket with a 2 s, 800 N burn.
    pub fn stable() -> Self {
        Self {
            thrust: 800.0,
            burn_time: 2.0,
            dry_mass: 10.0,
            propellant: 1.0,
            cd: 0.5,
            surfaces: vec![
                MockSurface {
                    cp: [0.0, 0.0, 0.8],
                    cn_alpha: 2.0,
                },
                MockSurface {
                    cp: [0.0, 0.0, -0.9],
                    cn_alpha: 6.0,
                },
            ],
            parachutes: Vec::new(),
        }
    }

    /// A drogue at apogee (no noise, no lag).
    pub fn drogue() -> ParachuteSpec {
        ParachuteSpec {
            name: "drogue".into(),
            cd_s: 1.0,
            trigger: TriggerKind::Apogee,
            sampling_rate: 100.0,
            lag: 1.0,
            noise: [0.0; 3],
            radius: 0.5,
            height: 0.5,
            added_mass_coefficient: 1.0,
        }
    }

    fn burning(&self, t: f64) -> bool {
        (0.0..=self.burn_time).contains(&t)
    }
}

impl VehicleModel for MockRocket {
    type Surface = MockSurface;

    fn surfaces(&self) -> &[MockSurface] {
        &self.surfaces
    }
    fn reference_area(&self) -> f64 {
        std::f64::consts::PI * 0.05 * 0.05
    }
    fn radius(&self) -> f64 {
        0.05
    }
    fn csys(&self) -> f64 {
        1.0
    }
    fn total_mass(&self, t: f64) -> f64 {
        let burnt = (t / self.burn_time).clamp(0.0, 1.0);
        self.dry_mass + self.propellant * (1.0 - burnt)
    }
    fn mass_flow_rate(&self, t: f64) -> f64 {
        if self.burning(t) {
            -self.propellant / self.burn_time
        } else {
            0.0
        }
    }
    fn mass_flow_rate_derivative(&self, _t: f64) -> f64 {
        0.0
    }
    fn com_to_cdm(&self, _t: f64) -> f64 {
        0.0
    }
    fn com_to_cdm_rate(&self, _t: f64) -> f64 {
        0.0
    }
    fn com_to_cdm_accel(&self, _t: f64) -> f64 {
        0.0
    }
    fn inertia(&self, t: f64) -> [f64; 6] {
        let m = self.total_mass(t);
        [m * 0.25, m * 0.25, m * 0.0025, 0.0, 0.0, 0.0]
    }
    fn inertia_rate(&self, t: f64) -> [f64; 6] {
        let md = self.mass_flow_rate(t);
        [md * 0.25, md * 0.25, md * 0.0025, 0.0, 0.0, 0.0]
    }
    fn nozzle_to_cdm(&self) -> f64 {
        1.0
    }
    fn nozzle_gyration(&self) -> [f64; 3] {
        [0.25, 0.25, 0.0005]
    }
    fn thrust(&self, t: f64) -> f64 {
        if self.burning(t) { self.thrust } else { 0.0 }
    }
    fn net_thrust(&self, t: f64, _p: f64) -> f64 {
        self.thrust(t).max(0.0)
    }
    fn thrust_knots(&self) -> Vec<f64> {
        vec![0.0, self.burn_time]
    }
    fn burn_start(&self) -> f64 {
        0.0
    }
    fn burn_out(&self) -> f64 {
        self.burn_time
    }
    fn drag_coefficient(&self, _power_on: bool, _mach: f64) -> f64 {
        self.cd
    }
    fn dry_mass(&self) -> f64 {
        self.dry_mass
    }
    fn center_of_dry_mass(&self) -> f64 {
        0.0
    }
    fn nozzle_position(&self) -> f64 {
        -1.0
    }
    fn rail_buttons(&self) -> Option<RailButtonGeometry> {
        Some(RailButtonGeometry {
            upper_position: 0.2,
            lower_position: -0.5,
            angular_position_rad: std::f64::consts::FRAC_PI_4,
        })
    }
    fn parachutes(&self) -> Vec<ParachuteSpec> {
        self.parachutes.clone()
    }
    fn static_margin(&self, _t: f64) -> f64 {
        0.0
    }
    fn stability_margin(&self, _mach: f64, _t: f64) -> f64 {
        0.0
    }
}
