//! N-dimensional tables: node reproduction, multilinear exactness, clamping, Shepard bounds;
//! triangulated tables: node reproduction, bounds inside the hull, planes everywhere.

use karman_math::{MathError, RegularGrid, ScatteredTable, TriangulatedTable};
use proptest::prelude::*;

/// A strictly increasing axis of 1–6 points.
fn axis() -> impl Strategy<Value = Vec<f64>> {
    (-10.0..10.0f64, prop::collection::vec(0.1..3.0f64, 0..5)).prop_map(|(start, steps)| {
        let mut a = vec![start];
        for s in steps {
            let last = a[a.len() - 1];
            a.push(last + s);
        }
        a
    })
}

proptest! {
    #[test]
    fn grid_reproduces_nodes_and_multilinear_functions(
        axes in prop::collection::vec(axis(), 1..4),
        c in prop::collection::vec(-5.0..5.0f64, 4),
        t in prop::collection::vec(-0.2..1.2f64, 3),
    ) {
        // f = c0 + Σ c_{k+1} x_k + product of all coordinates: multilinear, so the grid
        // interpolant equals f everywhere inside the grid.
        let f = |p: &[f64]| {
            c[0] + p.iter().enumerate().map(|(k, x)| c[k + 1] * x).sum::<f64>()
                + p.iter().product::<f64>()
        };
        let dims = axes.len();
        let total: usize = axes.iter().map(Vec::len).product();
        let node = |mut flat: usize| {
            let mut p = vec![0.0; dims];
            for k in (0..dims).rev() {
                p[k] = axes[k][flat % axes[k].len()];
                flat /= axes[k].len();
            }
            p
        };
        let values: Vec<f64> = (0..total).map(|i| f(&node(i))).collect();
        let grid = RegularGrid::new(axes.clone(), values.clone()).unwrap();
        for (i, v) in values.iter().enumerate() {
            prop_assert!((grid.eval(&node(i)) - v).abs() <= 1e-11 * (1.0 + v.abs()));
        }
        // A point at fractions t of each axis range; outside, coordinates are clamped.
        let p: Vec<f64> = axes.iter().zip(&t).map(|(a, tk)| a[0] + tk * (a[a.len() - 1] - a[0])).collect();
        let clamped: Vec<f64> = axes.iter().zip(&p).map(|(a, x)| x.clamp(a[0], a[a.len() - 1])).collect();
        let expected = f(&clamped);
        prop_assert!((grid.eval(&p) - expected).abs() <= 1e-10 * (1.0 + expected.abs()));
    }

    #[test]
    fn shepard_is_exact_at_nodes_and_within_bounds(
        nodes in prop::collection::vec(prop::collection::vec(-10.0..10.0f64, 2), 1..12),
        values in prop::collection::vec(-5.0..5.0f64, 12),
        query in prop::collection::vec(-12.0..12.0f64, 2),
        power in 1.0..4.0f64,
    ) {
        let values = &values[..nodes.len()];
        let flat: Vec<f64> = nodes.iter().flatten().copied().collect();
        let t = ScatteredTable::new(2, flat, values.to_vec(), power).unwrap();
        for (node, v) in nodes.iter().zip(values) {
            // The first node at distance zero wins when nodes coincide.
            let first = nodes.iter().position(|n| n == node).unwrap();
            prop_assert!((t.eval(node) - values[first]).abs() <= 1e-15, "{v}");
        }
        let (lo, hi) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(*v), h.max(*v)));
        let q = t.eval(&query);
        prop_assert!(q >= lo - 1e-12 && q <= hi + 1e-12, "{q} outside [{lo}, {hi}]");
    }

    #[test]
    fn triangulated_tables_are_exact_at_nodes_bounded_inside_and_exact_for_planes(
        nodes in prop::collection::vec((-10.0..10.0f64, -10.0..10.0f64), 3..25),
        values in prop::collection::vec(-5.0..5.0f64, 25),
        u in 0.0..1.0f64,
        v in 0.0..1.0f64,
        c in prop::collection::vec(-3.0..3.0f64, 3),
        far in (-30.0..30.0f64, -30.0..30.0f64),
    ) {
        // Grid-snapped coordinates also make repeated, collinear and cocircular points.
        let points: Vec<[f64; 2]> = nodes.iter().map(|&(x, y)| [x.round(), y.round()]).collect();
        let values = &values[..points.len()];
        let table = match TriangulatedTable::new(points.clone(), values.to_vec()) {
            Ok(t) => t,
            Err(MathError::RepeatedPoint { .. } | MathError::Collinear) => return Ok(()),
            Err(e) => return Err(TestCaseError::fail(format!("{e}"))),
        };
        for (p, v) in points.iter().zip(values) {
            prop_assert!((table.eval(p[0], p[1]) - v).abs() <= 1e-12, "node {p:?}");
        }
        // A point inside the triangle of three nodes is inside the hull: a convex combination.
        let [a, b, d] = [points[0], points[1], points[2]];
        let (s, t) = if u + v > 1.0 { (1.0 - u, 1.0 - v) } else { (u, v) };
        let q = [a[0] + s * (b[0] - a[0]) + t * (d[0] - a[0]), a[1] + s * (b[1] - a[1]) + t * (d[1] - a[1])];
        let (lo, hi) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(*v), h.max(*v)));
        let inside = table.eval(q[0], q[1]);
        prop_assert!(inside >= lo - 1e-9 && inside <= hi + 1e-9, "{inside} outside [{lo}, {hi}]");
        // A plane is reproduced inside the hull and, by the spline's linear part, outside.
        let plane = |p: [f64; 2]| c[0] + c[1] * p[0] + c[2] * p[1];
        let flat = TriangulatedTable::new(points.clone(), points.iter().map(|&p| plane(p)).collect()).unwrap();
        for p in [q, [far.0, far.1]] {
            let got = flat.eval(p[0], p[1]);
            prop_assert!((got - plane(p)).abs() <= 1e-7 * (1.0 + plane(p).abs()), "{p:?}: {got}");
        }
    }
}
