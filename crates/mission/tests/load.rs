//! Loading the validation missions.

use crate::common::validation_missions;
use karman_mission::load;

#[test]
fn validate_missions_load() {
    let Some(missions) = validation_missions() else {
        println!("skipped: validation data folder not found");
        return;
    };
    assert!(
        missions.len() >= 8,
        "expected the 8 validation missions, found {}",
        missions.len()
    );
    for path in &missions {
        if let Err(error) = load(path, &[]) {
            panic!("{error}");
        }
    }
}

/// `[rocket] interpolation` / `extrapolation` shape both drag curves (the power-on curve of
/// the minimal fixture is drag.csv: Mach 0, 0.5, 1, 2 → 0.50, 0.48, 0.62, 0.40).
#[test]
fn rocket_drag_curves_follow_their_interpolation_keys() {
    use karman_mission::Override;
    use karman_mission::assemble::{motor::build_motor, rocket::build_rocket};
    let cd_on = |sets: &[(&str, &str)]| {
        let overrides: Vec<Override> = sets
            .iter()
            .map(|(path, value)| Override::new(path, value).expect("override"))
            .collect();
        let mission = load(&crate::common::fixture("minimal.toml"), &overrides)
            .unwrap_or_else(|e| panic!("{e}"));
        let motor = build_motor(&mission).expect("motor");
        let rocket = build_rocket(&mission, &motor).expect("rocket");
        move |mach: f64| rocket.drag_coefficient(true, mach)
    };
    let linear = cd_on(&[]);
    assert!((linear(0.75) - 0.55).abs() < 1e-12, "{}", linear(0.75));
    assert!((linear(3.0) - 0.40).abs() < 1e-12, "held beyond Mach 2");
    let spline = cd_on(&[("rocket.interpolation", "\"spline\"")]);
    // SciPy's CubicSpline(bc_type="natural") through the same points gives 0.58565217391 at
    // Mach 1.5 (the chord: 0.51).
    assert!(
        (spline(1.5) - 0.585_652_173_913_043_6).abs() < 1e-12,
        "{}",
        spline(1.5)
    );
    assert!((spline(1.0) - 0.62).abs() < 1e-12, "through the points");
    let zero = cd_on(&[("rocket.extrapolation", "\"zero\"")]);
    assert!(zero(3.0).abs() < 1e-300 && (zero(0.75) - 0.55).abs() < 1e-12);
    let natural = cd_on(&[("rocket.extrapolation", "\"natural\"")]);
    // The last piece (1, 0.62)–(2, 0.40) continued to Mach 3: 0.18.
    assert!((natural(3.0) - 0.18).abs() < 1e-12, "{}", natural(3.0));
    // An unknown name is a located error naming the key.
    let bad = Override::new("rocket.extrapolation", "\"sideways\"").expect("override");
    let error = load(&crate::common::fixture("minimal.toml"), &[bad]).expect_err("rejected");
    assert!(error.to_string().contains("extrapolation"), "{error}");
}
