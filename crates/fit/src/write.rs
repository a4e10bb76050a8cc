//! The fitted copy of a mission: the user's file, its comments and layout kept (`toml_edit`),
//! each fitted value set in place, a header saying what was fitted to what.

use std::path::{Path, PathBuf};

use karman_mission::Mission;
use karman_mission::dispersion::files::write_atomic;
use karman_mission::paths::{self, Input};
use toml_edit::{Array, DocumentMut, Item, Value};

use crate::error::FitError;
use crate::fit::{Fit, FittedInput, Nominal};

/// Writes `mission` with the fitted values of `fit` to `out` (atomically), a header naming
/// `source` (the log) and each fitted factor with its uncertainty; relative data-file paths
/// are made absolute when `out` is in another folder, so the copy reads the same files. The
/// copy is loaded back before it is kept: a copy that does not load is an error and leaves
/// no file.
///
/// # Errors
/// [`FitError::Write`]: the mission file cannot be read or parsed, an input has no key in
/// the file to hold its fitted value (a derived knob such as `motor.total_impulse`, or the
/// `"estimate"` drag), the file cannot be written, or the copy does not load.
pub fn write_fitted(
    mission: &Mission,
    fit: &Fit,
    source: &str,
    out: &Path,
) -> Result<(), FitError> {
    let file = mission.path.display().to_string();
    let fail = |file: &str, reason: String| FitError::Write {
        file: file.to_owned(),
        reason,
    };
    let text = std::fs::read_to_string(&mission.path).map_err(|e| fail(&file, e.to_string()))?;
    let mut doc: DocumentMut = text
        .parse()
        .map_err(|e: toml_edit::TomlError| fail(&file, e.to_string()))?;
    for input in &fit.inputs {
        set_fitted(&mut doc, mission, input).map_err(|reason| fail(&file, reason))?;
    }
    let out_dir = absolute(out.parent().unwrap_or(Path::new(".")));
    if absolute(&mission.dir) != out_dir {
        rebase_paths(doc.as_table_mut(), &absolute(&mission.dir));
    }
    let mut header = format!(
        "# Fitted by `karman fit` to {source}: {} ({} flights; RMS {}).\n",
        fit.termination,
        fit.flights,
        fit.phases
            .iter()
            .map(|p| format!(
                "{} {:.3} -> {:.3} {}",
                p.phase,
                p.rms_before,
                p.rms_after,
                p.phase.unit()
            ))
            .collect::<Vec<_>>()
            .join(", ")
    );
    for input in &fit.inputs {
        let value = match (input.value(), input.value_std()) {
            (Some(v), Some(s)) => format!(", value {v:.6} ± {s:.6}"),
            _ => String::new(),
        };
        header.push_str(&format!(
            "#   {}: factor {:.5} ± {:.5} on the nominal{value}\n",
            input.path, input.factor, input.factor_std
        ));
    }
    if let Some([offset, std]) = fit.clock_offset_s {
        header.push_str(&format!(
            "#   the log's clock offset: {offset:+.3} ± {std:.3} s\n"
        ));
    }
    for warning in &fit.warnings {
        header.push_str(&format!("#   warning: {warning}\n"));
    }
    header.push_str(&format!("# From {file}.\n"));
    let written = format!("{header}{doc}");
    let out_name = out.display().to_string();
    write_atomic(out, written.as_bytes()).map_err(|e| fail(&out_name, e.to_string()))?;
    if let Err(e) = karman_mission::load(out, &[]) {
        let _ = std::fs::remove_file(out);
        return Err(fail(
            &out_name,
            format!("the fitted copy does not load: {e}"),
        ));
    }
    Ok(())
}

/// The path made absolute against the current directory (unchanged when that fails).
fn absolute(path: &Path) -> PathBuf {
    std::path::absolute(path).unwrap_or_else(|_| path.to_owned())
}

/// `new` in place of the value at `segments` under `table`, the old value's decor (its
/// comment) kept; a numeric segment indexes an array of tables or of values. `false` when
/// the path names no value in the file.
fn set_in_table(table: &mut toml_edit::Table, segments: &[&str], new: &Value) -> bool {
    let Some((first, rest)) = segments.split_first() else {
        return false;
    };
    let Some(item) = table.get_mut(first) else {
        return false;
    };
    match item {
        Item::Value(value) if rest.is_empty() => {
            replace(value, new);
            true
        }
        Item::Value(value) => set_in_value(value, rest, new),
        Item::Table(inner) => set_in_table(inner, rest, new),
        Item::ArrayOfTables(tables) => match rest.split_first() {
            Some((index, rest)) if !rest.is_empty() => index
                .parse::<usize>()
                .ok()
                .and_then(|i| tables.get_mut(i))
                .is_some_and(|t| set_in_table(t, rest, new)),
            _ => false,
        },
        Item::None => false,
    }
}

/// [`set_in_table`] inside an inline table or an array.
fn set_in_value(value: &mut Value, segments: &[&str], new: &Value) -> bool {
    let Some((first, rest)) = segments.split_first() else {
        return false;
    };
    let inner = match value {
        Value::InlineTable(table) => table.get_mut(first),
        Value::Array(array) => first.parse::<usize>().ok().and_then(|i| array.get_mut(i)),
        _ => None,
    };
    match inner {
        Some(inner) if rest.is_empty() => {
            replace(inner, new);
            true
        }
        Some(inner) => set_in_value(inner, rest, new),
        None => false,
    }
}

/// `new` in place of `old`, with `old`'s decor.
fn replace(old: &mut Value, new: &Value) {
    let decor = old.decor().clone();
    *old = new.clone();
    *old.decor_mut() = decor;
}

/// A TOML float of `v` (its shortest round-trip form).
fn float(v: f64) -> Value {
    Value::from(v)
}

/// Sets the fitted value of one input in `doc`.
fn set_fitted(doc: &mut DocumentMut, mission: &Mission, input: &FittedInput) -> Result<(), String> {
    let path = input.path.as_str();
    let resolved = paths::resolve(&mission.spec, path).map_err(|e| e.to_string())?;
    let new: Value = match (&input.nominal, resolved) {
        (_, Input::Knob(_)) => {
            return Err(format!(
                "`{path}` is a derived knob with no key of its own; the fitted factor is {:.5}",
                input.factor
            ));
        }
        (Nominal::Number(_), _) => float(input.value().unwrap_or(f64::NAN)),
        (Nominal::Array(values), _) => {
            let mut array = Array::new();
            for v in values {
                array.push(v * input.factor);
            }
            Value::Array(array)
        }
        (Nominal::Curve, Input::Curve(curve)) => {
            if curve.is_estimate() {
                return Err(format!(
                    "`{path}` is the estimated drag, which takes no factor in a mission file; \
                     the fitted factor is {:.5}",
                    input.factor
                ));
            }
            let points = curve
                .points(&mission.dir)
                .map_err(|e| format!("`{path}`: {e}"))?;
            let mut array = Array::new();
            for [x, y] in points {
                let mut point = Array::new();
                point.push(x);
                point.push(y * input.factor);
                point.decor_mut().set_prefix("\n    ");
                array.push_formatted(Value::Array(point));
            }
            array.set_trailing("\n");
            array.set_trailing_comma(true);
            Value::Array(array)
        }
        (Nominal::Curve, _) => {
            return Err(format!("`{path}` is a table the fitted copy cannot scale"));
        }
    };
    let segments: Vec<&str> = path.split('.').collect();
    if !set_in_table(doc.as_table_mut(), &segments, &new) {
        return Err(format!(
            "`{path}` has no value in the mission file (it is left at its default): add the \
             key with the fitted value by hand"
        ));
    }
    Ok(())
}

/// Makes every relative string that names an existing file of `dir` absolute.
fn rebase_paths(table: &mut toml_edit::Table, dir: &Path) {
    for (_, item) in table.iter_mut() {
        rebase_item(item, dir);
    }
}

fn rebase_item(item: &mut Item, dir: &Path) {
    match item {
        Item::Table(t) => rebase_paths(t, dir),
        Item::ArrayOfTables(a) => {
            for t in a.iter_mut() {
                rebase_paths(t, dir);
            }
        }
        Item::Value(v) => rebase_value(v, dir),
        Item::None => {}
    }
}

fn rebase_value(value: &mut Value, dir: &Path) {
    match value {
        Value::String(s) => {
            let text = s.value().clone();
            let candidate = Path::new(&text);
            if candidate.is_relative() && !text.is_empty() && dir.join(candidate).is_file() {
                let decor = s.decor().clone();
                let mut new = toml_edit::Formatted::new(dir.join(candidate).display().to_string());
                *new.decor_mut() = decor;
                *s = new;
            }
        }
        Value::Array(a) => {
            for v in a.iter_mut() {
                rebase_value(v, dir);
            }
        }
        Value::InlineTable(t) => {
            for (_, v) in t.iter_mut() {
                rebase_value(v, dir);
            }
        }
        _ => {}
    }
}
