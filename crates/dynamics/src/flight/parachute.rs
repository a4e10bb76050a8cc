//! The parachute triggers as sampled processes (docs/physics.md §9.4): an apogee trigger, or a
//! barometric height trigger reading the pressure with an AR(1) noise ([`NoiseStream`]).

use karman_model::{AtmosphereModel, ParachuteSpec, TriggerKind};

use super::actions::Action;
use super::process::{Connections, DenseOutput, Probe, SampledProcess, SignalId, StepBounds};
use crate::DynamicsError;
use crate::noise::NoiseStream;

/// Resolution of the height above which a noisy height trigger is out of reach within a step,
/// as a fraction of [`crate::FlightSettings::trigger_band`].
const REACH_RESOLUTION: f64 = 0.01;

/// The ASL height `z` where a noise-free height trigger switches, `h_baro(P(z)) − elevation =
/// height_agl`, by bisection (both functions are monotone); `None` if not bracketed.
fn trigger_height<A: AtmosphereModel>(atm: &A, elevation: f64, height_agl: f64) -> Option<f64> {
    let g = |z: f64| atm.barometric_height(atm.pressure(z)) - elevation - height_agl;
    let guess = elevation + height_agl;
    let (mut lo, mut hi) = (guess - 1000.0, guess + 1000.0);
    let (g_lo, g_hi) = (g(lo), g(hi));
    let bracketed = g_lo < 0.0 && g_hi > 0.0;
    if !bracketed {
        return None;
    }
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if g(mid) < 0.0 { lo = mid } else { hi = mid }
    }
    Some(0.5 * (lo + hi))
}

/// The lowest height in `(low, high]`, to `resolution`, at which the monotone predicate
/// `out_of_reach` (false at `low`, and once true, true at every greater height) holds; `None`
/// if it does not hold at `high`. Bisection: the answer is a height where the predicate was
/// evaluated true, so every height at or above it is out of reach.
fn reach_height(
    low: f64,
    high: f64,
    resolution: f64,
    out_of_reach: impl Fn(f64) -> bool,
) -> Option<f64> {
    if !out_of_reach(high) {
        return None;
    }
    let (mut lo, mut hi) = (low, high);
    while hi - lo > resolution {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if out_of_reach(mid) {
            hi = mid
        } else {
            lo = mid
        }
    }
    Some(hi)
}

/// One parachute's trigger: fires ([`Action::DeployDevice`]) when the rocket descends and,
/// for a height trigger, the barometric height of the noisy pressure is below the trigger
/// height above ground.
pub(super) struct ParachuteTrigger<'a, A> {
    atmosphere: &'a A,
    /// Index of the parachute among the vehicle's.
    index: usize,
    trigger: TriggerKind,
    rate: f64,
    stream: NoiseStream,
    /// The noise stream is advanced at every instant (a noisy height trigger).
    draws: bool,
    /// The ASL height below which a noise-free height trigger fires.
    threshold: Option<f64>,
    elevation: f64,
    /// [`crate::FlightSettings::trigger_band`], m.
    band: f64,
    /// Instants passed over whose noise has not been drawn yet ([`NoiseStream::skip`] jumps
    /// over them in one draw when the stream is next read, or when the step ends).
    undrawn: usize,
    fired: bool,
    /// The signals a custom condition reads ([`karman_model::TriggerCondition::signals`]), connected when
    /// the flight is set up, and the buffer their values are read into at each sample.
    signals: Vec<SignalId>,
    signal_values: Vec<f64>,
}

impl<'a, A: AtmosphereModel> ParachuteTrigger<'a, A> {
    /// The trigger of parachute `index` with its noise stream.
    pub fn new(
        atmosphere: &'a A,
        index: usize,
        spec: &ParachuteSpec,
        stream: NoiseStream,
        band: f64,
    ) -> Self {
        let elevation = atmosphere.elevation();
        Self {
            atmosphere,
            index,
            trigger: spec.trigger.clone(),
            rate: spec.sampling_rate,
            draws: !matches!(spec.trigger, TriggerKind::Apogee) && !stream.is_silent(),
            stream,
            threshold: match spec.trigger {
                TriggerKind::Apogee | TriggerKind::Custom(_) => None,
                TriggerKind::HeightAboveGround(h) => trigger_height(atmosphere, elevation, h),
            },
            elevation,
            band,
            undrawn: 0,
            fired: false,
            signals: Vec::new(),
            signal_values: Vec::new(),
        }
    }

    /// Whether a noisy height trigger `h` m above ground cannot fire at height `z` even with
    /// the noise at `bound`: the highest possible noisy pressure reads a barometric height at
    /// least the band above the trigger height.
    /// A custom condition at the probe's instant: the noisy pressure `P(z) + noise`, its
    /// barometric height above ground and the state (docs/physics.md §17).
    /// With the latest values of the signals it reads (NaN before their first), read into
    /// the trigger's buffer: no allocation.
    fn custom(&mut self, probe: &mut Probe<'_>, noise: f64) -> bool {
        let TriggerKind::Custom(condition) = &self.trigger else {
            return false;
        };
        let atm = self.atmosphere;
        let pressure = atm.pressure(probe.z()) + noise;
        let height = atm.barometric_height(pressure) - self.elevation;
        if self.signals.is_empty() {
            return condition.fires(probe.t(), pressure, height, &probe.state());
        }
        for (value, id) in self.signal_values.iter_mut().zip(&self.signals) {
            *value = probe.read(*id).map_or(f64::NAN, |s| s.value);
        }
        condition.fires_reading(
            probe.t(),
            pressure,
            height,
            &probe.state(),
            &self.signal_values,
        )
    }

    fn out_of_reach(&self, z: f64, bound: f64, h: f64) -> bool {
        let atm = self.atmosphere;
        atm.barometric_height(atm.pressure(z) + bound) - self.elevation >= h + self.band
    }
}

impl<A: AtmosphereModel> SampledProcess for ParachuteTrigger<'_, A> {
    fn rate(&self) -> f64 {
        self.rate
    }

    fn whole_step(&self) -> bool {
        matches!(self.trigger, TriggerKind::Custom(_))
    }

    /// A custom condition's signals ([`karman_model::TriggerCondition::signals`]).
    fn connect(&mut self, connections: &Connections<'_>) -> Result<(), DynamicsError> {
        if let TriggerKind::Custom(condition) = &self.trigger {
            self.signals = condition
                .signals()
                .iter()
                .map(|name| connections.signal(name))
                .collect::<Result<_, _>>()?;
            self.signal_values = vec![f64::NAN; self.signals.len()];
        }
        Ok(())
    }

    /// A silent (noise-free) parachute certainly cannot fire inside the step when `v_z > 0`
    /// throughout, or, for a height trigger, when the step stays above its threshold
    /// height by more than the band.
    fn cannot_act(&self, bounds: &StepBounds) -> bool {
        if self.fired {
            return true;
        }
        if !self.stream.is_silent() || matches!(self.trigger, TriggerKind::Custom(_)) {
            return false;
        }
        if bounds.vz[0] > 0.0 {
            return true;
        }
        match self.threshold {
            Some(z_threshold) => bounds.z[0] > z_threshold + self.band,
            None => false,
        }
    }

    /// Both triggers need `v_z < 0`; a noisy height trigger cannot fire where even the
    /// highest possible pressure, `P(z)` plus the noise stream's bound on its coming values
    /// ([`NoiseStream::upper_bound`]), reads a barometric height at least the band above its
    /// threshold (`h_baro` and `P` decrease with their arguments; the band absorbs round-off
    /// and interpolation wiggles): its instants above the lowest such height are passed over.
    fn first_candidate(
        &mut self,
        next: i64,
        last: i64,
        bounds: &StepBounds,
        dense: &mut dyn DenseOutput,
    ) -> i64 {
        let ([vz_low, vz_high], [z_low, z_high]) = (bounds.vz, bounds.z);
        if matches!(self.trigger, TriggerKind::Custom(_)) {
            // Sampled at every instant, ascent included (docs/physics.md §17).
            return next;
        }
        let descending = vz_low <= 0.0 || vz_low.is_nan();
        if !descending {
            return last + 1;
        }
        let TriggerKind::HeightAboveGround(h) = self.trigger else {
            return next;
        };
        if !self.draws {
            // A noise-free height trigger: `cannot_act` has already bounded it.
            return next;
        }
        let bound = self.stream.upper_bound();
        if self.out_of_reach(z_low, bound, h) {
            return last + 1;
        }
        // The step reaches down to the band: pass over the instants that are still out of
        // reach at their own height, i.e. above the lowest height `z_reach` found out of reach
        // (the predicate grows with `z`: `P` and `h_baro` both decrease).
        let interval = 1.0 / self.rate;
        let time = |j: i64| j as f64 * interval;
        let mut j = next;
        let resolution = REACH_RESOLUTION * self.band;
        if let Some(z_reach) = reach_height(z_low, z_high, resolution, |z| {
            self.out_of_reach(z, bound, h)
        }) {
            if vz_high < 0.0 {
                // Falling throughout: the dense heights decrease with j, so the first instant
                // below `z_reach` is found by bisection (a long step holds hundreds of
                // instants).
                let mut end = last + 1;
                while j < end {
                    let mid = j + (end - j) / 2;
                    if dense.component(time(mid), 2) >= z_reach {
                        j = mid + 1;
                    } else {
                        end = mid;
                    }
                }
            } else {
                while j <= last && dense.component(time(j), 2) >= z_reach {
                    j += 1;
                }
            }
        }
        j
    }

    fn pass_over(&mut self, count: usize) {
        if self.draws {
            self.undrawn += count;
        }
    }

    fn sample(&mut self, probe: &mut Probe<'_>) -> Option<Action> {
        let noise = if self.draws {
            self.stream.skip(std::mem::take(&mut self.undrawn));
            self.stream.next_value()
        } else {
            0.0
        };
        let fires = match &self.trigger {
            TriggerKind::Custom(_) => self.custom(probe, noise),
            _ => {
                probe.vz() < 0.0
                    && match self.trigger {
                        TriggerKind::Apogee | TriggerKind::Custom(_) => true,
                        TriggerKind::HeightAboveGround(h) => {
                            let z = probe.z();
                            match self.threshold {
                                // Noise-free: compare heights directly, away from the threshold.
                                Some(zt) if noise == 0.0 && (z - zt).abs() > self.band => z < zt,
                                _ => {
                                    let atm = self.atmosphere;
                                    atm.barometric_height(atm.pressure(z) + noise) - self.elevation
                                        < h
                                }
                            }
                        }
                    }
            }
        };
        if fires {
            self.fired = true;
            Some(Action::DeployDevice(self.index))
        } else {
            None
        }
    }

    fn end_step(&mut self) {
        self.stream.skip(std::mem::take(&mut self.undrawn));
    }

    fn is_done(&self) -> bool {
        self.fired
    }

    /// The plain trigger: the stream drawn at the instant whatever the trigger kind, the
    /// barometric height of the noisy pressure compared with the trigger height.
    #[cfg(test)]
    fn sample_directly(&mut self, probe: &mut Probe<'_>) -> Option<Action> {
        let noise = self.stream.next_value();
        let fires = match &self.trigger {
            TriggerKind::Custom(_) => self.custom(probe, noise),
            _ => {
                probe.vz() < 0.0
                    && match self.trigger {
                        TriggerKind::Apogee | TriggerKind::Custom(_) => true,
                        TriggerKind::HeightAboveGround(h) => {
                            let atm = self.atmosphere;
                            atm.barometric_height(atm.pressure(probe.z()) + noise) - self.elevation
                                < h
                        }
                    }
            }
        };
        fires.then(|| {
            self.fired = true;
            Action::DeployDevice(self.index)
        })
    }
}
