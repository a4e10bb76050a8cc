//! Tabulated functions of one variable.
//!
//! A [`Table1`] stores its samples and, for every interval `[x_i, x_{i+1}]`, the cubic
//! `y = a + b·d + c·d² + e·d³` with `d = x − x_i`. Linear interpolation is the special case
//! `c = e = 0`; the natural cubic spline (second derivative zero at both ends) follows
//! de Boor, *A Practical Guide to Splines* (1978), ch. IV, solved with the tridiagonal
//! (Thomas) algorithm. Evaluation is a binary search plus a Horner step: no allocation.

use crate::MathError;

/// How a table interpolates between its samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Interpolation {
    /// Straight lines between samples.
    #[default]
    Linear,
    /// Natural cubic spline (zero second derivative at both ends).
    Spline,
}

/// How a table behaves outside `[x_first, x_last]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Extrapolation {
    /// Hold the end values.
    #[default]
    Constant,
    /// Continue the end piece (line or cubic).
    Natural,
    /// Zero outside the samples.
    Zero,
}

/// A tabulated function of one variable with allocation-free evaluation.
#[derive(Debug, Clone, PartialEq)]
pub struct Table1 {
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// Per-interval cubic coefficients `[a, b, c, e]` in `d = x − x_i`.
    coeffs: Vec<[f64; 4]>,
    interpolation: Interpolation,
    extrapolation: Extrapolation,
}

impl Table1 {
    /// Builds a table from strictly increasing, finite `xs` and finite `ys`.
    ///
    /// # Errors
    /// [`MathError`] when the columns differ in length, hold fewer than one point, contain a
    /// non-finite value or `xs` does not strictly increase.
    pub fn new(
        xs: Vec<f64>,
        ys: Vec<f64>,
        interpolation: Interpolation,
        extrapolation: Extrapolation,
    ) -> Result<Self, MathError> {
        if xs.len() != ys.len() {
            return Err(MathError::LengthMismatch { x: xs.len(), y: ys.len() });
        }
        if xs.is_empty() {
            return Err(MathError::TooFewPoints { needed: 1, got: 0 });
        }
        for (index, (&x, &y)) in xs.iter().zip(&ys).enumerate() {
            for value in [x, y] {
                if !value.is_finite() {
                    return Err(MathError::NotFinite { index, value });
                }
            }
            if index > 0 && x <= xs[index - 1] {
                return Err(MathError::NotIncreasing { index, x, previous: xs[index - 1] });
            }
        }
        let coeffs = match interpolation {
            Interpolation::Linear => linear_coeffs(&xs, &ys),
            Interpolation::Spline => natural_spline_coeffs(&xs, &ys),
        };
        Ok(Table1 { xs, ys, coeffs, interpolation, extrapolation })
    }

    /// A linear table with constant extrapolation (the mission format's default curve).
    ///
    /// # Errors
    /// As [`Table1::new`].
    pub fn linear(xs: Vec<f64>, ys: Vec<f64>) -> Result<Self, MathError> {
        Self::new(xs, ys, Interpolation::Linear, Extrapolation::Constant)
    }

    /// Samples `f` at `n ≥ 2` equally spaced points of `[a, b]` (`numpy.linspace`).
    ///
    /// # Errors
    /// As [`Table1::new`] (e.g. when `f` returns NaN).
    pub fn sample(
        f: impl Fn(f64) -> f64,
        a: f64,
        b: f64,
        n: usize,
        interpolation: Interpolation,
        extrapolation: Extrapolation,
    ) -> Result<Self, MathError> {
        let xs = linspace(a, b, n);
        let ys = xs.iter().map(|&x| f(x)).collect();
        Self::new(xs, ys, interpolation, extrapolation)
    }

    /// The sample abscissae.
    #[must_use]
    pub fn xs(&self) -> &[f64] {
        &self.xs
    }
    /// The sample values.
    #[must_use]
    pub fn ys(&self) -> &[f64] {
        &self.ys
    }
    /// The interpolation method.
    #[must_use]
    pub fn interpolation(&self) -> Interpolation {
        self.interpolation
    }
    /// The extrapolation method.
    #[must_use]
    pub fn extrapolation(&self) -> Extrapolation {
        self.extrapolation
    }
    /// The domain `[x_first, x_last]` of the samples.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        (self.xs[0], self.xs[self.xs.len() - 1])
    }

    /// Index of the interval used for `x` (clamped to the first/last interval).
    #[inline]
    fn interval(&self, x: f64) -> usize {
        let n = self.coeffs.len();
        self.xs.partition_point(|&v| v <= x).saturating_sub(1).min(n.saturating_sub(1))
    }

    /// Value at `x`.
    #[inline]
    #[must_use]
    pub fn eval(&self, x: f64) -> f64 {
        let n = self.xs.len();
        if n == 1 {
            return if self.extrapolation == Extrapolation::Zero && x != self.xs[0] {
                0.0
            } else {
                self.ys[0]
            };
        }
        if x < self.xs[0] || x > self.xs[n - 1] {
            match self.extrapolation {
                Extrapolation::Constant => {
                    return if x < self.xs[0] { self.ys[0] } else { self.ys[n - 1] };
                }
                Extrapolation::Zero => return 0.0,
                Extrapolation::Natural => {}
            }
        }
        let i = self.interval(x);
        let [a, b, c, e] = self.coeffs[i];
        let d = x - self.xs[i];
        a + d * (b + d * (c + d * e))
    }

    /// First derivative at `x` (exact for the interpolant; zero where extrapolation is
    /// constant or zero).
    #[must_use]
    pub fn derivative(&self, x: f64) -> f64 {
        let n = self.xs.len();
        if n == 1 {
            return 0.0;
        }
        if (x < self.xs[0] || x > self.xs[n - 1]) && self.extrapolation != Extrapolation::Natural
        {
            return 0.0;
        }
        let i = self.interval(x);
        let [_, b, c, e] = self.coeffs[i];
        let d = x - self.xs[i];
        b + d * (2.0 * c + 3.0 * d * e)
    }

    /// Exact definite integral of the interpolant (with its extrapolation) from `a` to `b`.
    #[must_use]
    pub fn integral(&self, a: f64, b: f64) -> f64 {
        if b < a {
            return -self.integral(b, a);
        }
        let n = self.xs.len();
        let (x0, x1) = self.domain();
        let mut total = 0.0;
        // Left of the samples.
        if a < x0 {
            let hi = b.min(x0);
            total += match self.extrapolation {
                Extrapolation::Constant => self.ys[0] * (hi - a),
                Extrapolation::Zero => 0.0,
                Extrapolation::Natural if n > 1 => {
                    piece_integral(self.coeffs[0], a - x0, hi - x0)
                }
                Extrapolation::Natural => self.ys[0] * (hi - a),
            };
        }
        // Right of the samples.
        if b > x1 {
            let lo = a.max(x1);
            total += match self.extrapolation {
                Extrapolation::Constant => self.ys[n - 1] * (b - lo),
                Extrapolation::Zero => 0.0,
                Extrapolation::Natural if n > 1 => {
                    let xi = self.xs[n - 2];
                    piece_integral(self.coeffs[n - 2], lo - xi, b - xi)
                }
                Extrapolation::Natural => self.ys[0] * (b - lo),
            };
        }
        // Inside.
        let lo = a.max(x0);
        let hi = b.min(x1);
        if n > 1 && hi > lo {
            let first = self.interval(lo);
            let last = self.interval(hi);
            for i in first..=last {
                let s = lo.max(self.xs[i]);
                let e = hi.min(self.xs[i + 1]);
                if e > s {
                    total += piece_integral(self.coeffs[i], s - self.xs[i], e - self.xs[i]);
                }
            }
        }
        total
    }
}

/// `∫ a + b d + c d² + e d³` from `d0` to `d1`.
fn piece_integral([a, b, c, e]: [f64; 4], d0: f64, d1: f64) -> f64 {
    let p = |d: f64| d * (a + d * (b / 2.0 + d * (c / 3.0 + d * e / 4.0)));
    p(d1) - p(d0)
}

/// `n` equally spaced points from `a` to `b` inclusive, as `numpy.linspace`.
#[must_use]
pub fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    match n {
        0 => Vec::new(),
        1 => vec![a],
        _ => {
            let step = (b - a) / (n - 1) as f64;
            let mut v: Vec<f64> = (0..n).map(|i| a + i as f64 * step).collect();
            v[n - 1] = b;
            v
        }
    }
}

fn linear_coeffs(xs: &[f64], ys: &[f64]) -> Vec<[f64; 4]> {
    xs.windows(2)
        .zip(ys.windows(2))
        .map(|(x, y)| [y[0], (y[1] - y[0]) / (x[1] - x[0]), 0.0, 0.0])
        .collect()
}

/// Natural cubic spline: solve for the second derivatives `M_i` (M_0 = M_{n-1} = 0).
fn natural_spline_coeffs(xs: &[f64], ys: &[f64]) -> Vec<[f64; 4]> {
    let n = xs.len();
    if n < 3 {
        return linear_coeffs(xs, ys);
    }
    let h: Vec<f64> = xs.windows(2).map(|w| w[1] - w[0]).collect();
    // Tridiagonal system for M_1..M_{n-2}.
    let m = n - 2;
    let mut diag = vec![0.0; m];
    let mut upper = vec![0.0; m];
    let mut rhs = vec![0.0; m];
    for k in 0..m {
        let i = k + 1;
        diag[k] = 2.0 * (h[i - 1] + h[i]);
        upper[k] = h[i];
        rhs[k] = 6.0 * ((ys[i + 1] - ys[i]) / h[i] - (ys[i] - ys[i - 1]) / h[i - 1]);
    }
    // Thomas algorithm (the matrix is symmetric, strictly diagonally dominant).
    for k in 1..m {
        let w = h[k] / diag[k - 1];
        diag[k] -= w * upper[k - 1];
        rhs[k] -= w * rhs[k - 1];
    }
    let mut second = vec![0.0; n];
    for k in (0..m).rev() {
        let next = if k + 1 < m { second[k + 2] } else { 0.0 };
        second[k + 1] = (rhs[k] - upper[k] * next) / diag[k];
    }
    (0..n - 1)
        .map(|i| {
            let hi = h[i];
            let b = (ys[i + 1] - ys[i]) / hi - hi * (2.0 * second[i] + second[i + 1]) / 6.0;
            [ys[i], b, second[i] / 2.0, (second[i + 1] - second[i]) / (6.0 * hi)]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * (1.0 + b.abs())
    }

    #[test]
    fn linear_reproduces_nodes_and_midpoints() {
        let t = Table1::linear(vec![0.0, 1.0, 3.0], vec![0.0, 2.0, 0.0]).unwrap();
        assert!(close(t.eval(1.0), 2.0, 1e-15));
        assert!(close(t.eval(2.0), 1.0, 1e-15));
        assert!(close(t.eval(-1.0), 0.0, 1e-15));
        assert!(close(t.eval(10.0), 0.0, 1e-15));
        assert!(close(t.integral(0.0, 3.0), 3.0, 1e-14));
    }

    #[test]
    fn spline_is_exact_for_lines_and_natural_at_ends() {
        let xs = linspace(0.0, 4.0, 9);
        let ys: Vec<f64> = xs.iter().map(|x| 3.0 * x - 1.0).collect();
        let t = Table1::new(xs, ys, Interpolation::Spline, Extrapolation::Natural).unwrap();
        for x in [-2.0, 0.3, 1.7, 3.99, 6.0] {
            assert!(close(t.eval(x), 3.0 * x - 1.0, 1e-12));
            assert!(close(t.derivative(x), 3.0, 1e-12));
        }
    }

    #[test]
    fn rejects_bad_data() {
        assert!(matches!(
            Table1::linear(vec![0.0, 0.0], vec![1.0, 2.0]),
            Err(MathError::NotIncreasing { index: 1, .. })
        ));
        assert!(matches!(
            Table1::linear(vec![0.0, 1.0], vec![1.0, f64::NAN]),
            Err(MathError::NotFinite { index: 1, .. })
        ));
        assert!(matches!(Table1::linear(vec![], vec![]), Err(MathError::TooFewPoints { .. })));
    }
}
