//! The parsed TOML document of a mission, with the source span of every key and value:
//! `--set` overrides are applied to it, it is deserialized into the schema with every error
//! located, and validation looks up the line of a dotted key in it.
//!
//! Values inserted by an override get a *sentinel span* just past the end of the file text
//! (`len + 1 + index of the override`), so an error in them is reported as coming from that
//! `--set` argument rather than from a line of the file.

use crate::error::{Location, OverrideError, Problem, ProblemKind};
use crate::overrides::Override;
use crate::schema::surfaces::keys_of;
use crate::schema::{MissionSpec, SurfaceType};
use serde::Deserialize;
use std::borrow::Cow;
use std::collections::BTreeMap;
use std::ops::Range;
use toml::Spanned;
use toml::de::{DeArray, DeTable, DeValue};

/// The largest magnitude of a float a mission may hold: no physical input (a thrust of at most
/// 1e9 N, a tank pressure, a height) comes near it, and below it the products and squares the
/// models form stay finite, so an absurd value (`1e300`) is refused at its key rather than
/// ending as an infinity inside a model built from it.
pub(crate) const MAX_INPUT_MAGNITUDE: f64 = 1e15;

/// The `expected` of the [`ProblemKind::OutOfRange`] of a float beyond
/// [`MAX_INPUT_MAGNITUDE`] (a problem dropped when the key's own check reports it too).
pub(crate) const BEYOND_ANY_INPUT: &str = "no input of a mission exceeds 1e15 in magnitude";

/// Largest number of schema errors collected from one file before giving up.
const MAX_SCHEMA_ERRORS: usize = 50;

/// A mission file's TOML tree with spans, after overrides.
pub(crate) struct Document<'a> {
    text: &'a str,
    root: Spanned<DeTable<'a>>,
    overrides: Vec<String>,
}

/// A TOML syntax error, located.
pub(crate) struct SyntaxError {
    pub line: usize,
    pub column: usize,
    pub message: String,
}

/// Line and column (1-based, column in characters) of byte `offset` of `text`.
pub(crate) fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = text.get(..offset).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let column = before
        .get(line_start..)
        .map_or(1, |s| s.chars().count() + 1);
    (line, column)
}

/// A lookup key for a table of any lifetime (spans are ignored by key comparison).
fn key<'k>(segment: &str) -> Spanned<Cow<'k, str>> {
    Spanned::new(0..0, Cow::Owned(segment.to_owned()))
}

/// Rebuilds `value` with `span` on it and on everything inside it.
fn respan<'a>(value: DeValue<'a>, span: &Range<usize>) -> Spanned<DeValue<'a>> {
    let inner = match value {
        DeValue::Array(items) => {
            let mut out = DeArray::new();
            for item in items.iter() {
                out.push(respan(item.get_ref().clone(), span));
            }
            DeValue::Array(out)
        }
        DeValue::Table(table) => {
            let mut out = DeTable::new();
            for (k, v) in table {
                out.insert(
                    Spanned::new(span.clone(), k.into_inner()),
                    respan(v.into_inner(), span),
                );
            }
            DeValue::Table(out)
        }
        other => other,
    };
    Spanned::new(span.clone(), inner)
}

impl<'a> Document<'a> {
    /// Parses `text` as TOML.
    pub fn parse(text: &'a str) -> Result<Self, SyntaxError> {
        match DeTable::parse(text) {
            Ok(root) => Ok(Document {
                text,
                root,
                overrides: Vec::new(),
            }),
            Err(error) => {
                let (line, column) = line_column(text, error.span().map_or(0, |s| s.start));
                Err(SyntaxError {
                    line,
                    column,
                    message: error.message().trim_end().to_owned(),
                })
            }
        }
    }

    /// Where byte `offset` (a file offset or an override's sentinel) is.
    pub fn location(&self, offset: usize) -> Location {
        if offset > self.text.len() {
            let index = offset - self.text.len() - 1;
            if let Some(text) = self.overrides.get(index) {
                return Location::Override { text: text.clone() };
            }
        }
        let (line, column) = line_column(self.text, offset);
        Location::File { line, column }
    }

    /// Applies one override: every table on its path must exist; its last key may be new
    /// (the schema then decides whether it names an optional key).
    pub fn apply(&mut self, item: &'a Override) -> Result<(), Problem> {
        let index = self.overrides.len();
        self.overrides.push(item.text.clone());
        let sentinel = self.text.len() + 1 + index;
        let span = sentinel..sentinel + 1;
        let fail = |kind: ProblemKind| Problem {
            location: Location::Override {
                text: item.text.clone(),
            },
            key: item.path.join("."),
            kind,
        };
        let value = DeValue::parse(&item.value).map_err(|e| {
            fail(ProblemKind::Schema {
                message: OverrideError::Value {
                    value: item.value.clone(),
                    message: e.message().trim_end().to_owned(),
                }
                .to_string(),
            })
        })?;
        let Some((last, tables)) = item.path.split_last() else {
            return Err(fail(ProblemKind::UnknownPath {
                path: String::new(),
                reason: "the path is empty".to_owned(),
            }));
        };
        let mut table = self.root.get_mut();
        let mut depth = 0;
        while depth < tables.len() {
            let segment = &tables[depth];
            let here = item.path[..=depth].join(".");
            let available: Vec<String> = table.keys().map(|k| k.get_ref().to_string()).collect();
            let entry = table.get_mut(&key(segment)).ok_or_else(|| {
                fail(ProblemKind::UnknownPath {
                    path: item.path.join("."),
                    reason: format!(
                        "the mission has no `{here}`{}",
                        if available.is_empty() {
                            String::new()
                        } else {
                            format!(" (keys there: {})", available.join(", "))
                        }
                    ),
                })
            })?;
            match entry.get_mut() {
                DeValue::Table(inner) => table = inner,
                // An array is entered by a 0-based index: an array of tables followed by a
                // key (`motor.tanks.0.position`), the last segment for an entry of an array of
                // values (`rocket.inertia.0`).
                DeValue::Array(items) => {
                    let count = items.len();
                    let index = item
                        .path
                        .get(depth + 1)
                        .and_then(|i| i.parse::<usize>().ok());
                    let entry = index.and_then(|i| items.get_mut(i));
                    if depth + 1 == tables.len() {
                        if let Some(entry) = entry
                            && !entry.get_ref().is_table()
                        {
                            *entry = respan(value.into_inner(), &span);
                            return Ok(());
                        }
                    } else if let Some(DeValue::Table(inner)) = entry.map(Spanned::get_mut) {
                        table = inner;
                        depth += 2;
                        continue;
                    }
                    return Err(fail(ProblemKind::UnknownPath {
                        path: item.path.join("."),
                        reason: format!(
                            "`{here}` holds {count} entries, addressed by their index 0..{count} \
                             (followed by a key in an array of tables)"
                        ),
                    }));
                }
                _ => {
                    return Err(fail(ProblemKind::UnknownPath {
                        path: item.path.join("."),
                        reason: format!("`{here}` is a value, not a table"),
                    }));
                }
            }
            depth += 1;
        }
        let value = respan(value.into_inner(), &span);
        table.insert(Spanned::new(span, Cow::Borrowed(last.as_str())), value);
        Ok(())
    }

    /// The dotted key path of the deepest entry whose key or value contains `offset`.
    fn path_at(&self, offset: usize) -> Vec<String> {
        fn walk(
            table: &DeTable<'_>,
            offset: usize,
            prefix: &mut Vec<String>,
            best: &mut Vec<String>,
        ) {
            for (k, v) in table.iter() {
                prefix.push(k.get_ref().to_string());
                let here = k.span().contains(&offset) || v.span().contains(&offset);
                if here && prefix.len() > best.len() {
                    best.clone_from(prefix);
                }
                if let DeValue::Table(inner) = v.get_ref() {
                    walk(inner, offset, prefix, best);
                }
                prefix.pop();
            }
        }
        let mut best = Vec::new();
        walk(self.root.get_ref(), offset, &mut Vec::new(), &mut best);
        best
    }

    /// The span of the value at a dotted path, or of its deepest existing table. A numeric
    /// segment indexes an array of tables (`motor.tanks.0.position`).
    pub fn span_of(&self, path: &[&str]) -> Range<usize> {
        let mut span = 0..0;
        let mut table = self.root.get_ref();
        let mut segments = path.iter();
        while let Some(segment) = segments.next() {
            let Some((k, v)) = table.get_key_value(&key(segment)) else {
                break;
            };
            span = if v.get_ref().is_table() {
                k.span()
            } else {
                v.span()
            };
            match v.get_ref() {
                DeValue::Table(inner) => table = inner,
                DeValue::Array(items) => {
                    let Some(item) = segments
                        .next()
                        .and_then(|i| i.parse::<usize>().ok())
                        .and_then(|i| items.get(i))
                    else {
                        break;
                    };
                    match item.get_ref() {
                        DeValue::Table(inner) => {
                            span = inner
                                .iter()
                                .next()
                                .map_or_else(|| item.span(), |(k, _)| k.span());
                            table = inner;
                        }
                        _ => {
                            span = item.span();
                            break;
                        }
                    }
                }
                _ => break,
            }
        }
        span
    }

    /// A problem at the dotted path `key` (located at its value, or its deepest existing
    /// table when the key was defaulted).
    pub fn problem(&self, key: &str, kind: ProblemKind) -> Problem {
        let path: Vec<&str> = key.split('.').collect();
        Problem {
            location: self.location(self.span_of(&path).start),
            key: key.to_owned(),
            kind,
        }
    }

    /// The location of every key of the document by dotted path (tables at their key,
    /// values at their value), so that errors found after validation, while building the
    /// models, can still point at the key they concern.
    pub fn key_locations(&self) -> BTreeMap<String, Location> {
        fn walk(
            doc: &Document<'_>,
            table: &DeTable<'_>,
            prefix: &str,
            out: &mut BTreeMap<String, Location>,
        ) {
            for (k, v) in table.iter() {
                let path = if prefix.is_empty() {
                    k.get_ref().to_string()
                } else {
                    format!("{prefix}.{}", k.get_ref())
                };
                match v.get_ref() {
                    DeValue::Table(inner) => {
                        out.insert(path.clone(), doc.location(k.span().start));
                        walk(doc, inner, &path, out);
                    }
                    // An array of tables (`[[motor.tanks]]`): entries by index, each located
                    // at its first key.
                    DeValue::Array(items) if items.iter().any(|item| item.get_ref().is_table()) => {
                        out.insert(path.clone(), doc.location(k.span().start));
                        for (index, item) in items.iter().enumerate() {
                            let entry = format!("{path}.{index}");
                            if let DeValue::Table(inner) = item.get_ref() {
                                let start = inner
                                    .iter()
                                    .next()
                                    .map_or(item.span().start, |(k, _)| k.span().start);
                                out.insert(entry.clone(), doc.location(start));
                                walk(doc, inner, &entry, out);
                            }
                        }
                    }
                    _ => {
                        out.insert(path, doc.location(v.span().start));
                    }
                }
            }
        }
        let mut out = BTreeMap::new();
        walk(self, self.root.get_ref(), "", &mut out);
        out
    }

    /// Every NaN or infinite float of the document, except a `+inf` at one of `allow_inf`, and
    /// every float beyond [`MAX_INPUT_MAGNITUDE`] (an [`ProblemKind::OutOfRange`] whose
    /// `expected` is [`BEYOND_ANY_INPUT`]).
    pub fn non_finite(&self, allow_inf: &[&str]) -> Vec<Problem> {
        fn walk(
            doc: &Document<'_>,
            value: &Spanned<DeValue<'_>>,
            path: &str,
            allow_inf: &[&str],
            out: &mut Vec<Problem>,
        ) {
            match value.get_ref() {
                DeValue::Float(f) => {
                    let number: f64 = f.as_str().replace('_', "").parse().unwrap_or(f64::NAN);
                    // `allow_inf` names keys without the indices of array entries.
                    let allowed = number.is_infinite() && number > 0.0 && {
                        let key: Vec<&str> = path
                            .split('.')
                            .filter(|s| s.parse::<usize>().is_err())
                            .collect();
                        allow_inf.contains(&key.join(".").as_str())
                    };
                    if !number.is_finite() && !allowed {
                        out.push(Problem {
                            location: doc.location(value.span().start),
                            key: path.to_owned(),
                            kind: ProblemKind::NotFinite { value: number },
                        });
                    } else if number.is_finite() && number.abs() > MAX_INPUT_MAGNITUDE {
                        out.push(Problem {
                            location: doc.location(value.span().start),
                            key: path.to_owned(),
                            kind: ProblemKind::OutOfRange {
                                value: number,
                                expected: BEYOND_ANY_INPUT,
                            },
                        });
                    }
                }
                // An entry of an array of tables (`[[rocket.sensors]]`, `[[stages]]`) is
                // named by its index, as every other problem names it; a number of a plain
                // array by its key.
                DeValue::Array(items) => {
                    for (index, item) in items.iter().enumerate() {
                        if matches!(item.get_ref(), DeValue::Table(_)) {
                            walk(doc, item, &format!("{path}.{index}"), allow_inf, out);
                        } else {
                            walk(doc, item, path, allow_inf, out);
                        }
                    }
                }
                DeValue::Table(table) => {
                    for (k, v) in table.iter() {
                        let child = if path.is_empty() {
                            k.get_ref().to_string()
                        } else {
                            format!("{path}.{}", k.get_ref())
                        };
                        walk(doc, v, &child, allow_inf, out);
                    }
                }
                _ => {}
            }
        }
        let mut out = Vec::new();
        for (k, v) in self.root.get_ref().iter() {
            walk(self, v, k.get_ref(), allow_inf, &mut out);
        }
        out
    }

    /// Removes the entry at `path` from `root` (used to go on after a schema error).
    fn remove(root: &mut DeTable<'_>, path: &[String]) -> bool {
        let Some((last, tables)) = path.split_last() else {
            return false;
        };
        let mut table = root;
        for segment in tables {
            match table.get_mut(&key(segment)).map(Spanned::get_mut) {
                Some(DeValue::Table(inner)) => table = inner,
                _ => return false,
            }
        }
        table.remove(&key(last)).is_some()
    }

    /// Words a deserializer message for people: Rust type names become words, and an
    /// unknown-key message inside a surface table lists the keys of that surface's type (the
    /// deserializer lists the keys of every type).
    fn explain(&self, path: &[String], message: String) -> String {
        let message = message
            .replace("expected f64", "expected a number")
            .replace("expected u32", "expected a non-negative integer")
            .replace("expected u64", "expected a non-negative integer");
        let [rocket, surfaces, name, _] = path else {
            return message;
        };
        if rocket != "rocket" || surfaces != "surfaces" || !message.starts_with("unknown field") {
            return message;
        }
        let surface_type = self
            .root
            .get_ref()
            .get(&key("rocket"))
            .and_then(|v| v.get_ref().get("surfaces"))
            .and_then(|v| v.get_ref().get(name.as_str()))
            .and_then(|v| v.get_ref().get("type"))
            .and_then(|v| v.get_ref().as_str())
            .and_then(SurfaceType::parse);
        let (Some(surface_type), Some((head, _))) =
            (surface_type, message.split_once(", expected"))
        else {
            return message;
        };
        let accepted: Vec<String> = keys_of(surface_type)
            .0
            .iter()
            .map(|k| format!("`{k}`"))
            .collect();
        format!(
            "{head}; a {surface_type} surface accepts `type`, {}",
            accepted.join(", ")
        )
    }

    /// Deserializes the document into the schema. On failure, every schema error is
    /// collected: the offending entry is removed and deserialization tried again, until it
    /// succeeds, a key is reported missing, or [`MAX_SCHEMA_ERRORS`] is reached.
    pub fn deserialize(&self) -> Result<MissionSpec, Vec<Problem>> {
        let mut root = self.root.clone();
        let mut problems = Vec::new();
        let mut removed: Vec<Vec<String>> = Vec::new();
        loop {
            let deserializer = toml::de::Deserializer::from(root.clone());
            let error = match MissionSpec::deserialize(deserializer) {
                Ok(spec) if problems.is_empty() => return Ok(spec),
                Ok(_) => return Err(problems),
                Err(error) => error,
            };
            let message = error.message().trim_end().to_owned();
            // An error on the whole document (a missing top-level table) or without a span
            // concerns no key.
            let span = error.span().filter(|span| *span != self.root.span());
            let offset = span.as_ref().map_or(0, |s| s.start);
            let path = if span.is_some() {
                self.path_at(offset)
            } else {
                Vec::new()
            };
            let message = self.explain(&path, message);
            let missing = message.starts_with("missing field");
            // An error about a key removed after an earlier error is a consequence of that
            // removal, not a new problem.
            let caused_by_removal = removed.iter().any(|r| {
                r.split_last().is_some_and(|(last, parent)| {
                    message.contains(&format!("`{last}`")) && parent.starts_with(&path)
                })
            });
            if !caused_by_removal {
                problems.push(Problem {
                    location: self.location(offset),
                    key: path.join("."),
                    kind: ProblemKind::Schema { message },
                });
            }
            if missing
                || problems.len() >= MAX_SCHEMA_ERRORS
                || !Self::remove(root.get_mut(), &path)
            {
                return Err(problems);
            }
            removed.push(path);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_column_counts_characters() {
        let text = "a = 1\nbé = 2\n";
        assert_eq!(line_column(text, 0), (1, 1));
        assert_eq!(line_column(text, 6), (2, 1));
        // 'é' is two bytes: the '=' after "bé " is byte 10, column 4.
        assert_eq!(line_column(text, 10), (2, 4));
        assert_eq!(line_column(text, 1000), (3, 1));
    }

    #[test]
    fn path_at_finds_keys_in_sections() {
        let text = "[rocket]\nradius = 1\n[rocket.surfaces.nose]\nlength = 2\n";
        let doc = Document::parse(text).unwrap_or_else(|_| panic!("valid TOML"));
        let offset = text.find("length").expect("present");
        assert_eq!(
            doc.path_at(offset),
            ["rocket", "surfaces", "nose", "length"]
        );
        let offset = text.find("radius").expect("present");
        assert_eq!(doc.path_at(offset), ["rocket", "radius"]);
    }
}
