//! Every validation rule has a bad fixture in `tests/fixtures/bad/`. The first line of
//! each fixture says what the error must be: `# expect: LINE:COLUMN: text`. The test
//! checks the whole set of definitions is rejected with exactly that position, the
//! file name, and a message starting with that text.

use std::path::Path;

fn fixtures() -> Vec<std::path::PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/bad");
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    v.sort();
    v
}

#[test]
fn every_bad_fixture_is_rejected_with_file_line_column() {
    let files = fixtures();
    assert!(files.len() >= 10, "fixtures present");
    let mut failures = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap();
        let expect = text
            .lines()
            .next()
            .and_then(|l| l.strip_prefix("# expect: "))
            .unwrap_or_else(|| panic!("{} has no `# expect:` line", f.display()))
            .to_string();
        match jaus_spec::load(&[] as &[&Path], &[f]) {
            Ok(_) => failures.push(format!("{}: accepted, expected `{expect}`", f.display())),
            Err(errs) => {
                let want = format!("{}:{expect}", f.display());
                if !errs.0.iter().any(|e| e.to_string().starts_with(&want)) {
                    failures.push(format!(
                        "{}:\n  expected {want}\n  got      {errs}",
                        f.display()
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_built_in_definitions_are_the_files_of_the_directory() {
    let mut files: Vec<(String, String)> = std::fs::read_dir(jaus_spec::defs_dir())
        .expect("defs")
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "yaml").then(|| {
                let name = p.file_name()?.to_string_lossy().into_owned();
                Some((name, std::fs::read_to_string(&p).ok()?))
            })?
        })
        .collect();
    files.sort();
    let built_in: Vec<(String, String)> = jaus_spec::SDK_DEFS
        .iter()
        .map(|(n, t)| (n.to_string(), t.to_string()))
        .collect();
    assert_eq!(
        built_in, files,
        "SDK_DEFS must list every file of defs/, by name"
    );
    let a = jaus_spec::load_sdk().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        a.messages.len(),
        jaus_spec::load_dirs(&[jaus_spec::defs_dir()])
            .map(|s| s.messages.len())
            .unwrap_or(0)
    );
}

#[test]
fn the_shipped_definitions_validate() {
    let spec = jaus_spec::load_dirs(&[jaus_spec::defs_dir()]).unwrap_or_else(|e| panic!("{e}"));
    assert!(spec.messages.len() > 80);
    // The complement rule holds for every query.
    for m in &spec.messages {
        if (0x2000..0x4000).contains(&m.def.code.0) {
            assert!(
                spec.report_of(&m.def).is_some() || m.def.no_report,
                "{} has no report",
                m.def.name
            );
        }
    }
}

#[test]
fn all_errors_are_reported_at_once() {
    let text = "group: g\nmessages:\n  - name: QueryX\n    code: 0x2F00\n    fields:\n      - { name: a, type: nope }\n      - { name: b, type: list, of: u8 }\n";
    let errs = jaus_spec::load_texts(vec![("inline.yaml".into(), text.into())]).unwrap_err();
    assert_eq!(errs.0.len(), 3, "{errs}");
}

#[test]
fn a_validated_spec_carries_every_resolved_form() {
    use jaus_spec::{Bits, Int, TypeForm, TypeKind, Wire};
    let spec = jaus_spec::load_dirs(&[jaus_spec::defs_dir()]).unwrap_or_else(|e| panic!("{e}"));
    // Every message field, as written, with its wire form.
    let pose = spec.message("ReportGlobalPose").unwrap();
    assert_eq!(pose.presence, Some(Int::U16));
    assert_eq!(pose.fields.len(), pose.def.fields.len());
    let lat = &pose.fields[0];
    assert_eq!(lat.def.name, "latitude");
    assert_eq!(
        lat.wire,
        Wire::Scaled {
            int: Int::I32,
            lo: -90.0,
            hi: 90.0
        }
    );
    assert!(pose.fields.iter().any(|f| matches!(
        &f.wire,
        Wire::Named { name, kind: TypeKind::Bitfield, .. } if name == "TimeStamp"
    )));
    // Bit-field members with their bits, union variants with the form of their value.
    let Some(TypeForm::Bitfield { repr, members }) = spec.ty("TimeStamp").map(|t| &t.form) else {
        panic!("TimeStamp is a bit field");
    };
    assert_eq!(*repr, Int::U32);
    assert_eq!(members[0].bits, Bits::Range { lo: 0, hi: 9 });
    let Some(TypeForm::Union { repr, variants }) = spec.ty("EventLimit").map(|t| &t.form) else {
        panic!("EventLimit is a union");
    };
    assert_eq!(*repr, Int::U8);
    assert_eq!(variants[0].wire, Some(Wire::Int(Int::U8)));
    // Records expose their fields; other kinds have none.
    assert!(!spec.ty("EventRecord").unwrap().fields().is_empty());
    assert!(spec.ty("TimeStamp").unwrap().fields().is_empty());
}

/// A vendor's overlay builds on the SDK's definitions: it may use their types and
/// messages, may not repeat their names or codes (both positions are named), and gets a
/// warning for a code of its own outside the experimental range.
#[test]
fn overlays_extend_the_sdk_definitions() {
    let dir = std::env::temp_dir().join(format!("jaus-spec-overlay-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let good = dir.join("good.yaml");
    std::fs::write(
        &good,
        "group: acme\nmessages:\n  - name: ReportStamp\n    code: 0xD001\n    fields:\n      - { name: at, type: TimeStamp }\n  - name: SetPump\n    code: 0x0F00\n    fields:\n      - { name: on, type: u8 }\n",
    )
    .unwrap();
    let spec = jaus_spec::load_overlays(&[&good]).unwrap();
    assert!(spec.extends());
    let own: Vec<&str> = spec
        .messages
        .iter()
        .filter(|m| spec.is_own(m.source))
        .map(|m| m.def.name.as_str())
        .collect();
    assert_eq!(own, ["ReportStamp", "SetPump"]);
    assert!(spec
        .message("ReportGlobalPose")
        .is_some_and(|m| !spec.is_own(m.source)));
    assert_eq!(spec.warnings.len(), 1, "{:?}", spec.warnings);
    let w = spec.warnings[0].to_string();
    assert!(
        w.contains(
            "good.yaml:8:5: message `SetPump`: code 0x0F00 is outside the experimental range"
        ),
        "{w}"
    );

    let dup = dir.join("dup.yaml");
    std::fs::write(
        &dup,
        "group: acme\nmessages:\n  - name: ReportGlobalPose\n    code: 0xD002\n",
    )
    .unwrap();
    let e = jaus_spec::load_overlays(&[&dup]).unwrap_err().to_string();
    assert!(e.contains("dup.yaml:3:"), "{e}");
    assert!(
        e.contains("duplicate name `ReportGlobalPose` (first defined at ")
            && e.contains("platform.yaml:"),
        "{e}"
    );

    let standalone = dir.join("alone.yaml");
    std::fs::write(
        &standalone,
        "extends: none\ngroup: acme\nmessages:\n  - name: ReportGlobalPose\n    code: 0xD002\n",
    )
    .unwrap();
    let spec = jaus_spec::load_overlays(&[&standalone]).unwrap();
    assert!(!spec.extends() && spec.messages.len() == 1);

    let bad = dir.join("bad.yaml");
    std::fs::write(&bad, "extends: ra34\ngroup: acme\n").unwrap();
    let e = jaus_spec::load_overlays(&[&bad]).unwrap_err().to_string();
    assert!(
        e.contains("bad.yaml:1:") && e.contains("`extends: ra34`"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A list's `count_field` is parsed once, by validation, into a [`jaus_spec::CountRef`]
/// (`num_joints - 1`: the field and the constant), and [`jaus_spec::Spec::vars`] names
/// every field another depends on.
#[test]
fn count_fields_resolve_to_count_refs_and_vars() {
    use jaus_spec::{CountRef, Wire};
    let spec = jaus_spec::load_sdk().unwrap_or_else(|e| panic!("{e}"));
    let linked = spec
        .types
        .iter()
        .flat_map(|t| t.fields())
        .chain(spec.messages.iter().flat_map(|m| &m.fields))
        .find(|f| f.def.name == "linked_joints")
        .expect("a field `linked_joints`");
    let Wire::ListField { field, .. } = &linked.wire else {
        panic!("{:?}", linked.wire);
    };
    assert_eq!(
        *field,
        CountRef {
            field: "num_joints".into(),
            minus: 1
        }
    );
    assert_eq!(field.to_string(), "num_joints - 1");
    let vars = spec.vars();
    // A count (with and without a constant), a flag of `present_if`, a `tag_field`.
    for v in [
        "num_joints",
        "object_count",
        "confidence_and_object_id",
        "type_code",
    ] {
        assert!(vars.contains(v), "{v} in {vars:?}");
    }
    assert!(!vars.contains("latitude"));

    // Inside a list element too: there a constant that does not parse is an error.
    let text = "group: g\nmessages:\n  - name: ReportX\n    code: 0x4F00\n    fields:\n      - { name: n, type: u8 }\n      - { name: rows, type: list, count: u8, of: { type: list, count_field: n - x, of: u8 } }\n";
    let errs = jaus_spec::load_texts(vec![("inline.yaml".into(), text.into())]).unwrap_err();
    assert!(
        errs.to_string().contains("inline.yaml:7:")
            && errs.to_string().contains(
                "list element: `count_field` is a field name, optionally minus a constant"
            ),
        "{errs}"
    );
    let text = text.replace("n - x", "n - 1");
    let spec =
        jaus_spec::load_texts(vec![("inline.yaml".into(), text)]).unwrap_or_else(|e| panic!("{e}"));
    assert!(spec.vars().contains("n"));
}
