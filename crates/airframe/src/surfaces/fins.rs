//! Fin sets: planform geometry, normal-force slope vs Mach, roll forcing and damping.
//!
//! - Single-fin slope: Diederich's planform correlation (NACA TN 2335) as used by Barrowman
//!   (1967) and Niskanen (2009, §3.2.2), with RocketPy's piecewise Prandtl–Glauert factor β(M)
//!   (docs/physics.md §7.5).
//! - Fin-set slope: Niskanen's fin-count factor × the body interference `1 + r_t/(s + r_t)`.
//!   The factor N/2 is the average over the flow's roll angle θ of Niskanen's (2009, §3.2.2)
//!   `Σᵢ sin²(θ − φᵢ)` over the fins at roll positions φᵢ; for N ≥ 3 evenly spaced fins the
//!   sum is N/2 at every θ, for one or two fins it is not ([`FinAerodynamics::roll_factor`]).
//! - Roll: Barrowman (1967, ch. 3) forcing and damping interference factors `K_f`, `K_d` and the
//!   roll integral `G = ∫ c(ξ) ξ² dξ` (docs/physics.md §7.6), with RocketPy's `cos δ` on damping.
//! - Free-form fins: OpenRocket's 40-station span discretisation (Niskanen 2009, §3.2.2) as in
//!   RocketPy `FreeFormFins`.

use std::f64::consts::PI;

use karman_math::Table1;

use crate::error::{AirframeError, finite, non_negative, positive};

/// The angle unit of an airfoil lift curve's abscissa.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AngleUnit {
    /// Angle of attack in radians.
    Radians,
    /// Angle of attack in degrees.
    Degrees,
}

/// An airfoil lift curve `c_l(α)` (linear interpolation; RocketPy `airfoil=(curve, unit)`).
#[derive(Debug, Clone, PartialEq)]
pub struct Airfoil {
    /// Lift coefficient vs angle of attack.
    pub lift_curve: Table1,
    /// Unit of the curve's angle of attack.
    pub unit: AngleUnit,
}

/// Sweep of a trapezoidal fin's leading edge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sweep {
    /// No sweep given: the sweep length is `root_chord − tip_chord` (RocketPy default).
    Default,
    /// Axial distance from the root leading edge to the tip leading edge (m).
    Length(f64),
    /// Leading-edge sweep angle (deg): sweep length `span · tan(angle)`.
    AngleDeg(f64),
}

/// A set of identical trapezoidal fins (RocketPy `add_trapezoidal_fins`).
#[derive(Debug, Clone, PartialEq)]
pub struct TrapezoidalFinsSpec {
    /// Number of fins.
    pub n: u32,
    /// Root chord C_r (m).
    pub root_chord: f64,
    /// Tip chord C_t (m).
    pub tip_chord: f64,
    /// Span s (m).
    pub span: f64,
    /// Leading-edge sweep.
    pub sweep: Sweep,
    /// Cant angle δ (deg).
    pub cant_angle_deg: f64,
    /// Roll position φ₀ of the first fin about the rocket axis (deg), the others at
    /// `φ₀ + 360° i / N` (OpenRocket's fin-set rotation); it matters only for sets of one or
    /// two fins ([`FinAerodynamics::roll_factor`]).
    pub angular_position_deg: f64,
    /// Body radius at the fins r_t (m); `None` = the rocket radius.
    pub radius: Option<f64>,
    /// Optional airfoil lift curve (flat plate `2π` otherwise).
    pub airfoil: Option<Airfoil>,
}

/// A set of identical elliptical fins (RocketPy `add_elliptical_fins`).
#[derive(Debug, Clone, PartialEq)]
pub struct EllipticalFinsSpec {
    /// Number of fins.
    pub n: u32,
    /// Root chord C_r (m).
    pub root_chord: f64,
    /// Span s (m).
    pub span: f64,
    /// Cant angle δ (deg).
    pub cant_angle_deg: f64,
    /// Roll position φ₀ of the first fin about the rocket axis (deg), the others at
    /// `φ₀ + 360° i / N` (OpenRocket's fin-set rotation); it matters only for sets of one or
    /// two fins ([`FinAerodynamics::roll_factor`]).
    pub angular_position_deg: f64,
    /// Body radius at the fins r_t (m); `None` = the rocket radius.
    pub radius: Option<f64>,
    /// Optional airfoil lift curve.
    pub airfoil: Option<Airfoil>,
}

/// A set of identical free-form fins (RocketPy `add_free_form_fins`).
#[derive(Debug, Clone, PartialEq)]
pub struct FreeFormFinsSpec {
    /// Number of fins.
    pub n: u32,
    /// Outline `(x aft of the root leading edge, y spanwise from the root)`, starting and
    /// ending on the root (y = 0).
    pub shape_points: Vec<[f64; 2]>,
    /// Cant angle δ (deg).
    pub cant_angle_deg: f64,
    /// Roll position φ₀ of the first fin about the rocket axis (deg), the others at
    /// `φ₀ + 360° i / N` (OpenRocket's fin-set rotation); it matters only for sets of one or
    /// two fins ([`FinAerodynamics::roll_factor`]).
    pub angular_position_deg: f64,
    /// Body radius at the fins r_t (m); `None` = the rocket radius.
    pub radius: Option<f64>,
    /// Optional airfoil lift curve.
    pub airfoil: Option<Airfoil>,
}

/// Aerodynamic constants of a fin set; every Mach-dependent coefficient is a closed form of
/// these, evaluated at each call without allocation (docs/performance.md, "Fins").
#[derive(Debug, Clone, PartialEq)]
pub struct FinAerodynamics {
    /// Number of fins N.
    pub n: u32,
    /// Body radius at the fins r_t (m): the reference radius of the set, unless it is 0.
    pub body_radius: f64,
    /// Reference radius of the coefficients (m): `r_t`, or the rocket radius for fins on no
    /// body (`r_t = 0`: OpenRocket's "phantom" zero-radius body tube of a pod, which carries
    /// fins only).
    pub reference_radius: f64,
    /// One fin's planform area A_f (m²).
    pub fin_area: f64,
    /// Aspect ratio `2 s² / A_f`.
    pub aspect_ratio: f64,
    /// Mid-chord sweep angle Γ_c (rad).
    pub mid_chord_sweep: f64,
    /// Spanwise station of the mean aerodynamic chord from the root, Y_ma (m).
    pub mean_aerodynamic_span: f64,
    /// τ = (s + r_t)/r_t.
    pub tau: f64,
    /// Lift interference factor K_T = 1 + 1/τ.
    pub lift_interference: f64,
    /// Niskanen's fin-count factor f_N.
    pub fin_count_factor: f64,
    /// Incompressible 2-D lift slope cl_α0 (per rad).
    pub airfoil_lift_slope: f64,
    /// Roll forcing interference factor K_f (Barrowman 1967).
    pub roll_forcing_interference: f64,
    /// Roll damping interference factor K_d.
    pub roll_damping_interference: f64,
    /// Roll geometric integral G (m⁴).
    pub roll_integral: f64,
    /// Cant angle δ (rad).
    pub cant_angle: f64,
    /// Roll position φ₀ of the first fin about the rocket axis (rad).
    pub angular_position: f64,
    /// `2π AR A_f/A`, the numerator of CNα₁ (see [`FinAerodynamics::single_fin_cn_alpha`]).
    lift_numerator: f64,
    /// `(2π AR / (cl_α0 cos Γ_c))²`, so that `f_d² = ` this `· β²`.
    diederich_factor_squared: f64,
    /// The sign of `f_d` (that of `cl_α0`).
    diederich_sign: f64,
    forcing_factor: f64,
    damping_factor: f64,
}

/// The square of RocketPy's compressibility factor β(M) (docs/physics.md §7.5, **\[RP\]**):
/// `1 − M²` below Mach 0.8, held at `1 − 0.8²` up to Mach 1.1, `M² − 1` above.
#[inline]
fn beta_squared(mach: f64) -> f64 {
    if mach < 0.8 {
        1.0 - mach * mach
    } else if mach < 1.1 {
        1.0f64 - 0.8 * 0.8
    } else {
        mach * mach - 1.0
    }
}

/// Niskanen's (2009) fin-count correction factor (N/2 outside 5–8).
fn fin_count_factor(n: u32) -> f64 {
    match n {
        5 => 2.37,
        6 => 2.74,
        7 => 2.99,
        8 => 3.24,
        _ => f64::from(n) / 2.0,
    }
}

/// Barrowman's roll forcing interference factor K_f(τ).
fn roll_forcing_interference(tau: f64) -> f64 {
    let t2 = tau * tau;
    let a = ((t2 - 1.0) / (t2 + 1.0)).asin();
    let q = (t2 + 1.0).powi(2) / (t2 * (tau - 1.0).powi(2));
    (1.0 / (PI * PI))
        * ((PI * PI / 4.0) * (tau + 1.0).powi(2) / t2 + PI * q * a
            - 2.0 * PI * (tau + 1.0) / (tau * (tau - 1.0))
            + q * a * a
            - 4.0 * (tau + 1.0) / (tau * (tau - 1.0)) * a
            + 8.0 / (tau - 1.0).powi(2) * ((t2 + 1.0) / (2.0 * tau)).ln())
}

impl FinAerodynamics {
    /// Single-fin normal-force slope CNα₁(M) on the area `π r_t²` (docs/physics.md §7.5).
    #[inline]
    #[must_use]
    pub fn single_fin_cn_alpha(&self, mach: f64) -> f64 {
        // Diederich's form (docs/physics.md §7.5):
        // `cla·f_d·(A_f/A)·cos Γ_c / (2 + f_d √(1 + (2/f_d)²))`
        // with `cla = cl_α0/β` and `f_d = 2π AR / (cla cos Γ_c)`: the numerator is the
        // constant `2π AR A_f/A` and `f_d √(1 + (2/f_d)²) = sign(f_d) √(f_d² + 4)` with
        // `f_d² ∝ β²`, equal to the form above to rounding.
        let fd_squared = self.diederich_factor_squared * beta_squared(mach);
        self.lift_numerator / (2.0 + self.diederich_sign * (fd_squared + 4.0).sqrt())
    }

    /// Fin-set normal-force slope CNα_N(M) = f_N K_T CNα₁(M).
    #[inline]
    #[must_use]
    pub fn cn_alpha(&self, mach: f64) -> f64 {
        self.lift_interference * self.fin_count_factor * self.single_fin_cn_alpha(mach)
    }

    /// The factor that turns [`FinAerodynamics::cn_alpha`] into the slope of the set when
    /// the flow's lateral component comes at roll angle `theta` (rad, measured as the fins'
    /// [`FinAerodynamics::angular_position`]): Niskanen's (2009, §3.2.2) `Σᵢ sin²(θ − φᵢ)`,
    /// φᵢ = φ₀ + 2π i / N, over its average N/2. Exactly 1 for N ≥ 3, where the sum is N/2
    /// at every θ; for one fin `2 sin²(θ − φ₀)`, for two `2 sin²(θ − φ₀)` as well (the
    /// second fin, opposite, adds the same term).
    #[must_use]
    pub fn roll_factor(&self, theta: f64) -> f64 {
        if self.n >= 3 {
            return 1.0;
        }
        let sum: f64 = (0..self.n)
            .map(|i| {
                let phi = self.angular_position + 2.0 * PI * f64::from(i) / f64::from(self.n);
                (theta - phi).sin().powi(2)
            })
            .sum();
        sum / (0.5 * f64::from(self.n))
    }

    /// Roll forcing coefficient derivative C_lf,δ(M) = K_f N (Y_ma + r_t) CNα₁ / d.
    #[inline]
    #[must_use]
    pub fn roll_forcing_derivative(&self, mach: f64) -> f64 {
        self.forcing_factor * self.single_fin_cn_alpha(mach)
    }

    /// Roll damping coefficient derivative C_ld,ω(M) = 2 K_d N CNα₁ cos δ G / (A d²).
    #[inline]
    #[must_use]
    pub fn roll_damping_derivative(&self, mach: f64) -> f64 {
        self.damping_factor * self.single_fin_cn_alpha(mach)
    }

    /// `[CNα_N, C_lf,δ·δ, C_ld,ω]` at `mach` with CNα₁(M) evaluated once: the values of
    /// [`FinAerodynamics::cn_alpha`], [`FinAerodynamics::roll_forcing_derivative`] times the
    /// cant angle and [`FinAerodynamics::roll_damping_derivative`], to the bit.
    #[inline]
    #[must_use]
    pub fn coefficients(&self, mach: f64) -> [f64; 3] {
        let single = self.single_fin_cn_alpha(mach);
        [
            self.lift_interference * self.fin_count_factor * single,
            self.forcing_factor * single * self.cant_angle,
            self.damping_factor * single,
        ]
    }
}

/// Planform quantities shared by all fin kinds.
struct Planform {
    fin_area: f64,
    mid_chord_sweep: f64,
    mean_aerodynamic_span: f64,
    roll_integral: f64,
    roll_damping_interference: f64,
    cp_local: f64,
    span: f64,
    outline: Vec<[f64; 2]>,
}

/// A resolved fin set: aerodynamics, CP (m aft of the root leading edge) and outline.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct FinSet {
    pub aero: FinAerodynamics,
    pub cp_local: f64,
    pub root_chord: f64,
    pub span: f64,
    pub outline: Vec<[f64; 2]>,
}

fn check_count(name: &str, n: u32) -> Result<(), AirframeError> {
    if n == 0 {
        return Err(AirframeError::NotPositive {
            component: name.to_owned(),
            quantity: "n",
            value: 0.0,
        });
    }
    Ok(())
}

/// The 2-D lift slope at zero incidence: 2π, or the airfoil curve's slope at α = 1e-3 in the
/// curve's own unit (RocketPy 1.13 `airfoil_cl.differentiate(x=1e-3)`: the slope of the
/// linear segment holding it, the left one at a node), ×180/π for degrees.
fn airfoil_slope(name: &str, airfoil: Option<&Airfoil>, warnings: &mut Vec<String>) -> f64 {
    let Some(a) = airfoil else { return 2.0 * PI };
    let mut slope = a.lift_curve.derivative(1e-3);
    if a.unit == AngleUnit::Degrees {
        slope *= 180.0 / PI;
    }
    if slope <= 0.0 {
        warnings.push(format!(
            "{name}: the airfoil lift curve has slope {slope} per rad at zero incidence; \
             the fins produce no restoring lift"
        ));
    }
    slope
}

#[allow(clippy::too_many_arguments)]
fn finish(
    name: &str,
    n: u32,
    body_radius: f64,
    rocket_radius: f64,
    cant_angle_deg: f64,
    angular_position_deg: f64,
    root_chord: f64,
    airfoil: Option<&Airfoil>,
    p: Planform,
    mut warnings: Vec<String>,
) -> Result<(FinSet, Vec<String>), AirframeError> {
    let cant_angle_deg = finite(name, "cant_angle", cant_angle_deg)?;
    if cant_angle_deg.abs() >= 90.0 {
        return Err(AirframeError::OutOfRange {
            component: name.to_owned(),
            quantity: "cant_angle",
            value: cant_angle_deg,
            min: -90.0,
            max: 90.0,
        });
    }
    let cant = cant_angle_deg.to_radians();
    let angular_position = finite(name, "angular_position", angular_position_deg)?.to_radians();
    let tau = (p.span + body_radius) / body_radius;
    // Fins on no body (r_t = 0, τ = ∞): no body interference, `1 + 1/τ = 1` and Barrowman's
    // `K_f → 1`; the coefficients are then referred to the rocket radius.
    let reference_radius = if body_radius > 0.0 {
        body_radius
    } else {
        rocket_radius
    };
    let reference_area = PI * reference_radius * reference_radius;
    let d = 2.0 * reference_radius;
    let k_f = if body_radius > 0.0 {
        roll_forcing_interference(tau)
    } else {
        1.0
    };
    let nf = f64::from(n);
    let cla0 = airfoil_slope(name, airfoil, &mut warnings);
    let aspect_ratio = 2.0 * p.span * p.span / p.fin_area;
    let diederich_factor = 2.0 * PI * aspect_ratio / (cla0 * p.mid_chord_sweep.cos());
    let aero = FinAerodynamics {
        n,
        body_radius,
        reference_radius,
        fin_area: p.fin_area,
        aspect_ratio,
        mid_chord_sweep: p.mid_chord_sweep,
        mean_aerodynamic_span: p.mean_aerodynamic_span,
        tau,
        lift_interference: 1.0 + 1.0 / tau,
        fin_count_factor: fin_count_factor(n),
        airfoil_lift_slope: cla0,
        roll_forcing_interference: k_f,
        roll_damping_interference: p.roll_damping_interference,
        roll_integral: p.roll_integral,
        cant_angle: cant,
        angular_position,
        lift_numerator: 2.0 * PI * aspect_ratio * p.fin_area / reference_area,
        diederich_factor_squared: diederich_factor * diederich_factor,
        diederich_sign: diederich_factor.signum(),
        forcing_factor: k_f * nf * (p.mean_aerodynamic_span + body_radius) / d,
        damping_factor: 2.0 * p.roll_damping_interference * nf * cant.cos() * p.roll_integral
            / (reference_area * d * d),
    };
    for mach in [0.0, 0.5, 0.9, 1.2, 2.0] {
        let v = aero.cn_alpha(mach);
        if !v.is_finite() {
            return Err(AirframeError::Geometry {
                component: name.to_owned(),
                reason: format!("the normal-force slope at Mach {mach} is {v}"),
            });
        }
    }
    let set = FinSet {
        aero,
        cp_local: p.cp_local,
        root_chord,
        span: p.span,
        outline: p.outline,
    };
    Ok((set, warnings))
}

/// Builds a trapezoidal fin set (docs/physics.md §7.5, §7.6).
pub(crate) fn trapezoidal(
    name: &str,
    spec: &TrapezoidalFinsSpec,
    rocket_radius: f64,
) -> Result<(FinSet, Vec<String>), AirframeError> {
    check_count(name, spec.n)?;
    let cr = positive(name, "root_chord", spec.root_chord)?;
    let ct = non_negative(name, "tip_chord", spec.tip_chord)?;
    let s = finite(name, "span", spec.span)?;
    if s <= 0.0 {
        return Err(AirframeError::Geometry {
            component: name.to_owned(),
            reason: format!("span {s} m: a fin needs a positive span"),
        });
    }
    // 0: fins on no body (a pod's phantom tube).
    let r = non_negative(name, "radius", spec.radius.unwrap_or(rocket_radius))?;
    let sweep = match spec.sweep {
        Sweep::Default => cr - ct,
        Sweep::Length(l) => finite(name, "sweep_length", l)?,
        Sweep::AngleDeg(a) => {
            let a = finite(name, "sweep_angle", a)?;
            if a.abs() >= 90.0 {
                return Err(AirframeError::OutOfRange {
                    component: name.to_owned(),
                    quantity: "sweep_angle",
                    value: a,
                    min: -90.0,
                    max: 90.0,
                });
            }
            (a * PI / 180.0).tan() * s
        }
    };
    let yr = cr + ct;
    let lambda = ct / cr;
    let tau = (s + r) / r;
    // No body (τ = ∞): no damping interference.
    let k_d = if r > 0.0 {
        1.0 + ((tau - lambda) / tau - ((1.0 - lambda) / (tau - 1.0)) * tau.ln())
            / ((tau + 1.0) * (tau - lambda) / 2.0
                - (1.0 - lambda) * (tau.powi(3) - 1.0) / (3.0 * (tau - 1.0)))
    } else {
        1.0
    };
    let g = ((cr + 3.0 * ct) * s.powi(3)
        + 4.0 * (cr + 2.0 * ct) * r * s * s
        + 6.0 * (cr + ct) * s * r * r)
        / 12.0;
    let outline = vec![[0.0, 0.0], [sweep, s], [sweep + ct, s], [cr, 0.0]];
    let p = Planform {
        fin_area: yr * s / 2.0,
        mid_chord_sweep: ((sweep + 0.5 * ct - 0.5 * cr) / s).atan(),
        mean_aerodynamic_span: (s / 3.0) * (cr + 2.0 * ct) / yr,
        roll_integral: g,
        roll_damping_interference: k_d,
        cp_local: (sweep / 3.0) * ((cr + 2.0 * ct) / yr) + (1.0 / 6.0) * (cr + ct - cr * ct / yr),
        span: s,
        outline,
    };
    finish(
        name,
        spec.n,
        r,
        rocket_radius,
        spec.cant_angle_deg,
        spec.angular_position_deg,
        cr,
        spec.airfoil.as_ref(),
        p,
        Vec::new(),
    )
}

/// Builds an elliptical fin set (RocketPy "Elliptical Fins Equations", docs/physics.md §7.5–7.6).
pub(crate) fn elliptical(
    name: &str,
    spec: &EllipticalFinsSpec,
    rocket_radius: f64,
) -> Result<(FinSet, Vec<String>), AirframeError> {
    check_count(name, spec.n)?;
    let cr = positive(name, "root_chord", spec.root_chord)?;
    let s = positive(name, "span", spec.span)?;
    // 0: fins on no body (a pod's phantom tube).
    let r = non_negative(name, "radius", spec.radius.unwrap_or(rocket_radius))?;
    let k_d = if r <= 0.0 {
        // No body: no damping interference.
        1.0
    } else if s > r {
        let q = (s * s - r * r).sqrt();
        1.0 + r
            * r
            * (2.0 * r * r * q * ((2.0 * s * q + 2.0 * s * s) / r).ln()
                - 2.0 * r * r * q * (2.0 * s).ln()
                + 2.0 * s.powi(3)
                - PI * r * s * s
                - 2.0 * r * r * s
                + PI * r.powi(3))
            / (2.0 * s * s * (s / 3.0 + PI * r / 4.0) * (s * s - r * r))
    } else if s < r {
        let q = (r * r - s * s).sqrt();
        1.0 - r
            * r
            * (2.0 * s.powi(3) - PI * s * s * r - 2.0 * s * r * r
                + PI * r.powi(3)
                + 2.0 * r * r * q * (s / q).atan()
                - PI * r * r * q)
            / (2.0 * s * (r * r - s * s) * (s * s / 3.0 + PI * s * r / 4.0))
    } else {
        (28.0 - 3.0 * PI) / (4.0 + 3.0 * PI)
    };
    let outline = (0..36)
        .map(|i| {
            let a = f64::from(i * 5).to_radians();
            [cr / 2.0 + cr / 2.0 * a.cos(), s * a.sin()]
        })
        .rev()
        .collect();
    let p = Planform {
        fin_area: (PI * cr / 2.0 * s) / 2.0,
        mid_chord_sweep: 0.0,
        mean_aerodynamic_span: s / (3.0 * PI) * (9.0 * PI * PI - 64.0).sqrt(),
        roll_integral: cr * s * (3.0 * PI * s * s + 32.0 * r * s + 12.0 * PI * r * r) / 48.0,
        roll_damping_interference: k_d,
        cp_local: 0.288 * cr,
        span: s,
        outline,
    };
    finish(
        name,
        spec.n,
        r,
        rocket_radius,
        spec.cant_angle_deg,
        spec.angular_position_deg,
        cr,
        spec.airfoil.as_ref(),
        p,
        Vec::new(),
    )
}

/// Number of span stations of the free-form discretisation (OpenRocket, RocketPy).
const STATIONS: usize = 40;

/// Builds a free-form fin set (RocketPy `FreeFormFins.evaluate_geometrical_parameters`).
pub(crate) fn free_form(
    name: &str,
    spec: &FreeFormFinsSpec,
    rocket_radius: f64,
) -> Result<(FinSet, Vec<String>), AirframeError> {
    check_count(name, spec.n)?;
    let pts = &spec.shape_points;
    if pts.len() < 3 {
        return Err(AirframeError::Geometry {
            component: name.to_owned(),
            reason: format!(
                "a free-form fin needs at least 3 shape points, got {}",
                pts.len()
            ),
        });
    }
    for [x, y] in pts {
        finite(name, "shape_points x", *x)?;
        finite(name, "shape_points y", *y)?;
    }
    // 0: fins on no body (a pod's phantom tube).
    let r = non_negative(name, "radius", spec.radius.unwrap_or(rocket_radius))?;
    let mut warnings = Vec::new();
    let mut down = false;
    for w in pts.windows(2) {
        if w[1][1] > w[0][1] && down {
            warnings.push(format!(
                "{name}: jagged fin shape; the CP and pitch moment may be slightly inaccurate"
            ));
            break;
        }
        if w[1][1] < w[0][1] {
            down = true;
        }
    }
    // RocketPy's root chord is the distance between the first and the last point: 0 for a
    // closed outline (Hedy's fins), which it accepts; it only labels the fin. The outline's
    // chordwise extent is what must not vanish.
    let (first, last) = (pts[0], pts[pts.len() - 1]);
    let root_chord = (first[0] - last[0]).abs();
    let extent = |axis: usize| {
        let (lo, hi) = pts
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p[axis]), b.max(p[axis]))
            });
        hi - lo
    };
    let (span, chord) = (extent(1), extent(0));
    if span <= 0.0 || chord <= 0.0 {
        return Err(AirframeError::Geometry {
            component: name.to_owned(),
            reason: format!("shape points give span {span} m and chordwise extent {chord} m"),
        });
    }
    let area = pts
        .windows(2)
        .map(|w| (w[0][1] + w[1][1]) * (w[0][0] - w[1][0]))
        .sum::<f64>()
        .abs()
        / 2.0;
    // A sliver: less than 1e-4 of its bounding box (1 mm² for a 10 cm × 10 cm fin).
    if area < 1e-4 * span * chord {
        return Err(AirframeError::Geometry {
            component: name.to_owned(),
            reason: format!("fin area {area} m² is too small"),
        });
    }
    let (lead, trail, length) = stations(pts, span);
    let last_station = (STATIONS - 1) as f64;
    let dy = span / last_station;
    let (mut total, mut mac_len, mut mac_span, mut mac_lead) = (0.0, 0.0, 0.0, 0.0);
    let (mut g, mut kd_num, mut kd_den, mut cos_sum) = (0.0, 0.0, 0.0, 0.0);
    for i in 0..STATIONS {
        let chord = trail[i] - lead[i];
        let y = i as f64 * dy;
        mac_len += chord * chord;
        mac_span += y * chord;
        mac_lead += lead[i] * chord;
        total += chord;
        g += length[i] * (r + y).powi(2);
        kd_num += r.powi(3) * chord / (r + y).powi(2);
        kd_den += (r + y) * chord;
        if i > 0 {
            let dx = (trail[i] + lead[i]) / 2.0 - (trail[i - 1] + lead[i - 1]) / 2.0;
            cos_sum += dy / dx.hypot(dy);
        }
    }
    total *= dy;
    mac_len = mac_len * dy / total;
    mac_span = mac_span * dy / total;
    mac_lead = mac_lead * dy / total;
    let cos_gamma = (cos_sum / last_station).clamp(-1.0, 1.0);
    let p = Planform {
        fin_area: area,
        mid_chord_sweep: cos_gamma.acos(),
        mean_aerodynamic_span: mac_span,
        roll_integral: g * dy,
        // No body (r = 0, where the root station's term is 0/0): no damping interference.
        roll_damping_interference: if r > 0.0 {
            1.0 + (kd_num * dy) / (kd_den * dy)
        } else {
            1.0
        },
        cp_local: mac_lead + 0.25 * mac_len,
        span,
        outline: pts.clone(),
    };
    finish(
        name,
        spec.n,
        r,
        rocket_radius,
        spec.cant_angle_deg,
        spec.angular_position_deg,
        root_chord,
        spec.airfoil.as_ref(),
        p,
        warnings,
    )
}

/// The free-form outline `pts` cut at [`STATIONS`] span stations (`y = i · span / (STATIONS −
/// 1)`), as RocketPy 1.13 does: at each station the leading and trailing edges' chordwise
/// positions and the chord length inside the outline, `(lead, trail, length)`; a station the
/// outline never reaches is 0, a length kept within its chord.
fn stations(pts: &[[f64; 2]], span: f64) -> ([f64; STATIONS], [f64; STATIONS], [f64; STATIONS]) {
    let mut lead = [f64::INFINITY; STATIONS];
    let mut trail = [f64::NEG_INFINITY; STATIONS];
    let mut length = [0.0f64; STATIONS];
    let last_station = (STATIONS - 1) as f64;
    let station = |y: f64| -> usize {
        // Python's int() truncates toward zero; the result is then clipped to the stations.
        let v = (y / span * last_station).trunc();
        if v <= 0.0 {
            0
        } else {
            (v as usize).min(STATIONS - 1)
        }
    };
    for w in pts.windows(2) {
        let ([x1, y1], [x2, y2]) = (w[0], w[1]);
        let (mut a, mut b) = (station(y1), station(y2));
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        for (i, ((ld, tr), len)) in lead
            .iter_mut()
            .zip(trail.iter_mut())
            .zip(length.iter_mut())
            .enumerate()
            .take(b + 1)
            .skip(a)
        {
            let y = i as f64 * span / last_station;
            #[allow(clippy::float_cmp)] // RocketPy's exact test for a horizontal edge.
            let x = if y1 != y2 {
                ((y - y2) / (y1 - y2) * x1 + (y1 - y) / (y1 - y2) * x2)
                    .clamp(x1.min(x2), x1.max(x2))
            } else {
                x1
            };
            *ld = ld.min(x);
            *tr = tr.max(x);
            if y1 < y2 {
                *len -= x;
            } else {
                *len += x;
            }
        }
    }
    for i in 0..STATIONS {
        if !lead[i].is_finite() || !trail[i].is_finite() {
            lead[i] = 0.0;
            trail[i] = 0.0;
        }
        if length[i] < 0.0 || length[i].is_nan() {
            length[i] = 0.0;
        }
        if length[i] > trail[i] - lead[i] {
            length[i] = trail[i] - lead[i];
        }
    }
    (lead, trail, length)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    /// docs/physics.md §7.5: the Calisto fin set WITHOUT airfoil, 0.5° cant.
    fn calisto() -> FinSet {
        let spec = TrapezoidalFinsSpec {
            n: 4,
            root_chord: 0.12,
            tip_chord: 0.06,
            span: 0.11,
            sweep: Sweep::Default,
            cant_angle_deg: 0.5,
            angular_position_deg: 0.0,
            radius: None,
            airfoil: None,
        };
        trapezoidal("fins", &spec, 0.0635).expect("valid fins").0
    }

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    #[test]
    fn fins_on_no_body_have_no_interference_and_the_rocket_reference() {
        // OpenRocket's phantom pod tube (r_t = 0): `1 + r_t/(s + r_t) = 1` and the slope is
        // on the rocket's area, so the set's force `A_ref CNα` equals that of a lone fin pair
        // `N/2 · 2π AR A_f / (2 + √(…))` with no body factor, and K_f = K_d = 1.
        let rocket = 0.0168;
        let mut spec = TrapezoidalFinsSpec {
            n: 2,
            root_chord: 0.028,
            tip_chord: 0.0127,
            span: 0.019,
            sweep: Sweep::Length(0.0127),
            cant_angle_deg: 1.0,
            angular_position_deg: 90.0,
            radius: Some(0.0),
            airfoil: None,
        };
        let bare = trapezoidal("stab", &spec, rocket)
            .expect("fins on no body")
            .0
            .aero;
        assert!(bare.reference_radius.to_bits() == rocket.to_bits());
        assert!(bare.lift_interference.to_bits() == 1.0f64.to_bits());
        assert!(bare.roll_forcing_interference.to_bits() == 1.0f64.to_bits());
        assert!(bare.roll_damping_interference.to_bits() == 1.0f64.to_bits());
        for mach in [0.0, 0.5, 1.2] {
            assert!(bare.cn_alpha(mach).is_finite() && bare.cn_alpha(mach) > 0.0);
            assert!(bare.roll_forcing_derivative(mach).is_finite());
            assert!(bare.roll_damping_derivative(mach).is_finite());
        }
        // On a thin body the slope per unit fin approaches it from above (interference > 1).
        spec.radius = Some(1e-6);
        let thin = trapezoidal("stab", &spec, rocket).expect("fins").0.aero;
        let force = |a: &FinAerodynamics| a.cn_alpha(0.3) * a.reference_radius.powi(2);
        assert!(
            close(force(&thin), force(&bare), 1e-3),
            "{} {}",
            force(&thin),
            force(&bare)
        );
        for (name, fins) in [
            (
                "elliptical",
                elliptical(
                    "e",
                    &EllipticalFinsSpec {
                        n: 2,
                        root_chord: 0.03,
                        span: 0.02,
                        cant_angle_deg: 0.0,
                        angular_position_deg: 0.0,
                        radius: Some(0.0),
                        airfoil: None,
                    },
                    rocket,
                ),
            ),
            (
                "free-form",
                free_form(
                    "f",
                    &FreeFormFinsSpec {
                        n: 1,
                        shape_points: vec![[0.0, 0.0], [0.01, 0.02], [0.03, 0.0]],
                        cant_angle_deg: 0.0,
                        angular_position_deg: 0.0,
                        radius: Some(0.0),
                        airfoil: None,
                    },
                    rocket,
                ),
            ),
        ] {
            let a = fins.expect(name).0.aero;
            assert!(
                a.roll_damping_interference.to_bits() == 1.0f64.to_bits(),
                "{name}"
            );
            assert!(a.cn_alpha(0.3).is_finite(), "{name}");
        }
    }

    #[test]
    fn single_fin_slope_is_diederich_s_form_as_rocketpy_writes_it() {
        // docs/physics.md §7.5 (RocketPy's form): cl_α2D = cl_α0/β, F_D = 2π AR/(cl_α2D cos Γ_c),
        // CNα₁ = cl_α2D·F_D·(A_f/A)·cos Γ_c / (2 + F_D √(1 + (2/F_D)²)); the evaluated form
        // (one root, one division) must agree to rounding at every Mach regime of β.
        let a = calisto().aero;
        let area_ratio = a.fin_area / (PI * a.body_radius * a.body_radius);
        let cos_gamma = a.mid_chord_sweep.cos();
        for mach in [0.0f64, 0.3, 0.79, 0.8, 0.95, 1.1, 1.5, 3.0] {
            let beta: f64 = if mach < 0.8 {
                (1.0 - mach * mach).sqrt()
            } else if mach < 1.1 {
                (1.0f64 - 0.8 * 0.8).sqrt()
            } else {
                (mach * mach - 1.0).sqrt()
            };
            let cla = a.airfoil_lift_slope / beta;
            let fd = 2.0 * PI * a.aspect_ratio / (cla * cos_gamma);
            let rocketpy =
                cla * fd * area_ratio * cos_gamma / (2.0 + fd * (1.0 + (2.0 / fd).powi(2)).sqrt());
            // Rounding: a few operations of relative error 2⁻⁵³ each.
            assert!(
                close(a.single_fin_cn_alpha(mach), rocketpy, 1e-14),
                "Mach {mach}"
            );
            let [cn, forcing, damping] = a.coefficients(mach);
            assert!(cn.to_bits() == a.cn_alpha(mach).to_bits());
            assert!(
                forcing.to_bits() == (a.roll_forcing_derivative(mach) * a.cant_angle).to_bits()
            );
            assert!(damping.to_bits() == a.roll_damping_derivative(mach).to_bits());
        }
    }

    #[test]
    fn calisto_geometry_matches_physics_md() {
        // docs/physics.md §7.5 quotes 6-7 significant digits; tolerance is half a unit of the last.
        let f = calisto();
        let a = &f.aero;
        assert!(close(a.fin_area, 9.9e-3, 1e-12));
        assert!(close(a.aspect_ratio, 2.444444, 2e-7));
        assert!(close(a.mid_chord_sweep, 0.266252, 2e-6));
        assert!(close(a.mean_aerodynamic_span, 0.048889, 1e-5));
        assert!(close(a.tau, 2.732283, 2e-7));
        assert!(close(a.lift_interference, 1.365994, 4e-7));
    }

    #[test]
    fn calisto_cn_alpha_vs_mach_matches_physics_md() {
        let f = calisto();
        for (mach, value) in [
            (0.0, 6.27255),
            (0.5, 6.59948),
            (0.8, 7.26757),
            (1.0, 7.26757),
            (1.1, 7.60391),
            (1.5, 5.99757),
            (2.0, 4.80635),
        ] {
            let v = f.aero.cn_alpha(mach);
            assert!(close(v, value, 1e-6), "Mach {mach}: {v} vs {value}");
        }
    }

    #[test]
    fn calisto_roll_coefficients_match_physics_md() {
        let a = calisto().aero;
        assert!(close(a.roll_forcing_interference, 0.934720, 1e-6));
        assert!(close(a.roll_damping_interference, 1.229132, 1e-6));
        assert!(close(a.roll_integral, 1.346623e-4, 1e-6));
        assert!(close(a.roll_forcing_derivative(0.0), 7.59673, 1e-6));
        assert!(close(a.roll_damping_derivative(0.0), 14.87916, 1e-6));
    }

    #[test]
    fn trapezoidal_cp_matches_formula() {
        // x_cp for C_r 0.12, C_t 0.06, sweep 0.06: 0.06/3·(0.24/0.18) + (0.18 − 0.04)/6.
        let f = calisto();
        let expected = 0.02 * (0.24 / 0.18) + (0.18 - 0.0072 / 0.18) / 6.0;
        assert!((f.cp_local - expected).abs() < 1e-15);
    }

    #[test]
    fn fin_count_table() {
        assert!((fin_count_factor(3) - 1.5).abs() < 1e-15);
        assert!((fin_count_factor(6) - 2.74).abs() < 1e-15);
        assert!((fin_count_factor(10) - 5.0).abs() < 1e-15);
    }

    #[test]
    fn roll_factor_is_one_for_three_or_more_fins_and_sin_squared_below() {
        let mut a = calisto().aero;
        for n in [3, 4, 5, 8] {
            a.n = n;
            a.angular_position = 0.3;
            for theta in [0.0, 0.4, 1.0, 2.5] {
                assert!(a.roll_factor(theta).to_bits() == 1.0f64.to_bits());
            }
        }
        // A pair at 90°: flow along 0° is normal to both fins (twice the average), along
        // 90° in their plane (none); a single fin likewise. Either averages to 1 over θ.
        for n in [1, 2] {
            a.n = n;
            a.angular_position = 90f64.to_radians();
            assert!(close(a.roll_factor(0.0), 2.0, 1e-15));
            assert!(a.roll_factor(FRAC_PI_2).abs() < 1e-15);
            assert!(close(a.roll_factor(PI / 6.0), 1.5, 1e-14));
            let k = 360;
            let mean = (0..k)
                .map(|i| a.roll_factor(2.0 * PI * f64::from(i) / f64::from(k)))
                .sum::<f64>()
                / f64::from(k);
            assert!(close(mean, 1.0, 1e-12), "{mean}");
        }
    }

    #[test]
    fn free_form_of_a_trapezoid_approaches_trapezoidal() {
        // The same Calisto planform as a polygon; the 40-station discretisation reproduces
        // area and Y_ma closely (OpenRocket's method is a discretisation, not exact).
        let spec = FreeFormFinsSpec {
            n: 4,
            shape_points: vec![[0.0, 0.0], [0.06, 0.11], [0.12, 0.11], [0.12, 0.0]],
            cant_angle_deg: 0.0,
            angular_position_deg: 0.0,
            radius: Some(0.0635),
            airfoil: None,
        };
        let (f, w) = free_form("fins", &spec, 0.0635).expect("valid fins");
        assert!(w.is_empty());
        let t = calisto();
        assert!(close(f.aero.fin_area, t.aero.fin_area, 1e-12));
        assert!(close(f.aero.cn_alpha(0.3), t.aero.cn_alpha(0.3), 1e-2));
        assert!(close(
            f.aero.mean_aerodynamic_span,
            t.aero.mean_aerodynamic_span,
            3e-2
        ));
    }

    #[test]
    fn elliptical_damping_factor_is_continuous_at_span_equal_radius() {
        let k = |s: f64| {
            let spec = EllipticalFinsSpec {
                n: 3,
                root_chord: 0.1,
                span: s,
                cant_angle_deg: 0.0,
                angular_position_deg: 0.0,
                radius: Some(0.05),
                airfoil: None,
            };
            elliptical("e", &spec, 0.05)
                .expect("valid fins")
                .0
                .aero
                .roll_damping_interference
        };
        let mid = k(0.05);
        assert!((k(0.05 * (1.0 + 1e-5)) - mid).abs() < 1e-3);
        assert!((k(0.05 * (1.0 - 1e-5)) - mid).abs() < 1e-3);
    }

    #[test]
    fn impossible_fins_are_errors() {
        let base = TrapezoidalFinsSpec {
            n: 4,
            root_chord: 0.12,
            tip_chord: 0.06,
            span: 0.11,
            sweep: Sweep::Default,
            cant_angle_deg: 0.0,
            angular_position_deg: 0.0,
            radius: None,
            airfoil: None,
        };
        let mut s = base.clone();
        s.span = 0.0;
        assert!(
            trapezoidal("f", &s, 0.0635).is_err(),
            "tip chord with zero span"
        );
        let mut s = base.clone();
        s.root_chord = -0.1;
        assert!(trapezoidal("f", &s, 0.0635).is_err());
        let mut s = base.clone();
        s.tip_chord = -0.01;
        assert!(trapezoidal("f", &s, 0.0635).is_err());
        let mut s = base.clone();
        s.n = 0;
        assert!(trapezoidal("f", &s, 0.0635).is_err());
        let mut s = base.clone();
        s.sweep = Sweep::AngleDeg(90.0);
        assert!(trapezoidal("f", &s, 0.0635).is_err());
        let mut s = base;
        s.span = f64::NAN;
        assert!(trapezoidal("f", &s, 0.0635).is_err());
        let ff = FreeFormFinsSpec {
            n: 3,
            shape_points: vec![[0.0, 0.0], [0.1, 0.0], [0.2, 0.0]],
            cant_angle_deg: 0.0,
            angular_position_deg: 0.0,
            radius: None,
            airfoil: None,
        };
        assert!(free_form("f", &ff, 0.05).is_err());
    }
}
