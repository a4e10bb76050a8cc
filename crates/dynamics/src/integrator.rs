//! Adaptive Dormand–Prince 5(4) integrator with dense output.
//!
//! The method is the embedded Runge–Kutta pair RK5(4)7M of Dormand & Prince (1980), *A family
//! of embedded Runge–Kutta formulae*, J. Comput. Appl. Math. 6(1), 19–26, propagated with the
//! fifth-order solution (local extrapolation) and the FSAL property, as in Hairer, Nørsett &
//! Wanner, *Solving Ordinary Differential Equations I* (2nd ed., 1993), §II.5 (Table 5.2). Its
//! continuous extension is the fourth-order dense output of the same book, §II.6 (the `d_i`
//! coefficients of the DOPRI5 code, eq. 6.12 ff.).
//!
//! Step-size control uses the scaled **max** norm `max_i |err_i| / (atol_i + rtol·max(|y_i|,
//! |ŷ_i|))`, the norm of ODEPACK's LSODA (`vmnorm`, Hindmarsh 1983; Petzold 1983), which
//! RocketPy integrates with: the RMS norm of SciPy's `RK45` dilutes a velocity error over the
//! thirteen components and lets steps grow past what LSODA accepts (Calisto: 16 % fewer steps,
//! but maxima sampled at the stored points drift by up to 0.16 %). The controller is
//! `h ← h · min(10, max(0.2, 0.9 · err^(−1/5)))` (no growth right after a rejection) and the
//! initial step comes from the algorithm of HNW I, §II.4 ("Starting step size"), as in SciPy.
//!
//! The state is a fixed `[f64; N]`; the seven stages live inside the integrator, so a step
//! never allocates.

// Index loops over several parallel fixed-size arrays read closer to the formulas.
#![allow(clippy::needless_range_loop)]

use crate::DynamicsError;

/// Nodes `c_i` of the Dormand–Prince 5(4) tableau (HNW I, Table 5.2).
const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];

/// Lower-triangular coupling coefficients `a_ij` (HNW I, Table 5.2); row 6 holds the
/// fifth-order weights `b_i` (FSAL: the seventh stage is `f(t + h, y_new)`).
const A: [[f64; 6]; 7] = [
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];

/// Error weights `e_i = b_i − b̂_i` (fifth minus fourth order), HNW I, Table 5.2 / DOPRI5.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

/// Dense-output coefficients `d_i` of DOPRI5 (HNW I, §II.6, Dormand & Prince's continuous
/// extension of order 4).
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// Safety factor of the step-size controller.
const SAFETY: f64 = 0.9;
/// Smallest step-size reduction factor after a rejected step.
const MIN_FACTOR: f64 = 0.2;
/// Largest step-size growth factor after an accepted step.
const MAX_FACTOR: f64 = 10.0;
/// Exponent of the controller, `−1/(q+1)` with the error-estimator order `q = 4`.
const ERROR_EXPONENT: f64 = -1.0 / 5.0;

/// Tolerances and limits of the integrator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerances<const N: usize> {
    /// Relative tolerance (scalar).
    pub rtol: f64,
    /// Absolute tolerance per state component.
    pub atol: [f64; N],
    /// Largest step, s (`f64::INFINITY` for none).
    pub max_step: f64,
    /// Smallest step, s, before the integrator gives up. The effective floor is
    /// `max(min_step, 10 ε |t|)`.
    pub min_step: f64,
    /// Largest number of accepted plus rejected steps in one integration (one phase).
    pub max_steps: usize,
}

/// Result of one [`DormandPrince::step`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepStatus {
    /// A step was accepted; more remain before the time bound.
    Running,
    /// The accepted step reached the time bound.
    Finished,
}

/// The integrator: current point, last step's stages (for the dense output) and counters.
#[derive(Debug, Clone)]
pub struct DormandPrince<const N: usize> {
    tol: Tolerances<N>,
    t: f64,
    y: [f64; N],
    f: [f64; N],
    t_old: f64,
    y_old: [f64; N],
    h_last: f64,
    h: f64,
    t_bound: f64,
    stop: f64,
    k: [[f64; N]; 7],
    steps: usize,
    rejected: usize,
    nfev: usize,
}

/// Scaled RMS norm `sqrt(Σ (v_i/s_i)² / N)`.
#[inline]
fn rms_norm<const N: usize>(v: &[f64; N], scale: &[f64; N]) -> f64 {
    let mut sum = 0.0;
    for i in 0..N {
        let r = v[i] / scale[i];
        sum += r * r;
    }
    (sum / N as f64).sqrt()
}

impl<const N: usize> DormandPrince<N> {
    /// Starts an integration of `y' = f(t, y)` at `(t0, y0)` towards `t_bound > t0`.
    ///
    /// Evaluates `f(t0, y0)` and selects the first step (HNW I, §II.4), capped by
    /// `tol.max_step` and the interval length.
    ///
    /// # Errors
    /// [`DynamicsError::NonFinite`] when the initial state or derivative is not finite.
    pub fn new<F>(
        f: &mut F,
        t0: f64,
        y0: [f64; N],
        t_bound: f64,
        tol: Tolerances<N>,
    ) -> Result<Self, DynamicsError>
    where
        F: FnMut(f64, &[f64; N]) -> [f64; N],
    {
        let f0 = f(t0, &y0);
        if y0.iter().chain(f0.iter()).any(|v| !v.is_finite()) {
            return Err(DynamicsError::NonFinite { t: t0 });
        }
        let mut integ = Self {
            tol,
            t: t0,
            y: y0,
            f: f0,
            t_old: t0,
            y_old: y0,
            h_last: 0.0,
            h: 0.0,
            t_bound,
            stop: f64::INFINITY,
            k: [[0.0; N]; 7],
            steps: 0,
            rejected: 0,
            nfev: 1,
        };
        integ.h = integ.initial_step(f);
        Ok(integ)
    }

    /// Initial step of HNW I, §II.4 for a method of order 5 (as SciPy's `select_initial_step`),
    /// in a dimensionally consistent form: with the tolerance-weighted norms `d0 = ‖y‖`,
    /// `d1 = ‖f‖` (1/time) and `d2 ≈ ‖f′‖` (1/time²), "negligible" is judged over the
    /// interval `T = t_bound − t`, the fall-back steps are fractions of `T`, and the fifth
    /// derivative (the order of the error estimator, as SciPy) is estimated as `d2·ω³` with
    /// the rate `ω = d2/d1` (`√d2` when `d1` is negligible), so the step follows the unit of
    /// time (dimensional-analysis tests).
    fn initial_step<F>(&mut self, f: &mut F) -> f64
    where
        F: FnMut(f64, &[f64; N]) -> [f64; N],
    {
        let interval = self.t_bound - self.t;
        if interval <= 0.0 {
            return 0.0;
        }
        let mut scale = [0.0; N];
        for i in 0..N {
            scale[i] = self.tol.atol[i] + self.y[i].abs() * self.tol.rtol;
        }
        let d0 = rms_norm(&self.y, &scale);
        let d1 = rms_norm(&self.f, &scale);
        let negligible_rate = d1 * interval < 1e-5;
        let h0 = if d0 < 1e-5 || negligible_rate {
            1e-6 * interval
        } else {
            0.01 * d0 / d1
        };
        let h0 = h0.min(interval);
        let mut y1 = [0.0; N];
        for i in 0..N {
            y1[i] = self.y[i] + h0 * self.f[i];
        }
        let f1 = f(self.t + h0, &y1);
        self.nfev += 1;
        let mut diff = [0.0; N];
        for i in 0..N {
            diff[i] = f1[i] - self.f[i];
        }
        let d2 = rms_norm(&diff, &scale) / h0;
        let h1 = if negligible_rate && d2 * interval * interval <= 1e-15 {
            (h0 * 1e-3).max(1e-6 * interval)
        } else {
            let rate = if negligible_rate { d2.sqrt() } else { d2 / d1 };
            (0.01 / (d2 * rate.powi(3))).powf(1.0 / 5.0)
        };
        let h = (100.0 * h0).min(h1).min(self.tol.max_step).min(interval);
        if h.is_finite() && h > 0.0 {
            h
        } else {
            interval.min(self.tol.max_step)
        }
    }

    /// Sets a stop time: steps end exactly there (without restarting) so that no step
    /// straddles a kink of the right-hand side (e.g. a thrust-curve knot). A stop at or
    /// before the current time, or past the bound, has no effect.
    pub fn set_stop(&mut self, t_stop: f64) {
        self.stop = t_stop;
    }

    /// Current time.
    #[inline]
    #[must_use]
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Current state.
    #[inline]
    #[must_use]
    pub fn y(&self) -> &[f64; N] {
        &self.y
    }

    /// Derivative at the current point (FSAL stage).
    #[inline]
    #[must_use]
    pub fn f(&self) -> &[f64; N] {
        &self.f
    }

    /// Start time of the last accepted step.
    #[inline]
    #[must_use]
    pub fn t_old(&self) -> f64 {
        self.t_old
    }

    /// State at the start of the last accepted step.
    #[inline]
    #[must_use]
    pub fn y_old(&self) -> &[f64; N] {
        &self.y_old
    }

    /// Length of the last accepted step.
    #[inline]
    #[must_use]
    pub fn last_step(&self) -> f64 {
        self.h_last
    }

    /// Accepted steps so far.
    #[inline]
    #[must_use]
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// Rejected steps so far.
    #[inline]
    #[must_use]
    pub fn rejected_steps(&self) -> usize {
        self.rejected
    }

    /// Right-hand-side evaluations so far.
    #[inline]
    #[must_use]
    pub fn evaluations(&self) -> usize {
        self.nfev
    }

    /// Takes one accepted step (retrying with smaller steps after rejections), never past
    /// the time bound.
    ///
    /// # Errors
    /// [`DynamicsError::StepTooSmall`] when the step falls below the minimum,
    /// [`DynamicsError::TooManySteps`] past `max_steps`, [`DynamicsError::NonFinite`] when the
    /// derivative is not finite even at the minimum step.
    pub fn step<F>(&mut self, f: &mut F) -> Result<StepStatus, DynamicsError>
    where
        F: FnMut(f64, &[f64; N]) -> [f64; N],
    {
        let t = self.t;
        let min_step = self.tol.min_step.max(10.0 * f64::EPSILON * t.abs());
        let mut h = self.h.min(self.tol.max_step).max(min_step);
        let mut step_rejected = false;
        loop {
            if self.steps + self.rejected >= self.tol.max_steps {
                return Err(DynamicsError::TooManySteps {
                    t,
                    steps: self.steps + self.rejected,
                });
            }
            if h < min_step {
                return Err(DynamicsError::StepTooSmall { t, step: h });
            }
            let t_end = if self.stop > t {
                self.t_bound.min(self.stop)
            } else {
                self.t_bound
            };
            let truncated = t + h >= t_end;
            let t_new = if truncated { t_end } else { t + h };
            let h_eff = t_new - t;
            let y_new = self.stages(f, h_eff, t_new);
            let finite = y_new.iter().chain(self.k[6].iter()).all(|v| v.is_finite());
            let error_norm = if finite {
                self.error_norm(h_eff, &y_new)
            } else {
                f64::INFINITY
            };
            if error_norm < 1.0 {
                let factor = if error_norm <= 0.0 {
                    MAX_FACTOR
                } else {
                    (SAFETY * error_norm.powf(ERROR_EXPONENT)).min(MAX_FACTOR)
                };
                let factor = if step_rejected {
                    factor.min(1.0)
                } else {
                    factor
                };
                // A step cut short at a stop says nothing against the longer proposal.
                self.h = if truncated {
                    h.max(h_eff * factor)
                } else {
                    h_eff * factor
                };
                self.t_old = t;
                self.y_old = self.y;
                self.t = t_new;
                self.y = y_new;
                self.f = self.k[6];
                self.h_last = h_eff;
                self.steps += 1;
                return Ok(if t_new >= self.t_bound {
                    StepStatus::Finished
                } else {
                    StepStatus::Running
                });
            }
            self.rejected += 1;
            step_rejected = true;
            if !finite && h_eff <= min_step {
                return Err(DynamicsError::NonFinite { t });
            }
            let factor = if finite {
                (SAFETY * error_norm.powf(ERROR_EXPONENT)).max(MIN_FACTOR)
            } else {
                MIN_FACTOR
            };
            h = h_eff * factor;
        }
    }

    /// Evaluates the seven stages for a step `h` from the current point to `t_new`; returns
    /// `y_new` and leaves `f(t_new, y_new)` in `k[6]`. The last stage is taken at `t_new`
    /// itself, not at `t + h` (which may differ from it in the last bit), so the FSAL
    /// derivative is the derivative at the stored point: a step ending on a stop (burn-out)
    /// sees the equations that hold there, and callers may use it as the point's derivative.
    #[inline]
    fn stages<F>(&mut self, f: &mut F, h: f64, t_new: f64) -> [f64; N]
    where
        F: FnMut(f64, &[f64; N]) -> [f64; N],
    {
        self.k[0] = self.f;
        let mut y_stage = [0.0; N];
        for s in 1..7 {
            // Stage-major loops (vectorised over the components); each component still sums
            // its terms in stage order, so the result is the same to the bit. A zero
            // coefficient (a_62) adds nothing to a finite sum and is skipped.
            let mut acc = [0.0; N];
            for (a, k) in A[s].iter().zip(&self.k).take(s) {
                if *a != 0.0 {
                    for (acc, k) in acc.iter_mut().zip(k) {
                        *acc += a * k;
                    }
                }
            }
            for i in 0..N {
                y_stage[i] = self.y[i] + h * acc[i];
            }
            let t_stage = if s == 6 { t_new } else { self.t + C[s] * h };
            self.k[s] = f(t_stage, &y_stage);
            self.nfev += 1;
        }
        // Row 6 of A holds b, so the last stage point is the fifth-order solution.
        y_stage
    }

    /// Scaled max norm of the embedded error estimate, in one pass over the components (the
    /// zero weight `e_2` skipped as in [`DormandPrince::stages`]).
    #[inline]
    fn error_norm(&self, h: f64, y_new: &[f64; N]) -> f64 {
        let mut acc = [0.0; N];
        for (e, k) in E.iter().zip(&self.k) {
            if *e != 0.0 {
                for (acc, k) in acc.iter_mut().zip(k) {
                    *acc += e * k;
                }
            }
        }
        let mut m: f64 = 0.0;
        for i in 0..N {
            let scale = self.tol.atol[i] + self.y[i].abs().max(y_new[i].abs()) * self.tol.rtol;
            m = m.max((h * acc[i] / scale).abs());
        }
        m
    }

    /// Dense output of the last accepted step at `t` (`t_old ≤ t ≤ t`; extrapolates
    /// outside), fourth order (HNW I, §II.6).
    #[must_use]
    pub fn dense(&self, t: f64) -> [f64; N] {
        let mut out = [0.0; N];
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.dense_component(t, i);
        }
        out
    }

    /// One component of [`DormandPrince::dense`].
    #[inline]
    #[must_use]
    pub fn dense_component(&self, t: f64, i: usize) -> f64 {
        let h = self.h_last;
        if h <= 0.0 {
            return self.y[i];
        }
        let theta = (t - self.t_old) / h;
        let theta1 = 1.0 - theta;
        let y0 = self.y_old[i];
        let ydiff = self.y[i] - y0;
        let bspl = h * self.k[0][i] - ydiff;
        let r4 = ydiff - h * self.k[6][i] - bspl;
        let mut acc = 0.0;
        for (j, d) in D.iter().enumerate() {
            acc += d * self.k[j][i];
        }
        let r5 = h * acc;
        y0 + theta * (ydiff + theta1 * (bspl + theta * (r4 + theta1 * r5)))
    }

    /// Derivative at the start of the last accepted step.
    #[inline]
    #[must_use]
    pub fn f_old(&self) -> &[f64; N] {
        &self.k[0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tol<const N: usize>(rtol: f64, atol: f64) -> Tolerances<N> {
        Tolerances {
            rtol,
            atol: [atol; N],
            max_step: f64::INFINITY,
            min_step: 0.0,
            max_steps: 100_000,
        }
    }

    #[test]
    fn tableau_rows_sum_to_nodes() {
        // Consistency condition Σ_j a_ij = c_i of every explicit RK tableau (HNW I, eq. 1.9).
        for s in 1..6 {
            let sum: f64 = A[s].iter().sum();
            assert!((sum - C[s]).abs() < 1e-15, "row {s}: {sum} vs {}", C[s]);
        }
        // The fifth-order weights sum to 1 and the error weights to 0.
        assert!((A[6].iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert!(E.iter().sum::<f64>().abs() < 1e-15);
    }

    #[test]
    fn exponential_decay_matches_closed_form() {
        let mut f = |_t: f64, y: &[f64; 1]| [-y[0]];
        let mut dp = DormandPrince::new(&mut f, 0.0, [1.0], 5.0, tol(1e-9, 1e-12)).unwrap();
        while dp.step(&mut f).unwrap() == StepStatus::Running {}
        assert!((dp.t() - 5.0).abs() < 1e-15);
        let exact = (-5.0f64).exp();
        assert!(
            (dp.y()[0] - exact).abs() / exact < 1e-7,
            "{} vs {exact}",
            dp.y()[0]
        );
    }

    #[test]
    fn harmonic_oscillator_dense_output_is_accurate() {
        // y'' = −y: dense output inside steps must match sin/cos to the tolerance level.
        let mut f = |_t: f64, y: &[f64; 2]| [y[1], -y[0]];
        let mut dp = DormandPrince::new(&mut f, 0.0, [0.0, 1.0], 10.0, tol(1e-8, 1e-10)).unwrap();
        let mut worst: f64 = 0.0;
        loop {
            let status = dp.step(&mut f).unwrap();
            for k in 1..4 {
                let t = dp.t_old() + dp.last_step() * f64::from(k) / 4.0;
                let y = dp.dense(t);
                worst = worst
                    .max((y[0] - t.sin()).abs())
                    .max((y[1] - t.cos()).abs());
            }
            if status == StepStatus::Finished {
                break;
            }
        }
        assert!(worst < 1e-6, "dense output error {worst}");
        // Dense output reproduces both step ends exactly.
        let y_end = dp.dense(dp.t());
        assert!((y_end[0] - dp.y()[0]).abs() < 1e-14);
    }

    #[test]
    fn zero_derivative_start_grows_steps_geometrically() {
        // physics.md §10.4: a zero derivative gives a zero error estimate; the controller grows
        // the step by MAX_FACTOR per step, which the max_step cap must bound.
        let mut f = |_t: f64, _y: &[f64; 1]| [0.0];
        let mut t = tol::<1>(1e-6, 1e-3);
        t.max_step = 0.01;
        let mut dp = DormandPrince::new(&mut f, 0.0, [0.0], 1.0, t).unwrap();
        let mut largest: f64 = 0.0;
        while dp.step(&mut f).unwrap() == StepStatus::Running {
            largest = largest.max(dp.last_step());
        }
        assert!(largest <= 0.01 + 1e-15);
    }

    #[test]
    fn blow_up_ends_with_an_error_not_a_hang() {
        // y' = y², y(0) = 1 blows up at t = 1; integrating to 2 must fail in bounded steps.
        let mut f = |_t: f64, y: &[f64; 1]| [y[0] * y[0]];
        let mut dp = DormandPrince::new(&mut f, 0.0, [1.0], 2.0, tol(1e-6, 1e-6)).unwrap();
        let result = loop {
            match dp.step(&mut f) {
                Ok(StepStatus::Running) => {}
                Ok(StepStatus::Finished) => break Ok(()),
                Err(e) => break Err(e),
            }
        };
        assert!(result.is_err(), "integration past a singularity must fail");
    }

    #[test]
    fn step_budget_is_enforced() {
        let mut f = |_t: f64, y: &[f64; 2]| [y[1], -1e6 * y[0]];
        let mut t = tol::<2>(1e-10, 1e-12);
        t.max_steps = 50;
        let mut dp = DormandPrince::new(&mut f, 0.0, [1.0, 0.0], 100.0, t).unwrap();
        let err = loop {
            match dp.step(&mut f) {
                Ok(StepStatus::Running) => {}
                Ok(StepStatus::Finished) => panic!("cannot finish in 50 steps"),
                Err(e) => break e,
            }
        };
        assert!(matches!(err, DynamicsError::TooManySteps { .. }));
    }
}
