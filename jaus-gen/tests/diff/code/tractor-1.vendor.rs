// Vendor code written against `tractor-1/` in the style the compatibility classes
// assume (docs/spec-revisions.md, "What compatible means for your code"): struct
// literals and patterns of generated types end with `..`, and every `match` on a
// generated enum or on `Message` has a `_` arm. tests/tests/revision_compile.rs of the
// workspace compiles it against the code generated from `tractor-1/` and from every
// revision `jaus-gen diff` calls compatible with it (`tractor-2/`).

use std::time::Instant;

use jaus::component::{Component, Config, Refused};
use jaus::Address;

use components::implement_controller::{self, Ctx, ImplementController};
use components::implement_logger::{self, ImplementLogger};

/// The implement: its depth and mode.
#[derive(Debug, Clone, Default)]
pub struct Implement {
    /// Depth, m.
    pub depth: f64,
    /// What the implement does.
    pub mode: ImplementMode,
}

impl Implement {
    /// The report of the implement's state.
    pub fn report(&self) -> ReportImplementState {
        ReportImplementState {
            mode: self.mode,
            depth: self.depth,
            hitch: HitchFlags {
                locked: true,
                ..Default::default()
            },
            hitch_angle: Some(0.125),
            ..Default::default()
        }
    }
}

impl ImplementController for Implement {
    fn on_set_implement_depth(
        &mut self,
        _ctx: &mut Ctx<'_>,
        msg: &SetImplementDepth,
    ) -> Result<(), Refused> {
        self.depth = msg.depth;
        Ok(())
    }

    fn on_set_implement_mode(
        &mut self,
        _ctx: &mut Ctx<'_>,
        msg: &SetImplementMode,
    ) -> Result<(), Refused> {
        self.mode = msg.mode;
        Ok(())
    }

    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        if let Some(controller) = ctx.controller() {
            let report = self.report();
            ctx.send(controller, report);
        }
    }
}

/// Counts what it is sent.
#[derive(Debug, Default)]
pub struct Logger {
    /// Messages seen.
    pub seen: usize,
}

impl ImplementLogger for Logger {
    fn on_other_message(
        &mut self,
        _ctx: &mut implement_logger::Ctx<'_>,
        _msg: &Message,
    ) -> Result<Option<Message>, Refused> {
        self.seen += 1;
        Ok(None)
    }
}

/// The Implement Controller at 1.1.220.1.
pub fn controller(t0: Instant) -> Component<implement_controller::Dispatch<Implement>> {
    implement_controller::component(
        Address::new(1, 1, 220, 1),
        Implement::default(),
        Config::default(),
        t0,
    )
}

/// The Implement Logger at 1.1.221.1.
pub fn logger(t0: Instant) -> Component<implement_logger::Dispatch<Logger>> {
    implement_logger::component(
        Address::new(1, 1, 221, 1),
        Logger::default(),
        Config::default(),
        t0,
    )
}

/// What a message says, in a word.
pub fn describe(msg: &Message) -> &'static str {
    match msg {
        Message::ReportImplementState(r) => match r.mode {
            ImplementMode::Raised => "raised",
            ImplementMode::Working => "working",
            _ => "another mode",
        },
        Message::SetImplementDepth(_) => "set depth",
        _ => "another message",
    }
}

/// The depth and the hitch lock of a report, by destructuring.
pub fn depth_and_lock(r: &ReportImplementState) -> (f64, bool) {
    let ReportImplementState { depth, hitch, .. } = r;
    let HitchFlags { locked, .. } = hitch;
    (*depth, *locked)
}
