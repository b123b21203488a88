//! [`ProxyEndpoint`]: an RA 3.3 component of the proxy (the SDK's component runtime
//! around one of the proxy's behaviours) with what crosses to AS-4 besides its
//! messages: control and state (see the [module](super) documentation).
//!
//! The runtime would grant control at once; the endpoint holds a Request Component
//! Control of a driver back until the proxy holds AS-4 control of the vehicle's
//! component, then hands it on (the runtime confirms it, with its usual rules of
//! authority and preemption). Losing AS-4 control ends the RA 3.3 controller's control
//! (Reject Component Control, then [`Component::forget`]). The vehicle's AS-4 state
//! reaches the runtime as the core messages that cause the same change (Standby from
//! the controller; Set and Clear Emergency from an address of its own, instance 0,
//! which no real component has).

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::component::{Behaviour, Component, Endpoint, Outgoing};
use jaus::messages::{
    ClearEmergency, ClearEmergencyCode, ConfirmComponentControl, ControlResponse, EmergencyCode,
    Message as Ra33Message, RejectComponentControl, RequestComponentControl, SetEmergency, Standby,
};
use jaus::wire::Header;
use jaus::{Address, JausMessage};

use super::shared::{lock, As4Control, SharedRef};
use super::Role;
use crate::messages::{ComponentState, ControlConfirmation};

/// How long an RA 3.3 Request Component Control waits for AS-4 control.
pub const CONTROL_WAIT: Duration = Duration::from_secs(5);

/// A Request Component Control held back until AS-4 control is granted.
#[derive(Debug)]
struct Pending {
    header: Header,
    body: Vec<u8>,
    since: Instant,
}

/// One RA 3.3 component of a proxy (see the module's documentation).
#[derive(Debug)]
pub struct ProxyEndpoint<B: Behaviour> {
    inner: Component<B>,
    role: Role,
    shared: SharedRef,
    pending: Option<Pending>,
    outbox: VecDeque<Outgoing>,
    seen: Option<u64>,
    last_as4: Option<ComponentState>,
    raised: bool,
    now: Instant,
}

impl<B: Behaviour> ProxyEndpoint<B> {
    /// `inner`, presenting `role`, sharing `shared` with the proxy's AS-4 side, from
    /// `now` on.
    pub fn new(inner: Component<B>, role: Role, shared: SharedRef, now: Instant) -> Self {
        Self {
            inner,
            role,
            shared,
            pending: None,
            outbox: VecDeque::new(),
            seen: None,
            last_as4: None,
            raised: false,
            now,
        }
    }

    /// The component.
    pub fn component(&self) -> &Component<B> {
        &self.inner
    }

    /// The role it presents.
    pub fn role(&self) -> Role {
        self.role
    }

    /// Whether a Request Component Control waits for AS-4 control.
    pub fn control_pending(&self) -> bool {
        self.pending.is_some()
    }

    fn reply(&mut self, to: Address, m: impl Into<Ra33Message>) {
        let m: Ra33Message = m.into();
        self.outbox.push_back(Outgoing {
            header: Header::new(m.code(), to, self.inner.address()),
            name: m.name(),
            body: m.to_bytes(),
        });
    }

    /// Hands `m` to the runtime as if `from` had sent it.
    fn inject(&mut self, now: Instant, from: Address, m: impl Into<Ra33Message>) {
        let m: Ra33Message = m.into();
        match m.to_bytes() {
            Ok(body) => {
                let h = Header::new(m.code(), self.inner.address(), from);
                self.inner.handle(now, &h, &body);
            }
            Err(e) => tracing::warn!(message = m.name(), "not encoded: {e}"),
        }
    }

    /// The address the vehicle's own emergencies come from.
    fn vehicle_address(&self) -> Address {
        Address {
            instance: 0,
            ..self.inner.address()
        }
    }

    fn request(&mut self, now: Instant, header: &Header, body: &[u8]) {
        let (found, control) = {
            let s = lock(&self.shared);
            let at = s.service(self.role);
            (at.is_some(), at.map(|a| s.control(a)))
        };
        if !found {
            tracing::info!(role = ?self.role, from = %header.source, "control refused: the AS-4 service is not found");
            self.reply(
                header.source,
                ConfirmComponentControl {
                    response_code: ControlResponse::NotAvailable,
                },
            );
            return;
        }
        if control == Some(As4Control::Granted) {
            self.inner.handle(now, header, body);
            return;
        }
        let new = Pending {
            header: *header,
            body: body.to_vec(),
            since: now,
        };
        if let Some(old) = self.pending.replace(new) {
            if old.header.source != header.source {
                self.reply(
                    old.header.source,
                    ConfirmComponentControl {
                        response_code: ControlResponse::NotAvailable,
                    },
                );
            }
        }
        lock(&self.shared).want(self.role, true);
    }

    /// After the runtime handled something: AS-4 control is wanted while an RA 3.3
    /// client controls this driver or waits for it.
    fn settle(&mut self) {
        if !self.role.is_driver() {
            return;
        }
        let want = self.pending.is_some() || self.inner.controller().is_some();
        lock(&self.shared).want(self.role, want);
    }

    /// Carries what the AS-4 side learnt over: control granted, refused or lost, and
    /// the vehicle's state.
    fn sync(&mut self, now: Instant) {
        let (control, status, changes) = {
            let s = lock(&self.shared);
            let at = s.service(self.role);
            (
                at.map(|a| s.control(a)),
                at.and_then(|a| s.status(a)),
                s.changes(),
            )
        };
        self.seen = Some(changes);
        if !self.role.is_driver() {
            return;
        }
        if let Some(p) = &self.pending {
            let expired = now.saturating_duration_since(p.since) >= CONTROL_WAIT;
            match control {
                Some(As4Control::Granted) => {
                    if let Some(p) = self.pending.take() {
                        self.inner.handle(now, &p.header, &p.body);
                    }
                }
                Some(As4Control::Refused(code)) => {
                    let to = p.header.source;
                    self.pending = None;
                    let response_code = if code == ControlConfirmation::InsufficientAuthority {
                        ControlResponse::InsufficientAuthority
                    } else {
                        ControlResponse::NotAvailable
                    };
                    self.reply(to, ConfirmComponentControl { response_code });
                }
                _ if expired => {
                    let to = p.header.source;
                    self.pending = None;
                    tracing::warn!(role = ?self.role, %to, "no AS-4 control within {CONTROL_WAIT:?}");
                    self.reply(
                        to,
                        ConfirmComponentControl {
                            response_code: ControlResponse::NotAvailable,
                        },
                    );
                }
                _ => {}
            }
        }
        if let Some((c, _)) = self.inner.controller() {
            if control == Some(As4Control::Lost) && self.pending.is_none() {
                tracing::warn!(role = ?self.role, controller = %c, "AS-4 control lost: RA 3.3 control ends");
                self.reply(c, RejectComponentControl {});
                self.inner.forget(c);
            }
        }
        if status != self.last_as4 {
            let before = self.last_as4;
            self.last_as4 = status;
            self.follow(now, before, status);
        }
        self.settle();
    }

    /// The vehicle's component went from `before` to `after`: the runtime follows.
    fn follow(
        &mut self,
        now: Instant,
        before: Option<ComponentState>,
        after: Option<ComponentState>,
    ) {
        use jaus::component::CoreState;
        let mine = self.inner.state();
        let vehicle = self.vehicle_address();
        if after == Some(ComponentState::Emergency) {
            if mine != CoreState::Emergency {
                self.raised = true;
                self.inject(
                    now,
                    vehicle,
                    SetEmergency {
                        emergency_code: EmergencyCode {
                            transition_to_emergency: true,
                            ..EmergencyCode::default()
                        },
                    },
                );
            }
            return;
        }
        if before == Some(ComponentState::Emergency) && self.raised {
            self.raised = false;
            self.inject(
                now,
                vehicle,
                ClearEmergency {
                    emergency_code: ClearEmergencyCode {
                        clear_emergency: true,
                        ..ClearEmergencyCode::default()
                    },
                },
            );
        }
        if before == Some(ComponentState::Ready) && mine == CoreState::Ready {
            if let Some((c, _)) = self.inner.controller() {
                self.inject(now, c, Standby {});
            }
        }
    }

    fn urgent(&self) -> bool {
        !self.outbox.is_empty() || self.seen != Some(lock(&self.shared).changes())
    }
}

impl<B: Behaviour> Endpoint for ProxyEndpoint<B> {
    fn address(&self) -> Address {
        self.inner.address()
    }

    fn handle(&mut self, now: Instant, header: &Header, body: &[u8]) {
        self.now = self.now.max(now);
        let for_me = header.destination.matches(&self.inner.address());
        if for_me
            && self.role.is_driver()
            && header.command_code == RequestComponentControl::CODE
            && header.ack_nak == jaus::wire::AckNak::None
        {
            self.request(now, header, body);
        } else {
            self.inner.handle(now, header, body);
        }
        self.settle();
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.now = self.now.max(now);
        self.inner.handle_timeout(now);
        self.sync(now);
    }

    fn poll_transmit(&mut self) -> Option<Outgoing> {
        self.outbox
            .pop_front()
            .or_else(|| Endpoint::poll_transmit(&mut self.inner))
    }

    fn poll_timeout(&self) -> Option<Instant> {
        let urgent = self.urgent().then_some(self.now);
        let waiting = self.pending.as_ref().map(|p| p.since + CONTROL_WAIT);
        [self.inner.poll_timeout(), urgent, waiting]
            .into_iter()
            .flatten()
            .min()
    }

    fn forget(&mut self, gone: Address) {
        self.inner.forget(gone);
        if self
            .pending
            .as_ref()
            .is_some_and(|p| p.header.source == gone)
        {
            self.pending = None;
        }
        self.settle();
    }

    fn wall_clock(&mut self, now: Instant, utc: Duration) {
        self.inner.wall_clock(now, utc);
    }

    fn stats(&self) -> Option<jaus::component::Stats> {
        Some(self.inner.stats())
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}
