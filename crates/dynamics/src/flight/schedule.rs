//! The schedule of a flight: its phases in time order, each with the equations
//! ([`PhaseKind`]) and the [`Configuration`] it flies; an action or an event that changes
//! either inserts a phase, and the end of the flight is the last phase's bound.

use karman_model::{AtmosphereModel, Configuration, MAX_CONTROLS, VehicleModel};

use crate::equations::{CanopyState, Cursors, Derivative, Equations};
use crate::settings::{FlightSettings, SimulationMode};
use crate::state::State;

/// Which equations of motion a phase integrates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PhaseKind {
    /// 1-DOF slide along the rail (docs/physics.md §8.1).
    Rail,
    /// 6-DOF variable-mass flight (§8.2).
    SixDof,
    /// 3-DOF point-mass flight (§8.5, [`SimulationMode::ThreeDof`]) with this weathercock
    /// coefficient, 1/s.
    PointMass {
        /// [`FlightSettings::weathercock_coefficient`].
        weathercock: f64,
    },
    /// 3-DOF descent under the given canopy (§8.4), or a tumbling body ([`Action::Tumble`](crate::Action::Tumble):
    /// its drag area, no added mass).
    Parachute(CanopyState),
}

impl PhaseKind {
    /// The free flight (from rail exit until a canopy opens) the settings ask for.
    #[must_use]
    pub fn free_flight(settings: &FlightSettings) -> Self {
        match settings.simulation_mode {
            SimulationMode::SixDof => Self::SixDof,
            SimulationMode::ThreeDof => Self::PointMass {
                weathercock: settings.weathercock_coefficient,
            },
        }
    }

    /// Whether the phase's equations read the configuration's control inputs (the air
    /// brakes' level, docs/physics.md §16.1): the free flight, 6-DOF or point mass. The rail's
    /// equations drop them and a canopy's descent has none.
    #[must_use]
    pub fn reads_controls(&self) -> bool {
        matches!(self, Self::SixDof | Self::PointMass { .. })
    }
}

/// Evaluates the equations of a phase in a configuration.
#[inline(always)]
pub(crate) fn evaluate<A: AtmosphereModel, V: VehicleModel>(
    eq: &Equations<'_, A, V>,
    kind: &PhaseKind,
    configuration: &Configuration,
    t: f64,
    u: &State,
    cursors: &mut Cursors,
) -> Derivative {
    match kind {
        PhaseKind::Rail => eq.rail(t, u, configuration, cursors),
        PhaseKind::SixDof => eq.six_dof(t, u, configuration, cursors),
        PhaseKind::PointMass { weathercock } => {
            eq.point_mass(t, u, *weathercock, configuration, cursors)
        }
        PhaseKind::Parachute(canopy) => eq.parachute(t, u, canopy, cursors),
    }
}

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

/// The phases of a flight in strictly increasing start times, the last one its final bound.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Schedule {
    phases: Vec<Phase>,
}

impl Schedule {
    /// One phase from `first.t` to the final bound at `end`.
    pub fn new(first: Phase, end: f64) -> Self {
        Self {
            phases: vec![first, Phase::end(end)],
        }
    }

    /// Number of entries, the final bound included.
    pub fn len(&self) -> usize {
        self.phases.len()
    }

    /// Entry `index` (a phase or the final bound).
    pub fn get(&self, index: usize) -> Option<&Phase> {
        self.phases.get(index)
    }

    /// Inserts a phase before index `index` keeping start times strictly increasing; ties
    /// are shifted by 1e-7 s as RocketPy's `FlightPhases.add` does. A phase at or after the
    /// final bound is dropped (the flight ends first).
    pub fn insert(&mut self, mut index: usize, mut phase: Phase) {
        let phases = &mut self.phases;
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

    /// Ends the flight at phase `index`: every later phase is replaced by a final bound at
    /// `t`.
    pub fn end_at(&mut self, index: usize, t: f64) {
        self.phases.truncate(index + 1);
        self.phases.push(Phase::end(t));
    }

    /// The phases already scheduled after phase `index` fly control `control` at `value`.
    pub fn set_later_controls(&mut self, index: usize, control: usize, value: f64) {
        for later in &mut self.phases[index + 1..] {
            if later.kind.is_some() && control < MAX_CONTROLS {
                later.configuration.controls[control] = value;
            }
        }
    }
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
        let mut phases = Schedule::new(phase(0.0, PhaseKind::Rail), 600.0);
        phases.insert(1, phase(0.4, PhaseKind::SixDof));
        phases.insert(2, phase(0.4, PhaseKind::SixDof));
        phases.insert(1, phase(700.0, PhaseKind::SixDof));
        let ts: Vec<f64> = phases.phases.iter().map(|p| p.t).collect();
        assert_eq!(ts.len(), 4);
        assert!(ts.windows(2).all(|w| w[0] < w[1]), "{ts:?}");
        assert!((ts[2] - 0.4 - 1e-7).abs() < 1e-12);
    }
}
