//! [`karman_model::AtmosphereModel`] for [`Environment`]: the atmosphere as the flight engine
//! queries it (the inherent methods, with the height searches of one evaluation shared).

use karman_math::Cursor;
use karman_model::{Air, AtmosphereModel};

use crate::Environment;

impl AtmosphereModel for Environment {
    #[inline]
    fn elevation(&self) -> f64 {
        Environment::elevation(self)
    }
    #[inline]
    fn pressure(&self, z: f64) -> f64 {
        Environment::pressure(self, z)
    }
    #[inline]
    fn density(&self, z: f64) -> f64 {
        Environment::density(self, z)
    }
    #[inline]
    fn speed_of_sound(&self, z: f64) -> f64 {
        Environment::speed_of_sound(self, z)
    }
    #[inline]
    fn dynamic_viscosity(&self, z: f64) -> f64 {
        Environment::dynamic_viscosity(self, z)
    }
    #[inline]
    fn wind(&self, z: f64) -> [f64; 2] {
        Environment::wind(self, z)
    }
    #[inline]
    fn air(&self, z: f64) -> Air {
        AtmosphereModel::air_near(self, z, &mut Cursor::default())
    }
    #[inline]
    fn air_near(&self, z: f64, cursor: &mut Cursor) -> Air {
        let s = Environment::air_near(self, z, cursor);
        Air {
            pressure: s.pressure,
            density: s.density,
            speed_of_sound: s.speed_of_sound,
            gravity: s.gravity,
        }
    }
    fn uniform_wind(&self) -> Option<[f64; 2]> {
        Environment::uniform_wind(self)
    }
    #[inline]
    fn gravity(&self, z: f64) -> f64 {
        Environment::gravity(self, z)
    }
    #[inline]
    fn earth_rotation_enu(&self) -> [f64; 3] {
        Environment::earth_rotation_enu(self)
    }
    #[inline]
    fn barometric_height(&self, pressure: f64) -> f64 {
        Environment::barometric_height(self, pressure)
    }
}
