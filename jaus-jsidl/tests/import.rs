//! The importer on small JSIDL fixtures of our own, one per language feature
//! (`tests/fixtures/ok/FEATURE/` and `tests/fixtures/published/FEATURE/`), each
//! compared with the YAML it must give (`tests/golden/FEATURE/*.yaml`) and validated by
//! jaus-spec; and on fixtures it must refuse (`tests/fixtures/err/CASE/`), each with
//! the file, line, element and reason. After reviewing a change of the output, rewrite the golden files with
//!
//! ```sh
//! UPDATE_GOLDEN=1 cargo test -p jaus-jsidl --test import
//! ```

use jaus_spec::model::TransitionKind;
use std::path::{Path, PathBuf};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures")
}

/// The fixture directories of the features: `ok/` (each construct of the language) and
/// `published/` (the constructs the published sets use that need more than a plain
/// mapping). jaus-gen's tests import every `ok/` fixture together; the `published/` ones
/// stand alone.
const KINDS: [&str; 2] = ["ok", "published"];

fn feature_dir(feature: &str) -> PathBuf {
    KINDS
        .iter()
        .map(|k| fixtures().join(k).join(feature))
        .find(|d| d.is_dir())
        .unwrap_or_else(|| panic!("no fixture `{feature}`"))
}

fn import(feature: &str) -> jaus_jsidl::Import {
    jaus_jsidl::import(&[feature_dir(feature)]).unwrap_or_else(|e| panic!("{feature}: {e}"))
}

/// Every fixture imports, validates, and gives its golden YAML byte for byte.
#[test]
fn every_fixture_gives_its_golden_yaml() {
    let golden = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    let update = std::env::var_os("UPDATE_GOLDEN").is_some();
    let mut features: Vec<String> = KINDS
        .iter()
        .flat_map(|k| std::fs::read_dir(fixtures().join(k)).unwrap())
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    features.sort();
    assert!(features.len() >= 20, "{features:?}");
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
        ("array", "Array.xml:8:9: <array name=\"Grid\">: an array has 1 to 256 elements"),
        ("duplicate", "B.xml:3:3: <message_def name=\"Bad\">: a message named `Bad` is already defined at "),
        ("floor", "Floor.xml:9:11: <scale_range>: integer_function `floor`"),
        ("header", "Header.xml:5:5: <header name=\"H\">: only the standard header"),
        ("malformed", "Malformed.xml:9:7: not well-formed XML"),
        ("missing_set", "MissingSet.xml:9:9: <declared_fixed_field name=\"Speed\">: `other.Speed`: the set urn:test:err:Other version 9.9 is not among the imported files"),
        ("offset_limit", "OffsetLimit.xml:9:11: <value_set>: `offset_to_lower_limit=\"true\"` with the lower limit 10"),
        ("redeclared_differently", "B.xml: declares urn:test:err:Shared version 1.0, as "),
        ("message_differs", "Second.xml:3:3: <message_def name=\"ClearAlarm\">: a message named `ClearAlarm` is already defined at "),
        ("many", "3 errors:"),
        ("optional_no_pv", "OptionalNoPv.xml:8:9: <fixed_field name=\"Speed\">: an optional item needs a presence vector"),
        ("signed_enum_range", "SignedEnumRange.xml:9:11: <value_set>: named values of a signed `byte` beyond its largest value"),
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

fn refused(case: &str) -> String {
    match jaus_jsidl::import(&[fixtures().join("err").join(case)]) {
        Ok(_) => panic!("{case}: imported, but must be refused"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_set_declared_twice_alike_is_read_once() {
    let im = import("redeclared");
    let names: Vec<_> = im.files.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["shared.yaml", "own_tanks.yaml"]);
    let spec = im.load().unwrap();
    assert!(spec.ty("TankRec").is_some());
    assert_eq!(spec.types.len(), 1);
}

#[test]
fn a_set_declared_twice_differently_names_both_files_and_the_first_difference() {
    let err = refused("redeclared_differently");
    assert!(
        err.contains("redeclared_differently/A.xml does, differently"),
        "{err}"
    );
    assert!(
        err.contains("<scale_range> at ") && err.contains("A.xml:4:5 and at "),
        "{err}"
    );
    assert!(
        err.contains("B.xml:4:5: `real_upper_limit=\"100\"` against `real_upper_limit=\"200\"`"),
        "{err}"
    );
}

#[test]
fn a_set_reference_resolves_through_the_sets_referred_to() {
    let spec = import("nested_refs").load().unwrap();
    assert!(spec.message("QueryBrightness").is_some());
    assert_eq!(spec.message("ReportBrightness").unwrap().fields.len(), 1);
}

#[test]
fn an_offset_from_a_lower_limit_of_0_sends_the_values_themselves() {
    let spec = import("offset_limit").load().unwrap();
    let m = spec.message("SetPump").unwrap();
    assert_eq!(m.fields[0].def.ty, "SetPumpPumpMode");
    assert_eq!(m.fields[1].wire, jaus_spec::Wire::Int(jaus_spec::Int::U8));
}

#[test]
fn limits_may_be_constant_expressions() {
    let spec = import("expressions").load().unwrap();
    let m = spec.message("SetSteering").unwrap();
    assert_eq!(
        m.fields[0].def.scale,
        Some([-std::f64::consts::PI, std::f64::consts::FRAC_PI_2])
    );
    assert_eq!(m.fields[1].def.scale, Some([-25.0, 16.0]));
    let d = m.fields[1].def.description.as_deref().unwrap();
    assert!(d.contains("`-4*k.TURN` to `(k.TURN + 1.75) * 2`"), "{d}");
}

#[test]
fn a_scaled_or_enumerated_variable_field_type_is_a_named_type() {
    let spec = import("scaled_variants").load().unwrap();
    let u = spec.ty("SetEffortEffort").unwrap();
    let tys: Vec<_> = u
        .def
        .variants
        .iter()
        .map(|v| (v.tag, v.ty.as_deref().unwrap()))
        .collect();
    assert_eq!(
        tys,
        [
            (1, "SetEffortEffortTorque"),
            (2, "SetEffortEffortForce"),
            (3, "SetEffortEffortPreset"),
            (4, "u8")
        ]
    );
    let torque = spec.ty("SetEffortEffortTorque").unwrap();
    assert_eq!(torque.def.fields[0].scale, Some([-200.0, 200.0]));
    assert_eq!(torque.def.fields[0].unit.as_deref(), Some("N m"));
}

#[test]
fn an_array_is_a_record_of_its_elements_in_row_major_order() {
    let spec = import("arrays").load().unwrap();
    let v = spec.ty("Offset3").unwrap();
    let names: Vec<_> = v.def.fields.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["axis_0", "axis_1", "axis_2"]);
    assert_eq!(v.def.fields[2].scale, Some([-5.0, 5.0]));
    let w = spec.ty("SetMountWeights").unwrap();
    let names: Vec<_> = w.def.fields.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "weight_0_0",
            "weight_0_1",
            "weight_0_2",
            "weight_1_0",
            "weight_1_1",
            "weight_1_2"
        ]
    );
    let m = spec.message("SetMount").unwrap();
    let tys: Vec<_> = m.fields.iter().map(|f| f.def.ty.as_str()).collect();
    assert_eq!(tys, ["Offset3", "Offset3", "SetMountWeights"]);
}

#[test]
fn the_same_message_in_two_sets_is_read_once() {
    let spec = import("same_message").load().unwrap();
    let names: Vec<_> = spec.messages.iter().map(|m| m.def.name.as_str()).collect();
    assert_eq!(
        names,
        ["ClearAlarm", "ResetFirstAlarms", "ResetSecondAlarms"]
    );
}

#[test]
fn two_messages_of_a_name_that_differ_are_refused_with_the_difference() {
    let err = refused("message_differs");
    assert!(
        err.contains("First.xml:3:3, differently (<fixed_field name=\"AlarmID\"> at "),
        "{err}"
    );
    assert!(
        err.contains("unsigned short integer") && err.contains("unsigned integer"),
        "{err}"
    );
}

#[test]
fn a_state_starting_in_a_sub_state_it_does_not_declare_extends_the_inherited_one() {
    let spec = import("extending").load().unwrap();
    let pump = &spec.service("Pump").unwrap().def;
    let machine = &pump.behaviour.as_ref().unwrap().machines[0];
    assert!(machine.extends);
    let top = &machine.states[0];
    assert!(top.redefine, "holds a state that extends an inherited one");
    let running = &top.states[0];
    assert_eq!(running.initial.as_deref(), Some("Idle"));
    assert!(
        running.redefine,
        "starts in a sub-state it does not declare"
    );
    // Every state of an extending machine extends the inherited one of its name (a
    // new one is added as any new state).
    assert!(running.states[0].redefine);
    let base = &spec.service("PumpBase").unwrap().def;
    assert!(!base.behaviour.as_ref().unwrap().machines[0].states[0].redefine);
    // Extending by the machine's name alone: every state extends the inherited one.
    let plain = &spec.service("PlainPump").unwrap().def;
    let machine = &plain.behaviour.as_ref().unwrap().machines[0];
    assert!(machine.extends, "named after the inherited machine");
    let top = &machine.states[0];
    assert!(top.redefine && top.states[0].redefine && top.states[0].states[0].redefine);
}

#[test]
fn the_quirks_of_the_published_hmi_set_import() {
    let spec = import("quirks").load().unwrap();
    let report = spec
        .message("ReportDcm")
        .expect("`ReportDCM` named as the importer names");
    let ty = |n: &str| {
        report
            .def
            .fields
            .iter()
            .find(|f| f.name == n)
            .unwrap()
            .ty
            .clone()
    };
    // A signed byte is an i8; named values on one, an unsigned enumeration of the same
    // bytes, which says so.
    assert_eq!(ty("trim"), "i8");
    let state = spec.ty(&ty("state")).unwrap();
    assert_eq!(state.def.repr.as_deref(), Some("u8"));
    assert!(state
        .def
        .description
        .as_deref()
        .unwrap_or("")
        .contains("Signed (`byte`)"));
    // Entries sharing a placeholder name are told apart by their index.
    let reading = spec.ty(&ty("reading")).unwrap();
    let names: Vec<&str> = reading
        .def
        .variants
        .iter()
        .map(|v| v.name.as_str())
        .collect();
    assert_eq!(names, ["RenameMe", "RenameMe1"]);
    // The parent is named as the machine names it, and the transition's message as the
    // importer names messages.
    let dcm = &spec.service("Dcm").unwrap().def;
    assert_eq!(dcm.inherits.as_ref().unwrap().name, "base");
    let t = &dcm.behaviour.as_ref().unwrap().machines[0].states[0].transitions[0];
    assert_eq!(t.parameters[0].ty, "QueryDcm");
}

#[test]
fn every_error_of_a_run_is_reported_by_file_and_line() {
    let err = jaus_jsidl::import(&[fixtures().join("err").join("many")]).unwrap_err();
    let all: Vec<String> = err.all().iter().map(|e| e.to_string()).collect();
    assert_eq!(all.len(), 3, "{err}");
    assert!(
        all[0].contains("One.xml:7:9: <fixed_field name=\"Offset\">: field type `quad integer`"),
        "{}",
        all[0]
    );
    assert!(
        all[1].contains(
            "One.xml:20:7: <declared_record name=\"Missing\">: `NoSuchRec` is not declared"
        ),
        "{}",
        all[1]
    );
    assert!(
        all[2].contains(
            "Two.xml:8:11: <scale_range>: `real_upper_limit=\"2 ^ 3\"`: not a constant expression"
        ),
        "{}",
        all[2]
    );
}

#[test]
fn a_variant_of_no_alternatives_is_its_tag_alone() {
    let spec = import("empty_variant").load().unwrap();
    let none = spec.ty("ReportMountMountVarNoMount").unwrap();
    assert_eq!(none.def.kind, jaus_spec::model::TypeKind::Record);
    let f: Vec<_> = none
        .def
        .fields
        .iter()
        .map(|f| (f.name.as_str(), f.ty.as_str()))
        .collect();
    assert_eq!(f, [("vtag", "u8")]);
}
