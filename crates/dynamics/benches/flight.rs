//! Calisto flown from the rail to the ground: median wall time per flight, right-hand-side
//! evaluations per flight and nanoseconds per evaluation (target ≤ 0.3 ms per flight).
//!
//! The rocket is the validation mission `calisto/mission.toml` (RocketPy's "First Simulation"
//! rocket, Cesaroni M1670, ISA at Spaceport America), built here directly from the model
//! crates because karman-dynamics may not depend on karman-mission (layering); the numbers
//! below are that mission's, and the data files are read from the validation folder
//! (`KARMAN_VALIDATION_DATA` or `<workspace>/../shared/validation`). Parachute noise is zero.
//! The models are built once, outside the timing loop.

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

use criterion::{Criterion, criterion_group, criterion_main};
use karman_airframe::{
    Airfoil, AngleUnit, CoordinateSystem, MotorProperties, NoseConeSpec, NoseKind, Parachute,
    ParachuteSpec, RailButtons, Rocket, RocketInputs, SurfaceInput, SurfaceSpec, Sweep, TailSpec,
    TrapezoidalFinsSpec, Trigger,
};
use karman_atmos::{Atmosphere, Datum, Environment, EnvironmentConfig, Gravity};
use karman_dynamics::{FlightSettings, simulate};
use karman_math::{Interpolation, PhysicalConstants, Table1};
use karman_propulsion::{
    BatesGrains, BurnTime, Motor, MotorStructure, ThrustCurve, ThrustData, ThrustOptions,
    ThrustSource,
};

/// The validation folder, if present.
fn validation_dir() -> Option<PathBuf> {
    let dir = std::env::var_os("KARMAN_VALIDATION_DATA").map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/validation"),
        PathBuf::from,
    );
    dir.is_dir().then_some(dir)
}

/// A two-column data file as a linear table (constant extrapolation).
fn table(path: &Path) -> Table1 {
    let points = karman_math::csv::read_curve(path).expect("curve file");
    let (xs, ys) = points.iter().map(|p| (p[0], p[1])).unzip();
    Table1::linear(xs, ys).expect("curve table")
}

/// Calisto's environment and rocket (values of `calisto/mission.toml`).
fn calisto(dir: &Path) -> (Environment, Rocket) {
    let constants = PhysicalConstants::SI;
    let env = Environment::new(
        &EnvironmentConfig {
            latitude_deg: 32.990254,
            longitude_deg: -106.974998,
            elevation: 1400.0,
            datum: Datum::Sirgas2000,
            gravity: Gravity::Somigliana,
            atmosphere: Atmosphere::Standard,
        },
        &constants,
    )
    .expect("environment");

    let data = ThrustData::load(&dir.join("Cesaroni_M1670.eng")).expect("thrust file");
    let thrust = ThrustCurve::new(
        &ThrustSource::Data(Box::new(data)),
        &ThrustOptions {
            burn_time: Some(BurnTime::End(3.9)),
            reshape: None,
            interpolation: Interpolation::Linear,
        },
    )
    .expect("thrust curve");
    let motor = Motor::solid(
        thrust,
        MotorStructure {
            dry_mass: 1.815,
            dry_inertia: [0.125, 0.125, 0.002, 0.0, 0.0, 0.0],
            center_of_dry_mass: 0.317,
            nozzle_position: 0.0,
            nozzle_radius: 0.033,
            coordinate_system: karman_propulsion::CoordinateSystem::NozzleToCombustionChamber,
            reference_pressure: None,
        },
        BatesGrains {
            number: 5,
            density: 1815.0,
            outer_radius: 0.033,
            initial_inner_radius: 0.015,
            initial_height: 0.12,
            separation: 0.005,
            center_of_mass_position: 0.397,
            throat_radius: 0.011,
            only_radial_burn: false,
        },
    )
    .expect("motor");
    let (i11, i33) = motor.propellant_inertia();
    let properties = MotorProperties {
        thrust: motor.thrust_table().clone(),
        burn_start: motor.burn_start(),
        burn_out: motor.burn_out(),
        exhaust_velocity: motor.exhaust_velocity(),
        propellant_mass: motor.propellant_mass().clone(),
        propellant_center_of_mass: motor.propellant_center_of_mass().clone(),
        propellant_i11: i11.clone(),
        propellant_i33: i33.clone(),
        dry_mass: motor.dry_mass(),
        center_of_dry_mass: motor.center_of_dry_mass(),
        dry_inertia: motor.dry_inertia(),
        nozzle_position: motor.nozzle_position(),
        nozzle_radius: motor.nozzle_radius(),
        coordinate_system_sign: motor.coordinate_system_sign(),
        reference_pressure: motor.reference_pressure(),
    };

    let parachute = |name: &str, cd_s: f64, trigger: Trigger| {
        Parachute::new(&ParachuteSpec {
            name: name.into(),
            cd_s,
            trigger,
            sampling_rate: Some(105.0),
            lag: Some(1.5),
            noise: Some([0.0; 3]),
            radius: Some(1.5),
            height: Some(1.5),
            porosity: Some(0.0432),
            drag_coefficient: None,
        })
        .expect("parachute")
    };
    let inputs = RocketInputs {
        radius: 0.0635,
        mass: 14.426,
        inertia: [6.321, 6.321, 0.034, 0.0, 0.0, 0.0],
        center_of_mass_without_motor: 0.0,
        coordinate_system: CoordinateSystem::TailToNose,
        power_off_drag: table(&dir.join("powerOffDragCurve.csv")),
        power_on_drag: table(&dir.join("powerOnDragCurve.csv")),
        motor_position: -1.255,
        surfaces: vec![
            SurfaceInput {
                name: "nose".into(),
                position: 1.278,
                spec: SurfaceSpec::Nose(NoseConeSpec {
                    length: 0.55829,
                    kind: NoseKind::VonKarman,
                    base_radius: None,
                    bluffness: 0.0,
                }),
            },
            SurfaceInput {
                name: "fins".into(),
                position: -1.04956,
                spec: SurfaceSpec::TrapezoidalFins(TrapezoidalFinsSpec {
                    n: 4,
                    root_chord: 0.12,
                    tip_chord: 0.06,
                    span: 0.11,
                    sweep: Sweep::Default,
                    cant_angle_deg: 0.5,
                    radius: None,
                    airfoil: Some(Airfoil {
                        lift_curve: table(&dir.join("NACA0012-radians.txt")),
                        unit: AngleUnit::Radians,
                    }),
                }),
            },
            SurfaceInput {
                name: "tail".into(),
                position: -1.194656,
                spec: SurfaceSpec::Tail(TailSpec {
                    top_radius: 0.0635,
                    bottom_radius: 0.0435,
                    length: 0.06,
                    radius: None,
                }),
            },
        ],
        parachutes: vec![
            parachute("main", 10.0, Trigger::HeightAboveGround(800.0)),
            parachute("drogue", 1.0, Trigger::Apogee),
        ],
        rail_buttons: Some(RailButtons::new(0.0818, -0.6182, 45.0).expect("rail buttons")),
    };
    let rocket = Rocket::new(inputs, properties).expect("rocket");
    (env, rocket)
}

fn bench_flight(c: &mut Criterion) {
    let Some(dir) = validation_dir() else {
        println!("flight bench: skipped, the validation folder is absent");
        return;
    };
    let (env, rocket) = calisto(&dir.join("calisto"));
    let mut settings = FlightSettings::new(5.2);
    settings.inclination_deg = 85.0;
    settings.heading_deg = 0.0;

    // One flight outside criterion for the work counters and a per-evaluation figure.
    let flight = simulate(&env, &rocket, &settings).expect("Calisto flies");
    let evaluations = flight.stats.evaluations;
    let runs = 200u32;
    let start = Instant::now();
    for _ in 0..runs {
        black_box(simulate(black_box(&env), black_box(&rocket), &settings).expect("flies"));
    }
    let per_flight = start.elapsed() / runs;
    println!(
        "Calisto to the ground: {} steps ({} rejected), {evaluations} RHS evaluations, \
         {:.1} µs per flight (mean of {runs}), {:.0} ns per evaluation incl. event handling",
        flight.stats.steps,
        flight.stats.rejected_steps,
        per_flight.as_secs_f64() * 1e6,
        per_flight.as_secs_f64() * 1e9 / evaluations as f64,
    );

    let mut counts = [0usize; 3];
    for p in &flight.points {
        counts[match p.phase {
            karman_dynamics::PhaseKind::Rail => 0,
            karman_dynamics::PhaseKind::SixDof => 1,
            karman_dynamics::PhaseKind::Parachute(_) => 2,
        }] += 1;
    }
    println!(
        "stored points: rail {}, 6-DOF {}, parachute {}",
        counts[0], counts[1], counts[2]
    );

    let eq = karman_dynamics::equations::Equations::new(&env, &rocket);
    let e = [0.9230002039, -0.0402990592, 0.0166924169, 0.3823192025];
    let state = [
        1.0, 50.0, 1900.0, 3.0, 40.0, 150.0, e[0], e[1], e[2], e[3], 0.1, -0.2, 3.0,
    ];
    c.bench_function("rhs_six_dof_powered", |b| {
        b.iter(|| eq.six_dof(black_box(2.0), black_box(&state)))
    });
    c.bench_function("rhs_six_dof_coasting", |b| {
        b.iter(|| eq.six_dof(black_box(10.0), black_box(&state)))
    });
    c.bench_function("rhs_rail", |b| {
        b.iter(|| eq.rail(black_box(0.2), black_box(&state)))
    });
    c.bench_function("env_density", |b| b.iter(|| env.density(black_box(1900.0))));
    c.bench_function("env_wind", |b| b.iter(|| env.wind(black_box(1900.0))));
    c.bench_function("rocket_inertia", |b| {
        b.iter(|| rocket.inertia(black_box(2.0)))
    });
    c.bench_function("rocket_inertia_rate", |b| {
        b.iter(|| rocket.inertia_rate(black_box(2.0)))
    });
    c.bench_function("rocket_total_mass", |b| {
        b.iter(|| rocket.total_mass(black_box(2.0)))
    });
    c.bench_function("fins_cn_alpha", |b| {
        b.iter(|| rocket.surfaces()[1].cn_alpha(black_box(0.5)))
    });
    c.bench_function("fins_roll_damping", |b| {
        b.iter(|| rocket.surfaces()[1].roll_damping(black_box(0.5)))
    });
    c.bench_function("rocket_drag", |b| {
        b.iter(|| rocket.drag_coefficient(true, black_box(0.5)))
    });
    c.bench_function("calisto_flight_to_ground", |b| {
        b.iter(|| simulate(black_box(&env), black_box(&rocket), &settings).expect("flies"));
    });
    c.bench_function("calisto_flight_and_summary", |b| {
        b.iter(|| {
            let f = simulate(black_box(&env), black_box(&rocket), &settings).expect("flies");
            f.summary(&env, &rocket)
        });
    });
}

criterion_group!(benches, bench_flight);
criterion_main!(benches);
