//! Flight phases: the equations and the configuration each phase flies, in time order.

use karman_model::Configuration;

use super::PhaseKind;

/// A flight phase: start time, equations, configuration, and whether sampling instants at
/// its start are skipped (RocketPy's `clear`). The last phase of the list has no equations:
/// it is the flight's final time bound.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Phase {
    /// Start time, s.
    pub t: f64,
    /// The equations; `None` for the final bound.
    pub kind: Option<PhaseKind>,
    /// The configuration flown (control inputs, devices deployed).
    pub configuration: Configuration,
    /// Sampling instants at the phase start belong to the previous phase.
    pub clear: bool,
}

impl Phase {
    /// The final bound of a flight at `t`.
    pub fn end(t: f64) -> Self {
        Self {
            t,
            kind: None,
            configuration: Configuration::default(),
            clear: true,
        }
    }
}

/// Inserts a phase before index `index` keeping start times strictly increasing; ties are
/// shifted by 1e-7 s as RocketPy's `FlightPhases.add` does. A phase at or after the final
/// bound is dropped (the flight ends first).
pub(super) fn insert_phase(phases: &mut Vec<Phase>, mut index: usize, mut phase: Phase) {
    let Some(end) = phases.last().map(|p| p.t) else {
        return;
    };
    loop {
        if phase.t >= end {
            return;
        }
        if index == 0 {
            index = 1;
        }
        if index >= phases.len() {
            index = phases.len() - 1;
        }
        let prev = phases[index - 1].t;
        let next = phases[index].t;
        if prev < phase.t && phase.t < next {
            phases.insert(index, phase);
            return;
        }
        let tie = (phase.t - prev).abs() < f64::MIN_POSITIVE
            || (phase.t - next).abs() < f64::MIN_POSITIVE;
        let new_index = if phase.t < prev {
            index - 1
        } else if phase.t > next {
            index + 1
        } else {
            index
        };
        if tie {
            phase.t += 1e-7;
        }
        index = new_index;
    }
}

/// Ends the flight at phase `index`: every later phase is replaced by a final bound at `t`.
pub(super) fn end_at(phases: &mut Vec<Phase>, index: usize, t: f64) {
    phases.truncate(index + 1);
    phases.push(Phase::end(t));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phases_stay_sorted_and_ties_shift() {
        let phase = |t: f64, kind: PhaseKind| Phase {
            t,
            kind: Some(kind),
            configuration: Configuration::default(),
            clear: true,
        };
        let mut phases = vec![phase(0.0, PhaseKind::Rail), Phase::end(600.0)];
        insert_phase(&mut phases, 1, phase(0.4, PhaseKind::SixDof));
        insert_phase(&mut phases, 2, phase(0.4, PhaseKind::SixDof));
        insert_phase(&mut phases, 1, phase(700.0, PhaseKind::SixDof));
        let ts: Vec<f64> = phases.iter().map(|p| p.t).collect();
        assert_eq!(ts.len(), 4);
        assert!(ts.windows(2).all(|w| w[0] < w[1]), "{ts:?}");
        assert!((ts[2] - 0.4 - 1e-7).abs() < 1e-12);
    }
}
