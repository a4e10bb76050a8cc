//! Parachutes and rail buttons: data the flight engine uses for recovery events and the
//! launch rail (RocketPy `Parachute`, `RailButtons`; docs/physics.md §1, §8.1, §8.4, §9.4).

use std::f64::consts::PI;

use karman_model::TriggerKind;

use crate::error::{AirframeError, finite, non_negative, positive};

/// Default canopy drag coefficient used only to infer a canopy radius (hemispherical canopy,
/// NASA SP-8066; RocketPy `Parachute(drag_coefficient=1.4)`).
pub const DEFAULT_CANOPY_DRAG_COEFFICIENT: f64 = 1.4;
/// Default canopy porosity (RocketPy `Parachute(porosity=0.0432)`).
pub const DEFAULT_POROSITY: f64 = 0.0432;
/// Default trigger sampling rate (Hz) of `Rocket.add_parachute`.
pub const DEFAULT_SAMPLING_RATE: f64 = 100.0;

/// The user's description of a parachute; `None` fields take RocketPy's defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct ParachuteSpec {
    /// Name (the mission table name).
    pub name: String,
    /// Drag coefficient × reference area (m²).
    pub cd_s: f64,
    /// Ejection trigger.
    pub trigger: TriggerKind,
    /// Trigger sampling rate (Hz); default 100.
    pub sampling_rate: Option<f64>,
    /// Delay from trigger to full deployment (s); default 0.
    pub lag: Option<f64>,
    /// Pressure-signal noise `(mean Pa, std Pa, time correlation)`; default zero.
    pub noise: Option<[f64; 3]>,
    /// Canopy radius (m); default `sqrt(cd_s / (C_D π))`.
    pub radius: Option<f64>,
    /// Canopy height (m); default the radius.
    pub height: Option<f64>,
    /// Canopy porosity; default 0.0432.
    pub porosity: Option<f64>,
    /// Canopy drag coefficient C_D used for the default radius; default 1.4.
    pub drag_coefficient: Option<f64>,
}

/// A parachute with every default resolved (docs/physics.md §8.4).
#[derive(Debug, Clone, PartialEq)]
pub struct Parachute {
    /// Name.
    pub name: String,
    /// Drag coefficient × reference area (m²).
    pub cd_s: f64,
    /// Ejection trigger.
    pub trigger: TriggerKind,
    /// Trigger sampling rate (Hz).
    pub sampling_rate: f64,
    /// Delay from trigger to full deployment (s).
    pub lag: f64,
    /// Pressure-signal noise `(mean Pa, std Pa, time correlation)`.
    pub noise: [f64; 3],
    /// Canopy radius R_p (m).
    pub radius: f64,
    /// Canopy height H_p (m).
    pub height: f64,
    /// Canopy porosity.
    pub porosity: f64,
    /// Canopy drag coefficient used for the default radius.
    pub drag_coefficient: f64,
}

impl Parachute {
    /// Resolves defaults and checks the values.
    ///
    /// # Errors
    /// [`AirframeError`] for a non-positive `cd_s` or sampling rate, a negative lag, radius,
    /// height or noise deviation, a porosity outside `[0, 1]` or a correlation outside
    /// `[−1, 1]`.
    pub fn new(spec: &ParachuteSpec) -> Result<Self, AirframeError> {
        let c = spec.name.as_str();
        let cd_s = positive(c, "cd_s", spec.cd_s)?;
        if let TriggerKind::HeightAboveGround(h) = &spec.trigger {
            let h = *h;
            finite(c, "trigger", h)?;
        }
        let sampling_rate = positive(
            c,
            "sampling_rate",
            spec.sampling_rate.unwrap_or(DEFAULT_SAMPLING_RATE),
        )?;
        let lag = non_negative(c, "lag", spec.lag.unwrap_or(0.0))?;
        let noise = spec.noise.unwrap_or([0.0; 3]);
        finite(c, "noise mean", noise[0])?;
        non_negative(c, "noise standard deviation", noise[1])?;
        let corr = finite(c, "noise correlation", noise[2])?;
        if corr.abs() > 1.0 {
            return Err(AirframeError::OutOfRange {
                component: c.to_owned(),
                quantity: "noise correlation",
                value: corr,
                min: -1.0,
                max: 1.0,
            });
        }
        let drag_coefficient = positive(
            c,
            "drag_coefficient",
            spec.drag_coefficient
                .unwrap_or(DEFAULT_CANOPY_DRAG_COEFFICIENT),
        )?;
        let radius = match spec.radius {
            Some(r) => non_negative(c, "radius", r)?,
            None => (cd_s / (drag_coefficient * PI)).sqrt(),
        };
        let height = match spec.height {
            Some(h) => non_negative(c, "height", h)?,
            None => radius,
        };
        let porosity = finite(c, "porosity", spec.porosity.unwrap_or(DEFAULT_POROSITY))?;
        if !(0.0..=1.0).contains(&porosity) {
            return Err(AirframeError::OutOfRange {
                component: c.to_owned(),
                quantity: "porosity",
                value: porosity,
                min: 0.0,
                max: 1.0,
            });
        }
        Ok(Parachute {
            name: spec.name.clone(),
            cd_s,
            trigger: spec.trigger.clone(),
            sampling_rate,
            lag,
            noise,
            radius,
            height,
            porosity,
            drag_coefficient,
        })
    }

    /// Added-mass coefficient `C_a = 1.068 (1 − 1.465 p − 0.25975 p² + 1.2626 p³)` of the
    /// canopy of porosity `p` (RocketPy `Parachute`, after Knacke 1992 / NASA SP-8066).
    #[must_use]
    pub fn added_mass_coefficient(&self) -> f64 {
        let p = self.porosity;
        1.068 * (1.0 - 1.465 * p - 0.25975 * p * p + 1.2626 * p.powi(3))
    }
}

/// The launch-rail buttons (RocketPy `Rocket.set_rail_buttons`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RailButtons {
    /// Position of the button nearer the nose, user coordinates (m).
    pub upper_position: f64,
    /// Position of the button nearer the nozzle, user coordinates (m).
    pub lower_position: f64,
    /// Roll angle of the buttons from the user y axis (rad).
    pub angular_position_rad: f64,
}

impl RailButtons {
    /// Rail buttons at `upper`/`lower` (user coordinates, m) and `angular_position_deg`.
    ///
    /// # Errors
    /// [`AirframeError::NotFinite`] for a non-finite input.
    pub fn new(upper: f64, lower: f64, angular_position_deg: f64) -> Result<Self, AirframeError> {
        const C: &str = "rail_buttons";
        Ok(RailButtons {
            upper_position: finite(C, "upper_position", upper)?,
            lower_position: finite(C, "lower_position", lower)?,
            angular_position_rad: finite(C, "angular_position", angular_position_deg)?.to_radians(),
        })
    }

    /// Distance between the buttons `|upper − lower|` (m).
    #[must_use]
    pub fn buttons_distance(&self) -> f64 {
        (self.upper_position - self.lower_position).abs()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> ParachuteSpec {
        ParachuteSpec {
            name: "drogue".to_owned(),
            cd_s: 1.0,
            trigger: TriggerKind::Apogee,
            sampling_rate: None,
            lag: None,
            noise: None,
            radius: None,
            height: None,
            porosity: None,
            drag_coefficient: None,
        }
    }

    #[test]
    fn defaults_match_physics_md() {
        // docs/physics.md §13: cd_s 1.0 → R_p = H_p = 0.4768272, C_a = 0.99999941.
        let p = Parachute::new(&spec()).expect("valid parachute");
        assert!((p.radius - 0.476_827_2).abs() < 1e-7);
        assert!((p.height - p.radius).abs() < 1e-15);
        assert!((p.added_mass_coefficient() - 0.999_999_41).abs() < 1e-8);
        assert!((p.sampling_rate - 100.0).abs() < 1e-15);
        assert!(p.lag.abs() < 1e-15);
    }

    #[test]
    fn bad_parachutes_are_errors() {
        let mut s = spec();
        s.cd_s = 0.0;
        assert!(Parachute::new(&s).is_err());
        let mut s = spec();
        s.lag = Some(-1.0);
        assert!(Parachute::new(&s).is_err());
        let mut s = spec();
        s.noise = Some([0.0, 8.3, 1.5]);
        assert!(Parachute::new(&s).is_err());
        let mut s = spec();
        s.sampling_rate = Some(0.0);
        assert!(Parachute::new(&s).is_err());
        let mut s = spec();
        s.porosity = Some(2.0);
        assert!(Parachute::new(&s).is_err());
    }

    #[test]
    fn rail_buttons_store_radians() {
        let b = RailButtons::new(0.0818, -0.6182, 45.0).expect("valid buttons");
        assert!((b.angular_position_rad - PI / 4.0).abs() < 1e-15);
        assert!((b.buttons_distance() - 0.7).abs() < 1e-12);
        assert!(RailButtons::new(f64::NAN, 0.0, 45.0).is_err());
    }
}
