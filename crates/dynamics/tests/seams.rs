//! The engine's openings for sensors and custom studies: the dense output's derivative at a
//! sampling instant, the signal store between processes, control channels found by name,
//! user-defined events, and an atmosphere queried at time and position.

use karman_dynamics::{
    Action, AtmosphereModel, BodyFlow, Configuration, Connections, Cursor, DynamicsError, Event,
    FlightSettings, MassFlowLaw, MassSample, Probe, SampledProcess, SignalId, Termination,
    VehicleModel, VehicleSetup, simulate, simulate_with, simulate_with_events,
};

use karman_dynamics::state::State;

use crate::mock::{MockAtmosphere, MockRocket, MockSurface};

fn settings() -> FlightSettings {
    let mut settings = FlightSettings::new(3.0);
    settings.inclination_deg = 85.0;
    settings
}

/// Records the acceleration the probe reads: `(a_x, a_y, a_z)` on channels 0–2.
struct Accelerometer;

impl SampledProcess for Accelerometer {
    fn rate(&self) -> f64 {
        50.0
    }
    fn sample(&mut self, probe: &mut Probe<'_>) -> Option<Action> {
        let a = probe.acceleration();
        // Records do not end the step: one process may record several values per instant.
        probe.publish(0, a[2]);
        Some(Action::Record {
            channel: 2,
            value: a[2],
        })
    }
}

#[test]
fn the_probe_reads_the_acceleration_inside_steps() {
    // In vacuum after burn-out the only force is gravity: v̇ = (0, 0, −g) exactly, and the
    // dense output of a linear v_z reproduces it (the steps are long, so most instants lie
    // well inside them).
    let atm = MockAtmosphere {
        rho0: 0.0,
        ..MockAtmosphere::default()
    };
    let rocket = MockRocket::stable();
    let flight =
        simulate_with(&atm, &rocket, &settings(), vec![Box::new(Accelerometer)]).expect("flies");
    let coasting: Vec<_> = flight.records.iter().filter(|r| r.t > 2.1).collect();
    assert!(coasting.len() > 100, "{}", coasting.len());
    for r in &coasting {
        assert!(
            (r.value + atm.g).abs() < 1e-6,
            "a_z = {} at {}",
            r.value,
            r.t
        );
    }
    // During the burn the thrust lifts it: the reading is not gravity there.
    let burning = flight.records.iter().find(|r| r.t > 0.5 && r.t < 1.9);
    assert!(burning.expect("a burning instant").value > 0.0);
}

/// Publishes the height `z` at each instant as `"{name}"`.
struct Altimeter(&'static [&'static str]);

impl SampledProcess for Altimeter {
    fn rate(&self) -> f64 {
        20.0
    }
    fn outputs(&self) -> &[&str] {
        self.0
    }
    fn sample(&mut self, probe: &mut Probe<'_>) -> Option<Action> {
        let z = probe.z();
        probe.publish(0, z);
        None
    }
}

/// Reads the altimeter's last value and records how old it is (channel 0) and how far it
/// is from the true height at the instant (channel 1).
struct Reader {
    signal: Option<SignalId>,
}

impl SampledProcess for Reader {
    fn rate(&self) -> f64 {
        20.0
    }
    fn connect(&mut self, connections: &Connections<'_>) -> Result<(), DynamicsError> {
        self.signal = Some(connections.signal("altimeter.z")?);
        Ok(())
    }
    fn sample(&mut self, probe: &mut Probe<'_>) -> Option<Action> {
        let read = probe.read(self.signal?)?;
        let z = probe.z();
        // Two records at one instant: the first ends nothing, so keep it in the log by
        // returning the second and publishing nothing.
        let age = probe.t() - read.t;
        Some(Action::Record {
            channel: usize::from(age > 0.0),
            value: read.value - z,
        })
    }
}

#[test]
fn a_process_reads_what_an_earlier_one_published_at_the_same_instant() {
    let (atm, rocket) = (MockAtmosphere::default(), MockRocket::stable());
    let fly = |reader_first: bool| {
        let altimeter: Box<dyn SampledProcess> = Box::new(Altimeter(&["altimeter.z"]));
        let reader: Box<dyn SampledProcess> = Box::new(Reader { signal: None });
        let processes = if reader_first {
            vec![reader, altimeter]
        } else {
            vec![altimeter, reader]
        };
        simulate_with(&atm, &rocket, &settings(), processes).expect("flies")
    };
    // The altimeter first: the reader sees the value of the same instant, the true height.
    let after = fly(false);
    assert!(after.records.len() > 50);
    for r in &after.records {
        assert_eq!(r.channel, 0, "same instant at {}", r.t);
        assert_eq!(r.value.to_bits(), 0.0f64.to_bits(), "at {}", r.t);
    }
    // The reader first: it sees the previous instant's height, which differs while flying.
    let before = fly(true);
    assert!(before.records.iter().all(|r| r.channel == 1));
    assert!(before.records.iter().any(|r| r.value.abs() > 0.1));
}

#[test]
fn signals_are_connected_by_name_or_the_flight_does_not_start() {
    let (atm, rocket) = (MockAtmosphere::default(), MockRocket::stable());
    let missing = simulate_with(
        &atm,
        &rocket,
        &settings(),
        vec![Box::new(Reader { signal: None })],
    );
    assert!(
        matches!(&missing, Err(DynamicsError::Unconnected { kind: "signal", name }) if name == "altimeter.z"),
        "{missing:?}"
    );
    let twice = simulate_with(
        &atm,
        &rocket,
        &settings(),
        vec![
            Box::new(Altimeter(&["altimeter.z"])),
            Box::new(Altimeter(&["altimeter.z"])),
        ],
    );
    assert!(
        matches!(&twice, Err(DynamicsError::DuplicateSignal { name }) if name == "altimeter.z"),
        "{twice:?}"
    );
}

/// The mock rocket with two control channels, `"spare"` and `"brakes"`: the brakes'
/// level `l` multiplies the drag by `1 + 4 l`.
struct Braked(MockRocket);

impl VehicleModel for Braked {
    type Surface = MockSurface;
    fn setup(&self) -> VehicleSetup {
        self.0.setup()
    }
    fn surfaces(&self) -> &[MockSurface] {
        self.0.surfaces()
    }
    fn mass(&self, t: f64, law: MassFlowLaw, cursors: &mut [Cursor; 2]) -> MassSample {
        self.0.mass(t, law, cursors)
    }
    fn total_mass(&self, t: f64, cursor: &mut Cursor) -> f64 {
        VehicleModel::total_mass(&self.0, t, cursor)
    }
    fn thrust(&self, t: f64, p: f64, cursor: &mut Cursor) -> f64 {
        self.0.thrust(t, p, cursor)
    }
    fn axial_load(&self, flow: &BodyFlow, c: &Configuration, cursor: &mut Cursor) -> f64 {
        self.0.axial_load(flow, c, cursor) * (1.0 + 4.0 * c.controls[1])
    }
    fn control_channels(&self) -> &[&str] {
        &["spare", "brakes"]
    }
}

/// Sets the control channel `name` to 1 at its first instant after 3 s.
struct Deploy {
    name: &'static str,
    channel: usize,
    done: bool,
}

impl SampledProcess for Deploy {
    fn rate(&self) -> f64 {
        10.0
    }
    fn on_rail(&self) -> bool {
        true
    }
    fn whole_step(&self) -> bool {
        true
    }
    fn connect(&mut self, connections: &Connections<'_>) -> Result<(), DynamicsError> {
        self.channel = connections.control(self.name)?;
        Ok(())
    }
    fn sample(&mut self, probe: &mut Probe<'_>) -> Option<Action> {
        if self.done || probe.t() < 3.0 {
            return None;
        }
        self.done = true;
        Some(Action::SetControl {
            index: self.channel,
            value: 1.0,
        })
    }
    fn is_done(&self) -> bool {
        self.done
    }
}

#[test]
fn a_control_channel_is_found_by_the_name_the_vehicle_declares() {
    let atm = MockAtmosphere::default();
    let rocket = Braked(MockRocket::stable());
    let deploy = |name| Deploy {
        name,
        channel: usize::MAX,
        done: false,
    };
    let free = simulate(&atm, &rocket, &settings()).expect("flies");
    let braked =
        simulate_with(&atm, &rocket, &settings(), vec![Box::new(deploy("brakes"))]).expect("flies");
    let apogee = |f: &karman_dynamics::Flight| f.apogee.expect("apogee").1[2];
    assert!(
        apogee(&braked) < apogee(&free) - 1.0,
        "{} vs {}",
        apogee(&braked),
        apogee(&free)
    );
    let last = braked.points.last().expect("points");
    assert_eq!(
        last.configuration.controls.map(f64::to_bits)[..2],
        [0.0, 1.0].map(f64::to_bits)
    );
    let unknown = simulate_with(&atm, &rocket, &settings(), vec![Box::new(deploy("flaps"))]);
    assert!(
        matches!(&unknown, Err(DynamicsError::Unconnected { kind: "control channel", name }) if name == "flaps"),
        "{unknown:?}"
    );
}

/// Fires when the height falls through `height` m ASL.
struct Below {
    height: f64,
    action: Action,
    fired: Vec<(f64, f64)>,
}

impl Event for Below {
    fn value(&self, _t: f64, state: &State) -> f64 {
        state[karman_dynamics::state::Z] - self.height
    }
    fn fire(&mut self, t: f64, state: &State) -> Action {
        self.fired.push((t, state[2]));
        self.action
    }
}

#[test]
fn a_user_event_fires_its_action_at_its_root() {
    let (atm, rocket) = (MockAtmosphere::default(), MockRocket::stable());
    let free = simulate(&atm, &rocket, &settings()).expect("flies");
    let height = atm.elevation + 300.0;
    let event = Below {
        height,
        action: Action::Terminate,
        fired: Vec::new(),
    };
    let flight = simulate_with_events(
        &atm,
        &rocket,
        &settings(),
        Vec::new(),
        vec![Box::new(event)],
    )
    .expect("flies");
    assert_eq!(flight.termination, Termination::Terminated);
    let end = flight.points.last().expect("points");
    assert!((end.state[2] - height).abs() < 1e-6, "{}", end.state[2]);
    assert_eq!(flight.t_final.to_bits(), end.t.to_bits());
    // On the descent, after the apogee (the ascent crosses upward: no root).
    assert!(flight.t_final > free.apogee.expect("apogee").0);
    assert!(flight.t_final < free.t_final);
    // A recorded value does not end the flight.
    let record = Below {
        height,
        action: Action::Record {
            channel: 7,
            value: 1.0,
        },
        fired: Vec::new(),
    };
    let recorded = simulate_with_events(
        &atm,
        &rocket,
        &settings(),
        Vec::new(),
        vec![Box::new(record)],
    )
    .expect("flies");
    assert_eq!(recorded.termination, Termination::Impact);
    assert_eq!(recorded.records.len(), 1);
    assert_eq!(recorded.records[0].channel, 7);
    assert_eq!(recorded.records[0].process, 0, "after the (no) processes");
    assert!((recorded.records[0].t - flight.t_final).abs() < 1e-9);
}

/// The mock atmosphere with a wind growing with time, `(0.5 t, 0)` m/s, and a density
/// halved east of `x = 50 m`.
struct Changing(MockAtmosphere);

impl AtmosphereModel for Changing {
    fn elevation(&self) -> f64 {
        self.0.elevation()
    }
    fn pressure(&self, z: f64) -> f64 {
        self.0.pressure(z)
    }
    fn density(&self, z: f64) -> f64 {
        self.0.density(z)
    }
    fn speed_of_sound(&self, z: f64) -> f64 {
        self.0.speed_of_sound(z)
    }
    fn dynamic_viscosity(&self, z: f64) -> f64 {
        self.0.dynamic_viscosity(z)
    }
    fn wind(&self, z: f64) -> [f64; 2] {
        self.0.wind(z)
    }
    fn wind_at(&self, t: f64, _position: [f64; 3]) -> [f64; 2] {
        [0.5 * t, 0.0]
    }
    fn air_at(&self, _t: f64, p: [f64; 3], cursor: &mut Cursor) -> karman_dynamics::Air {
        let mut air = self.0.air_near(p[2], cursor);
        if p[0] > 50.0 {
            air.density *= 0.5;
        }
        air
    }
    fn gravity(&self, z: f64) -> f64 {
        self.0.gravity(z)
    }
    fn earth_rotation_enu(&self) -> [f64; 3] {
        self.0.earth_rotation_enu()
    }
    fn barometric_height(&self, pressure: f64) -> f64 {
        self.0.barometric_height(pressure)
    }
}

#[test]
fn the_equations_ask_the_atmosphere_at_time_and_position() {
    let rocket = MockRocket::stable();
    let mut s = settings();
    s.heading_deg = 90.0; // towards the east, past x = 50 m
    let still = simulate(&MockAtmosphere::default(), &rocket, &s).expect("flies");
    let changing = simulate(&Changing(MockAtmosphere::default()), &rocket, &s).expect("flies");
    let (a, b) = (
        still.impact.expect("lands").1,
        changing.impact.expect("lands").1,
    );
    // The growing wind pushes it east (the rocket weathercocks into it on the ascent, the
    // descent drifts with it), and the thinner air east of 50 m raises the apogee.
    assert!((b[0] - a[0]).abs() > 0.1, "{} vs {}", b[0], a[0]);
    let apogee = |f: &karman_dynamics::Flight| f.apogee.expect("apogee").1;
    assert!(apogee(&still)[0] > 50.0);
    assert!(apogee(&changing)[2] > apogee(&still)[2], "thinner air");
    // A model that keeps the defaults flies as before, bit for bit.
    struct Plain(MockAtmosphere);
    impl AtmosphereModel for Plain {
        fn elevation(&self) -> f64 {
            self.0.elevation()
        }
        fn pressure(&self, z: f64) -> f64 {
            self.0.pressure(z)
        }
        fn density(&self, z: f64) -> f64 {
            self.0.density(z)
        }
        fn speed_of_sound(&self, z: f64) -> f64 {
            self.0.speed_of_sound(z)
        }
        fn dynamic_viscosity(&self, z: f64) -> f64 {
            self.0.dynamic_viscosity(z)
        }
        fn wind(&self, z: f64) -> [f64; 2] {
            self.0.wind(z)
        }
        fn gravity(&self, z: f64) -> f64 {
            self.0.gravity(z)
        }
        fn earth_rotation_enu(&self) -> [f64; 3] {
            self.0.earth_rotation_enu()
        }
        fn barometric_height(&self, pressure: f64) -> f64 {
            self.0.barometric_height(pressure)
        }
    }
    let plain = simulate(&Plain(MockAtmosphere::default()), &rocket, &s).expect("flies");
    assert_eq!(plain, still);
}

#[path = "../examples/custom_process.rs"]
mod example;

#[test]
fn the_example_flies_its_analytic_rocket_with_its_accelerometer() {
    let flight = example::fly();
    let (_, apogee) = flight.apogee.expect("apogee");
    assert!(apogee[2] > 500.0, "{}", apogee[2]);
    // The readings' maximum is in the burn: thrust over mass less gravity and drag,
    // below 800 / 10 − g.
    let peak = flight.records.last().expect("readings");
    assert!(
        peak.t < 2.0 && peak.value > 40.0 && peak.value < 800.0 / 10.0 - 9.8,
        "{peak:?}"
    );
    assert!(flight.records.windows(2).all(|w| w[1].value > w[0].value));
}
