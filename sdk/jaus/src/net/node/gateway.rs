//! The node's side of its subsystem's Communicator (Part 1 §5.2.1, Figure 5-1): when
//! the communicator is on this node, messages leaving the subsystem are handed to its
//! endpoint packet by packet ([`Endpoint::gateway_send`](crate::component::Endpoint::gateway_send)) and the packets its data links
//! received ([`Endpoint::gateway_recv`](crate::component::Endpoint::gateway_recv)) are routed as if received. Any endpoint that
//! implements the two is a gateway; the network layer names no stock component.

use super::super::framing::{split, Framing, MAX_PACKET_BODY};
use super::super::PeerAddr;
use super::route::Origin;
use super::Node;
use crate::wire::{DataFlag, Header};
use crate::Address;

/// Most packets taken from the communicator's data links in one wake-up (the rest wait
/// for the next, which is due at once).
const MAX_LINK_PACKETS: usize = 1024;

impl<A: PeerAddr> Node<A> {
    /// Routes what this node's communicator received from its data links (bounded per
    /// wake-up).
    pub(super) fn drain_communicator(&mut self) {
        let Some(comm) = self.config.communicator else {
            return;
        };
        if comm.node != self.config.node || comm.subsystem != self.config.subsystem {
            return;
        }
        let now = self.now;
        for _ in 0..MAX_LINK_PACKETS {
            let buf = self.pool.take();
            let Some(e) = self.locals.endpoint_mut(comm) else {
                self.pool.give(buf);
                return;
            };
            let packet = match e.gateway_recv(now, buf) {
                Ok(p) => p,
                Err(buf) => {
                    self.pool.give(buf);
                    return;
                }
            };
            self.stats.from_communicator += 1;
            self.route_link_packet(comm, &packet);
            self.pool.give(packet);
            self.pump();
        }
    }

    /// One packet from another subsystem, through the communicator `comm`.
    fn route_link_packet(&mut self, comm: Address, packet: &[u8]) {
        let (header, body) = match Framing::Raw.packet(packet) {
            Ok(p) => p,
            Err(e) => {
                self.stats.bad_packet += 1;
                tracing::debug!(communicator = %comm, "packet from a data link dropped: {e}");
                return;
            }
        };
        let src = header.source;
        if src.subsystem == self.config.subsystem {
            // Our own traffic looped back by a link.
            self.stats.from_self += 1;
            return;
        }
        if !src.is_valid() || src.subsystem == 255 || src.node == 255 {
            self.stats.bad_packet += 1;
            tracing::debug!(communicator = %comm, source = %src, code = %header.command_code,
                "packet from a data link dropped: bad source address");
            return;
        }
        if header.data_flag == DataFlag::Single {
            self.route_borrowed(header, body, Origin::Link);
        } else if let Some((header, body)) = self.reassembler.push(self.now, &header, body) {
            self.route(header, body, Origin::Link);
        }
    }

    /// Hands a message leaving the subsystem to the communicator `comm` on this node,
    /// packet by packet.
    pub(super) fn send_gateway(&mut self, comm: Address, header: &Header, body: &[u8]) {
        if body.len() <= MAX_PACKET_BODY {
            let mut bytes = self.pool.take();
            match Framing::Raw.write_packet(&mut bytes, header, body) {
                Ok(()) => self.gateway_packet(comm, header, &bytes),
                Err(e) => {
                    self.stats.encode_errors += 1;
                    tracing::warn!(code = %header.command_code, destination = %header.destination, "not sent: {e}");
                }
            }
            self.pool.give(bytes);
            return;
        }
        match split(header, body) {
            Ok(packets) => {
                for p in &packets {
                    self.gateway_packet(comm, header, p);
                }
            }
            Err(e) => {
                self.stats.encode_errors += 1;
                tracing::warn!(code = %header.command_code, destination = %header.destination, "not sent: {e}");
            }
        }
    }

    fn gateway_packet(&mut self, comm: Address, header: &Header, packet: &[u8]) {
        let now = self.now;
        let taken = self
            .locals
            .endpoint_mut(comm)
            .is_some_and(|e| e.gateway_send(now, packet));
        if taken {
            self.stats.to_communicator += 1;
        } else {
            self.stats.no_such_component += 1;
            tracing::debug!(communicator = %comm, code = %header.command_code, destination = %header.destination,
                "not sent to another subsystem: the communicator is not a gateway on this node");
        }
    }
}
