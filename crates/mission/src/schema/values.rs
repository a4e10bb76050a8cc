//! Value types of the mission format that accept more than one TOML shape: curves, inertia
//! tensors (3 or 6 components), burn times (end or `[start, end]`), integrator tolerances (one
//! or 13 numbers) and parachute triggers (`"apogee"` or a height).

use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::ser::SerializeSeq;
use serde::{Deserialize, Serialize, Serializer};
use std::fmt;
use std::path::{Path, PathBuf};

/// A tabulated function of one variable (drag coefficient of Mach, thrust of time, a profile
/// of height), mission-format.md "Conventions".
#[derive(Debug, Clone, PartialEq)]
pub enum Curve {
    /// The same value everywhere.
    Constant(f64),
    /// Inline points `[[x0, y0], [x1, y1], ...]` in file order; [`Curve::sorted_points`]
    /// gives them sorted by x.
    Points(Vec<[f64; 2]>),
    /// A data file, as written in the mission (relative paths are relative to the mission
    /// file's directory: use [`Curve::file_path`]).
    File(PathBuf),
}

/// The keyword of a drag curve estimated from the geometry (`power_off_drag = "estimate"`).
pub const ESTIMATE: &str = "estimate";

impl Curve {
    /// Whether this is the drag keyword [`ESTIMATE`] rather than a file.
    pub fn is_estimate(&self) -> bool {
        matches!(self, Curve::File(path) if path.as_os_str() == ESTIMATE)
    }

    /// The data file of a [`Curve::File`], resolved against `mission_dir`.
    pub fn file_path(&self, mission_dir: &Path) -> Option<PathBuf> {
        match self {
            Curve::File(path) => Some(mission_dir.join(path)),
            Curve::Constant(_) | Curve::Points(_) => None,
        }
    }

    /// The inline points of a [`Curve::Points`] sorted by x with a stable sort (points with
    /// equal x keep their file order), as the contract asks.
    pub fn sorted_points(&self) -> Option<Vec<[f64; 2]>> {
        match self {
            Curve::Points(points) => {
                let mut sorted = points.clone();
                sorted.sort_by(|a, b| a[0].total_cmp(&b[0]));
                Some(sorted)
            }
            Curve::Constant(_) | Curve::File(_) => None,
        }
    }
}

impl Serialize for Curve {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Curve::Constant(value) => serializer.serialize_f64(*value),
            Curve::Points(points) => points.serialize(serializer),
            Curve::File(path) => path.serialize(serializer),
        }
    }
}

impl<'de> Deserialize<'de> for Curve {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct CurveVisitor;
        impl<'de> Visitor<'de> for CurveVisitor {
            type Value = Curve;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a curve: a number, a file path or [[x, y], ...]")
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Curve, E> {
                Ok(Curve::Constant(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Curve, E> {
                Ok(Curve::Constant(v as f64))
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Curve, E> {
                Ok(Curve::Constant(v))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Curve, E> {
                if v.trim().is_empty() {
                    return Err(E::custom("a curve file path must not be empty"));
                }
                Ok(Curve::File(PathBuf::from(v)))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Curve, A::Error> {
                let mut points = Vec::new();
                while let Some(point) = seq.next_element::<[f64; 2]>()? {
                    points.push(point);
                }
                if points.is_empty() {
                    return Err(de::Error::custom("a curve needs at least one [x, y] point"));
                }
                Ok(Curve::Points(points))
            }
        }
        deserializer.deserialize_any(CurveVisitor)
    }
}

/// Reads a sequence of `f64` of one of the lengths in `allowed`.
fn numbers<'de, A: SeqAccess<'de>>(mut seq: A, allowed: &[usize]) -> Result<Vec<f64>, A::Error> {
    let mut values = Vec::new();
    while let Some(value) = seq.next_element::<f64>()? {
        values.push(value);
    }
    if allowed.contains(&values.len()) {
        Ok(values)
    } else {
        let lengths: Vec<String> = allowed.iter().map(usize::to_string).collect();
        Err(de::Error::custom(format!(
            "expected {} numbers, got {}",
            lengths.join(" or "),
            values.len()
        )))
    }
}

/// An inertia tensor `(I11, I22, I33, I12, I13, I23)` in kg·m², RocketPy's order; written as
/// 3 numbers (principal axes, products zero) or 6.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Inertia(pub [f64; 6]);

impl Serialize for Inertia {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for Inertia {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct InertiaVisitor;
        impl<'de> Visitor<'de> for InertiaVisitor {
            type Value = Inertia;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("[I11, I22, I33] or [I11, I22, I33, I12, I13, I23]")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Inertia, A::Error> {
                let values = numbers(seq, &[3, 6])?;
                let mut inertia = [0.0; 6];
                inertia[..values.len()].copy_from_slice(&values);
                Ok(Inertia(inertia))
            }
        }
        deserializer.deserialize_seq(InertiaVisitor)
    }
}

/// `motor.burn_time`: the burn interval in s, written as its end (start 0) or `[start, end]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BurnTime {
    /// Start of the burn, s.
    pub start: f64,
    /// End of the burn, s.
    pub end: f64,
}

impl Serialize for BurnTime {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        [self.start, self.end].serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for BurnTime {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct BurnTimeVisitor;
        impl<'de> Visitor<'de> for BurnTimeVisitor {
            type Value = BurnTime;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a burn end time or [start, end]")
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<BurnTime, E> {
                self.visit_f64(v as f64)
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<BurnTime, E> {
                self.visit_f64(v as f64)
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<BurnTime, E> {
                Ok(BurnTime { start: 0.0, end: v })
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<BurnTime, A::Error> {
                let values = numbers(seq, &[2])?;
                Ok(BurnTime {
                    start: values[0],
                    end: values[1],
                })
            }
        }
        deserializer.deserialize_any(BurnTimeVisitor)
    }
}

/// Number of state components of the equations of motion (position 3, velocity 3,
/// quaternion 4, angular rate 3), the length of a per-state `atol`.
pub const STATE_SIZE: usize = 13;

/// `flight.atol`: the integrator's absolute tolerance, one number or one per state component.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Atol {
    /// The same tolerance for every state component.
    Scalar(f64),
    /// One tolerance per state component (x, y, z, vx, vy, vz, e0..e3, ω1..ω3).
    PerState([f64; STATE_SIZE]),
}

impl Atol {
    /// The tolerance of every state component.
    pub fn per_state(&self) -> [f64; STATE_SIZE] {
        match self {
            Atol::Scalar(value) => [*value; STATE_SIZE],
            Atol::PerState(values) => *values,
        }
    }
}

impl Serialize for Atol {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Atol::Scalar(value) => serializer.serialize_f64(*value),
            Atol::PerState(values) => {
                let mut seq = serializer.serialize_seq(Some(values.len()))?;
                for value in values {
                    seq.serialize_element(value)?;
                }
                seq.end()
            }
        }
    }
}

impl<'de> Deserialize<'de> for Atol {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct AtolVisitor;
        impl<'de> Visitor<'de> for AtolVisitor {
            type Value = Atol;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "a tolerance or {STATE_SIZE} per-state tolerances")
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Atol, E> {
                Ok(Atol::Scalar(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Atol, E> {
                Ok(Atol::Scalar(v as f64))
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Atol, E> {
                Ok(Atol::Scalar(v))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Atol, A::Error> {
                let values = numbers(seq, &[STATE_SIZE])?;
                let mut per_state = [0.0; STATE_SIZE];
                per_state.copy_from_slice(&values);
                Ok(Atol::PerState(per_state))
            }
        }
        deserializer.deserialize_any(AtolVisitor)
    }
}

/// `trigger` of a parachute.
#[derive(Debug, Clone, PartialEq)]
pub enum Trigger {
    /// Eject at apogee (first sampling instant with a descending velocity).
    Apogee,
    /// Eject on descent below this height above ground level, m.
    HeightAboveGround(f64),
    /// `"launch + X"`: eject at the first sampling instant at or after `X` s (RocketPy 1.14).
    Launch(f64),
    /// `"burnout + X"`: eject at the first sampling instant at or after the motor's burn-out
    /// plus `X` s (RocketPy 1.14).
    Burnout(f64),
    /// `{ expression = "..." }`: RocketPy's callable `trigger(p, h, y)` as an expression
    /// (mission-format.md "Custom triggers"); checked by validation.
    Expression(String),
}

/// Reads `"launch + X"` / `"burnout + X"` (spaces optional, case-insensitive).
fn timed_trigger(text: &str) -> Option<Trigger> {
    let (event, delay) = text.split_once('+')?;
    let delay: f64 = delay.trim().parse().ok().filter(|d: &f64| d.is_finite())?;
    match super::names::normalize(event).as_str() {
        "launch" => Some(Trigger::Launch(delay)),
        "burnout" => Some(Trigger::Burnout(delay)),
        _ => None,
    }
}

impl Serialize for Trigger {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Trigger::Apogee => serializer.serialize_str("apogee"),
            Trigger::HeightAboveGround(height) => serializer.serialize_f64(*height),
            Trigger::Launch(delay) => serializer.serialize_str(&format!("launch + {delay}")),
            Trigger::Burnout(delay) => serializer.serialize_str(&format!("burnout + {delay}")),
            Trigger::Expression(text) => {
                use serde::ser::SerializeMap;
                let mut map = serializer.serialize_map(Some(1))?;
                map.serialize_entry("expression", text)?;
                map.end()
            }
        }
    }
}

impl<'de> Deserialize<'de> for Trigger {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct TriggerVisitor;
        impl<'de> Visitor<'de> for TriggerVisitor {
            type Value = Trigger;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(
                    "\"apogee\", a height above ground level in m, \"launch + <s>\", \
                     \"burnout + <s>\" or { expression = \"...\" }",
                )
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Trigger, E> {
                Ok(Trigger::HeightAboveGround(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Trigger, E> {
                Ok(Trigger::HeightAboveGround(v as f64))
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Trigger, E> {
                Ok(Trigger::HeightAboveGround(v))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Trigger, E> {
                if super::names::normalize(v) == "apogee" {
                    return Ok(Trigger::Apogee);
                }
                timed_trigger(v).ok_or_else(|| {
                    E::custom(format!(
                        "unknown parachute trigger \"{v}\", expected \"apogee\", a height above \
                         ground level in m, \"launch + <seconds>\", \"burnout + <seconds>\" or \
                         {{ expression = \"...\" }}"
                    ))
                })
            }
            fn visit_map<A: de::MapAccess<'de>>(self, mut map: A) -> Result<Trigger, A::Error> {
                let mut expression = None;
                while let Some(key) = map.next_key::<String>()? {
                    if key != "expression" || expression.is_some() {
                        return Err(de::Error::custom(format!(
                            "a trigger table takes one key, `expression`; found `{key}`"
                        )));
                    }
                    expression = Some(map.next_value::<String>()?);
                }
                expression
                    .map(Trigger::Expression)
                    .ok_or_else(|| de::Error::custom("a trigger table needs `expression`"))
            }
        }
        deserializer.deserialize_any(TriggerVisitor)
    }
}

/// `drag_coefficient_curve` of the air brakes: `Cd(deployment_level, Mach)`.
#[derive(Debug, Clone, PartialEq)]
pub enum AirBrakesCurve {
    /// The same value everywhere.
    Constant(f64),
    /// Inline rows `[[level, mach, cd], ...]`, in file order (not sorted: the Shepard sums run
    /// in row order).
    Rows(Vec<[f64; 3]>),
    /// A 3-column data file (deployment level, Mach, Cd; an optional header line).
    File(PathBuf),
}

impl Serialize for AirBrakesCurve {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            AirBrakesCurve::Constant(value) => serializer.serialize_f64(*value),
            AirBrakesCurve::Rows(rows) => rows.serialize(serializer),
            AirBrakesCurve::File(path) => path.serialize(serializer),
        }
    }
}

impl<'de> Deserialize<'de> for AirBrakesCurve {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct CurveVisitor;
        impl<'de> Visitor<'de> for CurveVisitor {
            type Value = AirBrakesCurve;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a number, a file path or [[level, mach, cd], ...]")
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<AirBrakesCurve, E> {
                Ok(AirBrakesCurve::Constant(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<AirBrakesCurve, E> {
                Ok(AirBrakesCurve::Constant(v as f64))
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<AirBrakesCurve, E> {
                Ok(AirBrakesCurve::Constant(v))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<AirBrakesCurve, E> {
                if v.trim().is_empty() {
                    return Err(E::custom("a curve file path must not be empty"));
                }
                Ok(AirBrakesCurve::File(PathBuf::from(v)))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<AirBrakesCurve, A::Error> {
                let mut rows = Vec::new();
                while let Some(row) = seq.next_element::<[f64; 3]>()? {
                    rows.push(row);
                }
                if rows.is_empty() {
                    return Err(de::Error::custom(
                        "the table needs at least one [level, mach, cd] row",
                    ));
                }
                Ok(AirBrakesCurve::Rows(rows))
            }
        }
        deserializer.deserialize_any(CurveVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Deserialize)]
    struct Holder {
        curve: Curve,
    }

    fn curve(text: &str) -> Curve {
        toml::from_str::<Holder>(&format!("curve = {text}"))
            .map(|h| h.curve)
            .unwrap_or_else(|e| panic!("{text}: {e}"))
    }

    #[test]
    fn curve_shapes() {
        assert_eq!(curve("0.44"), Curve::Constant(0.44));
        assert_eq!(curve("1"), Curve::Constant(1.0));
        assert_eq!(curve("\"drag.csv\""), Curve::File("drag.csv".into()));
        assert_eq!(
            curve("[[1, 2.0], [0.5, 3]]"),
            Curve::Points(vec![[1.0, 2.0], [0.5, 3.0]])
        );
    }

    #[test]
    fn sorted_points_are_stable() {
        let c = Curve::Points(vec![[2.0, 1.0], [1.0, 5.0], [2.0, 0.0], [1.0, 6.0]]);
        assert_eq!(
            c.sorted_points(),
            Some(vec![[1.0, 5.0], [1.0, 6.0], [2.0, 1.0], [2.0, 0.0]])
        );
    }

    #[test]
    fn inertia_three_or_six() {
        #[derive(Deserialize)]
        struct H {
            i: Inertia,
        }
        let three: H = toml::from_str("i = [1, 2, 3]").expect("3 components");
        assert_eq!(three.i, Inertia([1.0, 2.0, 3.0, 0.0, 0.0, 0.0]));
        let six: H = toml::from_str("i = [1, 2, 3, 4, 5, 6]").expect("6 components");
        assert_eq!(six.i, Inertia([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]));
        assert!(toml::from_str::<H>("i = [1, 2]").is_err());
    }

    #[test]
    fn burn_time_and_trigger() {
        #[derive(Deserialize)]
        struct H {
            b: BurnTime,
            t: Trigger,
        }
        let h: H = toml::from_str("b = 3.9\nt = \"Apogee\"").expect("valid");
        assert_eq!(
            h.b,
            BurnTime {
                start: 0.0,
                end: 3.9
            }
        );
        assert_eq!(h.t, Trigger::Apogee);
        let h: H = toml::from_str("b = [0.5, 3]\nt = 800").expect("valid");
        assert_eq!(
            h.b,
            BurnTime {
                start: 0.5,
                end: 3.0
            }
        );
        assert_eq!(h.t, Trigger::HeightAboveGround(800.0));
        assert!(toml::from_str::<H>("b = 1\nt = \"perigee\"").is_err());
        let h: H = toml::from_str("b = 1\nt = \"Launch + 5\"").expect("valid");
        assert_eq!(h.t, Trigger::Launch(5.0));
        let h: H = toml::from_str("b = 1\nt = \"burnout+2.5\"").expect("valid");
        assert_eq!(h.t, Trigger::Burnout(2.5));
        let h: H = toml::from_str("b = 1\nt = { expression = \"vz < 5.0\" }").expect("valid");
        assert_eq!(h.t, Trigger::Expression("vz < 5.0".into()));
        for bad in [
            "\"launch + x\"",
            "\"landing + 2\"",
            "{ expr = \"a\" }",
            "{}",
        ] {
            assert!(
                toml::from_str::<H>(&format!("b = 1\nt = {bad}")).is_err(),
                "{bad}"
            );
        }
    }

    #[test]
    fn triggers_serialize_back() {
        #[derive(Deserialize, Serialize)]
        struct H {
            t: Trigger,
        }
        for t in [
            Trigger::Apogee,
            Trigger::HeightAboveGround(800.0),
            Trigger::Launch(0.1),
            Trigger::Burnout(3.25),
            Trigger::Expression("z > 300.0".into()),
        ] {
            let text = toml::to_string(&H { t: t.clone() }).expect("serializes");
            let back: H = toml::from_str(&text).expect("reads back");
            assert_eq!(back.t, t, "{text}");
        }
    }

    #[test]
    fn air_brake_curves() {
        #[derive(Debug, Deserialize)]
        struct H {
            c: AirBrakesCurve,
        }
        let c = |text: &str| toml::from_str::<H>(&format!("c = {text}")).map(|h| h.c);
        assert_eq!(c("0.8").expect("number"), AirBrakesCurve::Constant(0.8));
        assert_eq!(
            c("\"ab.csv\"").expect("file"),
            AirBrakesCurve::File("ab.csv".into())
        );
        assert_eq!(
            c("[[1, 0.1, 0.7], [0, 0.1, 0.5]]").expect("rows"),
            AirBrakesCurve::Rows(vec![[1.0, 0.1, 0.7], [0.0, 0.1, 0.5]])
        );
        assert!(c("[[1, 0.1]]").is_err());
        assert!(c("[]").is_err());
    }
}
