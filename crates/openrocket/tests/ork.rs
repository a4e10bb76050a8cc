//! The `.ork` reader and the mission writer on bad input: every error names the file and,
//! where there is one, the component; arbitrary bytes never panic; hostile files (too deep,
//! too large, not a regular file) are refused. The refusals of what karman cannot fly yet,
//! and the staging events mapped onto `separation` and `ignition_delay`. The imported
//! missions loaded and built are karman-mission's tests (`tests/ork.rs` there).

use karman_openrocket::{Design, ImportOptions, OrkError, document_text, import};
use proptest::prelude::*;
use std::path::{Path, PathBuf};

fn design(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/openrocket")
        .join(name)
        .join("design.ork")
}

fn simple_xml() -> String {
    let path = design("a_simple_model_rocket");
    document_text(&path, &std::fs::read(&path).expect("fixture")).expect("zip with rocket.ork")
}

fn parse_error(text: &str) -> String {
    match Design::parse(Path::new("bad.ork"), text) {
        Ok(_) => panic!("parsed"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn not_a_design() {
    let e = document_text(Path::new("x.ork"), b"\x00\x01binary").expect_err("binary");
    assert!(e.to_string().contains("x.ork"), "{e}");
    let e = document_text(Path::new("x.ork"), b"PK\x03\x04broken").expect_err("zip");
    assert!(e.to_string().contains("zip"), "{e}");
    let e = parse_error("<rocket/>");
    assert!(e.contains("bad.ork") && e.contains("<openrocket>"), "{e}");
    let e = parse_error("<openrocket version='1.10'><rocket>");
    assert!(e.contains("XML"), "{e}");
}

#[test]
fn unknown_version() {
    let text = simple_xml().replacen("version=\"1.10\"", "version=\"9.99\"", 1);
    let e = parse_error(&text);
    assert!(e.contains("9.99"), "{e}");
}

#[test]
fn nan_dimension_names_the_component() {
    let text = simple_xml().replacen("<length>0.3</length>", "<length>NaN</length>", 1);
    let e = parse_error(&text);
    assert!(e.contains("Body tube") && e.contains("<length>"), "{e}");
}

fn tempdir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("karman-ork-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

#[test]
fn missing_motor_names_the_designation() {
    let dir = tempdir();
    let file = dir.join("no_motor_here.ork");
    std::fs::write(&file, simple_xml()).expect("write");
    let e = import(&file, &ImportOptions::default()).expect_err("no .eng beside it");
    assert!(matches!(e, OrkError::Motor { .. }), "{e}");
    let text = e.to_string();
    assert!(
        text.contains("no_motor_here.ork") && text.contains("A8"),
        "{text}"
    );
}

#[test]
fn unknown_simulation_lists_the_names() {
    let options = ImportOptions {
        simulation: Some("Nope".into()),
        ..ImportOptions::default()
    };
    let e = import(&design("a_simple_model_rocket"), &options).expect_err("no such simulation");
    assert!(e.to_string().contains("\"Simulation 1\""), "{e}");
}

fn pods_xml() -> String {
    let path = design("pods_airframes_and_winglets");
    document_text(&path, &std::fs::read(&path).expect("fixture")).expect("zip with rocket.ork")
}

#[test]
fn powered_pods_and_parallel_boosters_are_refused_by_name() {
    let xml = pods_xml();
    // A motor mount inside the wing pods' body tube.
    let tube_end = "<radius>0.0068707</radius>\n                  </bodytube>";
    assert!(xml.contains(tube_end));
    let mount = "<radius>0.0068707</radius>\n<subcomponents><innertube><name>Pod mount</name>\
        <material type=\"bulk\" density=\"894.4\">Paper</material><length>0.03</length>\
        <outerradius>0.005</outerradius><thickness>0.0003</thickness><motormount>\
        <motor configid=\"ebe43947-e8b6-486a-aaea-07077ea9b8b7\"><manufacturer>Estes</manufacturer>\
        <designation>A8</designation><diameter>0.018</diameter><length>0.07</length>\
        <delay>3.0</delay></motor></motormount></innertube></subcomponents></bodytube>";
    let powered = xml.replacen(tube_end, mount, 1);
    let dir = tempdir();
    let file = dir.join("powered.ork");
    std::fs::write(&file, &powered).expect("write");
    let e = import(&file, &ImportOptions::default()).expect_err("powered pods");
    assert!(matches!(e, OrkError::Unsupported { .. }), "{e}");
    let text = e.to_string();
    assert!(text.contains("powered.ork"), "{text}");
    assert!(
        text.contains("Wing pods") && text.contains("Pod mount"),
        "{text}"
    );
    assert!(text.contains("motor mount"), "{text}");
    // Side boosters.
    let boosters =
        xml.replacen("<podset>", "<parallelstage>", 1)
            .replacen("</podset>", "</parallelstage>", 1);
    let e = parse_error(&boosters);
    assert!(
        e.contains("Wing pods") && e.contains("parallel booster"),
        "{e}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn arbitrary_bytes_do_not_panic(bytes in proptest::collection::vec(any::<u8>(), 0..512)) {
        if let Ok(text) = document_text(Path::new("fuzz.ork"), &bytes) {
            let _ = Design::parse(Path::new("fuzz.ork"), &text);
        }
    }

    #[test]
    fn mutated_designs_do_not_panic(cut in 0usize..4000, insert in "[<>/a-z0-9 .\"=-]{0,12}") {
        let text = simple_xml();
        let cut = cut.min(text.len());
        let cut = (0..=cut).rev().find(|&i| text.is_char_boundary(i)).unwrap_or(0);
        let mutated = format!("{}{insert}{}", &text[..cut], &text[cut..]);
        let _ = Design::parse(Path::new("fuzz.ork"), &mutated);
    }
}

/// `two_stage_high_power_rocket` with `edit` applied to its document, imported for its
/// second simulation (I59WN sustainer lit at the booster's burn-out, separation at that
/// ignition).
fn edited_two_stage(
    edit: impl Fn(&str) -> String,
) -> Result<karman_openrocket::Imported, OrkError> {
    let path = design("two_stage_high_power_rocket");
    let text = document_text(&path, &std::fs::read(&path).expect("fixture")).expect("document");
    let file = tempdir().join("edited_two_stage.ork");
    std::fs::write(&file, edit(&text)).expect("write");
    let options = ImportOptions {
        simulation: Some("Simulation 2".into()),
        motors: vec![path.parent().expect("dir").to_owned()],
        output_dir: None,
    };
    import(&file, &options)
}

#[test]
fn staged_designs_map_their_events_onto_separation_and_ignition_delay() {
    let imported = edited_two_stage(str::to_owned).expect("imports");
    assert!(
        imported.mission.contains(
            "[[stages]]\nname = \"Booster\"\nseparation = \"burnout + 0.0\"\nignition_delay = 0.0"
        ),
        "{}",
        imported.mission
    );
    // A 2 s ignition delay and separation 0.5 s after that ignition: separated 2.5 s after
    // the booster's burn-out, lit at once.
    let delayed = edited_two_stage(|t| {
        t.replacen(
            "<ignitionconfiguration configid=\"fadeeef3-4aa4-49e9-9581-71e14fa91c14\">\n                        <ignitionevent>burnout</ignitionevent>\n                        <ignitiondelay>0.0</ignitiondelay>",
            "<ignitionconfiguration configid=\"fadeeef3-4aa4-49e9-9581-71e14fa91c14\">\n                        <ignitionevent>burnout</ignitionevent>\n                        <ignitiondelay>2.0</ignitiondelay>",
            1,
        )
    })
    .expect("imports");
    assert!(
        delayed
            .mission
            .contains("separation = \"burnout + 2.0\"\nignition_delay = 0.0"),
        "{}",
        delayed.mission
    );
    // Separation at burn-out, ignition 2 s later: an air start.
    let air_start = edited_two_stage(|t| {
        t.replacen("<ignitiondelay>0.0</ignitiondelay>\n                      </ignitionconfiguration>\n                    </motormount>", "<ignitiondelay>2.0</ignitiondelay>\n                      </ignitionconfiguration>\n                    </motormount>", 1)
            .replacen("<separationevent>upperignition</separationevent>", "<separationevent>burnout</separationevent>", 1)
    })
    .expect("imports");
    assert!(
        air_start
            .mission
            .contains("separation = \"burnout + 0.0\"\nignition_delay = 2.0"),
        "{}",
        air_start.mission
    );
}

#[test]
fn staged_events_the_format_cannot_express_are_refused_by_name() {
    // The sustainer lit at launch, on the booster.
    let e = edited_two_stage(|t| {
        t.replacen("<ignitionevent>burnout</ignitionevent>\n                        <ignitiondelay>0.0</ignitiondelay>\n                      </ignitionconfiguration>\n                    </motormount>", "<ignitionevent>launch</ignitionevent>\n                        <ignitiondelay>0.0</ignitiondelay>\n                      </ignitionconfiguration>\n                    </motormount>", 1)
    })
    .expect_err("ignition at launch");
    assert!(matches!(e, OrkError::Unsupported { .. }), "{e}");
    assert!(
        e.to_string().contains("Sustainer Motor Mount") && e.to_string().contains("launch"),
        "{e}"
    );
    // A booster that never separates.
    let e = edited_two_stage(|t| {
        t.replacen(
            "<separationevent>upperignition</separationevent>",
            "<separationevent>never</separationevent>",
            1,
        )
    })
    .expect_err("never separates");
    assert!(
        e.to_string().contains("Booster") && e.to_string().contains("never"),
        "{e}"
    );
    // Separation half a second after the sustainer's ignition: it would burn on the stack.
    let e = edited_two_stage(|t| {
        t.replacen("<separationevent>upperignition</separationevent>\n            <separationaltitude>200.0</separationaltitude>\n            <separationdelay>0.0</separationdelay>", "<separationevent>upperignition</separationevent>\n            <separationaltitude>200.0</separationaltitude>\n            <separationdelay>0.5</separationdelay>", 1)
    })
    .expect_err("ignites before separation");
    assert!(
        e.to_string().contains("before the stage below separates"),
        "{e}"
    );
}

#[test]
fn a_stage_without_a_motor_rides_on_the_stage_below() {
    let imported =
        import(&design("deployable_payload"), &ImportOptions::default()).expect("imports");
    assert!(
        !imported.mission.contains("[[stages]]\n"),
        "{}",
        imported.mission
    );
    assert!(
        imported
            .warnings
            .iter()
            .any(|w| w.contains("Deployable Payload") && w.contains("not flown")),
        "{:?}",
        imported.warnings
    );
}

/// Walls thicker than their radius (a shoulder's, a body tube's) fill the part instead of
/// reaching a `clamp` with its bounds crossed; a negative shoulder radius is an error naming
/// the element.
#[test]
fn walls_thicker_than_their_radius_fill_the_part() {
    let text = simple_xml();
    let import_text = |xml: &str, name: &str| {
        let file = tempdir().join(name);
        std::fs::write(&file, xml).expect("write");
        let options = ImportOptions {
            motors: vec![
                design("a_simple_model_rocket")
                    .parent()
                    .expect("dir")
                    .to_owned(),
            ],
            ..ImportOptions::default()
        };
        import(&file, &options)
    };
    let thick = text.replacen(
        "<aftshoulderthickness>0.002</aftshoulderthickness>",
        "<aftshoulderthickness>0.5</aftshoulderthickness>",
        1,
    );
    assert_ne!(thick, text, "the fixture has the shoulder");
    import_text(&thick, "thick_shoulder.ork").expect("a filled shoulder imports");
    let at = text.find("<bodytube>").expect("a body tube");
    let open = text[at..].find("<thickness>").expect("its wall") + at;
    let close = text[open..].find("</thickness>").expect("end") + open + "</thickness>".len();
    let mut solid = text.clone();
    solid.replace_range(open..close, "<thickness>3.0</thickness>");
    import_text(&solid, "thick_tube.ork").expect("a filled tube imports");
    let negative = text.replacen(
        "<aftshoulderradius>0.0115</aftshoulderradius>",
        "<aftshoulderradius>-0.0115</aftshoulderradius>",
        1,
    );
    let e = import_text(&negative, "negative_shoulder.ork").expect_err("negative radius");
    assert!(
        e.to_string().contains("aftshoulderradius") && e.to_string().contains("negative"),
        "{e}"
    );
}

/// A negative length (the nose cone's here, read for its placement) is an error naming the
/// component and the element, not a `clamp` with its bounds crossed in the mass integral.
#[test]
fn a_negative_length_names_the_component() {
    let text = simple_xml().replacen("<length>0.1</length>", "<length>-0.1</length>", 1);
    let e = parse_error_or_import(&text, "negative_nose.ork");
    assert!(
        e.contains("Nose cone") && e.contains("<length>") && e.contains("negative"),
        "{e}"
    );
}

/// Values OpenRocket could never hold (a negative or fractional fin count, a negative drag
/// coefficient, deployment delay or density) are errors naming the component and the
/// element, not a mission written with a count of 0 that `check` then refuses.
#[test]
fn impossible_values_name_the_component_and_element() {
    let xml = simple_xml();
    let cases = [
        (
            "<fincount>3</fincount>",
            "<fincount>-3</fincount>",
            "fincount",
        ),
        (
            "<fincount>3</fincount>",
            "<fincount>2.5</fincount>",
            "fincount",
        ),
        ("<cd>auto</cd>", "<cd>-0.8</cd>", "<cd>"),
        ("density=\"680.0\"", "density=\"NaN\"", "material"),
    ];
    for (from, to, element) in cases {
        assert!(xml.contains(from), "the fixture holds {from}");
        let text = xml.replacen(from, to, 1);
        let e = parse_error_or_import(&text, "impossible.ork");
        assert!(e.contains(element), "{to}: {e}");
        assert!(e.contains("impossible.ork"), "{to}: {e}");
    }
}

/// The error of reading `xml` as a design, or of importing it.
fn parse_error_or_import(xml: &str, name: &str) -> String {
    let file = tempdir().join(name);
    std::fs::write(&file, xml).expect("write");
    let options = ImportOptions {
        motors: vec![
            design("a_simple_model_rocket")
                .parent()
                .expect("dir")
                .to_owned(),
        ],
        ..ImportOptions::default()
    };
    match import(&file, &options) {
        Ok(_) => panic!("{name} imported"),
        Err(e) => e.to_string(),
    }
}

/// A component tree 5,000 deep (inner tubes inside inner tubes) is an error naming the depth
/// limit, not a stack overflow; 20 deep still reads.
#[test]
fn a_component_tree_too_deep_is_an_error() {
    let text = simple_xml();
    let nested = |depth: usize| {
        let tube = "<innertube><name>t</name><length>0.01</length><outerradius>0.005</outerradius>\
                    <thickness>0.001</thickness><material type=\"bulk\" density=\"1000\">x</material>\
                    <subcomponents>";
        let at = text.find("<bodytube>").expect("a body tube");
        let subs =
            text[at..].find("<subcomponents>").expect("its parts") + at + "<subcomponents>".len();
        let mut xml = String::with_capacity(text.len() + depth * 300);
        xml.push_str(&text[..subs]);
        for _ in 0..depth {
            xml.push_str(tube);
        }
        for _ in 0..depth {
            xml.push_str("</subcomponents></innertube>");
        }
        xml.push_str(&text[subs..]);
        xml
    };
    let deep = nested(5000);
    let e = match Design::parse(Path::new("deep.ork"), &deep) {
        Ok(_) => panic!("a 5,000-deep tree parsed"),
        Err(e) => e.to_string(),
    };
    assert!(
        e.contains("deep.ork") && e.contains("nested more than 64 deep"),
        "{e}"
    );
    Design::parse(Path::new("twenty.ork"), &nested(20)).expect("20 deep reads");
}

/// A zip bomb (an entry that inflates past [`MAX_DOCUMENT_BYTES`]) stops at the cap with an
/// error; a file that is not a regular file (`/dev/zero`, which never ends) is refused before
/// it is read.
#[test]
fn a_zip_bomb_and_a_device_are_refused() {
    use karman_openrocket::{MAX_DOCUMENT_BYTES, read_document};
    use std::io::Write;
    let file = tempdir().join("bomb.ork");
    let mut zip = zip::ZipWriter::new(std::fs::File::create(&file).expect("create"));
    let deflated = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    zip.start_file("rocket.ork", deflated).expect("entry");
    let block = vec![b' '; 1 << 20];
    for _ in 0..=(MAX_DOCUMENT_BYTES >> 20) {
        zip.write_all(&block).expect("write");
    }
    zip.finish().expect("finish");
    let size = std::fs::metadata(&file).expect("size").len();
    assert!(
        size < MAX_DOCUMENT_BYTES / 100,
        "the bomb is small: {size} bytes"
    );
    let e = read_document(&file).expect_err("too large").to_string();
    assert!(
        e.contains("bomb.ork") && e.contains("decompressed") && e.contains("MiB"),
        "{e}"
    );
    let e = read_document(Path::new("/dev/zero"))
        .expect_err("a device")
        .to_string();
    assert!(
        e.contains("/dev/zero") && e.contains("not a regular file"),
        "{e}"
    );
}
