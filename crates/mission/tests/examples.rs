//! The crate's `examples/` programs run here, so that they keep working.

#[path = "../examples/fly_and_disperse.rs"]
#[allow(dead_code)]
mod fly_and_disperse;

use karman_mission::assemble::flight::simulate;
use karman_mission::load;

#[test]
fn the_example_flies_the_mission_and_its_study_in_memory() {
    let path = fly_and_disperse::example_mission();
    let findings = fly_and_disperse::run(&path, 8, 2).expect("runs");
    // The prepared flight of the example is the one-shot flight of the mission, to the bit.
    let nominal = simulate(&load(&path, &[]).expect("loads"))
        .expect("flies")
        .summary();
    assert_eq!(
        Some(findings.apogee_agl_m.to_bits()),
        nominal.apogee_agl_m.map(f64::to_bits)
    );
    assert_eq!(
        Some(findings.apogee_time_s.to_bits()),
        nominal.apogee_time_s.map(f64::to_bits)
    );
    let report = &findings.study.report;
    assert_eq!(findings.study.rows.len(), 8);
    assert_eq!(report.flown, 8);
    let summary = report
        .summary
        .as_ref()
        .expect("a whole study has a summary");
    let apogee = summary
        .outputs
        .iter()
        .find(|c| c.name == "apogee_agl_m")
        .and_then(|c| c.statistics.as_ref())
        .expect("apogee statistics");
    assert_eq!(apogee.count, 8);
    assert!(apogee.std > 0.0, "the draws change the apogee");
    // The draws are small (a 5 % drag factor, 40 N·s of impulse, ...): the mean apogee of
    // the sample stays near the nominal one.
    assert!(
        (apogee.mean - findings.apogee_agl_m).abs() < 0.05 * findings.apogee_agl_m,
        "{} vs {}",
        apogee.mean,
        findings.apogee_agl_m
    );
}
