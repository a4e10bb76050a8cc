//! Flight settings (RocketPy's `Flight` arguments, defaults of docs/physics.md §1 and §10).

use crate::DynamicsError;

/// RocketPy's default absolute tolerances: positions, velocities 1e-3; quaternion 1e-6;
/// angular rates 1e-3 (docs/physics.md §1, §10.1).
pub const DEFAULT_ATOL: [f64; 13] = [
    1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-6, 1e-6, 1e-6, 1e-6, 1e-3, 1e-3, 1e-3,
];

/// Which form of the 6-DOF equations a flight integrates (`[flight] equations`,
/// docs/physics.md §8.6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EquationsForm {
    /// The physically consistent form (default): the CM and nozzle vectors from the CDM to the
    /// CM and to the nozzle, and a mass flow that is the derivative of the vehicle's mass
    /// (docs/physics.md §5.4, §5.6, §8.6, §15.3; RocketPy issue #1186, PR #1196).
    #[default]
    Standard,
    /// RocketPy 1.13 exactly: its CM→CDM and nozzle→CDM vectors (the mirrored lever arms of
    /// docs/physics.md §5.4, §5.6) and `ṁ = −T/v̄_e` for every motor (§15.3). The parity tests
    /// and `cargo xtask validate` fly this form against the RocketPy references.
    RocketPy113,
}

/// Which equations fly the free flight from rail exit to the first canopy (`[flight]
/// simulation_mode`, RocketPy 1.12+'s `Flight(simulation_mode=...)`, docs/physics.md §8.5). The
/// rail slide (§8.1) and the parachute descents (§8.4) are the same in both modes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SimulationMode {
    /// The 6-DOF variable-mass equations (default, §8.2).
    #[default]
    SixDof,
    /// RocketPy's 3-DOF point mass (`u_dot_generalized_3dof`): translation only, the attitude
    /// held or relaxed toward the relative wind by the weathercock law
    /// ([`FlightSettings::weathercock_coefficient`]).
    ThreeDof,
}

/// Launch and integration settings of one flight.
#[derive(Debug, Clone, PartialEq)]
pub struct FlightSettings {
    /// Rail length, m.
    pub rail_length: f64,
    /// Rail inclination from the horizontal, degrees (default 80).
    pub inclination_deg: f64,
    /// Rail heading, degrees clockwise from north (default 90).
    pub heading_deg: f64,
    /// Simulation end time, s (default 600).
    pub max_time: f64,
    /// Stop at apogee (default false).
    pub terminate_on_apogee: bool,
    /// Relative tolerance (default 1e-6).
    pub rtol: f64,
    /// Absolute tolerance per state (default [`DEFAULT_ATOL`]).
    pub atol: [f64; 13],
    /// Largest integration step, s (default ∞).
    pub max_time_step: f64,
    /// Largest step while on the rail, s (default 0.01): the rail derivative is zero until
    /// thrust exceeds weight, so the controller would otherwise grow the step without bound
    /// and skip the burn (docs/physics.md §10.4).
    pub rail_max_time_step: f64,
    /// Largest step where a sampled process that sets a control input needs short steps, s
    /// (default ∞: no bound). A control input set "after the step"
    /// ([`Action::SetControlAfterStep`], RocketPy's `time_overshoot`) acts from the end of
    /// the solver step that holds the sample (docs/physics.md §16.4), so a mission with a
    /// controller bounds the steps of the phases whose equations read the control inputs
    /// (the free flight, [`PhaseKind::reads_controls`]) by its sampling interval, keeping
    /// that delay as short as RocketPy's LSODA steps make it. The steps that end the flight's
    /// sampling early are bounded too, since their instants are not sampled: the rail's
    /// (rail exit) and the one that reaches the ground (a descent step longer than the bound
    /// that reaches the ground is integrated again with bounded steps). The rest of the
    /// parachute descents, where the controls act on nothing, keep the solver's steps.
    ///
    /// [`PhaseKind::reads_controls`]: crate::flight::PhaseKind::reads_controls
    /// [`Action::SetControlAfterStep`]: crate::flight::Action::SetControlAfterStep
    pub control_max_time_step: f64,
    /// Smallest step before the flight fails, s (default 1e-12).
    pub min_time_step: f64,
    /// Step budget per flight phase (default 200 000).
    pub max_steps_per_phase: usize,
    /// Seed of the parachute trigger-noise streams (recorded with the flight).
    pub noise_seed: u64,
    /// End integration steps on every thrust-curve knot during the burn and at burn-out
    /// (default true): the right-hand side has a kink at each knot and a jump at burn-out.
    /// RocketPy has no nodes there (its LSODA absorbs them in many short max-norm-controlled
    /// steps); without them a DOPRI5 step at the default tolerances can straddle a
    /// kink and the apogee of a rocket with a jagged thrust curve drifts by ~0.1 %.
    pub stop_at_thrust_knots: bool,
    /// Height margin of the bounds that pass over parachute sampling instants where a height
    /// trigger cannot fire, m (default 1; a numerical parameter, not a physical one: it
    /// absorbs round-off in the barometric height of a pressure). It changes no deployment of
    /// a noise-free trigger; with trigger noise it moves where the noise stream jumps over
    /// skipped instants, which changes the drawn noise as a different seed would.
    pub trigger_band: f64,
    /// The form of the 6-DOF equations (default [`EquationsForm::Standard`]).
    pub equations: EquationsForm,
    /// The equations of the free flight (default [`SimulationMode::SixDof`]).
    pub simulation_mode: SimulationMode,
    /// The 3-DOF weathercock rate, 1/s (RocketPy's `PointMassRocket.weathercock_coeff`,
    /// default 0: the attitude stays the rail's): the rocket axis turns toward the relative
    /// wind at `coefficient · sin(angle)` rad/s. Unused in 6 DOF.
    pub weathercock_coefficient: f64,
}

impl FlightSettings {
    /// Settings with RocketPy's defaults for a rail of the given length.
    #[must_use]
    pub fn new(rail_length: f64) -> Self {
        Self {
            rail_length,
            inclination_deg: 80.0,
            heading_deg: 90.0,
            max_time: 600.0,
            terminate_on_apogee: false,
            rtol: 1e-6,
            atol: DEFAULT_ATOL,
            max_time_step: f64::INFINITY,
            rail_max_time_step: 0.01,
            control_max_time_step: f64::INFINITY,
            min_time_step: 1e-12,
            max_steps_per_phase: 200_000,
            noise_seed: 0,
            stop_at_thrust_knots: true,
            trigger_band: 1.0,
            equations: EquationsForm::Standard,
            simulation_mode: SimulationMode::SixDof,
            weathercock_coefficient: 0.0,
        }
    }

    /// Checks every setting's range.
    ///
    /// # Errors
    /// [`DynamicsError::InvalidSetting`] naming the first bad setting.
    pub fn validate(&self) -> Result<(), DynamicsError> {
        let check = |name: &'static str, value: f64, ok: bool, reason: &'static str| {
            if ok {
                Ok(())
            } else {
                Err(DynamicsError::InvalidSetting {
                    name,
                    value,
                    reason,
                })
            }
        };
        let r = self.rail_length;
        check(
            "rail_length",
            r,
            r.is_finite() && r > 0.0,
            "must be a positive length",
        )?;
        let i = self.inclination_deg;
        check(
            "inclination",
            i,
            // Past 90° the rail leans toward heading + 180° (RocketPy accepts it, and a
            // dispersion around a vertical rail draws such values).
            i.is_finite() && i > 0.0 && i < 180.0,
            "must be in (0, 180) deg",
        )?;
        let h = self.heading_deg;
        check("heading", h, h.is_finite(), "must be finite")?;
        let m = self.max_time;
        check(
            "max_time",
            m,
            m.is_finite() && m > 0.0,
            "must be a positive time",
        )?;
        let rt = self.rtol;
        check("rtol", rt, rt.is_finite() && rt > 0.0, "must be positive")?;
        for &a in &self.atol {
            check(
                "atol",
                a,
                a.is_finite() && a > 0.0,
                "every component must be positive",
            )?;
        }
        let s = self.max_time_step;
        check("max_time_step", s, s > 0.0, "must be positive")?;
        let s = self.rail_max_time_step;
        check("rail_max_time_step", s, s > 0.0, "must be positive")?;
        let s = self.control_max_time_step;
        check("control_max_time_step", s, s > 0.0, "must be positive")?;
        let s = self.min_time_step;
        check(
            "min_time_step",
            s,
            s.is_finite() && s >= 0.0,
            "must be non-negative",
        )?;
        let b = self.trigger_band;
        check(
            "trigger_band",
            b,
            b.is_finite() && b > 0.0,
            "must be a positive length",
        )?;
        let w = self.weathercock_coefficient;
        check(
            "weathercock_coeff",
            w,
            w.is_finite() && w >= 0.0,
            "must be a non-negative rate",
        )?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_rocketpy_defaults_and_valid() {
        let s = FlightSettings::new(5.2);
        assert!(s.validate().is_ok());
        assert!((s.inclination_deg - 80.0).abs() < 1e-12 && (s.heading_deg - 90.0).abs() < 1e-12);
        assert!((s.max_time - 600.0).abs() < 1e-12 && !s.terminate_on_apogee);
    }

    #[test]
    fn bad_settings_are_named() {
        let mut s = FlightSettings::new(5.2);
        s.inclination_deg = 91.0;
        assert!(s.validate().is_ok(), "a rail just past vertical is valid");
        s.inclination_deg = 180.0;
        let err = s.validate().unwrap_err();
        assert!(matches!(
            err,
            DynamicsError::InvalidSetting {
                name: "inclination",
                ..
            }
        ));
        let mut s = FlightSettings::new(f64::NAN);
        s.rtol = 0.0;
        assert!(matches!(
            s.validate().unwrap_err(),
            DynamicsError::InvalidSetting {
                name: "rail_length",
                ..
            }
        ));
    }
}
