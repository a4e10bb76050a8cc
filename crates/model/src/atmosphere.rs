//! The atmosphere the engine queries (docs/physics.md §4).

use karman_math::Cursor;

/// The atmosphere at one height, as the equations of motion use it
/// ([`AtmosphereModel::air`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Air {
    /// Air pressure, Pa.
    pub pressure: f64,
    /// Air density, kg/m³.
    pub density: f64,
    /// Speed of sound, m/s.
    pub speed_of_sound: f64,
    /// Gravity, m/s².
    pub gravity: f64,
}

/// Atmosphere, gravity and Earth rotation at the launch site (docs/physics.md §4). Heights are
/// geometric, metres above sea level. The methods marked "once" are read when a flight is
/// set up; the others are evaluated along the flight and allocate nothing.
pub trait AtmosphereModel {
    /// Launch elevation, m ASL (once).
    fn elevation(&self) -> f64;
    /// Air pressure, Pa.
    fn pressure(&self, z: f64) -> f64;
    /// Air density, kg/m³.
    fn density(&self, z: f64) -> f64;
    /// Speed of sound, m/s.
    fn speed_of_sound(&self, z: f64) -> f64;
    /// Dynamic viscosity, Pa·s.
    fn dynamic_viscosity(&self, z: f64) -> f64;
    /// Horizontal wind `(east, north)`, m/s.
    fn wind(&self, z: f64) -> [f64; 2];
    /// The wind when it is the same at every height, time and position, bit for bit what
    /// [`AtmosphereModel::wind`] and [`AtmosphereModel::wind_at`] return (once): the engine
    /// then skips the per-height lookups. `None` (the default) when it varies.
    fn uniform_wind(&self) -> Option<[f64; 2]> {
        None
    }
    /// The horizontal wind `(east, north)`, m/s, at time `t`, s, and position `position`
    /// (`(x, y, z)`, m, in the launch frame, `z` above sea level): what the equations of
    /// motion ask. The default is [`AtmosphereModel::wind`] at the height; a model that
    /// varies in time or across the launch frame overrides it (and returns `None` from
    /// [`AtmosphereModel::uniform_wind`]).
    #[inline]
    fn wind_at(&self, _t: f64, position: [f64; 3]) -> [f64; 2] {
        self.wind(position[2])
    }
    /// Gravity, m/s².
    fn gravity(&self, z: f64) -> f64;
    /// Pressure, density, speed of sound and gravity at once, equal to the individual
    /// methods; a model overrides it to share the height lookups.
    #[inline]
    fn air(&self, z: f64) -> Air {
        Air {
            pressure: self.pressure(z),
            density: self.density(z),
            speed_of_sound: self.speed_of_sound(z),
            gravity: self.gravity(z),
        }
    }
    /// [`AtmosphereModel::air`] with the height located from `cursor`, which the caller
    /// keeps between evaluations (updated): the same values whatever it holds. A model with
    /// tables overrides it to start its search where the last one ended; the default
    /// ignores it.
    #[inline]
    fn air_near(&self, z: f64, _cursor: &mut Cursor) -> Air {
        self.air(z)
    }
    /// The air at time `t`, s, and position `position` (`(x, y, z)`, m, launch frame), with
    /// the height located from `cursor` as [`AtmosphereModel::air_near`] does: what the
    /// equations of motion ask. The default is [`AtmosphereModel::air_near`] at the height;
    /// a model that varies in time or across the launch frame overrides it.
    #[inline]
    fn air_at(&self, _t: f64, position: [f64; 3], cursor: &mut Cursor) -> Air {
        self.air_near(position[2], cursor)
    }
    /// Earth rotation vector in the ENU launch frame, rad/s (once).
    fn earth_rotation_enu(&self) -> [f64; 3];
    /// Barometric height `h_baro(P)` of a (noisy) pressure, m ASL (docs/physics.md §4.4).
    fn barometric_height(&self, pressure: f64) -> f64;
}
