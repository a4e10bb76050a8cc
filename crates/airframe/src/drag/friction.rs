//! Skin-friction drag (Niskanen 2009, §3.4.1, after Hoerner 1965 ch. 2 and Schlichting;
//! docs/physics.md §20.2).
//!
//! The flat-plate coefficient of a fully turbulent boundary layer on the whole rocket length
//! L (Re = V L / ν),
//!
//! ```text
//! Cf = 1 / (1.50 ln Re − 5.6)²      (Re ≥ 10⁴;  Cf = 0.0148 below)
//! ```
//!
//! is corrected for compressibility by 1 − 0.1 M² (subsonic, M < 0.9) and
//! (1 + 0.15 M²)^−0.58 (supersonic, M > 1.1), blended linearly in between; per component it is
//! replaced by the roughness-limited value
//!
//! ```text
//! Cf,r = 0.032 (k / L)^0.2 · { 1 − 0.1 M²  (M < 0.9);  1 / (1 + 0.18 M²)  (M > 1.1) }
//! ```
//!
//! when that is larger (k the equivalent sand roughness of the surface finish). The body's
//! friction drag is Cf S_wet / A_ref times the fineness correction 1 + 1/(2 f_B), f_B the body
//! length over its largest radius; a fin set's is Cf (1 + 2 t / c̄) 2 S_fin n / A_ref with t the
//! fin thickness and c̄ its mean aerodynamic chord.

/// Linear blend across the transonic band 0.9 ≤ M ≤ 1.1 of a subsonic and a supersonic law.
fn transonic_blend(mach: f64, sub: impl Fn(f64) -> f64, sup: impl Fn(f64) -> f64) -> f64 {
    if mach < 0.9 {
        sub(mach)
    } else if mach > 1.1 {
        sup(mach)
    } else {
        sup(mach) * (mach - 0.9) / 0.2 + sub(mach) * (1.1 - mach) / 0.2
    }
}

/// Turbulent flat-plate skin-friction coefficient at Mach `mach` and Reynolds number
/// `reynolds` (based on the rocket length), with the compressibility correction.
#[must_use]
pub fn turbulent_coefficient(mach: f64, reynolds: f64) -> f64 {
    let cf = if reynolds < 1.0e4 {
        0.0148
    } else {
        1.0 / (1.50 * reynolds.ln() - 5.6).powi(2)
    };
    cf * transonic_blend(
        mach,
        |m| 1.0 - 0.1 * m * m,
        |m| 1.0 / (1.0 + 0.15 * m * m).powf(0.58),
    )
}

/// Roughness-limited skin-friction coefficient of a surface of sand roughness `roughness` on
/// a rocket of length `length` (the same unit), at Mach `mach`.
#[must_use]
pub fn roughness_limited_coefficient(mach: f64, roughness: f64, length: f64) -> f64 {
    // Between Mach 0.9 and 1.1 the correction blends its values at the band's ends.
    let sub = |m: f64| 1.0 - 0.1 * m * m;
    let sup = |m: f64| 1.0 / (1.0 + 0.18 * m * m);
    let correction = if mach < 0.9 {
        sub(mach)
    } else if mach > 1.1 {
        sup(mach)
    } else {
        sup(1.1) * (mach - 0.9) / 0.2 + sub(0.9) * (1.1 - mach) / 0.2
    };
    0.032 * (roughness / length).powf(0.2) * correction
}

/// The coefficient a component uses: the larger of the turbulent and its roughness-limited
/// value.
#[must_use]
pub fn component_coefficient(mach: f64, reynolds: f64, roughness: f64, length: f64) -> f64 {
    turbulent_coefficient(mach, reynolds)
        .max(roughness_limited_coefficient(mach, roughness, length))
}

/// The body's friction correction 1 + 1/(2 f_B) for its fineness f_B = length / max radius.
#[must_use]
pub fn body_fineness_correction(length: f64, max_radius: f64) -> f64 {
    1.0 + max_radius / (2.0 * length)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turbulent_law_and_its_floor() {
        let cf = turbulent_coefficient(0.0, 1.0e6);
        assert!((cf - 1.0 / (1.5 * 1.0e6f64.ln() - 5.6).powi(2)).abs() < 1e-15);
        assert!((turbulent_coefficient(0.0, 5.0e3) - 0.0148).abs() < 1e-15);
    }

    #[test]
    fn corrections_are_continuous_across_the_transonic_band() {
        for f in [
            |m: f64| turbulent_coefficient(m, 1e7),
            |m: f64| roughness_limited_coefficient(m, 60e-6, 1.0),
        ] {
            for edge in [0.9, 1.1] {
                let (a, b) = (f(edge - 1e-9), f(edge + 1e-9));
                assert!((a - b).abs() < 1e-9, "jump at {edge}: {a} {b}");
            }
        }
    }

    #[test]
    fn rough_surfaces_dominate_at_high_reynolds() {
        let smooth = component_coefficient(0.3, 1e7, 0.0, 1.0);
        let rough = component_coefficient(0.3, 1e7, 500e-6, 1.0);
        assert!(rough > smooth);
        assert!((smooth - turbulent_coefficient(0.3, 1e7)).abs() < 1e-15);
    }
}
