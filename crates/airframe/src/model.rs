//! The karman-model interfaces for the airframe: [`VehicleModel`] for [`Rocket`] and
//! [`SurfaceModel`] for [`Surface`], whose force law (RocketPy's normal force and, for fin
//! sets, roll moment; docs/physics.md §7.2, §7.6) lives here with the coefficients.

use karman_math::Cursor;
use karman_model::{
    BodyFlow, Configuration, Loads, LocalFlow, MAX_CONTROLS, MassFlowLaw, MassSample,
    ParachuteSpec, RailButtonGeometry, StabilityModel, SurfaceModel, VehicleModel, VehicleSetup,
};

use crate::air_brakes::AIR_BRAKES_CONTROL;
use crate::{Rocket, Surface};

impl SurfaceModel for Surface {
    #[inline(always)]
    fn cp_body(&self) -> [f64; 3] {
        self.cp_body
    }

    #[inline(always)]
    fn loads(&self, flow: &LocalFlow) -> Loads {
        let [cn_alpha, forcing, damping] = self.coefficients(flow.mach);
        let area = self.reference_area;
        let mut loads = Loads::normal_force(flow, area, cn_alpha, self.cp_body[2]);
        if self.is_fin_set() {
            let d = self.reference_length();
            loads.moment[2] = Loads::roll_moment(flow, area, d, forcing, damping);
        }
        loads
    }
}

impl VehicleModel for Rocket {
    type Surface = Surface;

    fn setup(&self) -> VehicleSetup {
        VehicleSetup {
            csys: self.csys(),
            burn_start: self.burn_start(),
            burn_out: self.burn_out(),
            thrust_knots: self.motor().thrust.xs().to_vec(),
            rail_buttons: self.rail_buttons().map(|b| RailButtonGeometry {
                upper_position: b.upper_position,
                lower_position: b.lower_position,
                angular_position_rad: b.angular_position_rad,
            }),
            parachutes: self
                .parachutes()
                .iter()
                .map(|p| ParachuteSpec {
                    name: p.name.clone(),
                    cd_s: p.cd_s,
                    trigger: p.trigger.clone(),
                    sampling_rate: p.sampling_rate,
                    lag: p.lag,
                    noise: p.noise,
                    radius: p.radius,
                    height: p.height,
                    added_mass_coefficient: p.added_mass_coefficient(),
                })
                .collect(),
            dry_mass: self.dry_mass(),
            nozzle_position: self.nozzle_position(),
            nozzle_to_cdm: self.nozzle_to_cdm(),
            nozzle_gyration: self.nozzle_gyration(),
            static_margins: [self.static_margin(0.0), self.static_margin(self.burn_out())],
            initial_controls: {
                let mut controls = [0.0; MAX_CONTROLS];
                if let Some(brakes) = self.air_brakes() {
                    controls[AIR_BRAKES_CONTROL] = brakes.initial_level();
                }
                controls
            },
            off_axis: self.off_axis(),
        }
    }

    #[inline]
    fn surfaces(&self) -> &[Surface] {
        Rocket::surfaces(self)
    }

    #[inline(always)]
    fn mass(&self, t: f64, law: MassFlowLaw, cursors: &mut [Cursor; 2]) -> MassSample {
        let p = self.mass_properties_near(t, cursors);
        match law {
            MassFlowLaw::ThrustOverExhaustVelocity => p,
            MassFlowLaw::MassDerivative => {
                let (mass_flow_rate, mass_flow_rate_derivative) =
                    self.mass_rate_near(t, &mut cursors[1]);
                MassSample {
                    mass_flow_rate,
                    mass_flow_rate_derivative,
                    ..p
                }
            }
        }
    }

    #[inline]
    fn total_mass(&self, t: f64, cursor: &mut Cursor) -> f64 {
        self.total_mass_near(t, cursor)
    }

    #[inline]
    fn thrust(&self, t: f64, ambient_pressure: f64, cursor: &mut Cursor) -> f64 {
        self.net_thrust_near(t, ambient_pressure, cursor)
    }

    /// The drag `−½ ρ |v|² A C_D(Mach)` of the power-on or power-off curve (docs/physics.md §7.1),
    /// with the air brakes' drag added or substituted while their level (control
    /// [`AIR_BRAKES_CONTROL`]) is above 0 (§16.1).
    #[inline(always)]
    fn axial_load(
        &self,
        flow: &BodyFlow,
        configuration: &Configuration,
        cursor: &mut Cursor,
    ) -> f64 {
        let cd = self.drag_coefficient_near(flow.power_on, flow.mach, cursor);
        let minus_half_rho_v2 = -0.5 * flow.density * flow.speed * flow.speed;
        let rocket = minus_half_rho_v2 * self.reference_area() * cd;
        match self.air_brakes() {
            Some(brakes) => brakes.axial_force(
                configuration.control(AIR_BRAKES_CONTROL),
                flow.mach,
                minus_half_rho_v2,
                rocket,
            ),
            None => rocket,
        }
    }
}

impl StabilityModel for Rocket {
    fn stability_margin(&self, mach: f64, t: f64) -> f64 {
        Rocket::stability_margin(self, mach, t)
    }
}
