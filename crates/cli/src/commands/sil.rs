//! `karman sil MISSION --exec PROGRAM [ARGS]...`: software in the loop. The mission flies with
//! its air brakes driven by an outside program (flight software in C, Python, anything that
//! reads and writes lines) instead of its Rhai controller: at every controller call (at
//! `t = j / sampling_rate` in every phase, where the Rhai controller would be called) karman
//! writes one line with the state and the sensors' latest readings to the program's standard
//! input and reads the level it answers from its standard output.
//!
//! The protocol, one line each way, numbers in Rust's shortest round-trip exponent form
//! (`1.5e0`, `NaN`; C's `strtod` reads them exactly, and `%.17g` writes a double that reads
//! back exactly):
//!
//! - first, karman → program: `karman-sil 1 rate R elevation E burn_out B reference_area A
//!   clamp C level L sensors N` then, for each sensor, ` NAME KIND` (`kind` one of
//!   `accelerometer`, `gyroscope`, `barometer`, `gnss`);
//! - at each call, karman → program: `step T X Y Z VX VY VZ E0 E1 E2 E3 WX WY WZ LEVEL`, then
//!   for each sensor ` TIME M0 M1 M2` (the latest reading, `NaN`s before the first; a
//!   barometer's pressure in `M0`);
//! - program → karman, once per `step`: `level VALUE` (stored as a Rhai write is: clipped to
//!   `[0, 1]` when the brakes clamp) or `keep`;
//! - at the end karman closes the program's input; the program should then exit.
//!
//! The program is held to the same instants and arithmetic as a controller in the mission,
//! so one that computes what the Rhai controller computes gives the same flight, bit for bit
//! (`fixtures/airbrakes/sil_apogee.c` and its twin `sil_apogee.rhai`). An answer that is not a
//! line of the protocol, a program that exits, or one that does not answer within
//! `--timeout` seconds ends the flight with an error naming the call's time. `--json` and
//! `--out DIR` are `karman simulate`'s (without the controller's record, which the program
//! keeps itself).

use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::Duration;

use anyhow::{Context, Result, bail};
use clap::Args;
use karman_mission::assemble::flight::{PreparedFlight, early_ending};
use karman_mission::script::{AirBrakeController, AirBrakesControl, ControlInputs};

use super::MissionArgs;

/// The longest line a program may answer, bytes (an answer is a few dozen).
const MAX_ANSWER: u64 = 4096;

/// Arguments of `karman sil`.
#[derive(Debug, Args)]
pub struct SilArgs {
    #[command(flatten)]
    pub mission: MissionArgs,
    /// Print the summary as JSON (as `karman simulate --json`).
    #[arg(long)]
    pub json: bool,
    /// Write summary.json, trajectory.csv, the sensors' readings, flight.kml and the plots
    /// into this directory (as `karman simulate --out`).
    #[arg(long, value_name = "DIR")]
    pub out: Option<std::path::PathBuf>,
    /// Seed of the parachute-trigger pressure noise.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Seconds the program may take to answer one call.
    #[arg(long, default_value_t = 10.0, value_name = "S")]
    pub timeout: f64,
    /// The program and its arguments (everything after `--exec`).
    #[arg(long, required = true, num_args = 1.., allow_hyphen_values = true, value_name = "PROGRAM")]
    pub exec: Vec<String>,
}

/// The outside program as the flight's air-brake controller.
struct Program {
    child: Child,
    input: Option<ChildStdin>,
    answers: Receiver<std::io::Result<String>>,
    timeout: Duration,
    header: Option<String>,
    line: String,
}

impl Program {
    /// Starts `command`, its output read line by line on a thread of its own.
    fn start(command: &[String], timeout: Duration, header: String) -> Result<Self> {
        let (program, arguments) = command.split_first().context("--exec names no program")?;
        let mut command = Command::new(program);
        // A process group of its own, so that what it starts (a shell's children) is killed
        // with it and holds none of karman's pipes open.
        #[cfg(unix)]
        std::os::unix::process::CommandExt::process_group(&mut command, 0);
        let mut child = command
            .args(arguments)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .with_context(|| format!("cannot run `{program}`"))?;
        let output = child.stdout.take().context("the program's output")?;
        let (send, answers) = channel();
        std::thread::spawn(move || {
            let mut reader = BufReader::new(output);
            loop {
                let mut line = String::new();
                let read = (&mut reader).take(MAX_ANSWER).read_line(&mut line);
                let end = matches!(read, Ok(0) | Err(_));
                if send.send(read.map(|_| line)).is_err() || end {
                    break;
                }
            }
        });
        Ok(Program {
            input: child.stdin.take(),
            child,
            answers,
            timeout,
            header: Some(header),
            line: String::with_capacity(512),
        })
    }

    /// Sends `line`, then reads the answer.
    fn exchange(&mut self) -> Result<String, String> {
        let gone = |what: &str| format!("the program {what} before answering");
        let input = self
            .input
            .as_mut()
            .ok_or_else(|| gone("closed its input"))?;
        if let Some(header) = self.header.take() {
            input
                .write_all(header.as_bytes())
                .map_err(|_| gone("exited"))?;
        }
        input
            .write_all(self.line.as_bytes())
            .and_then(|()| input.flush())
            .map_err(|_| gone("exited"))?;
        match self.answers.recv_timeout(self.timeout) {
            Ok(Ok(answer)) if answer.is_empty() => Err(gone("exited")),
            Ok(Ok(answer)) if !answer.ends_with('\n') => Err(format!(
                "the program's answer is longer than {MAX_ANSWER} bytes or has no end of line"
            )),
            Ok(Ok(answer)) => Ok(answer.trim_end().to_owned()),
            Ok(Err(e)) => Err(format!("cannot read the program's answer: {e}")),
            Err(RecvTimeoutError::Disconnected) => Err(gone("exited")),
            Err(RecvTimeoutError::Timeout) => Err(format!(
                "the program did not answer within {} s (--timeout)",
                self.timeout.as_secs_f64()
            )),
        }
    }

    /// Closes the program's input and waits for it to exit (killed after the timeout).
    fn finish(&mut self) {
        drop(self.input.take());
        let start = std::time::Instant::now();
        while start.elapsed() < self.timeout {
            if let Ok(Some(_)) = self.child.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(5));
        }
        self.kill();
    }

    /// Kills the program and its process group, and reaps it.
    fn kill(&mut self) {
        // The group is the child's own (set at spawn): POSIX `kill` signals it whole.
        #[cfg(unix)]
        let _ = Command::new("kill")
            .args(["-KILL", "--", &format!("-{}", self.child.id())])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status();
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Drop for Program {
    fn drop(&mut self) {
        if self.input.is_some() || matches!(self.child.try_wait(), Ok(None)) {
            self.kill();
        }
    }
}

/// Appends `value` to `line` in the protocol's number form.
fn number(line: &mut String, value: f64) {
    use std::fmt::Write as _;
    let _ = write!(line, " {value:e}");
}

impl AirBrakeController for Program {
    fn control(
        &mut self,
        inputs: &ControlInputs<'_>,
        air_brakes: &mut AirBrakesControl<'_>,
    ) -> Result<(), String> {
        self.line.clear();
        self.line.push_str("step");
        number(&mut self.line, inputs.time);
        for &v in inputs.state {
            number(&mut self.line, v);
        }
        number(&mut self.line, air_brakes.deployment_level());
        for reading in inputs.sensors {
            let (t, m) = reading.map_or((f64::NAN, [f64::NAN; 3]), |r| (r.time, r.measurement));
            number(&mut self.line, t);
            for v in m {
                number(&mut self.line, v);
            }
        }
        self.line.push('\n');
        let answer = self.exchange()?;
        let mut words = answer.split_whitespace();
        match (words.next(), words.next(), words.next()) {
            (Some("keep"), None, None) => Ok(()),
            (Some("level"), Some(v), None) => match v.parse::<f64>() {
                Ok(level) if level.is_finite() => {
                    air_brakes.set_deployment_level(level);
                    Ok(())
                }
                _ => Err(bad_answer(&answer)),
            },
            _ => Err(bad_answer(&answer)),
        }
    }
}

/// The error of an answer that is not a line of the protocol.
fn bad_answer(answer: &str) -> String {
    format!(
        "the program answered `{}`; expected `level VALUE` (a finite number) or `keep`",
        karman_mission::math::text::value(answer)
    )
}

/// Flies the mission with the program as its air-brake controller.
pub fn run(args: &SilArgs) -> Result<()> {
    if !(args.timeout.is_finite() && args.timeout > 0.0 && args.timeout <= 3600.0) {
        bail!(
            "--timeout {}: must be a number of seconds in (0, 3600]",
            args.timeout
        );
    }
    let mission = args.mission.load()?;
    if !mission.spec.stages.is_empty() {
        bail!(
            "{}: software in the loop flies single-stage rockets only (the mission has [[stages]])",
            mission.path.display()
        );
    }
    let Some(brakes) = &mission.spec.rocket.air_brakes else {
        bail!(
            "{}: the mission has no [rocket.air_brakes] for the program to drive",
            mission.path.display()
        );
    };
    let prepared = PreparedFlight::new(&mission)?;
    let rocket = prepared.rocket();
    let air_brakes = rocket.air_brakes().context("the rocket's air brakes")?;
    let mut header = format!("karman-sil 1 rate {:e}", brakes.sampling_rate);
    for (key, value) in [
        ("elevation", prepared.environment().elevation()),
        ("burn_out", rocket.burn_out()),
        ("reference_area", air_brakes.reference_area()),
    ] {
        header.push(' ');
        header.push_str(key);
        number(&mut header, value);
    }
    header.push_str(if air_brakes.clamp() {
        " clamp 1"
    } else {
        " clamp 0"
    });
    header.push_str(" level");
    number(&mut header, air_brakes.initial_level());
    let sensors = &mission.spec.rocket.sensors;
    header.push_str(&format!(" sensors {}", sensors.len()));
    for s in sensors {
        header.push_str(&format!(" {} {}", s.name, s.kind.as_str()));
    }
    header.push('\n');
    let mut program = Program::start(&args.exec, Duration::from_secs_f64(args.timeout), header)?;
    let flown = prepared.fly_with_controller(&mission, args.seed, &mut program);
    program.finish();
    let run = flown?;
    let summary = run.summary();
    super::print_warnings(&mission, &run.warnings);
    let mut out = std::io::stdout().lock();
    if args.json {
        let mut json = serde_json::to_value(&summary)?;
        json["warnings"] = serde_json::to_value(&run.warnings)?;
        writeln!(out, "{}", serde_json::to_string_pretty(&json)?)?;
    } else {
        writeln!(out, "{summary}")?;
    }
    if let Some(dir) = &args.out {
        let name = mission.spec.name.as_deref().unwrap_or("karman flight");
        super::simulate::write_whole(dir, |staging| {
            super::simulate::write_outputs(&run, name, args.seed, staging)
        })?;
    }
    match early_ending(summary.termination, &run.settings) {
        None => Ok(()),
        Some((_, message)) => bail!(message),
    }
}
