//! Thrust data as read from a file or given inline, before any burn-time processing.
//!
//! [`ThrustData`] is a validated list of `(time, thrust)` points (times non-decreasing, a
//! repeated time being a step, all values finite) with the motor description the file carried, if any. The readers live
//! in [`crate::eng`] (RASP), [`crate::rse`] (RockSim XML) and [`crate::csv`] (two columns)
//! and build it with this module's point checks; `ThrustData::load` (module `file`) picks a
//! reader from the file extension.

use crate::PropulsionError;

/// The motor description carried by a RASP header or a RockSim `<engine>` element.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MotorHeader {
    /// Motor designation (RASP name, RockSim `code`).
    pub designation: String,
    /// Manufacturer.
    pub manufacturer: String,
    /// Casing diameter, m (the files give mm).
    pub diameter: Option<f64>,
    /// Casing length, m (the files give mm).
    pub length: Option<f64>,
    /// Available ejection delays as written (e.g. `"6-10-14"`, `"P"` for plugged).
    pub delays: String,
    /// Propellant mass, kg (RockSim gives g).
    pub propellant_mass: Option<f64>,
    /// Loaded motor mass, kg (RockSim gives g).
    pub total_mass: Option<f64>,
}

impl MotorHeader {
    /// Motor dry mass `total − propellant`, RocketPy's default when `dry_mass` is not given.
    #[must_use]
    pub fn dry_mass(&self) -> Option<f64> {
        Some(self.total_mass? - self.propellant_mass?)
    }
}

/// Which reader produced a [`ThrustData`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ThrustFormat {
    /// RASP `.eng` (a `(0, 0)` point prepended, as RocketPy does).
    Eng,
    /// RockSim `.rse` XML.
    Rse,
    /// Two numeric columns.
    Csv,
    /// Points given inline (e.g. in a mission file).
    Inline,
}

/// Validated thrust samples: times non-decreasing (a repeated time is a step), every value
/// finite.
#[derive(Debug, Clone, PartialEq)]
pub struct ThrustData {
    /// Where the data came from (file path or label), for messages.
    pub source_name: String,
    /// The reader that produced it.
    pub format: ThrustFormat,
    /// Sample times, s.
    pub times: Vec<f64>,
    /// Thrust at each time, N.
    pub thrusts: Vec<f64>,
    /// The motor description of `.eng`/`.rse` files.
    pub header: Option<MotorHeader>,
    /// What the reader accepted but would not expect in a well-formed file (e.g. a RASP
    /// file without its header line), in words.
    pub warnings: Vec<String>,
}

impl ThrustData {
    /// Thrust points given inline, as the mission format allows: sorted by time with a
    /// stable sort, then checked (finite values, at least two points; a repeated time is a
    /// step, kept in the order given).
    /// Negative thrust is accepted, as in RocketPy (measured curves dip below zero).
    ///
    /// # Errors
    /// [`PropulsionError::Malformed`] for a non-finite value,
    /// [`PropulsionError::TooFewPoints`] for fewer than two points. Point numbers are the
    /// 1-based positions in `points` as given.
    pub fn from_points(
        source_name: &str,
        points: &[[f64; 2]],
    ) -> Result<ThrustData, PropulsionError> {
        for (i, p) in points.iter().enumerate() {
            for v in p {
                if !v.is_finite() {
                    return Err(PropulsionError::Malformed {
                        source_name: source_name.to_owned(),
                        line: i + 1,
                        text: v.to_string(),
                        reason: "value is not finite",
                    });
                }
            }
        }
        let mut order: Vec<usize> = (0..points.len()).collect();
        order.sort_by(|&a, &b| points[a][0].total_cmp(&points[b][0]));
        let mut builder = PointsBuilder::new(source_name, ThrustFormat::Inline);
        for &i in &order {
            builder.push(i + 1, points[i][0], points[i][1])?;
        }
        builder.finish(None, 2)
    }
}

/// Largest thrust a curve may give, N (Super Heavy's 33 engines give 7.4e7 N): a rocket
/// pushed by 1e300 N leaves the integrator's step limit at once.
pub(crate) const MAX_THRUST: f64 = 1e9;

/// Accumulates points in file order, checking that time never decreases (a repeated time is a
/// step, which only a linear curve takes: [`crate::ThrustCurve::new`] checks that).
pub(crate) struct PointsBuilder {
    source_name: String,
    format: ThrustFormat,
    times: Vec<f64>,
    thrusts: Vec<f64>,
}

impl PointsBuilder {
    pub(crate) fn new(source_name: &str, format: ThrustFormat) -> Self {
        PointsBuilder {
            source_name: source_name.to_owned(),
            format,
            times: Vec::new(),
            thrusts: Vec::new(),
        }
    }

    /// Appends a point read at `line`.
    ///
    /// # Errors
    /// [`PropulsionError::TimeNotIncreasing`] for a time before the previous one, and
    /// [`PropulsionError::Malformed`] for a thrust beyond [`MAX_THRUST`] (no flight can be
    /// integrated on it).
    pub(crate) fn push(
        &mut self,
        line: usize,
        time: f64,
        thrust: f64,
    ) -> Result<(), PropulsionError> {
        let beyond = |value: f64, reason: &'static str| PropulsionError::Malformed {
            source_name: self.source_name.clone(),
            line,
            text: karman_math::text::number(value),
            reason,
        };
        if thrust.abs() > MAX_THRUST {
            return Err(beyond(
                thrust,
                "thrust beyond 1e9 N (ten times the largest engine cluster flown)",
            ));
        }
        if let Some(&previous) = self.times.last() {
            if time < previous {
                return Err(PropulsionError::TimeNotIncreasing {
                    source_name: self.source_name.clone(),
                    line,
                    time,
                    previous,
                });
            }
        }
        self.times.push(time);
        self.thrusts.push(thrust);
        Ok(())
    }

    /// Error for a negative thrust at `line` (formats whose specification forbids it).
    pub(crate) fn negative_thrust(&self, line: usize, thrust: f64) -> PropulsionError {
        PropulsionError::NegativeThrust {
            source_name: self.source_name.clone(),
            line,
            thrust,
        }
    }

    /// Number of points so far.
    pub(crate) fn len(&self) -> usize {
        self.times.len()
    }

    /// The finished data, provided it holds at least `needed` points.
    pub(crate) fn finish(
        self,
        header: Option<MotorHeader>,
        needed: usize,
    ) -> Result<ThrustData, PropulsionError> {
        if self.times.len() < needed {
            return Err(PropulsionError::TooFewPoints {
                source_name: self.source_name,
                found: self.times.len(),
                needed,
            });
        }
        // Times never decrease (`push`), so the first and last equal means all equal.
        if let (Some(&first), Some(&last)) = (self.times.first(), self.times.last()) {
            if self.times.len() >= 2 && last <= first {
                return Err(PropulsionError::NoDuration {
                    source_name: self.source_name,
                    time: first,
                });
            }
        }
        Ok(ThrustData {
            source_name: self.source_name,
            format: self.format,
            times: self.times,
            thrusts: self.thrusts,
            header,
            warnings: Vec::new(),
        })
    }
}

/// Parses a finite `f64`, or reports `text` at `line` as malformed.
pub(crate) fn parse_number(
    source_name: &str,
    line: usize,
    text: &str,
) -> Result<f64, PropulsionError> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(PropulsionError::Malformed {
            source_name: source_name.to_owned(),
            line,
            text: text.to_owned(),
            reason: "value is not finite",
        }),
        Err(_) => Err(PropulsionError::Malformed {
            source_name: source_name.to_owned(),
            line,
            text: text.to_owned(),
            reason: "not a number",
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_error_says_its_cause_once_in_a_whole_chain() {
        let math = karman_math::MathError::TooFewPoints { needed: 2, got: 1 };
        let e = PropulsionError::table("propellant mass")(math);
        assert!(std::error::Error::source(&e).is_none());
        assert_eq!(
            e.to_string(),
            "propellant mass: a table needs at least 2 point(s), got 1"
        );
    }

    #[test]
    fn a_thrust_no_flight_survives_is_refused_at_its_point() {
        let e = ThrustData::from_points("t.eng", &[[0.0, 0.0], [0.1, 1e300], [2.0, 0.0]])
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "t.eng:2: thrust beyond 1e9 N (ten times the largest engine cluster flown): '1e300'"
        );
        // Super Heavy's thrust is a curve.
        ThrustData::from_points("t.eng", &[[0.0, 7.4e7], [3600.0, 0.0]]).expect("a curve");
    }

    #[test]
    fn inline_points_are_sorted_stably_and_checked() {
        let d = ThrustData::from_points("t", &[[1.0, 10.0], [0.0, 0.0], [2.0, -1.0]]).unwrap();
        assert_eq!(d.times, vec![0.0, 1.0, 2.0]);
        assert_eq!(d.thrusts, vec![0.0, 10.0, -1.0]);
        // A repeated time is a step, in the order given.
        let d = ThrustData::from_points("t", &[[1.0, 10.0], [0.0, 0.0], [1.0, 5.0]]).unwrap();
        assert_eq!(d.times, vec![0.0, 1.0, 1.0]);
        assert_eq!(d.thrusts, vec![0.0, 10.0, 5.0]);
        let e = ThrustData::from_points("t", &[[1.0, f64::NAN], [2.0, 0.0]]).unwrap_err();
        assert!(
            matches!(e, PropulsionError::Malformed { line: 1, .. }),
            "{e}"
        );
        let e = ThrustData::from_points("t", &[[1.0, 1.0]]).unwrap_err();
        assert!(
            matches!(e, PropulsionError::TooFewPoints { found: 1, .. }),
            "{e}"
        );
    }
}
