//! [`Function`]: a function of one variable that is a constant, a [`Table1`], an analytic
//! closure, or an expression of those (sum, difference, product, quotient, composition) —
//! the role of RocketPy's `Function` class (Ceotto et al. 2021).
//!
//! Expressions are trees of shared (`Arc`) nodes: building one allocates, evaluating it does
//! not. Operations between a table and a constant fold into a new table (every interpolation
//! is affine in the sample values, so `a·T + b` is exactly a table), so the common
//! "table times a number" costs one table evaluation.
//!
//! Calculus:
//! - derivative: exact for constants and tables, by the sum/product/quotient/chain rules for
//!   expressions, and by a central difference for closures with step
//!   `h = ε^{1/3}·max(1, |x|)` (≈ 6·10⁻⁶·max(1, |x|); it balances the O(h²) truncation and
//!   O(ε/h) rounding errors, Press et al., *Numerical Recipes* 3rd ed. §5.7);
//! - integral: exact for constants, tables and their sums/differences/constant multiples;
//!   adaptive Gauss–Kronrod ([`crate::quadrature`]) otherwise, split at the nodes of the
//!   tables involved;
//! - extrema over `[a, b]`: exact for constants and piecewise-cubic tables (endpoints, nodes and
//!   stationary points of each piece); otherwise the best of 512 equal samples refined by
//!   golden-section search on its two neighbouring intervals.

use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};
use std::sync::Arc;

use crate::quadrature::{Quadrature, QuadratureOptions, integrate_breakpoints};
use crate::table::Cursor;
use crate::{MathError, Table1};

/// An arithmetic operation between two functions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum BinaryOp {
    Add,
    Sub,
    Mul,
    Div,
}

impl BinaryOp {
    #[inline]
    fn apply(self, a: f64, b: f64) -> f64 {
        match self {
            BinaryOp::Add => a + b,
            BinaryOp::Sub => a - b,
            BinaryOp::Mul => a * b,
            BinaryOp::Div => a / b,
        }
    }
}

/// An analytic function of one variable.
type Closure = Arc<dyn Fn(f64) -> f64 + Send + Sync>;

#[derive(Clone)]
enum Repr {
    Constant(f64),
    Table(Arc<Table1>),
    Analytic(Closure),
    Binary(BinaryOp, Arc<Function>, Arc<Function>),
    /// `outer ∘ inner`.
    Compose(Arc<Function>, Arc<Function>),
}

/// A function of one variable: constant, table, closure or an expression of those.
/// Cheap to clone (shared nodes); `Send + Sync`.
#[derive(Clone)]
pub struct Function {
    repr: Repr,
}

/// Where a function reaches its minimum or maximum on an interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extremum {
    /// The abscissa.
    pub x: f64,
    /// The function value there.
    pub value: f64,
}

/// Samples of the numerical extremum search.
const EXTREMUM_SAMPLES: usize = 512;

impl fmt::Debug for Function {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.repr {
            Repr::Constant(c) => write!(f, "Constant({c})"),
            Repr::Table(t) => write!(
                f,
                "Table({} points, {:?}, {:?})",
                t.xs().len(),
                t.interpolation(),
                t.extrapolation()
            ),
            Repr::Analytic(_) => write!(f, "Analytic"),
            Repr::Binary(op, l, r) => write!(f, "{op:?}({l:?}, {r:?})"),
            Repr::Compose(o, i) => write!(f, "Compose({o:?}, {i:?})"),
        }
    }
}

impl From<f64> for Function {
    fn from(c: f64) -> Self {
        Function::constant(c)
    }
}

impl From<Table1> for Function {
    fn from(t: Table1) -> Self {
        Function::table(t)
    }
}

impl Function {
    /// The constant function `c`.
    #[must_use]
    pub fn constant(c: f64) -> Self {
        Function {
            repr: Repr::Constant(c),
        }
    }

    /// A tabulated function.
    #[must_use]
    pub fn table(t: Table1) -> Self {
        Function {
            repr: Repr::Table(Arc::new(t)),
        }
    }

    /// An analytic function given as a closure.
    pub fn analytic(f: impl Fn(f64) -> f64 + Send + Sync + 'static) -> Self {
        Function {
            repr: Repr::Analytic(Arc::new(f)),
        }
    }

    /// The value if this is a constant.
    #[must_use]
    pub fn as_constant(&self) -> Option<f64> {
        match self.repr {
            Repr::Constant(c) => Some(c),
            _ => None,
        }
    }

    /// The table if this is a tabulated function.
    #[must_use]
    pub fn as_table(&self) -> Option<&Table1> {
        match &self.repr {
            Repr::Table(t) => Some(t),
            _ => None,
        }
    }

    /// Value at `x`.
    #[inline]
    #[must_use]
    pub fn eval(&self, x: f64) -> f64 {
        match &self.repr {
            Repr::Constant(c) => *c,
            Repr::Table(t) => t.eval(x),
            Repr::Analytic(f) => f(x),
            Repr::Binary(op, l, r) => op.apply(l.eval(x), r.eval(x)),
            Repr::Compose(outer, inner) => outer.eval(inner.eval(x)),
        }
    }

    /// Evaluates at every `xs[k]` into `out[k]` without allocating (tables hunt their intervals
    /// with a [`Cursor`], fast for sorted `xs`).
    ///
    /// # Panics
    /// When `xs` and `out` differ in length (a programming error).
    pub fn eval_into(&self, xs: &[f64], out: &mut [f64]) {
        assert_eq!(
            xs.len(),
            out.len(),
            "eval_into: input and output lengths differ"
        );
        match &self.repr {
            Repr::Table(t) => {
                let mut cursor = Cursor::default();
                for (o, &x) in out.iter_mut().zip(xs) {
                    *o = t.eval_with(x, &mut cursor);
                }
            }
            _ => {
                for (o, &x) in out.iter_mut().zip(xs) {
                    *o = self.eval(x);
                }
            }
        }
    }

    /// First derivative at `x` (see the module docs for the method per kind).
    #[must_use]
    pub fn derivative(&self, x: f64) -> f64 {
        match &self.repr {
            Repr::Constant(_) => 0.0,
            Repr::Table(t) => t.derivative(x),
            Repr::Analytic(f) => {
                let step = f64::EPSILON.cbrt() * x.abs().max(1.0);
                // Make the step exactly representable around x.
                let h = (x + step) - x;
                (f(x + h) - f(x - h)) / (2.0 * h)
            }
            Repr::Binary(op, l, r) => {
                let (dl, dr) = (l.derivative(x), r.derivative(x));
                match op {
                    BinaryOp::Add => dl + dr,
                    BinaryOp::Sub => dl - dr,
                    BinaryOp::Mul => dl * r.eval(x) + l.eval(x) * dr,
                    BinaryOp::Div => {
                        let rv = r.eval(x);
                        (dl * rv - l.eval(x) * dr) / (rv * rv)
                    }
                }
            }
            Repr::Compose(outer, inner) => outer.derivative(inner.eval(x)) * inner.derivative(x),
        }
    }

    /// `self ∘ inner`, i.e. `x ↦ self(inner(x))`.
    #[must_use]
    pub fn compose(&self, inner: &Function) -> Function {
        match (&self.repr, &inner.repr) {
            (Repr::Constant(_), _) => self.clone(),
            (_, Repr::Constant(c)) => Function::constant(self.eval(*c)),
            _ => Function {
                repr: Repr::Compose(Arc::new(self.clone()), Arc::new(inner.clone())),
            },
        }
    }

    /// The inverse of a tabulated function with strictly monotone values
    /// ([`Table1::inverse`]).
    ///
    /// # Errors
    /// [`MathError::NotTabulated`] unless this is a table; the errors of [`Table1::inverse`].
    pub fn inverse(&self) -> Result<Function, MathError> {
        match &self.repr {
            Repr::Table(t) => Ok(Function::table(t.inverse()?)),
            _ => Err(MathError::NotTabulated {
                operation: "inverse",
            }),
        }
    }

    /// `∫_a^b f dx` with the default [`QuadratureOptions`] where quadrature is needed.
    ///
    /// # Errors
    /// As [`Function::integral_with`].
    pub fn integral(&self, a: f64, b: f64) -> Result<Quadrature, MathError> {
        self.integral_with(a, b, &QuadratureOptions::default())
    }

    /// `∫_a^b f dx`: exact (zero error, zero evaluations) for constants, tables and their
    /// linear combinations; adaptive Gauss–Kronrod otherwise, started from a subdivision at
    /// the nodes of the tables involved.
    ///
    /// # Errors
    /// [`MathError::InvalidInterval`] for a non-finite end;
    /// [`MathError::QuadratureNotConverged`] when quadrature misses the tolerance.
    pub fn integral_with(
        &self,
        a: f64,
        b: f64,
        options: &QuadratureOptions,
    ) -> Result<Quadrature, MathError> {
        if !a.is_finite() || !b.is_finite() {
            return Err(MathError::InvalidInterval { a, b });
        }
        let exact = |value| {
            Ok(Quadrature {
                value,
                abs_error: 0.0,
                evaluations: 0,
            })
        };
        match &self.repr {
            Repr::Constant(c) => exact(c * (b - a)),
            Repr::Table(t) => exact(t.integral(a, b)),
            Repr::Binary(op @ (BinaryOp::Add | BinaryOp::Sub), l, r) => {
                let (ql, qr) = (
                    l.integral_with(a, b, options)?,
                    r.integral_with(a, b, options)?,
                );
                Ok(Quadrature {
                    value: op.apply(ql.value, qr.value),
                    abs_error: ql.abs_error + qr.abs_error,
                    evaluations: ql.evaluations + qr.evaluations,
                })
            }
            Repr::Binary(BinaryOp::Mul, l, r) if l.as_constant().is_some() => {
                let q = r.integral_with(a, b, options)?;
                let c = l.as_constant().unwrap_or(0.0);
                Ok(Quadrature {
                    value: c * q.value,
                    abs_error: c.abs() * q.abs_error,
                    ..q
                })
            }
            Repr::Binary(op @ (BinaryOp::Mul | BinaryOp::Div), l, r)
                if r.as_constant().is_some() =>
            {
                let q = l.integral_with(a, b, options)?;
                let c = r.as_constant().unwrap_or(1.0);
                let value = op.apply(q.value, c);
                Ok(Quadrature {
                    value,
                    abs_error: op.apply(q.abs_error, c).abs(),
                    ..q
                })
            }
            _ => {
                let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
                let mut points = vec![lo];
                self.collect_nodes(lo, hi, &mut points);
                points.push(hi);
                points.sort_by(f64::total_cmp);
                points.dedup_by(|x, y| x.total_cmp(y).is_eq());
                let q = integrate_breakpoints(|x| self.eval(x), &points, options)?;
                Ok(if a <= b {
                    q
                } else {
                    Quadrature {
                        value: -q.value,
                        ..q
                    }
                })
            }
        }
    }

    /// Pushes the table nodes strictly inside `(lo, hi)` where `self` may have a kink.
    fn collect_nodes(&self, lo: f64, hi: f64, out: &mut Vec<f64>) {
        match &self.repr {
            Repr::Table(t) => out.extend(t.xs().iter().copied().filter(|&x| x > lo && x < hi)),
            Repr::Binary(_, l, r) => {
                l.collect_nodes(lo, hi, out);
                r.collect_nodes(lo, hi, out);
            }
            Repr::Compose(_, inner) => inner.collect_nodes(lo, hi, out),
            Repr::Constant(_) | Repr::Analytic(_) => {}
        }
    }

    /// The minimum over `[a, b]` (see the module docs for the method).
    ///
    /// # Errors
    /// [`MathError::InvalidInterval`] unless `a ≤ b`, both finite.
    pub fn minimum(&self, a: f64, b: f64) -> Result<Extremum, MathError> {
        self.extremum(a, b, false)
    }

    /// The maximum over `[a, b]` (see the module docs for the method).
    ///
    /// # Errors
    /// [`MathError::InvalidInterval`] unless `a ≤ b`, both finite.
    pub fn maximum(&self, a: f64, b: f64) -> Result<Extremum, MathError> {
        self.extremum(a, b, true)
    }

    fn extremum(&self, a: f64, b: f64, max: bool) -> Result<Extremum, MathError> {
        if !(a.is_finite() && b.is_finite() && a <= b) {
            return Err(MathError::InvalidInterval { a, b });
        }
        let better = |v: f64, best: f64| if max { v > best } else { v < best };
        let mut best: Option<Extremum> = None;
        let mut consider = |x: f64, value: f64| {
            if best.is_none_or(|e| better(value, e.value)) {
                best = Some(Extremum { x, value });
            }
        };
        match &self.repr {
            Repr::Constant(c) => consider(a, *c),
            Repr::Table(t) if t.extremum_candidates(a, b, |x| consider(x, t.eval(x))) => {}
            _ => {
                let h = (b - a) / EXTREMUM_SAMPLES as f64;
                let mut best_k = 0;
                let mut best_v = self.eval(a);
                for k in 1..=EXTREMUM_SAMPLES {
                    let x = if k == EXTREMUM_SAMPLES {
                        b
                    } else {
                        a + k as f64 * h
                    };
                    let v = self.eval(x);
                    if better(v, best_v) || best_v.is_nan() {
                        (best_k, best_v) = (k, v);
                    }
                }
                let x_best = if best_k == EXTREMUM_SAMPLES {
                    b
                } else {
                    a + best_k as f64 * h
                };
                consider(x_best, best_v);
                let lo = a + best_k.saturating_sub(1) as f64 * h;
                let hi = (a + (best_k + 1) as f64 * h).min(b);
                let sign = if max { -1.0 } else { 1.0 };
                let x = golden_section(|x| sign * self.eval(x), lo, hi);
                consider(x, self.eval(x));
            }
        }
        Ok(best.unwrap_or(Extremum {
            x: a,
            value: self.eval(a),
        }))
    }
}

/// Minimiser of a unimodal `f` on `[lo, hi]` by golden-section search (Kiefer 1953), to a
/// bracket of `4·ε·max(1, |x|)` or 200 steps.
fn golden_section(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    const INV_PHI: f64 = 0.618_033_988_749_894_9;
    let mut x1 = hi - INV_PHI * (hi - lo);
    let mut x2 = lo + INV_PHI * (hi - lo);
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..200 {
        if hi - lo <= 4.0 * f64::EPSILON * lo.abs().max(hi.abs()).max(1.0) {
            break;
        }
        if f1 <= f2 {
            hi = x2;
            (x2, f2) = (x1, f1);
            x1 = hi - INV_PHI * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            (x1, f1) = (x2, f2);
            x2 = lo + INV_PHI * (hi - lo);
            f2 = f(x2);
        }
    }
    if f1 <= f2 { x1 } else { x2 }
}

/// `op(lhs, rhs)`, folding constants and table–constant pairs.
fn combine(op: BinaryOp, lhs: Function, rhs: Function) -> Function {
    let affine = |t: &Table1, scale: f64, offset: f64| Function::table(t.map_affine(scale, offset));
    match (&lhs.repr, &rhs.repr) {
        (Repr::Constant(a), Repr::Constant(b)) => Function::constant(op.apply(*a, *b)),
        (Repr::Table(t), Repr::Constant(c)) => match op {
            BinaryOp::Add => affine(t, 1.0, *c),
            BinaryOp::Sub => affine(t, 1.0, -c),
            BinaryOp::Mul => affine(t, *c, 0.0),
            BinaryOp::Div => affine(t, 1.0 / c, 0.0),
        },
        (Repr::Constant(c), Repr::Table(t)) if op != BinaryOp::Div => match op {
            BinaryOp::Sub => affine(t, -1.0, *c),
            BinaryOp::Mul => affine(t, *c, 0.0),
            _ => affine(t, 1.0, *c),
        },
        _ => Function {
            repr: Repr::Binary(op, Arc::new(lhs), Arc::new(rhs)),
        },
    }
}

macro_rules! impl_op {
    ($trait:ident, $method:ident, $op:expr) => {
        impl $trait<Function> for Function {
            type Output = Function;
            fn $method(self, rhs: Function) -> Function {
                combine($op, self, rhs)
            }
        }
        impl $trait<&Function> for Function {
            type Output = Function;
            fn $method(self, rhs: &Function) -> Function {
                combine($op, self, rhs.clone())
            }
        }
        impl $trait<Function> for &Function {
            type Output = Function;
            fn $method(self, rhs: Function) -> Function {
                combine($op, self.clone(), rhs)
            }
        }
        impl $trait<&Function> for &Function {
            type Output = Function;
            fn $method(self, rhs: &Function) -> Function {
                combine($op, self.clone(), rhs.clone())
            }
        }
        impl $trait<f64> for Function {
            type Output = Function;
            fn $method(self, rhs: f64) -> Function {
                combine($op, self, Function::constant(rhs))
            }
        }
        impl $trait<f64> for &Function {
            type Output = Function;
            fn $method(self, rhs: f64) -> Function {
                combine($op, self.clone(), Function::constant(rhs))
            }
        }
        impl $trait<Function> for f64 {
            type Output = Function;
            fn $method(self, rhs: Function) -> Function {
                combine($op, Function::constant(self), rhs)
            }
        }
        impl $trait<&Function> for f64 {
            type Output = Function;
            fn $method(self, rhs: &Function) -> Function {
                combine($op, Function::constant(self), rhs.clone())
            }
        }
    };
}

impl_op!(Add, add, BinaryOp::Add);
impl_op!(Sub, sub, BinaryOp::Sub);
impl_op!(Mul, mul, BinaryOp::Mul);
impl_op!(Div, div, BinaryOp::Div);

impl Neg for Function {
    type Output = Function;
    fn neg(self) -> Function {
        combine(BinaryOp::Mul, Function::constant(-1.0), self)
    }
}

impl Neg for &Function {
    type Output = Function;
    fn neg(self) -> Function {
        -self.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Extrapolation, Interpolation};

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * (1.0 + b.abs())
    }

    fn ramp() -> Function {
        Function::table(Table1::linear(vec![0.0, 1.0, 2.0], vec![0.0, 2.0, 1.0]).unwrap())
    }

    #[test]
    fn table_constant_arithmetic_folds_into_a_table() {
        let f = 2.0 * ramp() + 1.0;
        let t = f.as_table().expect("folded");
        assert!(close(t.eval(0.5), 3.0, 1e-15));
        assert!(close(t.eval(1.5), 4.0, 1e-15));
        assert!((ramp() / 4.0).as_table().is_some());
        assert!((1.0 / ramp()).as_table().is_none());
        assert!(close((10.0 - ramp()).eval(1.0), 8.0, 1e-15));
        assert!(close((-&ramp()).eval(1.0), -2.0, 1e-15));
    }

    #[test]
    fn expressions_evaluate_and_differentiate() {
        let sq = Function::analytic(|x| x * x);
        let f = &ramp() * &sq - Function::constant(1.0);
        // On (0, 1): ramp = 2x, f = 2x³ − 1, f' = 6x².
        assert!(close(f.eval(0.5), -0.75, 1e-15));
        assert!(close(f.derivative(0.5), 1.5, 1e-9));
        let g = Function::analytic(f64::sin).compose(&sq);
        assert!(close(g.derivative(1.2), 2.0 * 1.2 * (1.44f64).cos(), 1e-8));
        let q = &sq / &ramp();
        assert!(close(q.derivative(0.5), 0.5, 1e-9));
    }

    #[test]
    fn integrals_exact_and_numerical() {
        let r = ramp();
        let q = (&r + &r).integral(0.0, 2.0).unwrap();
        assert!(close(q.value, 5.0, 1e-15));
        assert_eq!(q.evaluations, 0);
        // ∫_0^2 ramp² = ∫_0^1 4x² + ∫_1^2 (3 − x)² = 4/3 + 7/3.
        let q = (&r * &r).integral(0.0, 2.0).unwrap();
        assert!(close(q.value, 11.0 / 3.0, 1e-13), "{q:?}");
        assert!(q.evaluations > 0);
        let q = (&r * &r).integral(2.0, 0.0).unwrap();
        assert!(close(q.value, -11.0 / 3.0, 1e-13));
    }

    #[test]
    fn extrema() {
        let t = Table1::new(
            vec![0.0, 1.0, 2.0, 3.0],
            vec![0.0, 1.0, 0.0, 1.0],
            Interpolation::Spline,
            Extrapolation::Constant,
        )
        .unwrap();
        let f = Function::table(t);
        let m = f.maximum(0.0, 2.0).unwrap();
        // The spline overshoots above 1 near x = 1, with zero slope there.
        assert!(m.value >= 1.0 && f.derivative(m.x).abs() < 1e-12, "{m:?}");
        let s = Function::analytic(|x: f64| (x - 0.3).powi(2) + 2.0);
        let m = s.minimum(-1.0, 1.0).unwrap();
        assert!(close(m.x, 0.3, 1e-7) && close(m.value, 2.0, 1e-14), "{m:?}");
        assert!(s.minimum(1.0, 0.0).is_err());
    }

    #[test]
    fn functions_are_shareable_across_threads() {
        fn assert_send_sync<T: Send + Sync>() {}
        assert_send_sync::<Function>();
    }

    #[test]
    fn inverse_and_eval_into() {
        let inv = ramp().inverse();
        assert!(matches!(inv, Err(MathError::NotMonotone { .. })));
        let up = Function::table(Table1::linear(vec![0.0, 1.0], vec![1.0, 3.0]).unwrap());
        assert!(close(up.inverse().unwrap().eval(2.0), 0.5, 1e-15));
        let xs = [0.0, 0.25, 0.5, 1.5];
        let mut out = [0.0; 4];
        ramp().eval_into(&xs, &mut out);
        for (x, o) in xs.iter().zip(out) {
            assert!(close(o, ramp().eval(*x), 1e-15));
        }
    }
}
