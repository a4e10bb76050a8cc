//! Gauss–Kronrod quadrature against polynomials and known integrals.

use karman_math::{MathError, QuadratureOptions, integrate};
use proptest::prelude::*;

fn tight() -> QuadratureOptions {
    QuadratureOptions {
        abs_tol: 1e-13,
        rel_tol: 1e-13,
        max_evaluations: 200_000,
    }
}

proptest! {
    #[test]
    fn cubic_polynomials_are_exact(
        c in prop::collection::vec(-10.0..10.0f64, 4),
        a in -10.0..10.0f64,
        width in 0.01..20.0f64,
    ) {
        let b = a + width;
        let p = |x: f64| c[0] + x * (c[1] + x * (c[2] + x * c[3]));
        let prim = |x: f64| x * (c[0] + x * (c[1] / 2.0 + x * (c[2] / 3.0 + x * c[3] / 4.0)));
        // A single 21-point rule is exact to degree 31; the tolerance covers the rounding of
        // the sums, whose size is ∫|p| ≤ width · max|p|. The request is absolute at that
        // size: a relative request on an integral that cancels to almost nothing cannot be
        // met through rounding, and the integrator rightly says so (an error, tested in
        // `budget_and_bad_input_are_errors`-style tests), which is not what this property is
        // about.
        let size = width * (1.0 + c.iter().map(|k| k.abs()).sum::<f64>() * 20f64.powi(3));
        let options = QuadratureOptions { abs_tol: 1e-12 * size, rel_tol: 0.0, ..Default::default() };
        let q = integrate(p, a, b, &options).unwrap();
        let exact = prim(b) - prim(a);
        prop_assert!((q.value - exact).abs() <= 1e-12 * size, "{} vs {exact}", q.value);
        prop_assert_eq!(q.evaluations, 21);
    }

    #[test]
    fn exponential_on_random_intervals(a in -5.0..5.0f64, width in -10.0..10.0f64) {
        let b = a + width;
        let q = integrate(f64::exp, a, b, &tight()).unwrap();
        let exact = b.exp() - a.exp();
        prop_assert!((q.value - exact).abs() <= 1e-10 * (1.0 + exact.abs()));
    }
}

#[test]
fn known_integrals() {
    // ∫_0^π sin = 2.
    let q = integrate(f64::sin, 0.0, std::f64::consts::PI, &tight()).unwrap();
    assert!((q.value - 2.0).abs() < 1e-10, "{q:?}");
    // ∫_0^1 x^{-1/2} = 2: integrable endpoint singularity, resolved by repeated bisection.
    let q = integrate(|x: f64| 1.0 / x.sqrt(), 0.0, 1.0, &tight()).unwrap();
    assert!((q.value - 2.0).abs() < 1e-10, "{q:?}");
    assert!(q.abs_error <= 2e-13, "{q:?}");
    // ∫_0^1 e^x = e − 1.
    let q = integrate(f64::exp, 0.0, 1.0, &tight()).unwrap();
    assert!((q.value - (1f64.exp() - 1.0)).abs() < 1e-13, "{q:?}");
    // ∫_0^1 ln x = −1.
    let q = integrate(f64::ln, 0.0, 1.0, &tight()).unwrap();
    assert!((q.value + 1.0).abs() < 1e-10, "{q:?}");
}

#[test]
fn error_estimate_bounds_the_true_error() {
    // A peaked integrand with a loose tolerance: the estimate must still cover the error.
    let options = QuadratureOptions {
        abs_tol: 1e-6,
        rel_tol: 0.0,
        max_evaluations: 10_000,
    };
    let f = |x: f64| 1.0 / (1e-4 + x * x);
    let q = integrate(f, -1.0, 1.0, &options).unwrap();
    let exact = 2.0 * (1.0f64 / 1e-2).atan() / 1e-2;
    assert!((q.value - exact).abs() <= q.abs_error, "{q:?} vs {exact}");
}

#[test]
fn budget_and_bad_input_are_errors() {
    let options = QuadratureOptions {
        abs_tol: 1e-15,
        rel_tol: 0.0,
        max_evaluations: 200,
    };
    assert!(matches!(
        integrate(|x: f64| (1.0 / x).sin(), 1e-8, 1.0, &options),
        Err(MathError::QuadratureNotConverged { .. })
    ));
    assert!(matches!(
        integrate(f64::exp, 0.0, f64::INFINITY, &tight()),
        Err(MathError::InvalidInterval { .. })
    ));
    assert!(matches!(
        integrate(|_| f64::NAN, 0.0, 1.0, &tight()),
        Err(MathError::QuadratureNotConverged { .. })
    ));
}

#[test]
fn a_request_below_the_rounding_of_a_cancelling_integral_is_an_error_with_the_value() {
    // ∫ x³ over [−10, 10 + 1e-7] ≈ 1e-4 while ∫|x³| ≈ 5000: rounding in the sums (about
    // 50 ε · 5000 ≈ 6e-11) exceeds the default request (1e-12 absolute), so the integrator
    // reports that it cannot meet it, with the best value it has.
    let b: f64 = 10.0 + 1e-7;
    let exact = (b.powi(4) - 10f64.powi(4)) / 4.0;
    match integrate(|x: f64| x * x * x, -10.0, b, &QuadratureOptions::default()) {
        Err(MathError::QuadratureNotConverged {
            value, abs_error, ..
        }) => {
            assert!(
                (value - exact).abs() <= abs_error.max(1e-9),
                "{value} vs {exact}"
            );
        }
        other => panic!("expected QuadratureNotConverged, got {other:?}"),
    }
}
