//! The crate's `examples/` programs run here, so that they keep working.

#[path = "../examples/custom_surface.rs"]
#[allow(dead_code)]
mod custom_surface;

use karman_model::{Loads, SurfaceModel};

#[test]
fn the_example_canards_follow_the_linear_law_at_small_angles_and_exceed_it_beyond() {
    let canards = custom_surface::canards();
    assert_eq!(
        canards.loads(&custom_surface::flow(150.0, 0.0)),
        Loads::NONE,
        "no force along the axis"
    );
    let small = custom_surface::flow(150.0, 0.5);
    let linear = Loads::normal_force(&small, canards.area, canards.cn_alpha, canards.cp_z);
    let loads = canards.loads(&small);
    // sin α cos α = α − (2/3) α³ + …, the crossflow term is O(α²): 1.2/3.2 · α ≈ 0.33 %.
    let relative = (loads.force[0] - linear.force[0]) / linear.force[0];
    assert!(relative > 0.0 && relative < 0.004, "{relative}");
    for alpha_deg in [10.0f64, 30.0, 60.0] {
        let flow = custom_surface::flow(150.0, alpha_deg);
        let loads = canards.loads(&flow);
        let (sin, cos) = alpha_deg.to_radians().sin_cos();
        let cn = canards.cn_alpha * sin * cos + canards.crossflow * sin * sin;
        let expected = 0.5 * 1.225 * 150.0 * 150.0 * canards.area * cn;
        assert!(
            (loads.force[0] - expected).abs() < 1e-12 * expected,
            "{alpha_deg}°"
        );
        // The moment is the force's at the centre of pressure, the stream in the x-z plane.
        assert_eq!(
            loads.moment[1].to_bits(),
            (canards.cp_body()[2] * loads.force[0]).to_bits()
        );
        assert_eq!(loads.force[1].abs().to_bits(), 0.0f64.to_bits());
    }
}
