//! A range-safety report of one flight (`karman safety MISSION`): the figures a range-safety
//! officer asks for, each with pass / warn / fail against a threshold (docs/montecarlo.md,
//! "Range safety"). Everything is read from the nominal flight's summary and stored points:
//!
//! - rail-exit speed, and the stability margin at rail exit (the summary's);
//! - thrust-to-weight at rail exit, `T / (m g₀)` with the net thrust and mass of the stored
//!   points interpolated linearly at the rail-exit time;
//! - the least stability margin over the powered flight (rail exit to burn-out);
//! - the largest Mach number and dynamic pressure;
//! - the fin flutter speed of each trapezoidal fin set and its margin over the flight, NACA
//!   TN 4197 (Martin 1958) as restated for model rockets (Cipolla, "NACA TN 4197 flutter
//!   velocity analysis"):
//!   `V_f = a · sqrt( G / ( (24 ε γ / π) · AR³ / ((t/c)³ (AR + 2)) · (λ + 1)/2 · p ) )`,
//!   with `ε = 0.25`, `γ = 1.4`, `AR = b² / S` (`S = (c_r + c_t) b / 2`), `λ = c_t / c_r`,
//!   `t/c` the thickness over the root chord, `G` the fin material's shear modulus, `p` and
//!   `a` the local pressure and speed of sound (`24 ε γ p / π` is NACA's `DN · p / p₀`, its
//!   `DN = 24 ε γ p₀ / π`); along the flight `a = V / M` and `p = 2 q / (γ M²)` from the
//!   stored points' free-stream speed, Mach number and dynamic pressure (`q = ½ γ p M²`), and
//!   the margin is the least `V_f / V` over the points before apogee;
//! - the landing kinetic energy `½ m v²` with the mass of the last stored point and the
//!   impact speed, the descent rate at impact, and the drift (the impact's distance from the
//!   pad).
//!
//! Defaults (`SafetyRules::default`), each a common rule of thumb of student competitions:
//! rail-exit speed ≥ 30.48 m/s (100 ft/s) and stability margin at rail exit ≥ 1.5 calibres
//! (Spaceport America Cup, IREC design, test and evaluation guide), thrust-to-weight ≥ 5,
//! flutter margin ≥ 1.2 (the flutter speed 20 % above the flight speed), landing energy ≤
//! 101.7 J (75 ft·lbf, NASA Student Launch), descent rate at impact ≤ 9.14 m/s (30 ft/s),
//! drift ≤ 762 m (2 500 ft, NASA Student Launch). A figure within 10 % of its threshold on the
//! passing side is a warning.

use crate::assemble::flight::simulate_with_seed;
use crate::schema::SurfaceSpec;
use crate::{Mission, MissionError};
use karman_dynamics::Sample;
use karman_math::PhysicalConstants;
use serde::Serialize;

/// NACA TN 4197's location of the section's centre of mass aft of the quarter chord, as a
/// fraction of the chord (`ε`).
const EPSILON: f64 = 0.25;
/// The band on the passing side of a threshold, as a fraction of it, that is a warning.
const WARN_BAND: f64 = 0.10;

/// The thresholds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SafetyRules {
    /// Least rail-exit speed, m/s.
    pub min_rail_exit_speed_mps: f64,
    /// Least stability margin at rail exit and over the powered flight, calibres.
    pub min_stability_margin_cal: f64,
    /// Least thrust-to-weight ratio at rail exit.
    pub min_thrust_to_weight: f64,
    /// Least flutter margin `V_f / V`.
    pub min_flutter_margin: f64,
    /// Largest landing kinetic energy, J.
    pub max_landing_energy_j: f64,
    /// Largest descent rate at impact, m/s.
    pub max_descent_rate_mps: f64,
    /// Largest drift from the pad, m.
    pub max_drift_m: f64,
}

impl Default for SafetyRules {
    fn default() -> Self {
        SafetyRules {
            min_rail_exit_speed_mps: 30.48,
            min_stability_margin_cal: 1.5,
            min_thrust_to_weight: 5.0,
            min_flutter_margin: 1.2,
            max_landing_energy_j: 101.7,
            max_descent_rate_mps: 9.144,
            max_drift_m: 762.0,
        }
    }
}

/// The fins' material and thickness, for the flutter speed (the mission format has neither).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FinMaterial {
    /// Shear modulus `G`, Pa.
    pub shear_modulus_pa: f64,
    /// Thickness, m.
    pub thickness_m: f64,
}

/// Pass, warn or fail.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// Within the threshold, beyond the warning band.
    Pass,
    /// Within the threshold, inside the warning band.
    Warn,
    /// Beyond the threshold.
    Fail,
    /// Not assessed (the quantity did not occur, or an input is missing).
    None,
}

/// One figure of the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Check {
    /// Its name (`rail_exit_speed_mps`).
    pub name: String,
    /// Its value (none when it did not occur).
    pub value: Option<f64>,
    /// The threshold it is held to, if any.
    pub threshold: Option<f64>,
    /// `min` (the value must be at least the threshold) or `max`; none for a figure that is
    /// only reported.
    pub kind: Option<&'static str>,
    /// The verdict.
    pub verdict: Verdict,
    /// What it is, or why it is not assessed.
    pub note: String,
}

/// The report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SafetyReport {
    /// The thresholds used.
    pub rules: SafetyRules,
    /// The figures.
    pub checks: Vec<Check>,
}

/// The verdict of `value` against a lower (`at_least`) or upper bound.
fn verdict(value: f64, threshold: f64, at_least: bool) -> Verdict {
    let band = WARN_BAND * threshold.abs();
    match at_least {
        true if value < threshold => Verdict::Fail,
        true if value < threshold + band => Verdict::Warn,
        false if value > threshold => Verdict::Fail,
        false if value > threshold - band => Verdict::Warn,
        _ => Verdict::Pass,
    }
}

fn check(name: &str, value: Option<f64>, threshold: f64, at_least: bool, note: &str) -> Check {
    Check {
        name: name.to_owned(),
        value,
        threshold: Some(threshold),
        kind: Some(if at_least { "min" } else { "max" }),
        verdict: value.map_or(Verdict::None, |v| verdict(v, threshold, at_least)),
        note: note.to_owned(),
    }
}

fn reported(name: &str, value: Option<f64>, note: &str) -> Check {
    Check {
        name: name.to_owned(),
        value,
        threshold: None,
        kind: None,
        verdict: Verdict::None,
        note: note.to_owned(),
    }
}

/// The flutter speed of a trapezoidal fin (NACA TN 4197, the module's formula) at pressure
/// `pressure_pa` and speed of sound `sound_mps`: root and tip chords, span (semi-span from
/// the body) and thickness in metres, the shear modulus in pascals.
#[must_use]
pub fn flutter_speed(
    root_chord: f64,
    tip_chord: f64,
    span: f64,
    thickness: f64,
    shear_modulus: f64,
    pressure_pa: f64,
    sound_mps: f64,
) -> f64 {
    let area = 0.5 * (root_chord + tip_chord) * span;
    let aspect = span * span / area;
    let taper = tip_chord / root_chord;
    let t_over_c = thickness / root_chord;
    let denominator = (24.0 * EPSILON * PhysicalConstants::SI.heat_capacity_ratio
        / std::f64::consts::PI)
        * aspect.powi(3)
        / (t_over_c.powi(3) * (aspect + 2.0))
        * 0.5
        * (taper + 1.0)
        * pressure_pa;
    sound_mps * (shear_modulus / denominator).sqrt()
}

/// The value of `series` at time `t`, linear between the stored points around it.
fn at_time(times: &[f64], series: &[f64], t: f64) -> Option<f64> {
    let k = times.partition_point(|&s| s < t);
    match (k.checked_sub(1), times.get(k)) {
        (Some(i), Some(&t1)) => {
            let t0 = times[i];
            let w = if t1 > t0 { (t - t0) / (t1 - t0) } else { 0.0 };
            Some(series[i] + w * (series[k] - series[i]))
        }
        (None, Some(_)) => series.first().copied(),
        (Some(_), None) => series.last().copied(),
        (None, None) => None,
    }
}

/// The flutter margin of each trapezoidal fin set: the least flutter speed over airspeed on
/// the points before apogee (NACA TN 4197), not assessed without the fins' material.
fn flutter_checks(
    mission: &Mission,
    samples: &[Sample],
    apogee: Option<f64>,
    fins: Option<FinMaterial>,
    rules: &SafetyRules,
) -> Vec<Check> {
    let mut checks = Vec::new();
    for (name, surface) in &mission.spec.rocket.surfaces {
        let SurfaceSpec::TrapezoidalFins(fin) = surface else {
            continue;
        };
        let key = format!("flutter_margin.{name}");
        let Some(material) = fins else {
            checks.push(Check {
                verdict: Verdict::None,
                note: "not assessed: give the fins' shear modulus and thickness \
                       (--shear-modulus, --fin-thickness)"
                    .to_owned(),
                ..check(&key, None, rules.min_flutter_margin, true, "")
            });
            continue;
        };
        // The least V_f / V over the points before apogee, and where.
        let mut least: Option<(f64, f64, f64)> = None;
        for s in samples.iter().filter(|s| {
            apogee.is_none_or(|t| s.t <= t) && s.mach > 1e-3 && s.free_stream_speed > 0.0
        }) {
            let sound = s.free_stream_speed / s.mach;
            let pressure = 2.0 * s.dynamic_pressure
                / (PhysicalConstants::SI.heat_capacity_ratio * s.mach * s.mach);
            let vf = flutter_speed(
                fin.root_chord,
                fin.tip_chord,
                fin.span,
                material.thickness_m,
                material.shear_modulus_pa,
                pressure,
                sound,
            );
            let margin = vf / s.free_stream_speed;
            if margin.is_finite() && least.is_none_or(|(m, _, _)| margin < m) {
                least = Some((margin, vf, s.t));
            }
        }
        let note = least.map_or_else(
            || "no point of the ascent to assess".to_owned(),
            |(_, vf, t)| {
                format!(
                    "least flutter speed / airspeed of fins `{name}` before apogee (NACA TN \
                     4197): flutter speed {vf:.1} m/s at t = {t:.3} s"
                )
            },
        );
        checks.push(check(
            &key,
            least.map(|(m, _, _)| m),
            rules.min_flutter_margin,
            true,
            &note,
        ));
    }
    checks
}

/// Flies `mission` (seed `seed`) and reports its figures against `rules`; `fins` gives the
/// flutter speed (without it the flutter figures are not assessed, saying why).
///
/// # Errors
/// The mission's own errors; a multi-stage mission (not assessed yet).
pub fn safety(
    mission: &Mission,
    rules: &SafetyRules,
    fins: Option<FinMaterial>,
    seed: u64,
) -> Result<SafetyReport, MissionError> {
    if !mission.spec.stages.is_empty() {
        return Err(mission.model_error(
            "stages",
            "the range-safety report flies single-stage missions only (yet)",
        ));
    }
    let run = simulate_with_seed(mission, seed)?;
    let summary = run.summary();
    let samples = run.samples();
    let times: Vec<f64> = samples.iter().map(|s| s.t).collect();
    let event = |name: &str| {
        summary
            .events
            .iter()
            .find(|e| e.name == name)
            .map(|e| e.time_s)
    };
    let rail = summary.out_of_rail_time_s;
    let burnout = event("burnout");
    let apogee = summary.apogee_time_s;
    let mut checks = vec![
        check(
            "rail_exit_speed_mps",
            summary.out_of_rail_velocity_mps,
            rules.min_rail_exit_speed_mps,
            true,
            "speed at rail exit",
        ),
        check(
            "rail_exit_thrust_to_weight",
            rail.and_then(|t| {
                let thrust = at_time(
                    &times,
                    &samples.iter().map(|s| s.net_thrust).collect::<Vec<_>>(),
                    t,
                )?;
                let mass = at_time(
                    &times,
                    &samples.iter().map(|s| s.mass).collect::<Vec<_>>(),
                    t,
                )?;
                Some(thrust / (mass * PhysicalConstants::SI.standard_gravity))
            }),
            rules.min_thrust_to_weight,
            true,
            "net thrust over weight (m g0) at rail exit",
        ),
        check(
            "rail_exit_stability_margin_cal",
            summary.out_of_rail_stability_margin,
            rules.min_stability_margin_cal,
            true,
            "stability margin at rail exit",
        ),
    ];
    let powered_min = match (rail, burnout) {
        (Some(start), Some(end)) => samples
            .iter()
            .filter(|s| s.t >= start && s.t <= end && s.stability_margin.is_finite())
            .map(|s| s.stability_margin)
            .reduce(f64::min),
        _ => None,
    };
    checks.push(check(
        "min_powered_stability_margin_cal",
        powered_min,
        rules.min_stability_margin_cal,
        true,
        "least stability margin from rail exit to burn-out",
    ));
    checks.push(reported(
        "max_mach",
        Some(summary.max_mach),
        "largest Mach number",
    ));
    checks.push(reported(
        "max_dynamic_pressure_pa",
        Some(summary.max_dynamic_pressure_pa),
        "largest dynamic pressure",
    ));
    checks.extend(flutter_checks(mission, &samples, apogee, fins, rules));
    let landing_mass = samples.last().map(|s| s.mass);
    let impact = summary.impact_velocity_mps;
    checks.push(check(
        "landing_kinetic_energy_j",
        landing_mass.zip(impact).map(|(m, v)| 0.5 * m * v * v),
        rules.max_landing_energy_j,
        false,
        "1/2 m v^2 at impact, m the landing mass",
    ));
    checks.push(check(
        "descent_rate_mps",
        impact,
        rules.max_descent_rate_mps,
        false,
        "speed at impact",
    ));
    checks.push(check(
        "drift_m",
        summary
            .impact_x_m
            .zip(summary.impact_y_m)
            .map(|(x, y)| x.hypot(y)),
        rules.max_drift_m,
        false,
        "distance of the impact from the pad",
    ));
    Ok(SafetyReport {
        rules: *rules,
        checks,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flutter_speed_of_a_documented_fin() {
        // Cipolla's worked example of NACA TN 4197: root chord 12 in, tip chord 2.25 in,
        // semi-span 4 in, thickness 0.195 in, at 11 000 ft (p = 9.74 psi, a = 1073.85 ft/s).
        // His intermediate figures: U1 = DN AR^3 / ((t/c)^3 (AR + 2)) = 632 673.76 psi and
        // U2 = (λ + 1)/2 · p/p0 = 0.393 541 617, so V_f = a sqrt(G / (U1 U2)).
        let inch = 0.0254;
        let psi = 6_894.757_293_168;
        let ft = 0.3048;
        let (cr, ct, b, t) = (12.0 * inch, 2.25 * inch, 4.0 * inch, 0.195 * inch);
        let (p, a) = (9.74 * psi, 1073.85 * ft);
        let g = 3.0e6 * psi;
        let vf = flutter_speed(cr, ct, b, t, g, p, a);
        // By hand from the formula (SI): S = 0.01838706 m², AR = 0.5614035, λ = 0.1875,
        // t/c = 0.01625; 24 ε γ / π = 2.673803; AR³ = 0.1769397, (t/c)³ = 4.291016e-6;
        // the denominator 2.673803 · 0.1769397 / (4.291016e-6 · 2.5614035) · 0.59375 · p
        // = 25 557.61 p; V_f = a sqrt(G / (25 557.61 p)) = 327.3095 m/s · sqrt(3e6 / (9.74 ·
        // 25 557.61)) = 327.3095 · 3.471531 = 1136.26 m/s.
        assert!((vf - 1136.26).abs() < 0.02, "{vf}");
        // Cipolla's U1 · U2 (with his p0 = 14.69 psi): the same denominator over p/p0.
        let u = 632_673.76 * 0.393_541_617 * psi;
        let ours = g / ((vf / a) * (vf / a));
        assert!((ours / u - 1.0).abs() < 1e-3, "{ours} vs {u}");
    }

    #[test]
    fn verdicts_have_a_warning_band() {
        assert_eq!(verdict(35.0, 30.0, true), Verdict::Pass);
        assert_eq!(verdict(31.0, 30.0, true), Verdict::Warn);
        assert_eq!(verdict(29.0, 30.0, true), Verdict::Fail);
        assert_eq!(verdict(80.0, 100.0, false), Verdict::Pass);
        assert_eq!(verdict(95.0, 100.0, false), Verdict::Warn);
        assert_eq!(verdict(101.0, 100.0, false), Verdict::Fail);
    }
}
