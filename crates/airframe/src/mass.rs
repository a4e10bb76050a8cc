//! Time-dependent mass properties of the rocket with its motor (docs/physics.md §5.3–§5.5).
//!
//! RocketPy forms these quantities with `Function` arithmetic (RocketPy `Rocket.evaluate_*`):
//! when every operand is a table on the SAME abscissae, the result is a new table of the
//! node-wise values with the first operand's interpolation; otherwise it is a pointwise
//! formula of the operands. Solid motors give tables on one common time grid (so the
//! CM-offset `c(t)`, which is a ratio, is interpolated linearly between exact node values),
//! generic motors mix grids (so everything is pointwise). [`MassModel`] reproduces both. A
//! liquid motor whose tanks are on different grids hands its propellant over in parts
//! ([`MotorProperties::propellant_parts`]), summed pointwise at each instant as RocketPy's
//! `LiquidMotor` does (docs/physics.md §15.3).
//!
//! Derivatives are those of RocketPy 1.13's complex-step differentiation
//! (`Function.differentiate_complex_step`): its evaluator picks the interval from the REAL
//! part of `x + i·h` with `bisect_left`, so at a node the slope is that of the interval to the
//! left, at the first node that of the first interval, at the last node that of the last
//! interval, and 0 outside under constant or zero extrapolation — exactly
//! [`Table1::derivative`]. Second derivatives (`Function.differentiate(order=2)`) are the
//! table's own for a table and a central difference with RocketPy's step `dx = 1e-6` s for a
//! pointwise formula; the step is [`karman_math::PhysicalConstants::time_difference_step`],
//! so that it follows the unit of time.

use karman_math::{Cursor, Extrapolation, Table1};
use karman_model::MassSample;

use crate::error::AirframeError;
use crate::motor::MotorProperties;

/// Mass properties of rocket + motor as functions of time, allocation-free to evaluate.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MassModel {
    /// csys_r.
    csys: f64,
    /// csys_r · csys_m.
    s: f64,
    motor_position: f64,
    /// Rocket mass without motor.
    rocket_mass: f64,
    /// m_r z_r + m_md z_mdc (user coordinates).
    dry_moment: f64,
    /// m_dry = m_r + m_md.
    pub dry_mass: f64,
    /// z_CDM, user coordinates.
    pub cdm: f64,
    /// Dry inertia about the CDM, `(I11, I22, I33, I12, I13, I23)`.
    pub dry_inertia: [f64; 6],
    motor: MotorProperties,
    /// `1 / v̄_e`, 0 when the motor has no valid exhaust velocity.
    inverse_exhaust_velocity: f64,
    /// Node-wise tables (common grid of the propellant tables), if RocketPy builds them so.
    nodal_offset: Option<Table1>,
    nodal_center_of_mass: Option<Table1>,
    nodal_i11: Option<Table1>,
    /// Whether the propellant mass, node-wise offset and I11 and the propellant I33 are all
    /// tables on one time grid (a solid motor's), so that [`MassModel::properties`] finds
    /// the time once for all of them.
    one_grid: bool,
    /// For a propellant in parts whose tables are all held constant outside their nodes:
    /// the last node of any of them, and the parts' figures beyond it (the mass-flow fields
    /// aside), which no longer change.
    parts_settled: Option<(f64, MassSample)>,
    /// For each part, whether its centre-of-mass and I11 tables have its mass table's nodes
    /// (one search serves all of them).
    parts_one_grid: Vec<bool>,
    /// Step of the central second difference of a pointwise formula (time).
    difference_step: f64,
}

/// Whether two tables share their abscissae exactly, strictly increasing (RocketPy's
/// node-wise arithmetic; a table with a repeated abscissa is evaluated pointwise instead).
fn same_grid(a: &Table1, b: &Table1) -> bool {
    a.strictly_increasing() && a.same_abscissae(b)
}

impl MassModel {
    /// Builds the model (docs/physics.md §5.3, §5.5).
    pub(crate) fn new(
        csys: f64,
        rocket_mass: f64,
        rocket_com: f64,
        rocket_inertia: [f64; 6],
        motor_position: f64,
        motor: MotorProperties,
        difference_step: f64,
        warnings: &mut Vec<String>,
    ) -> Result<Self, AirframeError> {
        let s = csys * motor.coordinate_system_sign;
        let m_md = motor.dry_mass;
        let z_mdc = motor_position + s * motor.center_of_dry_mass;
        let dry_mass = rocket_mass + m_md;
        let dry_moment = rocket_mass * rocket_com + m_md * z_mdc;
        let cdm = dry_moment / dry_mass;
        let mi = motor.dry_inertia;
        let ri = rocket_inertia;
        let (dr, dm) = (rocket_com - cdm, z_mdc - cdm);
        let dry_inertia = [
            ri[0] + rocket_mass * dr * dr + mi[0] + m_md * dm * dm,
            ri[1] + rocket_mass * dr * dr + mi[1] + m_md * dm * dm,
            ri[2] + mi[2],
            ri[3] + mi[3],
            ri[4] + mi[4],
            ri[5] + mi[5],
        ];
        let ve = motor.exhaust_velocity;
        let inverse_exhaust_velocity = if ve.is_finite() && ve > 0.0 {
            1.0 / ve
        } else {
            if motor.thrust.ys().iter().any(|&t| t != 0.0) {
                warnings.push(format!(
                    "motor: exhaust velocity {ve} m/s is not positive; the mass flow rate is \
                     taken as zero"
                ));
            }
            0.0
        };
        let parts_one_grid = motor
            .propellant_parts
            .iter()
            .map(|p| same_grid(&p.mass, &p.center_of_mass) && same_grid(&p.mass, &p.i11))
            .collect();
        let mut model = MassModel {
            csys,
            s,
            motor_position,
            rocket_mass,
            dry_moment,
            dry_mass,
            cdm,
            dry_inertia,
            motor,
            inverse_exhaust_velocity,
            nodal_offset: None,
            nodal_center_of_mass: None,
            nodal_i11: None,
            one_grid: false,
            parts_settled: None,
            parts_one_grid,
            difference_step,
        };
        model.parts_settled = model.settled_parts();
        let m = &model.motor;
        if m.propellant_parts.is_empty()
            && same_grid(&m.propellant_center_of_mass, &m.propellant_mass)
        {
            // On the common grid the tables' own ordinates are the values at the nodes: the
            // node-wise tables follow from them without a lookup.
            let cpm = &m.propellant_center_of_mass;
            let masses = m.propellant_mass.ys();
            let positions: Vec<f64> = cpm.ys().iter().map(|&z| model.motor_to_user(z)).collect();
            let nodal = |ys: Vec<f64>, like: &Table1, quantity: &'static str| {
                Table1::on_same_abscissae(like, ys, like.interpolation(), like.extrapolation())
                    .map_err(|source| AirframeError::Table {
                        component: "rocket".to_owned(),
                        quantity,
                        error: source,
                    })
            };
            let nodes = || masses.iter().copied().zip(positions.iter().copied());
            let offsets = nodes().map(|(mp, zp)| model.offset_of(mp, zp)).collect();
            let offset = nodal(offsets, cpm, "com_to_cdm")?;
            let centers = nodes()
                .map(|(mp, zp)| model.center_of_mass_of(mp, zp))
                .collect();
            let center = nodal(centers, cpm, "center_of_mass")?;
            let i11 = if same_grid(&m.propellant_i11, &m.propellant_mass) {
                let i = &m.propellant_i11;
                let ys = masses
                    .iter()
                    .zip(&positions)
                    .zip(i.ys())
                    .map(|((&mp, &zp), &ip)| model.i11_of(mp, zp, ip))
                    .collect();
                Some(nodal(ys, i, "inertia I11")?)
            } else {
                None
            };
            model.one_grid = i11.is_some() && same_grid(&m.propellant_i33, &m.propellant_mass);
            model.nodal_offset = Some(offset);
            model.nodal_center_of_mass = Some(center);
            model.nodal_i11 = i11;
        }
        Ok(model)
    }

    /// The motor data.
    pub(crate) fn motor(&self) -> &MotorProperties {
        &self.motor
    }

    /// Propellant CM in user coordinates, z_pc(t).
    #[inline]
    pub(crate) fn propellant_position(&self, t: f64) -> f64 {
        if self.motor.propellant_parts.is_empty() {
            self.motor_position + self.s * self.motor.propellant_center_of_mass.eval(t)
        } else {
            self.motor_to_user(self.propellant_sum(t).1)
        }
    }

    /// Propellant mass `m_p`: the table, or the sum of the parts.
    #[inline]
    fn propellant_mass(&self, t: f64) -> f64 {
        let m = &self.motor;
        if m.propellant_parts.is_empty() {
            m.propellant_mass.eval(t)
        } else {
            m.propellant_parts.iter().map(|p| p.mass.eval(t)).sum()
        }
    }

    /// `(m_p, z_pc, I11_p)` of a propellant in parts ([`MotorProperties::propellant_parts`]),
    /// summed pointwise as RocketPy 1.13's `LiquidMotor` does on different grids:
    /// `m_p = Σ m_i`, `z_pc = Σ (m_i z_i)/m_p` with each moment `m_i z_i` the part's own
    /// node-wise table (the first part's `z` where no mass is left),
    /// `I11_p = Σ (I_i + m_i (z_i − z_pc)²)`; `z` in motor coordinates.
    fn propellant_sum(&self, t: f64) -> (f64, f64, f64) {
        let parts = &self.motor.propellant_parts;
        let (mut mass, mut moment) = (0.0, 0.0);
        for p in parts {
            mass += p.mass.eval(t);
            moment += p.moment.eval(t);
        }
        let z = if mass == 0.0 {
            parts.first().map_or(0.0, |p| p.center_of_mass.eval(t))
        } else {
            moment / mass
        };
        let i11 = parts.iter().fold(0.0, |sum, p| {
            let d = p.center_of_mass.eval(t) - z;
            sum + (p.i11.eval(t) + p.mass.eval(t) * (d * d))
        });
        (mass, z, i11)
    }

    /// `(ṁ_p, ż_pc, İ11_p)` of [`MassModel::propellant_sum`], differentiated exactly as
    /// RocketPy's complex step differentiates the pointwise formulas (each table's own slope,
    /// [`Table1::derivative`]): `ż_pc = (Σ d(m_i z_i)/dt − z_pc ṁ_p)/m_p`,
    /// `İ11_p = Σ (İ_i + ṁ_i d_i² + 2 m_i d_i ḋ_i)` with `d_i = z_i − z_pc`.
    fn propellant_sum_rates(&self, t: f64) -> (f64, f64, f64) {
        let parts = &self.motor.propellant_parts;
        let (mass, z, _) = self.propellant_sum(t);
        let (mut mass_rate, mut moment_rate) = (0.0, 0.0);
        for p in parts {
            mass_rate += p.mass.derivative(t);
            moment_rate += p.moment.derivative(t);
        }
        let z_dot = if mass == 0.0 {
            parts
                .first()
                .map_or(0.0, |p| p.center_of_mass.derivative(t))
        } else {
            (moment_rate - z * mass_rate) / mass
        };
        let i11_rate = parts.iter().fold(0.0, |sum, p| {
            let (mi, d) = (p.mass.eval(t), p.center_of_mass.eval(t) - z);
            let d_dot = p.center_of_mass.derivative(t) - z_dot;
            sum + p.i11.derivative(t) + p.mass.derivative(t) * d * d + 2.0 * mi * d * d_dot
        });
        (mass_rate, z_dot, i11_rate)
    }

    /// Motor-frame point → user coordinates.
    #[inline]
    pub(crate) fn motor_to_user(&self, z_motor: f64) -> f64 {
        self.motor_position + self.s * z_motor
    }

    /// m(t).
    #[inline]
    pub(crate) fn total_mass(&self, t: f64) -> f64 {
        self.dry_mass + self.propellant_mass(t)
    }

    /// [`MassModel::total_mass`] with the time located from `cursor` (propellant times;
    /// updated).
    #[inline]
    pub(crate) fn total_mass_near(&self, t: f64, cursor: &mut Cursor) -> f64 {
        let m = &self.motor;
        if m.propellant_parts.is_empty() {
            self.dry_mass + m.propellant_mass.eval_with(t, cursor)
        } else {
            self.total_mass(t)
        }
    }

    /// Signed ṁ(t) = −T(t)/v̄_e.
    #[inline]
    pub(crate) fn mass_flow_rate(&self, t: f64) -> f64 {
        -self.motor.thrust.eval(t) * self.inverse_exhaust_velocity
    }

    /// m̈(t): slope of ṁ (segment slope of the thrust table).
    #[inline]
    pub(crate) fn mass_flow_rate_derivative(&self, t: f64) -> f64 {
        -self.motor.thrust.derivative(t) * self.inverse_exhaust_velocity
    }

    /// `(dm/dt, d²m/dt²)` at `t`: the motor's mass-flow table and its slope when it has one,
    /// else the slopes of the propellant-mass table (docs/physics.md §6.2; the mass the equations
    /// fly), with the time located from `cursor` (updated).
    #[inline]
    pub(crate) fn mass_rate_near(&self, t: f64, cursor: &mut Cursor) -> (f64, f64) {
        let m = &self.motor;
        match &m.mass_flow {
            Some(flow) => {
                let at = flow.locate_with(t, cursor);
                (flow.eval_at(at, t), flow.derivative_at(at, t))
            }
            None if m.propellant_parts.is_empty() => {
                let mass = &m.propellant_mass;
                let at = mass.locate_with(t, cursor);
                (mass.derivative_at(at, t), mass.second_derivative_at(at, t))
            }
            None => m
                .propellant_parts
                .iter()
                .fold((0.0, 0.0), |(rate, accel), p| {
                    (
                        rate + p.mass.derivative(t),
                        accel + p.mass.second_derivative(t),
                    )
                }),
        }
    }

    /// c for propellant mass `mp` at `zp` (user coordinates).
    fn offset_of(&self, mp: f64, zp: f64) -> f64 {
        -self.csys * (zp - self.cdm) * mp / (self.dry_mass + mp)
    }

    /// z_CM for propellant mass `mp` at `zp`.
    fn center_of_mass_of(&self, mp: f64, zp: f64) -> f64 {
        (self.dry_moment + mp * zp) / (self.dry_mass + mp)
    }

    /// I11 about the CDM for propellant mass `mp` at `zp` with its own I11 `ip`.
    fn i11_of(&self, mp: f64, zp: f64, ip: f64) -> f64 {
        let d = self.cdm - zp;
        self.dry_inertia[0] + ip + mp * d * d
    }

    /// `(m_p, z_pc in user coordinates, I11_p)` at `t`, evaluated pointwise.
    fn propellant_pointwise(&self, t: f64) -> (f64, f64, f64) {
        let m = &self.motor;
        if m.propellant_parts.is_empty() {
            (
                m.propellant_mass.eval(t),
                self.propellant_position(t),
                m.propellant_i11.eval(t),
            )
        } else {
            let (mp, z, ip) = self.propellant_sum(t);
            (mp, self.motor_to_user(z), ip)
        }
    }

    fn offset_pointwise(&self, t: f64) -> f64 {
        let (mp, zp, _) = self.propellant_pointwise(t);
        self.offset_of(mp, zp)
    }

    fn center_of_mass_pointwise(&self, t: f64) -> f64 {
        let (mp, zp, _) = self.propellant_pointwise(t);
        self.center_of_mass_of(mp, zp)
    }

    fn i11_pointwise(&self, t: f64) -> f64 {
        let (mp, zp, ip) = self.propellant_pointwise(t);
        self.i11_of(mp, zp, ip)
    }

    /// `(ṁ_p, ż_pc in user coordinates, İ11_p)` at `t`.
    fn propellant_rates(&self, t: f64) -> (f64, f64, f64) {
        let m = &self.motor;
        if m.propellant_parts.is_empty() {
            (
                m.propellant_mass.derivative(t),
                self.s * m.propellant_center_of_mass.derivative(t),
                m.propellant_i11.derivative(t),
            )
        } else {
            let (mp_dot, z_dot, ip_dot) = self.propellant_sum_rates(t);
            (mp_dot, self.s * z_dot, ip_dot)
        }
    }

    /// c(t), RocketPy's `com_to_cdm_function` (docs/physics.md §5.4, RocketPy sign).
    #[inline]
    pub(crate) fn com_to_cdm(&self, t: f64) -> f64 {
        match &self.nodal_offset {
            Some(table) => table.eval(t),
            None => self.offset_pointwise(t),
        }
    }

    /// ċ(t), RocketPy's complex-step derivative of c.
    #[inline]
    pub(crate) fn com_to_cdm_rate(&self, t: f64) -> f64 {
        if let Some(table) = &self.nodal_offset {
            return table.derivative(t);
        }
        let (mp, zp, _) = self.propellant_pointwise(t);
        let (mp_dot, zp_dot, _) = self.propellant_rates(t);
        let total = self.dry_mass + mp;
        -self.csys
            * (zp_dot * mp / total + (zp - self.cdm) * mp_dot * self.dry_mass / (total * total))
    }

    /// c̈(t), RocketPy's `differentiate(t, order=2)` of c: the table's second derivative
    /// (0 for a linear table), or a central difference of the formula with the step
    /// `difference_step` (RocketPy's 1e-6 s) — for a propellant in parts, the exact second
    /// derivative of the pointwise formula ([`MassModel::parts_properties`]), which that
    /// difference equals away from the parts' nodes.
    #[inline]
    pub(crate) fn com_to_cdm_accel(&self, t: f64) -> f64 {
        let h = self.difference_step;
        match &self.nodal_offset {
            Some(table) => table.second_derivative(t),
            None if !self.motor.propellant_parts.is_empty() => {
                self.parts_properties(t, 0.0, 0.0).com_to_cdm_accel
            }
            None => {
                (self.offset_pointwise(t + h) - 2.0 * self.offset_pointwise(t)
                    + self.offset_pointwise(t - h))
                    / (h * h)
            }
        }
    }

    /// Centre of mass z_CM(t), user coordinates.
    #[inline]
    pub(crate) fn center_of_mass(&self, t: f64) -> f64 {
        match &self.nodal_center_of_mass {
            Some(table) => table.eval(t),
            None => self.center_of_mass_pointwise(t),
        }
    }

    /// Inertia about the CDM, `(I11, I22, I33, I12, I13, I23)` (docs/physics.md §5.5).
    #[inline]
    pub(crate) fn inertia(&self, t: f64) -> [f64; 6] {
        let i11 = match &self.nodal_i11 {
            Some(table) => table.eval(t),
            None => self.i11_pointwise(t),
        };
        let d = &self.dry_inertia;
        [
            i11,
            i11 - d[0] + d[1],
            d[2] + self.motor.propellant_i33.eval(t),
            d[3],
            d[4],
            d[5],
        ]
    }

    /// İ(t) component-wise, RocketPy's complex-step derivative.
    #[inline]
    pub(crate) fn inertia_rate(&self, t: f64) -> [f64; 6] {
        let m = &self.motor;
        let i11 = match &self.nodal_i11 {
            Some(table) => table.derivative(t),
            None => {
                let (mp, zp, _) = self.propellant_pointwise(t);
                let (mp_dot, zp_dot, ip_dot) = self.propellant_rates(t);
                let d = self.cdm - zp;
                let d_dot = -zp_dot;
                ip_dot + mp_dot * d * d + 2.0 * mp * d * d_dot
            }
        };
        [i11, i11, m.propellant_i33.derivative(t), 0.0, 0.0, 0.0]
    }

    /// Every time-dependent quantity at `t`, equal to the individual methods: the thrust
    /// table is searched once for ṁ and m̈, and on a solid motor's single grid the time is
    /// searched once for the mass, the offset and the inertia with their derivatives. The
    /// searches start from `cursors` (thrust times, propellant times; updated).
    #[inline]
    pub(crate) fn properties_near(&self, t: f64, cursors: &mut [Cursor; 2]) -> MassSample {
        let m = &self.motor;
        let [on_thrust_cursor, on_grid_cursor] = cursors;
        let on_thrust = m.thrust.locate_with(t, on_thrust_cursor);
        let mass_flow_rate = -m.thrust.eval_at(on_thrust, t) * self.inverse_exhaust_velocity;
        let mass_flow_rate_derivative =
            -m.thrust.derivative_at(on_thrust, t) * self.inverse_exhaust_velocity;
        match (&self.nodal_offset, &self.nodal_i11) {
            (Some(offset), Some(i11)) if self.one_grid => {
                let at = m.propellant_mass.locate_with(t, on_grid_cursor);
                let i = i11.eval_at(at, t);
                let i_rate = i11.derivative_at(at, t);
                let d = &self.dry_inertia;
                MassSample {
                    total_mass: self.dry_mass + m.propellant_mass.eval_at(at, t),
                    mass_flow_rate,
                    mass_flow_rate_derivative,
                    com_to_cdm: offset.eval_at(at, t),
                    com_to_cdm_rate: offset.derivative_at(at, t),
                    com_to_cdm_accel: offset.second_derivative_at(at, t),
                    inertia: [
                        i,
                        i - d[0] + d[1],
                        d[2] + m.propellant_i33.eval_at(at, t),
                        d[3],
                        d[4],
                        d[5],
                    ],
                    inertia_rate: [
                        i_rate,
                        i_rate,
                        m.propellant_i33.derivative_at(at, t),
                        0.0,
                        0.0,
                        0.0,
                    ],
                }
            }
            _ if !m.propellant_parts.is_empty() => match &self.parts_settled {
                Some((end, settled)) if t > *end => MassSample {
                    mass_flow_rate,
                    mass_flow_rate_derivative,
                    ..*settled
                },
                _ => self.parts_properties(t, mass_flow_rate, mass_flow_rate_derivative),
            },
            _ => MassSample {
                total_mass: self.total_mass(t),
                mass_flow_rate,
                mass_flow_rate_derivative,
                com_to_cdm: self.com_to_cdm(t),
                com_to_cdm_rate: self.com_to_cdm_rate(t),
                com_to_cdm_accel: self.com_to_cdm_accel(t),
                inertia: self.inertia(t),
                inertia_rate: self.inertia_rate(t),
            },
        }
    }

    /// The parts' settled figures ([`MassModel::parts_settled`]): their tables searched
    /// beyond the last node of any of them, when every table is held constant there.
    fn settled_parts(&self) -> Option<(f64, MassSample)> {
        let m = &self.motor;
        let mut tables = m
            .propellant_parts
            .iter()
            .flat_map(|p| [&p.mass, &p.moment, &p.center_of_mass, &p.i11]);
        if m.propellant_parts.is_empty()
            || !tables
                .clone()
                .chain([&m.propellant_i33])
                .all(|t| t.extrapolation() == Extrapolation::Constant)
        {
            return None;
        }
        let end = tables
            .by_ref()
            .chain([&m.propellant_i33])
            .map(|t| t.xs()[t.xs().len() - 1])
            .fold(f64::NEG_INFINITY, f64::max);
        // Any time beyond the end gives the same figures: the constant extrapolations.
        Some((end, self.parts_properties(end + 1.0, 0.0, 0.0)))
    }

    /// [`MassModel::properties_near`] for a propellant in parts: the formulas of
    /// [`MassModel::propellant_sum`] and [`MassModel::propellant_sum_rates`] with each part's
    /// tables searched once (its mass and moment share their nodes), and c̈ differentiated
    /// exactly: with `c = −σ N/D`, `N = (z_motor − z_cdm) m_p + s Σ (m_i z_i)`, `D = m_d + m_p`
    /// (σ the coordinate-system sign, `s` the motor's orientation, each table's own slopes,
    /// right-hand at a node), `c̈ = −σ [N''/D − (2 N' ṁ_p + N m̈_p)/D² + 2 N ṁ_p²/D³]`.
    ///
    /// RocketPy takes a central difference of step 1e-6 s, which this equals except within
    /// that step of a node. There the difference straddles a kink of the linear tables and
    /// returns a spike of the jump in slope over the step; RocketPy's own grids (its grain's
    /// solver output times) rarely meet its integrator's evaluation times, whereas a hybrid's
    /// grain grid here holds the thrust nodes, where the integrator ends its steps.
    fn parts_properties(
        &self,
        t: f64,
        mass_flow_rate: f64,
        mass_flow_rate_derivative: f64,
    ) -> MassSample {
        let parts = &self.motor.propellant_parts;
        let lever = self.motor_position - self.cdm;
        let (mut mp, mut mp1, mut mp2) = (0.0, 0.0, 0.0);
        let (mut q, mut q1) = (0.0, 0.0);
        let (mut n, mut n1, mut n2) = (0.0, 0.0, 0.0);
        for p in parts {
            let at = p.mass.locate(t);
            let (m, m1, m2) = (
                p.mass.eval_at(at, t),
                p.mass.derivative_at(at, t),
                p.mass.second_derivative_at(at, t),
            );
            let (qi, qi1, qi2) = (
                p.moment.eval_at(at, t),
                p.moment.derivative_at(at, t),
                p.moment.second_derivative_at(at, t),
            );
            mp += m;
            mp1 += m1;
            mp2 += m2;
            q += qi;
            q1 += qi1;
            n += lever * m + self.s * qi;
            n1 += lever * m1 + self.s * qi1;
            n2 += lever * m2 + self.s * qi2;
        }
        let (z, z_dot) = if mp == 0.0 {
            parts.first().map_or((0.0, 0.0), |p| {
                (p.center_of_mass.eval(t), p.center_of_mass.derivative(t))
            })
        } else {
            let z = q / mp;
            (z, (q1 - z * mp1) / mp)
        };
        let (mut ip, mut ip_dot) = (0.0, 0.0);
        for (p, &one_grid) in parts.iter().zip(&self.parts_one_grid) {
            let at_mass = p.mass.locate(t);
            let (at, at_i) = if one_grid {
                (at_mass, at_mass)
            } else {
                (p.center_of_mass.locate(t), p.i11.locate(t))
            };
            let d = p.center_of_mass.eval_at(at, t) - z;
            let d_dot = p.center_of_mass.derivative_at(at, t) - z_dot;
            let mi = p.mass.eval_at(at_mass, t);
            ip += p.i11.eval_at(at_i, t) + mi * (d * d);
            ip_dot += p.i11.derivative_at(at_i, t)
                + p.mass.derivative_at(at_mass, t) * d * d
                + 2.0 * mi * d * d_dot;
        }
        let zp = self.motor_to_user(z);
        let zp_dot = self.s * z_dot;
        let total = self.dry_mass + mp;
        let com_to_cdm_rate = -self.csys
            * (zp_dot * mp / total + (zp - self.cdm) * mp1 * self.dry_mass / (total * total));
        let com_to_cdm_accel = -self.csys
            * (n2 / total - (2.0 * n1 * mp1 + n * mp2) / (total * total)
                + 2.0 * n * mp1 * mp1 / (total * total * total));
        let i11 = self.i11_of(mp, zp, ip);
        let d = self.cdm - zp;
        let i11_rate = ip_dot + mp1 * d * d + 2.0 * mp * d * (-zp_dot);
        let dry = &self.dry_inertia;
        let i33 = &self.motor.propellant_i33;
        let at = i33.locate(t);
        MassSample {
            total_mass: total,
            mass_flow_rate,
            mass_flow_rate_derivative,
            com_to_cdm: self.offset_of(mp, zp),
            com_to_cdm_rate,
            com_to_cdm_accel,
            inertia: [
                i11,
                i11 - dry[0] + dry[1],
                dry[2] + i33.eval_at(at, t),
                dry[3],
                dry[4],
                dry[5],
            ],
            inertia_rate: [i11_rate, i11_rate, i33.derivative_at(at, t), 0.0, 0.0, 0.0],
        }
    }

    /// Rocket mass without motor.
    pub(crate) fn rocket_mass(&self) -> f64 {
        self.rocket_mass
    }
}
