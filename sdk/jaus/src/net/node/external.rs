//! Components of a node in other processes: they share the node's carrier (or
//! OpenJAUS's component sockets) and are known by the traffic they send. The table is
//! bounded ([`NodeConfig::max_external`](super::NodeConfig::max_external)); a component
//! silent for the timeout is removed; an address handed out by an OpenJAUS check-in is
//! held until the component is heard or checks out.

use std::collections::HashMap;
use std::time::{Duration, Instant};

use crate::net::Via;
use crate::Address;

/// An external component: where it is, when it was last heard, the socket of the node
/// that reaches it.
#[derive(Debug, Clone, Copy)]
struct Entry<A> {
    at: A,
    heard: Instant,
    via: Via,
}

/// The external-component table of a node.
#[derive(Debug)]
pub(crate) struct Externals<A> {
    table: HashMap<Address, Entry<A>>,
    /// Addresses given out by OpenJAUS check-ins, until the component is heard or
    /// checks out (→ when given).
    checked_in: HashMap<Address, Instant>,
    max: usize,
    timeout: Duration,
}

/// What hearing from an external component did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Heard {
    /// It was known; its place and time are updated.
    Known,
    /// It is new and now registered.
    Joined,
    /// It is new and the table is full.
    Full,
}

impl<A: Copy + PartialEq> Externals<A> {
    pub(crate) fn new(max: usize, timeout: Duration) -> Self {
        Self {
            table: HashMap::new(),
            checked_in: HashMap::new(),
            max,
            timeout,
        }
    }

    /// `src` was heard at `now` from `at` through `via`.
    pub(crate) fn heard(&mut self, now: Instant, src: Address, at: A, via: Via) -> Heard {
        let entry = Entry {
            at,
            heard: now,
            via,
        };
        if let Some(e) = self.table.get_mut(&src) {
            *e = entry;
            return Heard::Known;
        }
        if self.table.len() >= self.max {
            return Heard::Full;
        }
        self.checked_in.remove(&src);
        self.table.insert(src, entry);
        Heard::Joined
    }

    /// Removes and returns the components silent for the timeout at `now` (and forgets
    /// check-ins never followed by a packet within twice the timeout).
    pub(crate) fn expire(&mut self, now: Instant) -> Vec<Address> {
        let limit = self.timeout;
        self.checked_in
            .retain(|_, t| now.saturating_duration_since(*t) < limit * 2);
        let gone: Vec<Address> = self
            .table
            .iter()
            .filter(|(_, e)| now.saturating_duration_since(e.heard) >= limit)
            .map(|(a, _)| *a)
            .collect();
        for a in &gone {
            self.table.remove(a);
        }
        gone
    }

    /// When the next component times out.
    pub(crate) fn next_timeout(&self) -> Option<Instant> {
        self.table.values().map(|e| e.heard + self.timeout).min()
    }

    /// Whether `a` is an external component here.
    pub(crate) fn contains(&self, a: &Address) -> bool {
        self.table.contains_key(a)
    }

    /// Whether `a` is neither an external component nor held by a check-in.
    pub(crate) fn is_free(&self, a: &Address) -> bool {
        !self.table.contains_key(a) && !self.checked_in.contains_key(a)
    }

    /// Holds `a` for a component that checked in at `now`.
    pub(crate) fn check_in(&mut self, now: Instant, a: Address) {
        self.checked_in.insert(a, now);
    }

    /// `a` checked out; true if it was a registered component.
    pub(crate) fn check_out(&mut self, a: &Address) -> bool {
        self.checked_in.remove(a);
        self.table.remove(a).is_some()
    }

    pub(crate) fn is_empty(&self) -> bool {
        self.table.is_empty()
    }

    /// Every external component and where it is.
    pub(crate) fn iter(&self) -> impl Iterator<Item = (Address, A)> + '_ {
        self.table.iter().map(|(a, e)| (*a, e.at))
    }

    /// Where a message to `d` from `source` goes among the external components (not
    /// back to its sender).
    pub(crate) fn targets(&self, d: Address, source: Address) -> Vec<(A, Via)> {
        self.table
            .iter()
            .filter(|(a, _)| d.matches(a) && source != **a)
            .map(|(_, e)| (e.at, e.via))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounded_refreshed_and_expired() {
        let t0 = Instant::now();
        let s = Duration::from_secs(1);
        let mut x = Externals::new(2, Duration::from_secs(3));
        let (a, b, c) = (
            Address::new(1, 1, 40, 1),
            Address::new(1, 1, 41, 1),
            Address::new(1, 1, 42, 1),
        );
        assert_eq!(x.heard(t0, a, 7u8, Via::Network), Heard::Joined);
        assert_eq!(x.heard(t0 + s, b, 8, Via::Network), Heard::Joined);
        assert_eq!(x.heard(t0 + s, c, 9, Via::Network), Heard::Full);
        assert_eq!(x.heard(t0 + 2 * s, a, 7, Via::Network), Heard::Known);
        assert_eq!(x.next_timeout(), Some(t0 + 4 * s));
        assert_eq!(x.expire(t0 + 4 * s), vec![b]);
        assert!(x.contains(&a) && !x.contains(&b));
        x.check_in(t0, c);
        assert!(!x.is_free(&c));
        assert!(!x.check_out(&c));
        assert!(x.is_free(&c));
    }
}
