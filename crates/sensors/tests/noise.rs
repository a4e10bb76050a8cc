//! The noise model over long samples of a still input: the mean, standard deviation and
//! Allan deviation of the readings against the model's parameters (docs/physics.md §29.1),
//! within bounds stated with each check; and determinism of the seeded streams.

use karman_sensors::{NoiseParameters, Sensor, SensorKind, SensorSpec, Surroundings, Truth};

struct Site;
impl Surroundings for Site {
    fn pressure(&self, h: f64) -> f64 {
        101_325.0 - 12.0 * h
    }
    fn gravity(&self, _h: f64) -> f64 {
        9.80665
    }
    fn site(&self) -> [f64; 2] {
        [32.990254, -106.974998]
    }
    fn earth_radius(&self) -> f64 {
        6_371_000.0
    }
}

/// A still, upright rocket at 1400 m.
fn still() -> Truth {
    let mut u = [0.0; 13];
    u[2] = 1400.0;
    u[6] = 1.0;
    Truth {
        u,
        u_dot: [0.0; 13],
    }
}

fn gyro(noise: NoiseParameters, rate: f64, seed: u64, index: u64) -> Sensor {
    let mut spec = SensorSpec::new(
        "gyro",
        SensorKind::Gyroscope {
            acceleration_sensitivity: [0.0; 3],
        },
        rate,
        [0.0, 0.0, 0.4],
    );
    spec.noise = noise;
    Sensor::new(spec, seed, index).expect("valid sensor")
}

/// `n` readings of axis `axis`.
fn series(sensor: &mut Sensor, n: usize, axis: usize) -> Vec<f64> {
    let truth = still();
    (0..n)
        .map(|_| sensor.measure(&truth, &Site)[axis])
        .collect()
}

fn mean(x: &[f64]) -> f64 {
    x.iter().sum::<f64>() / x.len() as f64
}

fn std(x: &[f64]) -> f64 {
    let m = mean(x);
    (x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (x.len() - 1) as f64).sqrt()
}

/// Overlapping Allan variance of `y` at cluster size `m` (IEEE Std 952-1997, annex C).
fn allan_variance(y: &[f64], m: usize) -> f64 {
    let mut prefix = vec![0.0; y.len() + 1];
    for (i, v) in y.iter().enumerate() {
        prefix[i + 1] = prefix[i] + v;
    }
    let avg = |start: usize| (prefix[start + m] - prefix[start]) / m as f64;
    let count = y.len() + 1 - 2 * m;
    let sum: f64 = (0..count)
        .map(|j| (avg(j + m) - avg(j)).powi(2))
        .sum::<f64>();
    sum / (2.0 * count as f64)
}

#[test]
fn white_noise_and_bias_have_the_model_mean_and_standard_deviation() {
    let (rate, density, variance, bias): (f64, f64, f64, [f64; 3]) =
        (400.0, 2e-3, 2.5, [0.01, -0.02, 0.0]);
    let noise = NoiseParameters {
        noise_density: [density; 3],
        noise_variance: [variance; 3],
        constant_bias: bias,
        ..NoiseParameters::default()
    };
    let n = 200_000;
    let sigma = variance.sqrt() * density * rate.sqrt();
    let mut sensor = gyro(noise, rate, 11, 0);
    let truth = still();
    let readings: Vec<[f64; 3]> = (0..n).map(|_| sensor.measure(&truth, &Site)).collect();
    for axis in 0..3 {
        let x: Vec<f64> = readings.iter().map(|r| r[axis]).collect();
        // The mean's standard error is σ/√n; the sample standard deviation's is σ/√(2n).
        // Bounds: 5 standard errors (a chance below 1e-6 each of failing a correct model).
        let (m, s) = (mean(&x), std(&x));
        eprintln!(
            "axis {axis}: mean {m:.6e} (bias {}), std {s:.6e} (model {sigma:.6e})",
            bias[axis]
        );
        let se_mean = sigma / (n as f64).sqrt();
        let se_std = sigma / (2.0 * n as f64).sqrt();
        assert!(
            (m - bias[axis]).abs() < 5.0 * se_mean,
            "axis {axis}: mean {m}"
        );
        assert!(
            (s - sigma).abs() < 5.0 * se_std,
            "axis {axis}: std {s} vs {sigma}"
        );
        // White noise: Allan deviation σ/√m at cluster size m (a 10 % bound at m = 100,
        // where the overlapping estimator's relative error is about 1/√(n/m) ≈ 2 %).
        let avar = allan_variance(&x, 100);
        let expected = sigma * sigma / 100.0;
        assert!(
            (avar / expected - 1.0).abs() < 0.1,
            "axis {axis}: AVAR {avar} vs {expected}"
        );
    }
}

#[test]
fn the_random_walk_has_the_model_allan_deviation() {
    // Rate random walk K with unit variance V: per-sample increment variance q = K²V/f, and the
    // Allan variance of the readings at cluster size m is q (2m² + 1)/(6m) (≈ K²V τ/3 with
    // τ = m/f; the triangular weights of the increments in the difference of two cluster
    // means). 40 independent streams, each 20,000 samples; the mean Allan variance over the
    // streams must be within 4 standard errors (measured across the streams) of the model,
    // and that standard error below 10 % of it, so the check has teeth.
    let (rate, k, v): (f64, f64, f64) = (100.0, 0.05, 1.7);
    let noise = NoiseParameters {
        random_walk_density: [k; 3],
        random_walk_variance: [v; 3],
        ..NoiseParameters::default()
    };
    let q = k * k * v / rate;
    for m in [5usize, 50, 500] {
        let avars: Vec<f64> = (0..40)
            .map(|i| {
                let mut sensor = gyro(noise, rate, 3, i);
                allan_variance(&series(&mut sensor, 20_000, 2), m)
            })
            .collect();
        let expected = q * (2.0 * (m * m) as f64 + 1.0) / (6.0 * m as f64);
        let (mu, se) = (mean(&avars), std(&avars) / (avars.len() as f64).sqrt());
        eprintln!(
            "m = {m}: Allan variance {mu:.6e}, model {expected:.6e}, standard error {se:.3e}"
        );
        assert!(
            se < 0.1 * expected,
            "m = {m}: standard error {se} of {expected}"
        );
        assert!(
            (mu - expected).abs() < 4.0 * se,
            "m = {m}: Allan variance {mu} vs {expected} (se {se})"
        );
    }
}

#[test]
fn temperature_bias_scale_range_and_resolution_act_in_rocketpy_order() {
    // (x + b + ΔT b_T) (1 + ΔT/100 s_T), then clamped and quantised.
    let noise = NoiseParameters {
        constant_bias: [0.1; 3],
        operating_temperature: 308.15,
        temperature_bias: [0.01; 3],
        temperature_scale_factor: [0.5; 3],
        ..NoiseParameters::default()
    };
    let mut sensor = gyro(noise, 100.0, 0, 0);
    let mut truth = still();
    truth.u[10] = 1.0;
    let expected = (1.0 + 0.1 + 10.0 * 0.01) * (1.0 + 10.0 / 100.0 * 0.5);
    let w = sensor.measure(&truth, &Site);
    assert!((w[0] - expected).abs() < 1e-15, "{w:?}");
    assert!((w[1] - 0.2 * 1.05).abs() < 1e-15, "{w:?}");

    let noise = NoiseParameters {
        measurement_range: [-0.5, 0.75],
        resolution: 0.1,
        ..NoiseParameters::default()
    };
    let mut sensor = gyro(noise, 100.0, 0, 0);
    truth.u[10] = 2.0;
    truth.u[11] = -3.0;
    truth.u[12] = 0.25;
    let w = sensor.measure(&truth, &Site);
    // 0.75 → 7.5 steps → 8 (ties to even: 7.5 → 8), −0.5 → −5 steps, 0.25 → 2.5 → 2.
    assert_eq!(w.map(f64::to_bits), [0.8, -0.5, 0.2].map(f64::to_bits));
}

#[test]
fn cross_axis_sensitivity_mixes_the_axes() {
    let mut spec = SensorSpec::new(
        "gyro",
        SensorKind::Gyroscope {
            acceleration_sensitivity: [0.0; 3],
        },
        100.0,
        [0.0; 3],
    );
    spec.cross_axis_sensitivity = 2.0;
    let mut sensor = Sensor::new(spec, 0, 0).expect("sensor");
    let mut truth = still();
    truth.u[10] = 1.0;
    let w = sensor.measure(&truth, &Site);
    assert_eq!(w.map(f64::to_bits), [1.0, 0.02, 0.02].map(f64::to_bits));
}

#[test]
fn gnss_accuracy_is_the_spread_of_the_fix() {
    let spec = SensorSpec::new(
        "gps",
        SensorKind::Gnss {
            position_accuracy: 3.0,
            altitude_accuracy: 5.0,
        },
        10.0,
        [0.0; 3],
    );
    let mut sensor = Sensor::new(spec, 5, 2).expect("sensor");
    let truth = still();
    let n = 100_000;
    let fixes: Vec<[f64; 3]> = (0..n).map(|_| sensor.measure(&truth, &Site)).collect();
    let alt: Vec<f64> = fixes.iter().map(|f| f[2]).collect();
    let lat: Vec<f64> = fixes.iter().map(|f| f[0]).collect();
    let (se_mean, se_std) = (1.0 / (n as f64).sqrt(), 1.0 / (2.0 * n as f64).sqrt());
    assert!((mean(&alt) - 1400.0).abs() < 5.0 * 5.0 * se_mean);
    assert!(
        (std(&alt) - 5.0).abs() < 5.0 * 5.0 * se_std,
        "{}",
        std(&alt)
    );
    // One metre north is 1/R rad of latitude.
    let metre = (1.0 / 6_371_000.0f64).to_degrees();
    assert!(
        (std(&lat) / metre - 3.0).abs() < 5.0 * 3.0 * se_std,
        "{}",
        std(&lat) / metre
    );
    assert!(((mean(&lat) - 32.990254) / metre).abs() < 5.0 * 3.0 * se_mean);
}

#[test]
fn same_seed_same_readings_other_index_other_stream() {
    let noise = NoiseParameters {
        noise_density: [1e-3; 3],
        random_walk_density: [1e-3; 3],
        ..NoiseParameters::default()
    };
    let a = series(&mut gyro(noise, 100.0, 42, 1), 1000, 0);
    let b = series(&mut gyro(noise, 100.0, 42, 1), 1000, 0);
    let c = series(&mut gyro(noise, 100.0, 42, 2), 1000, 0);
    let d = series(&mut gyro(noise, 100.0, 43, 1), 1000, 0);
    let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a), bits(&b));
    assert_ne!(bits(&a), bits(&c));
    assert_ne!(bits(&a), bits(&d));
}

#[test]
fn bad_parameters_are_refused_by_name() {
    let spec = |noise: NoiseParameters| {
        let mut s = SensorSpec::new("baro", SensorKind::Barometer, 50.0, [0.0; 3]);
        s.noise = noise;
        s
    };
    let err = |s: SensorSpec| Sensor::new(s, 0, 0).expect_err("refused").to_string();
    let negative = NoiseParameters {
        noise_variance: [-1.0; 3],
        ..NoiseParameters::default()
    };
    assert!(err(spec(negative)).starts_with("noise_variance = -1"));
    let reversed = NoiseParameters {
        measurement_range: [2.0, 1.0],
        ..NoiseParameters::default()
    };
    assert!(err(spec(reversed)).starts_with("measurement_range"));
    let mut s = spec(NoiseParameters::default());
    s.sampling_rate = f64::NAN;
    assert!(err(s).starts_with("sampling_rate = NaN"));
    let mut s = spec(NoiseParameters::default());
    s.cross_axis_sensitivity = 101.0;
    assert!(err(s).starts_with("cross_axis_sensitivity"));
    let s = SensorSpec::new(
        "gps",
        SensorKind::Gnss {
            position_accuracy: -1.0,
            altitude_accuracy: 0.0,
        },
        1.0,
        [0.0; 3],
    );
    assert!(err(s).starts_with("position_accuracy"));
}
