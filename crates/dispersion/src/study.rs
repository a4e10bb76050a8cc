//! A study: what is varied, what is measured, how many samples with which seed, and its
//! record `study.json`, which identifies the study in an output directory (resume, merge).

use crate::distribution::VariedInput;
use crate::error::DispersionError;
use crate::sampling::{SCHEME, fnv1a64};
use serde::{Deserialize, Serialize};
use std::collections::HashSet;
use std::fmt;
use std::path::Path;
use std::str::FromStr;

/// Which outputs are the apogee and landing points and which one the histogram shows.
///
/// A study of several bodies (the stages of a multi-stage rocket, each landing on its own)
/// names the body of [`Points::apogee`] and [`Points::landing`] in [`Points::body`] and the
/// points of the others in [`Points::bodies`]; each body gets its own ellipses, and its own
/// colour in the landing plot and the KML file.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Points {
    /// Output names of the apogee's (x east, y north), m.
    pub apogee: Option<[String; 2]>,
    /// Output names of the landing (impact) point's (x east, y north), m.
    pub landing: Option<[String; 2]>,
    /// Output drawn as a histogram (e.g. `apogee_agl_m`).
    pub histogram: Option<String>,
    /// The body `apogee` and `landing` are of, when the study has several.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// The apogee and landing points of the other bodies.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<BodyPoints>,
}

/// The apogee and landing points of one more body of a study ([`Points::bodies`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BodyPoints {
    /// The body's name (`booster`).
    pub name: String,
    /// Output names of its apogee's (x east, y north), m.
    pub apogee: Option<[String; 2]>,
    /// Output names of its landing point's (x east, y north), m.
    pub landing: Option<[String; 2]>,
}

/// The launch site, to turn (x, y) offsets into latitude/longitude in `dispersion.kml`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Site {
    /// Launch latitude, degrees north.
    pub latitude_deg: f64,
    /// Launch longitude, degrees east.
    pub longitude_deg: f64,
    /// Earth radius of the inverted haversine, m (docs/physics.md §4.6 / §12.2).
    pub earth_radius: f64,
}

/// Something the model is made of, identified by the hash of its content: a data file the
/// mission reads (thrust curve, drag curve, weather file, script), or the mission itself after
/// its overrides. Part of the study's identity: a study is not resumed or merged with rows
/// flown on other data.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct DataFile {
    /// What it is to the model: the mission key that names the file (`rocket.power_off_drag`),
    /// or `mission` for the mission after overrides.
    pub role: String,
    /// The file as the mission names it (relative to the mission's folder when written so);
    /// for the mission, its file name.
    pub path: String,
    /// SHA-256 of the content, lowercase hexadecimal.
    pub sha256: String,
}

/// A Monte Carlo study.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    /// Seed of every random stream (recorded in `study.json` and `summary.json`).
    pub seed: u64,
    /// Number of samples; they are numbered `0..samples`.
    pub samples: u64,
    /// The varied inputs, in the order the flight function receives their values.
    pub inputs: Vec<VariedInput>,
    /// Names of the scalar outputs, in the order of [`crate::Outcome`]'s values.
    pub outputs: Vec<String>,
    /// Outputs that make the apogee/landing ellipses and the histogram.
    pub points: Points,
    /// Launch site for the KML export; none: no `dispersion.kml`.
    pub site: Option<Site>,
    /// Free text naming the model (the mission's name): the title of the plots and the KML.
    pub context: String,
    /// The data the model is made of ([`DataFile`]): part of the fingerprint, so a study is
    /// not resumed or merged with rows flown on other data.
    pub data: Vec<DataFile>,
}

impl Study {
    /// The columns of the outputs called `names` among [`Study::outputs`], in the order given;
    /// every output when `names` is empty.
    ///
    /// # Errors
    /// [`DispersionError::InvalidStudy`] naming a name that is not an output, with the study's
    /// outputs.
    pub fn output_columns(&self, names: &[String]) -> Result<Vec<usize>, DispersionError> {
        if names.is_empty() {
            return Ok((0..self.outputs.len()).collect());
        }
        names
            .iter()
            .map(|name| {
                self.outputs.iter().position(|o| o == name).ok_or_else(|| {
                    DispersionError::InvalidStudy {
                        reason: format!(
                            "`{name}` is not an output of the study (its outputs: {})",
                            self.outputs.join(", ")
                        ),
                    }
                })
            })
            .collect()
    }

    /// A study with no points, no site and no context.
    pub fn new(seed: u64, samples: u64, inputs: Vec<VariedInput>, outputs: Vec<String>) -> Self {
        Study {
            seed,
            samples,
            inputs,
            outputs,
            points: Points::default(),
            site: None,
            context: String::new(),
            data: Vec::new(),
        }
    }

    /// Checks the study: at least one sample, valid and fitting distributions, unique
    /// column names, point outputs that exist, a finite site.
    pub fn validate(&self) -> Result<(), DispersionError> {
        let invalid = |reason: String| Err(DispersionError::InvalidStudy { reason });
        if self.samples == 0 {
            return invalid("the number of samples must be at least 1".to_owned());
        }
        for input in &self.inputs {
            input.check()?;
        }
        let mut seen = HashSet::new();
        for name in self.columns() {
            if name.is_empty() || name.contains(['\n', '\r']) {
                return invalid(format!("column name {name:?} is empty or has a line break"));
            }
            if !seen.insert(name.clone()) {
                return invalid(format!("column `{name}` appears twice"));
            }
        }
        let others = self.points.bodies.iter();
        let pairs = [&self.points.apogee, &self.points.landing]
            .into_iter()
            .chain(others.flat_map(|b| [&b.apogee, &b.landing]));
        let named = pairs.flatten().flatten().chain(&self.points.histogram);
        for name in named {
            if !self.outputs.contains(name) {
                return invalid(format!("`{name}` is not one of the outputs"));
            }
        }
        let mut bodies = HashSet::new();
        let names = self
            .points
            .body
            .iter()
            .chain(self.points.bodies.iter().map(|b| &b.name));
        for name in names {
            if name.is_empty() || !bodies.insert(name) {
                return invalid(format!("body name {name:?} is empty or appears twice"));
            }
        }
        if !self.points.bodies.is_empty() && self.points.body.is_none() {
            return invalid("a study of several bodies names the first one".to_owned());
        }
        if let Some(site) = self.site {
            let finite = [site.latitude_deg, site.longitude_deg, site.earth_radius]
                .iter()
                .all(|v| v.is_finite());
            if !finite || site.earth_radius <= 0.0 || site.latitude_deg.abs() > 90.0 {
                return invalid(format!("launch site {site:?} is not a place on Earth"));
            }
        }
        Ok(())
    }

    /// Every column of `samples.csv`: `index`, `status`, `error`, the inputs, the outputs,
    /// `digest` (the row's digest, [`crate::files`]).
    pub fn columns(&self) -> Vec<String> {
        let fixed = ["index", "status", "error"].map(str::to_owned);
        let inputs = self.inputs.iter().map(VariedInput::column);
        fixed
            .into_iter()
            .chain(inputs)
            .chain(self.outputs.iter().cloned())
            .chain([crate::csv::DIGEST_COLUMN.to_owned()])
            .collect()
    }
}

/// A part of a study: samples with `index % count == number − 1`. Interleaving (rather than
/// contiguous blocks) spreads slow regions of the input space evenly over the shards.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// This shard, 1-based.
    pub number: u64,
    /// Number of shards.
    pub count: u64,
}

impl Shard {
    /// The whole study.
    pub const WHOLE: Shard = Shard {
        number: 1,
        count: 1,
    };

    /// Shard `number` of `count` (1-based).
    pub fn new(number: u64, count: u64) -> Result<Self, DispersionError> {
        if number == 0 || number > count {
            return Err(DispersionError::InvalidShard {
                text: format!("{number}/{count}"),
            });
        }
        Ok(Shard { number, count })
    }

    /// Number of this shard's samples in a study of `samples`.
    pub fn len(&self, samples: u64) -> u64 {
        let first = self.number - 1;
        if samples <= first {
            0
        } else {
            (samples - first).div_ceil(self.count)
        }
    }

    /// Whether the shard has no sample of a study of `samples`.
    pub fn is_empty(&self, samples: u64) -> bool {
        self.len(samples) == 0
    }

    /// The sample index at `position` (0-based) of this shard.
    pub fn index(&self, position: u64) -> u64 {
        position * self.count + (self.number - 1)
    }
}

impl FromStr for Shard {
    type Err = DispersionError;

    fn from_str(text: &str) -> Result<Self, DispersionError> {
        let invalid = || DispersionError::InvalidShard {
            text: text.to_owned(),
        };
        let (k, n) = text.split_once('/').ok_or_else(invalid)?;
        let k = k.trim().parse().map_err(|_| invalid())?;
        let n = n.trim().parse().map_err(|_| invalid())?;
        Shard::new(k, n).map_err(|_| invalid())
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.number, self.count)
    }
}

/// Version of the output files' layout (2: the data fingerprint and the sample statuses;
/// 3: the `digest` column of `samples.csv`).
pub(crate) const FORMAT_VERSION: u32 = 3;

/// What every version of `study.json` has: read first, so that a folder of another version
/// is named as such rather than reported as malformed.
#[derive(Deserialize)]
struct Version {
    format: String,
    version: u32,
}

/// The content of `study.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Record {
    pub format: String,
    pub version: u32,
    pub fingerprint: String,
    pub sampling: String,
    pub seed: u64,
    pub samples: u64,
    pub shard: Shard,
    pub inputs: Vec<VariedInput>,
    pub outputs: Vec<String>,
    pub points: Points,
    pub site: Option<Site>,
    pub context: String,
    #[serde(default)]
    pub data: Vec<DataFile>,
}

const FORMAT: &str = "karman-dispersion study";

/// Bytes `study.json` may have: the record of a study is its inputs and a few numbers, far
/// below this.
const MAX_STUDY_BYTES: u64 = 64 << 20;

impl Record {
    /// The record of `study`'s `shard`.
    pub fn new(study: &Study, shard: Shard) -> Self {
        let mut record = Record {
            format: FORMAT.to_owned(),
            version: FORMAT_VERSION,
            fingerprint: String::new(),
            sampling: SCHEME.to_owned(),
            seed: study.seed,
            samples: study.samples,
            shard: Shard::WHOLE,
            inputs: study.inputs.clone(),
            outputs: study.outputs.clone(),
            points: study.points.clone(),
            site: study.site,
            context: study.context.clone(),
            data: study.data.clone(),
        };
        // The fingerprint covers everything but the shard (all shards share it).
        let canonical = serde_json::to_string(&record).unwrap_or_default();
        record.fingerprint = format!("{:016x}", fnv1a64(canonical.as_bytes()));
        record.shard = shard;
        record
    }

    /// The study this record describes.
    pub fn study(&self) -> Study {
        Study {
            seed: self.seed,
            samples: self.samples,
            inputs: self.inputs.clone(),
            outputs: self.outputs.clone(),
            points: self.points.clone(),
            site: self.site,
            context: self.context.clone(),
            data: self.data.clone(),
        }
    }

    /// The text of `study.json`.
    pub fn to_json(&self) -> String {
        let mut text = serde_json::to_string_pretty(self).unwrap_or_default();
        text.push('\n');
        text
    }

    /// Reads `study.json`; `Ok(None)` when it does not exist.
    pub fn read(path: &Path) -> Result<Option<Self>, DispersionError> {
        let json = |message: String| DispersionError::Json {
            path: path.to_owned(),
            message,
        };
        let Some(file) = crate::regular::open_regular(path)? else {
            return Ok(None);
        };
        let mut text = String::new();
        std::io::Read::read_to_string(
            &mut std::io::Read::take(file, MAX_STUDY_BYTES + 1),
            &mut text,
        )
        .map_err(DispersionError::io(path))?;
        if text.len() as u64 > MAX_STUDY_BYTES {
            return Err(json(format!(
                "larger than {} bytes: not a study record",
                MAX_STUDY_BYTES
            )));
        }
        let version: Version = serde_json::from_str(&text).map_err(|e| json(e.to_string()))?;
        if version.format != FORMAT {
            return Err(json(format!(
                "not a {FORMAT} (format {:?}, version {})",
                version.format, version.version
            )));
        }
        if version.version != FORMAT_VERSION {
            let age = if version.version < FORMAT_VERSION {
                "an earlier"
            } else {
                "a later"
            };
            return Err(DispersionError::OtherVersion {
                path: path.to_owned(),
                version: version.version,
                reason: format!(
                    "written by {age} karman (study format version {}; this one reads version \
                     {FORMAT_VERSION}, whose samples.csv rows end with a digest that resume and \
                     merge check)",
                    version.version
                ),
            });
        }
        let record: Record = serde_json::from_str(&text).map_err(|e| json(e.to_string()))?;
        Ok(Some(record))
    }

    /// Names of the fields in which `other` differs from `self`.
    pub fn differences(&self, other: &Record) -> Vec<String> {
        let mut fields = Vec::new();
        let mut differ = |name: &str, same: bool| {
            if !same {
                fields.push(name.to_owned());
            }
        };
        differ("sampling", self.sampling == other.sampling);
        differ("seed", self.seed == other.seed);
        differ("samples", self.samples == other.samples);
        differ("shard", self.shard == other.shard);
        differ("inputs", self.inputs == other.inputs);
        differ("outputs", self.outputs == other.outputs);
        differ("points", self.points == other.points);
        differ("site", self.site == other.site);
        differ("context", self.context == other.context);
        fields.extend(data_differences(&self.data, &other.data));
        if fields.is_empty() && self.fingerprint != other.fingerprint {
            fields.push("fingerprint".to_owned());
        }
        fields
    }
}

/// The data files in which `b` differs from `a`, each named: a changed content, or a file
/// only one of them reads. (Paths are not compared: a file's path is part of the mission,
/// whose own hash covers it, and the same study may be flown from different folders.)
fn data_differences(a: &[DataFile], b: &[DataFile]) -> Vec<String> {
    let mut out = Vec::new();
    let describe = |f: &DataFile| {
        if f.role == "mission" {
            format!("the mission {} (after overrides)", f.path)
        } else {
            format!("{} (`{}`)", f.path, f.role)
        }
    };
    for x in a {
        match b.iter().find(|y| y.role == x.role) {
            None => out.push(format!("{} is not read by the other", describe(x))),
            Some(y) if y.sha256 != x.sha256 => {
                out.push(format!("the content of {}", describe(x)));
            }
            Some(_) => {}
        }
    }
    for y in b.iter().filter(|y| a.iter().all(|x| x.role != y.role)) {
        out.push(format!("{} is read only by the other", describe(y)));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_samples() {
        let samples = 10;
        let mut seen = vec![0; samples as usize];
        for number in 1..=3 {
            let shard = Shard::new(number, 3).expect("valid");
            for position in 0..shard.len(samples) {
                seen[shard.index(position) as usize] += 1;
            }
        }
        assert!(seen.iter().all(|&n| n == 1), "{seen:?}");
        assert_eq!(Shard::new(5, 8).expect("valid").len(3), 0);
    }

    #[test]
    fn shard_text() {
        assert_eq!(
            "2/8".parse::<Shard>().expect("valid"),
            Shard::new(2, 8).expect("valid")
        );
        for bad in ["0/3", "4/3", "1", "a/b", "1/0", "-1/2"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
        assert_eq!(Shard::WHOLE.to_string(), "1/1");
    }

    #[test]
    fn fingerprint_ignores_the_shard_only() {
        let study = Study::new(1, 10, vec![], vec!["a".to_owned()]);
        let whole = Record::new(&study, Shard::WHOLE);
        let part = Record::new(&study, Shard::new(2, 3).expect("valid"));
        assert_eq!(whole.fingerprint, part.fingerprint);
        assert_eq!(whole.differences(&part), ["shard"]);
        let other = Record::new(
            &Study {
                seed: 2,
                ..study.clone()
            },
            Shard::WHOLE,
        );
        assert_ne!(whole.fingerprint, other.fingerprint);
        assert_eq!(whole.differences(&other), ["seed"]);
    }

    #[test]
    fn a_changed_data_file_is_named() {
        let file = |role: &str, path: &str, sha256: &str| DataFile {
            role: role.to_owned(),
            path: path.to_owned(),
            sha256: sha256.to_owned(),
        };
        let mut study = Study::new(1, 10, vec![], vec!["a".to_owned()]);
        study.data = vec![
            file("mission", "m.toml", "00"),
            file("rocket.power_off_drag", "drag.csv", "11"),
            file("motor.thrust", "m.eng", "22"),
        ];
        let before = Record::new(&study, Shard::WHOLE);
        study.data[1].sha256 = "12".to_owned();
        study.data[0].sha256 = "01".to_owned();
        study.data.pop();
        study
            .data
            .push(file("environment.atmosphere.file", "w.nc", "33"));
        let after = Record::new(&study, Shard::WHOLE);
        assert_ne!(before.fingerprint, after.fingerprint);
        assert_eq!(
            before.differences(&after),
            [
                "the content of the mission m.toml (after overrides)",
                "the content of drag.csv (`rocket.power_off_drag`)",
                "m.eng (`motor.thrust`) is not read by the other",
                "w.nc (`environment.atmosphere.file`) is read only by the other",
            ]
        );
    }
}
