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

#[path = "../examples/rust_controller.rs"]
#[allow(dead_code)]
mod rust_controller;

/// The Rust twin of the Rhai apogee controller flies the Rhai controller's flight, bit for
/// bit: every stored point (time and state), every event, the same number of calls.
#[test]
fn the_rust_controller_flies_the_rhai_controller_s_flight() {
    use karman_mission::assemble::flight::PreparedFlight;
    let path = rust_controller::example_mission();
    let mission = load(&path, &[]).expect("loads");
    let prepared = PreparedFlight::new(&mission).expect("prepares");
    let rhai = prepared
        .fly(&mission, 0)
        .expect("the Rhai controller flies");
    let mut controller = rust_controller::ApogeeController::default();
    let rust = prepared
        .fly_with_controller(&mission, 0, &mut controller)
        .expect("the Rust controller flies");
    assert!(!rhai.flight.points.is_empty());
    assert_eq!(
        crate::common::point_bits(&rhai),
        crate::common::point_bits(&rust),
        "the stored points differ"
    );
    assert_eq!(
        format!("{:?}", rhai.summary()),
        format!("{:?}", rust.summary())
    );
    // The Rhai controller's record has one level per call; the Rust one was called as often.
    let record = rhai.controller.as_ref().expect("the Rhai run's record");
    assert_eq!(record.levels.len(), controller.calls);
    assert!(
        rust.controller.is_none(),
        "a Rust controller keeps no record"
    );
    // And the brakes did act: the apogee is below the brakes-shut flight's.
    let (apogee, _) = rust_controller::run(&path).expect("runs");
    assert!((apogee - 3047.0).abs() < 0.1, "{apogee}");
}

/// A Rust controller's error ends the flight there, named by the controller's key.
#[test]
fn a_failing_rust_controller_ends_the_flight_with_its_message() {
    use karman_mission::assemble::flight::PreparedFlight;
    use karman_mission::script::{AirBrakeController, AirBrakesControl, ControlInputs};
    struct Fails;
    impl AirBrakeController for Fails {
        fn control(
            &mut self,
            inputs: &ControlInputs<'_>,
            _: &mut AirBrakesControl<'_>,
        ) -> Result<(), String> {
            if inputs.time >= 2.0 {
                Err("lost the IMU".to_owned())
            } else {
                Ok(())
            }
        }
    }
    let mission = load(&rust_controller::example_mission(), &[]).expect("loads");
    let prepared = PreparedFlight::new(&mission).expect("prepares");
    let error = prepared
        .fly_with_controller(&mission, 0, &mut Fails)
        .expect_err("the controller fails");
    // The message and its causes, as the CLI prints them.
    let e = crate::common::chain(&error);
    assert!(e.contains("rocket.air_brakes.controller"), "{e}");
    assert!(e.contains("lost the IMU") && e.contains("t = 2 s"), "{e}");
}
