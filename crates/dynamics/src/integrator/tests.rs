//! Tests of the integrators.

#![allow(clippy::unreadable_literal)]

use super::*;
use crate::DynamicsError;

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
fn dense_derivative_is_the_slope_of_the_dense_output() {
    // y'' = −y: the interpolant's slope equals the right-hand side at both step ends, the
    // central difference of the dense output inside, and cos/−sin to the tolerance level.
    for pair in PAIRS {
        let f = |_t: f64, y: &[f64; 2]| [y[1], -y[0]];
        let mut rk = RungeKutta::new(pair, f, 0.0, [0.0, 1.0], 6.0, tol(1e-8, 1e-10)).unwrap();
        let mut worst: f64 = 0.0;
        loop {
            let status = rk.step().unwrap();
            let (t0, t1, h) = (rk.t_old(), rk.t(), rk.last_step());
            let (f0, f1) = (*rk.f_old(), *rk.f());
            for i in 0..2 {
                let (d0, d1) = (
                    rk.dense_derivative_component(t0, i),
                    rk.dense_derivative_component(t1, i),
                );
                assert!(
                    (d0 - f0[i]).abs() < 1e-12,
                    "{pair:?} start: {d0} vs {}",
                    f0[i]
                );
                assert!(
                    (d1 - f1[i]).abs() < 1e-12,
                    "{pair:?} end: {d1} vs {}",
                    f1[i]
                );
            }
            for k in 1..4 {
                let t = t0 + h * f64::from(k) / 4.0;
                // The difference's truncation error is O(dt²), its round-off O(ε/dt).
                let dt = 1e-3 * h;
                let bound = 1e-7 + 1e-14 / dt;
                let slope = [0, 1].map(|i| rk.dense_derivative_component(t, i));
                for (i, s) in slope.iter().enumerate() {
                    let fd = (rk.dense_component(t + dt, i) - rk.dense_component(t - dt, i))
                        / (2.0 * dt);
                    assert!((s - fd).abs() < bound, "{pair:?} at {t}: {s} vs {fd}");
                }
                worst = worst
                    .max((slope[0] - t.cos()).abs())
                    .max((slope[1] + t.sin()).abs());
            }
            if status == StepStatus::Finished {
                break;
            }
        }
        assert!(worst < 1e-4, "{pair:?}: derivative error {worst}");
    }
}

#[test]
fn dop853_dense_output_costs_three_evaluations_once_per_step() {
    let f = |_t: f64, y: &[f64; 2]| [y[1], -y[0]];
    let mut rk = RungeKutta::new(Pair::Dop853, f, 0.0, [0.0, 1.0], 10.0, tol(1e-8, 1e-10)).unwrap();
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
    let mut rk = RungeKutta::new(Pair::Rkc2, heat::<M>, 0.0, shape, 0.2, tol(1e-6, 1e-9)).unwrap();
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
    let mut rk = RungeKutta::new(Pair::Rkc2, f, 0.0, [0.0, 1.0], 10.0, tol(1e-8, 1e-10)).unwrap();
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
    // docs/physics.md §10.4: a zero derivative gives a zero error estimate; the controller grows
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
