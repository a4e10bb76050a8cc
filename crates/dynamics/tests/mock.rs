//! Small analytic models implementing the engine's traits, for tests that must not depend on
//! the mission files: an exponential atmosphere and a constant-thrust rocket.

use karman_dynamics::{
    AtmosphereModel, BodyFlow, Configuration, Cursor, Loads, LocalFlow, MassFlowLaw, MassSample,
    ParachuteSpec, RailButtonGeometry, StabilityModel, SurfaceModel, TriggerKind, VehicleModel,
    VehicleSetup,
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
    fn loads(&self, flow: &LocalFlow) -> Loads {
        let area = std::f64::consts::PI * 0.05 * 0.05;
        Loads::normal_force(flow, area, self.cn_alpha, self.cp[2])
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

    /// Total mass, kg.
    pub fn total_mass(&self, t: f64) -> f64 {
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
}

impl VehicleModel for MockRocket {
    type Surface = MockSurface;

    fn setup(&self) -> VehicleSetup {
        VehicleSetup {
            csys: 1.0,
            burn_start: 0.0,
            burn_out: self.burn_time,
            thrust_knots: vec![0.0, self.burn_time],
            rail_buttons: Some(RailButtonGeometry {
                upper_position: 0.2,
                lower_position: -0.5,
                angular_position_rad: std::f64::consts::FRAC_PI_4,
            }),
            parachutes: self.parachutes.clone(),
            dry_mass: self.dry_mass,
            nozzle_position: -1.0,
            nozzle_to_cdm: 1.0,
            nozzle_gyration: [0.25, 0.25, 0.0005],
            static_margins: [0.0; 2],
            initial_controls: [0.0; karman_model::MAX_CONTROLS],
            off_axis: karman_model::OffAxis::default(),
        }
    }
    fn surfaces(&self) -> &[MockSurface] {
        &self.surfaces
    }
    fn mass(&self, t: f64, _law: MassFlowLaw, _cursors: &mut [Cursor; 2]) -> MassSample {
        let m = self.total_mass(t);
        let md = self.mass_flow_rate(t);
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
        MockRocket::total_mass(self, t)
    }
    fn thrust(&self, t: f64, _ambient_pressure: f64, _cursor: &mut Cursor) -> f64 {
        if self.burning(t) { self.thrust } else { 0.0 }
    }
    fn axial_load(&self, flow: &BodyFlow, _configuration: &Configuration, _c: &mut Cursor) -> f64 {
        let area = std::f64::consts::PI * 0.05 * 0.05;
        -0.5 * flow.density * flow.speed * flow.speed * area * self.cd
    }
}

impl StabilityModel for MockRocket {
    fn stability_margin(&self, _mach: f64, _t: f64) -> f64 {
        0.0
    }
}
