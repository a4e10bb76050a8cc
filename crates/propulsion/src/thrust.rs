//! Thrust-curve processing shared by every motor type (docs/physics.md §6.1).
//!
//! Mirrors RocketPy's `Motor.__init__`, `Motor.reshape_thrust_curve` and `Motor.clip_thrust`
//! (rocketpy/motors/motor.py):
//!
//! 1. The source becomes a table with the chosen interpolation and **zero** extrapolation; a
//!    constant thrust is sampled at 50 equally spaced times over the burn interval.
//! 2. Burn interval `[t_b0, t_b1]`: as given (an end time `t` means `[0, t]`), else the first
//!    and last times of the data.
//! 3. Optional reshape `(new burn interval, new total impulse)`: times mapped affinely onto the
//!    new interval (`t' = k·t`, then shifted so the first time is the new start, with
//!    `k = Δt_new/Δt_data`), thrust scaled by `I_new / I_old` where `I_old` is the integral
//!    of the time-mapped curve over the new interval; the burn interval becomes the mapped
//!    data range.
//! 4. Clip: the interval is limited to the data range (recorded in
//!    [`ThrustCurve::burn_time_clipped`], RocketPy warns), the points strictly inside are kept
//!    and the end points `(t_b0, T(t_b0))`, `(t_b1, T(t_b1))` inserted (a step at `t_b0`
//!    keeps its last value after the first); the table is rebuilt with the same
//!    interpolation.
//!
//! A repeated time in the data is a step: a linear curve takes the first value at that time
//! and the last one right of it, as RocketPy's linear interpolation of the same points does;
//! the other interpolations refuse it ([`PropulsionError::RepeatedTime`]).
//! 5. Total impulse `∫ T dt` over the burn (exact for the interpolant: the trapezoid rule for
//!    linear interpolation), average thrust `I / (t_b1 − t_b0)`, maximum thrust over the
//!    clipped nodes.

use karman_math::{Extrapolation, Interpolation, Table1, linspace};

use crate::{PropulsionError, ThrustData};

/// Number of samples RocketPy takes of a constant (or callable) thrust over the burn.
const CALLABLE_SAMPLES: usize = 50;

/// Where a thrust curve comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum ThrustSource {
    /// A constant thrust, N (needs a burn time).
    Constant(f64),
    /// Validated samples from a file or an inline table.
    Data(Box<ThrustData>),
}

/// A burn interval as the user gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BurnTime {
    /// Burn from 0 to this time, s.
    End(f64),
    /// Burn from the first to the second time, s.
    Interval(f64, f64),
}

impl BurnTime {
    /// `(start, end)`, s.
    #[must_use]
    pub fn interval(self) -> (f64, f64) {
        match self {
            BurnTime::End(end) => (0.0, end),
            BurnTime::Interval(start, end) => (start, end),
        }
    }
}

/// Everything that shapes a thrust curve besides its source.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ThrustOptions {
    /// Burn interval; `None` takes the data's time range.
    pub burn_time: Option<BurnTime>,
    /// Optional reshape to `(burn time, total impulse N·s)` (RocketPy `reshape_thrust_curve`).
    pub reshape: Option<(BurnTime, f64)>,
    /// Interpolation between thrust samples (RocketPy default: linear).
    pub interpolation: Interpolation,
}

/// A processed thrust curve: clipped to the burn interval, zero outside it.
#[derive(Debug, Clone, PartialEq)]
pub struct ThrustCurve {
    table: Table1,
    burn_start: f64,
    burn_out: f64,
    total_impulse: f64,
    max_thrust: f64,
    max_thrust_time: f64,
    burn_time_clipped: bool,
}

impl ThrustCurve {
    /// Processes `source` as RocketPy's `Motor` does (module docs).
    ///
    /// # Errors
    /// [`PropulsionError::MissingBurnTime`] for a constant thrust without burn time,
    /// [`PropulsionError::InvalidParameter`] for a non-finite constant or reshape target,
    /// [`PropulsionError::InvalidBurnTime`] when the clipped interval is empty,
    /// [`PropulsionError::NoImpulse`] when a reshape starts from a curve without impulse,
    /// [`PropulsionError::Table`] when a table cannot be built.
    pub fn new(
        source: &ThrustSource,
        options: &ThrustOptions,
    ) -> Result<ThrustCurve, PropulsionError> {
        let interpolation = options.interpolation;
        let requested = options.burn_time.map(BurnTime::interval);
        if let Some((start, end)) = requested {
            check_finite("burn_time", start)?;
            check_finite("burn_time", end)?;
        }
        let mut table = match source {
            ThrustSource::Constant(thrust) => {
                check_finite("thrust", *thrust)?;
                let (start, end) = requested.ok_or(PropulsionError::MissingBurnTime)?;
                if end <= start {
                    return Err(PropulsionError::InvalidBurnTime {
                        start,
                        end,
                        data_start: start,
                        data_end: end,
                    });
                }
                Table1::sample(
                    |_| *thrust,
                    start,
                    end,
                    CALLABLE_SAMPLES,
                    interpolation,
                    Extrapolation::Zero,
                )
                .map_err(PropulsionError::table("thrust curve"))?
            }
            ThrustSource::Data(data) => {
                if interpolation != Interpolation::Linear
                    && let Some(w) = data.times.windows(2).find(|w| w[0] >= w[1])
                {
                    return Err(PropulsionError::RepeatedTime {
                        source_name: data.source_name.clone(),
                        time: w[0],
                    });
                }
                thrust_table(data.times.clone(), data.thrusts.clone(), interpolation)
                    .map_err(PropulsionError::table("thrust curve"))?
            }
        };
        let mut burn = requested.unwrap_or_else(|| table.domain());
        if let Some((new_burn, new_impulse)) = options.reshape {
            table = reshape(&table, new_burn.interval(), new_impulse)?;
            burn = table.domain();
        }
        let (data_start, data_end) = table.domain();
        let start = burn.0.max(data_start);
        let end = burn.1.min(data_end);
        let burn_time_clipped = start > burn.0 || end < burn.1;
        if end <= start {
            return Err(PropulsionError::InvalidBurnTime {
                start: burn.0,
                end: burn.1,
                data_start,
                data_end,
            });
        }
        let mut times = vec![start];
        let mut thrusts = vec![table.eval(start)];
        // A step at the start (a repeated time there): its last value starts the curve.
        let at_start = table
            .xs()
            .iter()
            .filter(|t| t.total_cmp(&start).is_eq())
            .count();
        if at_start > 1
            && let Some(last) = table.xs().iter().rposition(|t| t.total_cmp(&start).is_eq())
        {
            times.push(start);
            thrusts.push(table.ys()[last]);
        }
        for (&t, &f) in table.xs().iter().zip(table.ys()) {
            if t > start && t < end {
                times.push(t);
                thrusts.push(f);
            }
        }
        times.push(end);
        thrusts.push(table.eval(end));
        let table = thrust_table(times, thrusts, interpolation)
            .map_err(PropulsionError::table("clipped thrust curve"))?;
        let total_impulse = table.integral(start, end);
        let (mut max_thrust, mut max_thrust_time) = (f64::NEG_INFINITY, start);
        for (&t, &f) in table.xs().iter().zip(table.ys()) {
            if f > max_thrust {
                max_thrust = f;
                max_thrust_time = t;
            }
        }
        Ok(ThrustCurve {
            table,
            burn_start: start,
            burn_out: end,
            total_impulse,
            max_thrust,
            max_thrust_time,
            burn_time_clipped,
        })
    }

    /// A motor that never fires (RocketPy `EmptyMotor`: zero thrust sampled over `[0, 1]` s).
    #[must_use]
    pub fn zero() -> ThrustCurve {
        let times = linspace(0.0, 1.0, CALLABLE_SAMPLES);
        let thrusts = vec![0.0; times.len()];
        let table = Table1::new(times, thrusts, Interpolation::Linear, Extrapolation::Zero)
            .unwrap_or_else(|_| unreachable!("a linspace grid with finite zeros is a valid table"));
        ThrustCurve {
            table,
            burn_start: 0.0,
            burn_out: 1.0,
            total_impulse: 0.0,
            max_thrust: 0.0,
            max_thrust_time: 0.0,
            burn_time_clipped: false,
        }
    }

    /// The clipped thrust table `T(t)`, N (zero outside the burn).
    #[must_use]
    pub fn table(&self) -> &Table1 {
        &self.table
    }
    /// Thrust at `t`, N.
    #[inline]
    #[must_use]
    pub fn thrust(&self, t: f64) -> f64 {
        self.table.eval(t)
    }
    /// Burn start `t_b0`, s.
    #[must_use]
    pub fn burn_start(&self) -> f64 {
        self.burn_start
    }
    /// Burn out `t_b1`, s.
    #[must_use]
    pub fn burn_out(&self) -> f64 {
        self.burn_out
    }
    /// Burn duration `t_b1 − t_b0`, s.
    #[must_use]
    pub fn burn_duration(&self) -> f64 {
        self.burn_out - self.burn_start
    }
    /// Total impulse over the burn, N·s.
    #[must_use]
    pub fn total_impulse(&self) -> f64 {
        self.total_impulse
    }
    /// Average thrust `I / (t_b1 − t_b0)`, N.
    #[must_use]
    pub fn average_thrust(&self) -> f64 {
        self.total_impulse / self.burn_duration()
    }
    /// Largest thrust sample, N.
    #[must_use]
    pub fn max_thrust(&self) -> f64 {
        self.max_thrust
    }
    /// Time of the largest thrust sample (the first one if repeated), s.
    #[must_use]
    pub fn max_thrust_time(&self) -> f64 {
        self.max_thrust_time
    }
    /// Whether the requested burn interval reached outside the data and was clipped to it
    /// (RocketPy warns in that case).
    #[must_use]
    pub fn burn_time_clipped(&self) -> bool {
        self.burn_time_clipped
    }
}

/// RocketPy `Motor.reshape_thrust_curve`: affine time map, then impulse scaling.
fn reshape(
    table: &Table1,
    new_burn: (f64, f64),
    new_impulse: f64,
) -> Result<Table1, PropulsionError> {
    check_finite("reshape_thrust_curve burn time", new_burn.0)?;
    check_finite("reshape_thrust_curve burn time", new_burn.1)?;
    if new_burn.1 <= new_burn.0 {
        return Err(PropulsionError::InvalidParameter {
            name: "reshape_thrust_curve burn time",
            value: new_burn.1,
            reason: "must end after it starts",
        });
    }
    if !(new_impulse.is_finite() && new_impulse > 0.0) {
        return Err(PropulsionError::InvalidParameter {
            name: "reshape_thrust_curve total impulse",
            value: new_impulse,
            reason: "must be positive",
        });
    }
    let (t0, t1) = table.domain();
    let factor = (new_burn.1 - new_burn.0) / (t1 - t0);
    let scaled: Vec<f64> = table.xs().iter().map(|t| factor * t).collect();
    let first = scaled[0];
    let times: Vec<f64> = scaled.iter().map(|t| t - first + new_burn.0).collect();
    let mapped = thrust_table(times.clone(), table.ys().to_vec(), table.interpolation())
        .map_err(PropulsionError::table("reshaped thrust curve"))?;
    let old_impulse = mapped.integral(new_burn.0, new_burn.1);
    if !(old_impulse.is_finite() && old_impulse > 0.0) {
        return Err(PropulsionError::NoImpulse {
            impulse: old_impulse,
        });
    }
    let ratio = new_impulse / old_impulse;
    let thrusts = table.ys().iter().map(|f| ratio * f).collect();
    thrust_table(times, thrusts, table.interpolation())
        .map_err(PropulsionError::table("reshaped thrust curve"))
}

/// The thrust table on `times` with zero extrapolation. A repeated time (a step) is kept by a
/// linear table, as the mission format's linear curves keep it: at the time the first value,
/// right of it the last ([`Table1::linear_stepwise`], RocketPy's linear interpolation of the
/// same points); other interpolations need strictly increasing times.
fn thrust_table(
    times: Vec<f64>,
    thrusts: Vec<f64>,
    interpolation: Interpolation,
) -> Result<Table1, karman_math::MathError> {
    if interpolation == Interpolation::Linear && times.windows(2).any(|w| w[0] >= w[1]) {
        Table1::linear_stepwise(times, thrusts, Extrapolation::Zero)
    } else {
        Table1::new(times, thrusts, interpolation, Extrapolation::Zero)
    }
}

fn check_finite(name: &'static str, value: f64) -> Result<(), PropulsionError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(PropulsionError::InvalidParameter {
            name,
            value,
            reason: "must be finite",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ThrustFormat;

    fn data(times: &[f64], thrusts: &[f64]) -> ThrustSource {
        ThrustSource::Data(Box::new(ThrustData {
            source_name: "test".into(),
            format: ThrustFormat::Inline,
            times: times.to_vec(),
            thrusts: thrusts.to_vec(),
            header: None,
            warnings: Vec::new(),
        }))
    }

    #[test]
    fn a_repeated_time_is_a_step_of_a_linear_curve() {
        // An ignition step at 0 and a step down at 1 s: 0 → 100 N at once, 100 N to 1 s,
        // 50 N from 1 s to 2 s (RocketPy 1.13: the first value at the time, the last right of
        // it; the integral 100 + 50·1 − the two ramps of zero width).
        let src = data(&[0.0, 0.0, 1.0, 1.0, 2.0], &[0.0, 100.0, 100.0, 50.0, 50.0]);
        let c = ThrustCurve::new(&src, &ThrustOptions::default()).unwrap();
        let at = |t: f64| c.thrust(t).to_bits();
        assert_eq!(
            [at(0.0), at(0.5), at(1.0), at(1.5)],
            [0.0f64, 100.0, 100.0, 50.0].map(f64::to_bits)
        );
        assert!((c.total_impulse() - 150.0).abs() < 1e-12);
        // Clipped to [0, 1.5] and reshaped, the steps stay.
        let opts = ThrustOptions {
            burn_time: Some(BurnTime::End(1.5)),
            ..Default::default()
        };
        let c = ThrustCurve::new(&src, &opts).unwrap();
        assert!((c.total_impulse() - 125.0).abs() < 1e-12);
        let opts = ThrustOptions {
            reshape: Some((BurnTime::End(4.0), 300.0)),
            ..Default::default()
        };
        let c = ThrustCurve::new(&src, &opts).unwrap();
        assert!((c.total_impulse() - 300.0).abs() < 1e-9);
        assert_eq!(c.thrust(1.0).to_bits(), c.thrust(1.9).to_bits());
        // Other interpolations refuse the step, naming the time.
        for interpolation in [Interpolation::Spline, Interpolation::Akima] {
            let opts = ThrustOptions {
                interpolation,
                ..Default::default()
            };
            let e = ThrustCurve::new(&src, &opts).unwrap_err();
            assert_eq!(
                e,
                PropulsionError::RepeatedTime {
                    source_name: "test".into(),
                    time: 0.0
                }
            );
        }
    }

    #[test]
    fn clips_and_integrates() {
        // Triangle 0..2 s peaking at 100 N; clipped to [0, 1.5].
        let src = data(&[0.0, 1.0, 2.0], &[0.0, 100.0, 0.0]);
        let opts = ThrustOptions {
            burn_time: Some(BurnTime::End(1.5)),
            ..Default::default()
        };
        let c = ThrustCurve::new(&src, &opts).unwrap();
        assert_eq!(c.table().xs(), &[0.0, 1.0, 1.5]);
        assert!((c.thrust(1.5) - 50.0).abs() < 1e-12);
        assert!(c.thrust(1.6).abs() < 1e-300, "zero after burn-out");
        // 50 + (100 + 50)/2 · 0.5 = 87.5 N·s
        assert!((c.total_impulse() - 87.5).abs() < 1e-12);
        assert!((c.average_thrust() - 87.5 / 1.5).abs() < 1e-12);
        assert!(
            (c.max_thrust() - 100.0).abs() < 1e-12 && (c.max_thrust_time() - 1.0).abs() < 1e-15
        );
        assert!(!c.burn_time_clipped());
        let opts = ThrustOptions {
            burn_time: Some(BurnTime::Interval(-1.0, 5.0)),
            ..Default::default()
        };
        let c = ThrustCurve::new(&src, &opts).unwrap();
        assert!(c.burn_time_clipped());
        assert!((c.burn_start()).abs() < 1e-300 && (c.burn_out() - 2.0).abs() < 1e-15);
    }

    #[test]
    fn reshape_maps_time_and_scales_impulse() {
        let src = data(&[0.0, 1.0, 2.0], &[0.0, 100.0, 0.0]);
        let opts = ThrustOptions {
            reshape: Some((BurnTime::End(4.0), 300.0)),
            ..Default::default()
        };
        let c = ThrustCurve::new(&src, &opts).unwrap();
        assert_eq!(c.table().xs(), &[0.0, 2.0, 4.0]);
        assert!((c.total_impulse() - 300.0).abs() < 1e-12);
        assert!((c.max_thrust() - 150.0).abs() < 1e-12);
    }

    #[test]
    fn constant_thrust_is_sampled_over_the_burn() {
        let opts = ThrustOptions {
            burn_time: Some(BurnTime::Interval(1.0, 3.0)),
            ..Default::default()
        };
        let c = ThrustCurve::new(&ThrustSource::Constant(10.0), &opts).unwrap();
        assert_eq!(c.table().xs().len(), CALLABLE_SAMPLES);
        assert!((c.total_impulse() - 20.0).abs() < 1e-12);
        assert!(c.thrust(0.5).abs() < 1e-300);
        let e =
            ThrustCurve::new(&ThrustSource::Constant(10.0), &ThrustOptions::default()).unwrap_err();
        assert_eq!(e, PropulsionError::MissingBurnTime);
    }

    #[test]
    fn rejects_empty_burn() {
        let src = data(&[0.0, 1.0], &[1.0, 1.0]);
        let opts = ThrustOptions {
            burn_time: Some(BurnTime::Interval(2.0, 3.0)),
            ..Default::default()
        };
        assert!(matches!(
            ThrustCurve::new(&src, &opts),
            Err(PropulsionError::InvalidBurnTime { .. })
        ));
    }
}
