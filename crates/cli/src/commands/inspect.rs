//! `karman inspect MISSION`: the models a mission builds — environment, motor (with its tanks)
//! and rocket — as readable tables or, with `--json`, one object `{environment, motor, rocket}`
//! shaped like the validation `reference.json` files, plus `tanks` (one object per tank) for
//! hybrid and liquid motors. `--plot DIR` writes SVG profiles and curves (per tank: liquid and
//! gas mass, level and centre of mass), `--draw FILE.svg` a to-scale drawing of the rocket
//! with its CG and CP. A rocket whose drag is estimated from its geometry is also flown to
//! rail exit's state: its CP and stability margin there as OpenRocket computes them (body
//! lift at the angle of attack, the flow's roll angle OpenRocket rolls the rocket to) are
//! printed, and under `stability_at_rail_exit` in the JSON.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use karman_mission::Mission;
use karman_mission::airframe::{DragComponents, DragEstimate, MotorProperties, Rocket};
use karman_mission::assemble::{
    environment::build_environment,
    flight::simulate,
    motor::build_motor,
    rocket::{build_rocket, estimated_drag},
};
use karman_mission::atmos::Environment;
use karman_mission::math::linspace;
use karman_mission::propulsion::Motor;
use karman_mission::report::environment::{default_heights, environment_report};
use karman_mission::report::motor::{ExtraMotorReport, MotorReport, TankReport};
use karman_mission::report::rocket::{AngleStability, RocketReport, draw_rocket_svg};

use super::MissionArgs;
use crate::plot::{Series, line_chart};

/// Arguments of `karman inspect`.
#[derive(Debug, Args)]
pub struct InspectArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
    /// Print one JSON object {environment, motor, rocket} (and tanks) instead of tables.
    #[arg(long)]
    pub json: bool,
    /// Heights above sea level (m) for the environment, comma-separated; default: the launch
    /// elevation + 0, 50, 100, 200 m, then every 250 m up to max_expected_height.
    #[arg(long, value_name = "H1,H2,...", value_delimiter = ',')]
    pub heights: Option<Vec<f64>>,
    /// Times (s) for the motor, comma-separated; default: burn start + k/10 of the burn
    /// (k = 0..10) and burn-out + 1 s.
    #[arg(long, value_name = "T1,T2,...", value_delimiter = ',')]
    pub times: Option<Vec<f64>>,
    /// Write SVG charts of the atmosphere, wind and motor curves into this directory.
    #[arg(long, value_name = "DIR")]
    pub plot: Option<PathBuf>,
    /// Write a to-scale SVG drawing of the rocket, CG and CP marked, to this file.
    #[arg(long, value_name = "FILE.svg")]
    pub draw: Option<PathBuf>,
}

/// Builds the models and prints or writes what was asked.
pub fn run(args: &InspectArgs) -> Result<()> {
    let mission = args.mission.load()?;
    if !mission.spec.stages.is_empty() {
        super::print_warnings(
            &mission,
            &[
                "`stages`: a multi-stage rocket; shown is its top stage ([rocket], [motor]) alone"
                    .to_owned(),
            ],
        );
    }
    let environment = build_environment(&mission)?;
    let motor = build_motor(&mission)?;
    let rocket = build_rocket(&mission, &motor)?;
    let heights = args.heights.clone().unwrap_or_else(|| {
        default_heights(
            environment.elevation(),
            mission.spec.environment.max_expected_height,
        )
    });
    let env_report = environment_report(&environment, &heights);
    let motor_report = MotorReport::at(&motor, args.times.as_deref());
    let tanks = TankReport::for_motor(&motor, &motor_report.times_s);
    let extra_motors = ExtraMotorReport::for_mission(&mission, args.times.as_deref())?;
    let rocket_report = RocketReport::new(&rocket);
    let rail_exit = stability_at_rail_exit(&mission)?;
    let mut out = std::io::stdout().lock();
    if args.json {
        let mut value = serde_json::json!({
            "environment": env_report,
            "motor": motor_report,
            "rocket": rocket_report,
        });
        if !tanks.is_empty() {
            value["tanks"] = serde_json::to_value(&tanks)?;
        }
        if !extra_motors.is_empty() {
            value["extra_motors"] = serde_json::to_value(&extra_motors)?;
        }
        if let Some(stability) = &rail_exit {
            value["stability_at_rail_exit"] = serde_json::to_value(stability)?;
        }
        writeln!(out, "{}", serde_json::to_string_pretty(&value)?)?;
    } else {
        writeln!(out, "Environment\n{env_report}\n{motor_report}")?;
        for tank in &tanks {
            writeln!(out, "{tank}")?;
        }
        for extra in &extra_motors {
            writeln!(out, "{extra}")?;
        }
        writeln!(out, "{rocket_report}")?;
        if let Some(stability) = &rail_exit {
            writeln!(out, "At rail exit: {stability}")?;
        }
    }
    for warning in rocket.warnings() {
        eprintln!("warning: {warning}");
    }
    if let Some(dir) = &args.plot {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
        let top = heights
            .iter()
            .copied()
            .fold(environment.elevation() + 1000.0, f64::max);
        plot_environment(&environment, top, dir)?;
        let all = (!mission.spec.extra_motors.is_empty()).then(|| rocket.motor());
        plot_motor(&motor, all, dir)?;
        plot_drag(&rocket, estimated_drag(&mission, &motor)?.as_ref(), dir)?;
    }
    if let Some(file) = &args.draw {
        std::fs::write(file, draw_rocket_svg(&mission, &rocket))
            .with_context(|| format!("cannot write {}", file.display()))?;
    }
    Ok(())
}

/// OpenRocket's CP and margin at the rail exit of `mission`'s flight, for a single-stage
/// rocket whose drag is estimated from its geometry (`None` otherwise or if the flight
/// never leaves the rail): at the angle of attack and Mach karman's flight has there.
fn stability_at_rail_exit(mission: &Mission) -> Result<Option<AngleStability>> {
    if mission.spec.rocket.drag_estimate.is_none() || !mission.spec.stages.is_empty() {
        return Ok(None);
    }
    let run = simulate(mission)?;
    let Some(exit) = run.summary().out_of_rail_time_s else {
        return Ok(None);
    };
    let Some(sample) = run.samples().into_iter().find(|s| s.t >= exit) else {
        return Ok(None);
    };
    let stability = AngleStability::new(
        mission,
        &run.rocket,
        sample.t,
        sample.angle_of_attack_deg.to_radians(),
        sample.mach,
        |worst| worst,
    )?;
    Ok(Some(stability))
}

/// Profiles of pressure, temperature, density, speed of sound and wind from the launch
/// elevation to `top` (m ASL), height on the vertical axis.
fn plot_environment(env: &Environment, top: f64, dir: &Path) -> Result<()> {
    let heights = linspace(env.elevation(), top, 400);
    let profile = |f: &dyn Fn(f64) -> f64| heights.iter().map(|&h| (f(h), h)).collect::<Vec<_>>();
    let charts: [(&str, &str, &str, Vec<Series<'_>>); 5] = [
        (
            "pressure",
            "Pressure",
            "pressure (Pa)",
            vec![Series {
                label: "p",
                points: profile(&|h| env.pressure(h)),
            }],
        ),
        (
            "temperature",
            "Temperature",
            "temperature (K)",
            vec![Series {
                label: "T",
                points: profile(&|h| env.temperature(h)),
            }],
        ),
        (
            "density",
            "Density",
            "density (kg/m³)",
            vec![Series {
                label: "ρ",
                points: profile(&|h| env.density(h)),
            }],
        ),
        (
            "speed_of_sound",
            "Speed of sound",
            "speed of sound (m/s)",
            vec![Series {
                label: "a",
                points: profile(&|h| env.speed_of_sound(h)),
            }],
        ),
        (
            "wind",
            "Wind",
            "wind (m/s)",
            vec![
                Series {
                    label: "u (east)",
                    points: profile(&|h| env.wind(h)[0]),
                },
                Series {
                    label: "v (north)",
                    points: profile(&|h| env.wind(h)[1]),
                },
            ],
        ),
    ];
    for (file, title, x_label, series) in charts {
        line_chart(
            &dir.join(format!("{file}.svg")),
            title,
            x_label,
            "height ASL (m)",
            &series,
        )?;
    }
    Ok(())
}

/// Charts of `[motor]` (thrust, masses, inertia, its tanks') from ignition to burn-out + 1 s,
/// with, for a rocket with `[[extra_motors]]`, the thrust and propellant of `all` its motors
/// (each cluster, each at its ignition time) beside `[motor]`'s, to the last burn-out + 1 s.
fn plot_motor(motor: &Motor, all: Option<&MotorProperties>, dir: &Path) -> Result<()> {
    let end = all.map_or(motor.burn_out(), |a| a.burn_out.max(motor.burn_out()));
    let times = linspace(0.0_f64.min(motor.burn_start()), end + 1.0, 500);
    let curve = |f: &dyn Fn(f64) -> f64| times.iter().map(|&t| (t, f(t))).collect::<Vec<_>>();
    let [thrust_label, total_label, propellant_label] = if all.is_some() {
        ["[motor]", "[motor] total", "[motor] propellant"]
    } else {
        ["thrust", "total", "propellant"]
    };
    let mut thrust = vec![Series {
        label: thrust_label,
        points: curve(&|t| motor.thrust(t)),
    }];
    let mut mass = vec![
        Series {
            label: total_label,
            points: curve(&|t| motor.total_mass(t)),
        },
        Series {
            label: propellant_label,
            points: curve(&|t| motor.propellant_mass().eval(t)),
        },
    ];
    if let Some(all) = all {
        thrust.push(Series {
            label: "every motor",
            points: curve(&|t| all.thrust.eval(t)),
        });
        mass.push(Series {
            label: "every motor's propellant",
            points: curve(&|t| all.propellant_mass.eval(t)),
        });
    }
    line_chart(
        &dir.join("thrust.svg"),
        "Thrust",
        "time (s)",
        "thrust (N)",
        &thrust,
    )?;
    line_chart(
        &dir.join("motor_mass.svg"),
        "Motor mass",
        "time (s)",
        "mass (kg)",
        &mass,
    )?;
    line_chart(
        &dir.join("motor_inertia.svg"),
        "Motor inertia about its centre of mass",
        "time (s)",
        "inertia (kg·m²)",
        &[
            Series {
                label: "I11",
                points: curve(&|t| motor.inertia(t).0),
            },
            Series {
                label: "I33",
                points: curve(&|t| motor.inertia(t).1),
            },
        ],
    )?;
    for (index, p) in motor.tanks().iter().enumerate() {
        let tank = &p.tank;
        let title = |what: &str| format!("Tank {index} '{}': {what}", tank.name());
        line_chart(
            &dir.join(format!("tank_{index}_mass.svg")),
            &title("fluid masses"),
            "time (s)",
            "mass (kg)",
            &[
                Series {
                    label: "liquid",
                    points: curve(&|t| tank.liquid_mass().eval(t)),
                },
                Series {
                    label: "gas",
                    points: curve(&|t| tank.gas_mass().eval(t)),
                },
            ],
        )?;
        line_chart(
            &dir.join(format!("tank_{index}_level.svg")),
            &title("liquid level and centre of mass"),
            "time (s)",
            "height (m, motor coordinates)",
            &[
                Series {
                    label: "liquid level",
                    points: curve(&|t| p.position + tank.liquid_height().eval(t)),
                },
                Series {
                    label: "centre of mass",
                    points: curve(&|t| p.position + tank.center_of_mass().eval(t)),
                },
            ],
        )?;
    }
    Ok(())
}

/// The drag curves the flight uses against Mach and, when they are estimated from the
/// geometry, their friction, pressure and base terms.
fn plot_drag(rocket: &Rocket, estimate: Option<&DragEstimate>, dir: &Path) -> Result<()> {
    let machs = linspace(0.0, 3.0, 301);
    let curve = |on: bool| {
        machs
            .iter()
            .map(|&m| (m, rocket.drag_coefficient(on, m)))
            .collect::<Vec<_>>()
    };
    line_chart(
        &dir.join("drag.svg"),
        "Drag coefficient",
        "Mach",
        "Cd",
        &[
            Series {
                label: "power off",
                points: curve(false),
            },
            Series {
                label: "power on",
                points: curve(true),
            },
        ],
    )?;
    if let Some(e) = estimate {
        let term = |f: &dyn Fn(&DragComponents) -> f64| {
            e.mach
                .iter()
                .zip(&e.components)
                .map(|(m, c)| (*m, f(c)))
                .collect::<Vec<_>>()
        };
        line_chart(
            &dir.join("drag_components.svg"),
            "Estimated drag build-up",
            "Mach",
            "Cd",
            &[
                Series {
                    label: "total, power off",
                    points: term(&|c| c.power_off()),
                },
                Series {
                    label: "skin friction",
                    points: term(&|c| c.friction),
                },
                Series {
                    label: "pressure",
                    points: term(&|c| c.pressure),
                },
                Series {
                    label: "base, power off",
                    points: term(&|c| c.base),
                },
                Series {
                    label: "base, power on",
                    points: term(&|c| c.base_power_on),
                },
            ],
        )?;
    }
    Ok(())
}
