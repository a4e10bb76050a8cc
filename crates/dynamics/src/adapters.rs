//! [`AtmosphereModel`] and [`VehicleModel`] for the karman model crates: the only place where
//! the engine touches `karman_atmos::Environment` and `karman_airframe::Rocket`; and
//! [`motor_properties`], the motor as the airframe sees it (karman-airframe does not depend
//! on karman-propulsion, so the hand-over lives here, the first crate that sees both).

use karman_airframe::{MotorProperties, Rocket, Surface, Trigger};
use karman_atmos::Environment;
use karman_propulsion::Motor;

use crate::model::{
    Air, AtmosphereModel, Cursor, MassSample, ParachuteSpec, RailButtonGeometry, SurfaceModel,
    TriggerKind, VehicleModel,
};

/// The motor's tables and constants as the airframe needs them (`karman_airframe::MotorProperties`).
pub fn motor_properties(motor: &Motor) -> MotorProperties {
    let (i11, i33) = motor.propellant_inertia();
    MotorProperties {
        thrust: motor.thrust_table().clone(),
        burn_start: motor.burn_start(),
        burn_out: motor.burn_out(),
        exhaust_velocity: motor.exhaust_velocity(),
        propellant_mass: motor.propellant_mass().clone(),
        propellant_center_of_mass: motor.propellant_center_of_mass().clone(),
        propellant_i11: i11.clone(),
        propellant_i33: i33.clone(),
        dry_mass: motor.dry_mass(),
        center_of_dry_mass: motor.center_of_dry_mass(),
        dry_inertia: motor.dry_inertia(),
        nozzle_position: motor.nozzle_position(),
        nozzle_radius: motor.nozzle_radius(),
        coordinate_system_sign: motor.coordinate_system_sign(),
        reference_pressure: motor.reference_pressure(),
    }
}

impl AtmosphereModel for Environment {
    #[inline]
    fn elevation(&self) -> f64 {
        Environment::elevation(self)
    }
    #[inline]
    fn pressure(&self, z: f64) -> f64 {
        Environment::pressure(self, z)
    }
    #[inline]
    fn density(&self, z: f64) -> f64 {
        Environment::density(self, z)
    }
    #[inline]
    fn speed_of_sound(&self, z: f64) -> f64 {
        Environment::speed_of_sound(self, z)
    }
    #[inline]
    fn dynamic_viscosity(&self, z: f64) -> f64 {
        Environment::dynamic_viscosity(self, z)
    }
    #[inline]
    fn wind(&self, z: f64) -> [f64; 2] {
        Environment::wind(self, z)
    }
    #[inline]
    fn air(&self, z: f64) -> Air {
        AtmosphereModel::air_near(self, z, &mut Cursor::default())
    }
    #[inline]
    fn air_near(&self, z: f64, cursor: &mut Cursor) -> Air {
        let s = Environment::air_near(self, z, cursor);
        Air {
            pressure: s.pressure,
            density: s.density,
            speed_of_sound: s.speed_of_sound,
            gravity: s.gravity,
        }
    }
    fn uniform_wind(&self) -> Option<[f64; 2]> {
        Environment::uniform_wind(self)
    }
    #[inline]
    fn gravity(&self, z: f64) -> f64 {
        Environment::gravity(self, z)
    }
    #[inline]
    fn earth_rotation_enu(&self) -> [f64; 3] {
        Environment::earth_rotation_enu(self)
    }
    #[inline]
    fn barometric_height(&self, pressure: f64) -> f64 {
        Environment::barometric_height(self, pressure)
    }
}

impl SurfaceModel for Surface {
    #[inline]
    fn cp_body(&self) -> [f64; 3] {
        self.cp_body
    }
    #[inline]
    fn reference_area(&self) -> f64 {
        self.reference_area
    }
    #[inline]
    fn reference_length(&self) -> f64 {
        Surface::reference_length(self)
    }
    #[inline]
    fn cn_alpha(&self, mach: f64) -> f64 {
        Surface::cn_alpha(self, mach)
    }
    fn rolls(&self) -> bool {
        self.is_fin_set()
    }
    #[inline]
    fn roll_forcing(&self, mach: f64) -> f64 {
        Surface::roll_forcing(self, mach)
    }
    #[inline]
    fn roll_damping(&self, mach: f64) -> f64 {
        Surface::roll_damping(self, mach)
    }
    #[inline]
    fn coefficients(&self, mach: f64) -> [f64; 3] {
        Surface::coefficients(self, mach)
    }
}

impl VehicleModel for Rocket {
    type Surface = Surface;

    #[inline]
    fn surfaces(&self) -> &[Surface] {
        Rocket::surfaces(self)
    }
    #[inline]
    fn reference_area(&self) -> f64 {
        Rocket::reference_area(self)
    }
    #[inline]
    fn radius(&self) -> f64 {
        Rocket::radius(self)
    }
    #[inline]
    fn csys(&self) -> f64 {
        Rocket::csys(self)
    }
    #[inline]
    fn total_mass(&self, t: f64) -> f64 {
        Rocket::total_mass(self, t)
    }
    #[inline]
    fn mass_flow_rate(&self, t: f64) -> f64 {
        Rocket::mass_flow_rate(self, t)
    }
    #[inline]
    fn mass_flow_rate_derivative(&self, t: f64) -> f64 {
        Rocket::mass_flow_rate_derivative(self, t)
    }
    #[inline]
    fn com_to_cdm(&self, t: f64) -> f64 {
        Rocket::com_to_cdm(self, t)
    }
    #[inline]
    fn com_to_cdm_rate(&self, t: f64) -> f64 {
        Rocket::com_to_cdm_rate(self, t)
    }
    #[inline]
    fn com_to_cdm_accel(&self, t: f64) -> f64 {
        Rocket::com_to_cdm_accel(self, t)
    }
    #[inline]
    fn inertia(&self, t: f64) -> [f64; 6] {
        Rocket::inertia(self, t)
    }
    #[inline]
    fn inertia_rate(&self, t: f64) -> [f64; 6] {
        Rocket::inertia_rate(self, t)
    }
    #[inline]
    fn mass_sample(&self, t: f64) -> MassSample {
        self.mass_sample_near(t, &mut [Cursor::default(); 2])
    }
    #[inline]
    fn mass_sample_near(&self, t: f64, cursors: &mut [Cursor; 2]) -> MassSample {
        let p = Rocket::mass_properties_near(self, t, cursors);
        MassSample {
            total_mass: p.total_mass,
            mass_flow_rate: p.mass_flow_rate,
            mass_flow_rate_derivative: p.mass_flow_rate_derivative,
            com_to_cdm: p.com_to_cdm,
            com_to_cdm_rate: p.com_to_cdm_rate,
            com_to_cdm_accel: p.com_to_cdm_accel,
            inertia: p.inertia,
            inertia_rate: p.inertia_rate,
        }
    }
    #[inline]
    fn nozzle_to_cdm(&self) -> f64 {
        Rocket::nozzle_to_cdm(self)
    }
    #[inline]
    fn nozzle_gyration(&self) -> [f64; 3] {
        Rocket::nozzle_gyration(self)
    }
    #[inline]
    fn thrust(&self, t: f64) -> f64 {
        Rocket::thrust(self, t)
    }
    #[inline]
    fn net_thrust(&self, t: f64, ambient_pressure: f64) -> f64 {
        Rocket::net_thrust(self, t, ambient_pressure)
    }
    #[inline]
    fn net_thrust_near(&self, t: f64, ambient_pressure: f64, cursor: &mut Cursor) -> f64 {
        Rocket::net_thrust_near(self, t, ambient_pressure, cursor)
    }
    fn thrust_knots(&self) -> Vec<f64> {
        self.motor().thrust.xs().to_vec()
    }
    #[inline]
    fn burn_start(&self) -> f64 {
        Rocket::burn_start(self)
    }
    #[inline]
    fn burn_out(&self) -> f64 {
        Rocket::burn_out(self)
    }
    #[inline]
    fn drag_coefficient(&self, power_on: bool, mach: f64) -> f64 {
        Rocket::drag_coefficient(self, power_on, mach)
    }
    #[inline]
    fn drag_coefficient_near(&self, power_on: bool, mach: f64, cursor: &mut Cursor) -> f64 {
        Rocket::drag_coefficient_near(self, power_on, mach, cursor)
    }
    fn dry_mass(&self) -> f64 {
        Rocket::dry_mass(self)
    }
    fn center_of_dry_mass(&self) -> f64 {
        Rocket::center_of_dry_mass(self)
    }
    fn nozzle_position(&self) -> f64 {
        Rocket::nozzle_position(self)
    }
    fn rail_buttons(&self) -> Option<RailButtonGeometry> {
        Rocket::rail_buttons(self).map(|b| RailButtonGeometry {
            upper_position: b.upper_position,
            lower_position: b.lower_position,
            angular_position_rad: b.angular_position_rad,
        })
    }
    fn parachutes(&self) -> Vec<ParachuteSpec> {
        Rocket::parachutes(self)
            .iter()
            .map(|p| ParachuteSpec {
                name: p.name.clone(),
                cd_s: p.cd_s,
                trigger: match p.trigger {
                    Trigger::Apogee => TriggerKind::Apogee,
                    Trigger::HeightAboveGround(h) => TriggerKind::HeightAboveGround(h),
                },
                sampling_rate: p.sampling_rate,
                lag: p.lag,
                noise: p.noise,
                radius: p.radius,
                height: p.height,
                added_mass_coefficient: p.added_mass_coefficient(),
            })
            .collect()
    }
    fn static_margin(&self, t: f64) -> f64 {
        Rocket::static_margin(self, t)
    }
    fn stability_margin(&self, mach: f64, t: f64) -> f64 {
        Rocket::stability_margin(self, mach, t)
    }
}
