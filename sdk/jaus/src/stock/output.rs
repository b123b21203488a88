//! Control of the component a driver commands (the Primitive Driver for the platform
//! drivers, the Primitive Manipulator for the manipulator drivers): ask for control,
//! resume it once granted, watch its state and resume it again when it falls back to
//! Standby (after an emergency is cleared), give it back on leaving Ready.

use std::time::{Duration, Instant};

use crate::component::{Context, CoreState, Interface};
use crate::messages::{QueryComponentStatus, Resume};
use crate::Address;

/// How often a driver repeats Request Component Control while it has no answer, and
/// asks the output component it controls for its state.
pub const REQUEST_PERIOD: Duration = Duration::from_secs(1);

/// Control of one output component.
#[derive(Debug, Clone)]
pub struct OutputControl {
    target: Address,
    resumed: bool,
    last_request: Option<Instant>,
    last_query: Option<Instant>,
    last_resume: Option<Instant>,
    resumes: u64,
}

impl OutputControl {
    /// For the component at `target`.
    pub fn new(target: Address) -> Self {
        Self {
            target,
            resumed: false,
            last_request: None,
            last_query: None,
            last_resume: None,
            resumes: 0,
        }
    }

    /// The output component.
    pub fn target(&self) -> Address {
        self.target
    }

    /// Whether this driver controls the output component.
    pub fn granted<I: Interface>(&self, ctx: &Context<'_, I>) -> bool {
        ctx.has_control_of(self.target)
    }

    /// Resume messages sent to the output component so far (on each grant of control,
    /// and each time it reported Standby while controlled).
    pub fn resumes(&self) -> u64 {
        self.resumes
    }

    /// Keeps control of the output component and keeps it Ready: Resume once control is
    /// granted, then Query Component Status every [`REQUEST_PERIOD`] and Resume again
    /// when it reports Standby (an emergency cleared by anyone leaves a component in
    /// Standby, and nothing else would resume it while this driver keeps control). A
    /// component reporting Emergency is left alone: only Clear Emergency ends that.
    /// Call every tick while the driver is Ready.
    pub fn hold<I: Interface>(&mut self, ctx: &mut Context<'_, I>) {
        let out = self.target;
        let now = ctx.now();
        let due = |t: Option<Instant>| {
            t.is_none_or(|t| now.saturating_duration_since(t) >= REQUEST_PERIOD)
        };
        if ctx.has_control_of(out) {
            if !self.resumed {
                self.resume(ctx);
                self.resumed = true;
                self.last_query = Some(now);
                return;
            }
            if ctx.controlled_state(out) == Some(CoreState::Standby) && due(self.last_resume) {
                self.resume(ctx);
            }
            if due(self.last_query) {
                ctx.send_core(out, QueryComponentStatus {});
                self.last_query = Some(now);
            }
            return;
        }
        self.resumed = false;
        if due(self.last_request) {
            self.last_request = Some(now);
            ctx.request_control(out);
        }
    }

    fn resume<I: Interface>(&mut self, ctx: &mut Context<'_, I>) {
        ctx.send_core(self.target, Resume {});
        self.last_resume = Some(ctx.now());
        self.resumes += 1;
    }

    /// Gives control of the output component back (call on leaving Ready, after
    /// stopping), so another driver can take it.
    pub fn release<I: Interface>(&mut self, ctx: &mut Context<'_, I>) {
        if ctx.has_control_of(self.target) {
            ctx.release_control(self.target);
        }
        self.resumed = false;
        self.last_request = None;
        self.last_query = None;
    }
}
