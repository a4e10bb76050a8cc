//! Sampled processes and resumed flights on the mock rocket: a process that terminates the
//! flight, one that records values, a control value set in the step a parachute deploys in,
//! and `simulate_from` from a mid-flight state.

use karman_dynamics::{
    Action, Configuration, FlightSettings, ParachuteSpec, Probe, SampledProcess, Termination,
    TriggerKind, simulate, simulate_from, simulate_with,
};

use crate::mock::{MockAtmosphere, MockRocket};

/// A process at `rate` Hz that records its samples' heights on channel 0 and terminates the
/// flight at its first instant at or after `stop`.
struct StopAt {
    rate: f64,
    stop: f64,
    samples: usize,
}

impl SampledProcess for StopAt {
    fn rate(&self) -> f64 {
        self.rate
    }
    fn sample(&mut self, probe: &mut Probe<'_>) -> Option<Action> {
        self.samples += 1;
        if probe.t() >= self.stop {
            Some(Action::Terminate)
        } else if self.samples % 2 == 0 {
            Some(Action::Record {
                channel: 0,
                value: probe.z(),
            })
        } else {
            None
        }
    }
}

#[test]
fn a_process_returning_terminate_ends_the_flight_at_its_sample_instant() {
    let (atm, rocket) = (MockAtmosphere::default(), MockRocket::stable());
    let settings = FlightSettings::new(3.0);
    // 8 Hz: the instants j/8 are exact doubles, 3 s among them (during the coast).
    let stop = StopAt {
        rate: 8.0,
        stop: 3.0,
        samples: 0,
    };
    let flight = simulate_with(&atm, &rocket, &settings, vec![Box::new(stop)]).expect("flies");
    assert_eq!(flight.termination, Termination::Terminated);
    let last = flight.points.last().expect("points");
    assert!(
        (flight.t_final - 3.0).abs() <= f64::EPSILON * 3.0,
        "{}",
        flight.t_final
    );
    assert!(
        (last.t - flight.t_final).abs() <= 0.0,
        "{} vs {}",
        last.t,
        flight.t_final
    );
    assert!(flight.apogee.is_none() && flight.impact.is_none());
    // Without the process the flight goes on.
    let full = simulate(&atm, &rocket, &settings).expect("flies");
    assert_eq!(full.termination, Termination::Impact);
    // Recorded values: every second sample from rail exit on, at instants j/8, in time order.
    assert!(!flight.records.is_empty());
    assert!(flight.records.windows(2).all(|w| w[0].t < w[1].t));
    for r in &flight.records {
        assert_eq!((r.process, r.channel), (0, 0));
        assert!(((r.t * 8.0).round() - r.t * 8.0).abs() < 1e-9, "{}", r.t);
        assert!(r.value > atm.elevation && r.t < 3.0);
    }
}

/// A process at `rate` Hz that acts once, at its first instant at or after `at`.
struct Once {
    rate: f64,
    at: f64,
    action: Action,
    done: bool,
}

impl SampledProcess for Once {
    fn rate(&self) -> f64 {
        self.rate
    }
    fn sample(&mut self, probe: &mut Probe<'_>) -> Option<Action> {
        if self.done || probe.t() < self.at {
            return None;
        }
        self.done = true;
        Some(self.action)
    }
    fn is_done(&self) -> bool {
        self.done
    }
}

#[test]
fn a_control_set_for_after_the_step_survives_a_deployment_later_in_that_step() {
    let atm = MockAtmosphere::default();
    let mut rocket = MockRocket::stable();
    // A parachute whose own trigger never fires: the second process deploys it.
    rocket.parachutes = vec![ParachuteSpec {
        name: "chute".into(),
        cd_s: 2.0,
        trigger: TriggerKind::HeightAboveGround(-1.0),
        sampling_rate: 100.0,
        lag: 0.5,
        noise: [0.0; 3],
        radius: 0.5,
        height: 0.5,
        added_mass_coefficient: 1.0,
    }];
    let settings = FlightSettings::new(3.0);
    let (set_at, deploy_at, level) = (3.0, 3.001, 0.7);
    let fly = |deploy: bool| {
        let mut processes: Vec<Box<dyn SampledProcess>> = vec![Box::new(Once {
            rate: 1000.0,
            at: set_at,
            action: Action::SetControlAfterStep {
                index: 0,
                value: level,
            },
            done: false,
        })];
        if deploy {
            processes.push(Box::new(Once {
                rate: 1000.0,
                at: deploy_at,
                action: Action::DeployDevice(0),
                done: false,
            }));
        }
        simulate_with(&atm, &rocket, &settings, processes).expect("flies")
    };
    // Alone, the value acts from the end of the step holding its instant.
    let alone = fly(false);
    let first = alone
        .points
        .iter()
        .position(|p| p.configuration.controls[0].to_bits() == level.to_bits())
        .expect("the value is flown");
    assert!(alone.points[first - 1].t >= set_at, "from a step end");
    assert!(
        alone.points[first..]
            .iter()
            .all(|p| p.configuration.controls[0].to_bits() == level.to_bits())
    );
    // With the deployment one instant later in the same step, the step ends there and the
    // value acts from that instant, in the lag phase and under the parachute.
    let deployed = fly(true);
    assert_eq!(deployed.parachute_events.len(), 1);
    let event = &deployed.parachute_events[0];
    let cut = deployed
        .points
        .iter()
        .position(|p| p.t.to_bits() == event.trigger_time.to_bits())
        .expect("the step is cut at the deployment");
    assert!(
        deployed.points[cut - 1].t < set_at,
        "both instants are in one step"
    );
    let after = &deployed.points[cut + 1..];
    assert!(after.iter().any(|p| p.configuration.is_deployed(0)));
    assert!(
        after
            .iter()
            .all(|p| p.configuration.controls[0].to_bits() == level.to_bits()),
        "the value is lost after the deployment"
    );
}

#[test]
fn simulate_from_a_mid_flight_state_reaches_the_same_apogee() {
    let (atm, rocket) = (
        MockAtmosphere {
            wind: [2.0, -1.0],
            ..MockAtmosphere::default()
        },
        MockRocket::stable(),
    );
    let mut settings = FlightSettings::new(3.0);
    settings.inclination_deg = 85.0;
    settings.rtol = 1e-12;
    settings.atol = [1e-12; 13];
    let full = simulate(&atm, &rocket, &settings).expect("flies");
    let (t_apogee, apogee) = full.apogee.expect("apogee");
    // A stored point of the coast, a few seconds before apogee.
    let resume = full
        .points
        .iter()
        .find(|p| p.t > rocket.burn_time + 2.0)
        .expect("a coast point");
    assert!(resume.t < t_apogee - 1.0);
    let resumed = simulate_from(
        &atm,
        &rocket,
        &settings,
        resume.t,
        resume.state,
        Configuration::default(),
        Vec::new(),
    )
    .expect("resumes");
    let (t_again, again) = resumed.apogee.expect("apogee");
    let height = apogee[2] - atm.elevation;
    let error = (again[2] - apogee[2]).abs() / height;
    println!("resumed apogee: relative difference {error:e}");
    assert!(
        error < 1e-9,
        "apogee {} vs {}: {error:e}",
        again[2],
        apogee[2]
    );
    // The apogee instant is the linear root of v_z between the ends of the step that holds
    // it (RocketPy's, docs/physics.md §9.3): second order in the step, which differs between the
    // two flights; at apogee the height is stationary, so it hardly moves the height.
    assert!((t_again - t_apogee).abs() < 1e-4, "{t_again} vs {t_apogee}");
    assert!(resumed.rail_exit.is_none());
    assert_eq!(resumed.points[0].t.to_bits(), resume.t.to_bits());
    assert_eq!(resumed.termination, Termination::Impact);
}

#[test]
fn simulate_from_rejects_a_start_after_max_time() {
    let (atm, rocket) = (MockAtmosphere::default(), MockRocket::stable());
    let settings = FlightSettings::new(3.0);
    let state = [0.0; 13];
    let err = simulate_from(
        &atm,
        &rocket,
        &settings,
        settings.max_time,
        state,
        Configuration::default(),
        Vec::new(),
    );
    assert!(err.is_err());
}
