//! Dense output of the last accepted step (HNW I, §II.6; `dop853.f`'s `contd8`).

#![allow(clippy::needless_range_loop)]

use super::*;

impl<const N: usize, F> RungeKutta<N, F>
where
    F: FnMut(f64, &[f64; N]) -> [f64; N],
{
    /// The right-hand side `f(t, y)` at any point, outside the integration: what a sampled
    /// process that needs the equations' derivative at a dense state calls (a sensor,
    /// RocketPy's `u_dot = derivative(t, y)` at a time node). Not counted in
    /// [`RungeKutta::evaluations`], which counts the integration's own evaluations.
    pub fn rhs_at(&mut self, t: f64, y: &[f64; N]) -> [f64; N] {
        (self.rhs)(t, y)
    }

    /// The dense-output rows `F₀…F₆` of the last accepted step, made on first use: `F₀ = Δy`,
    /// `F₁ = h f₀ − Δy`, then for DOPRI5 `F₂ = Δy − h f₁ − F₁`, `F₃ = h Σ d_i k_i` (HNW I,
    /// §II.6), for DOP853 `F₂ = 2Δy − h (f₁ + f₀)`, `F₃…F₆ = h Σ d_ij k_j` after three extra
    /// evaluations (HNW I, §II.10; `dop853.f`'s `contd8`).
    pub(super) fn dense_rows(&mut self) -> &[[f64; N]; 7] {
        if self.rows_made {
            return &self.rows;
        }
        let h = self.h_last;
        let last = self.pair.last();
        if self.pair == Pair::Dop853 {
            let mut y_stage = [0.0; N];
            for (e, (a, c)) in dop853::A_EXTRA.iter().zip(dop853::C_EXTRA).enumerate() {
                let s = last + 1 + e;
                let acc = combine(&a[..s], &self.k[..s]);
                for i in 0..N {
                    y_stage[i] = self.y_old[i] + h * acc[i];
                }
                self.k[s] = (self.rhs)(self.t_old + c * h, &y_stage);
                self.nfev += 1;
            }
        }
        let rows = &mut self.rows;
        for i in 0..N {
            let dy = self.y[i] - self.y_old[i];
            rows[0][i] = dy;
            rows[1][i] = h * self.k[0][i] - dy;
            rows[2][i] = match self.pair {
                Pair::Dopri5 | Pair::Rkc2 => dy - h * self.k[last][i] - rows[1][i],
                Pair::Dop853 => 2.0 * dy - h * (self.k[last][i] + self.k[0][i]),
            };
        }
        match self.pair {
            Pair::Dopri5 => {
                let acc = combine(&dopri5::D, &self.k[..7]);
                for i in 0..N {
                    rows[3][i] = h * acc[i];
                }
            }
            Pair::Rkc2 => rows[3] = [0.0; N],
            Pair::Dop853 => {
                for (row, d) in rows[3..].iter_mut().zip(&dop853::D) {
                    let acc = combine(d, &self.k);
                    for i in 0..N {
                        row[i] = h * acc[i];
                    }
                }
            }
        }
        self.rows_made = true;
        &self.rows
    }

    /// Dense output of the last accepted step at `t` (`t_old ≤ t ≤ t`; extrapolates
    /// outside): fourth order for DOPRI5, seventh for DOP853.
    pub fn dense(&mut self, t: f64) -> [f64; N] {
        let mut out = [0.0; N];
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.dense_component(t, i);
        }
        out
    }

    /// One component of [`RungeKutta::dense`]:
    /// `y₀ + θ(F₀ + (1−θ)(F₁ + θ(F₂ + (1−θ)(F₃ + θ(F₄ + (1−θ)(F₅ + θF₆))))))`, `θ = (t − t₀)/h`.
    #[inline]
    pub fn dense_component(&mut self, t: f64, i: usize) -> f64 {
        let h = self.h_last;
        if h <= 0.0 {
            return self.y[i];
        }
        let theta = (t - self.t_old) / h;
        let theta1 = 1.0 - theta;
        let y0 = self.y_old[i];
        let pair = self.pair;
        let r = self.dense_rows();
        let inner = match pair {
            Pair::Dopri5 | Pair::Rkc2 => r[3][i],
            Pair::Dop853 => {
                let inner = r[5][i] + theta * r[6][i];
                let inner = r[4][i] + theta1 * inner;
                r[3][i] + theta * inner
            }
        };
        let inner = r[2][i] + theta1 * inner;
        let inner = r[1][i] + theta * inner;
        let inner = r[0][i] + theta1 * inner;
        y0 + theta * inner
    }

    /// Component `i` of the time derivative of [`RungeKutta::dense`] at `t`: the Horner
    /// nest of [`RungeKutta::dense_component`] differentiated level by level in `θ`
    /// (`d/dθ` of `a + s(θ) p(θ)` is `s′ p + s p′`, with `s = θ` or `1 − θ`), divided by
    /// `h`. At the step's ends it equals the right-hand side there (`f₀`, `f₁`) up to
    /// round-off: `F₀ + F₁ = h f₀` and `F₀ − F₁ − F₂ = h f₁` for both pairs.
    #[inline]
    pub fn dense_derivative_component(&mut self, t: f64, i: usize) -> f64 {
        let h = self.h_last;
        if h <= 0.0 {
            return self.f[i];
        }
        let theta = (t - self.t_old) / h;
        let theta1 = 1.0 - theta;
        let pair = self.pair;
        let r = self.dense_rows();
        // (value, d/dθ) of each level, innermost first.
        let (p, dp) = match pair {
            Pair::Dopri5 | Pair::Rkc2 => (r[3][i], 0.0),
            Pair::Dop853 => {
                let (p, dp) = (r[5][i] + theta * r[6][i], r[6][i]);
                let (p, dp) = (r[4][i] + theta1 * p, -p + theta1 * dp);
                (r[3][i] + theta * p, p + theta * dp)
            }
        };
        let (p, dp) = (r[2][i] + theta1 * p, -p + theta1 * dp);
        let (p, dp) = (r[1][i] + theta * p, p + theta * dp);
        let (p, dp) = (r[0][i] + theta1 * p, -p + theta1 * dp);
        (p + theta * dp) / h
    }
}
