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

const SIGNATURE: &str = "fn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes)";

/// A controller whose `controller_function` has `body`.
fn controller(body: &str) -> karman_script::Controller {
    crate::controllers::controller(&format!("{SIGNATURE} {{\n{body}\n}}"), true)
}

/// Calls `c` at 100 Hz until it fails or `calls` calls are made; the error and the number of
/// calls that succeeded.
fn fly(
    c: &mut karman_script::Controller,
    calls: usize,
) -> (Option<karman_script::ScriptError>, usize) {
    use crate::controllers::{STATE, row};
    for call in 0..calls {
        let t = call as f64 / 100.0;
        if let Err(error) = c.call(t, &STATE, &row(t)) {
            return (Some(error), call);
        }
    }
    (None, calls)
}

/// The process's peak resident memory, bytes (Linux), or 0 where unknown.
fn peak_memory() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|status| {
            let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
            let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
            Some(kib * 1024)
        })
        .unwrap_or(0)
}

/// Flies the loop of about 900,000 operations a call (6 a turn), under the per-call limit,
/// until the flight's budget of `budget` operations stops it; returns the calls made.
fn loop_under_the_call_limit(budget: Option<u64>) -> usize {
    use karman_script::sandbox::{MAX_FLIGHT_OPERATIONS, MAX_OPERATIONS};
    let mut c = controller(
        "    let i = 0;\n    while i < 150000 { i += 1; }\n    air_brakes.deployment_level = 0.5;",
    );
    if let Some(budget) = budget {
        c = c.with_operation_budget(budget);
    }
    let budget = budget.unwrap_or(MAX_FLIGHT_OPERATIONS);
    let started = std::time::Instant::now();
    let (error, calls) = fly(&mut c, 100_000);
    let message = error.expect("the flight's operation budget").to_string();
    assert!(
        message.starts_with("brakes.rhai:1:1: in `controller_function`"),
        "{message}"
    );
    assert!(
        message.contains(&format!("budget of {budget} operations per flight")),
        "{message}"
    );
    // Each call is under the call limit, so at least budget / limit calls fly.
    let least = (budget / MAX_OPERATIONS) as usize;
    assert!(calls >= least && calls < 2 * least.max(1), "{calls} calls");
    eprintln!(
        "flight budget {budget} reached after {calls} calls in {:?}",
        started.elapsed()
    );
    calls
}

#[test]
fn a_loop_just_under_the_call_limit_ends_the_flight_at_its_budget() {
    // A tenth of the budget, for the time of a debug build.
    loop_under_the_call_limit(Some(10_000_000));
}

/// The default budget: about 111 calls, 66 s in a debug build, a few seconds optimised.
#[test]
#[ignore = "a minute in a debug build"]
fn a_loop_just_under_the_call_limit_ends_the_flight_at_the_default_budget() {
    loop_under_the_call_limit(None);
}

#[test]
fn a_history_kept_in_the_record_ends_at_its_budget_within_bounded_memory() {
    use karman_script::sandbox::MAX_RECORD_VALUES;
    // The docs' way of keeping state, appending every call: the record grows quadratically.
    let mut c = controller("    let h = observed_variables[-1];\n    h.push(time);\n    return h;");
    let (error, calls) = fly(&mut c, 1_000_000);
    let error = error.expect("the record's budget");
    let message = error.to_string();
    assert!(
        message.starts_with("brakes.rhai:1:1: in `controller_function`"),
        "{message}"
    );
    assert!(
        message.contains(&format!("budget of {MAX_RECORD_VALUES} values")),
        "{message}"
    );
    // The initial record [0, 0] is 3 values; call k returns k + 4 (the array and the k + 3
    // numbers): the calls kept are the most whose sum stays within the budget.
    let kept: u64 = 3 + (0..calls as u64).map(|k| k + 4).sum::<u64>();
    assert!(
        kept <= MAX_RECORD_VALUES && kept + calls as u64 + 4 > MAX_RECORD_VALUES,
        "{calls}"
    );
    let record = c.record();
    assert_eq!(record.observed_variables.len(), calls + 1);
    let peak = peak_memory();
    eprintln!(
        "record budget reached after {calls} calls; peak memory {} MiB",
        peak >> 20
    );
    assert!(peak < 256 << 20, "peak resident memory {} MiB", peak >> 20);
}

#[test]
fn deeply_nested_returns_are_refused() {
    let mut c = controller("    let a = [];\n    for i in 0..1000 { a = [a]; }\n    return a;");
    let (error, _) = fly(&mut c, 1);
    let message = error.expect("the nesting limit").to_string();
    assert!(message.contains("nested deeper than 32"), "{message}");
}

#[test]
fn an_endless_sort_comparator_hits_the_call_limit() {
    for body in [
        // The comparator's limit error is discarded by Rhai's `sort`; the statement after it
        // or the end of the call must still report it.
        "    let a = [3.0, 1.0, 2.0, 5.0, 4.0, 9.0, 7.0];\n    a.sort(|x, y| { loop {} });\n    air_brakes.deployment_level = 0.5;",
        "    let a = [3.0, 1.0, 2.0, 5.0, 4.0, 9.0, 7.0];\n    a.sort(|x, y| { loop {} });",
        "    let a = [3.0, 1.0, 2.0];\n    a.sort(|x, y| { let i = 0; while true { i += 1; } 0 });\n    a",
    ] {
        let mut c = controller(body);
        let started = std::time::Instant::now();
        let (error, _) = fly(&mut c, 1);
        let message = error.expect("the call limit").to_string();
        assert!(message.contains("operations in one call"), "{message}");
        assert!(message.starts_with("brakes.rhai:"), "{message}");
        eprintln!("endless comparator stopped in {:?}", started.elapsed());
    }
}

/// An array grown one element at a time to the size limit ends its call in well under a
/// second: Rhai measures the whole array after every `push`, so the time of a call grows with
/// the square of the limit (at 100,000 elements one such call took 21 s in a debug build).
#[test]
fn an_array_grown_to_the_size_limit_fails_fast() {
    let mut c = controller("    let a = [];\n    for i in 0..100000000 { a.push(i); }\n    a");
    let started = std::time::Instant::now();
    let (error, calls) = fly(&mut c, 1);
    let message = error.expect("the array size limit").to_string();
    assert_eq!(calls, 0);
    assert!(message.contains("Size of array"), "{message}");
    let elapsed = started.elapsed();
    assert!(elapsed.as_secs_f64() < 5.0, "{elapsed:?}");
}
