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

/// Any number, finite or not, as a distribution parameter.
fn number() -> BoxedStrategy<f64> {
    prop_oneof![
        any::<f64>(),
        -1e3..1e3f64,
        Just(0.0),
        Just(f64::INFINITY),
        Just(f64::NAN),
        Just(1e-300),
        Just(1e300),
    ]
    .boxed()
}

/// Every distribution kind with arbitrary parameters (a truncation of one among them).
fn distribution() -> BoxedStrategy<karman_dispersion::Distribution> {
    use karman_dispersion::Distribution as D;
    let plain = prop_oneof![
        number().prop_map(|scale| D::Exponential { scale }).boxed(),
        (number(), number())
            .prop_map(|(shape, scale)| D::Gamma { shape, scale })
            .boxed(),
        (number(), number())
            .prop_map(|(loc, scale)| D::Gumbel { loc, scale })
            .boxed(),
        (number(), number())
            .prop_map(|(loc, scale)| D::Laplace { loc, scale })
            .boxed(),
        (number(), number())
            .prop_map(|(loc, scale)| D::Logistic { loc, scale })
            .boxed(),
        number().prop_map(|lam| D::Poisson { lam }).boxed(),
        (number(), number())
            .prop_map(|(mean, scale)| D::Wald { mean, scale })
            .boxed(),
        (any::<u64>(), number())
            .prop_map(|(n, p)| D::Binomial { n, p })
            .boxed(),
        number().prop_map(|df| D::Chisquare { df }).boxed(),
        (number(), number())
            .prop_map(|(mean, std)| D::Normal { mean, std })
            .boxed(),
    ]
    .boxed();
    prop_oneof![
        plain.clone(),
        (
            plain,
            proptest::option::of(number()),
            proptest::option::of(number())
        )
            .prop_map(|(d, low, high)| D::Truncated {
                distribution: Box::new(d),
                low,
                high,
            })
            .boxed(),
    ]
    .boxed()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    /// Arbitrary parameters are refused with a message or drawn from, never a panic (a
    /// crafted study.json reaches the sampler with any parameters it passed validation with).
    #[test]
    fn arbitrary_distribution_parameters_never_panic(d in distribution()) {
        use karman_dispersion::{Target, Variation, VariedInput, sampling::draw};
        let input = VariedInput::new("x", Target::Number(1.0), Variation::Value(d));
        if input.check().is_ok() {
            for index in 0..4 {
                let _ = draw(1, index, std::slice::from_ref(&input));
            }
        }
    }
}
