//! Calendar arithmetic for weather files: UTC civil dates ↔ Unix seconds (proleptic
//! Gregorian, the algorithm of H. Hinnant, "chrono-Compatible Low-Level Date Algorithms") and
//! CF time units (`"hours since 1900-01-01 00:00:00.0"`, CF Conventions 1.11 §4.4).

/// Days from 1970-01-01 to the civil date `y-m-d` (proleptic Gregorian).
#[must_use]
pub fn days_from_civil(y: i64, m: u32, d: u32) -> i64 {
    let y = if m <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let m = i64::from(m);
    let doy = (153 * (if m > 2 { m - 3 } else { m + 9 }) + 2) / 5 + i64::from(d) - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

/// The civil date `(y, m, d)` of a day count from 1970-01-01.
#[must_use]
pub fn civil_from_days(z: i64) -> (i64, u32, u32) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    let y = yoe + era * 400 + i64::from(m <= 2);
    (y, m, d)
}

/// Unix time (s) of a UTC civil date and time.
#[must_use]
pub fn unix_seconds(y: i64, month: u32, day: u32, hour: u32, minute: u32, second: f64) -> f64 {
    days_from_civil(y, month, day) as f64 * 86_400.0
        + f64::from(hour) * 3600.0
        + f64::from(minute) * 60.0
        + second
}

/// ISO 8601 rendering (`YYYY-MM-DDTHH:MM:SSZ`) of a Unix time, for messages.
#[must_use]
pub fn iso8601(unix: f64) -> String {
    if !unix.is_finite() {
        return format!("{unix}");
    }
    let secs = unix.round() as i64;
    let (y, m, d) = civil_from_days(secs.div_euclid(86_400));
    let rem = secs.rem_euclid(86_400);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
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
        if !(1..=12).contains(&m) || !(1..=31).contains(&d) {
            return None;
        }
        // Time of day, then an optional offset ("Z", "UTC", "+hh:mm", "-hh").
        let (clock, offset) = split_offset(time);
        let mut tp = clock.split(':');
        let hh: u32 = tp
            .next()
            .filter(|s| !s.is_empty())
            .map_or(Some(0), |s| s.parse().ok())?;
        let mm: u32 = tp.next().map_or(Some(0), |s| s.parse().ok())?;
        let ss: f64 = tp.next().map_or(Some(0.0), |s| s.parse().ok())?;
        if hh > 24 || mm > 59 || !(0.0..61.0).contains(&ss) {
            return None;
        }
        Some(TimeUnits {
            scale,
            epoch: unix_seconds(y, m, d, hh, mm, ss) - offset?,
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
    fn civil_round_trip() {
        for days in [-800_000_i64, -1, 0, 1, 18_000, 20_000, 2_000_000] {
            let (y, m, d) = civil_from_days(days);
            assert_eq!(days_from_civil(y, m, d), days);
        }
        assert_eq!(days_from_civil(1970, 1, 1), 0);
        assert_eq!(days_from_civil(2000, 3, 1), 11_017);
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
