//! Control of components, taken and kept: [`ControlKeeper`] takes and keeps control of a set of components with the
//! commander's authority, asks them to Resume when it gains control, watches their core
//! state and their controller, and says what changed ([`ControlEvent`]): control gained,
//! lost (a higher authority took it, the component let it go, or it restarted and no
//! longer names this component as its controller) and taken back, a component entering
//! Emergency or Failure. It is sans-IO like the runtime: call
//! [`tick`](ControlKeeper::tick) from the component's `tick` and
//! [`on_status`](ControlKeeper::on_status) with each Report Component Status.

use std::time::{Duration, Instant};

use crate::component::{Context, CoreState, Interface};
use crate::messages::{QueryComponentControl, QueryComponentStatus, ReportComponentStatus, Resume};
use crate::Address;

/// Settings of a [`ControlKeeper`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KeeperConfig {
    /// How long to wait before asking again for control not (or no longer) held.
    pub retry: Duration,
    /// How often each kept component's status is queried (and, while control is held,
    /// its controller: a component that restarted names another one, or none).
    pub status_period: Duration,
    /// Send Resume to a component when control of it is gained (it then leaves
    /// Standby for Ready).
    pub resume: bool,
}

/// Asks again every 0.5 s, queries status every 0.2 s, resumes on gaining control.
impl Default for KeeperConfig {
    fn default() -> Self {
        Self {
            retry: Duration::from_millis(500),
            status_period: Duration::from_millis(200),
            resume: true,
        }
    }
}

/// What changed for a kept component.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ControlEvent {
    /// Control was granted (for the first time or again).
    Gained(Address),
    /// Control was lost; the keeper asks again after [`KeeperConfig::retry`].
    Lost(Address),
    /// The component's core state changed (Emergency and Failure among them).
    State(Address, CoreState),
}

#[derive(Debug, Clone)]
struct Kept {
    address: Address,
    /// The authority to ask with (`None`: the component's own).
    authority: Option<u8>,
    held: bool,
    next_request: Option<Instant>,
    next_status: Option<Instant>,
    state: Option<CoreState>,
    gained: u32,
    lost: u32,
}

/// Takes and keeps control of components (see the module documentation).
#[derive(Debug, Clone)]
pub struct ControlKeeper {
    config: KeeperConfig,
    kept: Vec<Kept>,
}

/// [`KeeperConfig::default`], keeping nothing.
impl Default for ControlKeeper {
    fn default() -> Self {
        Self::new(KeeperConfig::default())
    }
}

impl ControlKeeper {
    /// With `config`, keeping nothing yet.
    pub fn new(config: KeeperConfig) -> Self {
        Self {
            config,
            kept: Vec::new(),
        }
    }

    /// Keeps control of `target` from now on, asking with the component's own authority.
    pub fn keep(&mut self, target: Address) {
        self.keep_at(target, None);
    }

    /// Keeps control of `target` from now on, asking with `authority` (a station whose
    /// operator picks the authority per component). Asking again with another authority
    /// replaces the one kept before and asks at once.
    pub fn keep_with(&mut self, target: Address, authority: u8) {
        self.keep_at(target, Some(authority));
    }

    fn keep_at(&mut self, target: Address, authority: Option<u8>) {
        if let Some(k) = self.kept.iter_mut().find(|k| k.address == target) {
            if k.authority != authority {
                k.authority = authority;
                k.next_request = None;
            }
        } else {
            self.kept.push(Kept {
                address: target,
                authority,
                held: false,
                next_request: None,
                next_status: None,
                state: None,
                gained: 0,
                lost: 0,
            });
        }
    }

    /// Stops keeping `target` and gives its control back.
    pub fn release<I: Interface>(&mut self, ctx: &mut Context<'_, I>, target: Address) {
        self.kept.retain(|k| k.address != target);
        if ctx.has_control_of(target) {
            ctx.release_control(target);
        }
    }

    /// The components kept, with the authority asked with (`None`: the component's own)
    /// and whether control is held.
    pub fn kept(&self) -> impl Iterator<Item = (Address, Option<u8>, bool)> + '_ {
        self.kept.iter().map(|k| (k.address, k.authority, k.held))
    }

    /// Whether control of every kept component is held.
    pub fn holds_all(&self) -> bool {
        self.kept.iter().all(|k| k.held)
    }

    /// Whether control of `target` is held.
    pub fn holds(&self, target: Address) -> bool {
        self.kept.iter().any(|k| k.address == target && k.held)
    }

    /// The last core state `target` reported.
    pub fn state(&self, target: Address) -> Option<CoreState> {
        self.kept
            .iter()
            .find(|k| k.address == target)
            .and_then(|k| k.state)
    }

    /// How often control of `target` was gained and lost.
    pub fn counts(&self, target: Address) -> Option<(u32, u32)> {
        self.kept
            .iter()
            .find(|k| k.address == target)
            .map(|k| (k.gained, k.lost))
    }

    /// Compares what is held with what the runtime says, asks for control where it is
    /// missing and due, resumes what was just gained, queries status when due; returns
    /// what changed.
    pub fn tick<I: Interface>(&mut self, ctx: &mut Context<'_, I>) -> Vec<ControlEvent> {
        let now = ctx.now();
        let mut events = Vec::new();
        for k in &mut self.kept {
            let held = ctx.has_control_of(k.address);
            match (k.held, held) {
                (false, true) => {
                    k.held = true;
                    k.gained += 1;
                    events.push(ControlEvent::Gained(k.address));
                    if self.config.resume {
                        ctx.send_core(k.address, Resume {});
                    }
                    // Look at its state at once.
                    k.next_status = None;
                }
                (true, false) => {
                    k.held = false;
                    k.lost += 1;
                    events.push(ControlEvent::Lost(k.address));
                    k.next_request = Some(now + self.config.retry);
                }
                _ => {}
            }
            if !k.held && k.next_request.is_none_or(|t| now >= t) {
                k.next_request = Some(now + self.config.retry);
                match k.authority {
                    Some(a) => ctx.request_control_with(k.address, a),
                    None => ctx.request_control(k.address),
                }
            }
            if k.next_status.is_none_or(|t| now >= t) {
                k.next_status = Some(now + self.config.status_period);
                ctx.send_core(k.address, QueryComponentStatus {});
                if k.held {
                    // A component that restarted (a new process) no longer names this
                    // one as its controller: the runtime then drops the control held
                    // and the next tick asks for it again.
                    ctx.send_core(k.address, QueryComponentControl {});
                }
            }
        }
        events
    }

    /// Takes a Report Component Status from `source`; the event when its state changed.
    pub fn on_status(
        &mut self,
        source: Address,
        r: &ReportComponentStatus,
    ) -> Option<ControlEvent> {
        let k = self.kept.iter_mut().find(|k| k.address == source)?;
        let state = CoreState::from_wire(r.primary_status_code)?;
        (k.state.replace(state) != Some(state)).then_some(ControlEvent::State(source, state))
    }
}
