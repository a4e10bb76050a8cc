//! Adaptive Gauss–Kronrod quadrature (docs/physics.md §28.3).
//!
//! The 21-point Kronrod extension of the 10-point Gauss rule (exact for polynomials of degree
//! ≤ 31), applied with QUADPACK's globally adaptive strategy (routine QAG, Piessens,
//! de Doncker-Kapenga, Überhuber & Kahaner, *QUADPACK*, Springer 1983, §2.2 and §4.3): the
//! subinterval with the largest error estimate is bisected until the sum of the estimates is
//! below `max(abs_tol, rel_tol·|value|)`; it stops with an error when the budget is spent or
//! the worst interval's error is its rounding bound (QUADPACK's roundoff exit). Each interval's error estimate is QUADPACK's
//! `resasc · min(1, (200 |K − G| / resasc)^{3/2})`, bounded below by `50 ε · ∫|f|` (rounding).
//! [`integrate_breakpoints`] starts from a given subdivision (QUADPACK QAGP) so that known
//! kinks (the nodes of a table) are never inside an interval.
//!
//! The work list lives on the heap: quadrature is for building models, not for the
//! equations-of-motion right-hand side.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::MathError;

/// Abscissae of the 21-point Kronrod rule on `[−1, 1]` (positive half, descending; odd
/// positions 1, 3, … (0-based) are the 10-point Gauss nodes). QUADPACK `dqk21`, values by
/// L. W. Fullerton (Bell Labs, 1981) to 33 digits.
#[allow(
    clippy::excessive_precision,
    reason = "digits exactly as published in QUADPACK"
)]
const XGK: [f64; 11] = [
    0.995_657_163_025_808_080_735_527_280_689_003,
    0.973_906_528_517_171_720_077_964_012_084_452,
    0.930_157_491_355_708_226_001_207_180_059_508,
    0.865_063_366_688_984_510_732_096_688_423_493,
    0.780_817_726_586_416_897_063_717_578_345_042,
    0.679_409_568_299_024_406_234_327_365_114_874,
    0.562_757_134_668_604_683_339_000_099_272_694,
    0.433_395_394_129_247_190_799_265_943_165_784,
    0.294_392_862_701_460_198_131_126_603_103_866,
    0.148_874_338_981_631_210_884_826_001_129_720,
    0.0,
];

/// Weights of the 21-point Kronrod rule, matching [`XGK`] (QUADPACK `dqk21`).
#[allow(
    clippy::excessive_precision,
    reason = "digits exactly as published in QUADPACK"
)]
const WGK: [f64; 11] = [
    0.011_694_638_867_371_874_278_064_396_062_192,
    0.032_558_162_307_964_727_478_818_972_459_390,
    0.054_755_896_574_351_996_031_381_300_244_580,
    0.075_039_674_810_919_952_767_043_140_916_190,
    0.093_125_454_583_697_605_535_065_465_083_366,
    0.109_387_158_802_297_641_899_210_590_325_805,
    0.123_491_976_262_065_851_077_958_109_831_074,
    0.134_709_217_311_473_325_928_054_001_771_707,
    0.142_775_938_577_060_080_797_094_273_138_717,
    0.147_739_104_901_338_491_374_841_515_972_068,
    0.149_445_554_002_916_905_664_936_468_389_821,
];

/// Weights of the 10-point Gauss rule at `XGK[1], XGK[3], …, XGK[9]` (QUADPACK `dqk21`).
#[allow(
    clippy::excessive_precision,
    reason = "digits exactly as published in QUADPACK"
)]
const WG: [f64; 5] = [
    0.066_671_344_308_688_137_593_568_809_893_332,
    0.149_451_349_150_580_593_145_776_339_657_697,
    0.219_086_362_515_982_043_995_534_934_228_163,
    0.269_266_719_309_996_355_091_226_921_569_469,
    0.295_524_224_714_752_870_173_892_994_651_338,
];

/// Evaluations of the integrand per application of the rule.
const RULE_EVALUATIONS: usize = 21;

/// Tolerances and budget of an adaptive quadrature.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadratureOptions {
    /// Absolute error tolerance, in the units of the integral (those of `f` times those of
    /// `x`): a dimensional value, to be expressed in the unit system of the problem (the
    /// default suits SI-sized integrals).
    pub abs_tol: f64,
    /// Relative error tolerance.
    pub rel_tol: f64,
    /// Largest number of integrand evaluations.
    pub max_evaluations: usize,
}

impl Default for QuadratureOptions {
    /// `abs_tol = 1e-12`, `rel_tol = 1e-10`, at most 100 000 evaluations.
    fn default() -> Self {
        QuadratureOptions {
            abs_tol: 1e-12,
            rel_tol: 1e-10,
            max_evaluations: 100_000,
        }
    }
}

/// The result of a quadrature.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quadrature {
    /// The integral.
    pub value: f64,
    /// Estimate of the absolute error (0 for integrals computed exactly).
    pub abs_error: f64,
    /// Number of integrand evaluations (0 for integrals computed exactly).
    pub evaluations: usize,
}

/// One subinterval and its rule result, ordered by error estimate.
#[derive(Debug, Clone, Copy)]
struct Segment {
    a: f64,
    b: f64,
    value: f64,
    error: f64,
    /// The rounding bound `50 ε ∫|f|` below which the error estimate cannot fall.
    rounding: f64,
}

impl PartialEq for Segment {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Segment {}
impl PartialOrd for Segment {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Segment {
    fn cmp(&self, other: &Self) -> Ordering {
        self.error.total_cmp(&other.error)
    }
}

/// The 21-point Gauss–Kronrod rule on `[a, b]` with QUADPACK's error estimate.
fn kronrod21(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> Segment {
    let center = 0.5 * (a + b);
    let half = 0.5 * (b - a);
    let f_center = f(center);
    let mut kronrod = WGK[10] * f_center;
    let mut abs_sum = kronrod.abs();
    let mut gauss = 0.0;
    let mut values = [[0.0; 2]; 10];
    for (j, pair) in values.iter_mut().enumerate() {
        let dx = half * XGK[j];
        let (f1, f2) = (f(center - dx), f(center + dx));
        *pair = [f1, f2];
        kronrod += WGK[j] * (f1 + f2);
        abs_sum += WGK[j] * (f1.abs() + f2.abs());
        if j % 2 == 1 {
            gauss += WG[j / 2] * (f1 + f2);
        }
    }
    let mean = 0.5 * kronrod;
    let mut asc = WGK[10] * (f_center - mean).abs();
    for (j, [f1, f2]) in values.iter().enumerate() {
        asc += WGK[j] * ((f1 - mean).abs() + (f2 - mean).abs());
    }
    let value = kronrod * half;
    let res_abs = abs_sum * half.abs();
    let res_asc = asc * half.abs();
    let mut error = ((kronrod - gauss) * half).abs();
    if res_asc > 0.0 && error > 0.0 {
        error = res_asc * (200.0 * error / res_asc).powf(1.5).min(1.0);
    }
    let rounding = 50.0 * f64::EPSILON * res_abs;
    if res_abs > f64::MIN_POSITIVE / (50.0 * f64::EPSILON) {
        error = error.max(rounding);
    }
    Segment {
        a,
        b,
        value,
        error,
        rounding,
    }
}

/// `∫_a^b f dx` by adaptive Gauss–Kronrod (21 points) on a finite interval; `b < a` gives the
/// negated integral.
///
/// # Errors
/// [`MathError::InvalidInterval`] for a non-finite end; [`MathError::QuadratureNotConverged`]
/// when the budget is spent (or an interval cannot be split further) before the tolerance is
/// met, or the integrand returns NaN.
pub fn integrate(
    f: impl Fn(f64) -> f64,
    a: f64,
    b: f64,
    options: &QuadratureOptions,
) -> Result<Quadrature, MathError> {
    integrate_breakpoints(f, &[a, b], options)
}

/// `∫ f dx` from `points[0]` to `points[last]`, starting from the subdivision at `points`
/// (which must be monotone: all non-decreasing or all non-increasing). Put known kinks or
/// discontinuities of `f` in `points`.
///
/// # Errors
/// As [`integrate`]; [`MathError::InvalidInterval`] for fewer than two points or a
/// non-monotone list.
pub fn integrate_breakpoints(
    f: impl Fn(f64) -> f64,
    points: &[f64],
    options: &QuadratureOptions,
) -> Result<Quadrature, MathError> {
    let (Some(&first), Some(&last)) = (points.first(), points.last()) else {
        return Err(MathError::InvalidInterval {
            a: f64::NAN,
            b: f64::NAN,
        });
    };
    if points.len() < 2 || points.iter().any(|p| !p.is_finite()) {
        return Err(MathError::InvalidInterval { a: first, b: last });
    }
    if last < first {
        let reversed: Vec<f64> = points.iter().rev().copied().collect();
        let q = integrate_breakpoints(f, &reversed, options)?;
        return Ok(Quadrature {
            value: -q.value,
            ..q
        });
    }
    if points.windows(2).any(|w| w[1] < w[0]) {
        return Err(MathError::InvalidInterval { a: first, b: last });
    }
    let mut heap = BinaryHeap::new();
    let mut evaluations = 0;
    for w in points.windows(2) {
        if w[1] > w[0] {
            heap.push(kronrod21(&f, w[0], w[1]));
            evaluations += RULE_EVALUATIONS;
        }
    }
    loop {
        let value: f64 = heap.iter().map(|s| s.value).sum();
        let error: f64 = heap.iter().map(|s| s.error).sum();
        let tolerance = options.abs_tol.max(options.rel_tol * value.abs());
        if error <= tolerance {
            return Ok(Quadrature {
                value,
                abs_error: error,
                evaluations,
            });
        }
        let fail = || MathError::QuadratureNotConverged {
            value,
            abs_error: error,
            tolerance,
            evaluations,
        };
        if !error.is_finite() || evaluations + 2 * RULE_EVALUATIONS > options.max_evaluations {
            return Err(fail());
        }
        let Some(worst) = heap.pop() else {
            return Err(fail());
        };
        let mid = 0.5 * (worst.a + worst.b);
        // Rounding dominates the worst interval (QUADPACK's roundoff exit, ier = 2), or the
        // interval cannot be split: bisection can no longer reduce the error.
        if worst.error <= worst.rounding || mid <= worst.a || mid >= worst.b {
            return Err(fail());
        }
        heap.push(kronrod21(&f, worst.a, mid));
        heap.push(kronrod21(&f, mid, worst.b));
        evaluations += 2 * RULE_EVALUATIONS;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_two() {
        // Both rules integrate 1 over [−1, 1] exactly.
        let kronrod = WGK[10] + 2.0 * WGK[..10].iter().sum::<f64>();
        let gauss = 2.0 * WG.iter().sum::<f64>();
        assert!((kronrod - 2.0).abs() < 4.0 * f64::EPSILON);
        assert!((gauss - 2.0).abs() < 4.0 * f64::EPSILON);
    }

    #[test]
    fn single_rule_is_exact_for_degree_31() {
        // ∫_{-1}^{1} x^30 dx = 2/31; the Kronrod rule is exact to degree 31.
        let s = kronrod21(&|x: f64| x.powi(30) + x.powi(31), -1.0, 1.0);
        assert!((s.value - 2.0 / 31.0).abs() < 1e-15);
    }

    #[test]
    fn reports_budget_exhaustion() {
        let options = QuadratureOptions {
            abs_tol: 1e-14,
            rel_tol: 0.0,
            max_evaluations: 100,
        };
        let r = integrate(|x: f64| (1.0 / x).sin(), 1e-6, 1.0, &options);
        assert!(
            matches!(r, Err(MathError::QuadratureNotConverged { .. })),
            "{r:?}"
        );
    }

    #[test]
    fn reversed_bounds_negate() {
        let o = QuadratureOptions::default();
        let q = integrate(f64::exp, 1.0, 0.0, &o).unwrap();
        assert!((q.value + (1f64.exp() - 1.0)).abs() < 1e-13);
        assert!(q.evaluations >= RULE_EVALUATIONS);
    }
}
