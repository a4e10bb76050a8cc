//! Arbitrary input never panics: the row parser and the reading of a damaged samples.csv.

use crate::common::{fly, options, study};
use karman_dispersion::{Shard, parse_row, run, summarize};
use proptest::prelude::*;

proptest! {
    #[test]
    fn parse_row_never_panics(line in ".*", inputs in 0usize..10, outputs in 0usize..10) {
        let _ = parse_row(&line, inputs, outputs);
    }

    #[test]
    fn quoted_fields_never_panic(line in "[0-9a-z,\"\\.\\-]{0,60}") {
        let _ = parse_row(&line, 2, 2);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// A samples.csv damaged anywhere (bytes replaced after a cut) is resumed or refused,
    /// never a panic.
    #[test]
    fn a_damaged_samples_file_never_panics(cut in 0usize..4000, junk in proptest::collection::vec(any::<u8>(), 0..80)) {
        let study = study(25);
        let tmp = tempfile::tempdir().expect("temporary directory");
        let dir = tmp.path().join("out");
        run(&study, &dir, &options(1, Shard::WHOLE), fly).expect("run");
        let path = dir.join("samples.csv");
        let mut bytes = std::fs::read(&path).expect("samples.csv");
        bytes.truncate(cut.min(bytes.len()));
        bytes.extend(&junk);
        std::fs::write(&path, &bytes).expect("write");
        let _ = summarize(&dir);
        let _ = run(&study, &dir, &options(1, Shard::WHOLE), fly);
    }
}
