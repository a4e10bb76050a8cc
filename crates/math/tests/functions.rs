//! [`Function`] arithmetic, calculus and extrema against pointwise definitions.

use karman_math::{Extrapolation, Function, Interpolation, Table1};
use proptest::prelude::*;

fn table(xs: &[f64], ys: &[f64], interp: Interpolation) -> Function {
    Function::table(Table1::new(xs.to_vec(), ys.to_vec(), interp, Extrapolation::Natural).unwrap())
}

proptest! {
    #[test]
    fn arithmetic_is_pointwise(
        ys in prop::collection::vec(-10.0..10.0f64, 6),
        zs in prop::collection::vec(1.0..10.0f64, 5),
        k in -5.0..5.0f64,
        x in -1.0..6.0f64,
    ) {
        let f = table(&[0.0, 1.0, 2.0, 3.0, 4.0, 5.0], &ys, Interpolation::Spline);
        let g = table(&[-0.5, 1.5, 2.0, 4.0, 5.5], &zs, Interpolation::Linear);
        let (fx, gx) = (f.eval(x), g.eval(x));
        let cases = [
            (&f + &g, fx + gx),
            (&f - &g, fx - gx),
            (&f * &g, fx * gx),
            (&f / &g, fx / gx),
            (k * &f + 1.5, k * fx + 1.5),
            (&f / 4.0 - k, fx / 4.0 - k),
            (k - &g, k - gx),
            (-&f, -fx),
        ];
        for (h, expected) in cases {
            prop_assert!((h.eval(x) - expected).abs() <= 1e-12 * (1.0 + expected.abs()), "{h:?}");
        }
        let composed = g.compose(&f);
        prop_assert!((composed.eval(x) - g.eval(fx)).abs() <= 1e-12 * (1.0 + gx.abs()));
    }

    #[test]
    fn derivatives_follow_the_rules(
        ys in prop::collection::vec(-10.0..10.0f64, 6),
        x in 0.05..4.95f64,
    ) {
        let f = table(&[0.0, 1.0, 2.0, 3.0, 4.0, 5.0], &ys, Interpolation::Akima);
        let s = Function::analytic(f64::sin);
        let h = &f * &s + &s / 2.0;
        // Reference: central difference of h with a small step away from the table's nodes.
        prop_assume!((x - x.round()).abs() > 1e-3);
        let e = 1e-6;
        let numeric = (h.eval(x + e) - h.eval(x - e)) / (2.0 * e);
        prop_assert!((h.derivative(x) - numeric).abs() <= 1e-6 * (1.0 + numeric.abs()));
    }

    #[test]
    fn linear_table_extrema_are_exact(
        ys in prop::collection::vec(-10.0..10.0f64, 8),
        a in -1.0..3.0f64,
        width in 0.0..6.0f64,
    ) {
        let xs = [0.0, 0.5, 1.0, 2.0, 3.0, 4.0, 4.5, 6.0];
        let f = table(&xs, &ys, Interpolation::Linear);
        let b = a + width;
        // The extremes of a piecewise-linear function lie at the ends or at nodes.
        let candidates = xs.iter().copied().filter(|&x| x > a && x < b).chain([a, b]);
        let (lo, hi) = candidates.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(f.eval(x)), hi.max(f.eval(x)))
        });
        prop_assert!((f.maximum(a, b).unwrap().value - hi).abs() <= 1e-12);
        prop_assert!((f.minimum(a, b).unwrap().value - lo).abs() <= 1e-12);
    }
}

#[test]
fn integral_of_products_of_tables_uses_their_nodes() {
    let xs = [0.0, 1.0, 2.5, 4.0];
    let f = table(&xs, &[1.0, 3.0, -1.0, 2.0], Interpolation::Linear);
    let g = table(&[0.5, 3.0], &[2.0, 7.0], Interpolation::Linear);
    let h = &f * &g;
    // Reference: h is piecewise quadratic between {0, 0.5, 1, 2.5, 3, 4}; Simpson's rule is
    // exact on each piece.
    let knots = [0.0, 0.5, 1.0, 2.5, 3.0, 4.0];
    let simpson: f64 = knots
        .windows(2)
        .map(|w| {
            (w[1] - w[0]) / 6.0 * (h.eval(w[0]) + 4.0 * h.eval(0.5 * (w[0] + w[1])) + h.eval(w[1]))
        })
        .sum();
    let q = h.integral(0.0, 4.0).unwrap();
    assert!((q.value - simpson).abs() < 1e-12, "{q:?} vs {simpson}");
}

#[test]
fn smooth_closure_extrema_are_refined() {
    let f = Function::analytic(|x: f64| (3.0 * x).sin() * (-0.2 * x).exp());
    let m = f.maximum(0.0, 3.0).unwrap();
    // Stationary point of sin(3x)e^{-0.2x}: tan(3x) = 15, first root.
    let x_star = 15f64.atan() / 3.0;
    assert!((m.x - x_star).abs() < 1e-6, "{m:?} vs {x_star}");
    assert!((m.value - f.eval(x_star)).abs() < 1e-12);
}
