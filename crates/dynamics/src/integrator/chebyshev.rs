//! The Runge–Kutta–Chebyshev steps: stage count, stability limit, stages and the power
//! method for the spectral radius (van der Houwen & Sommeijer 1980; Sommeijer, Shampine &
//! Verwer 1997).

#![allow(clippy::needless_range_loop)]

use super::*;

impl<const N: usize, F> RungeKutta<N, F>
where
    F: FnMut(f64, &[f64; N]) -> [f64; N],
{
    /// The stage count `s = 1 + ⌊√(1 + 1.54 h ρ)⌋` (at least 2) that keeps a step `h` inside
    /// the stability region for the estimated spectral radius `ρ` (Sommeijer, Shampine &
    /// Verwer 1997, §2).
    pub(super) fn chebyshev_stage_count(&self, h: f64) -> usize {
        let s = 1.0 + (1.0 + rkc::STAGE_FACTOR * h * self.radius).sqrt().floor();
        // A float-to-integer cast saturates; the step limit keeps `s` below the cap anyway.
        (s as usize).max(2)
    }

    /// The longest RKC step whose stage count stays within `√(rtol / (10 ε))`: the round-off
    /// of the stage recursion grows like `s²ε`, which must stay well below the tolerance (the
    /// cap of the RKC code).
    pub(super) fn chebyshev_step_limit(&self) -> f64 {
        let cap = (self.tol.rtol / (10.0 * f64::EPSILON))
            .sqrt()
            .round()
            .max(2.0);
        (cap * cap - 1.0) / (rkc::STAGE_FACTOR * self.radius)
    }

    /// One step of the damped second-order Runge–Kutta–Chebyshev method (Sommeijer, Shampine
    /// & Verwer 1997, eqs. 2.1–2.6; van der Houwen & Sommeijer 1980): with the shifted
    /// Chebyshev polynomials `T_j` of the first kind, `w₀ = 1 + ε/s²`, `w₁ = T_s′(w₀)/T_s″(w₀)`
    /// and `b_j = T_j″(w₀)/T_j′(w₀)²` (`b₀ = b₁ = b₂`), the stages are `Y₁ = y + b₁w₁ h f(y)` and
    /// `Y_j = (1 − μ_j − ν_j) y + μ_j Y_{j−1} + ν_j Y_{j−2} + μ̃_j h (f(Y_{j−1}) − a_{j−1} f(y))`
    /// with `μ_j = 2 b_j w₀/b_{j−1}`, `ν_j = −b_j/b_{j−2}`, `μ̃_j = 2 b_j w₁/b_{j−1}` and
    /// `a_j = 1 − b_j T_j(w₀)`; `Y_s` is the new point. `T_j`, `T_j′` and `T_j″` at `w₀` follow
    /// from the three-term recurrence and the stage instants `c_j` from the same combination
    /// of the earlier ones. `s − 1` evaluations, plus `f(t_new, y_new)` in slot 1.
    pub(super) fn chebyshev_stages(&mut self, h: f64, t_new: f64) -> [f64; N] {
        let s = self.chebyshev_stage_count(h);
        let sf = s as f64;
        let w0 = 1.0 + rkc::DAMPING / (sf * sf);
        let w0_sq_1 = w0 * w0 - 1.0;
        let root = w0_sq_1.sqrt();
        // arccosh(w₀) · s: T_s(w₀) = cosh(s θ), from which T_s′ and T_s″.
        let arg = sf * (w0 + root).ln();
        let w1 = arg.sinh() * w0_sq_1 / (arg.cosh() * sf * root - w0 * arg.sinh());
        let (t, y0, f0) = (self.t, self.y, self.f);
        // T_{j−2}, T_{j−1} and their first and second derivatives at w₀, from T₀ = 1, T₁ = w₀.
        let (mut cheb, mut cheb_prev) = (w0, 1.0);
        let (mut slope, mut slope_prev) = (1.0, 0.0);
        let (mut curv, mut curv_prev) = (0.0, 0.0);
        let b_first = 1.0 / (4.0 * w0 * w0);
        let (mut b, mut b_prev) = (b_first, b_first);
        let mu1 = w1 * b_first;
        let mut y_prev = y0;
        let mut y_cur = [0.0; N];
        for i in 0..N {
            y_cur[i] = y0[i] + h * mu1 * f0[i];
        }
        let (mut c, mut c_prev) = (mu1, 0.0);
        for _ in 2..=s {
            let cheb_next = 2.0 * w0 * cheb - cheb_prev;
            let slope_next = 2.0 * w0 * slope - slope_prev + 2.0 * cheb;
            let curv_next = 2.0 * w0 * curv - curv_prev + 4.0 * slope;
            let b_next = curv_next / (slope_next * slope_next);
            let a = 1.0 - cheb * b;
            let mu = 2.0 * w0 * b_next / b;
            let nu = -b_next / b_prev;
            let mu_tilde = mu * w1 / w0;
            let f = (self.rhs)(t + c * h, &y_cur);
            let mut y_next = [0.0; N];
            for i in 0..N {
                y_next[i] = (1.0 - mu - nu) * y0[i]
                    + mu * y_cur[i]
                    + nu * y_prev[i]
                    + mu_tilde * h * (f[i] - a * f0[i]);
            }
            let c_next = mu * c + nu * c_prev + mu_tilde * (1.0 - a);
            (y_prev, y_cur) = (y_cur, y_next);
            (c_prev, c) = (c, c_next);
            (cheb_prev, cheb) = (cheb, cheb_next);
            (slope_prev, slope) = (slope, slope_next);
            (curv_prev, curv) = (curv, curv_next);
            (b_prev, b) = (b, b_next);
        }
        self.k[1] = (self.rhs)(t_new, &y_cur);
        self.nfev += s;
        y_cur
    }

    /// The spectral radius of the Jacobian at the current point, by the nonlinear power
    /// method of the RKC code (Sommeijer, Shampine & Verwer 1997, §3.2): a perturbation `d` of
    /// fixed size is replaced by `f(t, y + d) − f(t, y)` rescaled to that size until the ratio
    /// of the two sizes settles to 1 %. Sizes are taken in the tolerance-weighted norm
    /// `‖x‖ = rms(x_i / (atol_i + rtol |y_i|))` (the eigenvalues are those of the Jacobian in any
    /// norm, and the perturbation follows the state's units); the perturbation is `√ε ‖y‖` (at
    /// least `√ε`), it starts from the last direction found (at the first estimate, the
    /// derivative plus a direction with a share of every component) and the result carries a
    /// 20 % margin. Ratios below `1/(t_bound − t)` are not
    /// told apart, as they cannot constrain the step. Without convergence (complex dominant
    /// eigenvalues) the largest ratio met is used. Evaluations count as the method's.
    pub(super) fn estimate_radius(&mut self) {
        let (t, y, f) = (self.t, self.y, self.f);
        let weight = self.tolerance_scale(&y);
        let size = f64::EPSILON.sqrt() * rms_norm(&y, &weight).max(1.0);
        // A direction with a share of every component (signs in an irregular pattern), so that
        // no eigenvector is missing from the start for want of round-off.
        let spread: [f64; N] = std::array::from_fn(|i| {
            if (i * 7 + 3) % 5 < 2 {
                -weight[i]
            } else {
                weight[i]
            }
        });
        let unit = |d: &[f64; N]| {
            let norm = rms_norm(d, &weight);
            d.map(|v| if norm > 0.0 { v / norm } else { 0.0 })
        };
        let mut d = if rms_norm(&self.eigen, &weight) > 0.0 {
            unit(&self.eigen)
        } else {
            let (f_unit, spread_unit) = (unit(&f), unit(&spread));
            std::array::from_fn(|i| f_unit[i] + spread_unit[i])
        };
        d = unit(&d).map(|v| v * size);
        let interval = self.t_bound - t;
        let small = if interval > 0.0 { 1.0 / interval } else { 0.0 };
        let (mut ratio, mut largest) = (0.0_f64, 0.0_f64);
        let mut converged = false;
        for iteration in 0..rkc::POWER_ITERATIONS {
            let mut probe = [0.0; N];
            for i in 0..N {
                probe[i] = y[i] + d[i];
            }
            let fp = (self.rhs)(t, &probe);
            self.nfev += 1;
            let mut diff = [0.0; N];
            for i in 0..N {
                diff[i] = fp[i] - f[i];
            }
            let norm = rms_norm(&diff, &weight);
            if !norm.is_finite() {
                break;
            }
            let previous = ratio;
            ratio = norm / size;
            largest = largest.max(ratio);
            if iteration > 0 && (ratio - previous).abs() <= rkc::POWER_TOLERANCE * ratio.max(small)
            {
                converged = true;
                break;
            }
            if norm > 0.0 {
                d = diff.map(|v| v * (size / norm));
            } else {
                // The perturbation vanished in f: turn the direction by flipping one component.
                let i = iteration % N;
                d[i] = -d[i];
            }
        }
        self.eigen = d;
        self.radius = rkc::RADIUS_MARGIN * if converged { ratio } else { largest };
        self.radius_age = 0;
    }
}
