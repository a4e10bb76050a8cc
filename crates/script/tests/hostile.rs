//! Hostile trigger expressions and controller scripts: each ends with a clear, located, short
//! error, never a stack overflow, a panic, a hang or unbounded memory.

use karman_script::expression::{MAX_DEPTH, QUOTED_CHARS};
use karman_script::{Expression, TriggerInputs};

fn inputs() -> TriggerInputs {
    TriggerInputs {
        pressure: 1.0,
        height: 2.0,
        state: [0.5; 13],
    }
}

/// Parses `text`, expecting an error; returns its one-line message, checked to be short.
fn refused(text: &str) -> (usize, String) {
    match Expression::parse(text) {
        Ok(expression) => panic!(
            "accepted a hostile expression of {} characters (evaluates to {})",
            text.len(),
            expression.evaluate(&inputs())
        ),
        Err(error) => {
            let message = error.to_string();
            assert!(!message.contains('\n'), "{message}");
            assert!(!message.contains('\0'), "{message:?}");
            assert!(message.len() < 300, "{} bytes: {message}", message.len());
            (error.column, message)
        }
    }
}

#[test]
fn thousands_of_nested_parentheses_are_a_depth_error() {
    let deep = format!("{}vz < 1.0{}", "(".repeat(5000), ")".repeat(5000));
    let (column, message) = refused(&deep);
    // The parenthesis that crosses the limit.
    assert_eq!(column, MAX_DEPTH + 1, "{message}");
    assert!(message.contains("deeper than 64"), "{message}");
    // Up to the limit is fine.
    let limit = format!("{}vz < 1.0{}", "(".repeat(MAX_DEPTH), ")".repeat(MAX_DEPTH));
    assert!(
        Expression::parse(&limit)
            .expect("64 levels")
            .evaluate(&inputs())
    );
}

#[test]
fn long_unary_chains_are_a_depth_error() {
    let minus = format!("{}vz < 1.0", "-".repeat(100_000));
    assert!(refused(&minus).1.contains("deeper than"));
    let spaced = format!("{}vz < 1.0", "- ".repeat(10_000));
    assert!(refused(&spaced).1.contains("deeper than"));
    let not = format!("{}true", "!".repeat(100_000));
    assert!(refused(&not).1.contains("deeper than"));
}

#[test]
fn long_operator_chains_are_a_depth_error() {
    let sum = format!("{} > 0.0", vec!["1.0"; 100_000].join(" + "));
    assert!(refused(&sum).1.contains("deeper than"));
    let and = vec!["vz < 1.0"; 100_000].join(" && ");
    assert!(refused(&and).1.contains("deeper than"));
    let calls = format!("{}vz{} < 1.0", "abs(".repeat(10_000), ")".repeat(10_000));
    assert!(refused(&calls).1.contains("deeper than"));
    let arguments = format!("min({}) < 1.0", vec!["vz"; 100_000].join(", "));
    assert!(refused(&arguments).1.contains("takes 2"));
    // A chain within the limit evaluates: 62 additions and the comparison are 63 levels
    // above the literals.
    let ok = format!("{} > 0.0", vec!["1.0"; MAX_DEPTH - 1].join(" + "));
    assert!(
        Expression::parse(&ok)
            .expect("62 additions")
            .evaluate(&inputs())
    );
    let over = format!("{} > 0.0", vec!["1.0"; MAX_DEPTH].join(" + "));
    assert!(refused(&over).1.contains("deeper than"));
}

#[test]
fn huge_literals_and_names_are_cut_in_errors() {
    let digits = "1".repeat(100_000);
    for text in [
        format!("vz < {digits}"),
        format!("vz < {digits}.0"),
        format!("vz < 1.{digits}e999999999999"),
        format!("{} < 1.0", "v".repeat(100_000)),
    ] {
        let (_, message) = refused(&text);
        assert!(message.contains("characters)"), "{message}");
        assert!(
            !message.contains(&"1".repeat(QUOTED_CHARS + 1)),
            "{message}"
        );
    }
    assert!(refused("vz < 1e400").1.contains("largest float"));
}

#[test]
fn empty_blank_and_nul_expressions_are_errors() {
    assert_eq!(refused("").0, 1);
    assert_eq!(refused(" \t\n ").0, 5);
    let (column, message) = refused("vz\0 < 1.0");
    assert_eq!(column, 3);
    assert!(message.contains("\\0"), "{message}");
    assert!(refused("\0").1.contains("not part of the language"));
}
