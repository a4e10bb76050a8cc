//! Nose cones: profile, centre of pressure and the effect of a spherical (bluff) tip.
//!
//! Normal-force slope `CNα = 2 (r_base / r_ref)²` (Barrowman 1967, slender-body theory; no Mach
//! dependence as in RocketPy, docs/physics.md §7.3). The CP lies `k·L` aft of the tip, with `k` per
//! profile (Barrowman 1967 for cone and ogive; RocketPy `NoseCone` for the others).

use std::f64::consts::PI;

use karman_math::PhysicalConstants;

use crate::error::{AirframeError, positive};

/// The profile family of a nose cone (RocketPy `NoseCone.kind`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NoseKind {
    /// Straight cone, `k = 2/3`.
    Conical,
    /// Tangent ogive (RocketPy treats "ogive" and "tangent" alike).
    Ogive,
    /// Half ellipsoid, `k = 1/3`.
    Elliptical,
    /// Von Kármán (Haack series, C = 0), `k = 0.5`.
    VonKarman,
    /// LV-Haack (Haack series, C = 1/3), `k = 0.563`.
    LvHaack,
    /// Parabola (K' = 1), `k = 0.5`.
    Parabolic,
    /// Power series `y = R (x/L)^n`, `0 < n ≤ 1`, `k = 2n/(2n+1)`.
    PowerSeries(f64),
}

impl NoseKind {
    /// The kind's name in RocketPy's spelling.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            NoseKind::Conical => "conical",
            NoseKind::Ogive => "ogive",
            NoseKind::Elliptical => "elliptical",
            NoseKind::VonKarman => "von karman",
            NoseKind::LvHaack => "lvhaack",
            NoseKind::Parabolic => "parabolic",
            NoseKind::PowerSeries(_) => "powerseries",
        }
    }
}

/// The user's description of a nose cone (RocketPy `Rocket.add_nose`).
#[derive(Debug, Clone, PartialEq)]
pub struct NoseConeSpec {
    /// Length from tip to base (m).
    pub length: f64,
    /// Profile family.
    pub kind: NoseKind,
    /// Base radius (m); `None` = the rocket radius.
    pub base_radius: Option<f64>,
    /// Ratio of the spherical tip radius to the base radius, in `[0, 1]`; 0 = sharp.
    pub bluffness: f64,
}

/// A resolved nose cone.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct NoseCone {
    pub kind: NoseKind,
    /// Effective length (shortened by a bluff tip, docs/physics.md §7.3).
    pub length: f64,
    pub base_radius: f64,
    /// CP distance aft of the tip (m).
    pub cp_local: f64,
    /// Profile `(x from the tip, radius)`, 127 points clustered at the tip.
    pub profile: Vec<[f64; 2]>,
}

/// Radius of the sharp profile at `x` aft of the tip (RocketPy `NoseCone.y_nosecone`).
fn profile_radius(kind: NoseKind, length: f64, radius: f64, x: f64) -> f64 {
    let haack_theta = |x: f64| (1.0 - 2.0 * (x / length).clamp(0.0, 1.0)).acos();
    match kind {
        NoseKind::Conical => x * radius / length,
        NoseKind::LvHaack => {
            let t = haack_theta(x);
            radius
                * (t - (2.0 * t).sin() / 2.0 + t.sin().powi(3) / 3.0)
                    .max(0.0)
                    .sqrt()
                / PI.sqrt()
        }
        NoseKind::Ogive => {
            let rho = (radius * radius + length * length) / (2.0 * radius);
            let d = (x - length).min(0.0);
            (rho * rho - d * d).max(0.0).sqrt() + (radius - rho)
        }
        NoseKind::Elliptical => {
            let u = (x - length) / length;
            radius * (1.0 - u * u).max(0.0).sqrt()
        }
        NoseKind::VonKarman => {
            let t = haack_theta(x);
            radius * (t - (2.0 * t).sin() / 2.0).max(0.0).sqrt() / PI.sqrt()
        }
        NoseKind::Parabolic => radius * (2.0 * x / length - (x / length).powi(2)),
        NoseKind::PowerSeries(n) => radius * (x / length).max(0.0).powf(n),
    }
}

/// The CP factor `k` of `x_cp = k·L` (docs/physics.md §7.3), with the ogive factor from the
/// ogive volume `V = π[L ρ² − L³/3 − (ρ − R) ρ² asin(L/ρ)]`, `k = 1 − V/(π R² L)`.
fn cp_factor(kind: NoseKind, length: f64, radius: f64) -> f64 {
    match kind {
        NoseKind::Conical => 2.0 / 3.0,
        NoseKind::Ogive => {
            let rho = (radius * radius + length * length) / (2.0 * radius);
            let volume = PI
                * (length * rho * rho
                    - length.powi(3) / 3.0
                    - (rho - radius) * rho * rho * (length / rho).clamp(-1.0, 1.0).asin());
            1.0 - volume / (PI * radius * radius * length)
        }
        NoseKind::Elliptical => 1.0 / 3.0,
        NoseKind::VonKarman | NoseKind::Parabolic => 0.5,
        NoseKind::LvHaack => 0.563,
        NoseKind::PowerSeries(n) => 2.0 * n / (2.0 * n + 1.0),
    }
}

/// Number of profile points RocketPy's `evaluate_nose_shape` uses.
const PROFILE_POINTS: usize = 127;

/// Builds the nose cone, returning it and any warnings; `constants` give the unit system
/// (RocketPy's 1 mm tolerance of the bluff-tip construction).
pub(crate) fn build(
    name: &str,
    spec: &NoseConeSpec,
    rocket_radius: f64,
    constants: &PhysicalConstants,
) -> Result<(NoseCone, Vec<String>), AirframeError> {
    let length = positive(name, "length", spec.length)?;
    let radius = positive(
        name,
        "base_radius",
        spec.base_radius.unwrap_or(rocket_radius),
    )?;
    if !(0.0..=1.0).contains(&spec.bluffness) {
        return Err(AirframeError::OutOfRange {
            component: name.to_owned(),
            quantity: "bluffness",
            value: spec.bluffness,
            min: 0.0,
            max: 1.0,
        });
    }
    if matches!(spec.kind, NoseKind::PowerSeries(_)) && spec.bluffness > 0.0 {
        return Err(AirframeError::Geometry {
            component: name.to_owned(),
            reason: "bluffness must be 0 for a power-series nose cone".to_owned(),
        });
    }
    if let NoseKind::PowerSeries(n) = spec.kind {
        if !(n > 0.0 && n <= 1.0) {
            return Err(AirframeError::OutOfRange {
                component: name.to_owned(),
                quantity: "power",
                value: n,
                min: 0.0,
                max: 1.0,
            });
        }
    }
    let mut warnings = Vec::new();
    // k uses the length as given (RocketPy computes it before the bluff-tip shortening).
    let k = cp_factor(spec.kind, length, radius);
    let y = |x: f64| profile_radius(spec.kind, length, radius, x);
    let tip = bluff_tip(
        spec.kind,
        length,
        radius,
        spec.bluffness,
        constants.nose_shape_tolerance,
        &y,
    );
    let (r_circle, center, x_init) = match tip {
        Some(t) => t,
        None => {
            if spec.bluffness > 0.0 {
                warnings.push(format!(
                    "{name}: bluffness {} is too small for a {} nose cone; the tip is kept sharp",
                    spec.bluffness,
                    spec.kind.name()
                ));
            }
            (0.0, 0.0, 0.0)
        }
    };
    let shift = center - r_circle;
    let span = length - shift;
    let mut effective = length;
    if (span - length).abs() >= constants.nose_shape_tolerance {
        effective = span;
        warnings.push(format!(
            "{name}: the bluff tip shortens the nose cone from {length} m to {span} m"
        ));
    }
    let profile = (0..PROFILE_POINTS)
        .map(|i| {
            let u = i as f64 / (PROFILE_POINTS - 1) as f64;
            let x = span * u.powi(3);
            let xs = x + shift;
            let r = if xs >= x_init {
                y(xs)
            } else {
                (r_circle * r_circle - (xs - center).powi(2)).abs().sqrt()
            };
            [x, r]
        })
        .collect();
    let cone = NoseCone {
        kind: spec.kind,
        length: effective,
        base_radius: radius,
        cp_local: k * effective,
        profile,
    };
    Ok((cone, warnings))
}

/// The spherical tip of a bluff nose (RocketPy `evaluate_nose_shape`): the circle of radius
/// `b·R` tangent to the profile. Returns `(circle radius, circle centre x, tangency x)` or
/// `None` for a sharp tip. An elliptical nose keeps a sharp tip when the circle is inside the
/// profile at `x = probe` (RocketPy's 1 mm).
fn bluff_tip(
    kind: NoseKind,
    length: f64,
    radius: f64,
    bluffness: f64,
    probe: f64,
    y: &impl Fn(f64) -> f64,
) -> Option<(f64, f64, f64)> {
    if bluffness <= 0.0 {
        return None;
    }
    let r_circle = bluffness * radius;
    let h = 1e-7 * length;
    let slope = |x: f64| {
        let a = (x - h).max(0.0);
        let b = (x + h).min(length);
        (y(b) - y(a)) / (b - a)
    };
    if kind == NoseKind::Elliptical {
        let x = probe;
        let test = (r_circle * r_circle - (x - r_circle).powi(2))
            .max(0.0)
            .sqrt();
        if test <= y(x) {
            return None;
        }
    }
    // Radius of the circle tangent to the profile at x whose centre is on the axis:
    // y·sqrt(1 + y'²); its centre is at x + y·y'.
    let g = |x: f64| {
        let s = slope(x);
        y(x) * (1.0 + s * s).sqrt() - r_circle
    };
    const SCAN: usize = 400;
    let mut best: Option<(f64, f64)> = None;
    let mut prev_x = length * 1e-9;
    let mut prev_g = g(prev_x);
    for i in 1..=SCAN {
        let x = length * i as f64 / SCAN as f64;
        let gx = g(x);
        if prev_g.is_finite() && gx.is_finite() && prev_g.signum() != gx.signum() {
            let mid = 0.5 * (prev_x + x);
            if best.is_none_or(|(bx, _)| (mid - r_circle).abs() < (bx - r_circle).abs()) {
                best = Some((prev_x, x));
            }
        }
        prev_x = x;
        prev_g = gx;
    }
    let (mut a, mut b) = best?;
    let ga = g(a);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if (g(m) > 0.0) == (ga > 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    let x_init = 0.5 * (a + b);
    let center = x_init + y(x_init) * slope(x_init);
    Some((r_circle, center, x_init))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(kind: NoseKind) -> NoseConeSpec {
        NoseConeSpec {
            length: 0.55829,
            kind,
            base_radius: None,
            bluffness: 0.0,
        }
    }

    #[test]
    fn cp_factors_match_physics_table() {
        // docs/physics.md §7.3
        let cases = [
            (NoseKind::Conical, 2.0 / 3.0),
            (NoseKind::Elliptical, 1.0 / 3.0),
            (NoseKind::VonKarman, 0.5),
            (NoseKind::LvHaack, 0.563),
            (NoseKind::Parabolic, 0.5),
            (NoseKind::PowerSeries(0.5), 0.5),
        ];
        for (kind, k) in cases {
            let (cone, w) =
                build("nose", &spec(kind), 0.0635, &PhysicalConstants::SI).expect("valid nose");
            assert!(w.is_empty());
            assert!((cone.cp_local - k * 0.55829).abs() < 1e-12, "{kind:?}");
        }
    }

    #[test]
    fn ogive_cp_matches_ndrt_reference() {
        // validation/ndrt_2020/reference.json: nose cp_m 0.28210487231911097 with the tip at 0,
        // nose_to_tail, length 0.61, radius 0.1015.
        let s = NoseConeSpec {
            length: 0.61,
            kind: NoseKind::Ogive,
            base_radius: None,
            bluffness: 0.0,
        };
        let (cone, _) = build("nose", &s, 0.1015, &PhysicalConstants::SI).expect("valid nose");
        assert!((cone.cp_local - 0.282_104_872_319_110_97).abs() < 1e-12);
    }

    #[test]
    fn bluff_tip_shortens_the_cone_and_is_tangent() {
        let mut s = spec(NoseKind::Ogive);
        s.bluffness = 0.3;
        let (cone, w) = build("nose", &s, 0.0635, &PhysicalConstants::SI).expect("valid nose");
        assert!(
            cone.length < 0.55829 && cone.length > 0.4,
            "length {}",
            cone.length
        );
        assert_eq!(w.len(), 1);
        // The profile starts on the axis and ends at the base radius.
        assert!(cone.profile[0][1].abs() < 1e-9);
        let last = cone.profile[PROFILE_POINTS - 1];
        assert!((last[0] - cone.length).abs() < 1e-12);
        assert!((last[1] - 0.0635).abs() < 1e-9);
    }

    #[test]
    fn profile_of_sharp_cone_is_the_shape() {
        let (cone, _) = build(
            "nose",
            &spec(NoseKind::Conical),
            0.0635,
            &PhysicalConstants::SI,
        )
        .expect("valid nose");
        for [x, r] in &cone.profile {
            assert!((r - x * 0.0635 / 0.55829).abs() < 1e-12);
        }
    }

    #[test]
    fn impossible_noses_are_errors() {
        let mut s = spec(NoseKind::Conical);
        s.length = -1.0;
        assert!(build("nose", &s, 0.0635, &PhysicalConstants::SI).is_err());
        let mut s = spec(NoseKind::Conical);
        s.bluffness = 1.5;
        assert!(build("nose", &s, 0.0635, &PhysicalConstants::SI).is_err());
        let mut s = spec(NoseKind::PowerSeries(0.5));
        s.bluffness = 0.2;
        assert!(build("nose", &s, 0.0635, &PhysicalConstants::SI).is_err());
        assert!(
            build(
                "nose",
                &spec(NoseKind::PowerSeries(1.5)),
                0.0635,
                &PhysicalConstants::SI
            )
            .is_err()
        );
        assert!(
            build(
                "nose",
                &spec(NoseKind::PowerSeries(f64::NAN)),
                0.0635,
                &PhysicalConstants::SI
            )
            .is_err()
        );
        assert!(
            build(
                "nose",
                &spec(NoseKind::Conical),
                0.0,
                &PhysicalConstants::SI
            )
            .is_err()
        );
    }
}
