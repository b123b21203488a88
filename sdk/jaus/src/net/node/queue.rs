//! A node's buffers: the pool of byte buffers it reuses and the bounded queue of
//! datagrams waiting for its shell. Both are bounded; what does not fit is dropped and
//! counted by the caller.

use std::collections::VecDeque;

use super::super::framing::MAX_PACKET_BODY;
use crate::net::Datagram;
use crate::wire::HEADER_LEN;

/// Most byte buffers a node keeps for reuse.
const POOL_BUFFERS: usize = 256;
/// Largest buffer kept for reuse (bigger ones, of multi-packet messages, are freed).
const POOL_BUFFER_BYTES: usize = 8 + HEADER_LEN + MAX_PACKET_BODY + 64;

/// Byte buffers for bodies and datagrams, reused: the shell hands sent datagrams back,
/// so that routing a message allocates nothing once the pool is warm.
#[derive(Debug, Default)]
pub(crate) struct Pool {
    free: Vec<Vec<u8>>,
}

impl Pool {
    /// An empty buffer (a new one when the pool is empty).
    pub(crate) fn take(&mut self) -> Vec<u8> {
        self.free.pop().unwrap_or_default()
    }

    /// Keeps `bytes` for reuse, within the bounds.
    pub(crate) fn give(&mut self, mut bytes: Vec<u8>) {
        if self.free.len() < POOL_BUFFERS && bytes.capacity() <= POOL_BUFFER_BYTES {
            bytes.clear();
            self.free.push(bytes);
        }
    }

    /// The free buffers, for a component runtime that draws from them directly.
    pub(crate) fn buffers(&mut self) -> &mut Vec<Vec<u8>> {
        &mut self.free
    }
}

/// Datagrams waiting to be sent, at most `max`.
#[derive(Debug)]
pub(crate) struct Outbox<A> {
    queue: VecDeque<Datagram<A>>,
    max: usize,
}

/// The outbox was full: the datagram was dropped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Full;

impl<A> Outbox<A> {
    pub(crate) fn new(max: usize) -> Self {
        Self {
            queue: VecDeque::new(),
            max,
        }
    }

    /// Whether one more datagram fits.
    pub(crate) fn has_room(&self) -> bool {
        self.queue.len() < self.max
    }

    /// Queues `d`, or drops it when the outbox is full.
    pub(crate) fn push(&mut self, d: Datagram<A>) -> Result<(), Full> {
        if !self.has_room() {
            return Err(Full);
        }
        self.queue.push_back(d);
        Ok(())
    }

    /// The oldest datagram.
    pub(crate) fn pop(&mut self) -> Option<Datagram<A>> {
        self.queue.pop_front()
    }
}
