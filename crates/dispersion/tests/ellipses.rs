//! Ellipses of a synthetic Gaussian cloud of known covariance.

use karman_dispersion::sampling::sample_rng;
use karman_dispersion::{
    Ellipse, NORMAL_SIGMA_PROBABILITY, k_sigma_probability, probability_scale,
};
use rand_distr::{Distribution as _, StandardNormal};

const POINTS: usize = 100_000;

/// 1e5 points, centre (100, −50), standard deviations 20 m and 5 m, major axis at 30° from
/// east.
fn cloud() -> Vec<[f64; 2]> {
    let mut rng = sample_rng(1, 0, 0);
    let (sin_t, cos_t) = 30f64.to_radians().sin_cos();
    (0..POINTS)
        .map(|_| {
            let z: [f64; 2] = [
                StandardNormal.sample(&mut rng),
                StandardNormal.sample(&mut rng),
            ];
            let (u, v) = (20.0 * z[0], 5.0 * z[1]);
            [100.0 + cos_t * u - sin_t * v, -50.0 + sin_t * u + cos_t * v]
        })
        .collect()
}

/// Squared Mahalanobis distance of `p` from the ellipse's centre.
fn distance2(e: &Ellipse, p: &[f64; 2]) -> f64 {
    let (sin_t, cos_t) = e.orientation_deg.to_radians().sin_cos();
    let (dx, dy) = (p[0] - e.center[0], p[1] - e.center[1]);
    let u = cos_t * dx + sin_t * dy;
    let v = -sin_t * dx + cos_t * dy;
    u * u / e.eigenvalues[0] + v * v / e.eigenvalues[1]
}

#[test]
fn ellipse_of_a_known_gaussian_cloud() {
    let points = cloud();
    let e = Ellipse::fit(&points).expect("fit");
    // Relative standard error of a variance estimate: sqrt(2/n) = 0.45 %; 1 % is > 2 of them.
    assert!(
        (e.eigenvalues[0] / 400.0 - 1.0).abs() < 0.01,
        "{:?}",
        e.eigenvalues
    );
    assert!(
        (e.eigenvalues[1] / 25.0 - 1.0).abs() < 0.01,
        "{:?}",
        e.eigenvalues
    );
    let [a, b] = e.semi_axes(2.0);
    assert!(
        (a / 40.0 - 1.0).abs() < 0.01 && (b / 10.0 - 1.0).abs() < 0.01,
        "{a} {b}"
    );
    // The angle's standard error is about sqrt(λ1 λ2 / n) / (λ1 − λ2) rad = 0.01°.
    assert!(
        (e.orientation_deg - 30.0).abs() < 0.1,
        "{}",
        e.orientation_deg
    );
    // Centre: standard error 20/sqrt(n) = 0.063 m.
    assert!((e.center[0] - 100.0).abs() < 0.3 && (e.center[1] + 50.0).abs() < 0.3);

    // Coverage: the k-σ ellipses hold 1 − exp(−k²/2), the probability ellipses p.
    let inside =
        |k: f64| points.iter().filter(|p| distance2(&e, p) <= k * k).count() as f64 / POINTS as f64;
    let binomial = |p: f64| 5.0 * (p * (1.0 - p) / POINTS as f64).sqrt();
    for k in [1.0, 2.0, 3.0] {
        let p = k_sigma_probability(k);
        assert!(
            (inside(k) - p).abs() < binomial(p),
            "k = {k}: {} vs {p}",
            inside(k)
        );
    }
    for p in NORMAL_SIGMA_PROBABILITY {
        let k = probability_scale(p);
        assert!(
            (inside(k) - p).abs() < binomial(p),
            "p = {p}: {}",
            inside(k)
        );
    }
}

#[test]
fn boundary_points_lie_on_the_contour() {
    let e = Ellipse::fit(&cloud()).expect("fit");
    for p in e.boundary(3.0, 100) {
        assert!((distance2(&e, &p) - 9.0).abs() < 1e-9);
    }
}
