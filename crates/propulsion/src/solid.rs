//! Solid motor with BATES grains (docs/physics.md §6.4; RocketPy `SolidMotor`,
//! rocketpy/motors/solid_motor.py).
//!
//! `N` identical cylindrical grains (outer radius `R_o`, bore `r`, height `h`, density `ρ_g`)
//! burn on the bore and both ends at the same rate. With the volume rate of one grain
//! `V̇ = ṁ / (N ρ_g)` and burning area `A_b = 2π(R_o² − r² + r h)`, RocketPy integrates
//! `ṙ = −V̇/A_b`, `ḣ = −2ṙ` (LSODA). Here the same solution is obtained in closed form:
//! `ḣ = −2ṙ` gives `h = h_0 − 2(r − r_0)`, and the grain volume is known exactly from the thrust
//! curve, `V(t) = (m_p0 − ∫ T dt / v̄_e)/(N ρ_g)`, so `r` is the root of the cubic
//! `π(R_o² − r²)(h_0 − 2(r − r_0)) = V`, monotone on `[r_0, min(R_o, r_0 + h_0/2)]` (with
//! `only_radial_burn`, `h = h_0` and `r = √(R_o² − V/(π h_0))`). As in RocketPy, the burn stops
//! when the grain is consumed (`(R_o − r)h = 0`, which a thrust curve with negative tail values
//! reaches before its end) and the geometry is held after that.
//!
//! The tables are sampled on the thrust-curve nodes with every interval split into pieces of at
//! most [`PhysicalConstants::propellant_grid_step`] (5 ms in SI; longer for burns beyond
//! 250 s) and interpolated linearly (RocketPy samples at the LSODA output times; the two agree
//! to ~1e-4 relative, the error of RocketPy's linear interpolation between its steps). The
//! step is taken from the constants, not written here, so that it follows the unit of time.
//! Inertia of the grain stack about its centre (grain centres fixed, spaced `h_0 + s_g`):
//! `I11_p = N m_g [(R_o² + r²)/4 + h²/12] + m_g Σ d_i²`, `d_i = (i − (N−1)/2)(h_0 + s_g)`;
//! `I33_p = ½ m_p (R_o² + r²)`.

use karman_math::{Cursor, Extrapolation, Interpolation, PhysicalConstants, Table1};

use crate::propellant::{finite, non_negative, positive};
use crate::{PropellantModel, PropellantTables, PropulsionError, ThrustCurve};

/// Bound on the table size for very long burns: the spacing grows beyond
/// [`PhysicalConstants::propellant_grid_step`] so that the grid holds at most about this many
/// points besides the thrust nodes.
const MAX_GRID_POINTS: f64 = 50_000.0;

/// Relative slack on the number of grid steps in a thrust-curve interval (a few roundings).
const PIECE_ROUNDING: f64 = 1e-12;

/// Rounding allowance on the remaining propellant mass, relative to the initial mass.
const MASS_ROUNDING: f64 = 1e-12;

/// BATES grain geometry and material (RocketPy `SolidMotor` grain arguments).
#[derive(Debug, Clone, PartialEq)]
pub struct BatesGrains {
    /// Number of grains `N`.
    pub number: u32,
    /// Grain density `ρ_g`, kg/m³.
    pub density: f64,
    /// Outer radius `R_o`, m.
    pub outer_radius: f64,
    /// Initial bore radius `r_0`, m.
    pub initial_inner_radius: f64,
    /// Initial grain height `h_0`, m.
    pub initial_height: f64,
    /// Axial gap between grains `s_g`, m.
    pub separation: f64,
    /// Centre of mass of the grain stack, m, motor coordinates (constant).
    pub center_of_mass_position: f64,
    /// Nozzle throat radius, m (RocketPy default 0.01; used only for `Kn`).
    pub throat_radius: f64,
    /// Burn only on the bore (heights constant), RocketPy `only_radial_burn`.
    pub only_radial_burn: bool,
}

/// Bore radius and height of every grain at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GrainState {
    /// Bore radius `r`, m.
    pub inner_radius: f64,
    /// Grain height `h`, m.
    pub height: f64,
}

impl BatesGrains {
    /// Volume of one grain in the state `s`, m³.
    #[must_use]
    pub fn grain_volume(&self, s: GrainState) -> f64 {
        std::f64::consts::PI * (self.outer_radius.powi(2) - s.inner_radius.powi(2)) * s.height
    }

    /// Total burning area of the `N` grains, m² (`2πrh` per grain with `only_radial_burn`).
    #[must_use]
    pub fn burn_area(&self, s: GrainState) -> f64 {
        let per_grain = if self.only_radial_burn {
            s.inner_radius * s.height
        } else {
            self.outer_radius.powi(2) - s.inner_radius.powi(2) + s.inner_radius * s.height
        };
        2.0 * std::f64::consts::PI * per_grain * f64::from(self.number)
    }

    /// Klemmung `Kn = A_b / A_t` (burning area over throat area).
    #[must_use]
    pub fn kn(&self, s: GrainState) -> f64 {
        self.burn_area(s) / (std::f64::consts::PI * self.throat_radius.powi(2))
    }

    /// The grain state holding `propellant_mass` kg of propellant (inverse of the regression;
    /// masses above the initial one give the initial state, zero or less the burnt-out one).
    #[inline]
    #[must_use]
    pub fn state_for_mass(&self, propellant_mass: f64) -> GrainState {
        let (ro, r0, h0) = (
            self.outer_radius,
            self.initial_inner_radius,
            self.initial_height,
        );
        let volume = propellant_mass / (f64::from(self.number) * self.density);
        let initial = GrainState {
            inner_radius: r0,
            height: h0,
        };
        if volume >= self.grain_volume(initial) {
            return initial;
        }
        if self.only_radial_burn {
            let r = (ro * ro - volume.max(0.0) / (std::f64::consts::PI * h0))
                .max(0.0)
                .sqrt();
            return GrainState {
                inner_radius: r.min(ro),
                height: h0,
            };
        }
        let state = |r: f64| GrainState {
            inner_radius: r,
            height: h0 - 2.0 * (r - r0),
        };
        let r_end = ro.min(r0 + h0 / 2.0);
        if volume <= 0.0 {
            return state(r_end);
        }
        // Newton's method on the decreasing cubic g(r) = V(r) − V, safeguarded by the bracket
        // [lo, hi] it keeps (a step leaving it bisects instead). Near the root a Newton step s
        // leaves an error of about |g″/(2g′)|·s², so the iteration stops once that is below
        // half an ulp of r, without the confirming step that would only measure rounding
        // noise; a step that rounds to no change at all means the same.
        let excess = |r: f64| self.grain_volume(state(r)) - volume;
        let (mut lo, mut hi) = (r0, r_end);
        let full = self.grain_volume(initial);
        // The bore where the burnt volume fraction would put it if the volume fell linearly:
        // two or three Newton steps away, and independent of the neighbouring grid points'.
        let guess = r0 + (r_end - r0) * (1.0 - volume / full);
        // g′(r) = −2π[r·h(r) + R_o² − r²] and g″(r) = −2π[h(r) − 4r], h(r) = h_0 − 2(r − r_0).
        let derivatives = |r: f64| {
            let h = h0 - 2.0 * (r - r0);
            (
                -2.0 * std::f64::consts::PI * (r * h + (ro * ro - r * r)),
                -2.0 * std::f64::consts::PI * (h - 4.0 * r),
            )
        };
        // The error left by a Newton step `step` taken at `r`, |g″/(2g′)|·step², below half an
        // ulp of `r`.
        let converged = |step: f64, slope: f64, curvature: f64, r: f64| {
            (curvature * step * step).abs() <= (slope * f64::EPSILON * r).abs()
        };
        // The usual case first: three plain Newton steps, without the exits that depend on the
        // data (mispredicted branches kept successive grid points from overlapping), accepted
        // when the last one leaves an error below half an ulp inside the bracket.
        let mut r = guess;
        let mut last = (0.0, 0.0, 0.0);
        for _ in 0..3 {
            let (slope, curvature) = derivatives(r);
            let step = excess(r) / slope;
            r -= step;
            last = (step, slope, curvature);
        }
        let (step, slope, curvature) = last;
        if r > lo && r < hi && converged(step, slope, curvature, r) {
            return state(r);
        }
        let mut r = guess;
        for _ in 0..200 {
            let g = excess(r);
            if g > 0.0 {
                lo = r;
            } else if g < 0.0 {
                hi = r;
            } else {
                break;
            }
            let (slope, curvature) = derivatives(r);
            let step = g / slope;
            let newton = r - step;
            #[allow(clippy::float_cmp)] // a step below half an ulp: r is the root to rounding.
            if newton == r {
                break;
            }
            if newton > lo && newton < hi {
                r = newton;
                if converged(step, slope, curvature, r) {
                    break;
                }
            } else {
                r = 0.5 * (lo + hi);
                if hi - lo <= 4.0 * f64::EPSILON * r {
                    break;
                }
            }
        }
        state(r)
    }

    /// Propellant inertia `(I11_p, I33_p)` about the grain-stack centre, kg·m², for the state
    /// `s` holding `propellant_mass` kg.
    #[must_use]
    pub fn inertia(&self, s: GrainState, propellant_mass: f64) -> (f64, f64) {
        self.inertia_with_spread(s, propellant_mass, self.spread())
    }

    /// `Σ d_i²` over the grain centres, `d_i = (i − (N−1)/2)(h_0 + s_g)`, m²: the
    /// parallel-axis part of `I11_p` per kilogram of one grain. The centres stay where they
    /// are while the grains burn, so the tables compute it once.
    fn spread(&self) -> f64 {
        let pitch = self.initial_height + self.separation;
        let half = (f64::from(self.number) - 1.0) / 2.0;
        (0..self.number)
            .map(|i| ((f64::from(i) - half) * pitch).powi(2))
            .sum()
    }

    /// [`BatesGrains::inertia`] with the grains' [`BatesGrains::spread`] given.
    fn inertia_with_spread(&self, s: GrainState, propellant_mass: f64, spread: f64) -> (f64, f64) {
        let n = f64::from(self.number);
        let grain_mass = propellant_mass / n;
        let (ro2, r2) = (self.outer_radius.powi(2), s.inner_radius.powi(2));
        let one_grain = grain_mass * ((ro2 + r2) / 4.0 + s.height.powi(2) / 12.0);
        (
            n * one_grain + grain_mass * spread,
            0.5 * propellant_mass * (ro2 + r2),
        )
    }
}

impl PropellantModel for BatesGrains {
    fn initial_mass(&self) -> f64 {
        let initial = GrainState {
            inner_radius: self.initial_inner_radius,
            height: self.initial_height,
        };
        f64::from(self.number) * self.density * self.grain_volume(initial)
    }

    fn validate(&self) -> Result<(), PropulsionError> {
        if self.number == 0 {
            return Err(PropulsionError::InvalidParameter {
                name: "grain_number",
                value: 0.0,
                reason: "must be at least 1",
            });
        }
        positive("grain_density", self.density)?;
        positive("grain_outer_radius", self.outer_radius)?;
        non_negative("grain_initial_inner_radius", self.initial_inner_radius)?;
        if self.initial_inner_radius >= self.outer_radius {
            return Err(PropulsionError::InvalidParameter {
                name: "grain_initial_inner_radius",
                value: self.initial_inner_radius,
                reason: "must be smaller than grain_outer_radius",
            });
        }
        positive("grain_initial_height", self.initial_height)?;
        non_negative("grain_separation", self.separation)?;
        finite(
            "grains_center_of_mass_position",
            self.center_of_mass_position,
        )?;
        positive("throat_radius", self.throat_radius)
    }

    fn tables(
        &self,
        thrust: &ThrustCurve,
        exhaust_velocity: f64,
        constants: &PhysicalConstants,
    ) -> Result<PropellantTables, PropulsionError> {
        let m0 = self.initial_mass();
        let curve = thrust.table();
        // The grid advances through the thrust curve, so its intervals are found from the
        // previous one's.
        let mut cursor = Cursor::default();
        let burnt = |a: f64, b: f64| -curve.integral_with(a, b, &mut cursor) / exhaust_velocity;
        let (times, masses) = regress(&grain_grid(curve, constants), m0, burnt);
        let mut i11 = Vec::with_capacity(times.len());
        let mut i33 = Vec::with_capacity(times.len());
        let spread = self.spread();
        for &m in &masses {
            let state = self.state_for_mass(m);
            let (a, c) = self.inertia_with_spread(state, m, spread);
            i11.push(a);
            i33.push(c);
        }
        let com = vec![self.center_of_mass_position; times.len()];
        let (lin, hold) = (Interpolation::Linear, Extrapolation::Constant);
        let mass = Table1::new(times, masses, lin, hold)
            .map_err(PropulsionError::table("propellant mass"))?;
        // The other quantities share the mass table's time grid.
        let table = |what, ys| {
            Table1::on_same_abscissae(&mass, ys, lin, hold).map_err(PropulsionError::table(what))
        };
        Ok(PropellantTables {
            center_of_mass: table("propellant centre of mass", com)?,
            i11: table("propellant I11", i11)?,
            i33: table("propellant I33", i33)?,
            mass,
            parts: Vec::new(),
        })
    }
}

/// The time grid of a grain's tables (strictly increasing): the thrust-curve nodes, each
/// once, every interval split into equal pieces of at most [`PhysicalConstants::propellant_grid_step`] (longer for very long burns).
pub(crate) fn grain_grid(curve: &Table1, constants: &PhysicalConstants) -> Vec<f64> {
    let nodes = curve.xs();
    let (start, end) = curve.domain();
    let step = constants
        .propellant_grid_step
        .max((end - start) / MAX_GRID_POINTS);
    // An interval that is a whole number of steps up to rounding gets that number of
    // pieces: the count must not depend on the rounding of (b − a)/step, which differs
    // between unit systems (found by the dimensional-analysis tests).
    let pieces_of =
        |a: f64, b: f64| ((b - a) / step * (1.0 - PIECE_ROUNDING)).ceil().max(1.0) as usize;
    let mut times = vec![nodes[0]];
    for pair in nodes.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        // A repeated time is a step of the thrust (`ThrustData`): the mass is continuous
        // there and the grid holds the instant once.
        if b <= a {
            continue;
        }
        let pieces = pieces_of(a, b);
        times.extend((1..pieces).map(|k| a + (b - a) * k as f64 / pieces as f64));
        times.push(b);
    }
    times
}

/// The grain mass at the nodes of `grid` from `m0` and the mass change `flow(a, b)` over each
/// interval, up to the instant the grain is consumed (found by bisection inside its interval;
/// the returned times stop there).
pub(crate) fn regress(
    grid: &[f64],
    m0: f64,
    mut flow: impl FnMut(f64, f64) -> f64,
) -> (Vec<f64>, Vec<f64>) {
    let mut times = Vec::with_capacity(grid.len());
    let mut masses = Vec::with_capacity(grid.len());
    times.push(grid[0]);
    masses.push(m0);
    for &t in &grid[1..] {
        let (t_prev, m_prev) = (times[times.len() - 1], masses[masses.len() - 1]);
        let m = m_prev + flow(t_prev, t);
        // Since v̄_e = I_tot/m_p0 the mass reaches 0 exactly at the end of a non-negative
        // curve, and the sum above lands within rounding of it on either side; only a clearly
        // negative mass means the grain is gone before the end (a negative tail). Otherwise a
        // thrust tapering to 0 would place a spurious burn-out a few 1e-8 of the burn early,
        // wherever the rounding falls (found by the dimensional-analysis tests: it differed
        // between unit systems).
        if m > -MASS_ROUNDING * m0 {
            times.push(t);
            masses.push(m.max(0.0));
            continue;
        }
        // Grain consumed inside (t_prev, t]: find the instant and stop there.
        let (mut lo, mut hi) = (t_prev, t);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if m_prev + flow(t_prev, mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        times.push(hi);
        masses.push(0.0);
        break;
    }
    (times, masses)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_of_the_thrust_is_one_instant_of_the_grain_grid() {
        let curve = Table1::linear_stepwise(
            vec![0.0, 0.5, 0.5, 2.0],
            vec![0.0, 500.0, 900.0, 0.0],
            Extrapolation::Zero,
        )
        .expect("a step");
        let grid = grain_grid(&curve, &PhysicalConstants::default());
        assert!(grid.windows(2).all(|w| w[0] < w[1]), "{grid:?}");
        assert_eq!(grid.iter().filter(|&&t| (t - 0.5).abs() < 1e-15).count(), 1);
        let (times, masses) = regress(&grid, 1.0, |a, b| curve.integral(a, b) / 2000.0);
        assert_eq!(times.len(), masses.len());
        Table1::new(
            times,
            masses,
            Interpolation::Linear,
            Extrapolation::Constant,
        )
        .expect("the mass table of a stepped curve");
    }

    fn calisto() -> BatesGrains {
        BatesGrains {
            number: 5,
            density: 1815.0,
            outer_radius: 0.033,
            initial_inner_radius: 0.015,
            initial_height: 0.12,
            separation: 0.005,
            center_of_mass_position: 0.397,
            throat_radius: 0.011,
            only_radial_burn: false,
        }
    }

    #[test]
    fn regression_inverts_volume_exactly() {
        let g = calisto();
        let m0 = g.initial_mass();
        // docs/physics.md §6.4: Calisto m_p0 = 2.955912 kg.
        assert!((m0 - 2.955_912).abs() < 5e-7, "{m0}");
        let fractions = (0..=400)
            .map(|k| f64::from(k) / 400.0)
            .chain([1e-6, 1e-12, 1.0 - 1e-12]);
        for frac in fractions {
            let s = g.state_for_mass(frac * m0);
            let back = 5.0 * 1815.0 * g.grain_volume(s);
            // The root to rounding: the volume of the cubic near its root, ~1e-16 relative.
            assert!((back - frac * m0).abs() <= 1e-14 * m0, "{frac}: {back}");
            // ḣ = −2ṙ ⇒ h − h0 = −2 (r − r0)
            assert!(((s.height - 0.12) + 2.0 * (s.inner_radius - 0.015)).abs() < 1e-15);
        }
        let radial = BatesGrains {
            only_radial_burn: true,
            ..calisto()
        };
        let s = radial.state_for_mass(0.5 * m0);
        assert!((s.height - 0.12).abs() < 1e-15);
        assert!((5.0 * 1815.0 * radial.grain_volume(s) - 0.5 * m0).abs() < 1e-12);
    }

    #[test]
    fn roots_of_unusual_grains_are_exact_too() {
        // Far from Calisto's proportions the linear-fraction guess is poor near the ends and
        // three Newton steps do not always suffice: the safeguarded iteration takes over.
        let grains = [
            BatesGrains {
                outer_radius: 0.05,
                initial_inner_radius: 0.001,
                initial_height: 0.3,
                ..calisto()
            },
            BatesGrains {
                outer_radius: 0.2,
                initial_inner_radius: 0.19,
                initial_height: 0.01,
                ..calisto()
            },
        ];
        for g in grains {
            let m0 = g.initial_mass();
            for k in 0..=1000 {
                let frac = (f64::from(k) / 1000.0).powi(3);
                let s = g.state_for_mass(frac * m0);
                let back = 5.0 * 1815.0 * g.grain_volume(s);
                assert!((back - frac * m0).abs() <= 1e-13 * m0, "{frac}: {back}");
            }
        }
    }

    #[test]
    fn inertia_matches_hand_formula_for_one_grain() {
        let g = BatesGrains {
            number: 1,
            ..calisto()
        };
        let s = GrainState {
            inner_radius: 0.02,
            height: 0.1,
        };
        let (i11, i33) = g.inertia(s, 2.0);
        let r2 = 0.033f64.powi(2) + 0.02f64.powi(2);
        assert!((i11 - 2.0 * (r2 / 4.0 + 0.01 / 12.0)).abs() < 1e-15);
        assert!((i33 - r2).abs() < 1e-15);
        assert!(
            g.spread().abs() < 1e-300,
            "one grain sits at the stack centre"
        );
    }

    #[test]
    fn spread_sums_the_squared_grain_offsets() {
        // Five grains spaced h0 + s_g = 0.125 m: offsets −2..2 pitches, Σ i² = 10.
        let g = calisto();
        assert!((g.spread() - 10.0 * 0.125f64.powi(2)).abs() < 1e-16);
        // Four grains: offsets ±0.5 and ±1.5 pitches, Σ = 5 pitches².
        let g = BatesGrains {
            number: 4,
            ..calisto()
        };
        assert!((g.spread() - 5.0 * 0.125f64.powi(2)).abs() < 1e-16);
        let s = GrainState {
            inner_radius: 0.02,
            height: 0.1,
        };
        let (with, without) = (g.inertia_with_spread(s, 2.0, g.spread()), g.inertia(s, 2.0));
        assert_eq!(with.0.to_bits(), without.0.to_bits());
        assert_eq!(with.1.to_bits(), without.1.to_bits());
    }

    #[test]
    fn tables_follow_the_impulse_and_stop_when_the_grain_is_gone() {
        use crate::{ThrustData, ThrustFormat, ThrustOptions, ThrustSource};
        // 95 N·s in total, with a negative tail: the grain is consumed when ∫T dt = 95 N·s,
        // at t = 1 + u with 50u² − 100u + 45 = 0, u = 1 − √0.1.
        let data = ThrustData {
            source_name: "test".into(),
            format: ThrustFormat::Inline,
            times: vec![0.0, 1.0, 2.0, 2.5],
            thrusts: vec![0.0, 100.0, 0.0, -20.0],
            header: None,
            warnings: Vec::new(),
        };
        let curve = ThrustCurve::new(
            &ThrustSource::Data(Box::new(data)),
            &ThrustOptions::default(),
        )
        .unwrap();
        let g = calisto();
        let m0 = g.initial_mass();
        let ve = curve.total_impulse() / m0;
        let tables = g.tables(&curve, ve, &PhysicalConstants::SI).unwrap();
        let (_, end) = tables.mass.domain();
        assert!(
            (end - (2.0 - 0.1f64.sqrt())).abs() < 1e-12,
            "burn-out at {end}"
        );
        assert!(tables.mass.eval(end).abs() < 1e-300 && tables.mass.eval(2.4).abs() < 1e-300);
        assert!(
            tables
                .mass
                .xs()
                .windows(2)
                .all(|w| w[1] - w[0] <= PhysicalConstants::SI.propellant_grid_step + 1e-12)
        );
        // m_p(0.5) = m0 − (½·0.5·50 N·s)/v̄_e, exact at a grid node.
        assert!((tables.mass.eval(0.5) - (m0 - 12.5 / ve)).abs() < 1e-12 * m0);
        assert!(tables.mass.ys().windows(2).all(|w| w[1] <= w[0]));
    }

    #[test]
    fn rejects_bad_geometry() {
        let g = BatesGrains {
            initial_inner_radius: 0.04,
            ..calisto()
        };
        assert!(matches!(
            g.validate(),
            Err(PropulsionError::InvalidParameter {
                name: "grain_initial_inner_radius",
                ..
            })
        ));
        let g = BatesGrains {
            density: f64::NAN,
            ..calisto()
        };
        assert!(g.validate().is_err());
        assert!(calisto().validate().is_ok());
    }
}
