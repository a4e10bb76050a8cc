//! Events: a scalar of the state whose sign change inside an accepted step is located by one
//! root routine ([`root`]), and what firing does (docs/physics.md §9.2, §9.3, §9.5). Rail exit,
//! apogee and impact are the instances checked after every step, in RocketPy's order; burn-out
//! and `max_time` are time nodes instead (a step stop, the last phase bound).

use super::actions::{Acted, Action, Target};
use super::log::{SolutionPoint, Termination};
use super::schedule::{Phase, PhaseKind};
use crate::DynamicsError;
use crate::equations::coasts_off_rail;
use crate::integrator::RungeKutta;
use crate::state::{State, VZ, Z};

/// A user-defined event: a scalar of the flight whose crossing of zero from above (from
/// `≥ 0` at a step's start to `< 0` at its end) fires an action at the root, located on the
/// dense output. Checked after every accepted step from rail exit on, after the built-in
/// events (rail exit, apogee, impact) and before the sampled processes; an event fires once.
pub trait Event {
    /// The event's value at time `t`, s, and state `state` (docs/physics.md §3).
    fn value(&self, t: f64, state: &State) -> f64;
    /// What happens at the root `t` with the state there; every action but
    /// [`Action::Record`] ends the step at the root.
    fn fire(&mut self, t: f64, state: &State) -> Action;
}

/// Bisection steps of a user event's root on the dense output: the bracket halves to below
/// `2⁻⁶⁰` of the step.
const EVENT_BISECTIONS: usize = 60;

/// The root in `(t0, t1)` of `g`, negative at `t1` and not negative at `t0`, by bisection.
fn bisect(t0: f64, t1: f64, mut g: impl FnMut(f64) -> f64) -> f64 {
    let (mut lo, mut hi) = (t0, t1);
    for _ in 0..EVENT_BISECTIONS {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if g(mid) < 0.0 { hi = mid } else { lo = mid }
    }
    hi
}

/// How an event's root is interpolated between the step's ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Root {
    /// The cubic Hermite interpolant of the end values and slopes, by bisection (rail exit
    /// §9.2, impact §9.5): the end values bracket a sign change by construction.
    Hermite,
    /// The straight line through the end values (RocketPy's apogee, §9.3; the slopes are
    /// unused).
    Linear,
}

/// The offset `τ ∈ (0, h)` from the step start of the root of a scalar with values `y0, y1`
/// and slopes `yp0, yp1` at the ends of a step of length `h`; `None` when a Hermite root is
/// not bracketed.
pub(super) fn root(form: Root, h: f64, y0: f64, yp0: f64, y1: f64, yp1: f64) -> Option<f64> {
    match form {
        Root::Hermite => hermite_root(h, y0, yp0, y1, yp1),
        Root::Linear => Some(-(y0 * h / (y1 - y0))),
    }
}

/// Real root in `(0, h)` of the cubic Hermite interpolant with values `y0, y1` and slopes
/// `yp0, yp1` at `0, h`, by bisection on the cubic.
fn hermite_root(h: f64, y0: f64, yp0: f64, y1: f64, yp1: f64) -> Option<f64> {
    let bracketed = h > 0.0 && y0 * y1 <= 0.0; // false for NaN too
    if !bracketed {
        return None;
    }
    // p(τ) = a τ³ + b τ² + c τ + d.
    let d = y0;
    let c = yp0;
    let b = (3.0 * (y1 - y0) / h - 2.0 * yp0 - yp1) / h;
    let a = (yp0 + yp1 - 2.0 * (y1 - y0) / h) / (h * h);
    let p = |x: f64| ((a * x + b) * x + c) * x + d;
    let (mut lo, mut hi) = (0.0, h);
    let mut plo = p(lo);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let pm = p(mid);
        if (pm <= 0.0) == (plo <= 0.0) && pm != 0.0 {
            lo = mid;
            plo = pm;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

/// The event checks of a flight and what they need to know.
pub(super) struct Events<'a> {
    /// The rocket has left the rail (sampling and the apogee and impact checks start).
    pub off_rail: bool,
    /// The equations of the free flight after rail exit ([`PhaseKind::free_flight`]).
    pub free_flight: PhaseKind,
    /// Rail travel to the upper button, m.
    pub rail_travel: f64,
    /// Gravity along the rail at the pad, `g sin i`, m/s² (the coast that decides whether a
    /// rocket still on the rail at burn-out leaves it).
    pub rail_gravity: f64,
    /// Launch elevation, m ASL.
    pub elevation: f64,
    /// Motor burn-out time, s.
    pub burn_out: f64,
    /// [`crate::FlightSettings::terminate_on_apogee`].
    pub terminate_on_apogee: bool,
    /// The user-defined events, with whether each has fired.
    pub custom: Vec<(Box<dyn Event + 'a>, bool)>,
    /// Index the first user event records under ([`crate::Record::process`]): the number
    /// of sampled processes.
    pub first_record: usize,
}

impl Events<'_> {
    /// Event checks after an accepted step (docs/physics.md §9.1 step 4): (a) rail exit, (b)
    /// apogee, (c) impact. Returns the state the next phase starts from when the current
    /// phase ends here; `Ok(None)` when the sampled processes are to be checked next.
    pub fn check<F: FnMut(f64, &State) -> State>(
        &mut self,
        target: &mut Target<'_>,
        integ: &mut RungeKutta<13, F>,
        index: usize,
        phase: &Phase,
        kind: PhaseKind,
    ) -> Result<Option<(f64, State)>, DynamicsError> {
        let elevation = self.elevation;
        let n = target.log.points.len();
        let prev = target.log.points[n - 2];
        let last = target.log.points[n - 1];
        let (t0, y0) = (prev.t, prev.state);
        let (t1, y1) = (last.t, last.state);
        let h = t1 - t0;

        // (a) Rail exit: `|Δr|² − L₁²` crosses zero.
        if !self.off_rail {
            let travel = self.rail_travel;
            let dr = |u: &State| [u[0], u[1], u[2] - elevation];
            let f = |u: &State| {
                let d = dr(u);
                d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - travel * travel
            };
            let fp = |u: &State| {
                let d = dr(u);
                2.0 * (d[0] * u[3] + d[1] * u[4] + d[2] * u[5])
            };
            if f(&y1) >= 0.0 {
                let tau = root(Root::Hermite, h, f(&y0), fp(&y0), f(&y1), fp(&y1)).ok_or(
                    DynamicsError::EventRoot {
                        event: "rail exit",
                        t0,
                        t1,
                    },
                )?;
                let (t_exit, y_exit) =
                    target
                        .log
                        .cut_step(integ, phase.configuration, kind, t0 + tau);
                target.log.rail_exit = Some((t_exit, y_exit));
                self.off_rail = true;
                target.schedule.insert(
                    index + 1,
                    Phase {
                        t: t_exit,
                        kind: Some(self.free_flight),
                        configuration: phase.configuration,
                        clear: true,
                    },
                );
                return Ok(Some((t_exit, y_exit)));
            }
            // Still on the rail at burn-out: the rocket leaves only if its speed there carries
            // it the rest of the way against gravity (the launch check's rule); otherwise the
            // clipped rail acceleration would let it creep off long after. The flight then ends
            // at burn-out (at the step's end when the step began after it).
            if kind == PhaseKind::Rail && t1 >= self.burn_out {
                let inside = t0 < self.burn_out && self.burn_out < t1;
                let u = if inside {
                    integ.dense(self.burn_out)
                } else {
                    y1
                };
                let d = dr(&u);
                let travelled = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                let speed = (u[3] * u[3] + u[4] * u[4] + u[5] * u[5]).sqrt();
                if !coasts_off_rail(travelled, speed, travel, self.rail_gravity) {
                    let (t, u) = if inside {
                        target
                            .log
                            .cut_step(integ, phase.configuration, kind, self.burn_out)
                    } else {
                        (t1, y1)
                    };
                    target.end_flight(index, t, Termination::StuckOnRail);
                    return Ok(Some((t, u)));
                }
            }
        }
        // (b) Apogee: `v_z` turns negative.
        if target.log.apogee.is_none() && self.off_rail && y1[VZ] < 0.0 {
            let tau = root(Root::Linear, h, y0[VZ], 0.0, y1[VZ], 0.0).unwrap_or(f64::NAN);
            let t_apogee = t0 + tau;
            let y_apogee = integ.dense(t_apogee);
            target.log.apogee = Some((t_apogee, y_apogee));
            if self.terminate_on_apogee {
                target
                    .log
                    .cut_step(integ, phase.configuration, kind, t_apogee);
                target.end_flight(index, t_apogee, Termination::Apogee);
                return Ok(Some((t_apogee, y_apogee)));
            }
            if n > 2 {
                target.log.points.insert(
                    n - 1,
                    SolutionPoint {
                        t: t_apogee,
                        state: y_apogee,
                        phase: kind,
                        configuration: phase.configuration,
                    },
                );
            }
        }
        // (c) Impact: `z − elevation` turns negative. RocketPy skips the impact check on the
        // apogee step; a step that spans both (a ballistic arc in vacuum) would then never
        // find the ground, so it is checked here. On the rail the height cannot fall below
        // the pad; only round-off (the fifth-order weights include a negative one) could make
        // it, so the check starts at rail exit.
        if self.off_rail && y1[Z] < elevation {
            let tau = root(
                Root::Hermite,
                h,
                y0[Z] - elevation,
                y0[VZ],
                y1[Z] - elevation,
                y1[VZ],
            )
            .ok_or(DynamicsError::EventRoot {
                event: "impact",
                t0,
                t1,
            })?;
            let (t_impact, y_impact) =
                target
                    .log
                    .cut_step(integ, phase.configuration, kind, t0 + tau);
            target.log.impact = Some((t_impact, y_impact));
            target.end_flight(index, t_impact, Termination::Impact);
            return Ok(Some((t_impact, y_impact)));
        }
        Ok(None)
    }
}

impl Events<'_> {
    /// The user-defined events after an accepted step (from rail exit on): the earliest root
    /// in the step of an event whose value crosses zero from above, and its action, as the
    /// process `first_record + k` of event `k`. `None` when none fires.
    pub fn check_custom<F: FnMut(f64, &State) -> State>(
        &mut self,
        integ: &mut RungeKutta<13, F>,
    ) -> Option<Acted> {
        if !self.off_rail || self.custom.is_empty() {
            return None;
        }
        let (t0, t1) = (integ.t_old(), integ.t());
        let (y0, y1) = (*integ.y_old(), *integ.y());
        let mut first: Option<(usize, f64)> = None;
        for (k, (event, fired)) in self.custom.iter().enumerate() {
            if *fired || !(event.value(t0, &y0) >= 0.0 && event.value(t1, &y1) < 0.0) {
                continue;
            }
            let t = bisect(t0, t1, |t| event.value(t, &integ.dense(t)));
            if first.is_none_or(|(_, t_first)| t < t_first) {
                first = Some((k, t));
            }
        }
        let (k, t) = first?;
        let (event, fired) = &mut self.custom[k];
        *fired = true;
        let action = event.fire(t, &integ.dense(t));
        Some(Acted {
            process: self.first_record + k,
            action,
            t,
            control: None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hermite_root_of_a_cubic() {
        // p(τ) = τ³ − 0.5 on [0, 1]: root 0.5^(1/3).
        let r = root(Root::Hermite, 1.0, -0.5, 0.0, 0.5, 3.0).unwrap();
        assert!((r - 0.5f64.cbrt()).abs() < 1e-12);
        assert!(root(Root::Hermite, 1.0, 1.0, 0.0, 2.0, 0.0).is_none());
    }

    #[test]
    fn bisection_finds_the_downward_crossing() {
        let t = bisect(0.0, 2.0, |t| 1.0 - t * t);
        assert!((t - 1.0).abs() < 1e-15, "{t}");
        // The root returned is where the value is negative (or the root itself).
        assert!(1.0 - t * t <= 0.0);
    }

    #[test]
    fn linear_root_of_a_line() {
        let r = root(Root::Linear, 2.0, 3.0, 0.0, -1.0, 0.0).unwrap();
        assert!((r - 1.5).abs() < 1e-15);
    }
}
