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

#[test]
fn each_body_of_a_study_gets_its_own_ellipses() {
    use karman_dispersion::{BodyPoints, Points, Row, Status, Study, summarize_rows};
    let names = ["x", "y", "booster.x", "booster.y"].map(str::to_owned);
    let mut study = Study::new(5, 200, Vec::new(), names.to_vec());
    study.points = Points {
        landing: Some(["x".into(), "y".into()]),
        body: Some("sustainer".into()),
        bodies: vec![BodyPoints {
            name: "booster".into(),
            apogee: None,
            landing: Some(["booster.x".into(), "booster.y".into()]),
        }],
        ..Points::default()
    };
    study.validate().expect("valid study");
    // Two clouds: the first 200 points of `cloud()` for the sustainer, the booster's half as
    // far from the pad and a quarter as spread; the booster is missing from the last row and
    // a failed sample counts for neither.
    let points = cloud();
    let mut rows: Vec<Row> = (0..200)
        .map(|i| {
            let [x, y] = points[i];
            let booster = (i < 199).then_some([0.5 * x, 0.5 * y]);
            Row {
                index: i as u64,
                status: Status::Completed,
                inputs: Vec::new(),
                outputs: vec![
                    Some(x),
                    Some(y),
                    booster.map(|b| b[0]),
                    booster.map(|b| b[1]),
                ],
            }
        })
        .collect();
    rows[7].status = Status::Failed("diverged".into());
    let summary = summarize_rows(&study, &rows);
    assert_eq!(summary.ellipses.len(), 2);
    let completed = |take: usize| -> Vec<usize> { (0..take).filter(|&i| i != 7).collect() };
    let sustainer: Vec<[f64; 2]> = completed(200).iter().map(|&i| points[i]).collect();
    let booster: Vec<[f64; 2]> = completed(199)
        .iter()
        .map(|&i| [0.5 * points[i][0], 0.5 * points[i][1]])
        .collect();
    for (ellipse, body, cloud) in [
        (&summary.ellipses[0], "sustainer", &sustainer),
        (&summary.ellipses[1], "booster", &booster),
    ] {
        let fit = Ellipse::fit(cloud).expect("fit");
        assert_eq!(ellipse.body.as_deref(), Some(body));
        assert_eq!(ellipse.name, "landing");
        assert_eq!(ellipse.points, cloud.len() as u64);
        for (a, b) in ellipse.center_m.iter().zip(&fit.center) {
            assert!((a - b).abs() < 1e-9 * (1.0 + b.abs()), "{body}: {a} vs {b}");
        }
        let semi = fit.semi_axes(1.0);
        let k1 = &ellipse.k_sigma_rocketpy[0];
        assert!((k1.semi_major_m - semi[0]).abs() < 1e-9 * semi[0], "{body}");
        assert!((k1.semi_minor_m - semi[1]).abs() < 1e-9 * semi[1], "{body}");
    }
    // The booster's cloud is half the size of the sustainer's.
    let ratio = summary.ellipses[1].k_sigma_rocketpy[0].semi_major_m
        / summary.ellipses[0].k_sigma_rocketpy[0].semi_major_m;
    assert!((ratio - 0.5).abs() < 0.02, "{ratio}");
    // A study of one body says nothing of bodies in its summary.
    let mut single = study.clone();
    single.points.body = None;
    single.points.bodies.clear();
    let text = serde_json::to_string(&summarize_rows(&single, &rows)).expect("JSON");
    assert!(!text.contains("\"body\""), "{text}");
}

#[test]
fn body_names_are_checked() {
    use karman_dispersion::{BodyPoints, Points, Study};
    let names = ["x", "y"].map(str::to_owned);
    let other = |name: &str, landing: [&str; 2]| BodyPoints {
        name: name.into(),
        apogee: None,
        landing: Some(landing.map(str::to_owned)),
    };
    for (body, bodies) in [
        (Some("a"), vec![other("a", ["x", "y"])]),
        (None, vec![other("b", ["x", "y"])]),
        (Some("a"), vec![other("b", ["x", "z"])]),
        (Some(""), Vec::new()),
    ] {
        let mut study = Study::new(1, 10, Vec::new(), names.to_vec());
        study.points = Points {
            body: body.map(str::to_owned),
            bodies,
            ..Points::default()
        };
        assert!(study.validate().is_err(), "{:?}", study.points);
    }
}
