//! The [`Motor`]: a processed thrust curve, the motor's dry structure and a propellant model,
//! with the accessors the airframe and dynamics crates use (docs/physics.md §5.2, §6).
//!
//! Motor-level quantities follow RocketPy's `Motor` base class (rocketpy/motors/motor.py):
//! - `m(t) = m_p(t) + m_dry`;
//! - `z_cm(t) = (z_p m_p + z_dry m_dry) / m` (motor coordinates);
//! - `I11(t) = I11_p + m_p (z_p − z_cm)² + I11_dry + m_dry (z_dry − z_cm)²` (parallel axis,
//!   about the motor's instantaneous centre of mass), `I33(t) = I33_p + I33_dry`;
//! - `v̄_e = I_tot / m_p0`, `ṁ(t) = −T(t)/v̄_e` (docs/physics.md §6.2);
//! - pressure thrust `(p_ref − p)·π r_n²` when a reference pressure is given (§6.3).

use karman_math::{Extrapolation, Interpolation, PhysicalConstants, Table1};

use crate::hybrid::HybridPropellant;
use crate::liquid::LiquidPropellant;
use crate::propellant::{finite, non_negative};
use crate::{
    BatesGrains, CylindricalChamber, PositionedTank, PropellantModel, PropellantTables,
    PropulsionError, ThrustCurve,
};
use karman_model::PropellantPart;

/// Orientation of the motor's axial coordinate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CoordinateSystem {
    /// Positive from the nozzle toward the combustion chamber (RocketPy default), `csys_m = +1`.
    #[default]
    NozzleToCombustionChamber,
    /// Positive from the combustion chamber toward the nozzle, `csys_m = −1`.
    CombustionChamberToNozzle,
}

impl CoordinateSystem {
    /// `csys_m`: +1 or −1.
    #[must_use]
    pub fn sign(self) -> f64 {
        match self {
            CoordinateSystem::NozzleToCombustionChamber => 1.0,
            CoordinateSystem::CombustionChamberToNozzle => -1.0,
        }
    }
}

/// The motor's structure: everything but thrust and propellant (RocketPy `Motor` arguments).
#[derive(Debug, Clone, PartialEq)]
pub struct MotorStructure {
    /// Dry mass `m_dry`, kg.
    pub dry_mass: f64,
    /// Dry inertia `(I11, I22, I33, I12, I13, I23)` about the dry centre of mass, kg·m²
    /// (RocketPy's convention: products carry their minus sign).
    pub dry_inertia: [f64; 6],
    /// Dry centre of mass, m, motor coordinates.
    pub center_of_dry_mass: f64,
    /// Nozzle exit position, m, motor coordinates.
    pub nozzle_position: f64,
    /// Nozzle exit radius `r_n`, m.
    pub nozzle_radius: f64,
    /// Orientation of the motor coordinates.
    pub coordinate_system: CoordinateSystem,
    /// Ambient pressure at which the thrust was measured, Pa (enables the pressure thrust).
    pub reference_pressure: Option<f64>,
}

impl MotorStructure {
    fn validate(&self) -> Result<(), PropulsionError> {
        non_negative("dry_mass", self.dry_mass)?;
        for (v, name) in
            self.dry_inertia
                .iter()
                .zip(["dry_inertia I11", "dry_inertia I22", "dry_inertia I33"])
        {
            non_negative(name, *v)?;
        }
        for v in &self.dry_inertia[3..] {
            finite("dry_inertia product", *v)?;
        }
        finite("center_of_dry_mass_position", self.center_of_dry_mass)?;
        finite("nozzle_position", self.nozzle_position)?;
        non_negative("nozzle_radius", self.nozzle_radius)?;
        if let Some(p) = self.reference_pressure {
            non_negative("reference_pressure", p)?;
        }
        Ok(())
    }
}

/// The motor type and its type-specific parameters.
#[derive(Debug, Clone, PartialEq)]
pub enum MotorKind {
    /// Solid motor with BATES grains.
    Solid(BatesGrains),
    /// Generic motor (propellant as a cylinder filling the chamber).
    Generic(CylindricalChamber),
    /// Liquid motor: all the propellant is in the tanks.
    Liquid(Vec<PositionedTank>),
    /// Hybrid motor: a solid fuel grain and oxidiser tanks.
    Hybrid(BatesGrains, Vec<PositionedTank>),
    /// No motor: no thrust, no mass (RocketPy `EmptyMotor`).
    Empty,
}

/// A rocket motor with precomputed tables; every per-step method is allocation-free.
#[derive(Debug, Clone, PartialEq)]
pub struct Motor {
    kind: MotorKind,
    structure: MotorStructure,
    thrust: ThrustCurve,
    propellant_initial_mass: f64,
    exhaust_velocity: f64,
    propellant: PropellantTables,
}

impl Motor {
    /// A solid motor (RocketPy `SolidMotor`), inputs in SI.
    ///
    /// # Errors
    /// [`PropulsionError::InvalidParameter`] for a parameter out of range,
    /// [`PropulsionError::NoImpulse`] for a curve without positive impulse,
    /// [`PropulsionError::ExhaustVelocity`] when `I_tot / m_p0` gives no finite mass flow.
    pub fn solid(
        thrust: ThrustCurve,
        structure: MotorStructure,
        grains: BatesGrains,
    ) -> Result<Motor, PropulsionError> {
        Self::solid_with(thrust, structure, grains, &PhysicalConstants::SI)
    }

    /// A solid motor whose inputs are in the unit system of `constants` (which sets the time
    /// spacing of its tables); [`Motor::solid`] with [`PhysicalConstants::SI`].
    ///
    /// # Errors
    /// As [`Motor::solid`].
    pub fn solid_with(
        thrust: ThrustCurve,
        structure: MotorStructure,
        grains: BatesGrains,
        constants: &PhysicalConstants,
    ) -> Result<Motor, PropulsionError> {
        let (propellant_initial_mass, exhaust_velocity, propellant) =
            Self::propellant(&thrust, &structure, &grains, constants)?;
        Ok(Motor {
            kind: MotorKind::Solid(grains),
            structure,
            thrust,
            propellant_initial_mass,
            exhaust_velocity,
            propellant,
        })
    }

    /// A generic motor (RocketPy `GenericMotor`). Its tables have no time step of their own
    /// (they are sampled on the thrust curve), so no constants are needed.
    ///
    /// # Errors
    /// As [`Motor::solid`].
    pub fn generic(
        thrust: ThrustCurve,
        structure: MotorStructure,
        chamber: CylindricalChamber,
    ) -> Result<Motor, PropulsionError> {
        let (propellant_initial_mass, exhaust_velocity, propellant) =
            Self::propellant(&thrust, &structure, &chamber, &PhysicalConstants::SI)?;
        Ok(Motor {
            kind: MotorKind::Generic(chamber),
            structure,
            thrust,
            propellant_initial_mass,
            exhaust_velocity,
            propellant,
        })
    }

    /// A liquid motor (RocketPy `LiquidMotor` with its `add_tank` calls, in order), inputs in
    /// SI: the propellant is the tanks' contents (docs/physics.md §15.3).
    ///
    /// # Errors
    /// As [`Motor::solid`]; no tanks is an [`PropulsionError::InvalidParameter`].
    pub fn liquid(
        thrust: ThrustCurve,
        structure: MotorStructure,
        tanks: Vec<PositionedTank>,
    ) -> Result<Motor, PropulsionError> {
        let model = LiquidPropellant {
            tanks: &tanks,
            burn_start: thrust.burn_start(),
        };
        let (propellant_initial_mass, exhaust_velocity, propellant) =
            Self::propellant(&thrust, &structure, &model, &PhysicalConstants::SI)?;
        Ok(Motor {
            kind: MotorKind::Liquid(tanks),
            structure,
            thrust,
            propellant_initial_mass,
            exhaust_velocity,
            propellant,
        })
    }

    /// A hybrid motor (RocketPy `HybridMotor` with its `add_tank` calls, in order), inputs in
    /// the unit system of `constants` (which sets the time spacing of the grain's tables):
    /// the grain regresses with the flow the tanks do not supply (docs/physics.md §15.4).
    ///
    /// # Errors
    /// As [`Motor::liquid`].
    pub fn hybrid(
        thrust: ThrustCurve,
        structure: MotorStructure,
        grains: BatesGrains,
        tanks: Vec<PositionedTank>,
        constants: &PhysicalConstants,
    ) -> Result<Motor, PropulsionError> {
        let model = HybridPropellant {
            grains: &grains,
            tanks: LiquidPropellant {
                tanks: &tanks,
                burn_start: thrust.burn_start(),
            },
        };
        let (propellant_initial_mass, exhaust_velocity, propellant) =
            Self::propellant(&thrust, &structure, &model, constants)?;
        Ok(Motor {
            kind: MotorKind::Hybrid(grains, tanks),
            structure,
            thrust,
            propellant_initial_mass,
            exhaust_velocity,
            propellant,
        })
    }

    /// No motor (RocketPy `EmptyMotor`): zero thrust over `[0, 1]` s, no mass. Its exhaust
    /// velocity is `+∞`, so `ṁ = −T/v̄_e` is zero.
    #[must_use]
    pub fn empty() -> Motor {
        let zero = || {
            Table1::new(
                vec![0.0],
                vec![0.0],
                Interpolation::Linear,
                Extrapolation::Constant,
            )
            .unwrap_or_else(|_| unreachable!("a single finite point is a valid table"))
        };
        Motor {
            kind: MotorKind::Empty,
            structure: MotorStructure {
                dry_mass: 0.0,
                dry_inertia: [0.0; 6],
                center_of_dry_mass: 0.0,
                nozzle_position: 0.0,
                nozzle_radius: 0.0,
                coordinate_system: CoordinateSystem::NozzleToCombustionChamber,
                reference_pressure: None,
            },
            thrust: ThrustCurve::zero(),
            propellant_initial_mass: 0.0,
            exhaust_velocity: f64::INFINITY,
            propellant: PropellantTables {
                mass: zero(),
                center_of_mass: zero(),
                i11: zero(),
                i33: zero(),
                parts: Vec::new(),
            },
        }
    }

    /// Validates the inputs and returns `(m_p0, v̄_e, propellant tables)`.
    fn propellant(
        thrust: &ThrustCurve,
        structure: &MotorStructure,
        model: &dyn PropellantModel,
        constants: &PhysicalConstants,
    ) -> Result<(f64, f64, PropellantTables), PropulsionError> {
        structure.validate()?;
        model.validate()?;
        let impulse = thrust.total_impulse();
        if !(impulse.is_finite() && impulse > 0.0) {
            return Err(PropulsionError::NoImpulse { impulse });
        }
        let initial_mass = model.initial_mass();
        let exhaust_velocity = impulse / initial_mass;
        // `ṁ = −T/v̄_e` must be finite wherever the thrust is: v̄_e positive (+∞ for a motor
        // without propellant) and the peak flow representable.
        let peak_thrust = thrust
            .table()
            .ys()
            .iter()
            .fold(0.0_f64, |a, t| a.max(t.abs()));
        if !(exhaust_velocity > 0.0 && (peak_thrust / exhaust_velocity).is_finite()) {
            return Err(PropulsionError::ExhaustVelocity {
                impulse,
                initial_mass,
                exhaust_velocity,
                peak_thrust,
            });
        }
        Ok((
            initial_mass,
            exhaust_velocity,
            model.tables(thrust, exhaust_velocity, constants)?,
        ))
    }

    /// The motor type and its parameters.
    #[must_use]
    pub fn kind(&self) -> &MotorKind {
        &self.kind
    }
    /// The processed thrust curve.
    #[must_use]
    pub fn thrust_curve(&self) -> &ThrustCurve {
        &self.thrust
    }
    /// Raw thrust table `T(t)`, N, zero outside the burn (docs/physics.md §6.1).
    #[must_use]
    pub fn thrust_table(&self) -> &Table1 {
        self.thrust.table()
    }
    /// Raw thrust at `t`, N.
    #[inline]
    #[must_use]
    pub fn thrust(&self, t: f64) -> f64 {
        self.thrust.thrust(t)
    }
    /// Burn start, s.
    #[must_use]
    pub fn burn_start(&self) -> f64 {
        self.thrust.burn_start()
    }
    /// Burn out, s.
    #[must_use]
    pub fn burn_out(&self) -> f64 {
        self.thrust.burn_out()
    }
    /// Total impulse, N·s.
    #[must_use]
    pub fn total_impulse(&self) -> f64 {
        self.thrust.total_impulse()
    }
    /// Average thrust over the burn, N.
    #[must_use]
    pub fn average_thrust(&self) -> f64 {
        self.thrust.average_thrust()
    }
    /// Largest thrust sample, N.
    #[must_use]
    pub fn max_thrust(&self) -> f64 {
        self.thrust.max_thrust()
    }
    /// Average exhaust velocity `v̄_e = I_tot / m_p0`, m/s (`+∞` for the empty motor).
    #[must_use]
    pub fn exhaust_velocity(&self) -> f64 {
        self.exhaust_velocity
    }
    /// The exhaust velocity RocketPy reports at `t` (`motor.exhaust_velocity(t)`), m/s: for a
    /// liquid motor the tanks' `−T(t)/ṁ_tanks(t)` (0 where the tanks do not flow; docs/physics.md
    /// §15.3, for reports only: the equations of motion use [`Motor::exhaust_velocity`]),
    /// for every other motor `v̄_e`.
    #[must_use]
    pub fn reported_exhaust_velocity(&self, t: f64) -> f64 {
        match &self.kind {
            MotorKind::Liquid(tanks) => {
                let flow: f64 = tanks.iter().map(|p| p.tank.net_mass_flow().eval(t)).sum();
                if flow == 0.0 {
                    0.0
                } else {
                    -self.thrust(t) / flow
                }
            }
            _ => self.exhaust_velocity,
        }
    }
    /// Signed propellant mass flow `ṁ = −T(t)/v̄_e`, kg/s (negative while burning).
    #[inline]
    #[must_use]
    pub fn mass_flow_rate(&self, t: f64) -> f64 {
        -self.thrust(t) / self.exhaust_velocity
    }
    /// Initial propellant mass `m_p0`, kg.
    #[must_use]
    pub fn propellant_initial_mass(&self) -> f64 {
        self.propellant_initial_mass
    }
    /// Propellant mass table `m_p(t)`, kg.
    #[must_use]
    pub fn propellant_mass(&self) -> &Table1 {
        &self.propellant.mass
    }
    /// Propellant centre of mass table `z_p(t)`, m, motor coordinates.
    #[must_use]
    pub fn propellant_center_of_mass(&self) -> &Table1 {
        &self.propellant.center_of_mass
    }
    /// Propellant inertia tables `(I11_p(t), I33_p(t))` about the propellant centre of mass,
    /// kg·m².
    #[must_use]
    pub fn propellant_inertia(&self) -> (&Table1, &Table1) {
        (&self.propellant.i11, &self.propellant.i33)
    }
    /// Dry mass, kg.
    #[must_use]
    pub fn dry_mass(&self) -> f64 {
        self.structure.dry_mass
    }
    /// Dry centre of mass, m, motor coordinates.
    #[must_use]
    pub fn center_of_dry_mass(&self) -> f64 {
        self.structure.center_of_dry_mass
    }
    /// Dry inertia `(I11, I22, I33, I12, I13, I23)` about the dry centre of mass, kg·m².
    #[must_use]
    pub fn dry_inertia(&self) -> [f64; 6] {
        self.structure.dry_inertia
    }
    /// Nozzle exit position, m, motor coordinates.
    #[must_use]
    pub fn nozzle_position(&self) -> f64 {
        self.structure.nozzle_position
    }
    /// Nozzle exit radius, m.
    #[must_use]
    pub fn nozzle_radius(&self) -> f64 {
        self.structure.nozzle_radius
    }
    /// The motor's tanks with their positions (liquid and hybrid motors; empty otherwise).
    #[must_use]
    pub fn tanks(&self) -> &[PositionedTank] {
        match &self.kind {
            MotorKind::Liquid(tanks) | MotorKind::Hybrid(_, tanks) => tanks,
            _ => &[],
        }
    }
    /// The parts whose pointwise sum the propellant is (docs/physics.md §15.3–15.4): the tanks of a
    /// liquid motor whose tanks are on different time grids, the grain and the tanks of a
    /// hybrid motor, for which RocketPy evaluates the sums pointwise; empty for every other
    /// motor, whose propellant tables are exact. The propellant tables then tabulate those
    /// sums on the union of the grids, for reports.
    #[must_use]
    pub fn propellant_parts(&self) -> &[PropellantPart] {
        &self.propellant.parts
    }
    /// Nozzle throat radius, m (solid and hybrid motors only).
    #[must_use]
    pub fn throat_radius(&self) -> Option<f64> {
        match &self.kind {
            MotorKind::Solid(g) | MotorKind::Hybrid(g, _) => Some(g.throat_radius),
            MotorKind::Generic(_) | MotorKind::Liquid(_) | MotorKind::Empty => None,
        }
    }
    /// Orientation of the motor coordinates.
    #[must_use]
    pub fn coordinate_system(&self) -> CoordinateSystem {
        self.structure.coordinate_system
    }
    /// `csys_m`: +1 for nozzle-to-combustion-chamber, −1 otherwise.
    #[must_use]
    pub fn coordinate_system_sign(&self) -> f64 {
        self.structure.coordinate_system.sign()
    }
    /// Reference pressure of the thrust data, Pa.
    #[must_use]
    pub fn reference_pressure(&self) -> Option<f64> {
        self.structure.reference_pressure
    }
    /// Pressure thrust `(p_ref − p)·π r_n²`, N, or 0 without a reference pressure
    /// (RocketPy `Motor.pressure_thrust`).
    #[inline]
    #[must_use]
    pub fn pressure_thrust(&self, ambient_pressure: f64) -> f64 {
        match self.structure.reference_pressure {
            Some(p_ref) => {
                (p_ref - ambient_pressure)
                    * std::f64::consts::PI
                    * self.structure.nozzle_radius.powi(2)
            }
            None => 0.0,
        }
    }
    /// Total motor mass `m_p(t) + m_dry`, kg.
    #[inline]
    #[must_use]
    pub fn total_mass(&self, t: f64) -> f64 {
        self.propellant.mass.eval(t) + self.structure.dry_mass
    }
    /// Propellant mass, propellant centre of mass and motor centre of mass at `t`.
    #[inline]
    fn mass_state(&self, t: f64) -> (f64, f64, f64) {
        let mp = self.propellant.mass.eval(t);
        let zp = self.propellant.center_of_mass.eval(t);
        let md = self.structure.dry_mass;
        let total = mp + md;
        let zc = if total > 0.0 {
            (zp * mp + md * self.structure.center_of_dry_mass) / total
        } else {
            zp
        };
        (mp, zp, zc)
    }
    /// Motor centre of mass, m, motor coordinates. A massless motor (no dry mass, propellant
    /// gone) takes the limit `m_p → 0`, the propellant centre of mass.
    #[inline]
    #[must_use]
    pub fn center_of_mass(&self, t: f64) -> f64 {
        self.mass_state(t).2
    }
    /// Motor inertia `(I11, I33)` about the motor's centre of mass at `t`, kg·m².
    #[inline]
    #[must_use]
    pub fn inertia(&self, t: f64) -> (f64, f64) {
        let (mp, zp, zc) = self.mass_state(t);
        let md = self.structure.dry_mass;
        let zd = self.structure.center_of_dry_mass;
        let [d11, _, d33, ..] = self.structure.dry_inertia;
        let i11 =
            self.propellant.i11.eval(t) + mp * (zp - zc).powi(2) + d11 + md * (zd - zc).powi(2);
        (i11, self.propellant.i33.eval(t) + d33)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BurnTime, ThrustOptions, ThrustSource};

    fn structure() -> MotorStructure {
        MotorStructure {
            dry_mass: 1.0,
            dry_inertia: [0.1, 0.1, 0.01, 0.0, 0.0, 0.0],
            center_of_dry_mass: 0.3,
            nozzle_position: 0.0,
            nozzle_radius: 0.03,
            coordinate_system: CoordinateSystem::NozzleToCombustionChamber,
            reference_pressure: Some(101_325.0),
        }
    }

    fn curve() -> ThrustCurve {
        let opts = ThrustOptions {
            burn_time: Some(BurnTime::End(2.0)),
            ..Default::default()
        };
        ThrustCurve::new(&ThrustSource::Constant(1000.0), &opts).unwrap()
    }

    #[test]
    fn generic_motor_mass_and_inertia() {
        let chamber = CylindricalChamber {
            radius: 0.05,
            height: 0.4,
            position: 0.5,
            propellant_initial_mass: 2.0,
        };
        let m = Motor::generic(curve(), structure(), chamber).unwrap();
        // v̄_e = 2000 N·s / 2 kg; constant thrust ⇒ m_p linear, half gone at t = 1 s.
        assert!((m.exhaust_velocity() - 1000.0).abs() < 1e-12);
        assert!((m.mass_flow_rate(1.0) + 1.0).abs() < 1e-12);
        assert!((m.total_mass(1.0) - 2.0).abs() < 1e-9);
        assert!((m.total_mass(5.0) - 1.0).abs() < 1e-9);
        let zc = (0.5 * 1.0 + 0.3 * 1.0) / 2.0;
        assert!((m.center_of_mass(1.0) - zc).abs() < 1e-9);
        let (i11, i33) = m.inertia(1.0);
        let expected = (3.0 * 0.0025 + 0.16) / 12.0
            + 1.0 * (0.5f64 - zc).powi(2)
            + 0.1
            + (0.3f64 - zc).powi(2);
        assert!((i11 - expected).abs() < 1e-9, "{i11} vs {expected}");
        assert!((i33 - (0.0025 / 2.0 + 0.01)).abs() < 1e-9);
        // Pressure thrust is positive in thinner air.
        assert!(m.pressure_thrust(50_000.0) > 0.0);
        assert!(m.throat_radius().is_none());
    }

    #[test]
    fn empty_motor_has_no_mass_or_flow() {
        let m = Motor::empty();
        assert!(m.total_mass(0.5).abs() < 1e-300);
        assert!(m.mass_flow_rate(0.5).abs() < 1e-300);
        assert!(m.thrust(0.5).abs() < 1e-300);
        assert!(m.center_of_mass(0.5).abs() < 1e-300);
    }

    #[test]
    fn rejects_bad_structure() {
        let chamber = CylindricalChamber {
            radius: 0.05,
            height: 0.4,
            position: 0.5,
            propellant_initial_mass: 2.0,
        };
        let s = MotorStructure {
            dry_mass: -1.0,
            ..structure()
        };
        assert!(matches!(
            Motor::generic(curve(), s, chamber),
            Err(PropulsionError::InvalidParameter {
                name: "dry_mass",
                ..
            })
        ));
    }
}
