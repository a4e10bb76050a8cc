//! Sobol indices by Saltelli's design against analytic values.

use karman_dispersion::{Distribution, Target, Variation, VariedInput, sobol};

fn uniform(name: &str, low: f64, high: f64) -> VariedInput {
    VariedInput::new(
        name,
        Target::Number(0.0),
        Variation::Value(Distribution::Uniform { low, high }),
    )
}

#[test]
fn an_additive_output_has_its_analytic_indices() {
    // y = x1 + 2 x2 + 3 x3 with x_i uniform on (0, 1): V_i = a_i² / 12, so
    // S_i = S_Ti = a_i² / Σ a² = 1/14, 4/14, 9/14.
    let inputs = [
        uniform("x1", 0.0, 1.0),
        uniform("x2", 0.0, 1.0),
        uniform("x3", 0.0, 1.0),
    ];
    let s = sobol(5, 8192, &inputs, |x| x[0] + 2.0 * x[1] + 3.0 * x[2]).expect("indices");
    assert_eq!(s.evaluations, 5 * 8192);
    for (i, expected) in [1.0 / 14.0, 4.0 / 14.0, 9.0 / 14.0].into_iter().enumerate() {
        assert!(
            (s.first[i] - expected).abs() < 0.02,
            "S_{i} = {} vs {expected}",
            s.first[i]
        );
        assert!(
            (s.total[i] - expected).abs() < 0.02,
            "ST_{i} = {} vs {expected}",
            s.total[i]
        );
    }
}

#[test]
fn the_ishigami_function_has_its_analytic_indices() {
    // Ishigami & Homma (1990), a = 7, b = 0.1, x_i uniform on (−π, π): S1 = 0.3139,
    // S2 = 0.4424, S3 = 0; ST1 = 0.5576, ST2 = 0.4424, ST3 = 0.2437 (Saltelli et al. 2010,
    // §4; Sobol & Levitan 1999). x3 acts only with x1: first order 0, total not.
    let pi = std::f64::consts::PI;
    let inputs = [
        uniform("x1", -pi, pi),
        uniform("x2", -pi, pi),
        uniform("x3", -pi, pi),
    ];
    let s = sobol(11, 32768, &inputs, |x| {
        x[0].sin() + 7.0 * x[1].sin().powi(2) + 0.1 * x[2].powi(4) * x[0].sin()
    })
    .expect("indices");
    for (i, (first, total)) in [(0.3139, 0.5576), (0.4424, 0.4424), (0.0, 0.2437)]
        .into_iter()
        .enumerate()
    {
        assert!(
            (s.first[i] - first).abs() < 0.02,
            "S_{i} = {} vs {first}",
            s.first[i]
        );
        assert!(
            (s.total[i] - total).abs() < 0.02,
            "ST_{i} = {} vs {total}",
            s.total[i]
        );
    }
}

#[test]
fn a_design_with_a_missing_value_is_refused() {
    let names = ["x".to_owned()];
    let mut values = vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
    values[4] = f64::NAN;
    let error = karman_dispersion::sobol_indices(&names, 2, &values).unwrap_err();
    assert!(error.to_string().contains("row 4"), "{error}");
    let error = karman_dispersion::sobol_indices(&names, 2, &values[..5]).unwrap_err();
    assert!(error.to_string().contains("has 6 rows, got 5"), "{error}");
}
