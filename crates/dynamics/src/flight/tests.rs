//! The engine's flight tests on the mock models: the bounded sampling against the direct
//! evaluation of every instant, replays, the integrator hand-overs.

use karman_model::{ParachuteSpec, TriggerKind};

use super::actions::Acted;
use super::instants::{Processes, node_key};
use super::log::{Log, acceleration};
use super::process::Probe;
use super::run::{Extras, Sampling, Start, fly};
use super::schedule::Phase;
use super::{Flight, IntegrationStats, evaluate};
use crate::equations::{Cursors, Equations};
use crate::integrator::RungeKutta;
use crate::settings::FlightSettings;
use crate::state::State;

impl Processes<'_> {
    /// The reference the bounded sampling must agree with: every instant of every active
    /// process collected into a node list, sorted, grouped by key and evaluated in order
    /// ([`super::SampledProcess::sample_directly`], every noisy stream drawn at each of its
    /// instants), with no bounds.
    pub(super) fn sample_every_instant<F: FnMut(f64, &State) -> State>(
        &mut self,
        integ: &mut RungeKutta<13, F>,
        phase: &Phase,
        log: &mut Log,
    ) -> Option<Acted> {
        if self.active.is_empty() {
            return None;
        }
        let (t_start, t_end) = log.last_step();
        let (k_start, k_end) = (node_key(t_start), node_key(t_end));
        let mut nodes: Vec<(f64, usize)> = Vec::new();
        for &p in &self.active {
            let interval = 1.0 / self.list[p].rate();
            let j0 = (t_start / interval).floor() as i64 - 1;
            let j1 = (t_end / interval).ceil() as i64 + 1;
            for j in j0..=j1 {
                let t = j as f64 * interval;
                if (k_start..=k_end).contains(&node_key(t)) {
                    nodes.push((t, p));
                }
            }
        }
        if nodes.is_empty() {
            return None;
        }
        nodes.sort_by(|a, b| a.0.total_cmp(&b.0));
        let first_key = node_key(nodes[0].0);
        let skip_first = phase.clear && (nodes[0].0 - phase.t).abs() < 1e-9;
        for &(t, p) in &nodes {
            let key = node_key(t);
            if key == k_end {
                break;
            }
            if skip_first && key == first_key && !self.list[p].sampled_at_cleared_start() {
                continue;
            }
            // The group is evaluated at its first instant.
            let t_node = nodes
                .iter()
                .find(|m| node_key(m.0) == key)
                .map_or(t, |m| m.0);
            let mut probe = Probe::new(t_node, integ, &mut self.signals);
            probe.sampling(p);
            if let Some(action) = self.list[p].sample_directly(&mut probe) {
                return Some(Acted {
                    process: p,
                    action,
                    t: t_node,
                    control: None,
                });
            }
        }
        None
    }
}

use crate::mock::{MockAtmosphere, MockRocket};

/// The test atmosphere: the mock's, with a constant wind (2, −1) m/s.
fn air() -> MockAtmosphere {
    MockAtmosphere {
        wind: [2.0, -1.0],
        ..MockAtmosphere::default()
    }
}

/// The mock's stable rocket with `parachutes`.
fn rocket(parachutes: Vec<ParachuteSpec>) -> MockRocket {
    MockRocket {
        parachutes,
        ..MockRocket::stable()
    }
}

/// A parachute with the given trigger, rate, lag and noise.
fn chute(name: &str, trigger: TriggerKind, rate: f64, lag: f64, noise: [f64; 3]) -> ParachuteSpec {
    ParachuteSpec {
        name: name.into(),
        cd_s: if trigger == TriggerKind::Apogee {
            0.5
        } else {
            2.0
        },
        trigger,
        sampling_rate: rate,
        lag,
        noise,
        radius: 0.5,
        height: 0.5,
        added_mass_coefficient: 1.0,
    }
}

fn fly_with(parachutes: Vec<ParachuteSpec>, seed: u64, sampling: Sampling) -> Flight {
    let mut settings = FlightSettings::new(3.0);
    settings.inclination_deg = 86.0;
    settings.noise_seed = seed;
    fly(
        &air(),
        &rocket(parachutes),
        &settings,
        Start::Rail,
        Extras::default(),
        sampling,
    )
    .expect("flies")
}

/// Calisto's trigger noise, Pa.
const CALISTO_NOISE: [f64; 3] = [0.0, 8.3, 0.5];

#[test]
fn stiff_descent_is_finished_by_chebyshev_steps_at_terminal_speed() {
    // The 10 kg rocket under a 2 m² canopy from apogee: the drag relaxes the descent speed
    // at 2g/v ≈ 2/s, which holds DOPRI5 to ≈ 1.5 s steps; RKC takes over and lands at the
    // terminal speed √(2mg/(ρ C_dS)) (the wind is constant, so the canopy drifts with it),
    // up to the lag of the speed behind the density change (≈ 3e-4 of it here).
    let main = ParachuteSpec {
        cd_s: 2.0,
        ..chute("main", TriggerKind::Apogee, 100.0, 0.0, [0.0; 3])
    };
    let flight = fly_with(vec![main], 1, Sampling::BoundedStepwise);
    assert!(flight.stats.chebyshev_steps > 0, "{:?}", flight.stats);
    let (_, state) = flight.impact.expect("lands");
    let (atm, body) = (air(), MockRocket::stable());
    let terminal = (2.0 * body.dry_mass * atm.g
        / (karman_model::AtmosphereModel::density(&atm, state[2]) * 2.0))
        .sqrt();
    assert!(
        (-state[5] / terminal - 1.0).abs() < 1e-3,
        "{} vs {terminal}",
        -state[5]
    );
    for (v, w) in state[3..5].iter().zip(atm.wind) {
        assert!((v - w).abs() < 1e-3 * terminal, "drift {v} vs wind {w}");
    }
}

#[test]
fn max_acceleration_is_the_largest_at_the_stored_points() {
    // The definition the FSAL shortcut replaces: the equations evaluated at every stored
    // point, and the next phase's equations at each phase boundary (the canopy peak).
    // A main canopy so large that its opening shock is the largest acceleration of the
    // flight, at the first instant of its phase.
    let chutes = || {
        let mut main = chute(
            "main",
            TriggerKind::HeightAboveGround(300.0),
            100.0,
            0.0,
            [0.0; 3],
        );
        main.cd_s = 400.0;
        vec![
            chute("drogue", TriggerKind::Apogee, 100.0, 1.0, [0.0; 3]),
            main,
        ]
    };
    let flight = fly_with(chutes(), 0, Sampling::Bounded);
    assert_eq!(flight.parachute_events.len(), 2);
    let (air, rocket) = (air(), rocket(chutes()));
    let eq = Equations::new(&air, &rocket, flight.equations);
    let mut cursors = Cursors::default();
    let mut at = |p: &super::SolutionPoint, t: f64, u: &State| {
        acceleration(&evaluate(&eq, &p.phase, &p.configuration, t, u, &mut cursors).u_dot)
    };
    let mut expected: f64 = 0.0;
    for p in &flight.points {
        expected = expected.max(at(p, p.t, &p.state));
    }
    for w in flight.points.windows(2) {
        if w[0].phase != w[1].phase {
            expected = expected.max(at(&w[1], w[0].t, &w[0].state));
        }
    }
    // The same evaluations (the FSAL stage is taken at the stored point's time).
    assert!(
        (flight.max_acceleration - expected).abs() <= 1e-12 * expected,
        "{} vs {expected}",
        flight.max_acceleration
    );
}

#[test]
fn noisy_flight_replays_bit_for_bit() {
    let chutes = || {
        vec![
            chute(
                "main",
                TriggerKind::HeightAboveGround(300.0),
                105.0,
                1.5,
                CALISTO_NOISE,
            ),
            chute("drogue", TriggerKind::Apogee, 105.0, 1.5, CALISTO_NOISE),
        ]
    };
    let a = fly_with(chutes(), 11, Sampling::Bounded);
    let b = fly_with(chutes(), 11, Sampling::Bounded);
    assert_eq!(a.parachute_events.len(), 2);
    let bits = |f: &Flight| {
        f.points
            .iter()
            .flat_map(|p| std::iter::once(p.t).chain(p.state))
            .map(f64::to_bits)
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(&a), bits(&b));
    assert_eq!(a, b);
}

#[test]
fn bounded_sampling_decides_as_direct_evaluation() {
    // Apogee of this rocket with no parachute, m above the pad.
    let ballistic = fly_with(Vec::new(), 0, Sampling::Bounded);
    let apogee_agl = ballistic.apogee.expect("apogee").1[2] - 100.0;
    let height = TriggerKind::HeightAboveGround;
    let cases: Vec<(&str, Vec<ParachuteSpec>)> = vec![
        (
            "Calisto-like, equal rates",
            vec![
                chute("main", height(300.0), 105.0, 1.5, CALISTO_NOISE),
                chute("drogue", TriggerKind::Apogee, 105.0, 1.5, CALISTO_NOISE),
            ],
        ),
        (
            "unequal rates, no lag, silent drogue",
            vec![
                chute("drogue", TriggerKind::Apogee, 100.0, 0.0, [0.0; 3]),
                chute("main", height(250.0), 30.0, 0.0, [2.0, 40.0, 0.8]),
            ],
        ),
        (
            // 0.3 m below apogee, with 8.3 Pa (~0.7 m) of noise: fires at apogee or not.
            "height trigger at the apogee threshold",
            vec![
                chute("high", height(apogee_agl - 0.3), 100.0, 0.0, CALISTO_NOISE),
                chute("low", height(200.0), 105.0, 1.0, CALISTO_NOISE),
                chute("quiet", height(120.0), 10.0, 0.0, [0.0; 3]),
            ],
        ),
        (
            "two noisy height triggers, one without lag",
            vec![
                chute("upper", height(400.0), 20.0, 0.0, [0.0, 300.0, 0.5]),
                chute("lower", height(150.0), 50.0, 0.7, [1.0, 300.0, 0.0]),
            ],
        ),
    ];
    let mut high_triggers = Vec::new();
    for (name, chutes) in &cases {
        for seed in 0..6 {
            let bounded = fly_with(chutes.clone(), seed, Sampling::BoundedStepwise);
            let direct = fly_with(chutes.clone(), seed, Sampling::Direct);
            assert!(
                !bounded.parachute_events.is_empty(),
                "{name}, seed {seed}: nothing fired"
            );
            assert_eq!(
                bounded.parachute_events, direct.parachute_events,
                "{name}, seed {seed}"
            );
            // The reference asks for dense values in more steps: DOP853 steps among them
            // make their three extra evaluations, which change no value.
            assert!(bounded.stats.evaluations <= direct.stats.evaluations);
            let direct = Flight {
                stats: IntegrationStats {
                    evaluations: bounded.stats.evaluations,
                    ..direct.stats
                },
                ..direct
            };
            assert_eq!(bounded, direct, "{name}, seed {seed}");
            let apogee_t = bounded.apogee.expect("apogee").0;
            high_triggers.extend(
                bounded
                    .parachute_events
                    .iter()
                    .filter(|e| e.name == "high")
                    .map(|e| e.trigger_time - apogee_t),
            );
        }
    }
    // The threshold case must depend on the draws to test anything.
    assert!(
        high_triggers
            .iter()
            .any(|&dt| (dt - high_triggers[0]).abs() > 1e-6),
        "high trigger instants after apogee {high_triggers:?}"
    );
}
