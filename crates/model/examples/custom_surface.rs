//! A custom aerodynamic surface: what a crate implements to give the engine a force law of
//! its own. The example is a pair of canards whose normal force keeps growing past the
//! linear range, with the crossflow term of a flat plate (Jorgensen's slender-body form,
//! NASA TR R-474, 1977: `C_N = C_Nα sin α cos α + η C_dc sin² α`), where the built-in surfaces
//! fly RocketPy's linear `C_Nα α` (docs/physics.md §7.2).
//!
//! A [`SurfaceModel`] says where its centre of pressure is (body axes, from the centre of dry
//! mass) and turns the stream there into a force and a moment about the centre of dry mass;
//! the engine sums the surfaces' loads. Run with
//! `cargo run -p karman-model --example custom_surface`.

use karman_model::{Loads, LocalFlow, SurfaceModel};

/// Canards with a nonlinear normal force.
pub struct Canards {
    /// Reference area, m².
    pub area: f64,
    /// Normal-force slope at small angles, 1/rad.
    pub cn_alpha: f64,
    /// Crossflow drag coefficient of the planform times its efficiency `η C_dc`.
    pub crossflow: f64,
    /// Axial position of the centre of pressure from the centre of dry mass, m (forward
    /// positive along the body's third axis).
    pub cp_z: f64,
}

impl SurfaceModel for Canards {
    fn cp_body(&self) -> [f64; 3] {
        [0.0, 0.0, self.cp_z]
    }

    fn loads(&self, flow: &LocalFlow) -> Loads {
        let s = flow.stream;
        let transverse = s[0].hypot(s[1]);
        if transverse == 0.0 {
            return Loads::NONE;
        }
        // The angle of attack between the axis and the oncoming stream (docs/physics.md §7.2).
        let alpha = transverse.atan2(-s[2]);
        let (sin, cos) = alpha.sin_cos();
        let cn = self.cn_alpha * sin * cos + self.crossflow * sin * sin;
        let normal = 0.5 * flow.density * flow.speed * flow.speed * self.area * cn;
        // Along the transverse stream, as the built-in normal force.
        let (fx, fy) = (normal * s[0] / transverse, normal * s[1] / transverse);
        Loads {
            force: [fx, fy, -0.0],
            // M = p × F with p = (0, 0, cp_z), F = (fx, fy, 0).
            moment: [-(self.cp_z * fy), self.cp_z * fx, -0.0],
        }
    }
}

/// The flow of a rocket at `speed` (m/s) and angle of attack `alpha_deg` in sea-level air.
pub fn flow(speed: f64, alpha_deg: f64) -> LocalFlow {
    let (sin, cos) = alpha_deg.to_radians().sin_cos();
    LocalFlow {
        stream: [speed * sin, 0.0, -speed * cos],
        speed,
        mach: speed / 340.3,
        density: 1.225,
        roll_rate: 0.0,
    }
}

/// The example's canards: 2 × 40 cm² at 0.6 m ahead of the centre of dry mass.
pub fn canards() -> Canards {
    Canards {
        area: 0.008,
        cn_alpha: 3.2,
        crossflow: 1.2,
        cp_z: 0.6,
    }
}

fn main() {
    let canards = canards();
    println!("alpha (deg)  normal force (N)  linear law (N)  pitch moment (N·m)");
    for alpha_deg in [0.0, 2.0, 5.0, 10.0, 20.0, 30.0] {
        let flow = flow(150.0, alpha_deg);
        let loads = canards.loads(&flow);
        let linear = Loads::normal_force(&flow, canards.area, canards.cn_alpha, canards.cp_z);
        println!(
            "{alpha_deg:>11.0}  {:>16.2}  {:>14.2}  {:>18.2}",
            loads.force[0], linear.force[0], loads.moment[1]
        );
    }
}
