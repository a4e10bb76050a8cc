//! Adaptive embedded Runge–Kutta integrators with dense output: the Dormand–Prince pairs
//! DOPRI5 and DOP853, and a Runge–Kutta–Chebyshev method for stiff stretches.
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
//! Which pair where ([`crate::flight`]): DOPRI5 on the rail (steps capped), through the burn
//! (steps end on every thrust-curve knot) and under parachutes, where a cheaper step wins,
//! until its steps are bounded by the stability of the drag relaxation (`h·2k|v| ≈ 3.3`, the
//! step's [`RungeKutta::stiffness`] estimate, HNW II §IV.2): the descent then goes on with RKC
//! (Calisto under its main canopy: DOPRI5 ~1.3 s steps, 4.6 evaluations per second of flight;
//! RKC steps growing to ~24 s with 5 stages, 0.8 per second). RKC is only second order, so
//! the transient after a canopy opens stays with DOPRI5 (RKC from the opening needed ~4× its
//! evaluations there). ODEPACK's LSODA, which RocketPy integrates with, answers the same
//! stiffness by switching from Adams to BDF formulas. DOP853 for the unpowered 6-DOF flight,
//! where accuracy sets the step: the attitude quaternion of a rolling rocket turns at half the
//! roll rate (Calisto: ~9 rad/s), and DOPRI5 needed ~410 steps (2,450 evaluations) for its 22 s
//! coast at the default tolerances, DOP853 ~100 steps (1,200 evaluations). Where the right-hand
//! side has kinks (linearly interpolated wind and temperature profiles: a reanalysis or a
//! sounding) every kink rejects a long step, and DOP853 loses (Astra: 18 % more evaluations
//! than DOPRI5): the flight hands such a phase back to DOPRI5 once its steps keep being
//! rejected. Through the burn DOP853 lost on every validation flight (knot stops cap its
//! steps).
//!
//! Both dense outputs share one form, `y₀ + θ(F₀ + (1−θ)(F₁ + θ(F₂ + (1−θ)(F₃ + θ(F₄ + (1−θ)(F₅
//! + θF₆))))))` with `θ = (t − t₀)/h`, `F₀ = Δy` and `F₁ = h f₀ − Δy` (HNW I, §II.6 and
//! `dop853.f`'s `contd8`); DOPRI5's stops at `F₃`.
//!
//! Step-size control uses the scaled **max** norm `max_i |err_i| / (atol_i + rtol·max(|y_i|,
//! |ŷ_i|))` (for DOP853 both embedded errors), the norm of ODEPACK's LSODA (`vmnorm`,
//! Hindmarsh 1983; Petzold 1983), which RocketPy integrates with: the RMS norm of SciPy's `RK45`
//! dilutes a velocity error over the thirteen components and lets steps grow past what LSODA
//! accepts (Calisto: 16 % fewer DOPRI5 steps, but maxima sampled at the stored points drift by
//! up to 0.16 %). The controller is `h ← h · min(10, max(0.2, 0.9 · err^(−1/(q+1))))` with the
//! estimator order `q` (no growth right after a rejection), and the initial step comes from the
//! algorithm of HNW I, §II.4 ("Starting step size"), as in SciPy.
//!
//! The state is a fixed `[f64; N]`; the stages live inside the integrator, which owns the
//! right-hand side, so neither a step nor a dense value allocates. The same controller drives
//! RKC with its error exponent −1/3.

// Index loops over several parallel fixed-size arrays read closer to the formulas.
#![allow(clippy::needless_range_loop, clippy::unreadable_literal)]

use crate::DynamicsError;

/// The DOPRI5 tableau.
mod dopri5 {
    /// Nodes `c_i` of the Dormand–Prince 5(4) tableau (HNW I, Table 5.2).
    pub const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];

    /// Lower-triangular coupling coefficients `a_ij` (HNW I, Table 5.2); row 6 holds the
    /// fifth-order weights `b_i` (FSAL: the seventh stage is `f(t + h, y_new)`).
    pub const A: [[f64; 6]; 7] = [
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
    pub const E: [f64; 7] = [
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
    pub const D: [f64; 7] = [
        -12715105075.0 / 11282082432.0,
        0.0,
        87487479700.0 / 32700410799.0,
        -10690763975.0 / 1880347072.0,
        701980252875.0 / 199316789632.0,
        -1453857185.0 / 822651844.0,
        69997945.0 / 29380423.0,
    ];
}

/// The DOP853 tableau, one row per line as a Butcher tableau.
#[rustfmt::skip]
mod dop853 {
    /// Stages of a step; the first is the previous step's `f(t + h, y_new)`.
    pub const STAGES: usize = 12;

    /// Nodes `c_i` of the twelve stages.
    pub const C: [f64; 12] = [0.0, 0.05260015195876773, 0.0789002279381516, 0.1183503419072274, 0.2816496580927726, 0.3333333333333333, 0.25, 0.3076923076923077, 0.6512820512820513, 0.6, 0.8571428571428571, 1.0];

    /// Coupling coefficients `a_ij` of the twelve stages (row `i`, columns `j < i`).
    pub const A: [[f64; 11]; 12] = [
        [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.05260015195876773, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0197250569845379, 0.0591751709536137, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.02958758547680685, 0.0, 0.08876275643042054, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.2413651341592667, 0.0, -0.8845494793282861, 0.924834003261792, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.037037037037037035, 0.0, 0.0, 0.17082860872947386, 0.12546768756682242, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.037109375, 0.0, 0.0, 0.17025221101954405, 0.06021653898045596, -0.017578125, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.03709200011850479, 0.0, 0.0, 0.17038392571223998, 0.10726203044637328, -0.015319437748624402, 0.008273789163814023, 0.0, 0.0, 0.0, 0.0],
        [0.6241109587160757, 0.0, 0.0, -3.3608926294469414, -0.868219346841726, 27.59209969944671, 20.154067550477894, -43.48988418106996, 0.0, 0.0, 0.0],
        [0.47766253643826434, 0.0, 0.0, -2.4881146199716677, -0.590290826836843, 21.230051448181193, 15.279233632882423, -33.28821096898486, -0.020331201708508627, 0.0, 0.0],
        [-0.9371424300859873, 0.0, 0.0, 5.186372428844064, 1.0914373489967295, -8.149787010746927, -18.52006565999696, 22.739487099350505, 2.4936055526796523, -3.0467644718982196, 0.0],
        [2.273310147516538, 0.0, 0.0, -10.53449546673725, -2.0008720582248625, -17.9589318631188, 27.94888452941996, -2.8589982771350235, -8.87285693353063, 12.360567175794303, 0.6433927460157636],
    ];

    /// Weights `b_i` of the eighth-order solution.
    pub const B: [f64; 12] = [0.054293734116568765, 0.0, 0.0, 0.0, 0.0, 4.450312892752409, 1.8915178993145003, -5.801203960010585, 0.3111643669578199, -0.1521609496625161, 0.20136540080403034, 0.04471061572777259];

    /// Weights of the fifth-order error estimate (`b_i − b̂_i`, the thirteenth on `f(t+h, y_new)`).
    pub const E5: [f64; 13] = [0.01312004499419488, 0.0, 0.0, 0.0, 0.0, -1.2251564463762044, -0.4957589496572502, 1.6643771824549864, -0.35032884874997366, 0.3341791187130175, 0.08192320648511571, -0.022355307863886294, 0.0];

    /// Weights of the third-order error estimate.
    pub const E3: [f64; 13] = [-0.18980075407240762, 0.0, 0.0, 0.0, 0.0, 4.450312892752409, 1.8915178993145003, -5.801203960010585, -0.4226823213237919, -0.1521609496625161, 0.20136540080403034, 0.02265179219836082, 0.0];

    /// Nodes of the three extra stages of the dense output.
    pub const C_EXTRA: [f64; 3] = [0.1, 0.2, 0.7777777777777778];

    /// Coupling coefficients of the three extra stages (columns: the thirteen stages of the step,
    /// then the earlier extra stages).
    pub const A_EXTRA: [[f64; 16]; 3] = [
        [0.056167502283047954, 0.0, 0.0, 0.0, 0.0, 0.0, 0.25350021021662483, -0.2462390374708025, -0.12419142326381637, 0.15329179827876568, 0.00820105229563469, 0.007567897660545699, -0.008298, 0.0, 0.0, 0.0],
        [0.03183464816350214, 0.0, 0.0, 0.0, 0.0, 0.028300909672366776, 0.053541988307438566, -0.05492374857139099, 0.0, 0.0, -0.00010834732869724932, 0.0003825710908356584, -0.00034046500868740456, 0.1413124436746325, 0.0, 0.0],
        [-0.42889630158379194, 0.0, 0.0, 0.0, 0.0, -4.697621415361164, 7.683421196062599, 4.06898981839711, 0.3567271874552811, 0.0, 0.0, 0.0, -0.0013990241651590145, 2.9475147891527724, -9.15095847217987, 0.0],
    ];

    /// Coefficients of the four highest terms of the dense output (HNW I, §II.10, `dop853.f`'s
    /// `d4j…d7j`).
    pub const D: [[f64; 16]; 4] = [
        [-8.428938276109013, 0.0, 0.0, 0.0, 0.0, 0.5667149535193777, -3.0689499459498917, 2.38466765651207, 2.117034582445028, -0.871391583777973, 2.2404374302607883, 0.6315787787694688, -0.08899033645133331, 18.148505520854727, -9.194632392478356, -4.436036387594894],
        [10.427508642579134, 0.0, 0.0, 0.0, 0.0, 242.28349177525817, 165.20045171727028, -374.5467547226902, -22.113666853125306, 7.733432668472264, -30.674084731089398, -9.332130526430229, 15.697238121770845, -31.139403219565178, -9.35292435884448, 35.81684148639408],
        [19.985053242002433, 0.0, 0.0, 0.0, 0.0, -387.0373087493518, -189.17813819516758, 527.8081592054236, -11.57390253995963, 6.8812326946963, -1.0006050966910838, 0.7777137798053443, -2.778205752353508, -60.19669523126412, 84.32040550667716, 11.99229113618279],
        [-25.69393346270375, 0.0, 0.0, 0.0, 0.0, -154.18974869023643, -231.5293791760455, 357.6391179106141, 93.40532418362432, -37.45832313645163, 104.0996495089623, 29.8402934266605, -43.53345659001114, 96.32455395918828, -39.17726167561544, -149.72683625798564],
    ];
}

/// Constants of the second-order Runge–Kutta–Chebyshev method (Sommeijer, Shampine & Verwer
/// 1997, §2 and the RKC code).
mod rkc {
    /// Damping `ε` of the shifted Chebyshev polynomials, `w₀ = 1 + ε/s²`: the stability
    /// region then stays at least ~0.95 wide along the negative real axis.
    pub const DAMPING: f64 = 2.0 / 13.0;
    /// With that damping the region reaches `β(s) ≈ 0.653 (s² − 1)`, so a step `h` of a
    /// problem of spectral radius `ρ` needs `s² ≥ 1 + 1.54 h ρ`.
    pub const STAGE_FACTOR: f64 = 1.54;
    /// The radius used is the power method's estimate times this margin, to err on the side
    /// of more stages.
    pub const RADIUS_MARGIN: f64 = 1.2;
    /// The radius is estimated again after this many accepted steps, and after a rejected
    /// step that did not start from a fresh estimate.
    pub const REESTIMATE_AFTER: usize = 25;
    /// Iterations of the power method before it settles for the largest ratio it met.
    pub const POWER_ITERATIONS: usize = 20;
    /// The power method stops when two successive ratios agree to this fraction.
    pub const POWER_TOLERANCE: f64 = 0.01;
}

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
    fn error_order(self) -> i32 {
        match self {
            Pair::Dopri5 => 4,
            Pair::Dop853 => 7,
            Pair::Rkc2 => 2,
        }
    }

    /// Exponent `−1/(q+1)` of the step-size controller.
    fn error_exponent(self) -> f64 {
        match self {
            Pair::Dopri5 => -1.0 / 5.0,
            Pair::Dop853 => -1.0 / 8.0,
            Pair::Rkc2 => -1.0 / 3.0,
        }
    }

    /// Slot of `f(t + h, y_new)` among the stages.
    fn last(self) -> usize {
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
fn rms_norm<const N: usize>(v: &[f64; N], scale: &[f64; N]) -> f64 {
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
fn combine<const N: usize>(weights: &[f64], k: &[[f64; N]]) -> [f64; N] {
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
    fn tolerance_scale(&self, y: &[f64; N]) -> [f64; N] {
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
    fn initial_step(&mut self) -> f64 {
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
    fn stages(&mut self, h: f64, t_new: f64) -> [f64; N] {
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

    /// The stage count `s = 1 + ⌊√(1 + 1.54 h ρ)⌋` (at least 2) that keeps a step `h` inside
    /// the stability region for the estimated spectral radius `ρ` (Sommeijer, Shampine &
    /// Verwer 1997, §2).
    fn chebyshev_stage_count(&self, h: f64) -> usize {
        let s = 1.0 + (1.0 + rkc::STAGE_FACTOR * h * self.radius).sqrt().floor();
        // A float-to-integer cast saturates; the step limit keeps `s` below the cap anyway.
        (s as usize).max(2)
    }

    /// The longest RKC step whose stage count stays within `√(rtol / (10 ε))`: the round-off
    /// of the stage recursion grows like `s²ε`, which must stay well below the tolerance (the
    /// cap of the RKC code).
    fn chebyshev_step_limit(&self) -> f64 {
        let cap = (self.tol.rtol / (10.0 * f64::EPSILON))
            .sqrt()
            .round()
            .max(2.0);
        (cap * cap - 1.0) / (rkc::STAGE_FACTOR * self.radius)
    }

    /// One step of the damped second-order Runge–Kutta–Chebyshev method (Sommeijer, Shampine
    /// & Verwer 1997, eqs. 2.1–2.6; van der Houwen & Sommeijer 1980): with the shifted
    /// Chebyshev polynomials `T_j` of the first kind, `w₀ = 1 + ε/s²`, `w₁ = T_s′(w₀)/T_s″(w₀)`
    /// and `b_j = T_j″(w₀)/T_j′(w₀)²` (`b₀ = b₁ = b₂`), the stages are `Y₁ = y + b₁w₁ h f(y)` and
    /// `Y_j = (1 − μ_j − ν_j) y + μ_j Y_{j−1} + ν_j Y_{j−2} + μ̃_j h (f(Y_{j−1}) − a_{j−1} f(y))`
    /// with `μ_j = 2 b_j w₀/b_{j−1}`, `ν_j = −b_j/b_{j−2}`, `μ̃_j = 2 b_j w₁/b_{j−1}` and
    /// `a_j = 1 − b_j T_j(w₀)`; `Y_s` is the new point. `T_j`, `T_j′` and `T_j″` at `w₀` follow
    /// from the three-term recurrence and the stage instants `c_j` from the same combination
    /// of the earlier ones. `s − 1` evaluations, plus `f(t_new, y_new)` in slot 1.
    fn chebyshev_stages(&mut self, h: f64, t_new: f64) -> [f64; N] {
        let s = self.chebyshev_stage_count(h);
        let sf = s as f64;
        let w0 = 1.0 + rkc::DAMPING / (sf * sf);
        let w0_sq_1 = w0 * w0 - 1.0;
        let root = w0_sq_1.sqrt();
        // arccosh(w₀) · s: T_s(w₀) = cosh(s θ), from which T_s′ and T_s″.
        let arg = sf * (w0 + root).ln();
        let w1 = arg.sinh() * w0_sq_1 / (arg.cosh() * sf * root - w0 * arg.sinh());
        let (t, y0, f0) = (self.t, self.y, self.f);
        // T_{j−2}, T_{j−1} and their first and second derivatives at w₀, from T₀ = 1, T₁ = w₀.
        let (mut cheb, mut cheb_prev) = (w0, 1.0);
        let (mut slope, mut slope_prev) = (1.0, 0.0);
        let (mut curv, mut curv_prev) = (0.0, 0.0);
        let b_first = 1.0 / (4.0 * w0 * w0);
        let (mut b, mut b_prev) = (b_first, b_first);
        let mu1 = w1 * b_first;
        let mut y_prev = y0;
        let mut y_cur = [0.0; N];
        for i in 0..N {
            y_cur[i] = y0[i] + h * mu1 * f0[i];
        }
        let (mut c, mut c_prev) = (mu1, 0.0);
        for _ in 2..=s {
            let cheb_next = 2.0 * w0 * cheb - cheb_prev;
            let slope_next = 2.0 * w0 * slope - slope_prev + 2.0 * cheb;
            let curv_next = 2.0 * w0 * curv - curv_prev + 4.0 * slope;
            let b_next = curv_next / (slope_next * slope_next);
            let a = 1.0 - cheb * b;
            let mu = 2.0 * w0 * b_next / b;
            let nu = -b_next / b_prev;
            let mu_tilde = mu * w1 / w0;
            let f = (self.rhs)(t + c * h, &y_cur);
            let mut y_next = [0.0; N];
            for i in 0..N {
                y_next[i] = (1.0 - mu - nu) * y0[i]
                    + mu * y_cur[i]
                    + nu * y_prev[i]
                    + mu_tilde * h * (f[i] - a * f0[i]);
            }
            let c_next = mu * c + nu * c_prev + mu_tilde * (1.0 - a);
            (y_prev, y_cur) = (y_cur, y_next);
            (c_prev, c) = (c, c_next);
            (cheb_prev, cheb) = (cheb, cheb_next);
            (slope_prev, slope) = (slope, slope_next);
            (curv_prev, curv) = (curv, curv_next);
            (b_prev, b) = (b, b_next);
        }
        self.k[1] = (self.rhs)(t_new, &y_cur);
        self.nfev += s;
        y_cur
    }

    /// The spectral radius of the Jacobian at the current point, by the nonlinear power
    /// method of the RKC code (Sommeijer, Shampine & Verwer 1997, §3.2): a perturbation `d` of
    /// fixed size is replaced by `f(t, y + d) − f(t, y)` rescaled to that size until the ratio
    /// of the two sizes settles to 1 %. Sizes are taken in the tolerance-weighted norm
    /// `‖x‖ = rms(x_i / (atol_i + rtol |y_i|))` (the eigenvalues are those of the Jacobian in any
    /// norm, and the perturbation follows the state's units); the perturbation is `√ε ‖y‖` (at
    /// least `√ε`), it starts from the last direction found (at the first estimate, the
    /// derivative plus a direction with a share of every component) and the result carries a
    /// 20 % margin. Ratios below `1/(t_bound − t)` are not
    /// told apart, as they cannot constrain the step. Without convergence (complex dominant
    /// eigenvalues) the largest ratio met is used. Evaluations count as the method's.
    fn estimate_radius(&mut self) {
        let (t, y, f) = (self.t, self.y, self.f);
        let weight = self.tolerance_scale(&y);
        let size = f64::EPSILON.sqrt() * rms_norm(&y, &weight).max(1.0);
        // A direction with a share of every component (signs in an irregular pattern), so that
        // no eigenvector is missing from the start for want of round-off.
        let spread: [f64; N] = std::array::from_fn(|i| {
            if (i * 7 + 3) % 5 < 2 {
                -weight[i]
            } else {
                weight[i]
            }
        });
        let unit = |d: &[f64; N]| {
            let norm = rms_norm(d, &weight);
            d.map(|v| if norm > 0.0 { v / norm } else { 0.0 })
        };
        let mut d = if rms_norm(&self.eigen, &weight) > 0.0 {
            unit(&self.eigen)
        } else {
            let (f_unit, spread_unit) = (unit(&f), unit(&spread));
            std::array::from_fn(|i| f_unit[i] + spread_unit[i])
        };
        d = unit(&d).map(|v| v * size);
        let interval = self.t_bound - t;
        let small = if interval > 0.0 { 1.0 / interval } else { 0.0 };
        let (mut ratio, mut largest) = (0.0_f64, 0.0_f64);
        let mut converged = false;
        for iteration in 0..rkc::POWER_ITERATIONS {
            let mut probe = [0.0; N];
            for i in 0..N {
                probe[i] = y[i] + d[i];
            }
            let fp = (self.rhs)(t, &probe);
            self.nfev += 1;
            let mut diff = [0.0; N];
            for i in 0..N {
                diff[i] = fp[i] - f[i];
            }
            let norm = rms_norm(&diff, &weight);
            if !norm.is_finite() {
                break;
            }
            let previous = ratio;
            ratio = norm / size;
            largest = largest.max(ratio);
            if iteration > 0 && (ratio - previous).abs() <= rkc::POWER_TOLERANCE * ratio.max(small)
            {
                converged = true;
                break;
            }
            if norm > 0.0 {
                d = diff.map(|v| v * (size / norm));
            } else {
                // The perturbation vanished in f: turn the direction by flipping one component.
                let i = iteration % N;
                d[i] = -d[i];
            }
        }
        self.eigen = d;
        self.radius = rkc::RADIUS_MARGIN * if converged { ratio } else { largest };
        self.radius_age = 0;
    }

    /// Stage `s`: `k_s = f(t_stage, y + h Σ_j a_j k_j)` with the row `a` of its coupling
    /// coefficients, summed stage-major (vectorised over the components, each component
    /// summing its terms in stage order); returns the stage point.
    #[inline(always)]
    fn stage(&mut self, s: usize, a: &[f64], h: f64, t_stage: f64) -> [f64; N] {
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
    fn error_norm(&self, h: f64, y_new: &[f64; N]) -> f64 {
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

    /// The dense-output rows `F₀…F₆` of the last accepted step, made on first use: `F₀ = Δy`,
    /// `F₁ = h f₀ − Δy`, then for DOPRI5 `F₂ = Δy − h f₁ − F₁`, `F₃ = h Σ d_i k_i` (HNW I,
    /// §II.6), for DOP853 `F₂ = 2Δy − h (f₁ + f₀)`, `F₃…F₆ = h Σ d_ij k_j` after three extra
    /// evaluations (HNW I, §II.10; `dop853.f`'s `contd8`).
    fn dense_rows(&mut self) -> &[[f64; N]; 7] {
        if self.rows_made {
            return &self.rows;
        }
        let h = self.h_last;
        let last = self.pair.last();
        if self.pair == Pair::Dop853 {
            let mut y_stage = [0.0; N];
            for (e, (a, c)) in dop853::A_EXTRA.iter().zip(dop853::C_EXTRA).enumerate() {
                let s = last + 1 + e;
                let acc = combine(&a[..s], &self.k[..s]);
                for i in 0..N {
                    y_stage[i] = self.y_old[i] + h * acc[i];
                }
                self.k[s] = (self.rhs)(self.t_old + c * h, &y_stage);
                self.nfev += 1;
            }
        }
        let rows = &mut self.rows;
        for i in 0..N {
            let dy = self.y[i] - self.y_old[i];
            rows[0][i] = dy;
            rows[1][i] = h * self.k[0][i] - dy;
            rows[2][i] = match self.pair {
                Pair::Dopri5 | Pair::Rkc2 => dy - h * self.k[last][i] - rows[1][i],
                Pair::Dop853 => 2.0 * dy - h * (self.k[last][i] + self.k[0][i]),
            };
        }
        match self.pair {
            Pair::Dopri5 => {
                let acc = combine(&dopri5::D, &self.k[..7]);
                for i in 0..N {
                    rows[3][i] = h * acc[i];
                }
            }
            Pair::Rkc2 => rows[3] = [0.0; N],
            Pair::Dop853 => {
                for (row, d) in rows[3..].iter_mut().zip(&dop853::D) {
                    let acc = combine(d, &self.k);
                    for i in 0..N {
                        row[i] = h * acc[i];
                    }
                }
            }
        }
        self.rows_made = true;
        &self.rows
    }

    /// Dense output of the last accepted step at `t` (`t_old ≤ t ≤ t`; extrapolates
    /// outside): fourth order for DOPRI5, seventh for DOP853.
    pub fn dense(&mut self, t: f64) -> [f64; N] {
        let mut out = [0.0; N];
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.dense_component(t, i);
        }
        out
    }

    /// One component of [`RungeKutta::dense`]:
    /// `y₀ + θ(F₀ + (1−θ)(F₁ + θ(F₂ + (1−θ)(F₃ + θ(F₄ + (1−θ)(F₅ + θF₆))))))`, `θ = (t − t₀)/h`.
    #[inline]
    pub fn dense_component(&mut self, t: f64, i: usize) -> f64 {
        let h = self.h_last;
        if h <= 0.0 {
            return self.y[i];
        }
        let theta = (t - self.t_old) / h;
        let theta1 = 1.0 - theta;
        let y0 = self.y_old[i];
        let pair = self.pair;
        let r = self.dense_rows();
        let inner = match pair {
            Pair::Dopri5 | Pair::Rkc2 => r[3][i],
            Pair::Dop853 => {
                let inner = r[5][i] + theta * r[6][i];
                let inner = r[4][i] + theta1 * inner;
                r[3][i] + theta * inner
            }
        };
        let inner = r[2][i] + theta1 * inner;
        let inner = r[1][i] + theta * inner;
        let inner = r[0][i] + theta1 * inner;
        y0 + theta * inner
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every method; the accuracy tests of the two high-order pairs use the first two.
    const PAIRS: [Pair; 3] = [Pair::Dopri5, Pair::Dop853, Pair::Rkc2];

    fn tol<const N: usize>(rtol: f64, atol: f64) -> Tolerances<N> {
        Tolerances {
            rtol,
            atol: [atol; N],
            max_step: f64::INFINITY,
            min_step: 0.0,
            max_steps: 100_000,
        }
    }

    /// Integrates to the bound; returns the integrator.
    fn run<const N: usize, F>(mut rk: RungeKutta<N, F>) -> RungeKutta<N, F>
    where
        F: FnMut(f64, &[f64; N]) -> [f64; N],
    {
        while rk.step().unwrap() == StepStatus::Running {}
        rk
    }

    #[test]
    fn tableau_rows_sum_to_nodes() {
        // Consistency condition Σ_j a_ij = c_i of every explicit RK tableau (HNW I, eq. 1.9);
        // the weights of each solution sum to 1 and those of each error estimate to 0.
        for s in 1..6 {
            let sum: f64 = dopri5::A[s].iter().sum();
            assert!((sum - dopri5::C[s]).abs() < 1e-15, "DOPRI5 row {s}");
        }
        assert!((dopri5::A[6].iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert!(dopri5::E.iter().sum::<f64>().abs() < 1e-15);
        for s in 1..dop853::STAGES {
            let sum: f64 = dop853::A[s].iter().sum();
            assert!((sum - dop853::C[s]).abs() < 1e-14, "DOP853 row {s}");
        }
        for (a, c) in dop853::A_EXTRA.iter().zip(dop853::C_EXTRA) {
            assert!((a.iter().sum::<f64>() - c).abs() < 1e-14);
        }
        assert!((dop853::B.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        assert!(dop853::E5.iter().sum::<f64>().abs() < 1e-14);
        assert!(dop853::E3.iter().sum::<f64>().abs() < 1e-14);
    }

    #[test]
    fn fixed_steps_converge_at_the_order_of_each_pair() {
        // y' = y cos t, y(0) = 1: y = exp(sin t). Steps fixed by max_step (the tolerance is
        // loose); halving the step divides the global error by 2^p, p = 5, 8 or 2.
        let error = |pair: Pair, h: f64| {
            let f = |t: f64, y: &[f64; 1]| [y[0] * t.cos()];
            let mut t = tol::<1>(1.0, 1.0);
            t.max_step = h;
            let rk = run(RungeKutta::new(pair, f, 0.0, [1.0], 4.0, t).unwrap());
            (rk.y()[0] - 4.0f64.sin().exp()).abs()
        };
        for (pair, order, h) in [
            (Pair::Dopri5, 5.0, 0.1),
            (Pair::Dop853, 8.0, 0.4),
            (Pair::Rkc2, 2.0, 0.05),
        ] {
            let observed = (error(pair, h) / error(pair, h / 2.0)).log2();
            assert!(
                (observed - order).abs() < 0.6,
                "{pair:?}: observed order {observed}"
            );
        }
    }

    #[test]
    fn exponential_decay_matches_closed_form() {
        for &pair in &PAIRS[..2] {
            let f = |_t: f64, y: &[f64; 1]| [-y[0]];
            let rk = run(RungeKutta::new(pair, f, 0.0, [1.0], 5.0, tol(1e-9, 1e-12)).unwrap());
            assert!((rk.t() - 5.0).abs() < 1e-15);
            let exact = (-5.0f64).exp();
            assert!(
                (rk.y()[0] - exact).abs() / exact < 1e-7,
                "{pair:?}: {} vs {exact}",
                rk.y()[0]
            );
        }
    }

    #[test]
    fn harmonic_oscillator_dense_output_is_accurate() {
        // y'' = −y: dense output inside steps must match sin/cos to the tolerance level.
        for &pair in &PAIRS[..2] {
            let f = |_t: f64, y: &[f64; 2]| [y[1], -y[0]];
            let mut rk = RungeKutta::new(pair, f, 0.0, [0.0, 1.0], 10.0, tol(1e-8, 1e-10)).unwrap();
            let mut worst: f64 = 0.0;
            loop {
                let status = rk.step().unwrap();
                for k in 1..4 {
                    let t = rk.t_old() + rk.last_step() * f64::from(k) / 4.0;
                    let y = rk.dense(t);
                    worst = worst
                        .max((y[0] - t.sin()).abs())
                        .max((y[1] - t.cos()).abs());
                }
                // Dense output reproduces both step ends.
                let (y0, y1) = (*rk.y_old(), *rk.y());
                let (t0, t1) = (rk.t_old(), rk.t());
                assert!((rk.dense(t0)[0] - y0[0]).abs() < 1e-14);
                assert!((rk.dense(t1)[0] - y1[0]).abs() < 1e-14);
                if status == StepStatus::Finished {
                    break;
                }
            }
            assert!(worst < 1e-6, "{pair:?}: dense output error {worst}");
        }
    }

    #[test]
    fn dop853_dense_output_costs_three_evaluations_once_per_step() {
        let f = |_t: f64, y: &[f64; 2]| [y[1], -y[0]];
        let mut rk =
            RungeKutta::new(Pair::Dop853, f, 0.0, [0.0, 1.0], 10.0, tol(1e-8, 1e-10)).unwrap();
        rk.step().unwrap();
        let before = rk.evaluations();
        let (a, b) = (rk.dense(0.3 * rk.t()), rk.dense(0.6 * rk.t()));
        assert_eq!(rk.evaluations(), before + 3);
        assert!((a[0] - b[0]).abs() > 1e-3, "two instants, two values");
        rk.step().unwrap();
        let before = rk.evaluations();
        rk.dense_component(rk.t_old(), 0);
        assert_eq!(rk.evaluations(), before + 3);
    }

    /// The semi-discrete heat equation `u_t = u_xx` on (0, 1), `u = 0` at both ends, on
    /// `M` interior points: eigenvalues `λ_k = −(4/Δx²) sin²(kπΔx/2)`, spectral radius ≈
    /// `4/Δx²`, eigenvectors `sin(kπx_i)`.
    fn heat<const M: usize>(_t: f64, u: &[f64; M]) -> [f64; M] {
        let dx = 1.0 / (M as f64 + 1.0);
        let mut du = [0.0; M];
        for i in 0..M {
            let left = if i == 0 { 0.0 } else { u[i - 1] };
            let right = if i + 1 == M { 0.0 } else { u[i + 1] };
            du[i] = (left - 2.0 * u[i] + right) / (dx * dx);
        }
        du
    }

    /// Mode `k` of [`heat`] on `M` points, and its exact decay rate.
    fn heat_mode<const M: usize>(k: f64) -> ([f64; M], f64) {
        let dx = 1.0 / (M as f64 + 1.0);
        let shape = std::array::from_fn(|i| (k * std::f64::consts::PI * (i + 1) as f64 * dx).sin());
        let rate = -(4.0 / (dx * dx)) * (k * std::f64::consts::PI * dx / 2.0).sin().powi(2);
        (shape, rate)
    }

    #[test]
    fn chebyshev_steps_follow_a_stiff_problem_stably_and_cheaply() {
        // Three modes of the heat equation on 40 points (spectral radius ≈ 6.7e3): the fast
        // modes die out, the slow one decays over the interval. RKC must follow the exact
        // solution to about the tolerance with steps far beyond explicit stability limits
        // (DOPRI5: hρ ≲ 3.3), and in far fewer evaluations than DOPRI5.
        const M: usize = 40;
        let modes = [(1.0, 1.0), (3.0, 0.5), (17.0, 0.25)].map(|(k, a)| (heat_mode::<M>(k), a));
        let exact = |t: f64| -> [f64; M] {
            std::array::from_fn(|i| {
                modes
                    .iter()
                    .map(|((shape, rate), a)| a * shape[i] * (rate * t).exp())
                    .sum()
            })
        };
        let t_end = 0.3;
        let evaluations = |pair: Pair| {
            let mut rk =
                RungeKutta::new(pair, heat::<M>, 0.0, exact(0.0), t_end, tol(1e-6, 1e-6)).unwrap();
            let mut longest: f64 = 0.0;
            while rk.step().unwrap() == StepStatus::Running {
                longest = longest.max(rk.last_step());
            }
            let worst = rk
                .y()
                .iter()
                .zip(exact(t_end))
                .map(|(y, e)| (y - e).abs())
                .fold(0.0, f64::max);
            (rk.evaluations(), rk.steps(), longest, worst)
        };
        let (rkc, steps, longest, worst) = evaluations(Pair::Rkc2);
        let (dopri, _, _, _) = evaluations(Pair::Dopri5);
        // The slow mode is ≈ 0.05 at the end; the second-order global error stays below the
        // local tolerance summed over the steps.
        assert!(
            worst < 1e-6 * steps as f64,
            "error {worst} after {steps} steps"
        );
        // Once the fast modes have died out the step is limited by accuracy alone.
        let radius = -heat_mode::<M>(M as f64).1;
        assert!(longest * radius > 5.0 * 3.3, "h ρ = {}", longest * radius);
        assert!(3 * rkc < dopri, "RKC {rkc} evaluations, DOPRI5 {dopri}");
    }

    #[test]
    fn dopri5_stiffness_is_h_lambda_and_reaches_the_stability_boundary() {
        // y' = −100 y: the estimate is exactly h·100 (up to rounding); once the solution has
        // decayed below the tolerance the steps are held at DOPRI5's stability boundary (≈ 3.3
        // on the negative real axis).
        let f = |_t: f64, y: &[f64; 1]| [-100.0 * y[0]];
        let mut rk = RungeKutta::new(Pair::Dopri5, f, 0.0, [1.0], 2.0, tol(1e-6, 1e-9)).unwrap();
        let mut largest: f64 = 0.0;
        while rk.step().unwrap() == StepStatus::Running {
            let expected = 100.0 * rk.last_step();
            assert!(
                (rk.stiffness() / expected - 1.0).abs() < 1e-9,
                "{} vs {expected}",
                rk.stiffness()
            );
            largest = largest.max(rk.stiffness());
        }
        // The accepted steps straddle the boundary (|R(hλ)| grows slowly past it, so a few
        // steps slightly beyond it pass the error test before the controller pulls back).
        assert!((3.0..4.0).contains(&largest), "{largest}");
        // The other methods report none.
        let rk = run(RungeKutta::new(Pair::Dop853, f, 0.0, [1.0], 0.1, tol(1e-6, 1e-9)).unwrap());
        assert!(rk.stiffness() == 0.0, "DOP853 reports no stiffness");
    }

    #[test]
    fn power_method_finds_the_dominant_eigenvalue() {
        // A diagonal system with eigenvalues −1, −10, −400, −1000: the estimate (without its
        // margin) is the largest magnitude to the power method's 1 %.
        let rates = [-1.0, -10.0, -400.0, -1000.0];
        let f = move |_t: f64, y: &[f64; 4]| std::array::from_fn(|i| rates[i] * y[i]);
        let mut rk = RungeKutta::new(
            Pair::Rkc2,
            f,
            0.0,
            [1.0, 2.0, 3.0, 4.0],
            1.0,
            tol(1e-6, 1e-9),
        )
        .unwrap();
        rk.step().unwrap();
        let estimate = rk.radius / rkc::RADIUS_MARGIN;
        assert!((estimate / 1000.0 - 1.0).abs() < 0.01, "{estimate}");
        // The heat equation from its slowest mode: the derivative is that eigenvector, but
        // the first direction tried also has a share of every component, so the estimate
        // reaches the fastest rate (to the 1 % of the iteration, which cannot tell the
        // closely spaced top rates apart in a few steps).
        const M: usize = 40;
        let ((shape, _), (_, fast)) = (heat_mode::<M>(1.0), heat_mode::<M>(M as f64));
        let mut rk =
            RungeKutta::new(Pair::Rkc2, heat::<M>, 0.0, shape, 0.2, tol(1e-6, 1e-9)).unwrap();
        rk.step().unwrap();
        let estimate = rk.radius / rkc::RADIUS_MARGIN;
        assert!(
            (0.85..=1.01).contains(&(estimate / -fast)),
            "{estimate} vs {fast}"
        );
    }

    #[test]
    fn chebyshev_accuracy_and_dense_output() {
        // Exponential decay: the second-order global error is bounded by the local tolerance
        // summed over the steps.
        let f = |_t: f64, y: &[f64; 1]| [-y[0]];
        let rk = run(RungeKutta::new(Pair::Rkc2, f, 0.0, [1.0], 5.0, tol(1e-7, 1e-12)).unwrap());
        let exact = (-5.0f64).exp();
        let relative = (rk.y()[0] / exact - 1.0).abs();
        assert!((rk.t() - 5.0).abs() < 1e-15);
        assert!(
            relative < 1e-7 * rk.steps() as f64,
            "{relative} in {} steps",
            rk.steps()
        );
        // Harmonic oscillator: the cubic Hermite dense output between two step ends is no
        // further from the exact solution than those ends are, plus a local-error allowance.
        let f = |_t: f64, y: &[f64; 2]| [y[1], -y[0]];
        let mut rk =
            RungeKutta::new(Pair::Rkc2, f, 0.0, [0.0, 1.0], 10.0, tol(1e-8, 1e-10)).unwrap();
        let error = |t: f64, y: [f64; 2]| (y[0] - t.sin()).abs().max((y[1] - t.cos()).abs());
        loop {
            let status = rk.step().unwrap();
            let (t0, t1) = (rk.t_old(), rk.t());
            let ends = error(t0, *rk.y_old()).max(error(t1, *rk.y()));
            for (t, y) in [(t0, *rk.y_old()), (t1, *rk.y())] {
                let d = rk.dense(t);
                assert!((d[0] - y[0]).abs() < 1e-14 && (d[1] - y[1]).abs() < 1e-14);
            }
            for k in 1..4 {
                let t = t0 + rk.last_step() * f64::from(k) / 4.0;
                let inside = error(t, rk.dense(t));
                assert!(
                    inside <= ends + 1e-8,
                    "{inside} inside, {ends} at the ends, t = {t}"
                );
            }
            if status == StepStatus::Finished {
                break;
            }
        }
    }

    #[test]
    fn zero_derivative_start_grows_steps_geometrically() {
        // physics.md §10.4: a zero derivative gives a zero error estimate; the controller grows
        // the step by MAX_FACTOR per step, which the max_step cap must bound.
        for pair in PAIRS {
            let f = |_t: f64, _y: &[f64; 1]| [0.0];
            let mut t = tol::<1>(1e-6, 1e-3);
            t.max_step = 0.01;
            let mut rk = RungeKutta::new(pair, f, 0.0, [0.0], 1.0, t).unwrap();
            let mut largest: f64 = 0.0;
            while rk.step().unwrap() == StepStatus::Running {
                largest = largest.max(rk.last_step());
            }
            assert!(largest <= 0.01 + 1e-15);
        }
    }

    #[test]
    fn blow_up_ends_with_an_error_not_a_hang() {
        // y' = y², y(0) = 1 blows up at t = 1; integrating to 2 must fail in bounded steps.
        for pair in PAIRS {
            let f = |_t: f64, y: &[f64; 1]| [y[0] * y[0]];
            let mut rk = RungeKutta::new(pair, f, 0.0, [1.0], 2.0, tol(1e-6, 1e-6)).unwrap();
            let result = loop {
                match rk.step() {
                    Ok(StepStatus::Running) => {}
                    Ok(StepStatus::Finished) => break Ok(()),
                    Err(e) => break Err(e),
                }
            };
            assert!(
                result.is_err(),
                "{pair:?}: integration past a singularity must fail"
            );
        }
    }

    #[test]
    fn step_budget_is_enforced() {
        for pair in PAIRS {
            let f = |_t: f64, y: &[f64; 2]| [y[1], -1e6 * y[0]];
            let mut t = tol::<2>(1e-10, 1e-12);
            t.max_steps = 50;
            let mut rk = RungeKutta::new(pair, f, 0.0, [1.0, 0.0], 100.0, t).unwrap();
            let err = loop {
                match rk.step() {
                    Ok(StepStatus::Running) => {}
                    Ok(StepStatus::Finished) => panic!("cannot finish in 50 steps"),
                    Err(e) => break e,
                }
            };
            assert!(matches!(err, DynamicsError::TooManySteps { .. }));
        }
    }
}
