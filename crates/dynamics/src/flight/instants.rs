//! The sampled processes of a flight and their instants in each step (docs/physics.md §9.4,
//! RocketPy's overshootable time nodes): the instants of every active process inside a step
//! are merged in time order (ties in process order), keyed to 1e-7 s as RocketPy's
//! `TimeNodes.merge` does, and grouped by key, each group evaluated at its first instant.

use super::actions::{Acted, Action};
use super::log::Log;
use super::process::{Probe, SampledProcess, Signals, StepBounds};
use super::schedule::Phase;
use crate::integrator::RungeKutta;
use crate::state::State;

/// The flight's sampled processes: the vehicle's parachute triggers, then the flight's own.
pub(super) struct Processes<'a> {
    pub list: Vec<Box<dyn SampledProcess + 'a>>,
    /// Indices of the processes still sampled, in order.
    pub active: Vec<usize>,
    /// The sampling instants of the last step, one range per process that samples it.
    pub instants: Vec<Instants>,
    /// What the processes publish and read.
    pub signals: Signals,
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

impl Processes<'_> {
    /// Process `p` is no longer sampled once it is done.
    pub fn retire_if_done(&mut self, p: usize) {
        if self.list[p].is_done() {
            self.active.retain(|&q| q != p);
        }
    }

    /// Collects into [`Processes::instants`] the instants inside the step of `bounds` (from
    /// its start `t_old` for a [`SampledProcess::whole_step`] process) of every active
    /// process that may sample it; returns the earliest.
    fn collect(&mut self, bounds: &StepBounds, t_old: f64, rail: bool) -> f64 {
        let [t_start, t_end] = bounds.t;
        // The instants of this step by their keys, so that one at the step end is deferred to
        // the next step and found there whatever the rounding of t/Δ.
        let (k_start, k_end) = (node_key(t_start), node_key(t_end));
        self.instants.clear();
        let mut first = f64::INFINITY;
        for &p in &self.active {
            let process = &self.list[p];
            if (rail && !process.on_rail()) || process.cannot_act(bounds) {
                continue;
            }
            let interval = 1.0 / process.rate();
            let (t_start, k_start) = if process.whole_step() {
                (t_old, node_key(t_old))
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
        first
    }

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
    pub fn sample<F: FnMut(f64, &State) -> State>(
        &mut self,
        integ: &mut RungeKutta<13, F>,
        phase: &Phase,
        rail: bool,
        log: &mut Log,
    ) -> Option<Acted> {
        if self.active.is_empty() {
            return None;
        }
        let (t_start, t_end) = log.last_step();
        let bounds = StepBounds::of(integ, t_start, t_end);
        let t_end = bounds.t[1];
        let first = self.collect(&bounds, integ.t_old(), rail);
        let k_end = node_key(t_end);
        if self.instants.is_empty() {
            return None;
        }
        // The first group is cleared when it sits on the start of a `clear` phase; the group
        // at the step end is evaluated with the next step.
        let first_key = node_key(first);
        let skip_first = phase.clear && (first - phase.t).abs() < 1e-9;
        let mut any_may_act = false;
        for range in &mut self.instants {
            let cleared = skip_first && !self.list[range.p].sampled_at_cleared_start();
            while cleared
                && range.next <= range.last
                && node_key(range.time(range.next)) == first_key
            {
                range.next += 1;
            }
            while range.last >= range.next && node_key(range.time(range.last)) == k_end {
                range.last -= 1;
            }
            range.first_candidate =
                self.list[range.p].first_candidate(range.next, range.last, &bounds, integ);
            any_may_act |= range.may_act();
        }
        if !any_may_act {
            for range in &self.instants {
                let process = &mut self.list[range.p];
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
                self.list[range.p].pass_over(usize::try_from(passed).unwrap_or(0));
            }
        }
        let mut group_key = None;
        let mut t_node = 0.0;
        let mut after_step = None;
        let mut probe = Probe::new(0.0, integ, &mut self.signals);
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
                probe.move_to(t_node);
            }
            let p = range.p;
            if j < range.first_candidate {
                self.list[p].pass_over(1);
                continue;
            }
            probe.sampling(p);
            match self.list[p].sample(&mut probe) {
                Some(Action::Record { channel, value }) => log.record(p, channel, value, t_node),
                Some(Action::SetControlAfterStep { index, value }) => {
                    after_step = Some((p, index, value));
                }
                Some(action) => break Some((p, action, t_node)),
                None => {}
            }
        };
        for range in &self.instants {
            self.list[range.p].end_step();
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
