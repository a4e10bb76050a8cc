//! One aerodynamic surface and its force law (docs/physics.md §7.2, §7.6).

/// The stream at a surface's centre of pressure, body axes (docs/physics.md §7.2): what a surface's
/// force law needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalFlow {
    /// Free-stream velocity relative to the surface, `s = w_b − v_b` (wind minus the
    /// surface's velocity, including `ω × p`), body axes, m/s.
    pub stream: [f64; 3],
    /// `|s|`, m/s.
    pub speed: f64,
    /// Mach number of `|s|` at the vehicle's height.
    pub mach: f64,
    /// Air density, kg/m³.
    pub density: f64,
    /// Roll rate `ω₃`, rad/s.
    pub roll_rate: f64,
}

/// Force and moment of one surface in body axes, the moment about the centre of dry mass.
///
/// [`Loads::NONE`] has every component `−0`, the additive identity of IEEE 754 arithmetic
/// (`x + (−0) = x` for every `x`, `+0` included): a component a surface does not produce adds
/// nothing to the vehicle's sums, to the bit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Loads {
    /// Force `(R1, R2, R3)`, N.
    pub force: [f64; 3],
    /// Moment `(M1, M2, M3)` about the CDM, N·m.
    pub moment: [f64; 3],
}

impl Loads {
    /// No force and no moment (every component `−0`).
    pub const NONE: Loads = Loads {
        force: [-0.0; 3],
        moment: [-0.0; 3],
    };

    /// RocketPy's normal force of a surface on the rocket axis (docs/physics.md §7.2): the lift
    /// `½ ρ |s|² A CNα α` along the transverse stream `(s₁, s₂)`, with the angle of attack
    /// `α = acos(−s₃/|s|)`, and its moment about the CDM for a centre of pressure at
    /// `(0, 0, cp_z)`. No force when the stream has no transverse component.
    ///
    /// `α` is evaluated in the equal form `atan2(|s_⊥|, −s₃)`, better conditioned at small
    /// angles, written as a plain arctangent for the usual nose-first stream (`s₃ < 0`).
    #[inline(always)]
    #[must_use]
    pub fn normal_force(flow: &LocalFlow, area: f64, cn_alpha: f64, cp_z: f64) -> Loads {
        let s = flow.stream;
        let transverse2 = s[0] * s[0] + s[1] * s[1];
        if transverse2 > 0.0 {
            let transverse = transverse2.sqrt();
            let alpha = if s[2] < 0.0 {
                (transverse / -s[2]).atan()
            } else {
                transverse.atan2(-s[2])
            };
            let sp = flow.speed;
            let lift = 0.5 * flow.density * sp * sp * area * cn_alpha * alpha;
            let inv = 1.0 / transverse;
            let fx = lift * s[0] * inv;
            let fy = lift * s[1] * inv;
            Loads {
                force: [fx, fy, -0.0],
                moment: [-(cp_z * fy), cp_z * fx, -0.0],
            }
        } else {
            Loads::NONE
        }
    }

    /// RocketPy's roll moment of a fin set (docs/physics.md §7.6): forcing
    /// `½ ρ |s|² A d C_lf,δ δ` minus damping `½ ρ |s| A d² C_ld,ω ω₃ / 2`, with the reference
    /// length `d`, `forcing = C_lf,δ·δ` and `damping = C_ld,ω` at the flow's Mach number.
    #[inline(always)]
    #[must_use]
    pub fn roll_moment(flow: &LocalFlow, area: f64, d: f64, forcing: f64, damping: f64) -> f64 {
        let (rho, sp) = (flow.density, flow.speed);
        0.5 * rho * sp * sp * area * d * forcing
            - 0.5 * rho * sp * area * d * d * damping * flow.roll_rate / 2.0
    }
}

/// One aerodynamic surface as the equations of motion see it: where it is, and the force law
/// that turns the stream there into loads. Implementations allocate nothing.
pub trait SurfaceModel {
    /// Centre of pressure in body axes, measured from the centre of dry mass, m: the point
    /// whose velocity and wind make the surface's [`LocalFlow`].
    fn cp_body(&self) -> [f64; 3];
    /// Force and moment about the CDM of the surface in the flow at its centre of pressure.
    fn loads(&self, flow: &LocalFlow) -> Loads;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn none_adds_nothing_to_the_bit() {
        for x in [0.0, -0.0, 1.5, -2.0, f64::INFINITY] {
            assert_eq!((x + Loads::NONE.force[0]).to_bits(), f64::to_bits(x));
        }
    }

    #[test]
    fn normal_force_is_the_lift_along_the_transverse_stream() {
        let flow = LocalFlow {
            stream: [3.0, 4.0, -100.0],
            speed: (9.0f64 + 16.0 + 10_000.0).sqrt(),
            mach: 0.3,
            density: 1.2,
            roll_rate: 0.0,
        };
        let loads = Loads::normal_force(&flow, 0.01, 2.0, -0.5);
        let alpha = (5.0f64 / 100.0).atan();
        let lift = 0.5 * 1.2 * flow.speed * flow.speed * 0.01 * 2.0 * alpha;
        assert!((loads.force[0] - lift * 0.6).abs() < 1e-12 * lift);
        assert!((loads.force[1] - lift * 0.8).abs() < 1e-12 * lift);
        // M = p × F with p = (0, 0, −0.5).
        assert!((loads.moment[0] - 0.5 * loads.force[1]).abs() < 1e-12 * lift);
        assert!((loads.moment[1] + 0.5 * loads.force[0]).abs() < 1e-12 * lift);
        let axial = LocalFlow {
            stream: [0.0, 0.0, -100.0],
            ..flow
        };
        assert_eq!(Loads::normal_force(&axial, 0.01, 2.0, -0.5), Loads::NONE);
    }
}
