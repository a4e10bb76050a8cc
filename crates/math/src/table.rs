//! Tabulated functions of one variable (docs/physics.md §28.1).
//!
//! A [`Table1`] stores its samples and an interpolant built once:
//!
//! - piecewise cubics `y = a + b·d + c·d² + e·d³` with `d = x − x_i` on every interval
//!   `[x_i, x_{i+1}]` for [`Interpolation::Linear`] (`c = e = 0`), [`Interpolation::Spline`]
//!   (natural cubic spline, second derivative zero at both ends: de Boor, *A Practical Guide to
//!   Splines* (1978), ch. IV, solved with the tridiagonal Thomas algorithm — the same spline as
//!   RocketPy's `Function.__interpolate_spline__`), and [`Interpolation::Akima`]
//!   (Akima 1970, *J. ACM* 17(4), 589–602 — the `"akima"` of RocketPy 1.13's `Function`,
//!   `rocketpy.mathutils._calc._fitting.fit_akima`);
//! - one polynomial through every sample for [`Interpolation::Polynomial`], in the scaled
//!   variable `t = (x − x_mid)/h ∈ [−1, 1]`; its coefficients solve the Vandermonde system by
//!   LU decomposition with partial pivoting (nalgebra), which is far better conditioned than
//!   RocketPy's Vandermonde system in raw `x` and agrees with it to rounding.
//!
//! Evaluation follows RocketPy's interval choice (Python `bisect_left`): `x` uses the interval
//! `[x_{i−1}, x_i]` with `i` the first index where `x_i ≥ x` (the first interval for
//! `x ≤ x_0`). For a continuous interpolant this is invisible; it fixes the value at a repeated
//! abscissa of a [`Table1::linear_stepwise`] table and the one-sided slope at a node.
//! Evaluation finds the interval through a bucket index (O(1) for evenly spread samples, a
//! binary search of one bucket otherwise) or a [`Cursor`] hunt, then takes a Horner step: no
//! allocation.
//!
//! A table never changes once built, so its abscissae, cubic pieces and bucket index are
//! reference counted: a clone copies only the sample values (and a polynomial's coefficients),
//! and tables on the same abscissae ([`Table1::on_same_abscissae`], e.g. the mass, centre of
//! mass and inertia of a motor on its time grid) share the abscissae and their bucket index
//! instead of copying and rebuilding them. The values stay a vector of the table's own, moved
//! in without a copy (docs/performance.md, "Tables").

use std::sync::Arc;

use nalgebra::{DMatrix, DVector};

use crate::MathError;

/// How a table interpolates between its samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Interpolation {
    /// Straight lines between samples.
    #[default]
    Linear,
    /// Natural cubic spline (zero second derivative at both ends), C².
    Spline,
    /// Akima (1970) piecewise cubic: node slopes weighted by the changes of the neighbouring
    /// secant slopes, two extra secants extrapolated at each end as in Akima's paper. C¹ and
    /// free of the overshoot of splines near steps. Needs no special case below 3 points (then
    /// it is linear).
    Akima,
    /// The single polynomial of degree `n − 1` through all `n` samples.
    Polynomial,
}

/// How a table behaves outside `[x_first, x_last]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Extrapolation {
    /// Hold the end values.
    #[default]
    Constant,
    /// Continue the end piece (line, cubic or the polynomial).
    Natural,
    /// Zero outside the samples.
    Zero,
}

/// How [`Table1::from_points`] treats the order of its points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointOrder {
    /// Sort the points stably by x. Repeated x are then kept for linear tables (with the
    /// semantics of [`Table1::linear_stepwise`]) and rejected for the others.
    SortStably,
    /// The points must already be strictly increasing in x; the first row that is not is an
    /// error naming it.
    StrictlyIncreasing,
}

/// A remembered interval for evaluating a table along a monotone sequence of abscissae
/// (integration steps, output grids): [`Table1::eval_with`] and [`Table1::locate_with`] first
/// try the interval of the previous call and its neighbours before falling back to the search.
/// Any cursor works with any table; a stale one only costs the search.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Cursor(usize);

/// Where an abscissa falls among a table's samples ([`Table1::locate`]). It depends on the
/// abscissae only, so one search serves every table on the same abscissae
/// ([`Table1::same_abscissae`]) through [`Table1::eval_at`] and its siblings.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Location {
    /// Left of the first sample.
    Below,
    /// Right of the last sample.
    Above,
    /// Within the samples, on this interval (RocketPy's `bisect_left` choice).
    Interval(usize),
}

/// One cubic piece of a [`Table1`], detached from it: `a + d(b + d(c + d·e))` with
/// `d = x − x0` ([`Table1::piece`]). It evaluates bit for bit as the table does wherever the
/// table uses that piece, so that a caller may gather the pieces of several tables over a
/// common interval and evaluate them without any lookup.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    x0: f64,
    coeffs: [f64; 4],
}

impl Piece {
    /// The constant `value` (a held or zero extrapolation, a one-sample table).
    #[must_use]
    pub const fn constant(value: f64) -> Self {
        Self {
            x0: 0.0,
            coeffs: [value, 0.0, 0.0, 0.0],
        }
    }

    /// Value at `x` (finite).
    #[inline(always)]
    #[must_use]
    pub fn eval(&self, x: f64) -> f64 {
        cubic_value(self.x0, self.coeffs, x)
    }
}

/// The cubic `[a, b, c, e]` in `d = x − x0` at `x`; the one evaluation of every cubic piece.
#[inline(always)]
fn cubic_value(x0: f64, [a, b, c, e]: [f64; 4], x: f64) -> f64 {
    let d = x - x0;
    // A straight piece (c and e both ±0, as every linear table's): `a + d·b` is the same
    // number as the full Horner form, without its two dependent multiply-adds on the
    // critical path.
    if (c.to_bits() | e.to_bits()) << 1 == 0 {
        a + d * b
    } else {
        a + d * (b + d * (c + d * e))
    }
}

/// The single interpolating polynomial, in the scaled variable `t = (x − center)/half_width`.
#[derive(Debug, Clone, PartialEq)]
struct Polynomial {
    center: f64,
    half_width: f64,
    /// Coefficients of `t⁰, t¹, …`.
    coeffs: Vec<f64>,
}

impl Polynomial {
    fn t(&self, x: f64) -> f64 {
        (x - self.center) / self.half_width
    }

    fn eval(&self, x: f64) -> f64 {
        let t = self.t(x);
        self.coeffs.iter().rev().fold(0.0, |acc, &c| acc * t + c)
    }

    fn derivative(&self, x: f64) -> f64 {
        let t = self.t(x);
        let dp = self
            .coeffs
            .iter()
            .enumerate()
            .skip(1)
            .rev()
            .fold(0.0, |acc, (k, &c)| acc * t + k as f64 * c);
        dp / self.half_width
    }

    fn second_derivative(&self, x: f64) -> f64 {
        let t = self.t(x);
        let d2p = self
            .coeffs
            .iter()
            .enumerate()
            .skip(2)
            .rev()
            .fold(0.0, |acc, (k, &c)| acc * t + (k * (k - 1)) as f64 * c);
        d2p / (self.half_width * self.half_width)
    }

    /// `∫_a^b p dx`.
    fn integral(&self, a: f64, b: f64) -> f64 {
        let antiderivative = |x: f64| {
            let t = self.t(x);
            t * self
                .coeffs
                .iter()
                .enumerate()
                .rev()
                .fold(0.0, |acc, (k, &c)| acc * t + c / (k + 1) as f64)
        };
        self.half_width * (antiderivative(b) - antiderivative(a))
    }
}

/// A bucket index over the abscissae, so that finding the interval of `x` costs O(1) for
/// evenly spread samples instead of a full binary search. The domain is cut into `m = n − 1`
/// equal buckets; `key(x) = ⌊(x − x_0)·m/(x_last − x_0)⌋` clamped to `[0, m − 1]` is a
/// monotone function of `x` (correctly rounded subtraction and multiplication are monotone),
/// so with `start[b] = #{i : key(x_i) < b}` the count of samples below `x` lies in
/// `[start[key(x)], start[key(x) + 1]]` exactly, and a search of that (short) range finds it.
#[derive(Debug, Clone, PartialEq)]
struct Guide {
    start: Arc<[usize]>,
    scale: f64,
}

impl Guide {
    fn new(xs: &[f64]) -> Self {
        let n = xs.len();
        let buckets = n.max(2) - 1;
        let scale = buckets as f64 / (xs[n - 1] - xs[0]);
        // The keys of the (sorted) samples do not decrease: the count below bucket `b` is the
        // index of the first sample with a key of at least `b`, found in one pass.
        let mut start = Vec::with_capacity(buckets + 1);
        for (i, &x) in xs.iter().enumerate() {
            let k = bucket(x - xs[0], scale, buckets - 1);
            while start.len() <= k {
                start.push(i);
            }
        }
        start.resize(buckets + 1, n);
        Guide {
            start: start.into(),
            scale,
        }
    }

    #[inline]
    fn key(&self, x0: f64, x: f64) -> usize {
        bucket(x - x0, self.scale, self.start.len() - 2)
    }
}

/// The bucket `⌊offset·scale⌋` clamped to `[0, last]`. `as i64` saturates (NaN gives 0), which
/// keeps the key monotone, with the same clamped result as the unsigned conversion.
#[inline]
fn bucket(offset: f64, scale: f64, last: usize) -> usize {
    ((offset * scale) as i64).clamp(0, last as i64) as usize
}

/// The interpolant between the samples.
#[derive(Debug, Clone, PartialEq)]
enum Pieces {
    /// Per-interval cubic coefficients `[a, b, c, e]` in `d = x − x_i`.
    Cubic(Arc<[[f64; 4]]>),
    /// One polynomial through all samples.
    Polynomial(Polynomial),
}

/// A tabulated function of one variable with allocation-free evaluation.
#[derive(Debug, Clone, PartialEq)]
pub struct Table1 {
    xs: Arc<[f64]>,
    ys: Vec<f64>,
    pieces: Pieces,
    guide: Guide,
    /// Whether `xs` strictly increases: always, but for a stepwise table with a repeated
    /// abscissa.
    increasing: bool,
    interpolation: Interpolation,
    extrapolation: Extrapolation,
}

/// The interpolant of validated, strictly increasing samples; finite samples can still give
/// coefficients that overflow (a spline through samples 1e-222 apart), which is an error.
fn pieces(xs: &[f64], ys: &[f64], interpolation: Interpolation) -> Result<Pieces, MathError> {
    let finite = |c: &[f64]| c.iter().all(|v| v.is_finite());
    let cubic = |coeffs: Arc<[[f64; 4]]>| {
        let bad = coeffs.iter().position(|c| !finite(c));
        (Pieces::Cubic(coeffs), bad)
    };
    let (pieces, bad) = match interpolation {
        // Linear pieces: only a slope can overflow, and it is checked as the pieces are made.
        Interpolation::Linear => {
            let (coeffs, bad) = linear_coeffs_checked(xs, ys);
            (Pieces::Cubic(coeffs), bad)
        }
        Interpolation::Spline => cubic(natural_spline_coeffs(xs, ys)),
        Interpolation::Akima => cubic(hermite_coeffs(xs, ys, &akima_slopes(xs, ys))),
        Interpolation::Polynomial => {
            if xs.len() == 1 {
                (Pieces::Cubic(Arc::from([])), None)
            } else {
                let p = polynomial(xs, ys)?;
                let bad = (!finite(&p.coeffs)).then_some(0);
                (Pieces::Polynomial(p), bad)
            }
        }
    };
    match bad {
        Some(interval) => Err(MathError::InterpolantNotFinite { interval }),
        None => Ok(pieces),
    }
}

/// Checks lengths and finiteness; `strict` demands strictly increasing x, otherwise
/// non-decreasing x.
fn validate(xs: &[f64], ys: &[f64], strict: bool) -> Result<(), MathError> {
    if xs.len() != ys.len() {
        return Err(MathError::LengthMismatch {
            x: xs.len(),
            y: ys.len(),
        });
    }
    if xs.is_empty() {
        return Err(MathError::TooFewPoints { needed: 1, got: 0 });
    }
    // Folds over every point decide validity; the loop below finds the first offending point
    // of a column that is not valid.
    let finite = xs
        .iter()
        .zip(ys)
        .fold(true, |ok, (x, y)| ok & x.is_finite() & y.is_finite());
    let ordered = if strict {
        xs.windows(2).fold(true, |ok, w| ok & (w[0] < w[1]))
    } else {
        xs.windows(2).fold(true, |ok, w| ok & (w[0] <= w[1]))
    };
    if finite && ordered {
        return Ok(());
    }
    for (index, (&x, &y)) in xs.iter().zip(ys).enumerate() {
        for value in [x, y] {
            if !value.is_finite() {
                return Err(MathError::NotFinite { index, value });
            }
        }
        if index > 0 {
            let previous = xs[index - 1];
            if x < previous || (strict && x <= previous) {
                return Err(MathError::NotIncreasing { index, x, previous });
            }
        }
    }
    Ok(())
}

/// [`validate`] of `ys` against `n` abscissae known to be finite and strictly increasing: the
/// same errors, without another look at the abscissae.
fn validate_values(n: usize, ys: &[f64]) -> Result<(), MathError> {
    if ys.len() != n {
        return Err(MathError::LengthMismatch { x: n, y: ys.len() });
    }
    if ys.iter().fold(true, |ok, y| ok & y.is_finite()) {
        return Ok(());
    }
    match ys.iter().position(|y| !y.is_finite()) {
        Some(index) => Err(MathError::NotFinite {
            index,
            value: ys[index],
        }),
        None => Ok(()),
    }
}

impl Table1 {
    /// Builds a table from strictly increasing, finite `xs` and finite `ys`.
    ///
    /// # Errors
    /// [`MathError`] when the columns differ in length, hold no point, contain a non-finite
    /// value, `xs` does not strictly increase, or (polynomial) the Vandermonde system is
    /// singular to working precision.
    pub fn new(
        xs: Vec<f64>,
        ys: Vec<f64>,
        interpolation: Interpolation,
        extrapolation: Extrapolation,
    ) -> Result<Self, MathError> {
        validate(&xs, &ys, true)?;
        let pieces = pieces(&xs, &ys, interpolation)?;
        let guide = Guide::new(&xs);
        Ok(Table1 {
            xs: xs.into(),
            ys,
            pieces,
            guide,
            increasing: true,
            interpolation,
            extrapolation,
        })
    }

    /// The table of `ys` on the abscissae of `like`: equal to [`Table1::new`] with a copy of
    /// `like.xs()` (and the same errors), but sharing `like`'s abscissae and bucket index
    /// instead of copying and rebuilding them. Several quantities sampled on one grid are
    /// tabulated so, and [`Table1::same_abscissae`] of such tables is immediate.
    ///
    /// # Errors
    /// As [`Table1::new`] with `like.xs()`: `like` may be a [`Table1::linear_stepwise`] table
    /// with repeated abscissae, which no table built here accepts.
    pub fn on_same_abscissae(
        like: &Table1,
        ys: Vec<f64>,
        interpolation: Interpolation,
        extrapolation: Extrapolation,
    ) -> Result<Self, MathError> {
        if like.increasing {
            validate_values(like.xs.len(), &ys)?;
        } else {
            validate(&like.xs, &ys, true)?;
        }
        Ok(Table1 {
            xs: Arc::clone(&like.xs),
            pieces: pieces(&like.xs, &ys, interpolation)?,
            ys,
            guide: like.guide.clone(),
            increasing: true,
            interpolation,
            extrapolation,
        })
    }

    /// A linear table with constant extrapolation (the mission format's default curve).
    ///
    /// # Errors
    /// As [`Table1::new`].
    pub fn linear(xs: Vec<f64>, ys: Vec<f64>) -> Result<Self, MathError> {
        Self::new(xs, ys, Interpolation::Linear, Extrapolation::Constant)
    }

    /// A linear table whose abscissae may repeat (non-decreasing `xs`), as RocketPy accepts for
    /// drag curves sorted by Mach. At an abscissa `v` repeated at indices `k..=l` the value is
    /// `y_k` (the first duplicate); strictly to the right of `v` the line starts from `y_l`
    /// (the last duplicate) — exactly RocketPy's `bisect_left` linear interpolation. Constant
    /// extrapolation holds `y_first` and `y_last`. Between distinct abscissae it is an ordinary
    /// linear table.
    ///
    /// # Errors
    /// As [`Table1::new`], except that only a decreasing x is [`MathError::NotIncreasing`].
    pub fn linear_stepwise(
        xs: Vec<f64>,
        ys: Vec<f64>,
        extrapolation: Extrapolation,
    ) -> Result<Self, MathError> {
        validate(&xs, &ys, false)?;
        let pieces = Pieces::Cubic(linear_coeffs(&xs, &ys));
        let guide = Guide::new(&xs);
        Ok(Table1 {
            increasing: xs.windows(2).all(|w| w[0] < w[1]),
            xs: xs.into(),
            ys,
            pieces,
            guide,
            interpolation: Interpolation::Linear,
            extrapolation,
        })
    }

    /// Builds a table from `[x, y]` points (a curve read from a file or written inline).
    /// With [`PointOrder::SortStably`] the points are sorted stably by x first; a linear table
    /// then keeps repeated x ([`Table1::linear_stepwise`]). Errors name the index of the
    /// offending point in `points` (not in the sorted order).
    ///
    /// # Errors
    /// As [`Table1::new`]; [`MathError::NotIncreasing`] for a repeated or decreasing x that the
    /// order or interpolation does not allow.
    pub fn from_points(
        points: &[[f64; 2]],
        interpolation: Interpolation,
        extrapolation: Extrapolation,
        order: PointOrder,
    ) -> Result<Self, MathError> {
        for (index, point) in points.iter().enumerate() {
            for &value in point {
                if !value.is_finite() {
                    return Err(MathError::NotFinite { index, value });
                }
            }
        }
        let mut perm: Vec<usize> = (0..points.len()).collect();
        if order == PointOrder::SortStably {
            perm.sort_by(|&i, &j| points[i][0].total_cmp(&points[j][0]));
        }
        let xs: Vec<f64> = perm.iter().map(|&i| points[i][0]).collect();
        let ys: Vec<f64> = perm.iter().map(|&i| points[i][1]).collect();
        let built = if order == PointOrder::SortStably && interpolation == Interpolation::Linear {
            Self::linear_stepwise(xs, ys, extrapolation)
        } else {
            Self::new(xs, ys, interpolation, extrapolation)
        };
        built.map_err(|err| match err {
            MathError::NotIncreasing { index, x, previous } => MathError::NotIncreasing {
                index: perm.get(index).copied().unwrap_or(index),
                x,
                previous,
            },
            other => other,
        })
    }

    /// Samples `f` at `n ≥ 1` equally spaced points of `[a, b]` (`numpy.linspace`).
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

    /// Whether the abscissae strictly increase: always, but for a
    /// [`Table1::linear_stepwise`] table with a repeated abscissa.
    #[must_use]
    pub fn strictly_increasing(&self) -> bool {
        self.increasing
    }
    /// The domain `[x_first, x_last]` of the samples.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        (self.xs[0], self.xs[self.xs.len() - 1])
    }

    /// Interval used for `x` (RocketPy's `bisect_left` choice, clamped to the end
    /// intervals). Needs at least two samples.
    #[inline(always)]
    fn interval(&self, x: f64) -> usize {
        let n = self.xs.len();
        let k = self.guide.key(self.xs[0], x);
        let (lo, hi) = (self.guide.start[k], self.guide.start[k + 1]);
        // The count of samples below `x`: a scan of a short bucket (the usual one or two
        // samples of evenly spread abscissae), else a binary search; the same count.
        let below = if hi - lo <= 4 {
            let mut i = lo;
            while i < hi && self.xs[i] < x {
                i += 1;
            }
            i
        } else {
            lo + self.xs[lo..hi].partition_point(|&v| v < x)
        };
        below.clamp(1, n - 1) - 1
    }

    /// Whether interval `j` is the one [`Table1::interval`] would choose for `x`.
    #[inline]
    fn interval_holds(&self, j: usize, x: f64) -> bool {
        let last = self.xs.len() - 2;
        (j == 0 || self.xs[j] < x) && (j == last || x <= self.xs[j + 1])
    }

    /// Whether `other` has exactly these abscissae (bit for bit), so that a [`Location`] of
    /// one is valid for the other.
    #[must_use]
    pub fn same_abscissae(&self, other: &Table1) -> bool {
        Arc::ptr_eq(&self.xs, &other.xs)
            || (self.xs.len() == other.xs.len()
                && self
                    .xs
                    .iter()
                    .zip(other.xs.iter())
                    .all(|(a, b)| a.to_bits() == b.to_bits()))
    }

    /// Where `x` falls among the samples: the search that [`Table1::eval`] does, done once for
    /// several tables on the same abscissae.
    #[inline(always)]
    #[must_use]
    pub fn locate(&self, x: f64) -> Location {
        let n = self.xs.len();
        if x < self.xs[0] {
            Location::Below
        } else if x > self.xs[n - 1] {
            Location::Above
        } else if n == 1 {
            Location::Interval(0)
        } else {
            Location::Interval(self.interval(x))
        }
    }

    /// [`Table1::locate`] starting from `cursor` (and updating it): the interval of the
    /// previous call and its neighbours are tried before the search, the same location
    /// whatever the cursor holds. Along slowly moving abscissae (the heights, Mach numbers and
    /// times of an integration) the interval is usually the remembered one, known before `x`
    /// is, so that only two comparisons wait for `x`.
    #[inline(always)]
    #[must_use]
    pub fn locate_with(&self, x: f64, cursor: &mut Cursor) -> Location {
        let n = self.xs.len();
        if x < self.xs[0] {
            Location::Below
        } else if x > self.xs[n - 1] {
            Location::Above
        } else if n == 1 {
            Location::Interval(0)
        } else {
            Location::Interval(self.interval_with(x, cursor))
        }
    }

    /// [`Table1::interval`] starting from `cursor` (and updating it): the remembered interval
    /// and its neighbours, then the search. Needs at least two samples.
    #[inline(always)]
    fn interval_with(&self, x: f64, cursor: &mut Cursor) -> usize {
        let n = self.xs.len();
        let j = cursor.0.min(n - 2);
        let i = if self.interval_holds(j, x) {
            j
        } else if j + 2 < n && self.interval_holds(j + 1, x) {
            j + 1
        } else if j > 0 && self.interval_holds(j - 1, x) {
            j - 1
        } else {
            self.interval(x)
        };
        cursor.0 = i;
        i
    }

    /// The piece that evaluates `at`, or the value itself where extrapolation is constant or
    /// zero. An interval past this table's (a location from a table with other abscissae) is
    /// clamped: a wrong value, never a panic.
    #[inline(always)]
    fn piece_at(&self, at: Location) -> Result<usize, f64> {
        let n = self.xs.len();
        let end = n.saturating_sub(2);
        match (at, self.extrapolation) {
            (Location::Interval(i), _) => Ok(i.min(end)),
            (Location::Below, Extrapolation::Natural) => Ok(0),
            (Location::Above, Extrapolation::Natural) => Ok(end),
            (Location::Below, Extrapolation::Constant) => Err(self.ys[0]),
            (Location::Above, Extrapolation::Constant) => Err(self.ys[n - 1]),
            (_, Extrapolation::Zero) => Err(0.0),
        }
    }

    /// Value at `x` located by [`Table1::locate`] of a table with the same abscissae (this one
    /// or another): equal to [`Table1::eval`]`(x)`.
    #[inline(always)]
    #[must_use]
    pub fn eval_at(&self, at: Location, x: f64) -> f64 {
        match self.piece_at(at) {
            Err(v) => v,
            Ok(_) if self.xs.len() == 1 => self.ys[0],
            Ok(i) => self.piece_value(i, x),
        }
    }

    /// First derivative at `x` located by [`Table1::locate`]: equal to
    /// [`Table1::derivative`]`(x)`.
    #[inline]
    #[must_use]
    pub fn derivative_at(&self, at: Location, x: f64) -> f64 {
        match self.piece_at(at) {
            Ok(i) if self.xs.len() > 1 => self.piece_derivative(i, x),
            _ => 0.0,
        }
    }

    /// Second derivative at `x` located by [`Table1::locate`]: equal to
    /// [`Table1::second_derivative`]`(x)`.
    #[inline]
    #[must_use]
    pub fn second_derivative_at(&self, at: Location, x: f64) -> f64 {
        match self.piece_at(at) {
            Ok(i) if self.xs.len() > 1 => match &self.pieces {
                Pieces::Cubic(coeffs) => {
                    let [_, _, c, e] = coeffs[i];
                    2.0 * c + 6.0 * e * (x - self.xs[i])
                }
                Pieces::Polynomial(p) => p.second_derivative(x),
            },
            _ => 0.0,
        }
    }

    /// The interpolant on interval `i` (or the polynomial) at `x`.
    #[inline(always)]
    fn piece_value(&self, i: usize, x: f64) -> f64 {
        match &self.pieces {
            Pieces::Cubic(coeffs) => cubic_value(self.xs[i], coeffs[i], x),
            Pieces::Polynomial(p) => p.eval(x),
        }
    }

    /// The piece that [`Table1::eval_at`] evaluates at `at`, as a [`Piece`]: a constant where
    /// the table holds or zeroes its ends or has one sample; `None` for a single polynomial.
    #[must_use]
    pub fn piece(&self, at: Location) -> Option<Piece> {
        match self.piece_at(at) {
            Err(v) => Some(Piece::constant(v)),
            Ok(_) if self.xs.len() == 1 => Some(Piece::constant(self.ys[0])),
            Ok(i) => match &self.pieces {
                Pieces::Cubic(coeffs) => Some(Piece {
                    x0: self.xs[i],
                    coeffs: coeffs[i],
                }),
                Pieces::Polynomial(_) => None,
            },
        }
    }

    /// Value at `x`.
    #[inline]
    #[must_use]
    pub fn eval(&self, x: f64) -> f64 {
        self.eval_at(self.locate(x), x)
    }

    /// Value at `x`, starting the interval search from `cursor` (and updating it). Same result
    /// as [`Table1::eval`]; faster when successive `x` are close.
    #[inline]
    #[must_use]
    pub fn eval_with(&self, x: f64, cursor: &mut Cursor) -> f64 {
        self.eval_at(self.locate_with(x, cursor), x)
    }

    /// Evaluates at every `xs[k]` into `out[k]`, hunting intervals with a [`Cursor`] (fast for
    /// sorted `xs`). No allocation.
    ///
    /// # Panics
    /// When `xs` and `out` differ in length (a programming error).
    pub fn eval_into(&self, xs: &[f64], out: &mut [f64]) {
        assert_eq!(
            xs.len(),
            out.len(),
            "eval_into: input and output lengths differ"
        );
        let mut cursor = Cursor::default();
        for (o, &x) in out.iter_mut().zip(xs) {
            *o = self.eval_with(x, &mut cursor);
        }
    }

    /// First derivative at `x`: exact for the interpolant (the left interval's slope at an
    /// interior node, RocketPy's `bisect_left` choice, which is also what RocketPy 1.13's
    /// complex-step derivative returns for a table); zero where extrapolation is constant or
    /// zero.
    #[must_use]
    pub fn derivative(&self, x: f64) -> f64 {
        self.derivative_at(self.locate(x), x)
    }

    /// Derivative of piece `i` (or of the polynomial) at `x`.
    #[inline]
    fn piece_derivative(&self, i: usize, x: f64) -> f64 {
        match &self.pieces {
            Pieces::Cubic(coeffs) => {
                let [_, b, c, e] = coeffs[i];
                let d = x - self.xs[i];
                b + d * (2.0 * c + 3.0 * d * e)
            }
            Pieces::Polynomial(p) => p.derivative(x),
        }
    }

    /// Second derivative at `x`: exact for the interpolant (zero for linear tables, as
    /// RocketPy returns for them); zero where extrapolation is constant or zero.
    #[must_use]
    pub fn second_derivative(&self, x: f64) -> f64 {
        self.second_derivative_at(self.locate(x), x)
    }

    /// `∫` of the natural continuation from `s` to `e` (both on one side of the samples).
    fn natural_integral(&self, left: bool, s: f64, e: f64) -> f64 {
        let n = self.xs.len();
        match &self.pieces {
            Pieces::Cubic(coeffs) if n > 1 => {
                let i = if left { 0 } else { n - 2 };
                piece_integral(coeffs[i], s - self.xs[i], e - self.xs[i])
            }
            Pieces::Polynomial(p) => p.integral(s, e),
            Pieces::Cubic(_) => self.ys[0] * (e - s),
        }
    }

    /// Exact definite integral of the interpolant (with its extrapolation) from `a` to `b`.
    #[must_use]
    pub fn integral(&self, a: f64, b: f64) -> f64 {
        self.integral_with(a, b, &mut Cursor::default())
    }

    /// [`Table1::integral`] with the intervals of the ends searched from `cursor` (and the
    /// cursor left at the interval of the upper end): the same number, cheaper along
    /// consecutive intervals of integration `[t_0, t_1], [t_1, t_2], …`.
    #[must_use]
    pub fn integral_with(&self, a: f64, b: f64, cursor: &mut Cursor) -> f64 {
        let reversed = b < a;
        let (a, b) = if reversed { (b, a) } else { (a, b) };
        let n = self.xs.len();
        let (x0, x1) = self.domain();
        let mut total = 0.0;
        if a < x0 {
            let hi = b.min(x0);
            total += match self.extrapolation {
                Extrapolation::Constant => self.ys[0] * (hi - a),
                Extrapolation::Zero => 0.0,
                Extrapolation::Natural => self.natural_integral(true, a, hi),
            };
        }
        if b > x1 {
            let lo = a.max(x1);
            total += match self.extrapolation {
                Extrapolation::Constant => self.ys[n - 1] * (b - lo),
                Extrapolation::Zero => 0.0,
                Extrapolation::Natural => self.natural_integral(false, lo, b),
            };
        }
        let lo = a.max(x0);
        let hi = b.min(x1);
        if n > 1 && hi > lo {
            match &self.pieces {
                Pieces::Cubic(coeffs) => {
                    let first = self.interval_with(lo, cursor);
                    // `hi` in the interval of `lo` (the usual short integral) needs no search.
                    let last = if hi <= self.xs[first + 1] {
                        first
                    } else {
                        self.interval_with(hi, cursor)
                    };
                    total = (first..=last).fold(total, |total, i| {
                        let (left, right) = (self.xs[i], self.xs[i + 1]);
                        let s = lo.max(left);
                        let e = hi.min(right);
                        if e > s {
                            total + piece_integral(coeffs[i], s - left, e - left)
                        } else {
                            total
                        }
                    });
                }
                Pieces::Polynomial(p) => total += p.integral(lo, hi),
            }
        }
        if reversed { -total } else { total }
    }

    /// The table times `k`: `scaled(k)(x) = k · self(x)`. Every interpolant and extrapolation
    /// here is linear in the samples, so scaling the samples and the coefficients gives the
    /// interpolant of the scaled samples exactly (a cluster of `k` identical motors).
    #[must_use]
    pub fn scaled(&self, k: f64) -> Table1 {
        let pieces = match &self.pieces {
            Pieces::Cubic(c) => Pieces::Cubic(c.iter().map(|p| p.map(|a| k * a)).collect()),
            Pieces::Polynomial(p) => Pieces::Polynomial(Polynomial {
                center: p.center,
                half_width: p.half_width,
                coeffs: p.coeffs.iter().map(|a| k * a).collect(),
            }),
        };
        Table1 {
            xs: Arc::clone(&self.xs),
            ys: self.ys.iter().map(|y| k * y).collect(),
            pieces,
            guide: self.guide.clone(),
            increasing: self.increasing,
            interpolation: self.interpolation,
            extrapolation: self.extrapolation,
        }
    }

    /// The table moved by `dx` along its abscissa: `shifted(dx)(x) = self(x − dx)` (a motor
    /// ignited `dx` s late). Piecewise tables keep their coefficients, which are written in
    /// the offset from each sample; a single polynomial is fitted again.
    ///
    /// # Errors
    /// [`MathError::NotFinite`] for a non-finite `dx`, [`MathError::NotIncreasing`] when the
    /// shift rounds two abscissae together, as [`Table1::new`].
    pub fn shifted(&self, dx: f64) -> Result<Table1, MathError> {
        let xs: Vec<f64> = self.xs.iter().map(|&x| x + dx).collect();
        if let Pieces::Polynomial(_) = self.pieces {
            return Table1::new(xs, self.ys.clone(), self.interpolation, self.extrapolation);
        }
        validate(&xs, &self.ys, self.increasing)?;
        Ok(Table1 {
            guide: Guide::new(&xs),
            xs: xs.into(),
            ys: self.ys.clone(),
            pieces: self.pieces.clone(),
            increasing: self.increasing,
            interpolation: self.interpolation,
            extrapolation: self.extrapolation,
        })
    }

    /// The inverse function of a table with strictly monotone values: the samples with x and
    /// y swapped (reversed when decreasing), with this table's interpolation and
    /// extrapolation. Exact for linear tables; for the others it interpolates the swapped
    /// samples.
    ///
    /// # Errors
    /// [`MathError::NotMonotone`] naming the first value that breaks strict monotonicity;
    /// [`MathError::TooFewPoints`] for fewer than two samples.
    pub fn inverse(&self) -> Result<Table1, MathError> {
        let n = self.ys.len();
        if n < 2 {
            return Err(MathError::TooFewPoints { needed: 2, got: n });
        }
        let increasing = self.ys[1] > self.ys[0];
        for index in 1..n {
            let (previous, y) = (self.ys[index - 1], self.ys[index]);
            if (increasing && y <= previous) || (!increasing && y >= previous) {
                return Err(MathError::NotMonotone { index, y, previous });
            }
        }
        let (mut xs, mut ys) = (self.ys.to_vec(), self.xs.to_vec());
        if !increasing {
            xs.reverse();
            ys.reverse();
        }
        Table1::new(xs, ys, self.interpolation, self.extrapolation)
    }

    /// The table of `scale · f + offset` (exact for every interpolation: each is affine in the
    /// sample values).
    pub(crate) fn map_affine(&self, scale: f64, offset: f64) -> Table1 {
        let pieces = match &self.pieces {
            Pieces::Cubic(coeffs) => Pieces::Cubic(
                coeffs
                    .iter()
                    .map(|&[a, b, c, e]| [scale * a + offset, scale * b, scale * c, scale * e])
                    .collect(),
            ),
            Pieces::Polynomial(p) => Pieces::Polynomial(Polynomial {
                center: p.center,
                half_width: p.half_width,
                coeffs: p
                    .coeffs
                    .iter()
                    .enumerate()
                    .map(|(k, &c)| {
                        if k == 0 {
                            scale * c + offset
                        } else {
                            scale * c
                        }
                    })
                    .collect(),
            }),
        };
        Table1 {
            xs: Arc::clone(&self.xs),
            ys: self.ys.iter().map(|&y| scale * y + offset).collect(),
            pieces,
            guide: self.guide.clone(),
            increasing: self.increasing,
            interpolation: self.interpolation,
            extrapolation: self.extrapolation,
        }
    }

    /// Calls `visit` with every abscissa in `[a, b]` where the extremum of this table over
    /// `[a, b]` may lie: `a`, `b`, the samples inside and the stationary points of each cubic
    /// piece (also of the naturally extrapolated end pieces). Returns `false` (visiting
    /// nothing) for a polynomial table, whose extrema must be searched numerically.
    pub(crate) fn extremum_candidates(&self, a: f64, b: f64, mut visit: impl FnMut(f64)) -> bool {
        let Pieces::Cubic(coeffs) = &self.pieces else {
            return false;
        };
        visit(a);
        visit(b);
        let n = self.xs.len();
        for (i, &[_, slope, c, e]) in coeffs.iter().enumerate() {
            let natural = self.extrapolation == Extrapolation::Natural;
            let lo = if i == 0 && natural {
                a
            } else {
                self.xs[i].max(a)
            };
            let hi = if i + 2 == n && natural {
                b
            } else {
                self.xs[i + 1].min(b)
            };
            if lo > hi {
                continue;
            }
            if self.xs[i] > a && self.xs[i] < b {
                visit(self.xs[i]);
            }
            for d in stationary_points(slope, c, e).into_iter().flatten() {
                let x = self.xs[i] + d;
                if x >= lo && x <= hi {
                    visit(x);
                }
            }
        }
        if n > 1 && self.xs[n - 1] > a && self.xs[n - 1] < b {
            visit(self.xs[n - 1]);
        }
        true
    }
}

/// Real roots `d` of `b + 2c·d + 3e·d² = 0` (numerically stable quadratic formula).
fn stationary_points(b: f64, c: f64, e: f64) -> [Option<f64>; 2] {
    if e.abs() > 0.0 {
        let disc = c * c - 3.0 * e * b;
        if disc < 0.0 {
            return [None, None];
        }
        let q = -(c + c.signum() * disc.sqrt());
        if q.abs() > 0.0 {
            [Some(q / (3.0 * e)), Some(b / q)]
        } else {
            [Some(0.0), None]
        }
    } else if c.abs() > 0.0 {
        [Some(-b / (2.0 * c)), None]
    } else {
        [None, None]
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

/// Linear pieces. A zero-width interval (repeated x) is never used inside the samples; it holds
/// its left value, except the last interval, whose value is the last sample so that natural
/// extrapolation to the right continues from it.
fn linear_coeffs(xs: &[f64], ys: &[f64]) -> Arc<[[f64; 4]]> {
    linear_coeffs_checked(xs, ys).0
}

/// [`linear_coeffs`] and the first interval whose slope is not finite, if any (finite
/// samples can still give a slope that overflows; the other coefficients are samples and
/// zeros).
fn linear_coeffs_checked(xs: &[f64], ys: &[f64]) -> (Arc<[[f64; 4]]>, Option<usize>) {
    let last = xs.len().saturating_sub(2);
    let mut bad = None;
    let coeffs = xs
        .windows(2)
        .zip(ys.windows(2))
        .enumerate()
        .map(|(i, (x, y))| {
            let h = x[1] - x[0];
            if h > 0.0 {
                let slope = (y[1] - y[0]) / h;
                if bad.is_none() && !slope.is_finite() {
                    bad = Some(i);
                }
                [y[0], slope, 0.0, 0.0]
            } else if i == last {
                [y[1], 0.0, 0.0, 0.0]
            } else {
                [y[0], 0.0, 0.0, 0.0]
            }
        })
        .collect();
    (coeffs, bad)
}

/// Natural cubic spline: solve for the second derivatives `M_i` (M_0 = M_{n-1} = 0).
fn natural_spline_coeffs(xs: &[f64], ys: &[f64]) -> Arc<[[f64; 4]]> {
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
            [
                ys[i],
                b,
                second[i] / 2.0,
                (second[i + 1] - second[i]) / (6.0 * hi),
            ]
        })
        .collect()
}

/// Cubic Hermite pieces with node slopes `t` (C¹ by construction).
fn hermite_coeffs(xs: &[f64], ys: &[f64], t: &[f64]) -> Arc<[[f64; 4]]> {
    (0..xs.len() - 1)
        .map(|i| {
            let h = xs[i + 1] - xs[i];
            let m = (ys[i + 1] - ys[i]) / h;
            [
                ys[i],
                t[i],
                (3.0 * m - 2.0 * t[i] - t[i + 1]) / h,
                (t[i] + t[i + 1] - 2.0 * m) / (h * h),
            ]
        })
        .collect()
}

/// Secant slopes `m_i` of the intervals.
fn secants(xs: &[f64], ys: &[f64]) -> Vec<f64> {
    xs.windows(2)
        .zip(ys.windows(2))
        .map(|(x, y)| (y[1] - y[0]) / (x[1] - x[0]))
        .collect()
}

/// Akima (1970) node slopes. The secants are extended by two on each side with Akima's
/// end rule `m_{−1} = 2m_0 − m_1`, `m_{−2} = 2m_{−1} − m_0` (eqs. 8–10 of the paper); at
/// node `i`, with `w_1 = |m_{i+1} − m_i|`, `w_2 = |m_{i−1} − m_{i−2}|`, the slope is
/// `(w_1 m_{i−1} + w_2 m_i)/(w_1 + w_2)`, or the mean of `m_{i−1}`, `m_i` when both weights
/// vanish (eq. 1).
fn akima_slopes(xs: &[f64], ys: &[f64]) -> Vec<f64> {
    let n = xs.len();
    let m = secants(xs, ys);
    if n < 3 {
        return vec![m.first().copied().unwrap_or(0.0); n];
    }
    // ext[k + 2] = m_k for k = −2 ..= n.
    let mut ext = vec![0.0; n + 3];
    ext[2..n + 1].copy_from_slice(&m);
    ext[1] = 2.0 * ext[2] - ext[3];
    ext[0] = 2.0 * ext[1] - ext[2];
    ext[n + 1] = 2.0 * ext[n] - ext[n - 1];
    ext[n + 2] = 2.0 * ext[n + 1] - ext[n];
    (0..n)
        .map(|i| {
            let (m_l2, m_l1, m_r1, m_r2) = (ext[i], ext[i + 1], ext[i + 2], ext[i + 3]);
            let w1 = (m_r2 - m_r1).abs();
            let w2 = (m_l1 - m_l2).abs();
            if w1 + w2 > 0.0 {
                (w1 * m_l1 + w2 * m_r1) / (w1 + w2)
            } else {
                0.5 * (m_l1 + m_r1)
            }
        })
        .collect()
}

/// The interpolating polynomial through all (≥ 2) samples, solved by LU with partial
/// pivoting on the Vandermonde matrix of `t = (x − center)/half_width ∈ [−1, 1]`.
fn polynomial(xs: &[f64], ys: &[f64]) -> Result<Polynomial, MathError> {
    let n = xs.len();
    let (first, last) = (xs[0], xs[n - 1]);
    let center = 0.5 * (first + last);
    let half_width = 0.5 * (last - first);
    let t: Vec<f64> = xs.iter().map(|&x| (x - center) / half_width).collect();
    let matrix = DMatrix::from_fn(n, n, |r, c| t[r].powi(c as i32));
    let rhs = DVector::from_column_slice(ys);
    let solution = matrix
        .lu()
        .solve(&rhs)
        .ok_or(MathError::Singular { size: n })?;
    if solution.iter().any(|c| !c.is_finite()) {
        return Err(MathError::Singular { size: n });
    }
    Ok(Polynomial {
        center,
        half_width,
        coeffs: solution.iter().copied().collect(),
    })
}

/// `ys` at `x` on the polyline through `(xs, ys)` (`xs` increasing, both of one length, at
/// least one point), held at its first and last values outside `[xs₀, xsₙ]`: linear
/// interpolation of a series read once, without building a [`Table1`] (a simulated flight's
/// altitude at a log sample's time).
#[must_use]
pub fn interpolate_clamped(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let i = xs.partition_point(|&v| v < x);
    if i == 0 {
        return ys[0];
    }
    if i >= xs.len() {
        return ys[xs.len() - 1];
    }
    let (x0, x1) = (xs[i - 1], xs[i]);
    ys[i - 1] + (ys[i] - ys[i - 1]) * (x - x0) / (x1 - x0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_polyline_interpolates_and_holds_its_ends() {
        let (xs, ys) = ([0.0, 1.0, 3.0], [10.0, 20.0, 0.0]);
        assert!((interpolate_clamped(&xs, &ys, 0.5) - 15.0).abs() < 1e-12);
        assert!((interpolate_clamped(&xs, &ys, 2.0) - 10.0).abs() < 1e-12);
        assert!((interpolate_clamped(&xs, &ys, -1.0) - 10.0).abs() < 1e-12);
        assert!(interpolate_clamped(&xs, &ys, 9.0).abs() < 1e-12);
        assert!((interpolate_clamped(&xs, &ys, 1.0) - 20.0).abs() < 1e-12);
    }

    #[test]
    fn a_scaled_table_is_the_table_of_the_scaled_samples() {
        let xs = vec![0.0, 0.4, 1.1, 1.5, 2.6];
        let ys = vec![0.0, 3.0, -1.0, 2.5, 0.5];
        for interpolation in [
            Interpolation::Linear,
            Interpolation::Spline,
            Interpolation::Akima,
            Interpolation::Polynomial,
        ] {
            for extrapolation in [
                Extrapolation::Constant,
                Extrapolation::Natural,
                Extrapolation::Zero,
            ] {
                let table = Table1::new(xs.clone(), ys.clone(), interpolation, extrapolation)
                    .expect("valid");
                let scaled_samples = Table1::new(
                    xs.clone(),
                    ys.iter().map(|y| 4.0 * y).collect(),
                    interpolation,
                    extrapolation,
                )
                .expect("valid");
                let scaled = table.scaled(4.0);
                for x in [-0.5, 0.0, 0.2, 0.4, 0.9, 1.3, 2.0, 2.6, 3.1] {
                    let (a, b) = (scaled.eval(x), scaled_samples.eval(x));
                    assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0), "{x}: {a} vs {b}");
                    assert!((a - 4.0 * table.eval(x)).abs() <= 1e-12 * a.abs().max(1.0));
                }
            }
        }
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * (1.0 + b.abs())
    }

    #[test]
    fn shifted_tables_are_the_same_function_later() {
        let xs = vec![0.0, 0.4, 1.0, 2.5, 3.0];
        let ys = vec![0.0, 3.0, 2.0, 2.5, 0.0];
        for interpolation in [
            Interpolation::Linear,
            Interpolation::Spline,
            Interpolation::Akima,
            Interpolation::Polynomial,
        ] {
            let t =
                Table1::new(xs.clone(), ys.clone(), interpolation, Extrapolation::Zero).unwrap();
            let s = t.shifted(7.25).unwrap();
            for k in 0..=40 {
                let x = -0.5 + 0.1 * f64::from(k);
                assert!(
                    close(s.eval(x + 7.25), t.eval(x), 1e-12),
                    "{interpolation:?} {x}"
                );
                assert!(close(s.derivative(x + 7.25), t.derivative(x), 1e-9));
            }
        }
        let stepwise = Table1::linear_stepwise(
            vec![0.0, 1.0, 1.0, 2.0],
            vec![0.0, 1.0, 4.0, 4.0],
            Extrapolation::Constant,
        )
        .unwrap();
        let s = stepwise.shifted(2.0).unwrap();
        assert!(close(s.eval(3.0), 1.0, 1e-15) && close(s.eval(3.5), 4.0, 1e-15));
        assert!(stepwise.shifted(f64::NAN).is_err());
    }

    #[test]
    fn linear_reproduces_nodes_and_midpoints() {
        let t = Table1::linear(vec![0.0, 1.0, 3.0], vec![0.0, 2.0, 0.0]).unwrap();
        assert!(close(t.eval(1.0), 2.0, 1e-15));
        assert!(close(t.eval(2.0), 1.0, 1e-15));
        assert!(close(t.eval(-1.0), 0.0, 1e-15));
        assert!(close(t.eval(10.0), 0.0, 1e-15));
        assert!(close(t.integral(0.0, 3.0), 3.0, 1e-14));
        // bisect_left: the slope at an interior node is the left interval's.
        assert!(close(t.derivative(1.0), 2.0, 1e-15));
        assert!(close(t.derivative(1.0 + 1e-9), -1.0, 1e-15));
    }

    #[test]
    fn spline_is_exact_for_lines_and_natural_at_ends() {
        let xs = linspace(0.0, 4.0, 9);
        let ys: Vec<f64> = xs.iter().map(|x| 3.0 * x - 1.0).collect();
        let t = Table1::new(xs, ys, Interpolation::Spline, Extrapolation::Natural).unwrap();
        for x in [-2.0, 0.3, 1.7, 3.99, 6.0] {
            assert!(close(t.eval(x), 3.0 * x - 1.0, 1e-12));
            assert!(close(t.derivative(x), 3.0, 1e-12));
            assert!(close(t.second_derivative(x), 0.0, 1e-12));
        }
    }

    #[test]
    fn akima_reproduces_lines_and_keeps_steps_flat() {
        // Akima's method is exact for straight lines (all secants equal).
        let xs = vec![0.0, 0.5, 2.0, 3.0, 5.0];
        let ys: Vec<f64> = xs.iter().map(|x| 2.0 - 0.5 * x).collect();
        let t = Table1::new(xs, ys, Interpolation::Akima, Extrapolation::Natural).unwrap();
        for x in [-1.0, 0.2, 1.1, 2.5, 4.9, 7.0] {
            assert!(close(t.eval(x), 2.0 - 0.5 * x, 1e-14));
        }
        // A step: Akima does not overshoot on the flat parts (weights vanish there).
        let xs = vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        let ys = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        let t = Table1::new(xs, ys, Interpolation::Akima, Extrapolation::Constant).unwrap();
        for k in 0..=20 {
            let x = 0.1 * f64::from(k);
            assert!(t.eval(x).abs() < 1e-15, "x = {x}: {}", t.eval(x));
        }
    }

    #[test]
    fn polynomial_is_the_interpolating_polynomial() {
        let f = |x: f64| 1.0 - 2.0 * x + 0.5 * x.powi(3) - 0.1 * x.powi(4);
        let t = Table1::sample(
            f,
            -1.0,
            4.0,
            5,
            Interpolation::Polynomial,
            Extrapolation::Natural,
        )
        .unwrap();
        for x in [-3.0, -0.3, 1.234, 3.9, 6.0] {
            assert!(close(t.eval(x), f(x), 1e-11), "{x}");
            let df = -2.0 + 1.5 * x * x - 0.4 * x.powi(3);
            assert!(close(t.derivative(x), df, 1e-11));
            assert!(close(t.second_derivative(x), 3.0 * x - 1.2 * x * x, 1e-11));
        }
        let antiderivative = |x: f64| x - x * x + 0.125 * x.powi(4) - 0.02 * x.powi(5);
        assert!(close(
            t.integral(-2.0, 5.0),
            antiderivative(5.0) - antiderivative(-2.0),
            1e-11
        ));
    }

    #[test]
    fn stepwise_follows_bisect_left() {
        let t = Table1::linear_stepwise(
            vec![0.0, 1.0, 1.0, 1.0, 2.0],
            vec![0.0, 1.0, 5.0, 3.0, 4.0],
            Extrapolation::Constant,
        )
        .unwrap();
        assert!(
            close(t.eval(1.0), 1.0, 1e-15),
            "first duplicate at the repeated x"
        );
        assert!(
            close(t.eval(1.5), 3.5, 1e-15),
            "last duplicate to its right"
        );
        assert!(close(t.eval(0.5), 0.5, 1e-15));
        assert!(close(t.integral(0.0, 2.0), 0.5 + 3.5, 1e-15));
        let mut cursor = Cursor::default();
        for x in [0.5, 1.0, 1.0 + 1e-12, 1.5, 2.0, 1.0, 0.0] {
            assert!(close(t.eval_with(x, &mut cursor), t.eval(x), 1e-15));
        }
        assert!(matches!(
            Table1::new(
                vec![0.0, 1.0, 1.0],
                vec![0.0; 3],
                Interpolation::Spline,
                Extrapolation::Zero
            ),
            Err(MathError::NotIncreasing { index: 2, .. })
        ));
        assert!(matches!(
            Table1::linear_stepwise(vec![0.0, 1.0, 0.5], vec![0.0; 3], Extrapolation::Zero),
            Err(MathError::NotIncreasing { index: 2, .. })
        ));
    }

    #[test]
    fn from_points_sorts_stably_and_names_original_rows() {
        let points = [[2.0, 20.0], [1.0, 10.0], [2.0, 21.0], [0.0, 0.0]];
        let t = Table1::from_points(
            &points,
            Interpolation::Linear,
            Extrapolation::Constant,
            PointOrder::SortStably,
        )
        .unwrap();
        assert_eq!(t.xs(), &[0.0, 1.0, 2.0, 2.0]);
        assert_eq!(t.ys(), &[0.0, 10.0, 20.0, 21.0]);
        let err = Table1::from_points(
            &points,
            Interpolation::Spline,
            Extrapolation::Constant,
            PointOrder::SortStably,
        );
        assert!(
            matches!(err, Err(MathError::NotIncreasing { index: 2, .. })),
            "{err:?}"
        );
        let err = Table1::from_points(
            &points,
            Interpolation::Linear,
            Extrapolation::Constant,
            PointOrder::StrictlyIncreasing,
        );
        assert!(
            matches!(err, Err(MathError::NotIncreasing { index: 1, .. })),
            "{err:?}"
        );
    }

    #[test]
    fn inverse_swaps_and_orders() {
        let t = Table1::linear(vec![0.0, 1.0, 2.0], vec![4.0, 2.0, 1.0]).unwrap();
        let inv = t.inverse().unwrap();
        assert_eq!(inv.xs(), &[1.0, 2.0, 4.0]);
        assert!(close(inv.eval(3.0), 0.5, 1e-15));
        let flat = Table1::linear(vec![0.0, 1.0, 2.0], vec![0.0, 1.0, 1.0]).unwrap();
        assert!(matches!(
            flat.inverse(),
            Err(MathError::NotMonotone { index: 2, .. })
        ));
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
        assert!(matches!(
            Table1::linear(vec![], vec![]),
            Err(MathError::TooFewPoints { .. })
        ));
        // Finite samples 3e-222 apart: the spline's curvature overflows.
        let (xs, ys) = (vec![0.0, 3e-222, 1.0], vec![0.0, 1.6, 0.0]);
        assert!(matches!(
            Table1::new(
                xs.clone(),
                ys.clone(),
                Interpolation::Spline,
                Extrapolation::Constant
            ),
            Err(MathError::InterpolantNotFinite { .. })
        ));
        assert!(Table1::linear(xs, ys).is_ok());
    }

    #[test]
    fn single_point_tables() {
        let t = Table1::new(
            vec![1.0],
            vec![3.0],
            Interpolation::Polynomial,
            Extrapolation::Zero,
        )
        .unwrap();
        assert!(close(t.eval(1.0), 3.0, 1e-15));
        assert!(close(t.eval(2.0), 0.0, 1e-15));
        let t = Table1::new(
            vec![1.0],
            vec![3.0],
            Interpolation::Akima,
            Extrapolation::Natural,
        )
        .unwrap();
        assert!(close(t.eval(-5.0), 3.0, 1e-15));
        assert!(close(t.integral(0.0, 2.0), 6.0, 1e-15));
    }

    #[test]
    fn one_location_serves_tables_on_the_same_abscissae() {
        let xs = vec![0.0, 0.5, 1.5, 1.5, 3.0, 4.0];
        let probes = [-1.0, 0.0, 0.2, 0.5, 1.5, 2.0, 3.0, 3.9, 4.0, 7.0];
        let kinds = [
            Interpolation::Linear,
            Interpolation::Spline,
            Interpolation::Akima,
            Interpolation::Polynomial,
        ];
        let extrapolations = [
            Extrapolation::Constant,
            Extrapolation::Natural,
            Extrapolation::Zero,
        ];
        let base =
            Table1::linear_stepwise(xs.clone(), vec![0.0; xs.len()], Extrapolation::Zero).unwrap();
        let single = Table1::new(
            vec![2.0],
            vec![4.0],
            Interpolation::Linear,
            Extrapolation::Zero,
        )
        .unwrap();
        let mut tables = vec![single.clone()];
        for (k, i) in kinds.into_iter().enumerate() {
            for e in extrapolations {
                let ys = xs.iter().map(|x| (x + k as f64).sin()).collect();
                // Repeated abscissae only for linear tables (stepwise semantics).
                let t = if i == Interpolation::Linear {
                    Table1::linear_stepwise(xs.clone(), ys, e)
                } else {
                    let strict = [0.0, 0.5, 1.5, 1.7, 3.0, 4.0];
                    Table1::new(strict.to_vec(), ys, i, e)
                };
                tables.push(t.unwrap());
            }
        }
        for t in &tables {
            for x in probes {
                // A location from the table itself, or from another on the same abscissae.
                let at = if base.same_abscissae(t) {
                    base.locate(x)
                } else {
                    t.locate(x)
                };
                let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
                assert!(same(t.eval_at(at, x), t.eval(x)), "{t:?} at {x}");
                assert!(same(t.derivative_at(at, x), t.derivative(x)));
                assert!(same(t.second_derivative_at(at, x), t.second_derivative(x)));
            }
        }
        // A cursor carried along the probes (both ways), or stale from a longer table,
        // locates exactly as the search does.
        let mut stale = Cursor::default();
        let long = Table1::linear((0..50).map(f64::from).collect(), vec![0.0; 50]).unwrap();
        assert_eq!(long.locate_with(40.5, &mut stale), Location::Interval(40));
        for t in tables.iter().chain([&base]) {
            let mut carried = Cursor::default();
            for &x in probes.iter().chain(probes.iter().rev()) {
                assert_eq!(t.locate_with(x, &mut carried), t.locate(x), "{t:?} at {x}");
                assert_eq!(t.locate_with(x, &mut stale.clone()), t.locate(x));
            }
        }
        assert!(!base.same_abscissae(&single));
        // A location of a longer table is clamped, not a panic.
        assert!(single.eval_at(base.locate(3.5), 2.0).is_finite());
    }

    #[test]
    fn errors_name_the_first_offending_point() {
        let nan_first = Table1::linear(vec![0.0, 1.0, 1.0, 2.0], vec![0.0, f64::NAN, 0.0, 0.0]);
        assert!(matches!(
            nan_first,
            Err(MathError::NotFinite { index: 1, .. })
        ));
        let order_first = Table1::linear(vec![0.0, 2.0, 1.0, f64::NAN], vec![0.0; 4]);
        assert!(matches!(
            order_first,
            Err(MathError::NotIncreasing { index: 2, .. })
        ));
        // At one index a non-finite value comes before the order.
        let same = Table1::linear(vec![0.0, 2.0, 1.0], vec![0.0, 0.0, f64::INFINITY]);
        assert!(matches!(same, Err(MathError::NotFinite { index: 2, .. })));
        let stepwise =
            Table1::linear_stepwise(vec![0.0, 1.0, 1.0, 0.5], vec![0.0; 4], Extrapolation::Zero);
        assert!(matches!(
            stepwise,
            Err(MathError::NotIncreasing { index: 3, .. })
        ));
    }

    #[test]
    fn bucket_is_the_clamped_floor() {
        // The saturating unsigned floor clamped to `last`, which it replaces.
        let reference = |v: f64, last: usize| (v as usize).min(last);
        let values = [
            f64::NAN,
            f64::NEG_INFINITY,
            -1e300,
            -1.0,
            -0.5,
            -0.0,
            0.0,
            0.999_999,
            1.0,
            6.5,
            7.0,
            7.5,
            1e10,
            9.3e18,
            2e19,
            f64::INFINITY,
        ];
        for last in [0, 1, 7, 1000] {
            for v in values {
                assert_eq!(bucket(v, 1.0, last), reference(v, last), "{v} {last}");
            }
        }
        // A degenerate span (one sample, or all samples equal): 0·∞ is NaN, bucket 0.
        assert_eq!(bucket(0.0, f64::INFINITY, 0), 0);
    }

    #[test]
    fn tables_on_the_same_abscissae_are_the_tables_on_a_copy() {
        let xs = vec![0.0, 0.5, 1.5, 1.7, 3.0, 4.0];
        let like = Table1::linear(xs.clone(), vec![0.0; xs.len()]).unwrap();
        let ys: Vec<f64> = xs.iter().map(|x: &f64| x.sin() + 0.1 * x * x).collect();
        let kinds = [
            Interpolation::Linear,
            Interpolation::Spline,
            Interpolation::Akima,
            Interpolation::Polynomial,
        ];
        for kind in kinds {
            for e in [Extrapolation::Natural, Extrapolation::Zero] {
                let shared = Table1::on_same_abscissae(&like, ys.clone(), kind, e).unwrap();
                let copied = Table1::new(xs.clone(), ys.clone(), kind, e).unwrap();
                assert_eq!(shared, copied, "{kind:?} {e:?}");
                assert!(shared.same_abscissae(&like) && like.same_abscissae(&shared));
                let mut cursor = Cursor::default();
                for x in [-1.0, 0.0, 0.2, 1.5, 1.6, 3.9, 4.0, 5.0] {
                    assert_eq!(shared.locate(x), copied.locate(x));
                    assert_eq!(shared.locate_with(x, &mut cursor), copied.locate(x));
                }
            }
        }
        // The same errors as a table built on a copy of the abscissae.
        let nan = vec![0.0, 1.0, f64::NAN, 0.0, 0.0, 0.0];
        let linear = (Interpolation::Linear, Extrapolation::Constant);
        for ys in [vec![0.0; 3], nan] {
            let shared = Table1::on_same_abscissae(&like, ys.clone(), linear.0, linear.1);
            let copied = Table1::new(xs.clone(), ys, linear.0, linear.1);
            assert_eq!(format!("{shared:?}"), format!("{copied:?}"));
            assert!(shared.is_err());
        }
        let repeated = vec![0.0, 1.0, 1.0, 2.0];
        let stepwise =
            Table1::linear_stepwise(repeated.clone(), vec![0.0; 4], Extrapolation::Zero).unwrap();
        let shared = Table1::on_same_abscissae(&stepwise, vec![1.0; 4], linear.0, linear.1);
        let copied = Table1::new(repeated, vec![1.0; 4], linear.0, linear.1);
        assert!(matches!(
            shared,
            Err(MathError::NotIncreasing { index: 2, .. })
        ));
        assert_eq!(format!("{shared:?}"), format!("{copied:?}"));
        assert!(like.strictly_increasing() && !stepwise.strictly_increasing());
        // A stepwise table without repeats lends its abscissae like any other.
        let distinct =
            Table1::linear_stepwise(xs.clone(), vec![0.0; xs.len()], Extrapolation::Zero).unwrap();
        assert!(distinct.strictly_increasing());
        let shared = Table1::on_same_abscissae(&distinct, ys.clone(), linear.0, linear.1);
        assert_eq!(
            shared.unwrap(),
            Table1::new(xs, ys, linear.0, linear.1).unwrap()
        );
    }

    /// Samples of `cos 2x` on uneven abscissae.
    fn cosine_samples() -> (Vec<f64>, Vec<f64>) {
        let xs = vec![0.0, 0.5, 1.5, 1.7, 3.0, 4.0];
        let ys = xs.iter().map(|x: &f64| (2.0 * x).cos()).collect();
        (xs, ys)
    }

    #[test]
    fn integral_with_a_cursor_is_the_integral() {
        let (xs, ys) = cosine_samples();
        let kinds = [
            Interpolation::Linear,
            Interpolation::Spline,
            Interpolation::Akima,
            Interpolation::Polynomial,
        ];
        let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
        for kind in kinds {
            for e in [Extrapolation::Natural, Extrapolation::Constant] {
                let t = Table1::new(xs.clone(), ys.clone(), kind, e).unwrap();
                // Consecutive intervals of a grid (nodes included), as the propellant tables
                // integrate the thrust, then bounds in any order, reversed or outside.
                let mut cursor = Cursor::default();
                let grid: Vec<f64> = (0..=40).map(|k| 0.1 * f64::from(k)).collect();
                for w in grid.windows(2) {
                    let with = t.integral_with(w[0], w[1], &mut cursor);
                    assert!(same(with, t.integral(w[0], w[1])), "{kind:?} {w:?}");
                }
                for (a, b) in [(3.9, 0.2), (-1.0, 5.0), (1.5, 1.5), (0.5, 1.7), (4.5, 6.0)] {
                    let with = t.integral_with(a, b, &mut cursor);
                    assert!(same(with, t.integral(a, b)), "{kind:?} {a} {b}");
                }
            }
        }
    }

    #[test]
    fn a_detached_piece_evaluates_as_its_table() {
        let (xs, ys) = cosine_samples();
        let kinds = [
            Interpolation::Linear,
            Interpolation::Spline,
            Interpolation::Akima,
        ];
        let ends = [
            Extrapolation::Natural,
            Extrapolation::Constant,
            Extrapolation::Zero,
        ];
        // Knots, points between them and outside on both sides.
        let probes: Vec<f64> = (-10..=50)
            .map(|k| 0.1 * f64::from(k))
            .chain(xs.clone())
            .collect();
        for kind in kinds {
            for e in ends {
                let t = Table1::new(xs.clone(), ys.clone(), kind, e).unwrap();
                for &x in &probes {
                    let piece = t.piece(t.locate(x)).unwrap();
                    assert_eq!(
                        piece.eval(x).to_bits(),
                        t.eval(x).to_bits(),
                        "{kind:?} {e:?} {x}"
                    );
                }
            }
        }
        let one = Table1::new(
            vec![2.0],
            vec![7.5],
            Interpolation::Linear,
            Extrapolation::Natural,
        );
        let one = one.unwrap();
        for x in [-3.0, 2.0, 9.0] {
            assert_eq!(
                one.piece(one.locate(x)).unwrap().eval(x).to_bits(),
                7.5f64.to_bits()
            );
        }
        let polynomial = Table1::new(xs, ys, Interpolation::Polynomial, Extrapolation::Natural);
        assert_eq!(polynomial.unwrap().piece(Location::Interval(1)), None);
    }
}
