//! Sampled processes: discrete processes sampled at a rate during the flight, on the dense
//! output of the integration steps (RocketPy's overshootable time nodes, docs/physics.md §9.4),
//! whose samples may return an [`Action`].
//!
//! The instants of a process are `j / rate` (`j` an integer), keyed to 1e-7 s as RocketPy's
//! `TimeNodes.merge` does: the instants of all active processes inside a step are merged in
//! time order (ties in process order) and grouped by key, each group evaluated at its first
//! instant; the first group of a `clear` phase belongs to the previous phase, the group at
//! the step end to the next step. A process passes whole steps over with bounds: with
//! [`SampledProcess::cannot_act`] it has no instants in the step at all; with
//! [`SampledProcess::first_candidate`] its earlier instants keep their place in the merge but
//! are only counted ([`SampledProcess::pass_over`]), not sampled.

use super::Action;
use super::actions::Acted;
use super::phases::Phase;
use super::run::Run;
use crate::integrator::RungeKutta;
use crate::state::State;

/// Bounds of the vertical speed and the height over the last accepted step, from its end
/// values widened by `h · max|derivative|` at the ends, a generous allowance for the dense
/// output between them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepBounds {
    /// The sampling window `[t_start, t_end]`, s: the step's, from the apogee on in the step
    /// that holds the apogee (the last two stored points).
    pub t: [f64; 2],
    /// `[low, high]` of `v_z`, m/s.
    pub vz: [f64; 2],
    /// `[low, high]` of `z`, m ASL.
    pub z: [f64; 2],
}

impl StepBounds {
    /// The bounds of the last step of `integ`, whose sampling window is `[t_start, t_end]`.
    fn of<F>(integ: &RungeKutta<13, F>, t_start: f64, t_end: f64) -> Self {
        let (y0, y1) = (integ.y_old(), integ.y());
        let (f0, f1) = (integ.f_old(), integ.f());
        let h = integ.last_step();
        let bounds = |a: f64, b: f64, slope: f64| [a.min(b) - h * slope, a.max(b) + h * slope];
        Self {
            t: [t_start, t_end],
            vz: bounds(y0[5], y1[5], f0[5].abs().max(f1[5].abs())),
            z: bounds(y0[2], y1[2], y0[5].abs().max(y1[5].abs())),
        }
    }
}

/// The dense output of the last accepted step (docs/physics.md §10.3).
pub trait DenseOutput {
    /// Component `i` of the state at `t` inside the step.
    fn component(&mut self, t: f64, i: usize) -> f64;
    /// The state at `t` inside the step.
    fn state(&mut self, t: f64) -> State;
    /// The step's end: its time and the state stored there.
    fn step_end(&self) -> (f64, State);
}

impl<F: FnMut(f64, &State) -> State> DenseOutput for RungeKutta<13, F> {
    #[inline]
    fn component(&mut self, t: f64, i: usize) -> f64 {
        self.dense_component(t, i)
    }
    fn state(&mut self, t: f64) -> State {
        self.dense(t)
    }
    fn step_end(&self) -> (f64, State) {
        (self.t(), *self.y())
    }
}

/// The flight at one sampling instant, as a process reads it: the dense values at the
/// instant, computed once for all the processes of its group.
pub struct Probe<'s> {
    t: f64,
    dense: &'s mut dyn DenseOutput,
    z: Option<f64>,
    vz: Option<f64>,
}

impl<'s> Probe<'s> {
    pub(super) fn new(t: f64, dense: &'s mut dyn DenseOutput) -> Self {
        Self {
            t,
            dense,
            z: None,
            vz: None,
        }
    }

    /// The instant, s.
    #[must_use]
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Height `z`, m ASL.
    pub fn z(&mut self) -> f64 {
        let (t, dense) = (self.t, &mut self.dense);
        *self.z.get_or_insert_with(|| dense.component(t, 2))
    }

    /// Vertical speed `v_z`, m/s.
    pub fn vz(&mut self) -> f64 {
        let (t, dense) = (self.t, &mut self.dense);
        *self.vz.get_or_insert_with(|| dense.component(t, 5))
    }

    /// The whole state (docs/physics.md §3).
    pub fn state(&mut self) -> State {
        self.dense.state(self.t)
    }

    /// The end of the integration step holding the instant: its time and state (RocketPy's
    /// last stored solution row, `state_history[-1]`, docs/physics.md §16.4).
    #[must_use]
    pub fn step_end(&self) -> (f64, State) {
        self.dense.step_end()
    }
}

/// A discrete process sampled at a fixed rate during the flight: a parachute trigger, a
/// controller, a sensor. Its instants are `j / rate`; the engine merges them with the other
/// processes' (module documentation) and calls, per step:
/// [`SampledProcess::cannot_act`], then (if it can) [`SampledProcess::first_candidate`],
/// then in time order [`SampledProcess::pass_over`] or [`SampledProcess::sample`] for each
/// instant, and [`SampledProcess::end_step`] when the step's instants are done (or one acted).
///
/// Contract: the process's state depends on the instants it is given and on its own inputs
/// only (a noise stream's draws on its seed and index), so a flight replays bit for bit.
pub trait SampledProcess {
    /// Sampling rate, Hz (a process with a rate that is not positive is never sampled).
    fn rate(&self) -> f64;
    /// Whether the process is sampled on the launch rail too (a controller is: RocketPy
    /// calls controllers in every phase). Default: false, sampling starts at rail exit.
    fn on_rail(&self) -> bool {
        false
    }
    /// Whether the process is sampled over the whole step that holds the apogee. RocketPy
    /// starts that step's window at the apogee (docs/physics.md §9.4's quirk, harmless for the
    /// built-in triggers, which need `v_z < 0`); a condition that may hold on the ascent
    /// (a custom trigger, a controller) is sampled from the step's start, so that its instants
    /// do not depend on where the solver's steps fall. Default: false.
    fn whole_step(&self) -> bool {
        false
    }
    /// Whether the process certainly cannot act anywhere in the step with these bounds: it
    /// then has no instants there (not even for the merge). Default: false.
    fn cannot_act(&self, _bounds: &StepBounds) -> bool {
        false
    }
    /// The first of the step's instants `j ∈ [next, last]` at which the process may act
    /// (`last + 1` when none): the instants before it are passed over. Default: `next`.
    fn first_candidate(
        &mut self,
        next: i64,
        _last: i64,
        _bounds: &StepBounds,
        _dense: &mut dyn DenseOutput,
    ) -> i64 {
        next
    }
    /// `count` instants passed over without a sample (a noise stream advances its state).
    fn pass_over(&mut self, _count: usize) {}
    /// Samples the process at the probe's instant; an action ends the step there (except
    /// [`Action::Record`]).
    fn sample(&mut self, probe: &mut Probe<'_>) -> Option<Action>;
    /// The step's instants are done (up to the one that acted, if any).
    fn end_step(&mut self) {}
    /// Whether the process is over (e.g. a parachute deployed): it is no longer sampled.
    fn is_done(&self) -> bool {
        false
    }
    /// Test-only: the sample of the unbounded reference evaluation, which draws every
    /// instant (default: [`SampledProcess::sample`]).
    #[cfg(test)]
    fn sample_directly(&mut self, probe: &mut Probe<'_>) -> Option<Action> {
        self.sample(probe)
    }
}

/// Key of a sampling instant rounded to 1e-7 s (RocketPy's `TimeNodes.merge`): `(t·1e7)`
/// rounded half away from zero, as `f64::round` does, without its libm call.
#[inline]
pub(super) fn node_key(t: f64) -> i64 {
    let x = t * 1e7;
    if x.abs() >= 4_503_599_627_370_496.0 {
        // Already an integer (or infinite: the cast saturates, as after `round`).
        return x as i64;
    }
    // Below 2^52 the truncation and the fraction it leaves are exact.
    let whole = x as i64;
    let fraction = x - whole as f64;
    whole + i64::from(fraction >= 0.5) - i64::from(fraction <= -0.5)
}

/// The sampling instants `j · interval`, `j = next..=last`, of one process in the last step.
#[derive(Debug, Clone, Copy)]
pub(super) struct Instants {
    /// Process index.
    pub p: usize,
    /// Sampling interval `1 / rate`, s.
    pub interval: f64,
    /// Next instant to evaluate.
    pub next: i64,
    /// Last instant to evaluate.
    pub last: i64,
    /// First instant at which the process may act: the bounds exclude the instants before
    /// it (`last + 1` when they exclude the whole step).
    pub first_candidate: i64,
}

impl Instants {
    /// Time of instant `j`, s (computed as RocketPy's node list does, `j · Δ`).
    #[inline]
    pub fn time(&self, j: i64) -> f64 {
        j as f64 * self.interval
    }

    /// Number of instants left.
    #[inline]
    fn count(&self) -> usize {
        usize::try_from(self.last - self.next + 1).unwrap_or(0)
    }

    /// Whether the process may act at one of the instants left.
    #[inline]
    fn may_act(&self) -> bool {
        self.first_candidate <= self.last
    }
}

impl Run<'_> {
    /// The sampled processes' instants of the last step (docs/physics.md §9.4, RocketPy's
    /// `__process_overshootable_nodes`): the first action, with its process and instant.
    ///
    /// Before any instant is evaluated each process is bounded over the step
    /// ([`SampledProcess::cannot_act`], [`SampledProcess::first_candidate`]); when none may
    /// act the step's instants are only passed over; otherwise they are evaluated in order,
    /// those before a process's first candidate only passed over. Recorded values
    /// ([`Action::Record`]) are stored on the way and do not end the step; nor does a value
    /// set for after the step ([`Action::SetControlAfterStep`]), which goes with the action
    /// that ends the step, if one does ([`Acted::control`]).
    pub(super) fn sample_processes<F: FnMut(f64, &State) -> State>(
        &mut self,
        integ: &mut RungeKutta<13, F>,
        phase: &Phase,
        rail: bool,
    ) -> Option<Acted> {
        if self.active.is_empty() {
            return None;
        }
        let n = self.points.len();
        let bounds = StepBounds::of(integ, self.points[n - 2].t, self.points[n - 1].t);
        let [t_start, t_end] = bounds.t;
        // The instants of this step by their keys, so that one at the step end is deferred to
        // the next step and found there whatever the rounding of t/Δ.
        let (k_start, k_end) = (node_key(t_start), node_key(t_end));
        self.instants.clear();
        let mut first = f64::INFINITY;
        for &p in &self.active {
            let process = &self.processes[p];
            if (rail && !process.on_rail()) || process.cannot_act(&bounds) {
                continue;
            }
            let interval = 1.0 / process.rate();
            let (t_start, k_start) = if process.whole_step() {
                (integ.t_old(), node_key(integ.t_old()))
            } else {
                (t_start, k_start)
            };
            let mut range = Instants {
                p,
                interval,
                next: (t_start / interval).floor() as i64 - 1,
                last: (t_end / interval).ceil() as i64 + 1,
                first_candidate: 0,
            };
            // The keys grow with j: the instants in the window form one run of j.
            while range.next <= range.last && node_key(range.time(range.next)) < k_start {
                range.next += 1;
            }
            while range.last >= range.next && node_key(range.time(range.last)) > k_end {
                range.last -= 1;
            }
            if range.count() > 0 {
                first = first.min(range.time(range.next));
                self.instants.push(range);
            }
        }
        if self.instants.is_empty() {
            return None;
        }
        // The first group is cleared when it sits on the start of a `clear` phase; the group
        // at the step end is evaluated with the next step.
        let first_key = node_key(first);
        let skip_first = phase.clear && (first - phase.t).abs() < 1e-9;
        let mut any_may_act = false;
        for range in &mut self.instants {
            while skip_first
                && range.next <= range.last
                && node_key(range.time(range.next)) == first_key
            {
                range.next += 1;
            }
            while range.last >= range.next && node_key(range.time(range.last)) == k_end {
                range.last -= 1;
            }
            range.first_candidate =
                self.processes[range.p].first_candidate(range.next, range.last, &bounds, integ);
            any_may_act |= range.may_act();
        }
        if !any_may_act {
            for range in &self.instants {
                let process = &mut self.processes[range.p];
                process.pass_over(range.count());
                process.end_step();
            }
            return None;
        }
        if let [range] = self.instants.as_mut_slice() {
            // One process: the instants before its first candidate are passed over at once
            // (with several, they still take part in the grouping of the instants by key).
            let passed = range.first_candidate.min(range.last + 1) - range.next;
            if passed > 0 {
                range.next += passed;
                self.processes[range.p].pass_over(usize::try_from(passed).unwrap_or(0));
            }
        }
        let mut group_key = None;
        let mut t_node = 0.0;
        let mut after_step = None;
        let mut probe = Probe::new(0.0, integ);
        let acted = loop {
            // The earliest instant left; ties go to the earlier process.
            let mut earliest: Option<(usize, f64)> = None;
            for (k, range) in self.instants.iter().enumerate() {
                if range.next > range.last {
                    continue;
                }
                let t = range.time(range.next);
                if earliest.is_none_or(|(_, t_min)| t < t_min) {
                    earliest = Some((k, t));
                }
            }
            // None once every instant is evaluated: no action.
            let Some((k, t)) = earliest else {
                break None;
            };
            let range = &mut self.instants[k];
            let j = range.next;
            range.next += 1;
            let key = node_key(t);
            if group_key != Some(key) {
                group_key = Some(key);
                t_node = t;
                probe = Probe::new(t_node, probe.dense);
            }
            let p = range.p;
            if j < range.first_candidate {
                self.processes[p].pass_over(1);
                continue;
            }
            match self.processes[p].sample(&mut probe) {
                Some(Action::Record { channel, value }) => self.record(p, channel, value, t_node),
                Some(Action::SetControlAfterStep { index, value }) => {
                    after_step = Some((p, index, value));
                }
                Some(action) => break Some((p, action, t_node)),
                None => {}
            }
        };
        for range in &self.instants {
            self.processes[range.p].end_step();
        }
        // A value set for after the step takes effect at its end, or, when an action ended the
        // step earlier, from that action's instant (the later phases start there).
        match acted {
            Some((process, action, t)) => Some(Acted {
                process,
                action,
                t,
                control: after_step.map(|(_, index, value)| (index, value)),
            }),
            None => after_step.map(|(process, index, value)| Acted {
                process,
                action: Action::SetControlAfterStep { index, value },
                t: t_end,
                control: None,
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn node_keys_round_as_f64_round() {
        let mut times = vec![
            0.0,
            -0.0,
            1e-8,
            5e-8,
            1.5e-7,
            2.5e-7,
            -2.5e-7,
            0.123_456_75,
            1e300,
        ];
        times.extend([
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            4.503_599_627_370_497e8,
        ]);
        // Halves and their neighbours at many scales, and a dense sweep.
        for k in 0..2000 {
            let half = (f64::from(k) + 0.5) * 1e-7 * 1.37f64.powi(k % 60);
            times.extend([half, f64::from_bits(half.to_bits() + 1), -half]);
            times.push(f64::from(k) * 0.012_345_678_9);
        }
        for t in times {
            assert_eq!(super::node_key(t), (t * 1e7).round() as i64, "{t}");
        }
    }
}
