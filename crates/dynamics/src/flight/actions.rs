//! Actions: what a sampled process's sample may do to the flight.

use karman_model::ParachuteSpec;

use super::log::{Log, ParachuteEvent, Termination};
use super::schedule::{Phase, PhaseKind, Schedule};
use crate::equations::CanopyState;
use crate::integrator::RungeKutta;
use crate::state::State;

/// What a sample may do. Every action but [`Action::Record`] ends the integration step at the
/// sample instant (the last point is rolled back there) and starts the phase that follows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Action {
    /// Deploy recovery device `i` (parachute `i` of the vehicle): after its lag the descent
    /// goes on under it (docs/physics.md §9.4, §8.4).
    DeployDevice(usize),
    /// Set control input `index` (`< MAX_CONTROLS`) of the configuration to `value` from this
    /// instant on; a bad index is ignored.
    SetControl {
        /// Control index.
        index: usize,
        /// New value.
        value: f64,
    },
    /// Set control input `index` to `value` from the end of the current integration step
    /// on: the step was integrated with the old value and stands (RocketPy's
    /// `time_overshoot = true`, docs/physics.md §16.4); the step's later instants are still
    /// sampled, and the last such value set in the step wins.
    SetControlAfterStep {
        /// Control index.
        index: usize,
        /// New value.
        value: f64,
    },
    /// The body tumbles from this instant on, to its end: a 3-DOF descent under the drag
    /// area `drag_area` (m²), the equations of a canopy without added mass (docs/physics.md §8.4);
    /// the tumble drag of a spent stage without recovery (Niskanen 2009, §3.5;
    /// docs/physics.md §23.4).
    Tumble {
        /// Drag coefficient times its area, m².
        drag_area: f64,
    },
    /// Separate stage `stage`: the flight ends here with [`Termination::Separation`], and each
    /// part goes on with [`crate::simulate_from`].
    SeparateStage(usize),
    /// Record `value` on the process's channel `channel` ([`crate::Flight::records`]); the
    /// step goes on.
    Record {
        /// The process's channel number.
        channel: usize,
        /// The value.
        value: f64,
    },
    /// End the flight here ([`Termination::Terminated`]).
    Terminate,
}

/// The first action of a step's samples ([`Run::sample_processes`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Acted {
    /// The process that acted.
    pub process: usize,
    /// Its action.
    pub action: Action,
    /// The sampling instant, s.
    pub t: f64,
    /// A control value `(index, value)` set for after the step
    /// ([`Action::SetControlAfterStep`]) at an earlier instant of the same step: the action
    /// ends the step at its instant, so the value acts from there, in the phases the action
    /// starts and in those already scheduled.
    pub control: Option<(usize, f64)>,
}

/// What an action acts on: the flight's schedule and log, and the vehicle's parachutes
/// (what [`Action::DeployDevice`] deploys).
pub(super) struct Target<'r> {
    pub schedule: &'r mut Schedule,
    pub log: &'r mut Log,
    pub parachutes: &'r [ParachuteSpec],
}

impl Target<'_> {
    /// Carries out the action `acted` inside the last step of phase `index`: the step is cut
    /// at its instant (except for [`Action::SetControlAfterStep`]), and the state the next
    /// phase starts from is returned.
    pub fn act<F: FnMut(f64, &State) -> State>(
        &mut self,
        integ: &mut RungeKutta<13, F>,
        acted: Acted,
        index: usize,
        phase: &Phase,
        kind: PhaseKind,
    ) -> (f64, State) {
        let Acted {
            process: p,
            action,
            t,
            control,
        } = acted;
        // A value set earlier in the step acts from the action's instant on.
        let controlled;
        let phase = match control.and_then(|(c, value)| {
            let configuration = phase.configuration.with_control(c, value)?;
            Some((c, value, configuration))
        }) {
            Some((c, value, configuration)) => {
                self.schedule.set_later_controls(index, c, value);
                controlled = Phase {
                    configuration,
                    ..*phase
                };
                &controlled
            }
            None => phase,
        };
        let cut = match action {
            // The step stands: the next phase starts from its end point.
            Action::SetControlAfterStep { .. } => (integ.t(), *integ.y()),
            _ => self.log.cut_step(integ, phase.configuration, kind, t),
        };
        match action {
            Action::DeployDevice(device) => self.deploy(device, index, phase, kind, t),
            Action::SetControl {
                index: control,
                value,
            } => {
                let set = |phase: &Phase| phase.configuration.with_control(control, value);
                if let Some(configuration) = set(phase) {
                    self.schedule.set_later_controls(index, control, value);
                    self.schedule.insert(
                        index + 1,
                        Phase {
                            t,
                            kind: Some(kind),
                            configuration,
                            clear: true,
                        },
                    );
                }
            }
            Action::SetControlAfterStep {
                index: control,
                value,
            } => {
                if let Some(configuration) = phase.configuration.with_control(control, value) {
                    self.schedule.set_later_controls(index, control, value);
                    // A phase at the step end, unless the next phase starts there anyway.
                    if self.schedule.get(index + 1).is_none_or(|next| next.t > t) {
                        self.schedule.insert(
                            index + 1,
                            Phase {
                                t,
                                kind: Some(kind),
                                configuration,
                                clear: false,
                            },
                        );
                    }
                }
            }
            Action::Tumble { drag_area } => self.tumble(drag_area, index, phase, t),
            Action::SeparateStage(stage) => {
                self.log.separation = Some((t, stage));
                self.end_flight(index, t, Termination::Separation);
            }
            Action::Terminate => self.end_flight(index, t, Termination::Terminated),
            Action::Record { channel, value } => self.log.record(p, channel, value, t),
        }
        cut
    }

    /// Ends the flight at phase `index` and `t` with `termination`.
    pub fn end_flight(&mut self, index: usize, t: f64, termination: Termination) {
        self.schedule.end_at(index, t);
        self.log.termination = termination;
    }

    /// Starts the tumbling descent under `drag_area` at `t` (once: a later tumble is ignored).
    fn tumble(&mut self, drag_area: f64, index: usize, phase: &Phase, t: f64) {
        if self.log.tumble.is_some() {
            return;
        }
        let canopy = CanopyState {
            cd_s: drag_area,
            radius: 0.0,
            height: 0.0,
            added_mass_coefficient: 0.0,
        };
        self.schedule.insert(
            index + 1,
            Phase {
                t,
                kind: Some(PhaseKind::Parachute(canopy)),
                configuration: phase.configuration,
                clear: true,
            },
        );
        self.log.tumble = Some(t);
    }

    /// Schedules a triggered parachute: an optional lag phase with the current equations,
    /// then the parachute phase (docs/physics.md §9.4).
    fn deploy(&mut self, device: usize, index: usize, phase: &Phase, kind: PhaseKind, t: f64) {
        let Some(spec) = self.parachutes.get(device) else {
            return;
        };
        let (lag, name) = (spec.lag, spec.name.clone());
        let canopy = CanopyState {
            cd_s: spec.cd_s,
            radius: spec.radius,
            height: spec.height,
            added_mass_coefficient: spec.added_mass_coefficient,
        };
        let configuration = phase.configuration.with_deployed(device);
        let mut at = index + 1;
        if lag != 0.0 {
            self.schedule.insert(
                at,
                Phase {
                    t,
                    kind: Some(kind),
                    configuration,
                    clear: true,
                },
            );
            at += 1;
        }
        self.schedule.insert(
            at,
            Phase {
                t: t + lag,
                kind: Some(PhaseKind::Parachute(canopy)),
                configuration,
                clear: false,
            },
        );
        // Without lag the parachute phase starts right at the node: it must follow the current
        // phase, which the insertion above guarantees.
        self.log.parachute_events.push(ParachuteEvent {
            name,
            trigger_time: t,
            inflation_time: t + lag,
        });
    }
}
