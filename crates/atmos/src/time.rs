//! Calendar arithmetic for weather files: UTC civil dates ↔ Unix seconds (proleptic
//! Gregorian, on the `chrono` crate, which also rejects dates that do not exist) and CF time
//! units (`"hours since 1900-01-01 00:00:00.0"`, CF Conventions 1.11 §4.4).

use chrono::{DateTime, Datelike, NaiveDate, Timelike};

/// Unix time (s) of a UTC civil date and time; `None` for a date or time that does not exist
/// (February 31, hour 25).
#[must_use]
pub fn unix_seconds(
    year: i64,
    month: u32,
    day: u32,
    hour: u32,
    minute: u32,
    second: f64,
) -> Option<f64> {
    let date = NaiveDate::from_ymd_opt(i32::try_from(year).ok()?, month, day)?;
    let midnight = date.and_hms_opt(hour, minute, 0)?.and_utc().timestamp();
    Some(midnight as f64 + second)
}

/// The UTC calendar date of a Unix time (the day it falls in); `None` outside chrono's range.
#[must_use]
pub fn utc_date(unix: f64) -> Option<NaiveDate> {
    let secs = unix.floor();
    if !secs.is_finite() || secs.abs() > 1e15 {
        return None;
    }
    DateTime::from_timestamp(secs as i64, 0).map(|t| t.date_naive())
}

/// ISO 8601 rendering (`YYYY-MM-DDTHH:MM:SSZ`) of a Unix time, for messages.
#[must_use]
pub fn iso8601(unix: f64) -> String {
    let secs = unix.round();
    let time = (secs.is_finite() && secs.abs() < 1e15)
        .then(|| DateTime::from_timestamp(secs as i64, 0))
        .flatten();
    match time {
        Some(t) => format!(
            "{:04}-{:02}-{:02}T{:02}:{:02}:{:02}Z",
            t.year(),
            t.month(),
            t.day(),
            t.hour(),
            t.minute(),
            t.second()
        ),
        None => format!("{unix}"),
    }
}

/// A parsed CF time unit: `value × scale + epoch` is Unix time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeUnits {
    /// Seconds per unit.
    pub scale: f64,
    /// Unix time of the reference date.
    pub epoch: f64,
}

impl TimeUnits {
    /// Parses `"<unit> since <date>[( |T)<time>][ <offset>|Z]"`; `unit` is one of seconds,
    /// minutes, hours, days (singular or plural, or the abbreviations s, sec, min, h, hr, d).
    /// Returns `None` when the text is not of that form.
    #[must_use]
    pub fn parse(text: &str) -> Option<TimeUnits> {
        let lower = text.trim().to_ascii_lowercase();
        let (unit, rest) = lower.split_once(" since ")?;
        let scale = match unit.trim() {
            "seconds" | "second" | "s" | "sec" | "secs" => 1.0,
            "minutes" | "minute" | "min" | "mins" => 60.0,
            "hours" | "hour" | "h" | "hr" | "hrs" => 3600.0,
            "days" | "day" | "d" => 86_400.0,
            _ => return None,
        };
        let rest = rest.trim();
        let (date, time) = match rest.find(['t', ' ']) {
            Some(i) => (&rest[..i], rest[i + 1..].trim()),
            None => (rest, ""),
        };
        let mut dp = date.split('-');
        let y: i64 = dp.next()?.parse().ok()?;
        let m: u32 = dp.next().map_or(Some(1), |s| s.parse().ok())?;
        let d: u32 = dp.next().map_or(Some(1), |s| s.parse().ok())?;
        // Time of day, then an optional offset ("Z", "UTC", "+hh:mm", "-hh").
        let (clock, offset) = split_offset(time);
        let mut tp = clock.split(':');
        let hh: u32 = tp
            .next()
            .filter(|s| !s.is_empty())
            .map_or(Some(0), |s| s.parse().ok())?;
        let mm: u32 = tp.next().map_or(Some(0), |s| s.parse().ok())?;
        let ss: f64 = tp.next().map_or(Some(0.0), |s| s.parse().ok())?;
        if !(0.0..61.0).contains(&ss) {
            return None;
        }
        Some(TimeUnits {
            scale,
            epoch: unix_seconds(y, m, d, hh, mm, ss)? - offset?,
        })
    }

    /// Unix time of a value in these units.
    #[inline]
    #[must_use]
    pub fn to_unix(&self, value: f64) -> f64 {
        value * self.scale + self.epoch
    }
}

/// Splits `"12:00:00+01:00"` into the clock and the offset in seconds (`None` if malformed).
fn split_offset(time: &str) -> (&str, Option<f64>) {
    let time = time.trim();
    let time = time
        .strip_suffix("utc")
        .or_else(|| time.strip_suffix('z'))
        .unwrap_or(time);
    let time = time.trim();
    match time.find(['+', '-']) {
        Some(i) => {
            let (clock, off) = time.split_at(i);
            let sign = if off.starts_with('-') { -1.0 } else { 1.0 };
            let mut parts = off[1..].trim().split(':');
            let hh: Option<f64> = parts.next().and_then(|s| s.parse().ok());
            let mm: Option<f64> = parts.next().map_or(Some(0.0), |s| s.parse().ok());
            (
                clock.trim(),
                hh.zip(mm).map(|(h, m)| sign * (h * 3600.0 + m * 60.0)),
            )
        }
        None => (time, Some(0.0)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dates_that_do_not_exist_are_refused() {
        assert_eq!(unix_seconds(1970, 1, 1, 0, 0, 0.0), Some(0.0));
        assert_eq!(
            unix_seconds(2000, 3, 1, 0, 0, 0.0),
            Some(11_017.0 * 86_400.0)
        );
        assert_eq!(unix_seconds(2026, 2, 31, 12, 0, 0.0), None);
        assert_eq!(unix_seconds(2025, 2, 29, 12, 0, 0.0), None);
        assert!(unix_seconds(2024, 2, 29, 12, 0, 0.0).is_some());
        assert_eq!(unix_seconds(2026, 1, 1, 25, 0, 0.0), None);
        assert!(TimeUnits::parse("hours since 1900-02-30 00:00:00").is_none());
        assert_eq!(
            utc_date(-1.0),
            NaiveDate::from_ymd_opt(1969, 12, 31),
            "the day a time falls in"
        );
    }

    #[test]
    fn era5_legacy_units() {
        // bella_lui's ERA5 file: hours since 1900; 1053157 h is 2020-02-22T13:00Z.
        let u = TimeUnits::parse("hours since 1900-01-01 00:00:00.0").expect("units");
        assert_eq!(iso8601(u.to_unix(1_053_157.0)), "2020-02-22T13:00:00Z");
        let v = TimeUnits::parse("seconds since 1970-01-01").expect("units");
        assert_eq!(iso8601(v.to_unix(1_665_655_200.0)), "2022-10-13T10:00:00Z");
    }

    #[test]
    fn offsets_and_garbage() {
        let u = TimeUnits::parse("days since 2000-01-01T00:00:00+01:00").expect("units");
        assert_eq!(iso8601(u.to_unix(0.0)), "1999-12-31T23:00:00Z");
        assert!(TimeUnits::parse("fortnights since 2000-01-01").is_none());
        assert!(TimeUnits::parse("hours since yesterday").is_none());
        assert!(TimeUnits::parse("hours").is_none());
    }
}
