//! Property tests of [`Table1`] interpolants: node reproduction, smoothness at the nodes,
//! exact integrals, cursor lookups and repeated abscissae.

use karman_math::{Cursor, Extrapolation, Interpolation, QuadratureOptions, Table1, quadrature};
use proptest::prelude::*;

const PIECEWISE: [Interpolation; 3] = [
    Interpolation::Linear,
    Interpolation::Spline,
    Interpolation::Akima,
];

/// Strictly increasing abscissae (steps 0.05–5 from a start in [−50, 50]) with values.
fn samples(max_len: usize) -> impl Strategy<Value = (Vec<f64>, Vec<f64>)> {
    (2..max_len).prop_flat_map(|n| {
        (
            -50.0..50.0f64,
            prop::collection::vec(0.05..5.0f64, n - 1),
            prop::collection::vec(-1e3..1e3f64, n),
        )
            .prop_map(|(start, steps, ys)| {
                let mut xs = vec![start];
                for s in steps {
                    let last = xs[xs.len() - 1];
                    xs.push(last + s);
                }
                (xs, ys)
            })
    })
}

fn scale(ys: &[f64]) -> f64 {
    ys.iter().fold(1.0f64, |m, y| m.max(y.abs()))
}

proptest! {
    #[test]
    fn every_interpolant_reproduces_its_nodes((xs, ys) in samples(40)) {
        let tol = 1e-11 * scale(&ys);
        for interp in PIECEWISE {
            let t = Table1::new(xs.clone(), ys.clone(), interp, Extrapolation::Natural).unwrap();
            for (x, y) in xs.iter().zip(&ys) {
                prop_assert!((t.eval(*x) - y).abs() <= tol, "{interp:?} at {x}: {} vs {y}", t.eval(*x));
            }
        }
    }

    #[test]
    fn polynomial_reproduces_its_nodes((xs, ys) in samples(8)) {
        // Up to degree 6 on steps ≥ 0.05: the scaled Vandermonde system stays well
        // conditioned enough for a backward-stable LU to give residuals near rounding.
        let t = Table1::new(xs.clone(), ys.clone(), Interpolation::Polynomial, Extrapolation::Natural)
            .unwrap();
        for (x, y) in xs.iter().zip(&ys) {
            prop_assert!((t.eval(*x) - y).abs() <= 1e-7 * scale(&ys), "{x}: {} vs {y}", t.eval(*x));
        }
    }

    #[test]
    fn hermite_interpolants_are_c1_and_spline_c2((xs, ys) in samples(30)) {
        // The slope at a node from the left piece (bisect_left) vs from the right piece
        // evaluated at the node's successor float; the change over one ulp of x is below the
        // tolerance (second derivatives are ≲ 1e3/0.05² here).
        let slope_scale = scale(&ys) / 0.05;
        for interp in [Interpolation::Spline, Interpolation::Akima] {
            let t = Table1::new(xs.clone(), ys.clone(), interp, Extrapolation::Natural).unwrap();
            for &x in &xs[1..xs.len() - 1] {
                let right = x.next_up();
                let (dl, dr) = (t.derivative(x), t.derivative(right));
                prop_assert!((dl - dr).abs() <= 1e-9 * slope_scale, "{interp:?} C1 at {x}: {dl} vs {dr}");
                if interp == Interpolation::Spline {
                    let (sl, sr) = (t.second_derivative(x), t.second_derivative(right));
                    prop_assert!((sl - sr).abs() <= 1e-9 * slope_scale / 0.05, "C2 at {x}: {sl} vs {sr}");
                }
            }
        }
    }

    #[test]
    fn exact_integrals_of_low_degree_polynomials(
        (xs, _) in samples(12),
        c in prop::collection::vec(-10.0..10.0f64, 4),
    ) {
        // Linear and natural-spline tables reproduce degree ≤ 1 exactly, the interpolating
        // polynomial (4 to 8 samples) degree ≤ 3, so their exact integrals are the
        // polynomial's. More samples give a high-degree global polynomial whose Vandermonde
        // system is ill-conditioned on clustered nodes (the method's nature, not a defect):
        // its rounding is not the quantity under test.
        let p = |x: f64, deg: usize| c.iter().take(deg + 1).rev().fold(0.0, |acc, k| acc * x + k);
        let prim = |x: f64, deg: usize| {
            x * c.iter().take(deg + 1).enumerate().rev().fold(0.0, |acc, (k, ck)| acc * x + ck / (k + 1) as f64)
        };
        let (a, b) = (xs[0] - 1.0, xs[xs.len() - 1] + 1.0);
        let mag = |deg: usize| 1.0 + (b - a) * (0..=deg).map(|k| c[k].abs() * a.abs().max(b.abs()).powi(k as i32)).sum::<f64>();
        for (interp, deg) in [(Interpolation::Linear, 1), (Interpolation::Spline, 1), (Interpolation::Polynomial, 3)] {
            if interp == Interpolation::Polynomial && !(4..=8).contains(&xs.len()) {
                continue;
            }
            let ys: Vec<f64> = xs.iter().map(|&x| p(x, deg)).collect();
            let t = Table1::new(xs.clone(), ys, interp, Extrapolation::Natural).unwrap();
            let exact = prim(b, deg) - prim(a, deg);
            prop_assert!((t.integral(a, b) - exact).abs() <= 1e-11 * mag(deg), "{interp:?}: {} vs {exact}", t.integral(a, b));
        }
    }

    #[test]
    fn table_integral_matches_gauss_kronrod((xs, ys) in samples(20)) {
        for interp in PIECEWISE {
            let t = Table1::new(xs.clone(), ys.clone(), interp, Extrapolation::Constant).unwrap();
            let (a, b) = (xs[0] - 0.5, xs[xs.len() - 1] + 0.5);
            let mut points = vec![a];
            points.extend_from_slice(&xs);
            points.push(b);
            // The tolerance is relative to ∫|f| (≤ scale·width): the integral itself may
            // cancel to a value far below the rounding of the sum.
            let tol = 1e-10 * scale(&ys) * (b - a);
            let options = QuadratureOptions { abs_tol: tol / 4.0, rel_tol: 0.0, ..Default::default() };
            let q = quadrature::integrate_breakpoints(|x| t.eval(x), &points, &options).unwrap();
            prop_assert!((q.value - t.integral(a, b)).abs() <= tol, "{interp:?}: {} vs {}", q.value, t.integral(a, b));
        }
    }

    #[test]
    fn cursor_lookup_equals_binary_search(
        (xs, ys) in samples(30),
        queries in prop::collection::vec(-60.0..200.0f64, 1..50),
    ) {
        for interp in PIECEWISE {
            let t = Table1::new(xs.clone(), ys.clone(), interp, Extrapolation::Natural).unwrap();
            let mut cursor = Cursor::default();
            let mut sorted = queries.clone();
            sorted.sort_by(f64::total_cmp);
            for &x in queries.iter().chain(&sorted).chain(&xs) {
                let (a, b) = (t.eval_with(x, &mut cursor), t.eval(x));
                prop_assert!((a - b).abs() <= 1e-12 * scale(&ys), "{interp:?} at {x}");
            }
        }
    }

    #[test]
    fn stepwise_tables_follow_bisect_left(
        (xs, ys) in samples(15),
        repeats in prop::collection::vec(1usize..4, 15),
    ) {
        // Repeat each abscissa 1–3 times with distinct values.
        let (mut rx, mut ry, mut groups) = (Vec::new(), Vec::new(), Vec::new());
        for (k, (&x, &y)) in xs.iter().zip(&ys).enumerate() {
            let first = rx.len();
            for r in 0..repeats[k] {
                rx.push(x);
                ry.push(y + r as f64);
            }
            groups.push((x, first, rx.len() - 1));
        }
        let t = Table1::linear_stepwise(rx, ry.clone(), Extrapolation::Constant).unwrap();
        for (k, &(x, first, last)) in groups.iter().enumerate() {
            prop_assert!((t.eval(x) - ry[first]).abs() <= 1e-12 * scale(&ry), "first duplicate at {x}");
            if k + 1 < groups.len() {
                let right = x + 1e-9 * (groups[k + 1].0 - x);
                prop_assert!((t.eval(right) - ry[last]).abs() <= 1e-6 * scale(&ry), "last duplicate right of {x}");
            }
        }
    }
}

/// RocketPy's linear interpolation, written from its definition (`bisect_left`, then the
/// line through the interval's ends), as the reference for the bucket-indexed lookup.
fn rocketpy_linear(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let n = xs.len();
    if x < xs[0] {
        return ys[0];
    }
    if x > xs[n - 1] {
        return ys[n - 1];
    }
    let i = xs.partition_point(|&v| v < x);
    if i == 0 {
        // x = x_0: Python's index −1 wraps to the last point, and the line from it through
        // (x_0, y_0) gives y_0 there.
        return ys[0];
    }
    // Here x_{i−1} < x ≤ x_i, so the interval has positive width.
    let (xl, yl) = (xs[i - 1], ys[i - 1]);
    (x - xl) * ((ys[i] - yl) / (xs[i] - xl)) + yl
}

proptest! {
    #[test]
    fn bucket_lookup_matches_bisect_left(
        steps in prop::collection::vec(prop_oneof![Just(0.0), 1e-12..1e-9f64, 1e-3..1.0f64, 10.0..1e3f64], 1..60),
        ys in prop::collection::vec(-1e3..1e3f64, 61),
        fractions in prop::collection::vec(-0.1..1.1f64, 20),
    ) {
        // Clustered, widely spread and repeated abscissae (a first step of 0 is allowed).
        let mut xs = vec![-3.0];
        for s in &steps {
            let last = xs[xs.len() - 1];
            xs.push(last + s);
        }
        let ys = &ys[..xs.len()];
        prop_assume!(xs[xs.len() - 1] > xs[0]);
        let t = Table1::linear_stepwise(xs.clone(), ys.to_vec(), Extrapolation::Constant).unwrap();
        let span = xs[xs.len() - 1] - xs[0];
        let queries = xs
            .iter()
            .flat_map(|&x| [x, x.next_up(), x.next_down()])
            .chain(fractions.iter().map(|f| xs[0] + f * span));
        for x in queries {
            let (got, want) = (t.eval(x), rocketpy_linear(&xs, ys, x));
            prop_assert!((got - want).abs() <= 1e-9 * scale(ys), "x = {x}: {got} vs {want}");
        }
    }
}
