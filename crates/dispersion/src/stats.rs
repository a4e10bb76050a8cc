//! Summary statistics and confidence ellipses (docs/physics.md §12.1–§12.2).
//!
//! Statistics follow RocketPy's `MonteCarlo` report: population standard deviation
//! (divisor N), median and 2.5 % / 97.5 % quantiles with NumPy's default linear
//! interpolation (Hyndman & Fan 1996, definition 7). Ellipses follow RocketPy's
//! `ellipses.py`: sample covariance (divisor N − 1), its eigen-decomposition, full axes
//! `2k√λ` for the k-σ contours, orientation `atan2(v1_y, v1_x)`. Besides those k-σ contours,
//! probability-calibrated ellipses use `k = sqrt(−2 ln(1 − p))`, the radius of the bivariate
//! normal's p-quantile contour (chi-square with 2 degrees of freedom).

use serde::Serialize;

/// Summary statistics of one column.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Statistics {
    /// Number of finite values.
    pub count: u64,
    /// Arithmetic mean.
    pub mean: f64,
    /// Population standard deviation (divisor N, NumPy `ddof = 0`).
    pub std: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// Median (50 % quantile).
    pub median: f64,
    /// 2.5 % quantile.
    pub p2_5: f64,
    /// 97.5 % quantile.
    pub p97_5: f64,
}

impl Statistics {
    /// Statistics of the finite `values` (in the given order for the mean, so the result
    /// does not depend on anything but the order of the samples); `None` when there are none.
    /// The slice is sorted in place.
    pub fn of(values: &mut Vec<f64>) -> Option<Self> {
        values.retain(|v| v.is_finite());
        if values.is_empty() {
            return None;
        }
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let variance = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
        values.sort_by(f64::total_cmp);
        Some(Statistics {
            count: values.len() as u64,
            mean,
            std: variance.sqrt(),
            min: values.first().copied().unwrap_or(f64::NAN),
            max: values.last().copied().unwrap_or(f64::NAN),
            median: quantile(values, 0.5),
            p2_5: quantile(values, 0.025),
            p97_5: quantile(values, 0.975),
        })
    }
}

/// The `p` quantile of ascending `sorted` values, linear between order statistics at
/// position `(n − 1) p` (NumPy's default `method="linear"`); NaN when empty.
pub fn quantile(sorted: &[f64], p: f64) -> f64 {
    let Some(last) = sorted.len().checked_sub(1) else {
        return f64::NAN;
    };
    let position = (last as f64) * p.clamp(0.0, 1.0);
    let below = position.floor() as usize;
    let above = (below + 1).min(last);
    let weight = position - below as f64;
    match (sorted.get(below), sorted.get(above)) {
        (Some(a), Some(b)) => a + (b - a) * weight,
        _ => f64::NAN,
    }
}

/// Two-sided probability of a normal variable within k standard deviations, k = 1, 2, 3:
/// `erf(k/√2)` (Abramowitz & Stegun 1964, table 26.1).
pub const NORMAL_SIGMA_PROBABILITY: [f64; 3] = [
    0.682_689_492_137_086,
    0.954_499_736_103_642,
    0.997_300_203_936_740,
];

/// The scale `k` of the ellipse holding probability `p` of a bivariate normal:
/// `k = sqrt(−2 ln(1 − p))` (chi-square with two degrees of freedom).
pub fn probability_scale(p: f64) -> f64 {
    (-2.0 * (1.0 - p).ln()).sqrt()
}

/// Probability a bivariate normal puts inside its k-σ ellipse: `1 − exp(−k²/2)`.
pub fn k_sigma_probability(k: f64) -> f64 {
    1.0 - (-0.5 * k * k).exp()
}

/// Running mean and co-moments of points (Welford 1962; Chan, Golub & LeVeque 1983), so
/// ellipses of any number of samples need constant memory. Non-finite points are skipped.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Moments {
    count: u64,
    mean: [f64; 2],
    /// Sums of products of deviations: xx, xy, yy.
    comoments: [f64; 3],
}

impl Moments {
    /// Adds a point.
    pub fn push(&mut self, x: f64, y: f64) {
        if !(x.is_finite() && y.is_finite()) {
            return;
        }
        self.count += 1;
        let n = self.count as f64;
        let dx = x - self.mean[0];
        let dy = y - self.mean[1];
        self.mean[0] += dx / n;
        self.mean[1] += dy / n;
        self.comoments[0] += dx * (x - self.mean[0]);
        self.comoments[1] += dx * (y - self.mean[1]);
        self.comoments[2] += dy * (y - self.mean[1]);
    }

    /// Points added.
    pub fn count(&self) -> u64 {
        self.count
    }

    /// The ellipse (sample covariance, divisor N − 1); `None` with fewer than two points.
    pub fn ellipse(&self) -> Option<Ellipse> {
        if self.count < 2 {
            return None;
        }
        let d = (self.count - 1) as f64;
        let [xx, xy, yy] = self.comoments.map(|c| c / d);
        Some(Ellipse::from_covariance(
            self.count,
            self.mean,
            [[xx, xy], [xy, yy]],
        ))
    }
}

/// A fitted ellipse: the centre and the eigen-decomposition of the sample covariance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipse {
    /// Number of points.
    pub count: u64,
    /// Mean of the points (x, y).
    pub center: [f64; 2],
    /// Sample covariance `[[sxx, sxy], [sxy, syy]]`, divisor N − 1.
    pub covariance: [[f64; 2]; 2],
    /// Eigenvalues, larger first.
    pub eigenvalues: [f64; 2],
    /// Direction of the major axis: degrees counter-clockwise from +x, in (−90, 90].
    pub orientation_deg: f64,
}

impl Ellipse {
    /// Fits the points (finite pairs only); `None` with fewer than two.
    pub fn fit(points: &[[f64; 2]]) -> Option<Self> {
        let mut moments = Moments::default();
        for p in points {
            moments.push(p[0], p[1]);
        }
        moments.ellipse()
    }

    /// The ellipse of a centre and a sample covariance `[[sxx, sxy], [sxy, syy]]`.
    pub fn from_covariance(count: u64, center: [f64; 2], covariance: [[f64; 2]; 2]) -> Self {
        let [[sxx, sxy], [_, syy]] = covariance;
        // Eigenvalues of a symmetric 2×2 matrix in closed form.
        let half_trace = 0.5 * (sxx + syy);
        let radius = (0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy).sqrt();
        let major = half_trace + radius;
        let minor = (half_trace - radius).max(0.0);
        // The major eigenvector is (λ1 − syy, sxy) or, equivalently, (sxy, λ1 − sxx); take the
        // better conditioned of the two.
        let (vx, vy) = if sxx >= syy {
            (major - syy, sxy)
        } else {
            (sxy, major - sxx)
        };
        let mut orientation_deg = if vx.abs() + vy.abs() > 0.0 {
            vy.atan2(vx).to_degrees()
        } else {
            0.0
        };
        // An eigenvector's sign is arbitrary: fold the angle into (−90°, 90°].
        if orientation_deg > 90.0 {
            orientation_deg -= 180.0;
        } else if orientation_deg <= -90.0 {
            orientation_deg += 180.0;
        }
        // No "-0°" in reports.
        orientation_deg += 0.0;
        Ellipse {
            count,
            center,
            covariance,
            eigenvalues: [major, minor],
            orientation_deg,
        }
    }

    /// Semi-axes (major, minor) of the contour at scale `k`: `k√λ1`, `k√λ2` (RocketPy's
    /// width and height are twice these).
    pub fn semi_axes(&self, k: f64) -> [f64; 2] {
        [
            k * self.eigenvalues[0].sqrt(),
            k * self.eigenvalues[1].sqrt(),
        ]
    }

    /// `n` points of the contour at scale `k`, `φ_i = 2π i / n` (docs/physics.md §12.2).
    pub fn boundary(&self, k: f64, n: usize) -> Vec<[f64; 2]> {
        let [a, b] = self.semi_axes(k);
        let (sin_t, cos_t) = self.orientation_deg.to_radians().sin_cos();
        (0..n)
            .map(|i| {
                let phi = std::f64::consts::TAU * i as f64 / n as f64;
                let (u, v) = (a * phi.cos(), b * phi.sin());
                [
                    self.center[0] + cos_t * u - sin_t * v,
                    self.center[1] + sin_t * u + cos_t * v,
                ]
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_by_hand() {
        // values 1..=5 in shuffled order: mean 3, population variance (4+1+0+1+4)/5 = 2,
        // median 3; 2.5 % at position 4·0.025 = 0.1 → 1 + 0.1·(2 − 1) = 1.1;
        // 97.5 % at position 3.9 → 4 + 0.9·(5 − 4) = 4.9.
        let mut values = vec![4.0, 1.0, 5.0, f64::NAN, 3.0, 2.0];
        let s = Statistics::of(&mut values).expect("finite values");
        assert_eq!(s.count, 5);
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert!(close(s.mean, 3.0));
        assert!(close(s.std, 2f64.sqrt()));
        assert!(close(s.min, 1.0) && close(s.max, 5.0) && close(s.median, 3.0));
        assert!(close(s.p2_5, 1.1), "{}", s.p2_5);
        assert!(close(s.p97_5, 4.9), "{}", s.p97_5);
        assert!(Statistics::of(&mut vec![f64::NAN]).is_none());
    }

    #[test]
    fn quantile_matches_numpy_linear() {
        // numpy.quantile([10, 20, 40], [0, 0.25, 0.5, 0.9, 1]) = [10, 15, 20, 36, 40].
        let sorted = [10.0, 20.0, 40.0];
        for (p, expected) in [
            (0.0, 10.0),
            (0.25, 15.0),
            (0.5, 20.0),
            (0.9, 36.0),
            (1.0, 40.0),
        ] {
            assert!((quantile(&sorted, p) - expected).abs() < 1e-12, "p = {p}");
        }
        assert!(quantile(&[], 0.5).is_nan());
        assert!((quantile(&[7.0], 0.3) - 7.0).abs() < 1e-15);
    }

    #[test]
    fn probability_scales() {
        // 95 % ellipse: k = sqrt(−2 ln 0.05) = 2.4477 (docs/physics.md §12.2).
        assert!((probability_scale(0.95) - 2.447_746_830_680_816).abs() < 1e-12);
        assert!((k_sigma_probability(probability_scale(0.6)) - 0.6).abs() < 1e-12);
        // 1 − exp(−1/2) = 39.35 % inside the 1-σ ellipse.
        assert!((k_sigma_probability(1.0) - 0.393_469_340_287_366_6).abs() < 1e-12);
    }

    #[test]
    fn ellipse_of_four_points() {
        // Points (±2, 0), (0, ±1): mean 0, covariance diag(8/3, 2/3), major axis along x.
        let e = Ellipse::fit(&[[2.0, 0.0], [-2.0, 0.0], [0.0, 1.0], [0.0, -1.0]]).expect("fit");
        assert!((e.eigenvalues[0] - 8.0 / 3.0).abs() < 1e-12);
        assert!((e.eigenvalues[1] - 2.0 / 3.0).abs() < 1e-12);
        assert!(e.orientation_deg.abs() < 1e-12);
        // Rotated by 90°: along y.
        let e = Ellipse::fit(&[[0.0, 2.0], [0.0, -2.0], [1.0, 0.0], [-1.0, 0.0]]).expect("fit");
        assert!((e.orientation_deg - 90.0).abs() < 1e-12);
        let ring = e.boundary(1.0, 4);
        assert!((ring[0][1] - (8.0f64 / 3.0).sqrt()).abs() < 1e-12);
        assert!(Ellipse::fit(&[[1.0, 1.0]]).is_none());
    }
}
