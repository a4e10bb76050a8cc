//! Starting an integration and one adaptive step: stages, error norm, step-size control
//! (HNW I, §II.4).

#![allow(clippy::needless_range_loop)]

use super::*;
use crate::DynamicsError;

impl<const N: usize, F> RungeKutta<N, F>
where
    F: FnMut(f64, &[f64; N]) -> [f64; N],
{
    /// Starts an integration of `y' = rhs(t, y)` with `pair` at `(t0, y0)` towards
    /// `t_bound > t0`.
    ///
    /// Evaluates `rhs(t0, y0)` and selects the first step (HNW I, §II.4), capped by
    /// `tol.max_step` and the interval length.
    ///
    /// # Errors
    /// [`DynamicsError::NonFinite`] when the initial state or derivative is not finite.
    pub fn new(
        pair: Pair,
        mut rhs: F,
        t0: f64,
        y0: [f64; N],
        t_bound: f64,
        tol: Tolerances<N>,
    ) -> Result<Self, DynamicsError> {
        let f0 = rhs(t0, &y0);
        if y0.iter().chain(f0.iter()).any(|v| !v.is_finite()) {
            return Err(DynamicsError::NonFinite { t: t0 });
        }
        let mut integ = Self {
            pair,
            rhs,
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
            k: [[0.0; N]; SLOTS],
            rows: [[0.0; N]; 7],
            rows_made: false,
            radius: f64::NAN,
            radius_age: 0,
            eigen: [0.0; N],
            steps: 0,
            rejected: 0,
            nfev: 1,
        };
        integ.h = integ.initial_step();
        Ok(integ)
    }

    /// Initial step of HNW I, §II.4 (as SciPy's `select_initial_step`) for an error estimate
    /// of order `q`, in a dimensionally consistent form: with the tolerance-weighted norms
    /// `d0 = ‖y‖`, `d1 = ‖f‖` (1/time) and `d2 ≈ ‖f′‖` (1/time²), "negligible" is judged over
    /// the interval `T = t_bound − t`, the fall-back steps are fractions of `T`, and the
    /// `(q+1)`-th derivative is estimated as `d2·ω^(q−1)` with the rate `ω = d2/d1` (`√d2` when
    /// `d1` is negligible), so the step follows the unit of time (dimensional-analysis tests).
    pub(super) fn initial_step(&mut self) -> f64 {
        let interval = self.t_bound - self.t;
        if interval <= 0.0 {
            return 0.0;
        }
        let scale = self.tolerance_scale(&self.y);
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
        let f1 = (self.rhs)(self.t + h0, &y1);
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
            let q = self.pair.error_order();
            (0.01 / (d2 * rate.powi(q - 1))).powf(1.0 / f64::from(q + 1))
        };
        let h = (100.0 * h0).min(h1).min(self.tol.max_step).min(interval);
        if h.is_finite() && h > 0.0 {
            h
        } else {
            interval.min(self.tol.max_step)
        }
    }

    /// Takes one accepted step (retrying with smaller steps after rejections), never past
    /// the time bound.
    ///
    /// # Errors
    /// [`DynamicsError::StepTooSmall`] when the step falls below the minimum,
    /// [`DynamicsError::TooManySteps`] past `max_steps`, [`DynamicsError::NonFinite`] when the
    /// derivative is not finite even at the minimum step.
    pub fn step(&mut self) -> Result<StepStatus, DynamicsError> {
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
            if self.pair == Pair::Rkc2 {
                if self.radius.is_nan()
                    || self.radius_age >= rkc::REESTIMATE_AFTER
                    || (step_rejected && self.radius_age > 0)
                {
                    self.estimate_radius();
                }
                h = h.min(self.chebyshev_step_limit());
            }
            if h < min_step {
                return Err(DynamicsError::StepTooSmall { t, step: h });
            }
            // A stop closer than the smallest step (the round-off of a sum of steps that was
            // meant to land on it) is treated as reached.
            let t_end = if self.stop - t > min_step {
                self.t_bound.min(self.stop)
            } else {
                self.t_bound
            };
            let truncated = t + h >= t_end;
            let t_new = if truncated { t_end } else { t + h };
            let h_eff = t_new - t;
            let y_new = self.stages(h_eff, t_new);
            let last = self.pair.last();
            let finite = y_new
                .iter()
                .chain(self.k[last].iter())
                .all(|v| v.is_finite());
            let error_norm = if finite {
                self.error_norm(h_eff, &y_new)
            } else {
                f64::INFINITY
            };
            if error_norm < 1.0 {
                let factor = if error_norm <= 0.0 {
                    MAX_FACTOR
                } else {
                    (SAFETY * error_norm.powf(self.pair.error_exponent())).min(MAX_FACTOR)
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
                self.f = self.k[last];
                self.h_last = h_eff;
                self.rows_made = false;
                self.steps += 1;
                self.radius_age += 1;
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
                (SAFETY * error_norm.powf(self.pair.error_exponent())).max(MIN_FACTOR)
            } else {
                MIN_FACTOR
            };
            h = h_eff * factor;
        }
    }

    /// Evaluates the stages of a step `h` from the current point to `t_new`; returns `y_new`
    /// and leaves `f(t_new, y_new)` in slot [`Pair::last`]. The last evaluation is taken at
    /// `t_new` itself, not at `t + h` (which may differ from it in the last bit), so the reused
    /// derivative is the derivative at the stored point: a step ending on a stop (burn-out)
    /// sees the equations that hold there, and callers may use it as the point's derivative.
    #[inline]
    pub(super) fn stages(&mut self, h: f64, t_new: f64) -> [f64; N] {
        self.k[0] = self.f;
        // The stages are written out one by one so that each sees its row of coefficients as
        // constants: the zero entries drop out at compile time and the sums unroll.
        macro_rules! stages {
            ($tableau:ident, [$($s:literal),*]) => {{
                $(
                    self.stage($s, &$tableau::A[$s][..$s], h, self.t + $tableau::C[$s] * h);
                )*
            }};
        }
        match self.pair {
            Pair::Dopri5 => {
                stages!(dopri5, [1, 2, 3, 4, 5]);
                self.nfev += 6;
                // Row 6 of A holds b, so the last stage point is the fifth-order solution.
                self.stage(6, &dopri5::A[6][..6], h, t_new)
            }
            Pair::Dop853 => {
                let stages = dop853::STAGES;
                stages!(dop853, [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]);
                self.stage(11, &dop853::A[11][..11], h, t_new);
                let acc = combine(&dop853::B, &self.k[..stages]);
                let mut y_new = [0.0; N];
                for i in 0..N {
                    y_new[i] = self.y[i] + h * acc[i];
                }
                self.k[stages] = (self.rhs)(t_new, &y_new);
                self.nfev += stages;
                y_new
            }
            Pair::Rkc2 => self.chebyshev_stages(h, t_new),
        }
    }

    /// Stage `s`: `k_s = f(t_stage, y + h Σ_j a_j k_j)` with the row `a` of its coupling
    /// coefficients, summed stage-major over whole state vectors (each component summing its
    /// terms in stage order); returns the stage point.
    #[inline(always)]
    pub(super) fn stage(&mut self, s: usize, a: &[f64], h: f64, t_stage: f64) -> [f64; N] {
        let acc = combine(a, &self.k[..s]);
        let mut y_stage = [0.0; N];
        for i in 0..N {
            y_stage[i] = self.y[i] + h * acc[i];
        }
        self.k[s] = (self.rhs)(t_stage, &y_stage);
        y_stage
    }

    /// The scaled max norm of the step's error: DOPRI5's embedded estimate, or DOP853's
    /// combination `h · err₅² / √(err₅² + 0.01 err₃²)` of the norms of its two estimates
    /// (HNW I, §II.10).
    #[inline]
    pub(super) fn error_norm(&self, h: f64, y_new: &[f64; N]) -> f64 {
        let scale =
            |i: usize| self.tol.atol[i] + self.y[i].abs().max(y_new[i].abs()) * self.tol.rtol;
        match self.pair {
            Pair::Dopri5 => {
                let e = combine(&dopri5::E, &self.k[..7]);
                let mut m: f64 = 0.0;
                for i in 0..N {
                    m = m.max((h * e[i] / scale(i)).abs());
                }
                m
            }
            Pair::Dop853 => {
                let e5 = combine(&dop853::E5, &self.k[..=dop853::STAGES]);
                let e3 = combine(&dop853::E3, &self.k[..=dop853::STAGES]);
                let (mut err5, mut err3): (f64, f64) = (0.0, 0.0);
                for i in 0..N {
                    let sc = scale(i);
                    err5 = err5.max((e5[i] / sc).abs());
                    err3 = err3.max((e3[i] / sc).abs());
                }
                if err5 == 0.0 && err3 == 0.0 {
                    return 0.0;
                }
                h.abs() * err5 * err5 / (err5 * err5 + 0.01 * err3 * err3).sqrt()
            }
            Pair::Rkc2 => {
                // Sommeijer, Shampine & Verwer 1997, eq. 2.7: (12 (yₙ − yₙ₊₁) + 6h (fₙ + fₙ₊₁)) / 15.
                let mut m: f64 = 0.0;
                for i in 0..N {
                    let e = 0.8 * (self.y[i] - y_new[i]) + 0.4 * h * (self.k[0][i] + self.k[1][i]);
                    m = m.max((e / scale(i)).abs());
                }
                m
            }
        }
    }
}
