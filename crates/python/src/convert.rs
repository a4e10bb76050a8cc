//! Values between Python and the mission format: Python data → TOML values (`from_dict`,
//! `set`), JSON-shaped reports → Python objects (lists of numbers as numpy arrays).

use numpy::PyArray1;
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// How deep dicts and lists may nest in a value given to the mission (a mission nests a few
/// levels; the limit keeps a self-referencing dict or a crafted deep one from exhausting the
/// stack, which would take the interpreter down with it).
pub const MAX_NESTING: usize = 64;

/// A Python value as a TOML value: `bool`, `int`, `float`, `str`, `datetime`-like objects
/// (their ISO text, as a TOML datetime), sequences (lists, tuples, numpy arrays) and
/// mappings with string keys. `at` names the place in messages (`rocket.mass`).
///
/// # Errors
/// `TypeError` for a value of another kind, `ValueError` for one nested more than
/// [`MAX_NESTING`] deep (a dict or list that contains itself never ends).
pub fn to_toml(value: &Bound<'_, PyAny>, at: &str) -> PyResult<toml::Value> {
    to_toml_nested(value, at, 0)
}

/// [`to_toml`] of a value `depth` levels inside the one given.
fn to_toml_nested(value: &Bound<'_, PyAny>, at: &str, depth: usize) -> PyResult<toml::Value> {
    if depth > MAX_NESTING {
        let shown: String = at.chars().take(120).collect();
        return Err(PyValueError::new_err(format!(
            "`{shown}…`: nested more than {MAX_NESTING} levels deep (a dict or list that \
             contains itself?)"
        )));
    }
    if value.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(value.extract()?));
    }
    if value.is_instance_of::<PyInt>() {
        return value
            .extract::<i64>()
            .map(toml::Value::Integer)
            .map_err(|_| {
                PyTypeError::new_err(format!(
                    "`{at}`: the integer {value} does not fit in 64 bits"
                ))
            });
    }
    if value.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(value.extract()?));
    }
    if value.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(value.extract()?));
    }
    if let Ok(dict) = value.cast::<PyDict>() {
        let mut table = toml::Table::new();
        for (key, item) in dict.iter() {
            let Ok(key) = key.extract::<String>() else {
                return Err(PyTypeError::new_err(format!(
                    "`{at}`: the key {key} is not a string"
                )));
            };
            let inner = if at.is_empty() {
                key.clone()
            } else {
                format!("{at}.{key}")
            };
            if item.is_none() {
                continue;
            }
            table.insert(key, to_toml_nested(&item, &inner, depth + 1)?);
        }
        return Ok(toml::Value::Table(table));
    }
    if value.hasattr("isoformat")? {
        let text: String = value.call_method0("isoformat")?.extract()?;
        return text
            .parse::<toml::value::Datetime>()
            .map(toml::Value::Datetime)
            .map_err(|e| {
                PyTypeError::new_err(format!("`{at}`: {text} is not a TOML datetime ({e})"))
            });
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let mut array = Vec::new();
        for (i, item) in value.try_iter()?.enumerate() {
            array.push(to_toml_nested(&item?, &format!("{at}[{i}]"), depth + 1)?);
        }
        return Ok(toml::Value::Array(array));
    }
    // numpy arrays and scalars: their plain Python form.
    if value.hasattr("tolist")? {
        return to_toml_nested(&value.call_method0("tolist")?, at, depth + 1);
    }
    let kind = value.get_type().name()?;
    Err(PyTypeError::new_err(format!(
        "`{at}`: a {kind} cannot be written in a mission (use numbers, strings, booleans, lists and dicts)"
    )))
}

/// A JSON value as a Python object: objects → dicts, arrays of numbers → float64 numpy
/// arrays, other arrays → lists, `null` → `None`.
pub fn from_json<'py>(py: Python<'py>, value: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    use serde_json::Value;
    Ok(match value {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => PyBool::new(py, *b).to_owned().into_any(),
        Value::Number(n) => match n.as_i64() {
            Some(i) if !n.is_f64() => i.into_pyobject(py)?.into_any(),
            _ => PyFloat::new(py, n.as_f64().unwrap_or(f64::NAN)).into_any(),
        },
        Value::String(s) => PyString::new(py, s).into_any(),
        Value::Array(items) if !items.is_empty() && items.iter().all(Value::is_number) => {
            let numbers: Vec<f64> = items.iter().filter_map(Value::as_f64).collect();
            PyArray1::from_vec(py, numbers).into_any()
        }
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(from_json(py, item)?)?;
            }
            list.into_any()
        }
        Value::Object(map) => {
            let dict = PyDict::new(py);
            for (key, item) in map {
                dict.set_item(key, from_json(py, item)?)?;
            }
            dict.into_any()
        }
    })
}

/// A serializable value as plain Python data through its JSON text (so objects keep their
/// fields' order): what `to_dict` methods return.
pub fn plain<'py, T: serde::Serialize + ?Sized>(
    py: Python<'py>,
    value: &T,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// A TOML value as Python data: tables → dicts (in order), arrays → lists, datetimes →
/// `datetime` objects (dates and times without a date as their text).
pub fn from_toml<'py>(py: Python<'py>, value: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        toml::Value::String(s) => PyString::new(py, s).into_any(),
        toml::Value::Integer(i) => i.into_pyobject(py)?.into_any(),
        toml::Value::Float(x) => PyFloat::new(py, *x).into_any(),
        toml::Value::Boolean(b) => PyBool::new(py, *b).to_owned().into_any(),
        toml::Value::Datetime(d) => {
            let text = d.to_string();
            if d.date.is_some() && d.time.is_some() {
                let iso = text.replace('Z', "+00:00");
                py.import("datetime")?
                    .getattr("datetime")?
                    .call_method1("fromisoformat", (iso,))?
            } else {
                PyString::new(py, &text).into_any()
            }
        }
        toml::Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(from_toml(py, item)?)?;
            }
            list.into_any()
        }
        toml::Value::Table(table) => {
            let dict = PyDict::new(py);
            for (key, item) in table {
                dict.set_item(key, from_toml(py, item)?)?;
            }
            dict.into_any()
        }
    })
}
