//! The node as OpenJAUS's node manager for component processes on the same machine
//! (docs/wire.md §8.5): the control socket (check-in, check-out, lookups in the system
//! tree) and the data socket (raw packets of those components). What the datagrams
//! mean is in [`oj`](super::super::oj); here the node answers and routes them.

use std::time::Instant;

use super::super::framing::Framing;
use super::super::oj::{matches_wildcard, Control};
use super::super::PeerAddr;
use super::route::Origin;
use super::Node;
use crate::net::{Datagram, Via};
use crate::Address;

impl<A: PeerAddr> Node<A> {
    /// A control datagram on OpenJAUS's component control socket (port 24627) from
    /// `peer` (docs/wire.md §8.5): check-in (an address for a component id: this node's
    /// subsystem and node, the lowest free instance), check-out, and lookups in the
    /// system tree; the answer goes back to `peer` through [`Via::ComponentControl`].
    /// Anything else is counted as a bad packet and dropped.
    pub fn handle_component_control(&mut self, now: Instant, peer: A, datagram: &[u8]) {
        self.advance(now);
        self.stats.received += 1;
        let request = match Control::decode(datagram) {
            Ok(c) => c,
            Err(e) => {
                self.stats.bad_packet += 1;
                tracing::debug!(%peer, "OpenJAUS control datagram dropped: {e}");
                return;
            }
        };
        let tree = self.manager.tree();
        let known = |a: Address| tree.components().contains(&a);
        let reply = match request {
            Control::CheckIn { component, .. } => {
                // Like OpenJAUS: no answer when the id is not a component's or no
                // instance is free.
                if component < 2 || component == 255 {
                    None
                } else {
                    let (ss, node) = (self.config.subsystem, self.config.node);
                    let free = (1..=254u8)
                        .map(|i| Address::new(ss, node, component, i))
                        .find(|a| !self.locals.contains(*a) && self.external.is_free(a));
                    free.map(|a| {
                        self.external.check_in(self.now, a);
                        tracing::info!(component = %a, %peer, "OpenJAUS component checked in");
                        Control::ReportAddress(a)
                    })
                }
            }
            Control::CheckOut(a) => {
                if self.external.check_out(&a) {
                    self.manager.remove_local(a);
                    tracing::info!(component = %a, "OpenJAUS component checked out");
                }
                None
            }
            Control::VerifyAddress(a) => Some(Control::AddressVerified(known(a))),
            Control::GetComponentAddressList { component } => Some(Control::ComponentAddressList(
                tree.components()
                    .into_iter()
                    .find(|a| a.component == component),
            )),
            Control::LookupAddress(pattern) => {
                let found = tree
                    .components()
                    .into_iter()
                    .find(|a| matches_wildcard(pattern, *a));
                Some(Control::LookupAddressResponse {
                    address: found.unwrap_or(pattern),
                    valid: found.is_some(),
                })
            }
            Control::LookupServiceAddress { code, output } => {
                let found = tree.components().into_iter().find(|a| {
                    tree.component(*a).is_some_and(|c| {
                        let list = if output { &c.outputs } else { &c.inputs };
                        list.contains(&code.0)
                    })
                });
                Some(Control::LookupServiceAddressResponse {
                    address: found.unwrap_or(Address::new(0, 0, 0, 0)),
                    found: found.is_some(),
                })
            }
            Control::ReadyCheck => Some(Control::ReportReady),
            // Answers are what a node manager sends, not what it takes.
            Control::ReportAddress(_)
            | Control::AddressVerified(_)
            | Control::ComponentAddressList(_)
            | Control::LookupAddressResponse { .. }
            | Control::LookupServiceAddressResponse { .. }
            | Control::ReportReady => {
                self.stats.bad_packet += 1;
                None
            }
        };
        if let Some(r) = reply {
            let d = Datagram {
                to: peer,
                bytes: r.encode().to_vec(),
                via: Via::ComponentControl,
            };
            if self.outbox.push(d).is_err() {
                self.stats.outbox_full += 1;
            }
        }
    }

    /// A raw JAUS packet on OpenJAUS's component data socket (port 24629) from `peer`:
    /// a component of this node in another process (checked in, or any id this node
    /// does not host), which is registered at `peer` and routed like a built-in
    /// component; messages for it go back raw through [`Via::ComponentData`].
    pub fn handle_component_data(&mut self, now: Instant, peer: A, datagram: &[u8]) {
        self.advance(now);
        self.stats.received += 1;
        let (header, body) = match Framing::Raw.packet(datagram) {
            Ok(p) => p,
            Err(e) => {
                self.stats.bad_packet += 1;
                tracing::debug!(%peer, "component datagram dropped: {e}");
                return;
            }
        };
        let src = header.source;
        let mine = src.subsystem == self.config.subsystem && src.node == self.config.node;
        if !mine || !self.accept_external(now, src, peer, Via::ComponentData) {
            self.stats.bad_packet += 1;
            return;
        }
        let Some((header, body)) = self.reassembler.message(now, &header, body) else {
            return;
        };
        self.route(header, body, Origin::Local);
        self.pump();
    }
}
