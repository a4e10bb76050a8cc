//! The CSV reader never panics and reads back what was written.

use std::path::Path;

use karman_math::csv::{parse_columns, parse_curve};
use proptest::prelude::*;

proptest! {
    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        let text = String::from_utf8_lossy(&bytes);
        let _ = parse_columns(&text, Path::new("fuzz.csv"));
        let _ = parse_curve(&text, Path::new("fuzz.csv"));
    }

    #[test]
    fn csv_like_strings_never_panic(text in "[0-9eE+\\-.,# \t\r\nnaifNAIF\u{feff}x]{0,200}") {
        let _ = parse_columns(&text, Path::new("fuzz.csv"));
        let _ = parse_curve(&text, Path::new("fuzz.csv"));
    }

    #[test]
    fn written_tables_read_back(
        rows in prop::collection::vec(prop::collection::vec(-1e6..1e6f64, 3), 1..30),
        comma in any::<bool>(),
        header in any::<bool>(),
    ) {
        let sep = if comma { ", " } else { "\t " };
        let mut text = String::from("# generated\n");
        if header {
            text.push_str("a,b,c\n");
        }
        for row in &rows {
            let fields: Vec<String> = row.iter().map(|v| format!("{v:e}")).collect();
            text.push_str(&fields.join(sep));
            text.push('\n');
        }
        let columns = parse_columns(&text, Path::new("t.csv")).unwrap();
        prop_assert_eq!(columns.len(), 3);
        for (r, row) in rows.iter().enumerate() {
            for (c, v) in row.iter().enumerate() {
                // `{:e}` prints the shortest representation that round-trips exactly.
                prop_assert_eq!(columns[c][r].to_bits(), v.to_bits());
            }
        }
    }
}
