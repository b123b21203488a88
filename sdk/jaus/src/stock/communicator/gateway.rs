//! [`CommunicatorEndpoint`]: the Communicator component as a node hosts it, the node's
//! gateway to other subsystems (Part 1 Figure 5-1).

use std::any::Any;
use std::time::Instant;

use super::component::StockCommunicator;
use crate::component::{Component, Config, Endpoint, Outgoing, Stats};
use crate::components::communicator;
use crate::link::DataLink;
use crate::{Address, Header};

/// The Communicator under the component runtime.
pub type CommunicatorComponent<L> = Component<communicator::Dispatch<StockCommunicator<L>>>;

/// A [`StockCommunicator`] hosted as a component that is also a gateway
/// ([`Endpoint::gateway_send`] / [`Endpoint::gateway_recv`]): add it to a node whose
/// `NodeConfig::communicator` names its address, and the node hands it every packet for
/// another subsystem and routes every packet its links receive.
///
/// ```
/// use std::time::Instant;
/// use jaus::component::Config;
/// use jaus::net::{Node, NodeConfig};
/// use jaus::stock::communicator::{CommunicatorConfig, CommunicatorEndpoint, DataLink, LinkError, StockCommunicator};
/// use jaus::Address;
///
/// /// A link that hears nothing and loses everything.
/// struct Void;
/// impl DataLink for Void {
///     fn id(&self) -> u8 { 1 }
///     fn send(&mut self, _: Instant, _: &[u8]) -> Result<(), LinkError> { Ok(()) }
///     fn recv(&mut self, _: Instant, _: &mut Vec<u8>) -> bool { false }
///     fn is_up(&self, _: Instant) -> bool { true }
/// }
///
/// let t0 = Instant::now();
/// let me = Address::new(1, 1, 35, 1);
/// let mut node = Node::new(NodeConfig { communicator: Some(me), ..NodeConfig::default() }, t0);
/// let stock = StockCommunicator::new(vec![Void], CommunicatorConfig::default(), t0).unwrap();
/// node.add(CommunicatorEndpoint::new(me, stock, Config::default(), t0)).unwrap();
/// ```
pub struct CommunicatorEndpoint<L: DataLink> {
    component: CommunicatorComponent<L>,
}

impl<L: DataLink> std::fmt::Debug for CommunicatorEndpoint<L> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CommunicatorEndpoint")
            .field("address", &self.component.address())
            .field("selected", &self.communicator().selected())
            .finish()
    }
}

impl<L: DataLink> CommunicatorEndpoint<L> {
    /// The Communicator `stock` at `address` under the runtime with `config`, from `now`.
    pub fn new(
        address: Address,
        stock: StockCommunicator<L>,
        config: Config,
        now: Instant,
    ) -> Self {
        Self {
            component: communicator::component(address, stock, config, now),
        }
    }

    /// The component (its runtime state and counters).
    pub fn component(&self) -> &CommunicatorComponent<L> {
        &self.component
    }

    /// The component, mutably.
    pub fn component_mut(&mut self) -> &mut CommunicatorComponent<L> {
        &mut self.component
    }

    /// The Communicator (link states, selection, counters).
    pub fn communicator(&self) -> &StockCommunicator<L> {
        &self.component.behaviour().0
    }

    /// The Communicator, mutably.
    pub fn communicator_mut(&mut self) -> &mut StockCommunicator<L> {
        &mut self.component.behaviour_mut().0
    }
}

impl<L: DataLink> Endpoint for CommunicatorEndpoint<L> {
    fn address(&self) -> Address {
        self.component.address()
    }

    fn handle(&mut self, now: Instant, header: &Header, body: &[u8]) {
        self.component.handle(now, header, body);
    }

    fn handle_timeout(&mut self, now: Instant) {
        if self.component.poll_timeout().is_some_and(|t| t <= now) {
            self.component.handle_timeout(now);
        }
        self.communicator_mut().service(now);
    }

    fn poll_transmit(&mut self) -> Option<Outgoing> {
        Endpoint::poll_transmit(&mut self.component)
    }

    fn poll_transmit_with(&mut self, buf: Vec<u8>) -> Result<Outgoing, Vec<u8>> {
        Endpoint::poll_transmit_with(&mut self.component, buf)
    }

    fn poll_timeout(&self) -> Option<Instant> {
        let c = self.component.poll_timeout();
        let l = self.communicator().poll_timeout();
        match (c, l) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }

    fn forget(&mut self, gone: Address) {
        self.component.forget(gone);
    }

    fn stats(&self) -> Option<Stats> {
        Some(self.component.stats())
    }

    fn gateway_send(&mut self, now: Instant, packet: &[u8]) -> bool {
        self.communicator_mut().forward(now, packet);
        true
    }

    fn gateway_recv(&mut self, now: Instant, buf: Vec<u8>) -> Result<Vec<u8>, Vec<u8>> {
        self.communicator_mut().receive(now, buf)
    }

    fn as_any(&self) -> &dyn Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}
