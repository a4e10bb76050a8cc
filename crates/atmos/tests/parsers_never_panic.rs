//! Arbitrary input never panics the text parsers (sounding formats, two-column tables, the
//! Open-Meteo JSON) nor the netCDF reader wrapper.

use karman_atmos::{OpenMeteo, Sounding, WeatherGrid, parse_table};
use proptest::prelude::*;

/// Text made of the characters these formats use, plus anything.
fn texty() -> impl Strategy<Value = String> {
    prop_oneof![
        "[ 0-9.,\\-+eE\\n\\t<>/PRE#a-z:]{0,400}",
        any::<String>(),
        "( *-?[0-9]{1,5}(\\.[0-9])?){0,12}(\\n( *-?[0-9]{1,5}(\\.[0-9])?){0,12}){0,20}",
    ]
}

proptest! {
    #[test]
    fn wyoming_parser_never_panics(text in texty()) {
        let _ = Sounding::parse_wyoming(&text, "fuzz");
        let rules = format!("----------\nPRES\nhPa\n----------\n{text}");
        if let Ok(s) = Sounding::parse_wyoming(&rules, "fuzz") {
            let _ = s.profiles(6.371e6);
        }
    }

    #[test]
    fn ruc_parser_never_panics(text in texty()) {
        if let Ok(s) = Sounding::parse_noaa_ruc(&text, "fuzz") {
            let _ = s.profiles(6.371e6);
        }
    }

    #[test]
    fn table_parser_never_panics(text in texty()) {
        let _ = parse_table(&text, "fuzz");
    }

    #[test]
    fn netcdf_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..512)) {
        let mut data = b"CDF\x01".to_vec();
        data.extend(bytes);
        if let Ok(g) = WeatherGrid::from_bytes(data, "fuzz.nc") {
            let _ = g.detect_dictionary();
        }
    }

    #[test]
    fn open_meteo_reader_never_panics(
        text in "[ 0-9.,\\-e\\[\\]{}:\"a-z_]{0,300}",
        values in proptest::collection::vec(prop_oneof![
            Just("null".to_string()),
            any::<f64>().prop_map(|v| format!("{v:?}")),
            Just("\"2024-06-01T12:00\"".to_string()),
        ], 0..6),
    ) {
        let _ = OpenMeteo::parse(text.as_bytes(), "fuzz.json");
        let list = values.join(", ");
        let body = format!(
            "{{\"utc_offset_seconds\": 0, \"hourly\": {{\"time\": [{list}], \
             \"temperature_1000hPa\": [{list}], \"geopotential_height_1000hPa\": [{list}], \
             \"wind_speed_1000hPa\": [{list}], \"wind_direction_1000hPa\": [{list}], \
             \"temperature_850hPa_member03\": [{list}]}}}}"
        );
        if let Ok(f) = OpenMeteo::parse(body.as_bytes(), "fuzz.json") {
            let (first, last) = f.time_span();
            for member in 0..f.members() {
                let _ = f.profile(0.5 * (first + last), Some(member), 6.371e6);
            }
        }
    }
}
