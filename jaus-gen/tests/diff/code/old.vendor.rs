// Code written against `old/` in the style the compatibility classes assume
// (docs/spec-revisions.md, "What compatible means for your code"): struct literals and
// patterns end with `..`, every `match` on a generated enum or on `Message` has a `_`
// arm. tests/tests/revision_compile.rs of the workspace compiles it against the messages
// generated from `old/` and from `compatible/`. (The components of this set of its own
// are stand-ins that compile only against the SDK's messages: the component changes are
// compiled through `tractor-1.vendor.rs`.)

/// A state report.
pub fn state(speed: f64) -> ReportState {
    ReportState {
        mode: 1,
        speed,
        heading: 0.5,
        name: "rev".into(),
        altitude: Some(12),
        ..Default::default()
    }
}

/// A status report with two flags set.
pub fn status() -> ReportStatus {
    ReportStatus {
        status: 3,
        flags: Flags {
            a: true,
            e: true,
            ..Default::default()
        },
        ..Default::default()
    }
}

/// The speed of a state report, by destructuring.
pub fn speed_of(s: &ReportState) -> f64 {
    let ReportState { speed, .. } = s;
    *speed
}

/// Whether a mode moves.
pub fn moving(m: Mode) -> bool {
    match m {
        Mode::Run => true,
        Mode::Idle | Mode::Stop => false,
        _ => false,
    }
}

/// What a message is, in a word.
pub fn describe(msg: &Message) -> &'static str {
    match msg {
        Message::ReportState(_) => "state",
        Message::SetMode(m) if moving(m.mode) => "moving",
        _ => "another message",
    }
}
