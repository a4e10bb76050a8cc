//! Adaptive embedded Runge–Kutta integrators with dense output: the Dormand–Prince pairs
//! DOPRI5 and DOP853, and a Runge–Kutta–Chebyshev method for stiff stretches (docs/physics.md
//! §26).
//!
//! - **DOPRI5**, the pair RK5(4)7M of Dormand & Prince (1980), *A family of embedded
//!   Runge–Kutta formulae*, J. Comput. Appl. Math. 6(1), 19–26, as in Hairer, Nørsett &
//!   Wanner, *Solving Ordinary Differential Equations I* (2nd ed., 1993), §II.5 (Table 5.2):
//!   seven stages, six evaluations per step (FSAL), propagation with the fifth-order solution,
//!   a fourth-order error estimate, and the fourth-order continuous extension of §II.6 (the
//!   `d_i` of the DOPRI5 code, eq. 6.12 ff.), free of further evaluations.
//! - **DOP853**, the eighth-order pair of Prince & Dormand (1981), *High order embedded
//!   Runge–Kutta formulae*, J. Comput. Appl. Math. 7(1), 67–75, in the form of Hairer's DOP853
//!   code (HNW I, §II.10): twelve evaluations per step (`f(t + h, y_new)` is reused as the next
//!   step's first stage), an error estimate that combines a fifth- and a third-order embedded
//!   solution, `err = err₅² / √(err₅² + 0.01 err₃²)`, and a continuous extension of order 7
//!   that needs three more evaluations, made only for the steps where a dense value is asked
//!   for. Its coefficients are those of `dop853.f`, written as the nearest doubles.
//! - **RKC2**, the damped second-order Runge–Kutta–Chebyshev method of van der Houwen &
//!   Sommeijer (1980) in the form of Sommeijer, Shampine & Verwer (1997), *RKC: an explicit
//!   solver for parabolic PDEs*, J. Comput. Appl. Math. 88, 315–326: `s` stages built on the
//!   Chebyshev recursion, whose stability interval grows like `0.65 s²` along the negative real
//!   axis, so a step costs `s ≈ √(1.54 hρ)` evaluations for a spectral radius `ρ` instead of
//!   `hρ/3.3` DOPRI5 steps of six. The radius comes from a nonlinear power method (re-run
//!   every 25 steps and after a rejection), the error estimate from the step's ends, the dense
//!   output is the cubic Hermite interpolant of those ends (DOPRI5's form without `F₃`).
//!
//! Which pair where ([`crate::flight`], docs/physics.md §26.5; the evaluation counts behind it
//! are in docs/performance.md, "Integrators"): DOPRI5 on the rail (steps capped), through the
//! burn (steps end on every thrust-curve knot) and under parachutes, where a cheaper step wins,
//! until its steps are bounded by the stability of the drag relaxation (`h·2k|v| ≈ 3.3`, the
//! step's [`RungeKutta::stiffness`] estimate, HNW II §IV.2): the descent then goes on with RKC.
//! RKC is only second order, so the transient after a canopy opens stays with DOPRI5.
//! ODEPACK's LSODA, which RocketPy integrates with, answers the same stiffness by switching
//! from Adams to BDF formulas. DOP853 for the unpowered 6-DOF flight, where accuracy sets the
//! step: the attitude quaternion of a rolling rocket turns at half the roll rate. Where the
//! right-hand side has kinks (linearly interpolated wind and temperature profiles: a
//! reanalysis or a sounding) every kink rejects a long step and DOP853 loses: the flight hands
//! such a phase back to DOPRI5 once its steps keep being rejected. Through the burn the knot
//! stops cap the steps and DOP853 loses too.
//!
//! Both dense outputs share one form, `y₀ + θ(F₀ + (1−θ)(F₁ + θ(F₂ + (1−θ)(F₃ + θ(F₄ + (1−θ)(F₅
//! + θF₆))))))` with `θ = (t − t₀)/h`, `F₀ = Δy` and `F₁ = h f₀ − Δy` (HNW I, §II.6 and
//! `dop853.f`'s `contd8`); DOPRI5's stops at `F₃`.
//!
//! Step-size control uses the scaled **max** norm `max_i |err_i| / (atol_i + rtol·max(|y_i|,
//! |ŷ_i|))` (for DOP853 both embedded errors), the norm of ODEPACK's LSODA (`vmnorm`,
//! Hindmarsh 1983; Petzold 1983), which RocketPy integrates with: the RMS norm of SciPy's `RK45`
//! dilutes a velocity error over the thirteen components and lets steps grow past what LSODA
//! accepts, which moves the maxima sampled at the stored points (docs/performance.md,
//! "Integrators"). The controller is `h ← h · min(10, max(0.2, 0.9 · err^(−1/(q+1))))` with the
//! estimator order `q` (no growth right after a rejection), and the initial step comes from the
//! algorithm of HNW I, §II.4 ("Starting step size"), as in SciPy.
//!
//! The state is a fixed `[f64; N]`; the stages live inside the integrator, which owns the
//! right-hand side, so neither a step nor a dense value allocates. The same controller drives
//! RKC with its error exponent −1/3.

// Index loops over several parallel fixed-size arrays read closer to the formulas.
#![allow(clippy::needless_range_loop, clippy::unreadable_literal)]

mod chebyshev;
mod dense;
mod step;
mod tableaux;
#[cfg(test)]
mod tests;

use tableaux::{dop853, dopri5, rkc};

/// Safety factor of the step-size controller.
const SAFETY: f64 = 0.9;
/// Smallest step-size reduction factor after a rejected step.
const MIN_FACTOR: f64 = 0.2;
/// Largest step-size growth factor after an accepted step.
const MAX_FACTOR: f64 = 10.0;
/// Stage slots: DOP853's twelve stages, `f(t + h, y_new)` and three dense-output stages.
const SLOTS: usize = 16;

/// An embedded Runge–Kutta pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pair {
    /// Dormand–Prince 5(4), six evaluations per step.
    Dopri5,
    /// Dormand–Prince 8(5,3), twelve evaluations per step.
    Dop853,
    /// Second-order Runge–Kutta–Chebyshev, `s` evaluations per step with `s` set by the step
    /// and the spectral radius of the Jacobian.
    Rkc2,
}

impl Pair {
    /// Order `q` of the error estimate that controls the step.
    pub(super) fn error_order(self) -> i32 {
        match self {
            Pair::Dopri5 => 4,
            Pair::Dop853 => 7,
            Pair::Rkc2 => 2,
        }
    }

    /// Exponent `−1/(q+1)` of the step-size controller.
    pub(super) fn error_exponent(self) -> f64 {
        match self {
            Pair::Dopri5 => -1.0 / 5.0,
            Pair::Dop853 => -1.0 / 8.0,
            Pair::Rkc2 => -1.0 / 3.0,
        }
    }

    /// Slot of `f(t + h, y_new)` among the stages.
    pub(super) fn last(self) -> usize {
        match self {
            Pair::Dopri5 => 6,
            Pair::Dop853 => dop853::STAGES,
            Pair::Rkc2 => 1,
        }
    }
}

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

/// Result of one [`RungeKutta::step`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepStatus {
    /// A step was accepted; more remain before the time bound.
    Running,
    /// The accepted step reached the time bound.
    Finished,
}

/// The integrator of `y' = f(t, y)`: the pair, the right-hand side, the current point, the
/// last step's stages (for the dense output) and counters.
#[derive(Debug, Clone)]
pub struct RungeKutta<const N: usize, F> {
    pair: Pair,
    rhs: F,
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
    /// Stages of the last step, `f(t + h, y_new)` at [`Pair::last`] and, for DOP853, the
    /// three dense-output stages after it.
    k: [[f64; N]; SLOTS],
    /// The seven coefficient rows of the dense output of the last accepted step…
    rows: [[f64; N]; 7],
    /// …valid once made for that step.
    rows_made: bool,
    /// RKC: the estimated spectral radius of the Jacobian (with its margin), NaN before the
    /// first estimate…
    radius: f64,
    /// …the accepted steps since that estimate…
    radius_age: usize,
    /// …and the power method's last direction, its start at the next estimate.
    eigen: [f64; N],
    steps: usize,
    rejected: usize,
    nfev: usize,
}

/// Scaled RMS norm `sqrt(Σ (v_i/s_i)² / N)`.
#[inline]
pub(super) fn rms_norm<const N: usize>(v: &[f64; N], scale: &[f64; N]) -> f64 {
    let mut sum = 0.0;
    for i in 0..N {
        let r = v[i] / scale[i];
        sum += r * r;
    }
    (sum / N as f64).sqrt()
}

/// `Σ_j w_j k_j` over the stages with a non-zero weight, in stage order (zero weights add
/// nothing to a finite sum and are skipped).
#[inline(always)]
pub(super) fn combine<const N: usize>(weights: &[f64], k: &[[f64; N]]) -> [f64; N] {
    let mut acc = [0.0; N];
    for (w, k) in weights.iter().zip(k) {
        if *w != 0.0 {
            for (acc, k) in acc.iter_mut().zip(k) {
                *acc += w * k;
            }
        }
    }
    acc
}

impl<const N: usize, F> RungeKutta<N, F> {
    /// The tolerance scale `atol_i + rtol |y_i|` of each component of `y`.
    #[inline]
    pub(super) fn tolerance_scale(&self, y: &[f64; N]) -> [f64; N] {
        std::array::from_fn(|i| self.tol.atol[i] + self.tol.rtol * y[i].abs())
    }

    /// Sets a stop time: steps end exactly there (without restarting) so that no step
    /// straddles a kink of the right-hand side (e.g. a thrust-curve knot). A stop at or
    /// before the current time, closer to it than the smallest step, or past the bound, has no
    /// effect.
    pub fn set_stop(&mut self, t_stop: f64) {
        self.stop = t_stop;
    }

    /// The pair that steps.
    #[inline]
    #[must_use]
    pub fn pair(&self) -> Pair {
        self.pair
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

    /// Derivative at the current point (the reused last evaluation of the step).
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

    /// Derivative at the start of the last accepted step.
    #[inline]
    #[must_use]
    pub fn f_old(&self) -> &[f64; N] {
        &self.k[0]
    }

    /// Length of the last accepted step.
    #[inline]
    #[must_use]
    pub fn last_step(&self) -> f64 {
        self.h_last
    }

    /// The right-hand side, given back when the integration is over (to start the next
    /// integrator of a flight with it).
    pub fn into_rhs(self) -> F {
        self.rhs
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

    /// DOPRI5's estimate of `h |λ|` for the last accepted step, the step times the dominant
    /// eigenvalue of the Jacobian along the step's last correction (0 for the other pairs):
    /// stages 6 and 7 are both taken at `t + h`, and the ratio of the differences of their
    /// derivatives and of their points estimates that eigenvalue (HNW II, §IV.2, the
    /// "stiffness detection" of DOPRI5), here in the tolerance-weighted norm so that it follows
    /// the units. Near DOPRI5's stability boundary (≈ 3.3 on the negative real axis) the steps
    /// are bound by stability, not accuracy: the problem is stiff for the pair. Computed on
    /// demand from the stored stages, without evaluations.
    #[must_use]
    pub fn stiffness(&self) -> f64 {
        if self.pair != Pair::Dopri5 || self.h_last <= 0.0 {
            return 0.0;
        }
        let h = self.h_last;
        let acc = combine(&dopri5::A[5][..5], &self.k[..5]);
        let weight = self.tolerance_scale(&self.y);
        let (mut dk, mut dy) = ([0.0; N], [0.0; N]);
        for i in 0..N {
            dk[i] = self.k[6][i] - self.k[5][i];
            dy[i] = self.y[i] - (self.y_old[i] + h * acc[i]);
        }
        let spread = rms_norm(&dy, &weight);
        if spread > 0.0 {
            h * rms_norm(&dk, &weight) / spread
        } else {
            0.0
        }
    }

    /// Right-hand-side evaluations so far (dense-output stages included).
    #[inline]
    #[must_use]
    pub fn evaluations(&self) -> usize {
        self.nfev
    }
}
