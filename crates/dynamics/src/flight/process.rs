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

use super::actions::Action;
use crate::DynamicsError;
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
    pub(super) fn of<F>(integ: &RungeKutta<13, F>, t_start: f64, t_end: f64) -> Self {
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
    /// Component `i` of the time derivative of the dense output at `t` inside the step (the
    /// interpolant's slope: a velocity component for `i < 3`, an acceleration for
    /// `3 ≤ i < 6`; it equals the right-hand side at the step's ends).
    fn derivative_component(&mut self, t: f64, i: usize) -> f64;
    /// The time derivative of the dense output at `t` inside the step.
    fn derivative(&mut self, t: f64) -> State {
        std::array::from_fn(|i| self.derivative_component(t, i))
    }
    /// The step's end: its time and the state stored there.
    fn step_end(&self) -> (f64, State);
    /// The right-hand side of the phase's equations at `(t, y)` (not an interpolant: the
    /// equations evaluated there, as RocketPy's `phase.derivative(t, y)`).
    fn right_hand_side(&mut self, t: f64, y: &State) -> State;
}

impl<F: FnMut(f64, &State) -> State> DenseOutput for RungeKutta<13, F> {
    #[inline]
    fn component(&mut self, t: f64, i: usize) -> f64 {
        self.dense_component(t, i)
    }
    fn state(&mut self, t: f64) -> State {
        self.dense(t)
    }
    fn derivative_component(&mut self, t: f64, i: usize) -> f64 {
        self.dense_derivative_component(t, i)
    }
    fn step_end(&self) -> (f64, State) {
        (self.t(), *self.y())
    }
    fn right_hand_side(&mut self, t: f64, y: &State) -> State {
        self.rhs_at(t, y)
    }
}

/// The flight at one sampling instant, as a process reads it: the dense values at the
/// instant, computed once for all the processes of its group, and the signal store the
/// processes publish to and read from.
pub struct Probe<'s> {
    t: f64,
    dense: &'s mut dyn DenseOutput,
    z: Option<f64>,
    vz: Option<f64>,
    signals: &'s mut Signals,
    /// The first output slot of the process being sampled, and its number of outputs.
    outputs: (usize, usize),
}

impl<'s> Probe<'s> {
    pub(super) fn new(t: f64, dense: &'s mut dyn DenseOutput, signals: &'s mut Signals) -> Self {
        Self {
            t,
            dense,
            z: None,
            vz: None,
            signals,
            outputs: (0, 0),
        }
    }

    /// Moves the probe to instant `t` (the dense values are read afresh there).
    pub(super) fn move_to(&mut self, t: f64) {
        self.t = t;
        self.z = None;
        self.vz = None;
    }

    /// The process `p` is sampled next: [`Probe::publish`] writes its outputs.
    #[inline]
    pub(super) fn sampling(&mut self, p: usize) {
        self.outputs = self.signals.outputs_of(p);
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

    /// The time derivative of the state at the instant, from the dense output
    /// ([`DenseOutput::derivative`]): the inertial acceleration is components 3–5.
    pub fn derivative(&mut self) -> State {
        self.dense.derivative(self.t)
    }

    /// The state at the instant and the right-hand side of the phase's equations there
    /// ([`DenseOutput::right_hand_side`]): RocketPy's `(u, u_dot)` at a time node, which its
    /// sensors measure from (docs/physics.md §29.2). The right-hand side is evaluated afresh
    /// at each call.
    pub fn state_and_rhs(&mut self) -> (State, State) {
        let state = self.dense.state(self.t);
        let rhs = self.dense.right_hand_side(self.t, &state);
        (state, rhs)
    }

    /// The inertial acceleration `v̇` at the instant, m/s² (the dense output's slope).
    pub fn acceleration(&mut self) -> [f64; 3] {
        let t = self.t;
        std::array::from_fn(|i| self.dense.derivative_component(t, 3 + i))
    }

    /// The end of the integration step holding the instant: its time and state (RocketPy's
    /// last stored solution row, `state_history[-1]`, docs/physics.md §16.4).
    #[must_use]
    pub fn step_end(&self) -> (f64, State) {
        self.dense.step_end()
    }

    /// Publishes `value` on output `output` of the process being sampled (an index into its
    /// [`SampledProcess::outputs`]; an index beyond them is ignored), stamped with the
    /// instant: the processes sampled after it read it with [`Probe::read`].
    pub fn publish(&mut self, output: usize, value: f64) {
        let (first, count) = self.outputs;
        if output < count {
            self.signals.values[first + output] = Some(Signal { t: self.t, value });
        }
    }

    /// The last value published on a signal, with its instant; `None` before the first.
    #[must_use]
    pub fn read(&self, id: SignalId) -> Option<Signal> {
        self.signals.read(id)
    }
}

/// A value a process published ([`Probe::publish`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Signal {
    /// The instant it was published at, s.
    pub t: f64,
    /// The value.
    pub value: f64,
}

/// A signal of the store, found by name with [`Connections::signal`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SignalId(usize);

/// The signal store: the last value of every output of every sampled process. A process
/// publishes at its instants; the processes sampled after it in the flight's sampling order
/// (time order, ties in process order) read the latest value. Sized when the flight is set
/// up: publishing and reading allocate nothing.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Signals {
    /// `(name, process)` of every output, in slot order.
    names: Vec<(String, usize)>,
    /// The first slot of each process.
    first: Vec<usize>,
    values: Vec<Option<Signal>>,
}

impl Signals {
    /// The store of `outputs`, the output names of each process in process order.
    ///
    /// # Errors
    /// [`DynamicsError::DuplicateSignal`] when two outputs share a name.
    pub(super) fn new<'n>(
        outputs: impl IntoIterator<Item = &'n [&'n str]>,
    ) -> Result<Self, DynamicsError> {
        let mut store = Self::default();
        for (p, names) in outputs.into_iter().enumerate() {
            store.first.push(store.names.len());
            for name in names {
                if store.names.iter().any(|(n, _)| n == name) {
                    return Err(DynamicsError::DuplicateSignal {
                        name: (*name).to_string(),
                    });
                }
                store.names.push(((*name).to_string(), p));
            }
        }
        store.first.push(store.names.len());
        store.values = vec![None; store.names.len()];
        Ok(store)
    }

    /// The first slot of process `p` and its number of outputs.
    #[inline]
    fn outputs_of(&self, p: usize) -> (usize, usize) {
        match (self.first.get(p), self.first.get(p + 1)) {
            (Some(&a), Some(&b)) => (a, b - a),
            _ => (0, 0),
        }
    }

    /// The signal named `name`.
    #[must_use]
    pub fn id(&self, name: &str) -> Option<SignalId> {
        self.names.iter().position(|(n, _)| n == name).map(SignalId)
    }

    /// The last value published on `id`.
    #[must_use]
    pub fn read(&self, id: SignalId) -> Option<Signal> {
        self.values.get(id.0).copied().flatten()
    }
}

/// What a process may connect to when the flight is set up
/// ([`SampledProcess::connect`]): the signals of the flight's processes and the control
/// channels the vehicle declares ([`VehicleModel::control_channels`]).
///
/// [`VehicleModel::control_channels`]: karman_model::VehicleModel::control_channels
pub struct Connections<'c> {
    pub(super) signals: &'c Signals,
    pub(super) controls: &'c [&'c str],
}

impl Connections<'_> {
    /// The signal published as `name` by one of the flight's processes.
    ///
    /// # Errors
    /// [`DynamicsError::Unconnected`] when no process publishes it.
    pub fn signal(&self, name: &str) -> Result<SignalId, DynamicsError> {
        self.signals
            .id(name)
            .ok_or_else(|| DynamicsError::Unconnected {
                kind: "signal",
                name: name.to_string(),
            })
    }

    /// The index of the vehicle's control channel `name` (what [`Action::SetControl`]
    /// takes).
    ///
    /// # Errors
    /// [`DynamicsError::Unconnected`] when the vehicle declares no such channel.
    pub fn control(&self, name: &str) -> Result<usize, DynamicsError> {
        self.controls
            .iter()
            .position(|c| *c == name)
            .ok_or_else(|| DynamicsError::Unconnected {
                kind: "control channel",
                name: name.to_string(),
            })
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
    /// The names of the values the process publishes ([`Probe::publish`] takes an index
    /// into them), unique in the flight. Default: none.
    fn outputs(&self) -> &[&str] {
        &[]
    }
    /// Called once when the flight is set up, after every process has declared its outputs:
    /// the process looks up the signals it reads and the control channels it sets.
    ///
    /// # Errors
    /// What is missing ([`DynamicsError::Unconnected`]): the flight does not start.
    fn connect(&mut self, _connections: &Connections<'_>) -> Result<(), DynamicsError> {
        Ok(())
    }
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
    /// Whether the process is sampled at the first instant group of a `clear` phase, the
    /// group at which an action ended the previous phase (a parachute deployed, a control
    /// set): the processes after the acting one in that group were not sampled there before
    /// the cut. A sensor is (RocketPy clears only the parachutes and callbacks of that node);
    /// it must then come after every process that may act, so that it is sampled once.
    /// Default: false.
    fn sampled_at_cleared_start(&self) -> bool {
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
