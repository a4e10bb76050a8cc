//! Cost of the drag estimate of one rocket (target: under 1 ms, issue 20): building the
//! [`DragModel`] (wetted areas, nose tables, fin planforms) and tabulating it from Mach 0 to 3,
//! as a Monte Carlo sample over geometry inputs does once per sample.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use karman_airframe::{
    BodySegment, DragGeometry, DragModel, FinCrossSection, FinSetDrag, FlowReference, LaunchLug,
    Profile, RailButtonDrag,
};
use karman_math::PhysicalConstants;

/// A 54 mm high-power rocket: Von Kármán nose, tube, boattail, four fins, a lug and buttons.
fn geometry() -> DragGeometry {
    let k = 60e-6;
    let segment = |name: &str, length, fore, aft, profile| BodySegment {
        name: name.into(),
        length,
        fore_radius: fore,
        aft_radius: aft,
        profile,
        roughness: k,
        drag_override: None,
    };
    DragGeometry {
        reference_radius: 0.028,
        body: vec![
            segment("nose", 0.3, 0.0, 0.028, Profile::Haack(0.0)),
            segment("tube", 1.2, 0.028, 0.028, Profile::Conical),
            segment("boattail", 0.05, 0.028, 0.022, Profile::Conical),
        ],
        fins: vec![FinSetDrag {
            name: "fins".into(),
            count: 4,
            outline: vec![[0.0, 0.0], [0.05, 0.07], [0.11, 0.07], [0.15, 0.0]],
            position: 1.3,
            thickness: 0.003,
            cross_section: FinCrossSection::Rounded,
            roughness: k,
        }],
        tube_fins: Vec::new(),
        launch_lugs: vec![LaunchLug {
            name: "lug".into(),
            outer_radius: 0.004,
            inner_radius: 0.0035,
            length: 0.05,
            count: 1,
            roughness: k,
        }],
        rail_buttons: Some(RailButtonDrag {
            outer_diameter: 0.0097,
            inner_diameter: 0.008,
            height: 0.0097,
            inner_height: 0.0026,
            positions: vec![0.9, 1.4],
        }),
        nozzle_exit_radius: 0.012,
        pods: Vec::new(),
    }
}

fn bench(c: &mut Criterion) {
    let g = geometry();
    let flow = FlowReference {
        speed_of_sound: 340.3,
        kinematic_viscosity: 1.46e-5,
    };
    c.bench_function("drag_estimate/build_and_tabulate", |b| {
        b.iter(|| {
            let model = DragModel::new(black_box(&g), &PhysicalConstants::SI).expect("geometry");
            black_box(model.estimate(&flow))
        });
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
