//! Enumerated string values of the mission format (atmosphere model, motor kind, nose kind,
//! coordinate systems, ...).
//!
//! RocketPy accepts several spellings of some values (`"von karman"`, `"Von Karman"`,
//! `"vonKarman"`); mission-format.md asks for all of them, so every enumeration here is read
//! case- and separator-insensitively: the text is lower-cased and spaces, `_` and `-` are
//! dropped before it is compared with the accepted spellings.

use serde::de::{self, Deserializer, Visitor};
use serde::{Deserialize, Serialize, Serializer};
use std::fmt;

/// Lower-cases `text` and drops spaces, underscores and hyphens, the comparison key of every
/// enumeration (`"Von Karman"`, `"von_karman"` and `"vonKarman"` all give `"vonkarman"`).
pub fn normalize(text: &str) -> String {
    text.chars()
        .filter(|c| !matches!(c, ' ' | '_' | '-'))
        .flat_map(char::to_lowercase)
        .collect()
}

/// Defines a string enumeration read with [`normalize`]; the first spelling of each variant
/// is its canonical name (written back by `Serialize` and shown in error messages).
macro_rules! names {
    (
        $(#[$meta:meta])*
        pub enum $name:ident ($what:literal) {
            $( $(#[$vmeta:meta])* $variant:ident => [$canonical:literal $(, $alias:literal)* $(,)?] ),+ $(,)?
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum $name {
            $( $(#[$vmeta])* $variant, )+
        }

        impl $name {
            /// Every variant, in declaration order.
            pub const ALL: &'static [$name] = &[$($name::$variant),+];

            /// The canonical spelling of this value in a mission file.
            pub fn as_str(self) -> &'static str {
                match self {
                    $( $name::$variant => $canonical, )+
                }
            }

            /// Reads a value, case- and separator-insensitively; `None` if it names nothing.
            pub fn parse(text: &str) -> Option<Self> {
                let key = normalize(text);
                $(
                    if key == normalize($canonical) $(|| key == normalize($alias))* {
                        return Some($name::$variant);
                    }
                )+
                None
            }

            /// The accepted canonical spellings, for error messages.
            pub fn expected() -> String {
                Self::ALL
                    .iter()
                    .map(|v| format!("\"{}\"", v.as_str()))
                    .collect::<Vec<_>>()
                    .join(", ")
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.as_str())
            }
        }

        impl Serialize for $name {
            fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                serializer.serialize_str(self.as_str())
            }
        }

        impl<'de> Deserialize<'de> for $name {
            fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
                struct NameVisitor;
                impl Visitor<'_> for NameVisitor {
                    type Value = $name;
                    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                        write!(f, "{} ({})", $what, $name::expected())
                    }
                    fn visit_str<E: de::Error>(self, v: &str) -> Result<$name, E> {
                        $name::parse(v).ok_or_else(|| {
                            E::custom(format!(
                                "unknown {} \"{}\", expected one of {}",
                                $what,
                                v,
                                $name::expected()
                            ))
                        })
                    }
                }
                deserializer.deserialize_str(NameVisitor)
            }
        }
    };
}

names! {
    /// `environment.atmosphere.model`.
    pub enum AtmosphereModel ("atmosphere model") {
        /// International Standard Atmosphere (ISO 2533), no wind.
        Standard => ["standard", "standard atmosphere", "isa"],
        /// Pressure, temperature and wind given as curves of height.
        Custom => ["custom", "custom atmosphere"],
        /// A radiosonde sounding file.
        Sounding => ["sounding"],
        /// A reanalysis grid (netCDF), e.g. ERA5.
        Reanalysis => ["reanalysis"],
        /// A forecast grid (netCDF), e.g. GFS.
        Forecast => ["forecast"],
        /// One member of an ensemble forecast grid (netCDF).
        Ensemble => ["ensemble"],
        /// An Open-Meteo pressure-level forecast saved as its JSON (a member of it when the
        /// file comes from the ensemble API).
        OpenMeteo => ["open_meteo"],
    }
}

names! {
    /// `environment.atmosphere.source`: the service `--fetch` downloads the file from.
    pub enum WeatherSource ("weather source") {
        /// Open-Meteo (forecast API; the ensemble API when `member` is given).
        OpenMeteo => ["open-meteo"],
        /// GFS 0.25° through UCAR THREDDS' NetCDF Subset Service.
        Gfs => ["gfs"],
        /// University of Wyoming soundings (needs `station`).
        Wyoming => ["wyoming"],
    }
}

names! {
    /// `environment.atmosphere.format` of a sounding file.
    pub enum SoundingFormat ("sounding format") {
        /// University of Wyoming TEXT:LIST page.
        Wyoming => ["wyoming"],
        /// NOAA RUC sounding.
        NoaaRuc => ["noaa_ruc", "noaa"],
    }
}

names! {
    /// `environment.datum`: the geodetic datum (all share the WGS-84 ellipsoid in RocketPy
    /// except SAD69 and NAD83's own; see docs/physics.md §4.6).
    pub enum Datum ("datum") {
        /// SIRGAS 2000, RocketPy's default.
        Sirgas2000 => ["SIRGAS2000"],
        /// South American Datum 1969.
        Sad69 => ["SAD69"],
        /// North American Datum 1983.
        Nad83 => ["NAD83"],
        /// World Geodetic System 1984.
        Wgs84 => ["WGS84"],
    }
}

names! {
    /// `motor.kind`.
    pub enum MotorKind ("motor kind") {
        /// A solid motor with BATES grains (RocketPy `SolidMotor`).
        Solid => ["solid", "solid motor"],
        /// A generic motor: a cylindrical propellant mass (RocketPy `GenericMotor`).
        Generic => ["generic", "generic motor"],
        /// A hybrid motor: a solid grain and oxidiser tanks (RocketPy `HybridMotor`).
        Hybrid => ["hybrid", "hybrid motor"],
        /// A liquid motor: tanks only (RocketPy `LiquidMotor`).
        Liquid => ["liquid", "liquid motor"],
    }
}

names! {
    /// `motor.tanks[].kind`.
    pub enum TankKindName ("tank kind") {
        /// Given by its flows (RocketPy `MassFlowRateBasedTank`).
        MassFlowRate => ["mass_flow_rate", "mass flow rate based"],
        /// Given by its gas volume (RocketPy `UllageBasedTank`).
        Ullage => ["ullage", "ullage based"],
        /// Given by its liquid level (RocketPy `LevelBasedTank`).
        Level => ["level", "level based"],
        /// Given by its masses (RocketPy `MassBasedTank`).
        Mass => ["mass", "mass based"],
    }
}

names! {
    /// `motor.tanks[].geometry.kind`.
    pub enum TankGeometryKind ("tank geometry") {
        /// A cylinder, optionally with spherical caps (RocketPy `CylindricalTank`).
        Cylindrical => ["cylindrical"],
        /// A sphere (RocketPy `SphericalTank`).
        Spherical => ["spherical"],
        /// A radius-of-height profile (RocketPy `TankGeometry`).
        Custom => ["custom"],
    }
}

names! {
    /// `motor.coordinate_system`: the direction of the motor's axial coordinate.
    pub enum MotorCoordinateSystem ("motor coordinate system") {
        /// Positions grow from the nozzle toward the combustion chamber (RocketPy default).
        NozzleToCombustionChamber => ["nozzle_to_combustion_chamber"],
        /// Positions grow from the combustion chamber toward the nozzle.
        CombustionChamberToNozzle => ["combustion_chamber_to_nozzle"],
    }
}

names! {
    /// `rocket.coordinate_system`: the direction of the rocket's axial coordinate.
    pub enum RocketCoordinateSystem ("rocket coordinate system") {
        /// Positions grow from the tail toward the nose (RocketPy default).
        TailToNose => ["tail_to_nose"],
        /// Positions grow from the nose toward the tail.
        NoseToTail => ["nose_to_tail"],
    }
}

names! {
    /// `motor.interpolation` (the thrust curve) and `rocket.interpolation` (both drag curves).
    pub enum InterpolationKind ("interpolation") {
        /// Piecewise linear (RocketPy default).
        Linear => ["linear"],
        /// Natural cubic spline.
        Spline => ["spline"],
        /// Akima spline.
        Akima => ["akima"],
        /// One polynomial through every point.
        Polynomial => ["polynomial"],
    }
}

names! {
    /// `rocket.extrapolation`: what the drag curves give outside their Mach range.
    pub enum ExtrapolationKind ("extrapolation") {
        /// Hold the end values (RocketPy's `"constant"`, the default).
        Constant => ["constant"],
        /// Continue the end piece (RocketPy's `"natural"`).
        Natural => ["natural"],
        /// Zero outside the range (RocketPy's `"zero"`).
        Zero => ["zero"],
    }
}

names! {
    /// `type` of an aerodynamic surface.
    pub enum SurfaceType ("surface type") {
        /// Nose cone (RocketPy `NoseCone`).
        Nose => ["nose", "nose cone", "nosecone"],
        /// Trapezoidal fin set.
        TrapezoidalFins => ["trapezoidal_fins"],
        /// Elliptical fin set.
        EllipticalFins => ["elliptical_fins"],
        /// Fin set given by its planform points.
        FreeFormFins => ["free_form_fins"],
        /// Conical transition or boattail (RocketPy `Tail`).
        Tail => ["tail", "transition", "boattail"],
        /// Tube fin set (OpenRocket's).
        TubeFins => ["tube_fins"],
    }
}

names! {
    /// `kind` of a nose cone (RocketPy `NoseCone.kind`).
    pub enum NoseKind ("nose kind") {
        /// Cone.
        Conical => ["conical", "cone"],
        /// Secant ogive.
        Ogive => ["ogive"],
        /// Tangent ogive.
        Tangent => ["tangent", "tangent ogive"],
        /// Von Kármán (LD-Haack) ogive.
        VonKarman => ["von karman", "vonkarman", "ldhaack"],
        /// LV-Haack series.
        LvHaack => ["lvhaack"],
        /// Parabolic series.
        Parabolic => ["parabolic"],
        /// Elliptical.
        Elliptical => ["elliptical"],
        /// Power series; needs `power`.
        PowerSeries => ["powerseries"],
    }
}

names! {
    /// `unit` of an airfoil lift curve's angle of attack.
    pub enum AngleUnit ("angle unit") {
        /// Radians.
        Radians => ["radians", "radian", "rad"],
        /// Degrees.
        Degrees => ["degrees", "degree", "deg"],
    }
}

names! {
    /// `rocket.drag_estimate.finish`: OpenRocket's surface finishes and their sand roughness
    /// (Niskanen 2009, Table 3.2).
    pub enum SurfaceFinish ("surface finish") {
        /// Rough, 500 µm.
        Rough => ["rough"],
        /// Unfinished (rough), 250 µm.
        RoughUnfinished => ["rough unfinished", "roughunfinished"],
        /// Unfinished, 150 µm.
        Unfinished => ["unfinished"],
        /// Regular paint, 60 µm.
        Normal => ["normal", "regular paint"],
        /// Smooth paint, 20 µm.
        Smooth => ["smooth", "smooth paint"],
        /// Optimum paint, 5 µm.
        Optimum => ["optimum", "optimum paint"],
        /// Polished (aircraft sheet metal), 2 µm.
        Polished => ["polished"],
        /// Finished and polished, 0.5 µm.
        FinishPolished => ["finish polished", "finishpolished"],
        /// Mirror, 0.
        Mirror => ["mirror"],
    }
}

impl SurfaceFinish {
    /// Equivalent sand roughness, m.
    pub fn roughness(self) -> f64 {
        match self {
            SurfaceFinish::Rough => 500e-6,
            SurfaceFinish::RoughUnfinished => 250e-6,
            SurfaceFinish::Unfinished => 150e-6,
            SurfaceFinish::Normal => 60e-6,
            SurfaceFinish::Smooth => 20e-6,
            SurfaceFinish::Optimum => 5e-6,
            SurfaceFinish::Polished => 2e-6,
            SurfaceFinish::FinishPolished => 0.5e-6,
            SurfaceFinish::Mirror => 0.0,
        }
    }
}

names! {
    /// `rocket.drag_estimate.fins.<surface>.cross_section`: a fin's edge profile.
    pub enum FinCrossSection ("fin cross section") {
        /// Square leading and trailing edges.
        Square => ["square"],
        /// Rounded edges.
        Rounded => ["rounded"],
        /// Airfoil: rounded leading edge, sharp trailing edge.
        Airfoil => ["airfoil"],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spellings_of_von_karman_are_one_kind() {
        for text in [
            "von karman",
            "Von Karman",
            "vonKarman",
            "VON_KARMAN",
            "von-karman",
        ] {
            assert_eq!(NoseKind::parse(text), Some(NoseKind::VonKarman), "{text}");
        }
        for text in ["lvhaack", "LV-Haack", "LV Haack"] {
            assert_eq!(NoseKind::parse(text), Some(NoseKind::LvHaack), "{text}");
        }
        assert_eq!(NoseKind::parse("karman"), None);
    }

    #[test]
    fn canonical_names_parse_back() {
        for kind in NoseKind::ALL {
            assert_eq!(NoseKind::parse(kind.as_str()), Some(*kind));
        }
        for model in AtmosphereModel::ALL {
            assert_eq!(AtmosphereModel::parse(model.as_str()), Some(*model));
        }
    }
}
