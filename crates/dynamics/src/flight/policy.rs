//! The integrator policy: which Runge–Kutta pair flies which stretch of a phase (see
//! [`crate::integrator`] and docs/physics.md §26.5; the measurements behind it are in
//! docs/performance.md, "Integrators").

use super::schedule::PhaseKind;
use crate::integrator::{Pair, RungeKutta};

/// DOP853 gives way to DOPRI5 for the rest of a phase once more than one in this many of
/// its attempted steps were rejected (a right-hand side with kinks).
const KINK_WINDOW: usize = 8;

/// Under a parachute DOPRI5 gives way to the Runge–Kutta–Chebyshev method once this many
/// accepted steps in a row had `h |λ|` ([`RungeKutta::stiffness`]) of at least
/// [`STIFF_BOUND`]…
const STIFF_STEPS: usize = 3;
/// …90 % of the reach of DOPRI5's stability region along the negative real axis (≈ 3.3): the
/// steps are then held back by stability, not accuracy.
const STIFF_BOUND: f64 = 3.0;

/// The pair choice within one phase: DOPRI5 on the rail, through the burn and under
/// parachutes until its steps are bound by stability, then RKC; DOP853 for the unpowered
/// free flight (6 DOF or point mass), handed back to DOPRI5 when its steps keep being
/// rejected.
#[derive(Debug, Clone, Copy)]
pub(super) struct Policy {
    /// A free-flight phase (6 DOF or point mass) that started before burn-out and has not
    /// passed it yet.
    burning: bool,
    /// A parachute descent (the RKC hand-over applies).
    descent: bool,
    /// Accepted DOPRI5 steps in a row held back by stability.
    stiff_steps: usize,
    /// Burn-out time, s.
    burn_out: f64,
}

impl Policy {
    /// The policy of a phase of `kind` starting at `t`, and the pair it starts with.
    pub fn new(kind: PhaseKind, t: f64, burn_out: f64) -> (Self, Pair) {
        let free = matches!(kind, PhaseKind::SixDof | PhaseKind::PointMass { .. });
        let burning = free && t < burn_out;
        let pair = if free && !burning {
            Pair::Dop853
        } else {
            Pair::Dopri5
        };
        let policy = Self {
            burning,
            descent: matches!(kind, PhaseKind::Parachute(_)),
            stiff_steps: 0,
            burn_out,
        };
        (policy, pair)
    }

    /// Before a step from `t` (phase bound `t_bound`): the pair the rest of the phase goes on
    /// with, when it changes here.
    pub fn switch<F>(&mut self, integ: &RungeKutta<13, F>, t: f64, t_bound: f64) -> Option<Pair> {
        if self.burning && t >= self.burn_out && t < t_bound {
            // The unpowered rest of the phase goes on with the eighth-order pair.
            self.burning = false;
            Some(Pair::Dop853)
        } else if integ.pair() == Pair::Dop853 && t < t_bound {
            let (rejected, tried) = (
                integ.rejected_steps(),
                integ.steps() + integ.rejected_steps(),
            );
            (tried >= KINK_WINDOW && rejected * KINK_WINDOW > tried).then_some(Pair::Dopri5)
        } else if self.stiff_steps >= STIFF_STEPS && t < t_bound {
            // The rest of the descent goes on with the stabilized pair.
            self.stiff_steps = 0;
            Some(Pair::Rkc2)
        } else {
            None
        }
    }

    /// After an accepted step: counts the DOPRI5 descent steps held back by stability.
    pub fn accepted<F>(&mut self, integ: &RungeKutta<13, F>) {
        if self.descent && integ.pair() == Pair::Dopri5 {
            self.stiff_steps = if integ.stiffness() >= STIFF_BOUND {
                self.stiff_steps + 1
            } else {
                0
            };
        }
    }
}
