//! What may change during a flight without changing the form of the equations: control
//! inputs and deployed recovery devices.

/// Number of control inputs a [`Configuration`] carries (a fixed array: the configuration is
/// copied into every flight phase and solution point without allocating).
pub const MAX_CONTROLS: usize = 4;

/// The state of a vehicle's discrete inputs at one instant: control inputs set by sampled
/// processes (e.g. an air-brake deployment level in `[0, 1]`, entering the axial load through
/// [`crate::VehicleModel::axial_load`]), and the recovery devices deployed so far.
///
/// The engine holds it constant over a flight phase; an action that changes it starts a new
/// phase at that instant (the right-hand side jumps there).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Configuration {
    /// Control inputs in the vehicle's order; 0 when unset.
    pub controls: [f64; MAX_CONTROLS],
    /// Recovery devices deployed, bit `i` for parachute `i` of [`crate::VehicleSetup`].
    pub deployed: u64,
}

impl Configuration {
    /// Control input `index`, or 0 when out of range.
    #[must_use]
    pub fn control(&self, index: usize) -> f64 {
        self.controls.get(index).copied().unwrap_or(0.0)
    }

    /// Whether recovery device `index` has been deployed.
    #[must_use]
    pub fn is_deployed(&self, index: usize) -> bool {
        index < 64 && self.deployed & (1 << index) != 0
    }

    /// This configuration with device `index` marked deployed (indices from 64 on are not
    /// recorded).
    #[must_use]
    pub fn with_deployed(mut self, index: usize) -> Self {
        if index < 64 {
            self.deployed |= 1 << index;
        }
        self
    }

    /// This configuration with control `index` set to `value`; `None` when `index` is not
    /// below [`MAX_CONTROLS`].
    #[must_use]
    pub fn with_control(mut self, index: usize, value: f64) -> Option<Self> {
        *self.controls.get_mut(index)? = value;
        Some(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn controls_and_devices_are_recorded() {
        let c = Configuration::default()
            .with_deployed(3)
            .with_control(1, 0.5)
            .expect("in range");
        assert!(c.is_deployed(3) && !c.is_deployed(2) && !c.is_deployed(70));
        assert!((c.control(1) - 0.5).abs() < 1e-15);
        assert!(c.control(9).abs() < 1e-15);
        assert!(c.with_control(MAX_CONTROLS, 1.0).is_none());
        assert_eq!(c.with_deployed(64), c);
    }
}
