//! RocketPy's 3-DOF point-mass free flight (docs/physics.md §8.5; RocketPy 1.12+ `Flight` with
//! `simulation_mode = "3 DOF"`, `Flight.u_dot_generalized_3dof` in
//! `rocketpy/simulation/flight.py` of RocketPy 1.13).
//!
//! The rocket is a point of mass `m(t)` (the total mass, no variable-mass terms) at the
//! centre of dry mass. With `K` the rotation of the attitude quaternion and every load in
//! body axes:
//!
//! ```text
//! R  = (0, 0, −½ ρ V² A C_D) + Σ_surfaces F_s       drag along the axis, the surfaces' forces
//! T  = (0, 0, T_net)                                 while t_b0 < t < t_b1 (pressure thrust incl.)
//! W  = Kᵀ (0, 0, −m g(z))
//! v̇  = K (T + W + R) / m,      ẋ = v,      ω̇ = 0
//! ```
//!
//! The drag curve is the power-on one for `t < t_b1` (RocketPy's 3-DOF test; the 6-DOF one
//! is `t_b0 < t < t_b1`), the surfaces see the same local streams as in 6 DOF (§7.2) but
//! their moments, the eccentricities (§7.8) and the Coriolis acceleration (§4.5) are left out.
//! The angular rates of the state are carried unchanged (they still enter the surfaces'
//! streams, as in RocketPy).
//!
//! The attitude is held, or with a weathercock coefficient `k_w > 0` (RocketPy's
//! `PointMassRocket.weathercock_coeff`) relaxed toward the relative wind: with the axis
//! `a = K e₃` taken from the raw quaternion and the target `d = (v − w)/|v − w|`,
//!
//! ```text
//! n = a × d;   ω_A = k_w |n| n/|n|   (|n| > 1e-8)
//!              ω_A = k_w p            (|n| ≤ 1e-8 and a·d < −0.999; p the unit of a × x̂, or a × ŷ)
//!              ω_A = 0                (aligned)
//! ė = ½ e ⊗ (0, Kᵀ ω_A)
//! ```
//!
//! so the axis turns toward the wind at `k_w sin θ` rad/s (θ the angle of attack), without
//! any angular state; in still relative air (`v = w`) the attitude is held.

use karman_model::{AtmosphereModel, Configuration, VehicleModel};

use super::{Cursors, Derivative, Equations};
use crate::state::{
    State, Vec3, cross, dot, mat_t_vec, mat_vec, norm, position, quaternion, quaternion_rate,
    rotation, scale,
};

/// Weathercock turn rate below which the axis counts as aligned with the wind (RocketPy).
const ALIGNED: f64 = 1e-8;
/// Cosine below which an aligned-looking axis points against the wind (RocketPy).
const ANTI_ALIGNED: f64 = -0.999;

impl<A: AtmosphereModel, V: VehicleModel> Equations<'_, A, V> {
    /// 3-DOF point-mass free flight (module documentation; RocketPy's
    /// `u_dot_generalized_3dof`) with the weathercock coefficient `weathercock`, 1/s.
    #[inline]
    #[must_use]
    pub fn point_mass(
        &self,
        t: f64,
        u: &State,
        weathercock: f64,
        configuration: &Configuration,
        cursors: &mut Cursors,
    ) -> Derivative {
        let v = [u[3], u[4], u[5]];
        let e = quaternion(u);
        let k = rotation(e);
        let mass = match &self.coast {
            Some(coast) if t >= self.burn_out => coast.mass,
            _ => self.vehicle.total_mass(t, &mut cursors.time[1]),
        };
        let air = self.atmosphere.air_at(t, position(u), &mut cursors.height);
        let (force, _, net_thrust) =
            self.loads(t, u, &k, &air, t < self.burn_out, configuration, cursors);
        let weight = mat_t_vec(&k, [0.0, 0.0, -mass * air.gravity]);
        let total = [
            weight[0] + force[0],
            weight[1] + force[1],
            net_thrust + weight[2] + force[2],
        ];
        let v_dot = mat_vec(&k, [total[0] / mass, total[1] / mass, total[2] / mass]);
        let e_dot = if weathercock > 0.0 {
            let wind = self.wind(t, position(u));
            let free = [wind[0] - v[0], wind[1] - v[1], -v[2]];
            weathercock_rate(e, &k, free, weathercock)
        } else {
            [0.0; 4]
        };
        Derivative {
            u_dot: [
                v[0], v[1], v[2], v_dot[0], v_dot[1], v_dot[2], e_dot[0], e_dot[1], e_dot[2],
                e_dot[3], 0.0, 0.0, 0.0,
            ],
            force,
            moment: [0.0; 3],
            net_thrust,
        }
    }
}

/// `ė` of the weathercock law (module documentation) for the quaternion `e` with rotation
/// `k`, free stream `w − v` and coefficient `coefficient > 0`.
fn weathercock_rate(e: [f64; 4], k: &[[f64; 3]; 3], free: Vec3, coefficient: f64) -> [f64; 4] {
    let speed = norm(free);
    // RocketPy skips speeds up to 1e-6 m/s; any positive speed has a direction, and a
    // threshold with a unit would not scale with the unit system.
    let moving = speed > 0.0; // false for NaN too
    if !moving {
        return [0.0; 4];
    }
    let [e0, e1, e2, e3] = e;
    // The rocket axis from the raw (unnormalised) quaternion, as RocketPy takes it.
    let axis = [
        2.0 * (e1 * e3 + e0 * e2),
        2.0 * (e2 * e3 - e0 * e1),
        1.0 - 2.0 * (e1 * e1 + e2 * e2),
    ];
    let desired = [-free[0] / speed, -free[1] / speed, -free[2] / speed];
    let turn = cross(axis, desired);
    let sin_angle = norm(turn);
    let omega_inertial = if sin_angle > ALIGNED {
        let unit = [
            turn[0] / sin_angle,
            turn[1] / sin_angle,
            turn[2] / sin_angle,
        ];
        scale(coefficient * sin_angle.min(1.0), unit)
    } else if dot(axis, desired) < ANTI_ALIGNED {
        // Head-on into the wind the turn axis is arbitrary: any perpendicular one.
        let mut perpendicular = cross(axis, [1.0, 0.0, 0.0]);
        if norm(perpendicular) < 1e-6 {
            perpendicular = cross(axis, [0.0, 1.0, 0.0]);
        }
        let n = norm(perpendicular);
        let unit = [
            perpendicular[0] / n,
            perpendicular[1] / n,
            perpendicular[2] / n,
        ];
        scale(coefficient, unit)
    } else {
        return [0.0; 4];
    };
    quaternion_rate(e, mat_t_vec(k, omega_inertial))
}
