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
        pods: Vec::new(),
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

/// A pod set of `count` ogive-nosed pods with a blunt-based tail cone, beside the simple
/// rocket's body tube.
fn with_pods(count: u32, blunt: bool) -> DragGeometry {
    let k = 60e-6;
    let segment = |name: &str, length: f64, fore: f64, aft: f64, profile| BodySegment {
        name: name.into(),
        length,
        fore_radius: fore,
        aft_radius: aft,
        profile,
        roughness: k,
        drag_override: None,
    };
    let r = 0.006;
    let tail_aft = if blunt { 0.003 } else { 0.0 };
    let mut g = simple_rocket();
    g.pods.push(karman_airframe::PodDrag {
        name: "pods".into(),
        count,
        position: 0.25,
        body: vec![
            segment("pod nose", 0.03, 0.0, r, Profile::Ogive(1.0)),
            segment("pod tube", 0.06, r, r, Profile::Conical),
            segment("pod tail", 0.02, r, tail_aft, Profile::Conical),
        ],
    });
    g
}

#[test]
fn pods_add_their_terms_once_per_pod() {
    // OpenRocket 24.12 sums every term of a pod's components once per instance; the pods lie
    // within the body's length and radius, so the fineness correction is the body's alone
    // and every term is linear in the pod count.
    let c = PhysicalConstants::SI;
    let terms = |g: &DragGeometry| {
        DragModel::new(g, &c)
            .expect("geometry")
            .components(0.3, 102.0, 1.5e-5)
    };
    let none = terms(&simple_rocket());
    for blunt in [false, true] {
        let one = terms(&with_pods(1, blunt));
        let three = terms(&with_pods(3, blunt));
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(1e-3);
        for (n, o, t) in [
            (none.friction, one.friction, three.friction),
            (none.pressure, one.pressure, three.pressure),
            (none.base, one.base, three.base),
            (none.base_power_on, one.base_power_on, three.base_power_on),
        ] {
            assert!(close(t - n, 3.0 * (o - n)), "{n} {o} {t}");
        }
        assert!(one.friction > none.friction && one.pressure > none.pressure);
        // A pod's base drag: only where its tail leaves a base.
        let base = one.base - none.base;
        assert!(
            if blunt {
                base > 0.0
            } else {
                base.abs() < 1e-15
            },
            "{base}"
        );
    }
}
