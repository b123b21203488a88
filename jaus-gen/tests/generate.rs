//! Generator behaviour: deterministic output, documentation from the YAML text,
//! template overrides and error reporting.

use jaus_gen::{Builder, Error};

fn ra33() -> Builder {
    Builder::new()
        .emit_rerun_if_changed(false)
        .spec_dir(jaus_spec::defs_dir())
        .feature_gates(true)
}

#[test]
fn same_input_gives_byte_identical_output() {
    let a = ra33().render().unwrap();
    let b = ra33().render().unwrap();
    assert_eq!(a.code, b.code);
    assert_eq!(a.components, b.components);
    assert!(a.messages >= 90, "{} messages", a.messages);
}

#[test]
fn every_component_gets_a_documented_trait_interface_and_dispatch() {
    let g = ra33().render().unwrap();
    let spec = jaus_spec::load_dirs(&[jaus_spec::defs_dir()]).unwrap();
    assert_eq!(g.component_count, spec.components.len());
    assert!(
        g.component_count >= 30,
        "Part 1 components and the node manager"
    );
    let code = &g.components;
    for c in &spec.components {
        let name = &c.def.name;
        assert!(
            code.contains(&format!("pub trait {name}: Send + 'static")),
            "{name}"
        );
        assert!(
            code.contains(&format!("pub const ID: u8 = {};", c.def.id)),
            "{name}"
        );
        assert!(code.contains(&format!("name: \"{name}\",")), "{name}");
        if let Some(stock) = &c.def.stock {
            assert!(
                code.contains(&format!("name: \"{}\",", stock.name)),
                "{name}"
            );
        }
    }
    // The component table: every component's INFO, stock implementations with the
    // hardware they run over.
    assert!(code.contains("pub static COMPONENTS: &[ComponentInfo] = &["));
    assert!(code.contains("    global_pose_sensor::INFO,"));
    let wm = &code[code
        .find("pub mod world_model_vector_knowledge_store")
        .unwrap()..];
    let wm = &wm[..wm.find("pub trait").unwrap()];
    assert!(
        wm.contains("name: \"world_model\",") && wm.contains("needs: Hardware::None"),
        "{wm}"
    );
    let rs = &code[code.find("pub mod range_sensor").unwrap()..];
    assert!(rs[..rs.find("pub trait").unwrap()].contains("needs: Hardware::Scanner"));
    // Function text, rules and the definition's position are in the trait docs.
    let wpd = &code[code.find("pub trait GlobalWaypointDriver").unwrap() - 4000
        ..code.find("pub trait GlobalWaypointDriver").unwrap()];
    assert!(
        wpd.contains("The function of the Global Waypoint Driver is to determine"),
        "{wpd}"
    );
    assert!(wpd.contains("# Rules (Part 1)"));
    assert!(wpd.contains("Defined in `platform.yaml:"));
    // Typed handlers, typed query replies, a mode machine with the core effect.
    assert!(code.contains("fn on_set_global_waypoint("));
    assert!(code.contains("-> Result<ReportGlobalPose, Refused>"));
    assert!(code.contains("Transition::Arrive => Some(CoreTransition::Standby)"));
    assert!(code.contains("impl Emits<SetWrenchEffort> for Interface {"));
    // It also takes Spool Mission, so it needs both groups.
    assert!(code.contains(
        "#[cfg(all(feature = \"planning\", feature = \"platform\"))]\npub mod global_waypoint_driver"
    ));
}

#[test]
fn generated_code_is_documented_from_the_yaml() {
    let code = ra33().render().unwrap().code;
    let pose = &code[code.find("pub struct ReportGlobalPose").unwrap() - 1500
        ..code.find("pub struct ReportGlobalPose").unwrap()];
    assert!(pose.contains("/// Report Global Pose (0x4402)."), "{pose}");
    let lat = &code[code.find("pub struct ReportGlobalPose").unwrap()..];
    let lat = &lat[..lat.find("pub latitude").unwrap()];
    assert!(lat.contains("Unit: deg."), "{lat}");
    assert!(
        lat.contains("Range `[-90, 90]`, carried as a scaled `i32`"),
        "{lat}"
    );
    assert!(
        lat.contains("#[jaus(bit = 0, scaled(i32, -90.0, 90.0), unit = \"deg\")]"),
        "{lat}"
    );
    assert!(code.contains("#[cfg(feature = \"platform\")]"));
}

#[test]
fn template_overrides_are_used_and_syntax_errors_point_into_the_output() {
    let dir = std::env::temp_dir().join(format!("jaus-gen-templates-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("messages.rs.j2"),
        "pub struct {{ messages[0].name }} { oops }\n",
    )
    .unwrap();
    match ra33().templates_dir(&dir).out_dir(&dir).render() {
        Err(Error::Syntax { path, line, .. }) => {
            assert_eq!(line, 1);
            assert!(std::fs::read_to_string(path)
                .unwrap()
                .contains("pub struct Set"));
        }
        other => panic!("expected a syntax error, got {other:?}"),
    }
    std::fs::write(
        dir.join("messages.rs.j2"),
        "pub const N: usize = {{ messages | length }};\n",
    )
    .unwrap();
    let g = ra33().templates_dir(&dir).render().unwrap();
    assert!(g.code.starts_with("pub const N: usize = "), "{}", g.code);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn invalid_definitions_fail_with_positions() {
    let dir = std::env::temp_dir().join(format!("jaus-gen-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("bad.yaml");
    std::fs::write(&f, "group: g\nmessages:\n  - name: ReportA\n    code: 0x4001\n    fields:\n      - { name: a, type: nope }\n").unwrap();
    let err = Builder::new()
        .emit_rerun_if_changed(false)
        .overlay(&f)
        .render()
        .unwrap_err();
    let text = err.to_string();
    assert!(matches!(err, Error::Spec(_)));
    assert!(
        text.contains("bad.yaml:6:20: message `ReportA`, field `a`: unknown type `nope`"),
        "{text}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn committed_reference_docs_are_up_to_date() {
    let spec = jaus_spec::load_dirs(&[jaus_spec::defs_dir()]).unwrap();
    let dir = std::env::temp_dir().join(format!("jaus-gen-docs-{}", std::process::id()));
    let files = jaus_gen::render_docs(&spec, &dir).unwrap();
    let committed = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/messages");
    let mut stale = Vec::new();
    for f in &files {
        let name = f.file_name().unwrap();
        let fresh = std::fs::read_to_string(f).unwrap();
        if std::fs::read_to_string(committed.join(name))
            .ok()
            .as_deref()
            != Some(fresh.as_str())
        {
            stale.push(name.to_string_lossy().into_owned());
        }
    }
    let extra = std::fs::read_dir(&committed)
        .map(|d| d.count())
        .unwrap_or(0);
    std::fs::remove_dir_all(&dir).ok();
    assert!(
        stale.is_empty() && extra == files.len(),
        "docs/messages is stale ({stale:?}; {extra} committed vs {} generated): run `cargo run -p jaus-gen --features cli -- docs --out docs/messages`",
        files.len()
    );
}
