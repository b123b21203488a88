//! Control of the component a driver commands (the Primitive Driver for the platform
//! drivers, the Primitive Manipulator for the manipulator drivers): ask for control,
//! resume it once granted, give it back on leaving Ready.

use std::time::{Duration, Instant};

use crate::component::{Context, Interface};
use crate::messages::Resume;
use crate::Address;

/// How often a driver repeats Request Component Control while it has no answer.
pub const REQUEST_PERIOD: Duration = Duration::from_secs(1);

/// Control of one output component.
#[derive(Debug, Clone)]
pub struct OutputControl {
    target: Address,
    resumed: bool,
    last_request: Option<Instant>,
}

impl OutputControl {
    /// For the component at `target`.
    pub fn new(target: Address) -> Self {
        Self {
            target,
            resumed: false,
            last_request: None,
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

    /// Keeps control of the output component and resumes it once controlled. Call every
    /// tick while the driver is Ready.
    pub fn hold<I: Interface>(&mut self, ctx: &mut Context<'_, I>) {
        let out = self.target;
        if ctx.has_control_of(out) {
            if !self.resumed {
                ctx.send_core(out, Resume {});
                self.resumed = true;
            }
            return;
        }
        self.resumed = false;
        let now = ctx.now();
        if self
            .last_request
            .is_none_or(|t| now.saturating_duration_since(t) >= REQUEST_PERIOD)
        {
            self.last_request = Some(now);
            ctx.request_control(out);
        }
    }

    /// Gives control of the output component back (call on leaving Ready, after
    /// stopping), so another driver can take it.
    pub fn release<I: Interface>(&mut self, ctx: &mut Context<'_, I>) {
        if ctx.has_control_of(self.target) {
            ctx.release_control(self.target);
        }
        self.resumed = false;
        self.last_request = None;
    }
}
