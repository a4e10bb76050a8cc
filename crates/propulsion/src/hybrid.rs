//! Hybrid motor: a solid fuel grain burning with the oxidiser of its tanks (docs/physics.md §15.4;
//! RocketPy `HybridMotor`, rocketpy/motors/hybrid_motor.py).
//!
//! RocketPy's `HybridMotor` is a `SolidMotor` (the grain) and a `LiquidMotor` (the tanks)
//! sharing the thrust curve:
//!
//! 1. `m_p0 = m_grain,0 + m_tanks(burn start)`, `v̄_e = I_tot/m_p0`, and the motor's flow
//!    `ṁ = −T/v̄_e`;
//! 2. the grain's flow is what the tanks do not supply, `ṁ_g = ṁ − Σ ṁ_tank,net` (tank net
//!    flows linear, zero outside their flux time), so the grain mass is
//!    `m_g(t) = m_g0 + ∫ ṁ_g dt` — exact here, both flows being piecewise linear — and the
//!    grain geometry follows from its volume as for a solid motor (§6.4; RocketPy integrates
//!    the same regression with LSODA); the burn stops when the grain is consumed, which may
//!    come before the motor's burn-out, and the geometry is held after that;
//! 3. `only_radial_burn` is RocketPy's hybrid default (true);
//! 4. `m_p = m_g + m_tanks`, `z_pc = (m_g z_g + m_tanks z_tanks)/m_p`, `I11_p` is each part's
//!    inertia moved to `z_pc`, `I33_p` the grain's `½ m_g (R_o² + r²)`.
//!
//! The grain and the tanks live on different grids, so RocketPy evaluates these pointwise
//! (`Function` arithmetic of tables on different grids): each part's moment `m z` is its own
//! node-wise table, and the sums are formed at each instant. The motor hands the two over as
//! propellant parts ([`crate::Motor::propellant_parts`]): the grain on its grid (the thrust
//! nodes, each interval split into pieces of at most
//! [`PhysicalConstants::propellant_grid_step`], and the tanks' nodes within the burn; mass and
//! `I11` linear, the centre of mass constant) and the tanks as the liquid motor's tables —
//! or, when the tanks are themselves on different grids, the tanks one by one (RocketPy nests
//! that sum inside the liquid motor; the two differ between nodes only by the tanks' moment
//! tables departing from the products of their mass and centre-of-mass tables). The
//! propellant tables tabulate the same sums on the union of the grids, linear between the
//! nodes, for reports, and hold the I33.

use karman_math::{Cursor, Extrapolation, Interpolation, PhysicalConstants, Table1};

use crate::liquid::{LiquidPropellant, tanks_at, union_grid};
use crate::propellant::propellant_part;
use crate::solid::{grain_grid, regress};
use crate::{
    BatesGrains, GrainState, PropellantModel, PropellantTables, PropulsionError, ThrustCurve,
};

/// Bisection steps that locate the grain's burn-out to the resolution of an `f64`.
const BISECTION_STEPS: usize = 200;

/// The grain and the tanks of a hybrid motor as its propellant model.
pub(crate) struct HybridPropellant<'a> {
    pub grains: &'a BatesGrains,
    pub tanks: LiquidPropellant<'a>,
}

/// The grain state holding `mass` kg, also above the initial mass (the grain gains mass while
/// the tanks deliver more than the thrust consumes): the bore then narrows, `h = h_0 + 2(r_0 −
/// r)` unless the burn is radial only.
fn grain_state(grains: &BatesGrains, mass: f64) -> GrainState {
    if mass <= grains.initial_mass() {
        return grains.state_for_mass(mass);
    }
    let (ro, r0, h0) = (
        grains.outer_radius,
        grains.initial_inner_radius,
        grains.initial_height,
    );
    let volume = mass / (f64::from(grains.number) * grains.density);
    if grains.only_radial_burn {
        let r = (ro * ro - volume / (std::f64::consts::PI * h0))
            .max(0.0)
            .sqrt();
        return GrainState {
            inner_radius: r,
            height: h0,
        };
    }
    let state = |r: f64| GrainState {
        inner_radius: r,
        height: h0 - 2.0 * (r - r0),
    };
    // The volume decreases with r on [0, r0]: bisect for it.
    let (mut lo, mut hi) = (0.0, r0);
    if grains.grain_volume(state(0.0)) <= volume {
        return state(0.0);
    }
    for _ in 0..BISECTION_STEPS {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if grains.grain_volume(state(mid)) > volume {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    state(0.5 * (lo + hi))
}

impl PropellantModel for HybridPropellant<'_> {
    fn initial_mass(&self) -> f64 {
        self.grains.initial_mass() + self.tanks.initial_mass()
    }

    fn validate(&self) -> Result<(), PropulsionError> {
        self.grains.validate()?;
        self.tanks.validate()
    }

    fn tables(
        &self,
        thrust: &ThrustCurve,
        exhaust_velocity: f64,
        constants: &PhysicalConstants,
    ) -> Result<PropellantTables, PropulsionError> {
        let grains = self.grains;
        let m0 = grains.initial_mass();
        let curve = thrust.table();
        let tanks = self.tanks.tanks;
        // ∫ ṁ_g over [a, b]: the thrust's share minus the tanks' net outflow.
        let mut cursor = Cursor::default();
        let grain_flow = |a: f64, b: f64| {
            let tank_flow: f64 = tanks
                .iter()
                .map(|p| p.tank.net_mass_flow().integral(a, b))
                .sum();
            -curve.integral_with(a, b, &mut cursor) / exhaust_velocity - tank_flow
        };
        let (start, end) = curve.domain();
        let mut grid = grain_grid(curve, constants);
        grid.extend(tanks.iter().flat_map(|p| {
            p.tank
                .mass()
                .xs()
                .iter()
                .copied()
                .filter(move |&t| t > start && t < end)
        }));
        let grid = union_grid(grid.into_iter());
        let (mut times, mut grain_mass) = regress(&grid, m0, grain_flow);
        // After the grain is gone the tanks still change: their nodes continue the grid.
        let burnt = times[times.len() - 1];
        let tail: Vec<f64> = grid.iter().copied().filter(|&t| t > burnt).collect();
        grain_mass.extend(std::iter::repeat_n(0.0, tail.len()));
        times.extend(tail);
        let grain_center = grains.center_of_mass_position;
        let n = times.len();
        let (mut mass, mut center, mut i11, mut i33, mut grain_i11s) = (
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
        );
        for (&t, &mg) in times.iter().zip(&grain_mass) {
            let (grain_i11, grain_i33) = grains.inertia(grain_state(grains, mg), mg);
            grain_i11s.push(grain_i11);
            let (ml, zl, il) = tanks_at(tanks, t);
            let m = mg + ml;
            let z = if m > 0.0 {
                (mg * grain_center + ml * zl) / m
            } else {
                zl
            };
            mass.push(m);
            center.push(z);
            i11.push(grain_i11 + mg * (grain_center - z).powi(2) + il + ml * (zl - z).powi(2));
            i33.push(grain_i33);
        }
        let (lin, hold) = (Interpolation::Linear, Extrapolation::Constant);
        let mass = Table1::new(times, mass, lin, hold)
            .map_err(PropulsionError::table("propellant mass"))?;
        let like = |ys, what| {
            Table1::on_same_abscissae(&mass, ys, lin, hold).map_err(PropulsionError::table(what))
        };
        let grain = propellant_part(
            like(grain_mass, "grain mass")?,
            like(vec![grain_center; n], "grain centre of mass")?,
            like(grain_i11s, "grain I11")?,
        )?;
        let liquid = self.tanks.tables(thrust, exhaust_velocity, constants)?;
        let mut parts = vec![grain];
        if liquid.parts.is_empty() {
            parts.push(propellant_part(
                liquid.mass,
                liquid.center_of_mass,
                liquid.i11,
            )?);
        } else {
            parts.extend(liquid.parts);
        }
        Ok(PropellantTables {
            center_of_mass: like(center, "propellant centre of mass")?,
            i11: like(i11, "propellant I11")?,
            i33: like(i33, "propellant I33")?,
            mass,
            parts,
        })
    }
}
