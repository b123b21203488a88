//! The importer on small JSIDL fixtures of our own, one per language feature
//! (`tests/fixtures/ok/FEATURE/`), each compared with the YAML it must give
//! (`tests/golden/FEATURE/*.yaml`) and validated by jaus-spec; and on fixtures it must
//! refuse (`tests/fixtures/err/CASE/`), each with the file, line, element and reason.
//! After reviewing a change of the output, rewrite the golden files with
//!
//! ```sh
//! UPDATE_GOLDEN=1 cargo test -p jaus-jsidl --test import
//! ```

use jaus_spec::model::TransitionKind;
use std::path::{Path, PathBuf};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures")
}

fn import(feature: &str) -> jaus_jsidl::Import {
    jaus_jsidl::import(&[fixtures().join("ok").join(feature)])
        .unwrap_or_else(|e| panic!("{feature}: {e}"))
}

/// Every fixture imports, validates, and gives its golden YAML byte for byte.
#[test]
fn every_fixture_gives_its_golden_yaml() {
    let golden = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    let update = std::env::var_os("UPDATE_GOLDEN").is_some();
    let mut features: Vec<String> = std::fs::read_dir(fixtures().join("ok"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    features.sort();
    assert!(features.len() >= 11, "{features:?}");
    let mut failures = Vec::new();
    for f in &features {
        let im = import(f);
        if let Err(e) = im.load() {
            failures.push(format!("{f}: does not validate: {e}"));
        }
        let dir = golden.join(f);
        if update {
            let _ = std::fs::remove_dir_all(&dir);
            im.write(&dir).unwrap();
            continue;
        }
        let mut expected: Vec<String> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        expected.sort();
        let mut got: Vec<String> = im.files.iter().map(|x| x.name.clone()).collect();
        got.sort();
        if expected != got {
            failures.push(format!("{f}: files {got:?}, golden {expected:?}"));
            continue;
        }
        for file in &im.files {
            let want = std::fs::read_to_string(dir.join(&file.name)).unwrap();
            if want != file.yaml {
                failures.push(format!(
                    "{f}/{}: differs from the golden file:\n--- golden\n{want}\n--- imported\n{}",
                    file.name, file.yaml
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn the_same_jsidl_gives_the_same_bytes() {
    let a = import("service");
    let b = import("service");
    let texts = |i: &jaus_jsidl::Import| i.texts(Path::new("x"));
    assert_eq!(texts(&a), texts(&b));
}

#[test]
fn fixed_fields_keep_scale_unit_and_named_values() {
    let spec = import("fields").load().unwrap();
    let m = spec.message("SetDriveTrim").unwrap();
    assert_eq!(m.def.code.0, 0x0D01);
    assert_eq!(m.def.is_command, Some(true));
    let speed = &m.fields[0];
    assert_eq!(
        speed.wire,
        jaus_spec::Wire::Scaled {
            int: jaus_spec::Int::U16,
            lo: -10.0,
            hi: 10.0
        }
    );
    assert_eq!(speed.def.unit.as_deref(), Some("m/s"));
    let gear = spec.ty("GearSelect").unwrap();
    let names: Vec<_> = gear
        .def
        .values
        .iter()
        .map(|v| (v.name.as_str(), v.value))
        .collect();
    assert_eq!(names, [("Park", 0), ("LowRange", 1), ("HighRange", 2)]);
    assert_eq!(m.fields[4].def.ty, "GearSelect");
}

#[test]
fn constants_stand_for_numbers() {
    let spec = import("constants").load().unwrap();
    let m = spec.message("SetHeading").unwrap();
    assert_eq!(m.fields[0].def.scale, Some([-3.5, 3.5]));
    assert_eq!(
        m.fields[1].def.length,
        Some(jaus_spec::model::Length::Fixed(12))
    );
}

#[test]
fn optional_fields_take_presence_bits_in_order() {
    let spec = import("records").load().unwrap();
    let m = spec.message("SetMarker").unwrap();
    assert_eq!(m.presence, Some(jaus_spec::Int::U8));
    let bits: Vec<_> = m.fields.iter().map(|f| f.def.bit).collect();
    assert_eq!(bits, [None, Some(0), Some(1)]);
    let r = spec.message("ReportMarker").unwrap();
    assert_eq!(r.presence, Some(jaus_spec::Int::U16));
}

#[test]
fn references_resolve_across_files_and_sets_of_sets() {
    let spec = import("refs").load().unwrap();
    let cruise = &spec.message("SetCruise").unwrap().fields[0];
    assert_eq!(cruise.def.name, "cruise");
    assert_eq!(cruise.def.scale, Some([0.0, 50.0]));
    let drive = &spec.message("SetDrive").unwrap().fields[0];
    assert_eq!(drive.def.name, "speed");
}

#[test]
fn a_service_keeps_its_sets_events_and_state_machine() {
    let spec = import("service").load().unwrap();
    assert_eq!(spec.services.len(), 2);
    let lamp = &spec
        .services
        .iter()
        .find(|s| s.def.name == "Lamp")
        .unwrap()
        .def;
    assert_eq!(lamp.inherits.as_ref().unwrap().id, "urn:test:lamp:LampBase");
    assert_eq!(lamp.inputs, ["SetLamp", "QueryLamp"]);
    assert_eq!(lamp.outputs, ["ReportLamp"]);
    assert_eq!(lamp.events[0].name, "Overheated");
    let b = lamp.behaviour.as_ref().unwrap();
    assert_eq!(b.start[0].state, "Receiving.Ready.Off");
    let m = &b.machines[0];
    assert!(m.extends);
    let receiving = &m.states[0];
    assert!(receiving.redefine);
    let ready = &receiving.states[0];
    assert_eq!(ready.initial.as_deref(), Some("Off"));
    assert_eq!(ready.entry[0].name, "resetLamp");
    assert_eq!(ready.exit[0].name, "saveLamp");
    assert!(ready.transitions[0].actions[0].send);
    assert_eq!(ready.transitions[0].kind, TransitionKind::Internal);
    let off = &ready.states[0].transitions[0];
    assert_eq!(
        off.guard.as_ref().unwrap().condition,
        "isOn(msg) && isAllowed(msg)"
    );
    assert_eq!(off.to.as_deref(), Some("Receiving.Ready.On"));
    assert_eq!(off.actions[0].args, ["msg"]);
    assert_eq!(ready.states[1].transitions[0].kind, TransitionKind::Push);
    let pop = &receiving.states[1].transitions[0];
    assert_eq!(pop.kind, TransitionKind::Pop);
    assert_eq!(pop.pop.as_ref().unwrap().name, "Cooled");
    assert_eq!(m.default.as_ref().unwrap().default_transitions.len(), 1);
    // The base's event keeps its data without the wire's count.
    let base = &spec
        .services
        .iter()
        .find(|s| s.def.name == "LampBase")
        .unwrap()
        .def;
    let payload = &base.events[0].fields[1];
    assert_eq!(
        (payload.name.as_str(), payload.ty.as_str()),
        ("payload", "bytes")
    );
    assert_eq!(payload.count, None);
}

/// What the importer refuses, each with the file, line, column, element and reason.
#[test]
fn what_cannot_be_represented_is_an_error_with_file_line_and_element() {
    let cases = [
        ("array", "Array.xml:8:9: <array name=\"Grid\">: arrays are not supported"),
        ("duplicate", "B.xml:3:3: <message_def name=\"Bad\">: a message or type named `Bad` is already defined"),
        ("floor", "Floor.xml:9:11: <scale_range>: integer_function `floor`"),
        ("header", "Header.xml:5:5: <header name=\"H\">: only the standard header"),
        ("malformed", "Malformed.xml:9:7: not well-formed XML"),
        ("missing_set", "MissingSet.xml:9:9: <declared_fixed_field name=\"Speed\">: `other.Speed`: the set urn:test:err:Other version 9.9 is not among the imported files"),
        ("offset_limit", "OffsetLimit.xml:9:11: <value_set>: `offset_to_lower_limit=\"true\"`"),
        ("optional_no_pv", "OptionalNoPv.xml:8:9: <fixed_field name=\"Speed\">: an optional item needs a presence vector"),
        ("signed_byte", "SignedByte.xml:8:9: <fixed_field name=\"Offset\">: field type `byte` is not supported"),
        ("u64_count", "U64Count.xml:9:11: <count_field>: a count of type `unsigned long integer` has no wire form"),
        ("unknown_ref", "UnknownRef.xml:8:9: <declared_fixed_field name=\"Speed\">: `nope` (of `nope.Speed`) names no declared_type_set_ref"),
    ];
    let dirs: Vec<_> = std::fs::read_dir(fixtures().join("err")).unwrap().collect();
    assert_eq!(dirs.len(), cases.len(), "every error fixture has its case");
    for (case, want) in cases {
        let err = match jaus_jsidl::import(&[fixtures().join("err").join(case)]) {
            Ok(_) => panic!("{case}: imported, but must be refused"),
            Err(e) => e.to_string(),
        };
        assert!(
            err.contains(want),
            "{case}: got\n  {err}\nwant it to contain\n  {want}"
        );
    }
}
