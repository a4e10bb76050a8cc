//! Functions of several variables (docs/physics.md §28.2): [`RegularGrid`] (tensor-product grid,
//! multilinear interpolation, clamped outside — scipy's `RegularGridInterpolator(method="linear")`
//! inside the grid, which RocketPy uses for gridded data) and [`ScatteredTable`] (inverse-distance
//! weighting, Shepard 1968, *Proc. 23rd ACM National Conference*, 517–524; RocketPy's `"shepard"`
//! interpolation is the power `p = 3`). Both serve tables such as `Cd(Mach, Re, …)` or air-brake
//! drag `Cd(deployment, Mach)`. Evaluation does not allocate.

use crate::MathError;

/// Largest number of axes of a [`RegularGrid`] (keeps evaluation on the stack).
pub const MAX_GRID_DIMENSIONS: usize = 8;

/// A function tabulated on a tensor-product grid.
#[derive(Debug, Clone, PartialEq)]
pub struct RegularGrid {
    axes: Vec<Vec<f64>>,
    /// Values in row-major order (the last axis varies fastest).
    values: Vec<f64>,
    /// Row-major strides of the axes.
    strides: Vec<usize>,
}

impl RegularGrid {
    /// Builds a grid from its axes (each finite, strictly increasing, at least one point) and
    /// its values in row-major order (`values[((i₀·n₁ + i₁)·n₂ + i₂)…]`).
    ///
    /// # Errors
    /// [`MathError::BadAxis`] for no axes, more than [`MAX_GRID_DIMENSIONS`], an empty,
    /// non-finite or non-increasing axis; [`MathError::WrongSize`] when the number of values
    /// is not the product of the axis lengths; [`MathError::NotFinite`] for a bad value.
    pub fn new(axes: Vec<Vec<f64>>, values: Vec<f64>) -> Result<Self, MathError> {
        if axes.is_empty() {
            return Err(MathError::BadAxis {
                axis: 0,
                reason: "a grid needs at least one axis",
            });
        }
        if axes.len() > MAX_GRID_DIMENSIONS {
            return Err(MathError::BadAxis {
                axis: MAX_GRID_DIMENSIONS,
                reason: "too many axes (at most 8)",
            });
        }
        for (axis, points) in axes.iter().enumerate() {
            if points.is_empty() {
                return Err(MathError::BadAxis {
                    axis,
                    reason: "empty axis",
                });
            }
            if points.iter().any(|v| !v.is_finite()) {
                return Err(MathError::BadAxis {
                    axis,
                    reason: "non-finite coordinate",
                });
            }
            if points.windows(2).any(|w| w[1] <= w[0]) {
                return Err(MathError::BadAxis {
                    axis,
                    reason: "coordinates must strictly increase",
                });
            }
        }
        let expected = axes
            .iter()
            .try_fold(1usize, |acc, a| acc.checked_mul(a.len()));
        let Some(expected) = expected else {
            return Err(MathError::WrongSize {
                expected: usize::MAX,
                got: values.len(),
            });
        };
        if values.len() != expected {
            return Err(MathError::WrongSize {
                expected,
                got: values.len(),
            });
        }
        if let Some((index, &value)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(MathError::NotFinite { index, value });
        }
        let mut strides = vec![1; axes.len()];
        for k in (0..axes.len() - 1).rev() {
            strides[k] = strides[k + 1] * axes[k + 1].len();
        }
        Ok(RegularGrid {
            axes,
            values,
            strides,
        })
    }

    /// Number of axes.
    #[must_use]
    pub fn dimensions(&self) -> usize {
        self.axes.len()
    }

    /// The axes.
    #[must_use]
    pub fn axes(&self) -> &[Vec<f64>] {
        &self.axes
    }

    /// Multilinear interpolation at `point`, each coordinate clamped to its axis range.
    ///
    /// # Panics
    /// When `point.len()` differs from [`RegularGrid::dimensions`] (a programming error).
    #[must_use]
    pub fn eval(&self, point: &[f64]) -> f64 {
        let dims = self.axes.len();
        assert_eq!(
            point.len(),
            dims,
            "RegularGrid::eval: wrong point dimension"
        );
        let mut base = [0usize; MAX_GRID_DIMENSIONS];
        let mut frac = [0.0f64; MAX_GRID_DIMENSIONS];
        let mut upper = [false; MAX_GRID_DIMENSIONS];
        for (k, (axis, &x)) in self.axes.iter().zip(point).enumerate() {
            let n = axis.len();
            if n == 1 || x <= axis[0] {
                base[k] = 0;
                frac[k] = 0.0;
            } else if x >= axis[n - 1] {
                base[k] = n - 2;
                frac[k] = 1.0;
            } else {
                let i = axis.partition_point(|&v| v <= x) - 1;
                base[k] = i;
                frac[k] = (x - axis[i]) / (axis[i + 1] - axis[i]);
            }
            upper[k] = n > 1;
        }
        let mut total = 0.0;
        for corner in 0..(1usize << dims) {
            let mut weight = 1.0;
            let mut index = 0;
            let mut skip = false;
            for k in 0..dims {
                let high = corner >> k & 1 == 1;
                if high && !upper[k] {
                    skip = true;
                    break;
                }
                weight *= if high { frac[k] } else { 1.0 - frac[k] };
                index += (base[k] + usize::from(high)) * self.strides[k];
            }
            if !skip && weight > 0.0 {
                total += weight * self.values[index];
            }
        }
        total
    }
}

/// A function known at scattered points, interpolated by inverse-distance weighting:
/// `f(x) = Σ w_i y_i / Σ w_i` with `w_i = |x − x_i|^{−p}`, and `f(x_i) = y_i` exactly at a
/// node (the first node at distance zero).
#[derive(Debug, Clone, PartialEq)]
pub struct ScatteredTable {
    dimensions: usize,
    /// Node coordinates, `dimensions` per node.
    nodes: Vec<f64>,
    values: Vec<f64>,
    power: f64,
}

impl ScatteredTable {
    /// Builds the table from `nodes` (`dimensions` coordinates per node, node after node),
    /// their `values` and the weighting power `p > 0` (RocketPy uses 3).
    ///
    /// # Errors
    /// [`MathError::BadAxis`] for zero dimensions or a bad power; [`MathError::WrongSize`] when
    /// the node coordinates are not `dimensions × values.len()`;
    /// [`MathError::TooFewPoints`] without nodes; [`MathError::NotFinite`] for a bad number.
    pub fn new(
        dimensions: usize,
        nodes: Vec<f64>,
        values: Vec<f64>,
        power: f64,
    ) -> Result<Self, MathError> {
        if dimensions == 0 {
            return Err(MathError::BadAxis {
                axis: 0,
                reason: "zero dimensions",
            });
        }
        if !(power.is_finite() && power > 0.0) {
            return Err(MathError::BadAxis {
                axis: 0,
                reason: "power must be finite and > 0",
            });
        }
        if values.is_empty() {
            return Err(MathError::TooFewPoints { needed: 1, got: 0 });
        }
        let expected = dimensions.saturating_mul(values.len());
        if nodes.len() != expected {
            return Err(MathError::WrongSize {
                expected,
                got: nodes.len(),
            });
        }
        for (i, &value) in nodes.iter().enumerate() {
            if !value.is_finite() {
                return Err(MathError::NotFinite {
                    index: i / dimensions,
                    value,
                });
            }
        }
        if let Some((index, &value)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(MathError::NotFinite { index, value });
        }
        Ok(ScatteredTable {
            dimensions,
            nodes,
            values,
            power,
        })
    }

    /// Number of coordinates per point.
    #[must_use]
    pub fn dimensions(&self) -> usize {
        self.dimensions
    }

    /// The interpolated value at `point`.
    ///
    /// # Panics
    /// When `point.len()` differs from [`ScatteredTable::dimensions`] (a programming error).
    #[must_use]
    pub fn eval(&self, point: &[f64]) -> f64 {
        assert_eq!(
            point.len(),
            self.dimensions,
            "ScatteredTable::eval: wrong point dimension"
        );
        if self.power.to_bits() == 3.0_f64.to_bits() {
            // RocketPy's power: `d⁻³ = 1 / (d² · d)`, without a general power.
            self.weighted(point, |d2| 1.0 / (d2 * d2.sqrt()))
        } else {
            let half_power = -0.5 * self.power;
            self.weighted(point, |d2| d2.powf(half_power))
        }
    }

    /// `Σ w(d_i²) y_i / Σ w(d_i²)` over the nodes in their order, or the value of the first
    /// node at distance zero.
    #[inline]
    fn weighted(&self, point: &[f64], weight: impl Fn(f64) -> f64) -> f64 {
        let (mut numerator, mut denominator) = (0.0, 0.0);
        for (node, &value) in self.nodes.chunks_exact(self.dimensions).zip(&self.values) {
            let d2: f64 = node.iter().zip(point).map(|(a, b)| (a - b) * (a - b)).sum();
            if d2 <= 0.0 {
                return value;
            }
            let w = weight(d2);
            numerator += w * value;
            denominator += w;
        }
        numerator / denominator
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_is_exact_for_bilinear_functions() {
        let f = |x: f64, y: f64| 1.0 + 2.0 * x - y + 0.5 * x * y;
        let xs = vec![0.0, 1.0, 3.0];
        let ys = vec![-1.0, 0.0, 2.0, 2.5];
        let values: Vec<f64> = xs
            .iter()
            .flat_map(|&x| ys.iter().map(move |&y| f(x, y)))
            .collect();
        let g = RegularGrid::new(vec![xs, ys], values).unwrap();
        for (x, y) in [(0.5, 0.5), (2.9, -0.7), (1.0, 2.0), (0.0, 2.5)] {
            assert!((g.eval(&[x, y]) - f(x, y)).abs() < 1e-13);
        }
        // Clamped outside.
        assert!((g.eval(&[10.0, -5.0]) - f(3.0, -1.0)).abs() < 1e-13);
    }

    #[test]
    fn grid_rejects_bad_shapes() {
        assert!(matches!(
            RegularGrid::new(vec![vec![0.0, 1.0]], vec![1.0]),
            Err(MathError::WrongSize {
                expected: 2,
                got: 1
            })
        ));
        assert!(matches!(
            RegularGrid::new(vec![vec![0.0, 0.0]], vec![1.0, 2.0]),
            Err(MathError::BadAxis { axis: 0, .. })
        ));
        let single = RegularGrid::new(vec![vec![2.0], vec![0.0, 1.0]], vec![3.0, 5.0]).unwrap();
        assert!((single.eval(&[7.0, 0.5]) - 4.0).abs() < 1e-15);
    }

    #[test]
    fn shepard_is_exact_at_nodes_and_bounded() {
        let t = ScatteredTable::new(
            2,
            vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0],
            vec![1.0, 2.0, 4.0],
            3.0,
        )
        .unwrap();
        assert!((t.eval(&[1.0, 0.0]) - 2.0).abs() < 1e-15);
        let v = t.eval(&[0.3, 0.3]);
        assert!(v > 1.0 && v < 4.0);
        // (0.5, 0.5) is equidistant from the three nodes: the plain mean.
        assert!((t.eval(&[0.5, 0.5]) - 7.0 / 3.0).abs() < 1e-14);
    }

    #[test]
    fn shepard_weights_follow_the_power() {
        let nodes: Vec<f64> = vec![0.0, 0.0, 1.0, 0.0, 0.0, 2.0, 1.5, 1.5];
        let values = vec![1.0, 2.0, 4.0, -3.0];
        let point = [0.3, 0.7];
        // Σ y d⁻ᵖ / Σ d⁻ᵖ with the distances themselves.
        let idw = |p: f64| {
            let (mut n, mut d) = (0.0, 0.0);
            for (node, y) in nodes.chunks_exact(2).zip(&values) {
                let w = (node[0] - point[0]).hypot(node[1] - point[1]).powf(-p);
                n += w * y;
                d += w;
            }
            n / d
        };
        for p in [3.0, 2.0, 3.5] {
            let t = ScatteredTable::new(2, nodes.clone(), values.clone(), p).unwrap();
            let (got, want) = (t.eval(&point), idw(p));
            assert!(
                (got - want).abs() < 1e-14 * want.abs(),
                "p = {p}: {got} {want}"
            );
        }
    }
}
