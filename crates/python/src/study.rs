//! `karman.Study`: a finished Monte Carlo study in memory — the sampled inputs and the
//! summary outputs of every sample as numpy arrays, statistics and ellipses.

use std::path::{Path, PathBuf};
use std::time::Duration;

use karman_mission::dispersion::{
    Row, RunReport, Status, Study as StudyDefinition, Summary, parse_row, sensitivity_of_rows,
    tolerance_of_rows,
};
use numpy::PyArray1;
use pyo3::exceptions::{PyOSError, PyRuntimeError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use karman_mission::assemble::stage_view::TOP_STAGE;

use crate::convert::{from_json, plain};

/// A finished Monte Carlo study.
#[pyclass(module = "karman", frozen)]
pub struct Study {
    seed: u64,
    index: Vec<u64>,
    inputs: Vec<(String, Vec<f64>)>,
    outputs: Vec<(String, Vec<f64>)>,
    failures: Vec<(u64, String)>,
    summary: Summary,
    threads: usize,
    elapsed: Duration,
    flown: u64,
    out: Option<PathBuf>,
    /// The study and its rows, for `sensitivity`.
    definition: StudyDefinition,
    rows: Vec<Row>,
}

impl Study {
    /// A finished study from its rows in index order (as `samples.csv` holds them) and its
    /// run's report; `out` is the folder it was written to, if any.
    pub fn new(
        study: &StudyDefinition,
        rows: Vec<Row>,
        report: &RunReport,
        out: Option<PathBuf>,
    ) -> PyResult<Self> {
        let (n_in, n_out) = (study.inputs.len(), study.outputs.len());
        let mut index = Vec::with_capacity(rows.len());
        let mut inputs: Vec<Vec<f64>> = vec![Vec::with_capacity(rows.len()); n_in];
        let mut outputs: Vec<Vec<f64>> = vec![Vec::with_capacity(rows.len()); n_out];
        let mut failures = Vec::new();
        for row in &rows {
            index.push(row.index);
            for (column, value) in inputs.iter_mut().zip(&row.inputs) {
                column.push(*value);
            }
            for (column, value) in outputs.iter_mut().zip(&row.outputs) {
                column.push(value.unwrap_or(f64::NAN));
            }
            match &row.status {
                Status::Completed => {}
                Status::Ended { kind, message } => {
                    failures.push((row.index, format!("{kind}: {message}")));
                }
                Status::Failed(error) => failures.push((row.index, error.clone())),
            }
        }
        let summary = report
            .summary
            .clone()
            .ok_or_else(|| PyRuntimeError::new_err("a whole study has a summary"))?;
        Ok(Study {
            seed: study.seed,
            index,
            inputs: study
                .inputs
                .iter()
                .map(|i| i.column())
                .zip(inputs)
                .collect(),
            outputs: study.outputs.iter().cloned().zip(outputs).collect(),
            failures,
            summary,
            threads: report.threads,
            elapsed: report.elapsed,
            flown: report.flown,
            out,
            definition: study.clone(),
            rows,
        })
    }

    /// The study written to `dir`, its rows read back from its `samples.csv`.
    pub fn read(study: &StudyDefinition, report: &RunReport, dir: &Path) -> PyResult<Self> {
        let path = dir.join(karman_mission::dispersion::files::SAMPLES_FILE);
        let text = std::fs::read_to_string(&path)
            .map_err(|e| PyOSError::new_err(format!("cannot read {}: {e}", path.display())))?;
        let (n_in, n_out) = (study.inputs.len(), study.outputs.len());
        let rows = text
            .lines()
            .enumerate()
            .skip(1)
            .map(|(number, line)| {
                parse_row(line, n_in, n_out).map_err(|reason| {
                    PyRuntimeError::new_err(format!(
                        "{}, line {}: {reason}",
                        path.display(),
                        number + 1
                    ))
                })
            })
            .collect::<PyResult<Vec<Row>>>()?;
        Study::new(study, rows, report, Some(dir.to_owned()))
    }

    fn columns<'py>(
        py: Python<'py>,
        columns: &[(String, Vec<f64>)],
    ) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for (name, values) in columns {
            dict.set_item(name, PyArray1::from_slice(py, values))?;
        }
        Ok(dict)
    }
}

#[pymethods]
impl Study {
    /// The study's seed.
    #[getter]
    fn seed(&self) -> u64 {
        self.seed
    }

    /// Number of samples.
    #[getter]
    fn samples(&self) -> usize {
        self.index.len()
    }

    /// The sample indices, in row order (0, 1, 2, ...).
    #[getter]
    fn index<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u64>> {
        PyArray1::from_slice(py, &self.index)
    }

    /// The sampled inputs by column of `samples.csv`: the dotted path, with `:factor` or
    /// `:offset` appended when the column holds a factor or an offset.
    #[getter]
    fn inputs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        Study::columns(py, &self.inputs)
    }

    /// The outputs by summary key (`apogee_agl_m`, `impact_x_m`, ...; the keys of
    /// `karman simulate --json`), NaN where a sample failed or the quantity did not occur.
    #[getter]
    fn outputs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        Study::columns(py, &self.outputs)
    }

    /// The samples that failed or ended before the flight the study asked for (`max_time`,
    /// stuck on the rail) as `(index, message)` pairs.
    #[getter]
    fn failures(&self) -> Vec<(u64, String)> {
        self.failures.clone()
    }

    /// `summary.json` of `karman montecarlo` as Python data.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        plain(py, &self.summary)
    }

    /// Statistics of each input and output column: `{name: {count, mean, std, min, max,
    /// median, p2_5, p97_5}}` (population standard deviation).
    #[getter]
    fn statistics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for column in self.summary.inputs.iter().chain(&self.summary.outputs) {
            dict.set_item(&column.name, plain(py, &column.statistics)?)?;
        }
        Ok(dict)
    }

    /// The apogee and landing ellipses by name (`"apogee"`, `"landing"`): centre,
    /// covariance, orientation and the 1/2/3-sigma contours in RocketPy's convention
    /// (`k_sigma_rocketpy`) and probability-calibrated (`probability`). In a study of a
    /// multi-stage rocket those of a lower stage are named after it as its output columns
    /// (`"booster.landing"`); the top stage's keep the plain names.
    #[getter]
    fn ellipses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for ellipse in &self.summary.ellipses {
            let value = serde_json::to_value(ellipse)
                .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
            let key = match ellipse.body.as_deref() {
                Some(body) if body != TOP_STAGE => format!("{body}.{}", ellipse.name),
                _ => ellipse.name.clone(),
            };
            dict.set_item(key, from_json(py, &value)?)?;
        }
        Ok(dict)
    }

    /// Which varied input causes the spread of each output: RocketPy 1.13's
    /// `SensitivityModel` (linear regression variance decomposition) on the completed
    /// samples, as `karman sensitivity` computes it. `outputs` names the outputs (default:
    /// every output that varies). Returns `{output: {"inputs": [names], "share",
    /// "coefficient", "effect_per_std", "mean", "std": arrays in the order of "inputs",
    /// "unexplained": float, "output_mean", "output_std": float, "samples": int}}`.
    #[pyo3(signature = (outputs = None))]
    fn sensitivity<'py>(
        &self,
        py: Python<'py>,
        outputs: Option<Vec<String>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let result =
            sensitivity_of_rows(&self.definition, &self.rows, &outputs.unwrap_or_default())
                .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
        let dict = PyDict::new(py);
        for output in &result.outputs {
            let entry = PyDict::new(py);
            let names: Vec<&str> = output.inputs.iter().map(|i| i.input.as_str()).collect();
            entry.set_item("inputs", names)?;
            let column = |f: fn(&karman_mission::dispersion::InputShare) -> f64| {
                output.inputs.iter().map(f).collect::<Vec<f64>>()
            };
            entry.set_item("share", PyArray1::from_vec(py, column(|i| i.share)))?;
            entry.set_item(
                "coefficient",
                PyArray1::from_vec(py, column(|i| i.coefficient)),
            )?;
            entry.set_item(
                "effect_per_std",
                PyArray1::from_vec(py, column(|i| i.effect_per_std)),
            )?;
            entry.set_item("mean", PyArray1::from_vec(py, column(|i| i.mean)))?;
            entry.set_item("std", PyArray1::from_vec(py, column(|i| i.std)))?;
            entry.set_item("unexplained", output.unexplained)?;
            entry.set_item("output_mean", output.mean)?;
            entry.set_item("output_std", output.std)?;
            entry.set_item("samples", output.samples)?;
            dict.set_item(&output.output, entry)?;
        }
        Ok(dict)
    }

    /// Wilks' one-sided tolerance bounds of each output, as `karman tolerance --json`:
    /// `{output: {"upper", "lower", "rank", "achieved_confidence", "samples",
    /// "samples_needed", "coverage", "confidence"}}`; `upper` is the value a fraction
    /// `coverage` of flights stays below with `confidence` (None with too few samples).
    #[pyo3(signature = (outputs = None, coverage = 0.99, confidence = 0.95))]
    fn tolerance<'py>(
        &self,
        py: Python<'py>,
        outputs: Option<Vec<String>>,
        coverage: f64,
        confidence: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let bounds = tolerance_of_rows(
            &self.definition,
            &self.rows,
            &outputs.unwrap_or_default(),
            coverage,
            confidence,
        )
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
        let dict = PyDict::new(py);
        for b in &bounds {
            dict.set_item(&b.output, plain(py, b)?)?;
        }
        Ok(dict)
    }

    /// Worker threads used.
    #[getter]
    fn threads(&self) -> usize {
        self.threads
    }

    /// Wall time of the flights, s.
    #[getter]
    fn elapsed(&self) -> f64 {
        self.elapsed.as_secs_f64()
    }

    /// Samples flown per second of wall time (0 when every sample was resumed from `out`).
    #[getter]
    fn rate(&self) -> f64 {
        self.flown as f64 / self.elapsed.as_secs_f64().max(1e-9)
    }

    /// The output folder given as `out=`, if any.
    #[getter]
    fn out(&self) -> Option<PathBuf> {
        self.out.clone()
    }

    /// Inputs and outputs as one pandas DataFrame indexed by sample; needs pandas.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let pandas = py.import("pandas")?;
        let columns = Study::columns(py, &self.inputs)?;
        for (name, values) in &self.outputs {
            columns.set_item(name, PyArray1::from_slice(py, values))?;
        }
        let kwargs = PyDict::new(py);
        kwargs.set_item("index", self.index(py))?;
        pandas.getattr("DataFrame")?.call((columns,), Some(&kwargs))
    }

    /// The landing (and apogee) points with their 1/2/3-sigma ellipses, drawn with
    /// matplotlib as `landing.svg` of `karman montecarlo`; `path` saves the figure. Returns
    /// the figure.
    #[pyo3(signature = (path = None, show = false))]
    fn plot_ellipses<'py>(
        slf: &Bound<'py, Self>,
        path: Option<String>,
        show: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        slf.py()
            .import("karman._plot")?
            .getattr("plot_ellipses")?
            .call1((slf, path, show))
    }

    fn __repr__(&self) -> String {
        format!(
            "<karman.Study: {} samples (seed {}), {} failed>",
            self.index.len(),
            self.seed,
            self.failures.len()
        )
    }
}
