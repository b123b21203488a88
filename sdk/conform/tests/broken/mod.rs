//! Components that break one rule each, built by wrapping a stock component's
//! endpoint: the tester must fail exactly the checks citing that rule. Shared by two test
//! crates, each using some of it.
#![allow(dead_code)]

use std::any::Any;
use std::time::Instant;

use jaus::component::{Endpoint, Outgoing};
use jaus::wire::MessageClass;
use jaus::{Address, CommandCode, Header};

/// Carries out commands from anyone: a command from a component not in control is
/// handed to the component as if the controller had sent it (breaks "controller-only").
pub struct AnyoneCommands {
    inner: Box<dyn Endpoint>,
    controller: Option<Address>,
}

impl AnyoneCommands {
    /// Wraps `inner`.
    pub fn new(inner: Box<dyn Endpoint>) -> Self {
        Self {
            inner,
            controller: None,
        }
    }
}

/// Commands every sender may give (control, emergencies, service connections, events).
fn open_to_all(code: CommandCode) -> bool {
    matches!(code.0, 0x0006..=0x0010 | 0x01F0..=0x01FF)
}

impl Endpoint for AnyoneCommands {
    fn address(&self) -> Address {
        self.inner.address()
    }
    fn handle(&mut self, now: Instant, header: &Header, body: &[u8]) {
        let mut h = *header;
        if let Some(c) = self.controller {
            if h.command_code.class() == MessageClass::Command
                && !open_to_all(h.command_code)
                && h.source != c
            {
                h.source = c;
            }
        }
        if h.command_code.0 == 0x000E && Some(h.source) == self.controller {
            self.controller = None;
        }
        self.inner.handle(now, &h, body);
    }
    fn handle_timeout(&mut self, now: Instant) {
        self.inner.handle_timeout(now);
    }
    fn poll_transmit(&mut self) -> Option<Outgoing> {
        let t = self.inner.poll_transmit()?;
        match t.header.command_code.0 {
            // Confirm Component Control, Control Accepted.
            0x000F if t.body.as_ref().is_ok_and(|b| b.first() == Some(&0)) => {
                self.controller = Some(t.header.destination);
            }
            0x0010 if Some(t.header.destination) == self.controller => self.controller = None,
            _ => {}
        }
        Some(t)
    }
    fn poll_timeout(&self) -> Option<Instant> {
        self.inner.poll_timeout()
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

/// Never answers one query: the query is dropped on arrival (breaks the read-back of
/// the commands that query reads back).
pub struct Mute {
    inner: Box<dyn Endpoint>,
    query: CommandCode,
}

impl Mute {
    /// Wraps `inner`, deaf to `query`.
    pub fn new(inner: Box<dyn Endpoint>, query: CommandCode) -> Self {
        Self { inner, query }
    }
}

impl Endpoint for Mute {
    fn address(&self) -> Address {
        self.inner.address()
    }
    fn handle(&mut self, now: Instant, header: &Header, body: &[u8]) {
        if header.command_code != self.query {
            self.inner.handle(now, header, body);
        }
    }
    fn handle_timeout(&mut self, now: Instant) {
        self.inner.handle_timeout(now);
    }
    fn poll_transmit(&mut self) -> Option<Outgoing> {
        self.inner.poll_transmit()
    }
    fn poll_timeout(&self) -> Option<Instant> {
        self.inner.poll_timeout()
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

/// Sends the reports of its service connections without the service-connection flag
/// (breaks "service-connections").
pub struct Unflagged(pub Box<dyn Endpoint>);

impl Endpoint for Unflagged {
    fn address(&self) -> Address {
        self.0.address()
    }
    fn handle(&mut self, now: Instant, header: &Header, body: &[u8]) {
        self.0.handle(now, header, body);
    }
    fn handle_timeout(&mut self, now: Instant) {
        self.0.handle_timeout(now);
    }
    fn poll_transmit(&mut self) -> Option<Outgoing> {
        let mut t = self.0.poll_transmit()?;
        t.header.service_connection = false;
        Some(t)
    }
    fn poll_timeout(&self) -> Option<Instant> {
        self.0.poll_timeout()
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}
