//! karman's flight of an imported design against the flight OpenRocket stored in it: the
//! figures of one simulation ([`OpenRocketComparison`] for a design of one axial stage,
//! [`StagedComparison`] for several), the acceptance they are held to (issue 20's and issue
//! 21's), and the designs and simulations excepted from it, with their reasons. Pure data:
//! the flight itself is karman-mission's (`report::openrocket::compare_folder`).

/// Designs karman refuses on purpose, by folder name, with the reason: their refusal is
/// reported and is not a miss. A listed design that imports is a miss (the entry is stale).
pub const KNOWN_REFUSALS: &[(&str, &str)] = &[];

/// Simulations of multi-stage designs whose apogee cannot match, by design and simulation,
/// with the reason: they are flown and reported, not held to [`STAGED_APOGEE`].
pub const STAGED_APOGEE_EXCEPTIONS: &[(&str, &str, &str)] = &[(
    "three_stage_low_power_rocket",
    "Simulation 3",
    "OpenRocket 24.12's motor-mass quirk (fixtures/openrocket/README.md): its three \
     identical C6 share one burn clock, so the two unlit ones lose their propellant with \
     the booster's and OpenRocket's stack is 0.021 kg (16 %) light at the first \
     separation; karman burns each motor on its own clock",
)];

/// Acceptance (issue 20): apogee 5 %, maximum speed 3 %, total Cd 10 % below Mach 0.8 and
/// 15 % above, CP 1 % of the body length, stability margin 0.1 caliber.
pub const APOGEE: f64 = 0.05;
/// See [`APOGEE`].
pub const MAX_SPEED: f64 = 0.03;
/// See [`APOGEE`].
pub const CD_SUBSONIC: f64 = 0.10;
/// See [`APOGEE`].
pub const CD_TRANSONIC: f64 = 0.15;
/// See [`APOGEE`].
pub const CP_FRACTION: f64 = 0.01;
/// See [`APOGEE`].
pub const MARGIN_CALIBERS: f64 = 0.1;

/// The figures of one simulation.
#[derive(Debug, Clone, PartialEq)]
pub struct OpenRocketComparison {
    /// The simulation's name.
    pub simulation: String,
    /// karman's apogee above the site (m) and OpenRocket's (`maxaltitude`; both deploy the
    /// parachutes as OpenRocket does, a short ejection delay before apogee included).
    pub apogee: (f64, f64),
    /// Maximum speed (m/s), karman and OpenRocket.
    pub max_speed: (f64, f64),
    /// Flight time to the ground hit (s), karman and OpenRocket (`flighttime`).
    pub flight_time: (f64, f64),
    /// Speed at the ground hit (m/s), karman and OpenRocket (`groundhitvelocity`).
    pub landing_speed: (f64, f64),
    /// Worst relative error of the total Cd over the ascent rows below Mach 0.8.
    pub cd_subsonic: f64,
    /// Worst relative error of the total Cd at or above Mach 0.8 (`NaN` without such rows).
    pub cd_transonic: f64,
    /// Centre of pressure from the nose tip (m) at the compared row: karman's estimate at
    /// OpenRocket's angle of attack and Mach there (karman-mission's `AngleStability`), and
    /// OpenRocket's.
    pub cp: (f64, f64),
    /// Body length (m), the scale of the CP error.
    pub body_length: f64,
    /// Stability margin (calibers), karman and OpenRocket, at the compared row.
    pub margin: (f64, f64),
    /// Time of the compared row (s): rod exit, OpenRocket's first stored CP.
    pub cp_time: f64,
    /// OpenRocket's angle of attack at that row (rad), at which both CPs are taken.
    pub cp_alpha: f64,
    /// The flow's roll angle there (rad), OpenRocket's (`rod_exit_roll`).
    pub cp_roll: f64,
}

impl OpenRocketComparison {
    /// Relative apogee error.
    #[must_use]
    pub fn apogee_error(&self) -> f64 {
        (self.apogee.0 - self.apogee.1).abs() / self.apogee.1
    }

    /// Relative maximum-speed error.
    #[must_use]
    pub fn max_speed_error(&self) -> f64 {
        (self.max_speed.0 - self.max_speed.1).abs() / self.max_speed.1
    }

    /// CP error as a fraction of the body length.
    #[must_use]
    pub fn cp_error(&self) -> f64 {
        (self.cp.0 - self.cp.1).abs() / self.body_length
    }

    /// Stability-margin error, calibers.
    #[must_use]
    pub fn margin_error(&self) -> f64 {
        (self.margin.0 - self.margin.1).abs()
    }
}

impl OpenRocketComparison {
    /// The acceptance criteria this simulation misses.
    #[must_use]
    pub fn failures(&self) -> Vec<String> {
        let mut out = Vec::new();
        let mut check = |what: &str, error: f64, limit: f64| {
            let within = error <= limit; // false for NaN
            if !within {
                out.push(format!("{what} {error:.4} > {limit}"));
            }
        };
        check("apogee", self.apogee_error(), APOGEE);
        check("max speed", self.max_speed_error(), MAX_SPEED);
        check("Cd below Mach 0.8", self.cd_subsonic, CD_SUBSONIC);
        if self.cd_transonic.is_finite() {
            check("Cd above Mach 0.8", self.cd_transonic, CD_TRANSONIC);
        }
        check("CP / body length", self.cp_error(), CP_FRACTION);
        check("margin (cal)", self.margin_error(), MARGIN_CALIBERS);
        out
    }
}

impl std::fmt::Display for OpenRocketComparison {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{:<28} apogee {:8.1} / {:8.1} m ({:5.2} %)  vmax {:6.1} / {:6.1} m/s ({:5.2} %)  Cd <M0.8 {:5.1} %  ≥M0.8 {:5.1} %  CP {:.4} / {:.4} m ({:.2} % of L)  margin {:.2} / {:.2} cal (rod exit, α {:.1}°, roll {:.0}°)  landing {:6.1} / {:6.1} s, {:4.2} / {:4.2} m/s",
            self.simulation,
            self.apogee.0,
            self.apogee.1,
            100.0 * self.apogee_error(),
            self.max_speed.0,
            self.max_speed.1,
            100.0 * self.max_speed_error(),
            100.0 * self.cd_subsonic,
            100.0 * self.cd_transonic,
            self.cp.0,
            self.cp.1,
            100.0 * self.cp_error(),
            self.margin.0,
            self.margin.1,
            self.cp_alpha.to_degrees(),
            self.cp_roll.to_degrees(),
            self.flight_time.0,
            self.flight_time.1,
            self.landing_speed.0,
            self.landing_speed.1,
        )
    }
}

/// Why a design, or one of its stored simulations, was not compared.
#[derive(Debug, Clone, PartialEq)]
pub enum Problem {
    /// karman's import refused it: the import's error (file, component, what).
    Refused(String),
    /// Its folder could not be read, or the imported mission did not fly: the error.
    Failed(String),
    /// Not compared, and not a miss: why (a flight altered by simulation extensions).
    Skipped(String),
}

impl std::fmt::Display for Problem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Problem::Refused(m) => write!(f, "refused: {m}"),
            Problem::Failed(m) => write!(f, "failed: {m}"),
            Problem::Skipped(m) => write!(f, "not compared: {m}"),
        }
    }
}

/// One stored simulation: its name and its comparison, or why there is none.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulationResult<T> {
    /// The simulation's name.
    pub simulation: String,
    /// The comparison.
    pub outcome: Result<T, Problem>,
}

/// Acceptance (issue 21): the top stage's apogee and every separation time within 3 %.
pub const STAGED_APOGEE: f64 = 0.03;
/// See [`STAGED_APOGEE`].
pub const SEPARATION_TIME: f64 = 0.03;

/// The figures of one simulation of a multi-stage design.
#[derive(Debug, Clone, PartialEq)]
pub struct StagedComparison {
    /// The simulation's name.
    pub simulation: String,
    /// The top stage's apogee above the site (m), karman and OpenRocket (`maxaltitude`; both
    /// deploy the parachutes as OpenRocket does).
    pub apogee: (f64, f64),
    /// Maximum speed of the top stage's path (m/s), karman and OpenRocket.
    pub max_speed: (f64, f64),
    /// karman's separation times (s), in time order.
    pub separations: Vec<f64>,
    /// OpenRocket's stage-separation events of the main branch up to the top stage's apogee
    /// (s), in time order.
    pub reference_separations: Vec<f64>,
    /// The mission flies the stack as one body (a stage without a motor rides on the one
    /// below): no separation is flown.
    pub one_body: bool,
    /// Worst relative error of the total Cd against OpenRocket's ascent rows after rod exit,
    /// per vehicle of the top stage's path (the launch stack first, the top stage alone
    /// last; one body: up to OpenRocket's first separation).
    pub cd: Vec<f64>,
}

impl StagedComparison {
    /// Relative apogee error.
    #[must_use]
    pub fn apogee_error(&self) -> f64 {
        (self.apogee.0 - self.apogee.1).abs() / self.apogee.1
    }

    /// Relative maximum-speed error.
    #[must_use]
    pub fn max_speed_error(&self) -> f64 {
        (self.max_speed.0 - self.max_speed.1).abs() / self.max_speed.1
    }

    /// Relative error of each separation time.
    #[must_use]
    pub fn separation_errors(&self) -> Vec<f64> {
        self.separations
            .iter()
            .zip(&self.reference_separations)
            .map(|(k, o)| (k - o).abs() / o)
            .collect()
    }

    /// The acceptance criteria this simulation misses; the apogee's only when `check_apogee`
    /// (see [`STAGED_APOGEE_EXCEPTIONS`]).
    #[must_use]
    pub fn failures(&self, check_apogee: bool) -> Vec<String> {
        let mut out = Vec::new();
        let error = self.apogee_error();
        let within = error <= STAGED_APOGEE; // false for NaN
        if check_apogee && !within {
            out.push(format!("apogee {error:.4} > {STAGED_APOGEE}"));
        }
        if !self.one_body && self.separations.len() != self.reference_separations.len() {
            out.push(format!(
                "{} separations flown, OpenRocket has {}",
                self.separations.len(),
                self.reference_separations.len()
            ));
        }
        for (i, e) in self.separation_errors().into_iter().enumerate() {
            let within = e <= SEPARATION_TIME; // false for NaN
            if !within {
                out.push(format!(
                    "separation {} time {e:.4} > {SEPARATION_TIME}",
                    i + 1
                ));
            }
        }
        out
    }
}

impl std::fmt::Display for StagedComparison {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{:<28} apogee {:8.1} / {:8.1} m ({:5.2} %)  vmax {:6.1} / {:6.1} m/s ({:5.2} %) ",
            self.simulation,
            self.apogee.0,
            self.apogee.1,
            100.0 * self.apogee_error(),
            self.max_speed.0,
            self.max_speed.1,
            100.0 * self.max_speed_error(),
        )?;
        let cd: Vec<String> = self
            .cd
            .iter()
            .map(|e| format!("{:.1}", 100.0 * e))
            .collect();
        write!(f, " Cd {} %;", cd.join(" / "))?;
        if self.one_body {
            let times: Vec<String> = self
                .reference_separations
                .iter()
                .map(|t| format!("{t:.3}"))
                .collect();
            return write!(
                f,
                " separation not flown (one body; OpenRocket: {} s)",
                times.join(", ")
            );
        }
        write!(f, " separations")?;
        for ((k, o), e) in self
            .separations
            .iter()
            .zip(&self.reference_separations)
            .zip(self.separation_errors())
        {
            write!(f, " {k:.3} / {o:.3} s ({:.2} %)", 100.0 * e)?;
        }
        Ok(())
    }
}

/// The comparisons of one design, by the number of its axial stages.
#[derive(Debug, Clone, PartialEq)]
pub enum Compared {
    /// One stage: issue 20's acceptance.
    Single(Vec<SimulationResult<OpenRocketComparison>>),
    /// Several: issue 21's.
    Staged(Vec<SimulationResult<StagedComparison>>),
}

/// One design folder compared with OpenRocket (karman-mission's `report::openrocket::compare`).
#[derive(Debug, Clone, PartialEq)]
pub struct DesignResult {
    /// The folder's name.
    pub design: String,
    /// Its simulations, or why none was compared (the design refused, its files unreadable).
    pub outcome: Result<Compared, Problem>,
}

/// The reason given for `design` in [`KNOWN_REFUSALS`].
#[must_use]
pub fn known_refusal(design: &str) -> Option<&'static str> {
    KNOWN_REFUSALS
        .iter()
        .find(|(name, _)| *name == design)
        .map(|(_, why)| *why)
}

/// The reason given for `simulation` of `design` in [`STAGED_APOGEE_EXCEPTIONS`].
#[must_use]
pub fn staged_apogee_exception(design: &str, simulation: &str) -> Option<&'static str> {
    STAGED_APOGEE_EXCEPTIONS
        .iter()
        .find(|(d, s, _)| *d == design && *s == simulation)
        .map(|(_, _, why)| *why)
}

impl DesignResult {
    /// The acceptance criteria the design misses, each prefixed with the design and the
    /// simulation: a refusal counts unless the design is a [`known_refusal`], and a known
    /// refusal that imports counts too (its entry is stale).
    #[must_use]
    pub fn failures(&self) -> Vec<String> {
        let known = known_refusal(&self.design);
        let mut out = Vec::new();
        let mut refused = false;
        let mut problem = |at: String, p: &Problem, out: &mut Vec<String>| match p {
            Problem::Refused(_) => {
                refused = true;
                if known.is_none() {
                    out.push(format!("{at}: {p}"));
                }
            }
            Problem::Failed(_) => out.push(format!("{at}: {p}")),
            Problem::Skipped(_) => {}
        };
        match &self.outcome {
            Err(p) => problem(self.design.clone(), p, &mut out),
            Ok(Compared::Single(sims)) => {
                for sim in sims {
                    let at = format!("{} {}", self.design, sim.simulation);
                    match &sim.outcome {
                        Ok(r) => out.extend(r.failures().into_iter().map(|m| format!("{at}: {m}"))),
                        Err(p) => problem(at, p, &mut out),
                    }
                }
            }
            Ok(Compared::Staged(sims)) => {
                for sim in sims {
                    let at = format!("{} {}", self.design, sim.simulation);
                    match &sim.outcome {
                        Ok(r) => {
                            let check_apogee =
                                staged_apogee_exception(&self.design, &sim.simulation).is_none();
                            out.extend(
                                r.failures(check_apogee)
                                    .into_iter()
                                    .map(|m| format!("{at}: {m}")),
                            );
                        }
                        Err(p) => problem(at, p, &mut out),
                    }
                }
            }
        }
        if known.is_some() && !refused {
            out.push(format!(
                "{}: listed in KNOWN_REFUSALS but imported: remove the entry",
                self.design
            ));
        }
        out
    }
}

impl std::fmt::Display for DesignResult {
    /// One line per simulation, each starting with the design's name; a known refusal or a
    /// staged apogee exception adds a line with its reason.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let design = &self.design;
        let note = |f: &mut std::fmt::Formatter<'_>, p: &Problem| -> std::fmt::Result {
            if let (Problem::Refused(_), Some(why)) = (p, known_refusal(design)) {
                writeln!(f, "{:<28} (a known refusal: {why})", "")?;
            }
            Ok(())
        };
        match &self.outcome {
            Err(p) => {
                writeln!(f, "{design:<28} {p}")?;
                note(f, p)?;
            }
            Ok(Compared::Single(sims)) => {
                for sim in sims {
                    match &sim.outcome {
                        Ok(r) => writeln!(f, "{design:<28} {r}")?,
                        Err(p) => {
                            writeln!(f, "{design:<28} {:<28} {p}", sim.simulation)?;
                            note(f, p)?;
                        }
                    }
                }
            }
            Ok(Compared::Staged(sims)) => {
                for sim in sims {
                    match &sim.outcome {
                        Ok(r) => {
                            writeln!(f, "{design:<28} {r}")?;
                            if let Some(why) = staged_apogee_exception(design, &sim.simulation) {
                                writeln!(f, "{:<28} (apogee not held to 3 %: {why})", "")?;
                            }
                        }
                        Err(p) => {
                            writeln!(f, "{design:<28} {:<28} {p}", sim.simulation)?;
                            note(f, p)?;
                        }
                    }
                }
            }
        }
        Ok(())
    }
}
