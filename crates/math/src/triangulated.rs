//! Linear interpolation of scattered data in the plane (docs/physics.md §28.2), as RocketPy 1.13
//! evaluates a two-variable `Function(..., interpolation="linear", extrapolation="natural")` (its
//! fluid densities `ρ(T, p)`, rocketpy/motors/fluid.py; rocketpy/mathutils/_calc/polation_nd.py):
//!
//! - inside the convex hull of the points, the piecewise-linear interpolant on their Delaunay
//!   triangulation (Delaunay 1934; scipy's `LinearNDInterpolator` on `scipy.spatial.Delaunay`,
//!   Qhull, Barber et al. 1996): `f(x) = Σ λ_i f_i` with `λ_i` the barycentric coordinates of
//!   `x` in the triangle that contains it;
//! - outside the hull, the thin-plate-spline radial-basis interpolant through all points
//!   (Duchon 1977; scipy's `RBFInterpolator` defaults: kernel `φ(r) = r² ln r`, shape
//!   parameter 1, no smoothing, a degree-1 polynomial):
//!   `s(x) = Σ_j c_j φ(|x − x_j|) + d_0 + d_1 x̂ + d_2 ŷ`, with `x̂ = (x − shift)/scale` per
//!   coordinate (`shift` the middle and `scale` the half-width of the points' bounding box, 1
//!   for a zero width), and `[Φ P; Pᵀ 0] [c; d] = [f; 0]`.
//!
//! Distances are taken in the raw coordinates, as scipy does (no rescaling), so with
//! `(temperature K, pressure Pa)` the pressure dominates both the triangulation and the
//! spline. The triangulation is built by a lexicographic sweep and Lawson's edge flips
//! (Lawson 1977); where four or more points are cocircular (the cells of a rectangular grid)
//! the Delaunay triangulation is not unique and a cell is split along either diagonal — Qhull's
//! choice there depends on the order of the points, so inside such cells the two can differ by
//! up to half the cell's twist `|f₀₀ + f₁₁ − f₀₁ − f₁₀| / 2`; everywhere else they agree to
//! rounding.
//!
//! RocketPy refuses fewer than three points (its domain needs as many rows as columns), points
//! all on one line (Qhull: the initial simplex is flat) and a repeated point (the spline's
//! system is singular); so does [`TriangulatedTable::new`].

use std::sync::OnceLock;

use nalgebra::{DMatrix, DVector};

use crate::MathError;

/// Relative tolerance of the in-circle test below which four points count as cocircular
/// (no flip), so that round-off cannot flip a diagonal back and forth.
const COCIRCULAR_TOLERANCE: f64 = 1e-10;

/// Barycentric tolerance of point location: scipy's `find_simplex` default `100 ε`.
const LOCATION_TOLERANCE: f64 = 100.0 * f64::EPSILON;

/// A function of two variables tabulated at scattered points: linear on their Delaunay
/// triangulation, a thin-plate spline outside their convex hull (module docs).
#[derive(Debug, Clone)]
pub struct TriangulatedTable {
    points: Vec<[f64; 2]>,
    values: Vec<f64>,
    /// Counter-clockwise triangles, indices into `points`.
    triangles: Vec<[usize; 3]>,
    /// The thin-plate spline, solved the first time a point outside the hull is evaluated.
    spline: OnceLock<Option<Spline>>,
}

impl PartialEq for TriangulatedTable {
    fn eq(&self, other: &Self) -> bool {
        self.points == other.points && self.values == other.values
    }
}

/// The thin-plate-spline coefficients.
#[derive(Debug, Clone)]
struct Spline {
    /// `c_j`, one per point.
    weights: Vec<f64>,
    /// `d_0, d_1, d_2`.
    polynomial: [f64; 3],
    shift: [f64; 2],
    scale: [f64; 2],
}

/// `r² ln r`, 0 at 0.
fn thin_plate(r: f64) -> f64 {
    if r == 0.0 { 0.0 } else { r * r * r.ln() }
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// Twice the signed area of `(a, b, c)`: positive when counter-clockwise.
fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Whether `d` lies strictly inside the circle through the counter-clockwise `a, b, c`,
/// beyond the relative [`COCIRCULAR_TOLERANCE`].
fn in_circle(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let (ax, ay) = (a[0] - d[0], a[1] - d[1]);
    let (bx, by) = (b[0] - d[0], b[1] - d[1]);
    let (cx, cy) = (c[0] - d[0], c[1] - d[1]);
    let (la, lb, lc) = (ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy);
    let terms = [
        la * (bx * cy - cx * by),
        lb * (cx * ay - ax * cy),
        lc * (ax * by - bx * ay),
    ];
    let scale = la * ((bx * cy).abs() + (cx * by).abs())
        + lb * ((cx * ay).abs() + (ax * cy).abs())
        + lc * ((ax * by).abs() + (bx * ay).abs());
    terms.iter().sum::<f64>() > COCIRCULAR_TOLERANCE * scale
}

impl TriangulatedTable {
    /// Builds the interpolant through `values[i]` at `points[i]`.
    ///
    /// # Errors
    /// [`MathError::TooFewPoints`] for fewer than three points, [`MathError::LengthMismatch`],
    /// [`MathError::NotFinite`] (index of the point or value), [`MathError::RepeatedPoint`],
    /// [`MathError::Collinear`].
    pub fn new(points: Vec<[f64; 2]>, values: Vec<f64>) -> Result<Self, MathError> {
        if points.len() != values.len() {
            return Err(MathError::LengthMismatch {
                x: points.len(),
                y: values.len(),
            });
        }
        if points.len() < 3 {
            return Err(MathError::TooFewPoints {
                needed: 3,
                got: points.len(),
            });
        }
        for (index, (p, &v)) in points.iter().zip(&values).enumerate() {
            if let Some(&value) = p.iter().chain([&v]).find(|x| !x.is_finite()) {
                return Err(MathError::NotFinite { index, value });
            }
        }
        let mut order: Vec<usize> = (0..points.len()).collect();
        order.sort_by(|&i, &j| {
            (points[i][0], points[i][1], i)
                .partial_cmp(&(points[j][0], points[j][1], j))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        for w in order.windows(2) {
            #[allow(clippy::float_cmp)] // the same point twice, as RocketPy's singular system.
            if points[w[0]] == points[w[1]] {
                return Err(MathError::RepeatedPoint {
                    index: w[0].max(w[1]),
                    first: w[0].min(w[1]),
                });
            }
        }
        let triangles = sweep(&points, &order).ok_or(MathError::Collinear)?;
        let mut table = TriangulatedTable {
            points,
            values,
            triangles,
            spline: OnceLock::new(),
        };
        table.make_delaunay();
        Ok(table)
    }

    /// The value at `(x, y)`: linear in the Delaunay triangle holding it, the thin-plate spline
    /// outside the hull (NaN should that spline's system be singular to working precision).
    #[must_use]
    pub fn eval(&self, x: f64, y: f64) -> f64 {
        let q = [x, y];
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| self.points[i]);
            let area = orient(a, b, c);
            let la = orient(q, b, c) / area;
            let lb = orient(a, q, c) / area;
            let lc = 1.0 - la - lb;
            if la >= -LOCATION_TOLERANCE && lb >= -LOCATION_TOLERANCE && lc >= -LOCATION_TOLERANCE {
                let [fa, fb, fc] = t.map(|i| self.values[i]);
                return la * fa + lb * fb + lc * fc;
            }
        }
        self.spline
            .get_or_init(|| self.solve_spline())
            .as_ref()
            .map_or(f64::NAN, |s| s.eval(&self.points, q))
    }

    /// Lawson's flips: every interior edge whose opposite vertex lies inside the other
    /// triangle's circumcircle is replaced by the other diagonal, until none is left (the
    /// Delaunay triangulation; each flip makes the triangulation strictly better, so the loop
    /// ends). Edges are visited in a fixed order, so ties are broken deterministically.
    fn make_delaunay(&mut self) {
        loop {
            let mut edges: Vec<([usize; 2], usize, usize)> = Vec::new();
            for (t, tri) in self.triangles.iter().enumerate() {
                for k in 0..3 {
                    let (a, b) = (tri[(k + 1) % 3], tri[(k + 2) % 3]);
                    edges.push(([a.min(b), a.max(b)], t, k));
                }
            }
            edges.sort_unstable();
            let mut touched = vec![false; self.triangles.len()];
            let mut flipped = false;
            for pair in edges.windows(2) {
                let ((e1, t1, k1), (e2, t2, k2)) = (pair[0], pair[1]);
                if e1 != e2 || touched[t1] || touched[t2] {
                    continue;
                }
                let (tri1, tri2) = (self.triangles[t1], self.triangles[t2]);
                // tri1 = (c, a, b) with c opposite the shared edge, tri2 holds d opposite it.
                let c = tri1[k1];
                let (a, b) = (tri1[(k1 + 1) % 3], tri1[(k1 + 2) % 3]);
                let d = tri2[k2];
                let p = |i: usize| self.points[i];
                if in_circle(p(c), p(a), p(b), p(d)) {
                    // Quadrilateral a, d, b, c (counter-clockwise) split along c–d.
                    self.triangles[t1] = [a, d, c];
                    self.triangles[t2] = [d, b, c];
                    touched[t1] = true;
                    touched[t2] = true;
                    flipped = true;
                }
            }
            if !flipped {
                return;
            }
        }
    }

    fn solve_spline(&self) -> Option<Spline> {
        let n = self.points.len();
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for p in &self.points {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let shift = [0.5 * (hi[0] + lo[0]), 0.5 * (hi[1] + lo[1])];
        let scale = [0, 1].map(|k| {
            let s = 0.5 * (hi[k] - lo[k]);
            if s == 0.0 { 1.0 } else { s }
        });
        let mut lhs = DMatrix::<f64>::zeros(n + 3, n + 3);
        for i in 0..n {
            for j in 0..n {
                lhs[(i, j)] = thin_plate(distance(self.points[i], self.points[j]));
            }
            let monomials = monomials(self.points[i], shift, scale);
            for (k, &m) in monomials.iter().enumerate() {
                lhs[(i, n + k)] = m;
                lhs[(n + k, i)] = m;
            }
        }
        let mut rhs = DVector::<f64>::zeros(n + 3);
        for (i, &v) in self.values.iter().enumerate() {
            rhs[i] = v;
        }
        let solution = lhs.lu().solve(&rhs)?;
        if solution.iter().any(|c| !c.is_finite()) {
            return None;
        }
        Some(Spline {
            weights: solution.as_slice()[..n].to_vec(),
            polynomial: [solution[n], solution[n + 1], solution[n + 2]],
            shift,
            scale,
        })
    }
}

/// `1, x̂, ŷ` at `p` (scipy's monomial order for degree 1 in two variables).
fn monomials(p: [f64; 2], shift: [f64; 2], scale: [f64; 2]) -> [f64; 3] {
    [
        1.0,
        (p[0] - shift[0]) / scale[0],
        (p[1] - shift[1]) / scale[1],
    ]
}

impl Spline {
    fn eval(&self, points: &[[f64; 2]], q: [f64; 2]) -> f64 {
        let radial: f64 = points
            .iter()
            .zip(&self.weights)
            .map(|(&p, &c)| c * thin_plate(distance(q, p)))
            .sum();
        let m = monomials(q, self.shift, self.scale);
        radial
            + self
                .polynomial
                .iter()
                .zip(m)
                .map(|(d, m)| d * m)
                .sum::<f64>()
    }
}

/// A triangulation of the points (distinct) by a sweep in lexicographic `order`: the points
/// before the first one off their line are fanned to it, and every later point — outside the
/// hull so far — is joined to each hull edge it sees. `None` when all points are collinear.
fn sweep(points: &[[f64; 2]], order: &[usize]) -> Option<Vec<[usize; 3]>> {
    let p = |i: usize| points[order[i]];
    let first_off = (2..order.len()).find(|&k| orient(p(0), p(1), p(k)) != 0.0)?;
    let apex = order[first_off];
    let mut triangles = Vec::with_capacity(2 * points.len());
    let left = orient(p(0), p(first_off - 1), p(first_off)) > 0.0;
    for i in 0..first_off - 1 {
        let (a, b) = (order[i], order[i + 1]);
        triangles.push(if left { [a, b, apex] } else { [b, a, apex] });
    }
    // The hull, counter-clockwise.
    let mut hull: Vec<usize> = order[..=first_off].to_vec();
    if !left {
        hull.reverse();
    }
    for &q in &order[first_off + 1..] {
        let n = hull.len();
        let sees = |k: usize| orient(points[hull[k]], points[hull[(k + 1) % n]], points[q]) < 0.0;
        let Some(seen) = (0..n).find(|&k| sees(k)) else {
            // On the hull's boundary to round-off: no triangle to add.
            continue;
        };
        // The run of visible edges is contiguous: widen it both ways from `seen`.
        let mut start = seen;
        while sees((start + n - 1) % n) && (start + n - 1) % n != seen {
            start = (start + n - 1) % n;
        }
        let mut count = 0;
        while count < n && sees((start + count) % n) {
            let (a, b) = (hull[(start + count) % n], hull[(start + count + 1) % n]);
            triangles.push([b, a, q]);
            count += 1;
        }
        // Vertices strictly inside the visible run leave the hull; `q` takes their place.
        let mut next = Vec::with_capacity(n + 1);
        for k in 0..=n - count {
            next.push(hull[(start + count + k) % n]);
        }
        next.push(q);
        hull = next;
    }
    Some(triangles)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproduces_planes_and_nodes() {
        let points = vec![
            [0.0, 0.0],
            [2.0, 0.0],
            [0.0, 3.0],
            [2.0, 3.0],
            [1.0, 1.0],
            [1.5, 2.5],
        ];
        let plane = |p: &[f64; 2]| 1.0 + 2.0 * p[0] - 0.5 * p[1];
        let values = points.iter().map(plane).collect();
        let table = TriangulatedTable::new(points.clone(), values).unwrap();
        for q in [[0.3, 0.2], [1.9, 2.9], [1.0, 1.5], [0.0, 1.0]] {
            assert!((table.eval(q[0], q[1]) - plane(&q)).abs() < 1e-12);
        }
        // The degree-1 part of the spline carries a plane exactly outside the hull too.
        assert!((table.eval(5.0, -1.0) - plane(&[5.0, -1.0])).abs() < 1e-9);
        for p in &points {
            assert!((table.eval(p[0], p[1]) - plane(p)).abs() < 1e-12);
        }
    }

    #[test]
    fn triangulation_is_delaunay() {
        // Points in general position: no vertex inside another triangle's circumcircle.
        let points: Vec<[f64; 2]> = (0..40)
            .map(|i| {
                let t = f64::from(i);
                [
                    (t * 0.618_034).fract() * 10.0,
                    (t * 0.414_214).fract() * 7.0,
                ]
            })
            .collect();
        let table = TriangulatedTable::new(points.clone(), vec![0.0; points.len()]).unwrap();
        for t in &table.triangles {
            let [a, b, c] = t.map(|i| points[i]);
            assert!(orient(a, b, c) > 0.0);
            for (i, &d) in points.iter().enumerate() {
                if !t.contains(&i) {
                    assert!(!in_circle(a, b, c, d));
                }
            }
        }
        // The triangles tile the hull: their areas add up to the hull's.
        let area: f64 = table
            .triangles
            .iter()
            .map(|t| 0.5 * orient(points[t[0]], points[t[1]], points[t[2]]))
            .sum();
        let mut order: Vec<usize> = (0..points.len()).collect();
        order.sort_by(|&i, &j| points[i].partial_cmp(&points[j]).unwrap());
        let hull_area = {
            // Monotone chain.
            let mut h: Vec<[f64; 2]> = Vec::new();
            for pass in 0..2 {
                let start = h.len();
                let seq: Vec<usize> = if pass == 0 {
                    order.clone()
                } else {
                    order.iter().rev().copied().collect()
                };
                for &i in &seq {
                    while h.len() >= start + 2
                        && orient(h[h.len() - 2], h[h.len() - 1], points[i]) <= 0.0
                    {
                        h.pop();
                    }
                    h.push(points[i]);
                }
                h.pop();
            }
            (0..h.len())
                .map(|k| 0.5 * orient([0.0, 0.0], h[k], h[(k + 1) % h.len()]))
                .sum::<f64>()
        };
        assert!((area - hull_area).abs() < 1e-9 * hull_area);
    }

    #[test]
    fn refuses_what_rocketpy_refuses() {
        let two = TriangulatedTable::new(vec![[0.0, 0.0], [1.0, 0.0]], vec![1.0, 2.0]);
        assert!(matches!(
            two,
            Err(MathError::TooFewPoints { needed: 3, got: 2 })
        ));
        let line = TriangulatedTable::new(
            vec![[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]],
            vec![1.0, 2.0, 3.0],
        );
        assert!(matches!(line, Err(MathError::Collinear)));
        let repeated = TriangulatedTable::new(
            vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 0.0]],
            vec![1.0, 2.0, 3.0, 4.0],
        );
        assert!(matches!(
            repeated,
            Err(MathError::RepeatedPoint { index: 3, first: 1 })
        ));
        let nan = TriangulatedTable::new(
            vec![[0.0, 0.0], [1.0, 0.0], [0.0, f64::NAN]],
            vec![1.0, 2.0, 3.0],
        );
        assert!(matches!(nan, Err(MathError::NotFinite { index: 2, .. })));
    }
}
