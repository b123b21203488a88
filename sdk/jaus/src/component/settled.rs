//! How a command a component sent ended, when its node makes commands arrive
//! (`jaus::net::NodeConfig::reliable`, issue 48): the node hands the outcome back to the
//! component that sent the command ([`Endpoint::settled`](super::Endpoint::settled)),
//! which keeps a bounded queue of them for its behaviour
//! ([`Context::take_settled`](super::Context::take_settled)).
//!
//! The type lives here, not in `jaus::net::reliable`, because components (the stock
//! ones, the spooler) are built without the network layer too.

use std::time::Duration;

use crate::{Address, CommandCode};

/// How a message sent with an acknowledgement requested ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Outcome {
    /// The peer acknowledged it (ACK).
    Acknowledged,
    /// The peer refused it (NAK): it arrived and was not carried out.
    Refused,
    /// No answer after every attempt: it may or may not have arrived.
    GaveUp,
}

impl std::fmt::Display for Outcome {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Outcome::Acknowledged => "acknowledged",
            Outcome::Refused => "refused",
            Outcome::GaveUp => "given up (no answer)",
        })
    }
}

/// The end of one command a component sent to a component of another node, as its
/// node's reliable delivery learnt it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Settled {
    /// The command's destination.
    pub to: Address,
    /// Its command code.
    pub code: CommandCode,
    /// Its sequence number (the component's own when it numbered it,
    /// [`Context::forward_numbered`](super::Context::forward_numbered); else the node's).
    pub sequence: u16,
    /// How it ended.
    pub outcome: Outcome,
    /// Copies sent.
    pub attempts: u32,
    /// From the first copy to the end.
    pub elapsed: Duration,
    /// Whether the destination has acknowledged anything so far (a peer that does
    /// drops retransmissions, so sending the command again is carried out once).
    pub peer_known: bool,
}

/// Most outcomes a component keeps for its behaviour (the oldest go first, counted in
/// [`Stats::settled_dropped`](super::Stats::settled_dropped)).
pub const MAX_SETTLED: usize = 1024;
