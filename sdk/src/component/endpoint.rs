//! [`Endpoint`]: the interface through which a node or a [`LocalBus`] drives any
//! component it hosts, and its implementation for [`Component`].
//!
//! [`LocalBus`]: super::local::LocalBus

use std::any::Any;
use std::time::Instant;

use super::{Behaviour, Component, Transmit};
use crate::{Address, Header};

/// Anything a node or a [`LocalBus`](super::local::LocalBus) hosts: a [`Component`] (of
/// any behaviour) or a test [`Probe`](super::local::Probe). The node and the bus drive it
/// through this trait alone.
pub trait Endpoint: Send + 'static {
    /// Its address.
    fn address(&self) -> Address;
    /// A message arrives.
    fn handle(&mut self, now: Instant, header: &Header, body: &[u8]);
    /// Time passes.
    fn handle_timeout(&mut self, now: Instant);
    /// Something to send.
    fn poll_transmit(&mut self) -> Option<Transmit>;
    /// When to be woken next.
    fn poll_timeout(&self) -> Option<Instant>;
    /// A component this endpoint may have dealt with is gone (the node layer saw it
    /// time out): end control, service connections and events involving it.
    fn forget(&mut self, gone: Address) {
        let _ = gone;
    }
    /// For [`LocalBus::get`](super::local::LocalBus::get).
    fn as_any(&self) -> &dyn Any;
    /// For [`LocalBus::get_mut`](super::local::LocalBus::get_mut).
    fn as_any_mut(&mut self) -> &mut dyn Any;
}

impl<B: Behaviour> Endpoint for Component<B> {
    fn address(&self) -> Address {
        Component::address(self)
    }
    fn handle(&mut self, now: Instant, header: &Header, body: &[u8]) {
        Component::handle(self, now, header, body);
    }
    fn handle_timeout(&mut self, now: Instant) {
        Component::handle_timeout(self, now);
    }
    fn poll_transmit(&mut self) -> Option<Transmit> {
        Component::poll_transmit(self)
    }
    fn poll_timeout(&self) -> Option<Instant> {
        Component::poll_timeout(self)
    }
    fn forget(&mut self, gone: Address) {
        Component::forget(self, gone);
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}
