//! The equations of motion and the integrator step loop must not allocate (style.md: nothing
//! the right-hand side calls per step allocates). Every validation mission is flown once with
//! the real models (karman-atmos' `Environment`, karman-airframe's `Rocket` through their
//! karman-model implementations), and so is the air-start example (several motors); then,
//! under `allocation_counter::measure` (which counts the current thread's allocations), the
//! right-hand side of the phase of every stored point is re-evaluated at that point (the 6-DOF
//! points through the 3-DOF point-mass equations too), and the integrator is stepped (dense
//! output included) through the 6-DOF phase and the parachute descent (everything but the
//! storing of solution points, which `simulate` does into a `Vec`).

use karman_mission::assemble::environment::build_environment;
use karman_mission::assemble::motor::build_motor;
use karman_mission::assemble::preflight::flight_settings;
use karman_mission::assemble::rocket::build_rocket;
use karman_mission::dynamics::equations::{CanopyState, Cursors, Equations};
use karman_mission::dynamics::integrator::{Pair, RungeKutta, StepStatus, Tolerances};
use karman_mission::dynamics::{Configuration, PhaseKind, SolutionPoint, simulate};

use crate::common::{flight_name, validation_missions};

/// Integration tolerances of the mission's flight settings, with generous step limits.
fn tolerances(rtol: f64, atol: [f64; 13]) -> Tolerances<13> {
    Tolerances {
        rtol,
        atol,
        max_step: f64::INFINITY,
        min_step: 1e-12,
        max_steps: 100_000,
    }
}

#[test]
fn equations_and_steps_do_not_allocate() {
    let Some(mut missions) = validation_missions() else {
        println!("allocation: skipped, the validation folder is absent");
        return;
    };
    // A rocket of several motors (`[[extra_motors]]`): the motors' sum is tabulated once.
    missions.push(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/airstart.toml"),
    );
    // The counter is live: a Vec allocates.
    let probe = allocation_counter::measure(|| drop(std::hint::black_box(vec![1.0f64; 4])));
    assert!(
        probe.count_total > 0,
        "the allocation counter counts nothing"
    );
    for path in missions {
        let name = flight_name(&path);
        let nominal = karman_mission::load(&path, &[]).expect("mission loads");
        let quiet = nominal.parachute_noise_off().expect("noise overrides");
        let mission = karman_mission::load(&path, &quiet).expect("mission loads");
        let env = build_environment(&mission).expect("environment");
        let motor = build_motor(&mission).expect("motor");
        let rocket = build_rocket(&mission, &motor).expect("rocket");
        let settings = flight_settings(&mission, 0);
        let flight = simulate(&env, &rocket, &settings).expect("mission flies");
        let points: &[SolutionPoint] = &flight.points;
        let eq = Equations::new(&env, &rocket, settings.equations);
        let tol = tolerances(settings.rtol, settings.atol);
        let first = |kind: fn(&PhaseKind) -> bool| points.iter().find(|p| kind(&p.phase));
        let six_dof_start = first(|k| matches!(k, PhaseKind::SixDof));
        let parachute_start = first(|k| matches!(k, PhaseKind::Parachute(_)));

        let mut phases = [0usize; 3];
        let mut sum = 0.0;
        let mut steps = 0usize;
        let configuration = &Configuration::default();
        let info = allocation_counter::measure(|| {
            let cursors = &mut Cursors::default();
            for p in points {
                let d = match p.phase {
                    PhaseKind::Rail => {
                        phases[0] += 1;
                        let (force, _, _) = eq.rail_loads(p.t, &p.state, configuration, cursors);
                        sum += force[2];
                        eq.rail(p.t, &p.state, configuration, cursors)
                    }
                    PhaseKind::SixDof => {
                        phases[1] += 1;
                        // The 3-DOF point-mass equations at the same state, weathercocking.
                        let d = eq.point_mass(p.t, &p.state, 1.0, configuration, cursors);
                        sum += d.u_dot.iter().sum::<f64>();
                        eq.six_dof(p.t, &p.state, configuration, cursors)
                    }
                    PhaseKind::PointMass { weathercock } => {
                        phases[1] += 1;
                        eq.point_mass(p.t, &p.state, weathercock, configuration, cursors)
                    }
                    PhaseKind::Parachute(canopy) => {
                        phases[2] += 1;
                        eq.parachute(p.t, &p.state, &canopy, cursors)
                    }
                };
                sum += d.u_dot.iter().sum::<f64>();
            }
            // The integrator loop of the 6-DOF phase, to apogee or 60 s at most.
            if let Some(p) = six_dof_start {
                let f = |t: f64, u: &[f64; 13]| eq.six_dof(t, u, configuration, cursors).u_dot;
                let bound = p.t + 60.0;
                let mut dp = RungeKutta::new(Pair::Dop853, f, p.t, p.state, bound, tol)
                    .expect("6-DOF starts");
                while dp.y()[5] > 0.0 {
                    match dp.step().expect("6-DOF steps") {
                        StepStatus::Running => steps += 1,
                        StepStatus::Finished => break,
                    }
                    sum += dp.dense(0.5 * (dp.t_old() + dp.t()))[2];
                }
            }
            // The parachute descent for 30 s, with both of its methods.
            if let Some(p) = parachute_start {
                let PhaseKind::Parachute(canopy) = p.phase else {
                    return;
                };
                let canopy: CanopyState = canopy;
                for pair in [Pair::Dopri5, Pair::Rkc2] {
                    let f = |t: f64, u: &[f64; 13]| eq.parachute(t, u, &canopy, cursors).u_dot;
                    let mut dp = RungeKutta::new(pair, f, p.t, p.state, p.t + 30.0, tol)
                        .expect("descent starts");
                    while let StepStatus::Running = dp.step().expect("descent steps") {
                        steps += 1;
                        sum += dp.dense(0.5 * (dp.t_old() + dp.t()))[2] + dp.stiffness();
                    }
                }
            }
        });
        assert!(sum.is_finite(), "{name}: non-finite derivatives");
        assert!(
            phases[1] > 0 && steps > 0,
            "{name}: no 6-DOF point or no integrator step exercised ({phases:?}, {steps} steps)"
        );
        println!(
            "{name}: {} rail, {} 6-DOF, {} parachute evaluations and {steps} integrator steps: \
             {} allocations",
            phases[0], phases[1], phases[2], info.count_total
        );
        assert_eq!(
            info.count_total, 0,
            "{name}: the equations of motion or the integrator allocated {} times",
            info.count_total
        );
    }
}

/// A trigger expression reading sensors is evaluated from the buffer the parachute's
/// process fills (allocated once, when the flight is set up), and a controller's sensor
/// handles are written in place: neither allocates per sample.
#[test]
fn sensor_reads_do_not_allocate() {
    use karman_script::{Expression, SensorShape, TriggerInputs};
    let shapes = [
        SensorShape {
            name: "baro",
            kind: "barometer",
            components: 1,
        },
        SensorShape {
            name: "imu",
            kind: "accelerometer",
            components: 3,
        },
    ];
    let expression = Expression::parse_with(
        "sensors.baro < 80000.0 && sensors[1][2] > 0.0 && sqrt(sensors.imu[0]) < vz",
        &shapes,
    )
    .expect("parses");
    let inputs = TriggerInputs {
        pressure: 1.0,
        height: 2.0,
        state: [0.5; 13],
    };
    let values = [79_000.0, 1.0, 0.01];
    let mut fired = 0;
    let counted = allocation_counter::measure(|| {
        for _ in 0..1000 {
            fired += usize::from(expression.evaluate_with(&inputs, std::hint::black_box(&values)));
        }
    });
    assert_eq!(fired, 1000);
    assert_eq!(counted.count_total, 0, "{counted:?}");
}
