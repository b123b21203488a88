//! The golden files of jaus-gen's snapshot tests (`jaus-gen/tests/golden/`) are code a
//! vendor crate would build: each is included here, in a module of its own, and compiles
//! against the SDK. The test checks that every golden file is included. (A component
//! with `any_message: true` gets `impl<M: StandardMessage> Emits<M> for Interface`: the
//! interface is the vendor's own type, so the orphan rule allows it in any crate.)

// Fixtures with feature gates name cargo features this crate does not have.
#![allow(unexpected_cfgs)]

/// Includes `NAME.messages.rs` of each fixture (and `NAME.components.rs` of those with
/// components) and lists what it included.
macro_rules! golden {
    (
        messages: [$($m:ident),* $(,)?],
        components: [$($c:ident),* $(,)?],
        services: [$($s:ident),* $(,)?] $(,)?
    ) => {
        // Nothing here uses most generated items; unused-item lints are not the point,
        // nor the lints of a fixture without messages (its `decode` matches no code).
        mod messages {
            $(
                #[allow(unused, clippy::match_single_binding)]
                pub mod $m {
                    include!(concat!(
                        env!("CARGO_MANIFEST_DIR"),
                        "/../jaus-gen/tests/golden/",
                        stringify!($m),
                        ".messages.rs"
                    ));
                }
            )*
        }
        mod components {
            $(
                #[allow(unused)]
                pub mod $c {
                    include!(concat!(
                        env!("CARGO_MANIFEST_DIR"),
                        "/../jaus-gen/tests/golden/",
                        stringify!($c),
                        ".components.rs"
                    ));
                }
            )*
        }
        // Services: in a child module of their fixture's messages, as documented.
        mod services {
            $(
                #[allow(unused, clippy::match_single_binding)]
                pub mod $s {
                    include!(concat!(
                        env!("CARGO_MANIFEST_DIR"),
                        "/../jaus-gen/tests/golden/",
                        stringify!($s),
                        ".messages.rs"
                    ));
                    pub mod services {
                        include!(concat!(
                            env!("CARGO_MANIFEST_DIR"),
                            "/../jaus-gen/tests/golden/",
                            stringify!($s),
                            ".services.rs"
                        ));
                    }
                }
            )*
        }
        const INCLUDED: &[&str] = &[
            $(concat!(stringify!($m), ".messages.rs"),)*
            $(concat!(stringify!($c), ".components.rs"),)*
            $(concat!(stringify!($s), ".services.rs"),)*
        ];
    };
}

golden! {
    messages: [
        bitfields,
        component_any_message,
        component_messages,
        component_modes,
        component_parts,
        component_plain,
        embedded,
        enums,
        feature_gates,
        flags,
        hsm_extend,
        hsm_guards,
        hsm_inherit,
        hsm_kinds,
        hsm_nested,
        lists,
        offsets,
        presence,
        queries,
        records,
        runtime,
        scaled,
        strings,
        unions,
    ],
    components: [
        component_any_message,
        component_messages,
        component_modes,
        component_parts,
        component_plain,
        feature_gates,
    ],
    services: [hsm_extend, hsm_guards, hsm_inherit, hsm_kinds, hsm_nested],
}

#[test]
fn every_golden_file_is_compiled() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../jaus-gen/tests/golden");
    let mut files: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|f| f.ends_with(".rs"))
        .collect();
    files.sort();
    let mut included: Vec<&str> = INCLUDED.to_vec();
    included.sort();
    assert_eq!(
        files, included,
        "add the new golden files to the list above"
    );
}

/// A few generated items in use: the vendor flow works on them like on the SDK's own.
#[test]
fn golden_code_runs() {
    use jaus::codec::Encode;
    use jaus::JausMessage;

    use messages::enums::{DriveMode, SetDriveMode};
    let m = SetDriveMode {
        mode: DriveMode::Unknown(3),
        ..Default::default()
    };
    let back = SetDriveMode::decode_body(&m.to_bytes().unwrap()).unwrap();
    assert_eq!(back, m);

    assert_eq!(
        messages::runtime::RUNTIME_INPUTS,
        &[
            jaus::CommandCode(0x0003),
            jaus::CommandCode(0x000D),
            jaus::CommandCode(0x2B00)
        ]
    );

    use components::component_modes::waypoint_follower::{Mode, Transition};
    use jaus::component::{CoreTransition, Modes};
    assert_eq!(Mode::Holding.next(Transition::Start), Some(Mode::Driving));
    assert_eq!(Mode::Idle.next(Transition::Hold), None);
    assert_eq!(
        Mode::core_effect(Transition::LosePose),
        Some(CoreTransition::Fail)
    );
}
