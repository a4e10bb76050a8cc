//! Pressure drag of the body (Niskanen 2009, §3.4.2–§3.4.4; docs/physics.md §20.3): forward-facing
//! faces (stagnation), nose cones and expanding transitions (shape- and Mach-dependent tables),
//! boattails, and the base.
//!
//! - Stagnation pressure of a blunt face, Hoerner (1965) ch. 15 / Niskanen eq. 3.86:
//!   C = 0.85 (1 + M²/4 + M⁴/40) subsonic, 0.85 (1.84 − 0.76/M² + 0.166/M⁴ + 0.035/M⁶)
//!   supersonic, on the frontal area of every step up in radius.
//! - Base drag, Fleeman (2001) / Niskanen eq. 3.94: 0.12 + 0.13 M² subsonic, 0.25/M supersonic,
//!   on every step down in radius (the rocket's base included).
//! - Conical and ogive noses, Niskanen eqs. 3.87–3.90 (after Hoerner and the slender-body
//!   cone formula): C(M=1) = sin φ, C(M=1.3) = 2.1 sin²φ + 0.6019 sin φ, a cubic between with
//!   the slopes 4/(γ+1)(1 − sin φ/2) and −1.1341 sin φ, and 2.1 sin²φ + 0.5 sin φ/√(M² − 1)
//!   above, times 0.72 (p − 1/2)² + 0.82 for an ogive of parameter p (cone: p = 0). φ is the
//!   cone half-angle (for an ogive, the joint angle at its base).
//! - Other shapes: the transonic and supersonic measurements at fineness 3 of NASA TR-R-100
//!   (Stoney 1961) as tabulated in Niskanen's Figure 3.13, interpolated in the shape parameter
//!   and carried to fineness f by C = C_stag (C₃/C_stag)^(log(f+1)/log 4).
//! - Subsonic, where the table starts above zero: C = a M^b + 0.8 sin²φ through its first
//!   point with its slope (Niskanen eq. 3.91).
//! - Boattails, Niskanen eq. 3.92: base drag times (3 − f)/2 for 1 < f < 3, f = L/(d₁ − d₂) the
//!   fineness of the contraction (full base drag at f ≤ 1, none at f ≥ 3).

use super::shape::Profile;

/// Stagnation pressure coefficient of a face normal to the flow at Mach `mach`.
#[must_use]
pub fn stagnation_coefficient(mach: f64) -> f64 {
    let q = if mach <= 1.0 {
        let m2 = mach * mach;
        1.0 + m2 / 4.0 + m2 * m2 / 40.0
    } else {
        let m2 = mach * mach;
        1.84 - 0.76 / m2 + 0.166 / (m2 * m2) + 0.035 / (m2 * m2 * m2)
    };
    0.85 * q
}

/// Base drag coefficient (on the base area) at Mach `mach`.
#[must_use]
pub fn base_coefficient(mach: f64) -> f64 {
    if mach <= 1.0 {
        0.12 + 0.13 * mach * mach
    } else {
        0.25 / mach
    }
}

/// A piecewise-linear function held constant beyond its ends, built point by point (a later
/// point at an existing abscissa replaces it).
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Polyline {
    points: Vec<[f64; 2]>,
}

impl Polyline {
    fn from_points(xs: &[f64], ys: &[f64]) -> Polyline {
        let mut p = Polyline::default();
        for (x, y) in xs.iter().zip(ys) {
            p.add(*x, *y);
        }
        p
    }

    fn add(&mut self, x: f64, y: f64) {
        match self.points.binary_search_by(|p| p[0].total_cmp(&x)) {
            Ok(i) => self.points[i][1] = y,
            Err(i) => self.points.insert(i, [x, y]),
        }
    }

    fn xs(&self) -> Vec<f64> {
        self.points.iter().map(|p| p[0]).collect()
    }

    pub(crate) fn eval(&self, x: f64) -> f64 {
        let pts = &self.points;
        let (Some(first), Some(last)) = (pts.first(), pts.last()) else {
            return 0.0;
        };
        if x <= first[0] {
            return first[1];
        }
        if x >= last[0] {
            return last[1];
        }
        let i = pts.partition_point(|p| p[0] <= x);
        let (a, b) = (pts[i - 1], pts[i]);
        a[1] + (x - a[0]) / (b[0] - a[0]) * (b[1] - a[1])
    }
}

/// Fineness-3 measurements (Mach, C) of NASA TR-R-100 for the shapes without a closed form.
const ELLIPSOID: (&[f64], &[f64]) = (
    &[1.2, 1.25, 1.3, 1.4, 1.6, 2.0, 2.4],
    &[0.110, 0.128, 0.140, 0.148, 0.152, 0.159, 0.162],
);
const POWER_1_4: (&[f64], &[f64]) = (
    &[1.2, 1.3, 1.4, 1.6, 1.8, 2.2, 2.6, 3.0, 3.6],
    &[
        0.140, 0.156, 0.169, 0.192, 0.206, 0.227, 0.241, 0.249, 0.252,
    ],
);
const POWER_1_2: (&[f64], &[f64]) = (
    &[0.925, 0.95, 1.0, 1.05, 1.1, 1.2, 1.3, 1.7, 2.0],
    &[0.0, 0.014, 0.050, 0.060, 0.059, 0.081, 0.084, 0.085, 0.078],
);
const POWER_3_4: (&[f64], &[f64]) = (
    &[0.8, 0.9, 1.0, 1.06, 1.2, 1.4, 1.6, 2.0, 2.8, 3.4],
    &[
        0.0, 0.015, 0.078, 0.121, 0.110, 0.098, 0.090, 0.084, 0.078, 0.074,
    ],
);
const VON_KARMAN: (&[f64], &[f64]) = (
    &[0.9, 0.95, 1.0, 1.05, 1.1, 1.2, 1.4, 1.6, 2.0, 3.0],
    &[
        0.0, 0.010, 0.027, 0.055, 0.070, 0.081, 0.095, 0.097, 0.091, 0.083,
    ],
);
const LV_HAACK: (&[f64], &[f64]) = (
    &[0.9, 0.95, 1.0, 1.05, 1.1, 1.2, 1.4, 1.6, 2.0],
    &[0.0, 0.010, 0.024, 0.066, 0.084, 0.100, 0.114, 0.117, 0.113],
);
const PARABOLIC_1: (&[f64], &[f64]) = (
    &[0.95, 0.975, 1.0, 1.05, 1.1, 1.2, 1.4, 1.7],
    &[0.0, 0.016, 0.041, 0.092, 0.109, 0.119, 0.113, 0.108],
);
const PARABOLIC_1_2: (&[f64], &[f64]) = (
    &[0.8, 0.9, 0.95, 1.0, 1.05, 1.1, 1.3, 1.5, 1.8],
    &[0.0, 0.016, 0.042, 0.100, 0.126, 0.125, 0.100, 0.090, 0.088],
);
const PARABOLIC_3_4: (&[f64], &[f64]) = (
    &[0.9, 0.95, 1.0, 1.05, 1.1, 1.2, 1.4, 1.7],
    &[0.0, 0.023, 0.073, 0.098, 0.107, 0.106, 0.089, 0.082],
);

fn table(data: (&[f64], &[f64])) -> Polyline {
    Polyline::from_points(data.0, data.1)
}

/// The stagnation coefficient sampled every 0.05 in Mach up to 3, linearly interpolated: the
/// blunt end of the power series and the reference of the fineness scaling.
fn blunt() -> Polyline {
    let mut p = Polyline::default();
    for i in 0..60 {
        let m = f64::from(i) * 0.05;
        p.add(m, stagnation_coefficient(m));
    }
    p
}

/// Conical (`p` = 0) or ogive nose pressure drag above Mach 1, for the joint sine `sin_phi`.
fn ogive(p: f64, sin_phi: f64, gamma: f64) -> Polyline {
    let s = sin_phi;
    // Cubic Hermite on [1, 1.3] through the values and slopes at both ends.
    let (x0, x1) = (1.0, 1.3);
    let (y0, y1) = (s, 2.1 * s * s + 0.6019 * s);
    let (d0, d1) = (4.0 / (gamma + 1.0) * (1.0 - 0.5 * s), -1.1341 * s);
    let h = x1 - x0;
    let cubic = |m: f64| {
        let t = (m - x0) / h;
        let (t2, t3) = (t * t, t * t * t);
        (2.0 * t3 - 3.0 * t2 + 1.0) * y0
            + (t3 - 2.0 * t2 + t) * h * d0
            + (-2.0 * t3 + 3.0 * t2) * y1
            + (t3 - t2) * h * d1
    };
    let mul = 0.72 * (p - 0.5).powi(2) + 0.82;
    let mut out = Polyline::default();
    for i in 0..=15 {
        let m = 1.0 + f64::from(i) * 0.02;
        out.add(m, mul * cubic(m));
    }
    for i in 66..200 {
        let m = f64::from(i) * 0.02;
        out.add(m, mul * (2.1 * s * s + 0.5 * s / (m * m - 1.0).sqrt()));
    }
    out
}

/// Blend `(1 − p) a + p b` on the union of both abscissae.
fn blend(a: &Polyline, b: &Polyline, p: f64) -> Polyline {
    let mut out = Polyline::default();
    for m in a.xs().into_iter().chain(b.xs()) {
        out.add(m, p * b.eval(m) + (1.0 - p) * a.eval(m));
    }
    out
}

/// Pressure drag coefficient (on the frontal area) of a nose cone or expanding transition of
/// profile `profile`, fineness `fineness` = L / (d_aft − d_fore) and aft joint sine `sin_phi`,
/// as a function of Mach.
pub(crate) fn nose_table(profile: Profile, fineness: f64, sin_phi: f64, gamma: f64) -> Polyline {
    let cone_of_fineness = || ogive(0.0, 1.0 / (1.0 + 4.0 * fineness * fineness).sqrt(), gamma);
    let fineness3 = |t: Polyline| {
        let stag = blunt();
        let exponent = (fineness + 1.0).ln() / 4.0f64.ln();
        let mut out = Polyline::default();
        for m in t.xs() {
            let c = stag.eval(m);
            out.add(m, c * (t.eval(m) / c).powf(exponent));
        }
        out
    };
    let mut out = match profile {
        Profile::Conical => ogive(0.0, sin_phi, gamma),
        Profile::Ogive(p) => ogive(p, sin_phi, gamma),
        Profile::Ellipsoid => fineness3(table(ELLIPSOID)),
        Profile::Power(k) => fineness3(if k <= 0.25 {
            blend(&blunt(), &table(POWER_1_4), k * 4.0)
        } else if k <= 0.5 {
            blend(&table(POWER_1_4), &table(POWER_1_2), (k - 0.25) * 4.0)
        } else if k <= 0.75 {
            blend(&table(POWER_1_2), &table(POWER_3_4), (k - 0.5) * 4.0)
        } else {
            blend(&table(POWER_3_4), &cone_of_fineness(), (k - 0.75) * 4.0)
        }),
        Profile::Parabolic(k) => fineness3(if k <= 0.5 {
            blend(&cone_of_fineness(), &table(PARABOLIC_1_2), k * 2.0)
        } else if k <= 0.75 {
            blend(
                &table(PARABOLIC_1_2),
                &table(PARABOLIC_3_4),
                (k - 0.5) * 4.0,
            )
        } else {
            blend(&table(PARABOLIC_3_4), &table(PARABOLIC_1), (k - 0.75) * 4.0)
        }),
        Profile::Haack(c) => fineness3(blend(&table(VON_KARMAN), &table(LV_HAACK), c * 3.0)),
    };
    subsonic_fit(&mut out, sin_phi);
    out
}

/// Niskanen eq. 3.91: below the first tabulated Mach number, C = a M^b + 0.8 sin²φ matched
/// to the table's first value and slope (when the table starts above zero and the fit is
/// well posed).
fn subsonic_fit(table: &mut Polyline, sin_phi: f64) {
    let Some(&[min, value]) = table.points.first() else {
        return;
    };
    if value < 0.001 {
        return;
    }
    let c0 = 0.8 * sin_phi * sin_phi;
    let slope = (table.eval(min + 0.01) - value) / 0.01;
    if c0 >= value - 0.01 || slope <= 0.01 {
        return;
    }
    let b = min * slope / (value - c0);
    let a = (value - c0) / min.powf(b);
    let mut m = 0.0;
    let mut i = 0;
    while m < min {
        table.add(m, a * m.powf(b) + c0);
        i += 1;
        m = f64::from(i) * 0.05;
    }
}

/// Boattail pressure drag coefficient (on the frontal area) for a contraction of fineness
/// `fineness` = L / (d_fore − d_aft), as a fraction of the base coefficient `base`.
#[must_use]
pub fn boattail_coefficient(fineness: f64, base: f64) -> f64 {
    if fineness >= 3.0 {
        0.0
    } else if fineness <= 1.0 {
        base
    } else {
        base * (3.0 - fineness) / 2.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stagnation_and_base_are_continuous_at_mach_1() {
        let (a, b) = (
            stagnation_coefficient(1.0),
            stagnation_coefficient(1.0 + 1e-9),
        );
        // Hoerner's two fits meet to 0.5 % at Mach 1.
        assert!((a - b).abs() < 0.01, "{a} {b}");
        assert!((base_coefficient(1.0) - 0.25).abs() < 1e-15);
        assert!((stagnation_coefficient(0.0) - 0.85).abs() < 1e-15);
    }

    #[test]
    fn cone_supersonic_formula() {
        let s = 0.2f64;
        let t = nose_table(Profile::Conical, 2.0, s, 1.4);
        let m = 2.0;
        let expected = 2.1 * s * s + 0.5 * s / (m * m - 1.0f64).sqrt();
        assert!(
            (t.eval(m) - expected).abs() < 1e-9,
            "{} {expected}",
            t.eval(m)
        );
        // The cubic joins the supersonic law at Mach 1.3 and starts from sin φ at Mach 1.
        assert!((t.eval(1.0) - s).abs() < 1e-12);
        // Subsonic: the fit falls to 0.8 sin²φ at Mach 0.
        assert!((t.eval(0.0) - 0.8 * s * s).abs() < 1e-12);
    }

    #[test]
    fn fineness_3_reproduces_the_measurements() {
        let t = nose_table(Profile::Haack(0.0), 3.0, 0.0, 1.4);
        assert!((t.eval(1.2) - 0.081).abs() < 1e-12);
        assert!(t.eval(0.5).abs() < 1e-12, "no subsonic pressure drag");
    }
}
