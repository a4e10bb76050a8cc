//! Shared helpers: the validation data folder and a hand-built Calisto rocket.
//!
//! The motor tables are built here from the `.eng` file and the BATES grain geometry
//! (docs/physics.md §6.1, §6.4) on a fine time grid, standing in for karman-propulsion (the
//! airframe crate may not depend on it).

use std::path::PathBuf;

use karman_airframe::{
    Airfoil, AngleUnit, CoordinateSystem, MotorProperties, NoseConeSpec, NoseKind, Parachute,
    ParachuteSpec, RailButtons, Rocket, RocketInputs, SurfaceInput, SurfaceSpec, Sweep, TailSpec,
    TrapezoidalFinsSpec, TriggerKind,
};
use karman_math::{Extrapolation, Interpolation, Table1, linspace};

/// The validation folder ([`karman_validation::folder`]), or `None` when it is unavailable
/// outside CI.
pub fn validation_dir() -> Option<PathBuf> {
    karman_validation::folder().map(|f| f.dir)
}

/// Two numeric columns of a text file (`,` or whitespace separated, `;` comments and
/// non-numeric lines skipped).
fn columns(path: &PathBuf) -> Vec<[f64; 2]> {
    let text = std::fs::read_to_string(path).expect("readable data file");
    text.lines()
        .filter_map(|line| {
            let mut it = line.split([',', ' ', '\t']).filter(|s| !s.is_empty());
            let a = it.next()?.parse().ok()?;
            let b = it.next()?.parse().ok()?;
            it.next().is_none().then_some([a, b])
        })
        .collect()
}

/// Calisto's Cesaroni M1670 as RocketPy builds it (docs/physics.md §6): `.eng` curve with a (0, 0)
/// point prepended, clipped to [0, 3.9] s; 5 BATES grains.
pub fn calisto_motor(dir: &std::path::Path) -> MotorProperties {
    let mut points = vec![[0.0, 0.0]];
    points.extend(columns(&dir.join("calisto/Cesaroni_M1670.eng")));
    let raw = Table1::new(
        points.iter().map(|p| p[0]).collect(),
        points.iter().map(|p| p[1]).collect(),
        Interpolation::Linear,
        Extrapolation::Zero,
    )
    .expect("thrust table");
    let burn_out = 3.9;
    let mut xs = vec![0.0];
    let mut ys = vec![raw.eval(0.0)];
    for p in points.iter().filter(|p| p[0] > 0.0 && p[0] < burn_out) {
        xs.push(p[0]);
        ys.push(p[1]);
    }
    xs.push(burn_out);
    ys.push(raw.eval(burn_out));
    let thrust = Table1::new(xs, ys, Interpolation::Linear, Extrapolation::Zero).expect("thrust");
    let (n, rho, r_out, r_in, h0, sep) = (5.0, 1815.0, 0.033, 0.015, 0.12, 0.005);
    let mp0 = n * rho * std::f64::consts::PI * (r_out * r_out - r_in * r_in) * h0;
    let impulse = thrust.integral(0.0, burn_out);
    let ve = impulse / mp0;
    let grid = linspace(0.0, burn_out, 4001);
    let mp: Vec<f64> = grid
        .iter()
        .map(|&t| (mp0 - thrust.integral(0.0, t) / ve).max(0.0))
        .collect();
    // Grain bore radius from the remaining mass: N ρ π (R² − r²)(h0 − 2(r − r0)) = m_p.
    let bore = |m: f64| {
        let mass = |r: f64| {
            n * rho * std::f64::consts::PI * (r_out * r_out - r * r) * (h0 - 2.0 * (r - r_in))
        };
        let (mut a, mut b) = (r_in, r_out.min(r_in + h0 / 2.0));
        for _ in 0..100 {
            let c = 0.5 * (a + b);
            if mass(c) > m { a = c } else { b = c }
        }
        0.5 * (a + b)
    };
    let spacing: f64 = (0..5)
        .map(|i| ((f64::from(i) - 2.0) * (h0 + sep)).powi(2))
        .sum();
    let (mut i11, mut i33) = (Vec::new(), Vec::new());
    for &m in &mp {
        let r = bore(m);
        let h = h0 - 2.0 * (r - r_in);
        let mg = m / n;
        i11.push(n * mg * ((r_out * r_out + r * r) / 4.0 + h * h / 12.0) + mg * spacing);
        i33.push(0.5 * m * (r_out * r_out + r * r));
    }
    let table = |ys: Vec<f64>| {
        Table1::new(
            grid.clone(),
            ys,
            Interpolation::Linear,
            Extrapolation::Constant,
        )
        .expect("table")
    };
    MotorProperties {
        thrust,
        burn_start: 0.0,
        burn_out,
        exhaust_velocity: ve,
        propellant_mass: table(mp),
        mass_flow: None,
        propellant_center_of_mass: table(vec![0.397; grid.len()]),
        propellant_i11: table(i11),
        propellant_i33: table(i33),
        propellant_parts: Vec::new(),
        dry_mass: 1.815,
        center_of_dry_mass: 0.317,
        dry_inertia: [0.125, 0.125, 0.002, 0.0, 0.0, 0.0],
        nozzle_position: 0.0,
        nozzle_radius: 0.033,
        coordinate_system_sign: 1.0,
        reference_pressure: None,
    }
}

/// A drag curve file of the validation folder as a linear table.
pub fn drag(dir: &std::path::Path, file: &str) -> Table1 {
    let pts = columns(&dir.join(file));
    Table1::linear(
        pts.iter().map(|p| p[0]).collect(),
        pts.iter().map(|p| p[1]).collect(),
    )
    .expect("drag table")
}

/// The NACA 0012 lift curve of validation/calisto.
pub fn naca0012(dir: &std::path::Path) -> Airfoil {
    let pts = columns(&dir.join("calisto/NACA0012-radians.txt"));
    Airfoil {
        lift_curve: Table1::linear(
            pts.iter().map(|p| p[0]).collect(),
            pts.iter().map(|p| p[1]).collect(),
        )
        .expect("airfoil table"),
        unit: AngleUnit::Radians,
    }
}

/// Calisto's inputs (validation/calisto/mission.toml); `airfoil` for the fins.
pub fn calisto_inputs(dir: &std::path::Path, airfoil: Option<Airfoil>) -> RocketInputs {
    let chute = |name: &str, cd_s: f64, trigger| {
        Parachute::new(&ParachuteSpec {
            name: name.to_owned(),
            cd_s,
            trigger,
            sampling_rate: Some(105.0),
            lag: Some(1.5),
            noise: Some([0.0, 8.3, 0.5]),
            radius: Some(1.5),
            height: Some(1.5),
            porosity: Some(0.0432),
            drag_coefficient: None,
        })
        .expect("valid parachute")
    };
    RocketInputs {
        radius: 0.0635,
        mass: 14.426,
        inertia: [6.321, 6.321, 0.034, 0.0, 0.0, 0.0],
        center_of_mass_without_motor: 0.0,
        coordinate_system: CoordinateSystem::TailToNose,
        power_off_drag: drag(dir, "calisto/powerOffDragCurve.csv"),
        power_on_drag: drag(dir, "calisto/powerOnDragCurve.csv"),
        motor_position: -1.255,
        surfaces: vec![
            SurfaceInput {
                pod: None,
                name: "nose".to_owned(),
                position: 1.278,
                spec: SurfaceSpec::Nose(NoseConeSpec {
                    length: 0.55829,
                    kind: NoseKind::VonKarman,
                    base_radius: None,
                    bluffness: 0.0,
                }),
            },
            SurfaceInput {
                pod: None,
                name: "fins".to_owned(),
                position: -1.04956,
                spec: SurfaceSpec::TrapezoidalFins(TrapezoidalFinsSpec {
                    n: 4,
                    root_chord: 0.12,
                    tip_chord: 0.06,
                    span: 0.11,
                    sweep: Sweep::Default,
                    cant_angle_deg: 0.5,
                    angular_position_deg: 0.0,
                    radius: None,
                    airfoil,
                }),
            },
            SurfaceInput {
                pod: None,
                name: "tail".to_owned(),
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
            chute("main", 10.0, TriggerKind::HeightAboveGround(800.0)),
            chute("drogue", 1.0, TriggerKind::Apogee),
        ],
        rail_buttons: Some(RailButtons::new(0.0818, -0.6182, 45.0).expect("valid buttons")),
        eccentricities: Default::default(),
    }
}

/// The Calisto rocket of docs/physics.md §13 (plain fins), or `None` without validation data.
pub fn calisto(airfoil: bool) -> Option<Rocket> {
    let dir = validation_dir()?;
    let foil = airfoil.then(|| naca0012(&dir));
    Some(Rocket::new(calisto_inputs(&dir, foil), calisto_motor(&dir)).expect("valid Calisto"))
}

/// A small motor: 100 N for 1 s burning 0.05 kg, tables on one grid.
pub fn small_motor() -> MotorProperties {
    let grid = vec![0.0, 0.5, 1.0];
    let lin =
        |ys: Vec<f64>, e| Table1::new(grid.clone(), ys, Interpolation::Linear, e).expect("table");
    MotorProperties {
        thrust: lin(vec![100.0, 100.0, 100.0], Extrapolation::Zero),
        burn_start: 0.0,
        burn_out: 1.0,
        exhaust_velocity: 2000.0,
        propellant_mass: lin(vec![0.05, 0.025, 0.0], Extrapolation::Constant),
        mass_flow: None,
        propellant_center_of_mass: lin(vec![0.1; 3], Extrapolation::Constant),
        propellant_i11: lin(vec![1e-4, 5e-5, 0.0], Extrapolation::Constant),
        propellant_i33: lin(vec![1e-5, 5e-6, 0.0], Extrapolation::Constant),
        propellant_parts: Vec::new(),
        dry_mass: 0.1,
        center_of_dry_mass: 0.1,
        dry_inertia: [1e-3, 1e-3, 1e-5, 0.0, 0.0, 0.0],
        nozzle_position: 0.0,
        nozzle_radius: 0.01,
        coordinate_system_sign: 1.0,
        reference_pressure: None,
    }
}

/// The surface `spec` built alone on a rocket of radius `rocket_radius` (with
/// [`small_motor`]), as the rocket resolves it.
pub fn single_surface(spec: SurfaceSpec, rocket_radius: f64) -> karman_airframe::Surface {
    let inputs = RocketInputs {
        radius: rocket_radius,
        mass: 1.0,
        inertia: [0.1, 0.1, 0.001, 0.0, 0.0, 0.0],
        center_of_mass_without_motor: 0.5,
        coordinate_system: CoordinateSystem::TailToNose,
        power_off_drag: Table1::linear(vec![0.0], vec![0.5]).expect("table"),
        power_on_drag: Table1::linear(vec![0.0], vec![0.5]).expect("table"),
        motor_position: 0.0,
        surfaces: vec![SurfaceInput {
            pod: None,
            name: "s".to_owned(),
            position: 0.3,
            spec,
        }],
        parachutes: Vec::new(),
        rail_buttons: None,
        eccentricities: Default::default(),
    };
    let rocket = Rocket::new(inputs, small_motor()).expect("valid rocket");
    rocket.surfaces()[0].clone()
}
