//! The generator of the hostile-input suite: hand-made cases of every class the audits of
//! issue 33 found, and seeded random mutations (cuts, deleted lines, replaced bytes and
//! values) of valid inputs. A fixed seed per class: every run writes the same files.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

/// What a case must do.
pub enum Expect {
    /// Exit 0, or exit 1 naming every string.
    Either(Vec<String>),
    /// The case is a `check`: exit 1 naming every string, or exit 0 and then the command
    /// given (the flight) exits 0.
    Flies(Vec<String>, Vec<String>),
    /// The case is an `import`: exit 1 naming every string, or exit 0 and then the command
    /// given (`check` of the imported mission) does not crash; with line prefixes given, no
    /// line of the mission starts with one and the check passes.
    Imports(Vec<String>, Vec<String>, Vec<String>),
}

/// One run of the binary and what it must do.
pub struct Case {
    /// What the case tries.
    pub name: String,
    /// The arguments of the run.
    pub args: Vec<String>,
    /// What it must do.
    pub expect: Expect,
}

/// SplitMix64: a small seeded generator (the cases must not depend on a crate's stream).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n` (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }

    pub fn bytes(&mut self, n: usize) -> Vec<u8> {
        (0..n).map(|_| self.next() as u8).collect()
    }
}

fn s(text: &str) -> String {
    text.to_owned()
}

fn path_arg(path: &Path) -> String {
    path.to_str().expect("UTF-8 path").to_owned()
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .and_then(|n| n.to_str())
        .expect("file name")
        .to_owned()
}

fn write(path: &Path, bytes: impl AsRef<[u8]>) -> PathBuf {
    std::fs::write(path, bytes).expect("write a case file");
    path.to_path_buf()
}

/// `text` as a TOML basic string, every control character escaped.
pub fn toml_string(text: &str) -> String {
    let mut out = String::from("\"");
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

fn repository(path: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path)
}

fn corpus(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/corpus")
        .join(name)
}

/// The bad-input corpus's mission with its data files, copied into `dir`; its text.
fn corpus_mission(dir: &Path) -> (PathBuf, String) {
    for name in ["thrust.eng", "power_off_drag.csv", "power_on_drag.csv"] {
        std::fs::copy(corpus(name), dir.join(name)).expect("corpus data file");
    }
    let text = std::fs::read_to_string(corpus("mission.toml")).expect("corpus mission");
    (write(&dir.join("base.toml"), &text), text)
}

/// The repository's example mission and its data files, copied into `dir` (a study's
/// mission).
pub fn example_mission(dir: &Path) -> PathBuf {
    for name in [
        "example_K1960.eng",
        "power_off_drag.csv",
        "power_on_drag.csv",
    ] {
        std::fs::copy(repository(&format!("fixtures/{name}")), dir.join(name))
            .expect("example data file");
    }
    let text = std::fs::read_to_string(repository("fixtures/example.toml")).expect("example");
    write(&dir.join("example.toml"), text)
}

/// `check MISSION --set...`, then (when it passes) `simulate` of the same.
fn flies(name: &str, mission: &Path, sets: &[String], located: Vec<String>) -> Case {
    let mut args = vec![s("check"), path_arg(mission)];
    for set in sets {
        args.push(s("--set"));
        args.push(set.clone());
    }
    let mut fly = args.clone();
    fly[0] = s("simulate");
    Case {
        name: name.to_owned(),
        args,
        expect: Expect::Flies(located, fly),
    }
}

/// A mission text written to `dir/NAME.toml` and flown as [`flies`], its file named in
/// every refusal (and `key` when given).
fn mission_case(dir: &Path, index: usize, name: &str, text: &[u8], key: Option<&str>) -> Case {
    let path = write(&dir.join(format!("m{index:03}.toml")), text);
    let mut located = vec![file_name(&path)];
    located.extend(key.map(str::to_owned));
    flies(name, &path, &[], located)
}

/// The line of `text` setting `key` (`key = ...` at the start of a line) replaced by `line`.
fn replace_line(text: &str, key: &str, line: &str) -> String {
    let prefix = format!("{key} =");
    let mut done = false;
    let out: Vec<String> = text
        .lines()
        .map(|l| {
            if !done && l.starts_with(&prefix) {
                done = true;
                line.to_owned()
            } else {
                l.to_owned()
            }
        })
        .collect();
    assert!(done, "the base mission sets {key}");
    out.join("\n") + "\n"
}

/// Numbers that break naive readers.
const HOSTILE_NUMBERS: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "-1",
    "0",
    "-0.0",
    "1e308",
    "-1e308",
    "1e-308",
    "5e-324",
    "99999999999999999999",
    "1e400",
    "0x7fffffffffffffff",
];

/// Hostile missions: unreadable files, nesting and number limits of the TOML reader,
/// impossible and huge values, odd names, and seeded cuts and edits of a valid mission.
pub fn missions(dir: &Path) -> Vec<Case> {
    let (base_path, base) = corpus_mission(dir);
    let mut cases = Vec::new();
    let mut push = |name: &str, text: Vec<u8>, key: Option<&str>| {
        let index = cases.len();
        cases.push(mission_case(dir, index, name, &text, key));
    };
    push("empty file", Vec::new(), None);
    push("NUL bytes", vec![0; 4096], None);
    push(
        "UTF-16",
        {
            let mut b = vec![0xFF, 0xFE];
            b.extend(base.encode_utf16().flat_map(u16::to_le_bytes));
            b
        },
        None,
    );
    push(
        "invalid UTF-8",
        {
            let mut b = base.clone().into_bytes();
            b.splice(200..200, [0xC3, 0x28, 0xFF]);
            b
        },
        None,
    );
    let depth = 50_000;
    push(
        "deep arrays",
        format!("x = {}{}\n", "[".repeat(depth), "]".repeat(depth)).into_bytes(),
        None,
    );
    push(
        "deep inline tables",
        format!("x = {}1{}\n", "{a=".repeat(depth), "}".repeat(depth)).into_bytes(),
        None,
    );
    push(
        "deep dotted key",
        format!("x{} = 1\n", ".a".repeat(depth)).into_bytes(),
        None,
    );
    push(
        "deep table header",
        format!("[{}]\n", vec!["a"; depth].join(".")).into_bytes(),
        None,
    );
    let number_cases: &[(&str, &str, &str)] = &[
        ("mass", "rocket.mass", "mass = 1e400"),
        ("mass", "rocket.mass", "mass = nan"),
        ("mass", "rocket.mass", "mass = -2.6"),
        ("mass", "rocket.mass", "mass = \"heavy\""),
        ("radius", "rocket.radius", "radius = inf"),
        ("radius", "rocket.radius", "radius = -0.0285"),
        ("radius", "rocket.radius", "radius = 0"),
        ("n", "rocket.surfaces.fins.n", "n = 0"),
        ("n", "rocket.surfaces.fins.n", "n = -3"),
        ("n", "rocket.surfaces.fins.n", "n = 1000000000"),
        ("length", "rocket.surfaces.nose.length", "length = -0.35"),
        ("rail_length", "flight.rail_length", "rail_length = 1e300"),
        ("rail_length", "flight.rail_length", "rail_length = -3"),
        ("inclination", "flight.inclination", "inclination = 1000"),
        ("latitude", "environment.latitude", "latitude = 1000"),
        ("elevation", "environment.elevation", "elevation = 1e12"),
        ("dry_mass", "motor.dry_mass", "dry_mass = -1"),
        (
            "grain_number",
            "motor.grain_number",
            "grain_number = 1000000000000",
        ),
        (
            "grain_outer_radius",
            "below grain_outer_radius",
            "grain_outer_radius = 0.001",
        ),
        ("throat_radius", "motor.throat_radius", "throat_radius = 1"),
        ("inertia", "rocket.inertia", "inertia = [0.7, 0.7]"),
        ("inertia", "rocket.inertia", "inertia = [nan, 0.7, 0.0021]"),
        ("date", "environment.date", "date = \"yesterday\""),
        ("kind", "motor.kind", "kind = \"nuclear\""),
        // Beyond any input: refused at the key, not as an infinity inside a model.
        (
            "grain_separation",
            "motor.grain_separation",
            "grain_separation = 1e300",
        ),
        (
            "center_of_mass_without_motor",
            "rocket.center_of_mass_without_motor",
            "center_of_mass_without_motor = -1e300",
        ),
        (
            "grain_density",
            "motor.grain_density",
            "grain_density = 1e300",
        ),
    ];
    for (key, full, line) in number_cases {
        let text = replace_line(&base, key, line);
        push(&format!("value {line}"), text.into_bytes(), Some(full));
    }
    // Eccentricities: beyond the body, non-finite, the wrong shape, the centre of mass with
    // another, absurdly large; each refused at its key.
    let eccentricities: &[(&str, &str)] = &[
        (
            "thrust_eccentricity = [1.0, 0.0]",
            "rocket.thrust_eccentricity",
        ),
        ("cp_eccentricity = [nan, 0.0]", "rocket.cp_eccentricity"),
        (
            "cm_eccentricity = [1e300, -1e300]",
            "rocket.cm_eccentricity",
        ),
        (
            "thrust_eccentricity = [0.001]",
            "rocket.thrust_eccentricity",
        ),
        ("cp_eccentricity = \"off\"", "rocket.cp_eccentricity"),
        (
            "cm_eccentricity = [0.001, 0.0]\ncp_eccentricity = [0.001, 0.0]",
            "rocket.cp_eccentricity",
        ),
    ];
    for (line, key) in eccentricities {
        let text = replace_line(&base, "mass", &format!("mass = 2.6\n{line}"));
        push(
            &format!("eccentricity {line}"),
            text.into_bytes(),
            Some(key),
        );
    }
    let huge = "9".repeat(100_000);
    push(
        "100,000-digit mass",
        replace_line(&base, "mass", &format!("mass = {huge}")).into_bytes(),
        Some("rocket.mass"),
    );
    push(
        "100,000-digit float mass",
        replace_line(&base, "mass", &format!("mass = 1.{huge}")).into_bytes(),
        Some("rocket.mass"),
    );
    push(
        "parachute sampling rate 1e10",
        base.replacen("sampling_rate = 105", "sampling_rate = 1e10", 1)
            .into_bytes(),
        Some("sampling_rate"),
    );
    push(
        "parachute lag 1e300",
        base.replacen("lag = 1.0", "lag = 1e300", 1).into_bytes(),
        None,
    );
    push(
        "parachute noise huge",
        base.replacen("noise = [0, 8.3, 0.5]", "noise = [0, 1e300, 1e300]", 1)
            .into_bytes(),
        None,
    );
    for (i, name) in [
        "a\nb = 1",
        "\"quoted\" # and [tables]",
        "\u{1}\u{1b}[31mred\u{7f}",
        "\u{202e}reversed",
        &"long name ".repeat(10_000),
    ]
    .iter()
    .enumerate()
    {
        let text = replace_line(&base, "name", &format!("name = {}", toml_string(name)));
        push(&format!("odd name {i}"), text.into_bytes(), None);
    }
    push(
        "duplicate key",
        base.replacen("mass = 2.6", "mass = 2.6\nmass = 2.7", 1)
            .into_bytes(),
        Some(":"),
    );
    push(
        "duplicate table",
        format!("{base}\n[rocket]\nmass = 1\n").into_bytes(),
        Some(":"),
    );
    push(
        "unknown key of 100,000 characters",
        format!("{}\n{} = 1\n", base, "k".repeat(100_000)).into_bytes(),
        None,
    );
    push(
        "unknown surface type",
        format!("{base}\n[rocket.surfaces.x]\ntype = \"warp\"\nposition = 0\n").into_bytes(),
        Some("rocket.surfaces.x"),
    );
    push(
        "rail buttons 1e300 m away",
        replace_line(&base, "upper_position", "upper_position = 1e300").into_bytes(),
        Some("rocket.rail_buttons.upper_position"),
    );
    push(
        "array of 1,000,000 numbers",
        replace_line(
            &base,
            "inertia",
            &format!("inertia = [{}]", vec!["0.7"; 1_000_000].join(",")),
        )
        .into_bytes(),
        Some("rocket.inertia"),
    );
    // Sensors, and triggers reading them: each flies, or is refused naming the key.
    let baro = "\n[[rocket.sensors]]\nkind = \"barometer\"\nname = \"baro\"\nsampling_rate = 100\nposition = 0\n";
    let sensor_cases: &[(&str, &str, &str, Option<&str>)] = &[
        (
            "a barometer read by the drogue's trigger",
            baro,
            "trigger = { expression = \"sensors.baro > 80000.0 && vz < 0.0\" }",
            None,
        ),
        (
            "a trigger reading a sensor past the list",
            baro,
            "trigger = { expression = \"sensors[1] < 1.0\" }",
            Some("rocket.parachutes.drogue.trigger"),
        ),
        (
            "a trigger reading a component of a barometer",
            baro,
            "trigger = { expression = \"sensors[0][0] < 1.0\" }",
            Some("rocket.parachutes.drogue.trigger"),
        ),
        (
            "a trigger reading an unknown sensor",
            baro,
            "trigger = { expression = \"sensors.gps[2] < 1.0\" }",
            Some("rocket.parachutes.drogue.trigger"),
        ),
        (
            "a barometer of enormous noise",
            "\n[[rocket.sensors]]\nkind = \"barometer\"\nname = \"baro\"\nsampling_rate = 100\nposition = 0\nnoise_density = 1e308\nrandom_walk_density = 1e308\n",
            "trigger = { expression = \"sensors.baro > 80000.0 && vz < 0.0\" }",
            None,
        ),
        (
            "a sensor rate of 1e10",
            "\n[[rocket.sensors]]\nkind = \"gyroscope\"\nname = \"w\"\nsampling_rate = 1e10\nposition = 0\n",
            "trigger = 300",
            Some("rocket.sensors.0.sampling_rate"),
        ),
        (
            "a sensor far outside the rocket",
            "\n[[rocket.sensors]]\nkind = \"gnss\"\nname = \"g\"\nsampling_rate = 1\nposition = [1e308, 0, 0]\n",
            "trigger = 300",
            Some("rocket.sensors.0.position"),
        ),
        (
            "a sensor range of NaN",
            "\n[[rocket.sensors]]\nkind = \"accelerometer\"\nname = \"a\"\nsampling_rate = 100\nposition = 0\nmeasurement_range = [nan, 1]\n",
            "trigger = 300",
            Some("measurement_range"),
        ),
        (
            "a sensor named by 10,000 characters",
            &format!(
                "\n[[rocket.sensors]]\nkind = \"barometer\"\nname = \"{}\"\nsampling_rate = 10\nposition = 0\n",
                "b".repeat(10_000)
            ),
            "trigger = 300",
            None,
        ),
    ];
    for (name, sensors, trigger, key) in sensor_cases {
        let text = replace_line(&base, "trigger", trigger) + *sensors;
        push(name, text.into_bytes(), *key);
    }

    let mut rng = Rng::new(0x6D15_5104);
    for i in 0..25 {
        let cut = rng.below(base.len());
        push(
            &format!("cut at byte {cut} ({i})"),
            base.as_bytes()[..cut].to_vec(),
            None,
        );
    }
    let lines: Vec<&str> = base.lines().collect();
    for i in 0..20 {
        let drop = rng.below(lines.len());
        let text: Vec<&str> = lines
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != drop)
            .map(|(_, l)| *l)
            .collect();
        push(
            &format!("line {} deleted ({i})", drop + 1),
            (text.join("\n") + "\n").into_bytes(),
            None,
        );
    }
    let alphabet = b"[]{}=\"'#\\\n\r\t\0,.-+eE9";
    for i in 0..20 {
        let mut bytes = base.clone().into_bytes();
        let at = rng.below(bytes.len());
        bytes[at] = *rng.pick(alphabet);
        push(&format!("byte {at} replaced ({i})"), bytes, None);
    }
    let numeric: Vec<usize> = lines
        .iter()
        .enumerate()
        .filter(|(_, l)| {
            l.split('=')
                .nth(1)
                .is_some_and(|v| v.trim().starts_with(|c: char| c.is_ascii_digit()))
        })
        .map(|(i, _)| i)
        .collect();
    for i in 0..25 {
        let at = *rng.pick(&numeric);
        let key = lines[at].split('=').next().unwrap_or_default().trim();
        let value = rng.pick(HOSTILE_NUMBERS);
        let mut edited: Vec<String> = lines.iter().map(|l| (*l).to_owned()).collect();
        edited[at] = format!("{key} = {value}");
        push(
            &format!("{key} = {value} ({i})"),
            (edited.join("\n") + "\n").into_bytes(),
            None,
        );
    }
    // A sounding of impossible winds (a million knots): the file is named, as it is wrong.
    let rule = "-".repeat(77);
    let row =
        |p: u32, z: u32| format!(" {p}.0  {z}  10.0  5.0  50  5  90  1000000  290  300  291\n");
    let sounding = write(
        &dir.join("winds.txt"),
        format!(
            "{rule}\n   PRES   HGHT   TEMP   DWPT   RELH   MIXR   DRCT   SKNT   THTA   THTE   THTV\n    hPa     m      C      C      %    g/kg    deg   knot     K      K      K \n{rule}\n{}{}{}",
            row(1000, 100),
            row(900, 2000),
            row(800, 3000)
        ),
    );
    cases.push(flies(
        "sounding of a million knots",
        &base_path,
        &[format!(
            "environment.atmosphere={{ model = \"sounding\", file = {}, format = \"wyoming\" }}",
            toml_string(&path_arg(&sounding))
        )],
        vec![s("winds.txt"), s("environment.atmosphere.file")],
    ));
    // Tolerances no flight can be integrated with: refused by `check`, not by the flight.
    for atol in ["1e-300", "[1e-30, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1]"] {
        cases.push(flies(
            &format!("atol = {atol}"),
            &base_path,
            &[format!("flight.atol={atol}")],
            vec![s("flight.atol")],
        ));
    }
    cases
}

/// Hostile trigger expressions of the main parachute (`--set`): nesting, long chains, huge
/// literals, unknown names, control characters, and seeded random token strings.
pub fn triggers(dir: &Path) -> Vec<Case> {
    let (mission, _) = corpus_mission(dir);
    let key = s("rocket.parachutes.main.trigger");
    let mut expressions: Vec<String> = vec![
        format!("{}h{} > 1.0", "(".repeat(5000), ")".repeat(5000)),
        format!("{}h > 1.0", "-".repeat(50_000)),
        format!("{}true", "!".repeat(50_000)),
        format!("{} > 1.0", vec!["h"; 20_000].join(" + ")),
        format!("{} > 1.0", vec!["h"; 20_000].join(" * ")),
        s("h > 1e999"),
        s("h > 1e-999"),
        format!("h > 1.{}", "9".repeat(50_000)),
        s("h > 1"),
        s("nan > 1.0"),
        s("foo(h) > 1.0"),
        s("sqrt(h, h) > 1.0"),
        s("sqrt(-1.0) > 0.0"),
        s("vz / 0.0 > 1.0"),
        s("h < 1.0 < 2.0"),
        s("h > 1.0 &&"),
        s("(((("),
        s(""),
        s("\"text\" > 1.0"),
        s("h > 1.0\u{0}"),
        s("h\n> 1.0"),
        s("h > 1.0 # comment"),
        s("h ＞ 1.0"),
        s("vz < 0.0 && h < 300.0"),
        // Sensor readings (the mission has no sensors: each a located refusal).
        s("sensors[0] < 1.0"),
        s("sensors.baro < 1.0"),
        s("sensors[0].measurement[2] < 1.0"),
        s("sensors[99999999999999999999999] < 1.0"),
        s("sensors[-1] < 1.0"),
        s("sensors[0.5] < 1.0"),
        s("sensors[0][0][0] < 1.0"),
        s("sensors. < 1.0"),
        s("sensors[ < 1.0"),
        s("sensors < 1.0"),
        format!("sensors.{} < 1.0", "x".repeat(50_000)),
        format!("{}sensors[0]{} > 1.0", "(".repeat(60), ")".repeat(60)),
    ];
    let tokens = [
        "h", "vz", "p", "(", ")", "+", "-", "*", "/", ">", "<", "&&", "||", "!", "1.0", "0.0",
        "1e308", "sqrt(", "abs(", ",", " ", "true", "==", "sensors", "[", "]", ".", "0",
    ];
    let mut rng = Rng::new(0x7219_6E55);
    for _ in 0..40 {
        let n = 1 + rng.below(30);
        expressions.push((0..n).map(|_| *rng.pick(&tokens)).collect());
    }
    expressions
        .iter()
        .enumerate()
        .map(|(i, e)| {
            let set = format!("{key}={{ expression = {} }}", toml_string(e));
            let shown: String = e.chars().take(40).collect();
            flies(
                &format!("trigger {i} `{shown}`"),
                &mission,
                &[set],
                vec![key.clone()],
            )
        })
        .collect()
}

const SIGNATURE: &str = "fn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes)";

/// Hostile controller scripts on the air-brakes example: syntax and signature errors, run-time
/// type errors of the first call, runaway loops, recursion, memory, sandbox escapes, and seeded
/// cuts of the example's controller.
pub fn scripts(dir: &Path) -> Vec<Case> {
    let mission = repository("fixtures/airbrakes/calisto_docs.toml");
    let body = |b: &str| format!("{SIGNATURE} {{\n    {b}\n}}\n");
    let mut sources: Vec<(String, Vec<u8>)> = vec![
        (s("empty"), Vec::new()),
        (s("binary"), Rng::new(3).bytes(2000)),
        (s("NUL"), vec![0; 100]),
        (s("invalid UTF-8"), b"fn controller_function(\xff\xfe)".to_vec()),
        (s("no function"), b"let x = 1;\n".to_vec()),
        (s("one parameter"), b"fn controller_function(a) { }\n".to_vec()),
        (s("nine parameters"), b"fn controller_function(a, b, c, d, e, f, g, h, i) { }\n".to_vec()),
        (s("syntax error"), body("let = ;").into_bytes()),
        (s("method on a number"), body("time.foo();").into_bytes()),
        (s("unknown air-brake property"), body("let x = air_brakes.nonexistent;").into_bytes()),
        (s("state index out of range"), body("let x = state[100];").into_bytes()),
        (s("level set to a string"), body("air_brakes.deployment_level = \"open\";").into_bytes()),
        (s("throw"), body("throw \"boom\";").into_bytes()),
        (s("endless loop"), body("loop { }").into_bytes()),
        (s("endless sort comparator"), body("let a = [3, 1, 2]; a.sort(|x, y| { loop { } });").into_bytes()),
        (s("string doubling"), body("let s = \"x\"; for i in 0..40 { s += s; } s").into_bytes()),
        (s("array growth"), body("let a = []; for i in 0..100000000 { a.push(i); } a").into_bytes()),
        (s("history kept in the record"), body(
            "let h = if observed_variables.len() > 0 { observed_variables[-1] } else { [] }; h.push(state); h",
        ).into_bytes()),
        (s("nested return"), body(&format!("{}1{}", "[".repeat(60), "]".repeat(60))).into_bytes()),
        (s("property of the record"), body("observed_variables[-1].foo").into_bytes()),
        (s("unknown environment method"), b"fn controller_function(time, sampling_rate, state, state_history, observed_variables, air_brakes, sensors, environment) { environment.nothing(1.0); }\n".to_vec()),
        (s("eval"), body("eval(\"1\");").into_bytes()),
        (s("import"), format!("import \"x\" as y;\n{}", body("")).into_bytes()),
        (s("deep parentheses"), body(&format!("let x = {}1{};", "(".repeat(20_000), ")".repeat(20_000))).into_bytes()),
        (s("deep blocks"), body(&format!("{}{}", "{".repeat(20_000), "}".repeat(20_000))).into_bytes()),
        (s("a megabyte of statements"), body(&"let x = 1.0;\n".repeat(80_000)).into_bytes()),
        (s("returns a string"), body("\"hello\"").into_bytes()),
        (s("NaN level"), body("air_brakes.deployment_level = 0.0 / 0.0;").into_bytes()),
        (s("integer level"), body("air_brakes.deployment_level = 1;").into_bytes()),
        (s("recursion"), format!("fn f(x) {{ f(x) }}\n{}", body("f(1)")).into_bytes()),
        (s("top-level endless loop"), format!("loop {{ }}\n{}", body("")).into_bytes()),
        (s("sleep"), body("sleep(100);").into_bytes()),
        (s("sleep through a function pointer"), body("Fn(\"sleep\").call(100.0);").into_bytes()),
        (s("curried arguments growing"), body("let f = Fn(\"abs\"); for i in 0..100000 { f = f.curry(i); }").into_bytes()),
    ];
    let example = std::fs::read_to_string(repository("fixtures/airbrakes/docs_controller.rhai"))
        .expect("the example controller");
    let mut rng = Rng::new(0x5C21_9700);
    for i in 0..15 {
        let cut = rng.below(example.len());
        sources.push((
            format!("example cut at {cut} ({i})"),
            example.as_bytes()[..cut].to_vec(),
        ));
    }
    sources
        .into_iter()
        .enumerate()
        .map(|(i, (name, bytes))| {
            let path = write(&dir.join(format!("s{i:03}.rhai")), bytes);
            let set = format!(
                "rocket.air_brakes.controller={}",
                toml_string(&path_arg(&path))
            );
            flies(
                &format!("script {name}"),
                &mission,
                &[set],
                vec![file_name(&path)],
            )
        })
        .collect()
}

/// The XML of the repository's simplest OpenRocket design.
fn simple_design_xml() -> String {
    let path = repository("fixtures/openrocket/a_simple_model_rocket/design.ork");
    let file = std::fs::File::open(path).expect("the simple design");
    let mut archive = zip::ZipArchive::new(file).expect("a zip archive");
    let mut entry = archive.by_name("rocket.ork").expect("rocket.ork");
    let mut text = String::new();
    entry.read_to_string(&mut text).expect("UTF-8 XML");
    text
}

/// A zip archive holding `entries`.
fn zipped(entries: &[(&str, &[u8])]) -> Vec<u8> {
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    for (name, bytes) in entries {
        zip.start_file(*name, zip::write::SimpleFileOptions::default())
            .expect("zip entry");
        zip.write_all(bytes).expect("zip entry");
    }
    zip.finish().expect("zip").into_inner()
}

/// `text` with the content of the `n`-th `<tag>...</tag>` replaced by `content`.
fn replace_tag(text: &str, tag: &str, n: usize, content: &str) -> String {
    let open = format!("<{tag}>");
    let close = format!("</{tag}>");
    let mut from = 0;
    for _ in 0..n {
        from += text[from..].find(&open).expect("tag") + open.len();
    }
    let start = from + text[from..].find(&open).expect("tag") + open.len();
    let end = start + text[start..].find(&close).expect("closing tag");
    format!("{}{content}{}", &text[..start], &text[end..])
}

/// Hostile OpenRocket designs: injected names, impossible and huge dimensions, walls thicker
/// than their tube, a deep tree, entity bombs, broken archives, and seeded cuts and value edits.
pub fn designs(dir: &Path) -> Vec<Case> {
    let xml = simple_design_xml();
    let motors = path_arg(&repository("fixtures/openrocket/a_simple_model_rocket"));
    let mut designs: Vec<(String, Vec<u8>, Vec<String>)> = Vec::new();
    let injected = "\n[motor]\nkind = \"injected\"\n# ";
    for (i, name) in [
        injected,
        "\"quoted\" 'single'",
        "# hash ]] [[brackets]]",
        "line\r\nfeed",
        "tab\tand \\ backslash",
        "\u{202e}reversed \u{fffd}",
    ]
    .iter()
    .enumerate()
    {
        let escaped = name.replace('&', "&amp;").replace('<', "&lt;");
        let text = replace_tag(&xml, "name", 0, &escaped);
        let text = replace_tag(&text, "name", 2, &escaped);
        designs.push((
            format!("injected name {i}"),
            text.into_bytes(),
            vec![s("kind = \"injected\""), s("[motor]\nkind")],
        ));
    }
    designs.push((
        s("control character in a name"),
        replace_tag(&xml, "name", 0, "bell\u{7}").into_bytes(),
        vec![],
    ));
    for (tag, n, value) in [
        ("length", 0, "-0.1"),
        ("length", 1, "-0.3"),
        ("length", 1, "0"),
        ("length", 1, "NaN"),
        ("length", 1, "Infinity"),
        ("length", 1, "1e308"),
        ("length", 1, "1e400"),
        ("thickness", 1, "10"),
        ("thickness", 1, "-0.001"),
        ("thickness", 0, "1"),
        ("aftradius", 0, "-0.0125"),
        ("aftradius", 0, "1e300"),
        ("radius", 0, "auto -1"),
        ("radius", 0, "garbage"),
    ] {
        let text = replace_tag(&xml, tag, n, value);
        designs.push((format!("<{tag}> {n} = {value}"), text.into_bytes(), vec![]));
    }
    let digits = "9".repeat(100_000);
    designs.push((
        s("100,000-digit length"),
        replace_tag(&xml, "length", 1, &digits).into_bytes(),
        vec![],
    ));
    let depth = 5000;
    let deep = format!(
        "<openrocket version=\"1.10\"><rocket><name>deep</name><subcomponents>{}{}</subcomponents></rocket></openrocket>",
        "<stage><name>s</name><subcomponents>".repeat(depth),
        "</subcomponents></stage>".repeat(depth)
    );
    designs.push((s("component tree 5000 deep"), deep.into_bytes(), vec![]));
    let laughs = "<?xml version=\"1.0\"?><!DOCTYPE lolz [<!ENTITY lol \"lol\"><!ENTITY lol2 \"&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;\"><!ENTITY lol3 \"&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;\"><!ENTITY lol4 \"&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;\"><!ENTITY lol5 \"&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;\"><!ENTITY lol6 \"&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;\"><!ENTITY lol7 \"&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;\"><!ENTITY lol8 \"&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;\"><!ENTITY lol9 \"&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;\">]><openrocket version=\"1.10\"><rocket><name>&lol9;</name></rocket></openrocket>";
    designs.push((s("billion laughs"), laughs.as_bytes().to_vec(), vec![]));
    designs.push((s("external entity"), b"<?xml version=\"1.0\"?><!DOCTYPE r [<!ENTITY x SYSTEM \"file:///etc/passwd\">]><openrocket version=\"1.10\"><rocket><name>&x;</name></rocket></openrocket>".to_vec(), vec![]));
    designs.push((s("empty file"), Vec::new(), vec![]));
    designs.push((s("binary"), Rng::new(5).bytes(4096), vec![]));
    designs.push((s("zip signature only"), b"PK\x03\x04".to_vec(), vec![]));
    let archive = zipped(&[("rocket.ork", xml.as_bytes())]);
    designs.push((s("zipped design"), archive.clone(), vec![]));
    designs.push((
        s("zip cut in half"),
        archive[..archive.len() / 2].to_vec(),
        vec![],
    ));
    designs.push((
        s("zip without rocket.ork"),
        zipped(&[("other.xml", xml.as_bytes())]),
        vec![],
    ));
    designs.push((
        s("zip of binary"),
        zipped(&[("rocket.ork", &Rng::new(6).bytes(1000))]),
        vec![],
    ));
    let deep_zip = zipped(&[(
        "rocket.ork",
        &designs
            .iter()
            .find(|d| d.0.starts_with("component tree"))
            .expect("deep")
            .1,
    )]);
    designs.push((s("zipped deep tree"), deep_zip, vec![]));
    let crowded: String = (0..100_000).map(|i| format!(" a{i}=\"1\"")).collect();
    designs.push((
        s("an element of 100,000 attributes"),
        xml.replacen("<openrocket ", &format!("<openrocket{crowded} "), 1)
            .into_bytes(),
        vec![],
    ));

    let mut rng = Rng::new(0x0A4C_0001);
    for i in 0..20 {
        let mut cut = rng.below(xml.len());
        while !xml.is_char_boundary(cut) {
            cut -= 1;
        }
        designs.push((
            format!("XML cut at {cut} ({i})"),
            xml.as_bytes()[..cut].to_vec(),
            vec![],
        ));
    }
    let numeric_tags = [
        "length",
        "thickness",
        "aftradius",
        "radius",
        "position",
        "axialoffset",
        "cd",
        "fincount",
        "rootchord",
        "tipchord",
        "height",
        "packedlength",
        "packedradius",
    ];
    for i in 0..30 {
        let tag = *rng.pick(&numeric_tags);
        let count = xml.matches(&format!("<{tag}>")).count();
        if count == 0 {
            continue;
        }
        let n = rng.below(count);
        let value = rng.pick(&[
            "-1", "0", "NaN", "1e308", "-1e308", "Infinity", "1e-320", "", "x",
        ]);
        designs.push((
            format!("<{tag}> {n} = {value} ({i})"),
            replace_tag(&xml, tag, n, value).into_bytes(),
            vec![],
        ));
    }

    designs
        .into_iter()
        .enumerate()
        .map(|(i, (name, bytes, forbidden))| {
            let design = write(&dir.join(format!("d{i:03}.ork")), bytes);
            let out = dir.join(format!("d{i:03}.toml"));
            let args = vec![
                s("import"),
                path_arg(&design),
                s("--motor"),
                motors.clone(),
                s("-o"),
                path_arg(&out),
            ];
            Case {
                name: format!("design {name}"),
                args,
                expect: Expect::Imports(
                    vec![file_name(&design)],
                    vec![s("check"), path_arg(&out)],
                    forbidden,
                ),
            }
        })
        .collect()
}

/// Hostile thrust curves (.eng, .rse, CSV) set on the corpus mission.
pub fn thrust_files(dir: &Path) -> Vec<Case> {
    let (mission, _) = corpus_mission(dir);
    let eng_head = "K1-EX 54 488 0 1.028 1.978 X\n";
    let rse = |data: &str| {
        format!(
            "<engine-database><engine-list><engine code=\"K1\" mfg=\"X\" dia=\"54\" len=\"400\" initWt=\"2000\" propWt=\"1000\" delays=\"P\"><data>{data}</data></engine></engine-list></engine-database>\n"
        )
    };
    let point = |t: &str, f: &str| format!("<eng-data t=\"{t}\" f=\"{f}\" m=\"1000\"/>");
    let many: String = (1..200_000)
        .map(|i| format!("{:.5} 700\n", f64::from(i) * 1e-5))
        .collect();
    let mut files: Vec<(String, &str, Vec<u8>, bool)> = vec![
        (s("empty"), "eng", Vec::new(), false),
        (s("binary"), "eng", Rng::new(7).bytes(3000), false),
        (s("header only"), "eng", eng_head.as_bytes().to_vec(), false),
        (
            s("NaN thrust"),
            "eng",
            format!("{eng_head}0.1 nan\n1.0 500\n2.0 0\n").into_bytes(),
            true,
        ),
        (
            s("inf thrust"),
            "eng",
            format!("{eng_head}0.1 inf\n1.0 500\n2.0 0\n").into_bytes(),
            true,
        ),
        (
            s("huge thrust"),
            "eng",
            format!("{eng_head}0.1 1e308\n1.0 1e308\n2.0 0\n").into_bytes(),
            false,
        ),
        (
            s("1e400 thrust"),
            "eng",
            format!("{eng_head}0.1 1e400\n2.0 0\n").into_bytes(),
            true,
        ),
        (
            s("unsorted time"),
            "eng",
            format!("{eng_head}0.5 500\n0.1 900\n2.0 0\n").into_bytes(),
            true,
        ),
        (
            s("repeated time"),
            "eng",
            format!("{eng_head}0.5 500\n0.5 900\n2.0 0\n").into_bytes(),
            true,
        ),
        (
            s("negative time"),
            "eng",
            format!("{eng_head}-1 500\n0.5 900\n2.0 0\n").into_bytes(),
            true,
        ),
        (
            s("all zero"),
            "eng",
            format!("{eng_head}0.1 0\n1.0 0\n2.0 0\n").into_bytes(),
            false,
        ),
        (
            s("burn of 1e-9 s"),
            "eng",
            format!("{eng_head}0.000000001 1000\n0.000000002 0\n").into_bytes(),
            false,
        ),
        (
            s("burn of 1e9 s"),
            "eng",
            format!("{eng_head}1 1000\n1000000000 0\n").into_bytes(),
            false,
        ),
        (
            s("200,000 points"),
            "eng",
            format!("{eng_head}{many}1.99 700\n2.0 0\n").into_bytes(),
            false,
        ),
        (
            s("a line of a megabyte"),
            "eng",
            format!("{eng_head}0.1 {}\n", "5".repeat(1 << 20)).into_bytes(),
            true,
        ),
        (
            s("CRLF and BOM"),
            "eng",
            format!("\u{feff}{eng_head}0.1 900\r\n1.0 800\r\n2.0 0\r\n").into_bytes(),
            false,
        ),
        (s("csv empty"), "csv", Vec::new(), false),
        (
            s("csv garbage"),
            "csv",
            b"time,thrust\nabc,def\n".to_vec(),
            true,
        ),
        (
            s("csv NaN"),
            "csv",
            b"time,thrust\n0,0\n0.1,NaN\n2,0\n".to_vec(),
            true,
        ),
        (
            s("csv unsorted"),
            "csv",
            b"time,thrust\n0,0\n1,900\n0.5,800\n2,0\n".to_vec(),
            true,
        ),
        (s("csv one column"), "csv", b"time\n0\n1\n".to_vec(), true),
        (
            s("csv huge"),
            "csv",
            b"time,thrust\n0,0\n0.1,1e300\n2,0\n".to_vec(),
            false,
        ),
        (
            s("csv quoted newline"),
            "csv",
            b"time,thrust\n0,0\n\"0.1\n\",900\n2,0\n".to_vec(),
            false,
        ),
        (s("csv binary"), "csv", Rng::new(8).bytes(3000), false),
        (s("rse empty"), "rse", Vec::new(), false),
        (s("rse binary"), "rse", Rng::new(9).bytes(3000), false),
        (
            s("rse NaN"),
            "rse",
            rse(&(point("0.1", "NaN") + &*point("1", "0"))).into_bytes(),
            false,
        ),
        (
            s("rse unsorted"),
            "rse",
            rse(&(point("1", "500") + &*point("0.1", "900") + &*point("2", "0"))).into_bytes(),
            false,
        ),
        (
            s("rse missing attribute"),
            "rse",
            rse("<eng-data t=\"0.1\"/>").into_bytes(),
            false,
        ),
        (
            s("rse deep"),
            "rse",
            format!("{}{}", "<a>".repeat(20_000), "</a>".repeat(20_000)).into_bytes(),
            false,
        ),
        (
            s("every point at t = 0"),
            "eng",
            format!("{eng_head}0 900\n0 0\n").into_bytes(),
            false,
        ),
        (
            s("csv every point at t = 2"),
            "csv",
            b"time,thrust\n2,900\n2,0\n".to_vec(),
            false,
        ),
        (
            s("rse element of 100,000 attributes"),
            "rse",
            format!(
                "<engine-database><engine-list><engine{} code=\"K1\"><data>{}</data></engine></engine-list></engine-database>\n",
                (0..100_000).map(|i| format!(" a{i}=\"1\"")).collect::<String>(),
                point("0.1", "900")
            )
            .into_bytes(),
            true,
        ),
        (
            s("rse negative"),
            "rse",
            rse(&(point("0.1", "-900") + &*point("1", "0"))).into_bytes(),
            false,
        ),
    ];
    let example = std::fs::read_to_string(corpus("thrust.eng")).expect("corpus thrust");
    let mut rng = Rng::new(0x7405_7000);
    for i in 0..15 {
        let mut bytes = example.clone().into_bytes();
        let at = rng.below(bytes.len());
        bytes[at] = *rng.pick(b"-.e9 \n\t;x\0");
        files.push((format!("eng byte {at} replaced ({i})"), "eng", bytes, false));
    }
    files
        .into_iter()
        .enumerate()
        .map(|(i, (name, ext, bytes, line))| {
            let path = write(&dir.join(format!("t{i:03}.{ext}")), bytes);
            let set = format!("motor.thrust={}", toml_string(&path_arg(&path)));
            let mut located = vec![file_name(&path)];
            if line {
                located.push(format!("{}:", file_name(&path)));
            }
            flies(&format!("thrust {name}"), &mission, &[set], located)
        })
        .collect()
}

/// Hostile flight logs for `log show`, `compare` and `fit`.
pub fn flight_logs(dir: &Path) -> Vec<Case> {
    let mission = example_mission(dir);
    let good = "time,altitude\n0,0\n0.5,10\n1,40\n2,120\n3,200\n4,230\n5,200\n6,150\n";
    let mut logs: Vec<(String, Vec<u8>)> = vec![
        (s("empty"), Vec::new()),
        (s("binary"), Rng::new(10).bytes(5000)),
        (s("NUL"), vec![0; 1000]),
        (s("header only"), b"time,altitude\n".to_vec()),
        (s("one row"), b"time,altitude\n0,0\n".to_vec()),
        (
            s("huge numbers"),
            b"time,altitude\n0,0\n1,1e308\n2,-1e308\n3,1e400\n".to_vec(),
        ),
        (s("NaN"), b"time,altitude\n0,0\n1,NaN\n2,nan\n".to_vec()),
        (
            s("unsorted time"),
            b"time,altitude\n3,0\n1,10\n2,40\n0,5\n".to_vec(),
        ),
        (
            s("constant time"),
            b"time,altitude\n1,0\n1,10\n1,40\n".to_vec(),
        ),
        (s("missing columns"), b"a,b\n1,2\n3,4\n".to_vec()),
        (
            s("ragged rows"),
            b"time,altitude\n0,0\n1\n2,40,7,8\n".to_vec(),
        ),
        (
            s("a line of a megabyte"),
            format!("time,altitude\n0,{}\n", "7".repeat(1 << 20)).into_bytes(),
        ),
        (
            s("CRLF and BOM"),
            format!("\u{feff}{}", good.replace('\n', "\r\n")).into_bytes(),
        ),
        (s("plain"), good.as_bytes().to_vec()),
        (
            s("100,000-digit time"),
            format!("time,altitude\n{},0\n", "9".repeat(100_000)).into_bytes(),
        ),
        (
            s("negative time"),
            b"time,altitude\n-1e300,0\n0,10\n".to_vec(),
        ),
    ];
    let mut rng = Rng::new(0x106F_11E5);
    for i in 0..8 {
        let cut = rng.below(good.len());
        logs.push((
            format!("cut at {cut} ({i})"),
            good.as_bytes()[..cut].to_vec(),
        ));
    }
    let mut cases = Vec::new();
    for (i, (name, bytes)) in logs.into_iter().enumerate() {
        let path = write(&dir.join(format!("l{i:03}.csv")), bytes);
        let log = path_arg(&path);
        let located = vec![file_name(&path)];
        let runs: [(&str, Vec<String>); 3] = [
            ("log show", vec![s("log"), s("show"), log.clone()]),
            (
                "compare",
                vec![s("compare"), path_arg(&mission), log.clone()],
            ),
            (
                "fit",
                vec![
                    s("fit"),
                    path_arg(&mission),
                    log.clone(),
                    s("--vary"),
                    s("rocket.mass"),
                ],
            ),
        ];
        for (command, args) in runs {
            // A fit of a log that reads flies the mission tens of times: the readable logs
            // are fitted once (the plain one), the others only where the log is refused.
            if command == "fit" && i % 3 != 0 {
                continue;
            }
            cases.push(Case {
                name: format!("{command} {name}"),
                args,
                expect: Expect::Either(located.clone()),
            });
        }
    }
    // Logs that are not regular files: a FIFO blocks whoever opens it, a device never ends.
    let fifo = dir.join("fifo.csv");
    replace_with_fifo(&fifo);
    let zero = dir.join("zero.csv");
    replace_with_link(&zero, Path::new("/dev/zero"));
    for log in [fifo, zero] {
        for args in [
            vec![s("log"), s("show"), path_arg(&log)],
            vec![s("compare"), path_arg(&mission), path_arg(&log)],
        ] {
            cases.push(Case {
                name: format!("{} {}", args[0], file_name(&log)),
                args,
                expect: Expect::Either(vec![file_name(&log), s("not a regular file")]),
            });
        }
    }
    cases
}

/// One tampering of a study folder.
pub struct Tamper {
    /// What it does.
    pub name: String,
    /// Changes the folder.
    pub apply: Box<dyn Fn(&Path)>,
    /// What a refusal must name.
    pub located: Vec<String>,
    /// Whether resuming may succeed (an interrupted run's cut last line is legitimate).
    pub may_succeed: bool,
}

fn tamper(
    name: &str,
    located: &[&str],
    may_succeed: bool,
    apply: impl Fn(&Path) + 'static,
) -> Tamper {
    Tamper {
        name: name.to_owned(),
        apply: Box::new(apply),
        located: located.iter().map(|l| (*l).to_owned()).collect(),
        may_succeed,
    }
}

/// Replaces `path` by a FIFO (`mkfifo`).
fn replace_with_fifo(path: &Path) {
    let _ = std::fs::remove_file(path);
    let made = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("mkfifo runs");
    assert!(made.success(), "mkfifo {}", path.display());
}

/// Replaces `path` by a symbolic link to `target`.
fn replace_with_link(path: &Path, target: &Path) {
    let _ = std::fs::remove_file(path);
    std::os::unix::fs::symlink(target, path).expect("a symbolic link");
}

/// Tamperings of a finished study (`files`: its files and bytes): cut, edited, reordered,
/// re-encoded and missing files, and seeded cuts and cell edits of `samples.csv`.
pub fn study_tampers(files: &BTreeMap<PathBuf, Vec<u8>>) -> Vec<Tamper> {
    let samples =
        String::from_utf8(files[Path::new("samples.csv")].clone()).expect("UTF-8 samples");
    let study = String::from_utf8(files[Path::new("study.json")].clone()).expect("UTF-8 study");
    let rows: Vec<String> = samples.lines().map(str::to_owned).collect();
    let set = |name: &'static str, text: String| {
        move |d: &Path| std::fs::write(d.join(name), &text).expect("tamper")
    };
    let mut tampers = vec![
        tamper("samples.csv removed", &[], true, |d| {
            std::fs::remove_file(d.join("samples.csv")).expect("rm")
        }),
        tamper("study.json removed", &["study.json"], false, |d| {
            std::fs::remove_file(d.join("study.json")).expect("rm")
        }),
        tamper(
            "study.json empty",
            &["study.json"],
            false,
            set("study.json", String::new()),
        ),
        tamper(
            "study.json garbage",
            &["study.json"],
            false,
            set("study.json", s("{\"seed\": [}")),
        ),
        tamper(
            "study.json huge number",
            &["study.json"],
            false,
            set(
                "study.json",
                study.replacen(
                    "\"seed\": 7",
                    &format!("\"seed\": {}", "9".repeat(10_000)),
                    1,
                ),
            ),
        ),
        tamper(
            "study.json deep",
            &["study.json"],
            false,
            set(
                "study.json",
                format!("{}{}", "[".repeat(100_000), "]".repeat(100_000)),
            ),
        ),
        tamper(
            "samples.csv empty",
            &[],
            true,
            set("samples.csv", String::new()),
        ),
        tamper(
            "samples.csv binary",
            &["samples.csv"],
            false,
            set(
                "samples.csv",
                String::from_utf8_lossy(&Rng::new(11).bytes(2000)).into_owned(),
            ),
        ),
        tamper(
            "samples.csv header changed",
            &["samples.csv"],
            false,
            set(
                "samples.csv",
                samples.replacen("index,status", "index,state", 1),
            ),
        ),
        tamper(
            "samples.csv with CRLF",
            &["samples.csv", "Windows line endings (CRLF)"],
            false,
            set("samples.csv", samples.replace('\n', "\r\n")),
        ),
        tamper(
            "samples.csv with a BOM",
            &["samples.csv", "byte-order mark"],
            false,
            set("samples.csv", format!("\u{feff}{samples}")),
        ),
        tamper(
            "samples.csv row deleted",
            &["samples.csv"],
            false,
            set("samples.csv", {
                let mut r = rows.clone();
                r.remove(2);
                r.join("\n") + "\n"
            }),
        ),
        tamper(
            "samples.csv row repeated",
            &["samples.csv"],
            false,
            set("samples.csv", {
                let mut r = rows.clone();
                r.insert(2, rows[2].clone());
                r.join("\n") + "\n"
            }),
        ),
        tamper(
            "samples.csv rows swapped",
            &["samples.csv"],
            false,
            set("samples.csv", {
                let mut r = rows.clone();
                r.swap(1, 2);
                r.join("\n") + "\n"
            }),
        ),
        tamper(
            "samples.csv a line of a megabyte",
            &["samples.csv"],
            false,
            set(
                "samples.csv",
                format!("{}{}\n", samples, "7".repeat(1 << 20)),
            ),
        ),
        tamper("samples.csv is a folder", &["samples.csv"], false, |d| {
            std::fs::remove_file(d.join("samples.csv")).expect("rm");
            std::fs::create_dir(d.join("samples.csv")).expect("mkdir");
        }),
        tamper("a stale lock", &[], true, set("study.lock", s("12345"))),
        // Files that are not regular: a FIFO blocks whoever opens it, a device never ends.
        tamper(
            "samples.csv a FIFO",
            &["samples.csv", "not a regular file"],
            false,
            |d| replace_with_fifo(&d.join("samples.csv")),
        ),
        tamper(
            "study.json a FIFO",
            &["study.json", "not a regular file"],
            false,
            |d| replace_with_fifo(&d.join("study.json")),
        ),
        tamper(
            "study.lock a FIFO",
            &["study.lock", "not a regular file"],
            false,
            |d| replace_with_fifo(&d.join("study.lock")),
        ),
        tamper(
            "samples.csv a link to /dev/zero",
            &["samples.csv", "not a regular file"],
            false,
            |d| replace_with_link(&d.join("samples.csv"), Path::new("/dev/zero")),
        ),
        tamper(
            "study.json a link to /dev/zero",
            &["study.json", "not a regular file"],
            false,
            |d| replace_with_link(&d.join("study.json"), Path::new("/dev/zero")),
        ),
        tamper(
            "samples.csv of 20 MB without a line end",
            &["samples.csv", "a line longer than"],
            false,
            set(
                "samples.csv",
                format!("{}{}", samples, "7".repeat(20 << 20)),
            ),
        ),
    ];
    let mut rng = Rng::new(0x57D1_0000);
    for i in 0..6 {
        // A cut inside the header or a data row: an interrupted run's partial line is dropped.
        let cut = 1 + rng.below(samples.len() - 1);
        let text = samples[..cut].to_owned();
        tampers.push(tamper(
            &format!("samples.csv cut at {cut} ({i})"),
            &[],
            true,
            set("samples.csv", text),
        ));
    }
    for i in 0..8 {
        let row = 1 + rng.below(rows.len() - 1);
        let cells: Vec<&str> = rows[row].split(',').collect();
        let column = 3 + rng.below(cells.len() - 3);
        let value = *rng.pick(&["1e308", "NaN", "-0", "x", "\"", "", "12345.678"]);
        let mut edited = cells.iter().map(|c| (*c).to_owned()).collect::<Vec<_>>();
        if edited[column] == value {
            continue;
        }
        edited[column] = value.to_owned();
        let mut r = rows.clone();
        r[row] = edited.join(",");
        let text = r.join("\n") + "\n";
        tampers.push(tamper(
            &format!("samples.csv row {row} cell {column} = {value} ({i})"),
            &["samples.csv"],
            false,
            set("samples.csv", text),
        ));
    }
    tampers
}
