//! The drag build-up against OpenRocket 24.12's stored flights (`fixtures/openrocket`): every
//! ascent row of "A simple model rocket" is a (Mach, Reynolds) test point of its friction,
//! pressure and base drag coefficients, stored to 3 decimals.

use std::path::PathBuf;

use karman_airframe::{
    BodySegment, DragGeometry, DragModel, FinCrossSection, FinSetDrag, LaunchLug, Profile,
};
use karman_math::PhysicalConstants;

fn reference(design: &str) -> serde_json::Value {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/openrocket")
        .join(design)
        .join("reference.json");
    serde_json::from_str(&std::fs::read_to_string(path).expect("fixture")).expect("json")
}

/// "A simple model rocket" as its `.ork` file describes it: tangent ogive 0.1 m, body tube
/// 0.3 m of radius 12.5 mm, three rounded 2 mm fins flush with the aft end, one launch lug,
/// regular paint (60 µm) everywhere.
fn simple_rocket() -> DragGeometry {
    let k = 60e-6;
    DragGeometry {
        reference_radius: 0.0125,
        body: vec![
            BodySegment {
                name: "Nose cone".into(),
                length: 0.1,
                fore_radius: 0.0,
                aft_radius: 0.0125,
                profile: Profile::Ogive(1.0),
                roughness: k,
                drag_override: None,
            },
            BodySegment {
                name: "Body tube".into(),
                length: 0.3,
                fore_radius: 0.0125,
                aft_radius: 0.0125,
                profile: Profile::Conical,
                roughness: k,
                drag_override: None,
            },
        ],
        fins: vec![FinSetDrag {
            name: "Trapezoidal fin set".into(),
            count: 3,
            outline: vec![[0.0, 0.0], [0.0254, 0.03], [0.0762, 0.03], [0.0508, 0.0]],
            position: 0.4 - 0.0508,
            thickness: 0.002,
            cross_section: FinCrossSection::Rounded,
            roughness: k,
        }],
        tube_fins: Vec::new(),
        launch_lugs: vec![LaunchLug {
            name: "Launch lug".into(),
            outer_radius: 0.0035,
            inner_radius: 0.0025,
            length: 0.035,
            count: 1,
            roughness: k,
        }],
        rail_buttons: None,
        nozzle_exit_radius: 0.0,
    }
}

#[test]
fn simple_model_rocket_rows_match_openrocket() {
    let model = DragModel::new(&simple_rocket(), &PhysicalConstants::SI).expect("geometry");
    let reference = reference("a_simple_model_rocket");
    let mut rows = 0;
    for sim in reference["simulations"].as_array().expect("simulations") {
        let ascent = &sim["branches"][0]["ascent"];
        let col = |name: &str| -> Vec<f64> {
            ascent[name]
                .as_array()
                .expect(name)
                .iter()
                .map(|v| v.as_f64().unwrap_or(f64::NAN))
                .collect()
        };
        let (mach, re, a) = (col("mach"), col("reynolds"), col("speed_of_sound_m_s"));
        let (friction, pressure, base) = (col("cd_friction"), col("cd_pressure"), col("cd_base"));
        for i in 0..mach.len() {
            let speed = mach[i] * a[i];
            // The stored Reynolds number fixes ν for this row's speed and length.
            let nu = speed * model.length() / re[i];
            let c = model.components(mach[i], speed, nu);
            // The storage rounding, ±0.0005.
            let tol = 0.0006;
            assert!(
                (c.friction - friction[i]).abs() < tol,
                "row {i}: friction {} vs {}",
                c.friction,
                friction[i]
            );
            assert!(
                (c.pressure - pressure[i]).abs() < tol,
                "row {i}: pressure {} vs {}",
                c.pressure,
                pressure[i]
            );
            assert!(
                (c.base - base[i]).abs() < tol,
                "row {i}: base {} vs {}",
                c.base,
                base[i]
            );
            rows += 1;
        }
    }
    assert!(rows > 500, "{rows} rows");
}
