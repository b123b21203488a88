//! What became of each delivery (issue 48): the mission messages and Spool Mission
//! batches the spooler sends to components of other nodes go under sequence numbers of
//! its own ([`Context::forward_numbered`](crate::component::Context::forward_numbered)).
//! When its node makes commands arrive (`jaus::net::NodeConfig::reliable`), the node
//! asks for an acknowledgement, resends until one comes, and hands the outcome back
//! ([`Context::take_settled`](crate::component::Context::take_settled)); the spooler takes
//! the outcomes at every tick:
//!
//! * **Acknowledged**: delivered; counted.
//! * **Refused** (NAK: the destination had it and did not carry it out): the mission is
//!   paused, the reason kept ([`StockMissionSpooler::pause_reason`], logged as a
//!   warning, reported to the mission's owner as Report Mission Status "paused"), and
//!   the refused messages are put back as not sent: Resume Mission sends them again,
//!   Replace Messages or Remove Messages can change them first. (When the outcome of
//!   a mission's last delivery comes after the mission finished, the mission becomes
//!   pending again, reported "pending", and Run Mission sends what failed.)
//! * **Given up** (no answer after every attempt): to a destination that has
//!   acknowledged something before (it answers, and drops retransmissions), the same
//!   message is sent again under the same sequence number, so that a destination that
//!   did get it carries it out once, up to [`SpoolerConfig::max_deliveries`] times; then
//!   the mission is paused as for a refusal. To a destination never heard acknowledging
//!   (OpenJAUS 3.3's components send no ACK/NAK, and carry out every copy), nothing is
//!   sent again: the message went as it always did, and is counted as unconfirmed.
//!
//! A destination the node knows never to acknowledge gets its messages once, as
//! before, and no outcome comes back; neither does one when the node does not make
//! commands arrive. A delivery waits for its outcome [`OUTCOME_TIMEOUT`] at most, and
//! at most [`MAX_AWAITING`] wait (the oldest is forgotten first); both are counted
//! ([`DeliveryStats`]). Deliveries on the spooler's own node are not tracked (nothing is
//! lost between components of one node).

use std::collections::{HashMap, HashSet, VecDeque};
use std::time::{Duration, Instant};

use super::mission::{ItemState, MissionState};
use super::StockMissionSpooler;
use crate::component::{Outcome, Settled};
use crate::components::mission_spooler::{Ctx, Transition};
use crate::messages::*;
use crate::{Address, CommandCode};

/// How long a delivery waits for its outcome (longer than the node's retries of one
/// message, about 6 s, plus time held behind earlier ones).
pub const OUTCOME_TIMEOUT: Duration = Duration::from_secs(60);

/// Most deliveries waiting for their outcome.
pub const MAX_AWAITING: usize = 4096;

/// What became of the deliveries to other nodes ([`StockMissionSpooler::delivery_stats`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct DeliveryStats {
    /// Deliveries to other nodes (mission messages, Spool Mission batches) under the
    /// spooler's own sequence numbers.
    pub tracked: u64,
    /// Acknowledged by their destination.
    pub acknowledged: u64,
    /// Refused by their destination (the mission paused).
    pub refused: u64,
    /// Given up by the node (no answer after every attempt).
    pub given_up: u64,
    /// Sent again after being given up (same sequence number).
    pub redelivered: u64,
    /// Given up to a destination never heard acknowledging: not sent again.
    pub unconfirmed: u64,
    /// Refusals of deliveries sent without control of the destination, sent again
    /// once control was asked for again (counted in `refused` too).
    pub resent_refused: u64,
    /// Missions paused because a delivery was refused or given up too often.
    pub paused: u64,
    /// No outcome within [`OUTCOME_TIMEOUT`] (the node does not make commands arrive,
    /// or the destination never acknowledges): forgotten.
    pub no_outcome: u64,
    /// Forgotten because [`MAX_AWAITING`] waited already.
    pub forgotten_full: u64,
}

/// One delivery waiting for its outcome.
#[derive(Debug)]
struct Awaiting {
    mission: u16,
    /// The uids of the mission messages it carries.
    uids: Vec<u16>,
    /// What was sent (sent again as it was).
    message: Message,
    sent: Instant,
    /// Times sent (1 for the first delivery).
    deliveries: u32,
    /// Whether the spooler held control of the destination when it sent it.
    controlled: bool,
}

/// The deliveries waiting for their outcome, by (destination, command code, sequence
/// number), and the reasons of the missions they paused.
#[derive(Debug, Default)]
pub(super) struct Outcomes {
    awaiting: HashMap<(Address, CommandCode, u16), Awaiting>,
    order: VecDeque<(Instant, (Address, CommandCode, u16))>,
    reasons: HashMap<u16, String>,
    /// Destinations whose outcomes the node reports (it tracks commands to them, and
    /// they answer): a mission waits for its deliveries to them before it finishes.
    answering: HashSet<Address>,
    /// Refusals of messages sent without control, by (mission, uid).
    refusals: HashMap<(u16, u16), u32>,
    stats: DeliveryStats,
}

fn other_node(me: Address, to: Address) -> bool {
    to.subsystem != me.subsystem || to.node != me.node
}

impl StockMissionSpooler {
    /// What became of the deliveries to other nodes.
    pub fn delivery_stats(&self) -> DeliveryStats {
        self.outcomes.stats
    }

    /// Why mission `id` was paused by a delivery (refused, or never acknowledged),
    /// until it is resumed, run or removed.
    pub fn pause_reason(&self, id: u16) -> Option<&str> {
        self.outcomes.reasons.get(&id).map(String::as_str)
    }

    /// Sends `message` (carrying mission `mission`'s messages `uids`) to `to`: under a
    /// sequence number of the spooler's own, and remembered for its outcome, when `to`
    /// is on another node.
    pub(super) fn deliver(
        &mut self,
        ctx: &mut Ctx<'_>,
        mission: u16,
        to: Address,
        uids: Vec<u16>,
        message: Message,
    ) {
        if !other_node(ctx.address(), to) {
            ctx.forward(to, message);
            return;
        }
        let now = ctx.now();
        let code = message.code();
        let controlled = ctx.has_control_of(to);
        let seq = ctx.forward_numbered(to, message.clone());
        self.outcomes.stats.tracked += 1;
        self.outcomes.remember(
            now,
            (to, code, seq),
            Awaiting {
                mission,
                uids,
                message,
                sent: now,
                deliveries: 1,
                controlled,
            },
        );
    }

    /// A resumed, run or removed mission has no pause reason any more.
    pub(super) fn clear_reason(&mut self, id: u16) {
        self.outcomes.reasons.remove(&id);
        self.outcomes.refusals.retain(|(m, _), _| *m != id);
    }

    /// Whether mission `id` has deliveries whose outcome is still to come (from
    /// destinations known to report one): it is not finished before they settle.
    pub(super) fn unsettled(&self, id: u16) -> bool {
        self.outcomes
            .awaiting
            .iter()
            .any(|((to, _, _), a)| a.mission == id && self.outcomes.answering.contains(to))
    }

    /// Takes the outcomes the node handed back (see the module's documentation).
    pub(super) fn take_outcomes(&mut self, ctx: &mut Ctx<'_>) {
        let now = ctx.now();
        self.outcomes.expire(now);
        while let Some(s) = ctx.take_settled() {
            self.settled(ctx, now, s);
        }
    }

    fn settled(&mut self, ctx: &mut Ctx<'_>, now: Instant, s: Settled) {
        let key = (s.to, s.code, s.sequence);
        if s.peer_known && self.outcomes.answering.len() < MAX_AWAITING {
            self.outcomes.answering.insert(s.to);
        }
        // Outcomes of other commands (control requests) are not the spooler's concern.
        let Some(mut a) = self.outcomes.awaiting.remove(&key) else {
            return;
        };
        let name = a.message.name();
        // Still being sent (not reported finished): messages put back go again.
        let going = self
            .missions
            .get(&a.mission)
            .is_some_and(|m| matches!(m.state, MissionState::Running | MissionState::Paused));
        match s.outcome {
            Outcome::Acknowledged => {
                self.outcomes.stats.acknowledged += 1;
                if !self.outcomes.refusals.is_empty() {
                    for u in &a.uids {
                        self.outcomes.refusals.remove(&(a.mission, *u));
                    }
                }
            }
            Outcome::Refused if !a.controlled && going && self.refused_again(&a) => {
                // Sent without control (the destination did not confirm the control
                // request within the probe timeout): control is asked for again, and
                // the messages go again once it is had (or the probe timeout passes).
                self.outcomes.stats.refused += 1;
                self.outcomes.stats.resent_refused += 1;
                tracing::info!(mission = a.mission, uids = ?a.uids, message = name, destination = %s.to,
                    "mission delivery refused while not in control of the destination: control asked for again, then sent again");
                self.repend(&a);
                self.control_asked.remove(&s.to);
                self.touch(a.mission);
            }
            Outcome::Refused => {
                self.outcomes.stats.refused += 1;
                let reason = format!(
                    "{name} (message uids {:?}) refused by {} (NAK)",
                    a.uids, s.to
                );
                self.pause_for(ctx, &a, reason);
            }
            Outcome::GaveUp if !s.peer_known => {
                self.outcomes.stats.given_up += 1;
                self.outcomes.stats.unconfirmed += 1;
                tracing::info!(mission = a.mission, uids = ?a.uids, message = name, destination = %s.to,
                    attempts = s.attempts, "mission delivery not acknowledged; the destination never acknowledges, so it is not sent again");
            }
            Outcome::GaveUp => {
                self.outcomes.stats.given_up += 1;
                let running = self
                    .missions
                    .get(&a.mission)
                    .is_some_and(|m| m.state == MissionState::Running);
                if a.deliveries < self.config.max_deliveries.max(1) && running {
                    tracing::warn!(mission = a.mission, uids = ?a.uids, message = name, destination = %s.to,
                        attempts = s.attempts, delivery = a.deliveries, "mission delivery given up: sent again");
                    self.outcomes.stats.redelivered += 1;
                    ctx.forward_again(s.to, a.message.clone(), s.sequence);
                    a.deliveries += 1;
                    a.sent = now;
                    self.outcomes.remember(now, key, a);
                } else {
                    let reason = format!(
                        "{name} (message uids {:?}) to {}: no acknowledgement after {} deliveries of {} copies",
                        a.uids, s.to, a.deliveries, s.attempts
                    );
                    self.pause_for(ctx, &a, reason);
                }
            }
        }
    }

    /// Whether the delivery's messages, refused while not in control, may go again
    /// (each [`SpoolerConfig::max_deliveries`](super::SpoolerConfig::max_deliveries)
    /// times in all); counts the refusal.
    fn refused_again(&mut self, a: &Awaiting) -> bool {
        let max = self.config.max_deliveries.max(1);
        if self.outcomes.refusals.len() >= MAX_AWAITING {
            self.outcomes.refusals.clear();
        }
        let mut again = true;
        for u in &a.uids {
            let n = self.outcomes.refusals.entry((a.mission, *u)).or_insert(0);
            *n += 1;
            again &= *n < max;
        }
        again
    }

    /// Puts the delivery's messages back as not sent (the cursor moved back to the
    /// first); true if any was.
    fn repend(&mut self, a: &Awaiting) -> bool {
        let Some(m) = self
            .missions
            .get_mut(&a.mission)
            .filter(|m| m.state != MissionState::Aborted)
        else {
            return false;
        };
        let mut first = None;
        for (i, it) in m.items.iter_mut().enumerate() {
            if a.uids.contains(&it.cmd.uid) && it.state == ItemState::Sent {
                it.state = ItemState::Pending;
                first.get_or_insert(i);
            }
        }
        if let Some(f) = first {
            m.cursor = m.cursor.min(f);
        }
        if m.waiting.is_some_and(|w| a.uids.contains(&w)) {
            m.waiting = None;
        }
        if first.is_some() && m.state == MissionState::Finished {
            m.state = MissionState::Pending;
        }
        first.is_some()
    }

    /// Pauses the delivery's mission with `reason`, its messages put back as not sent.
    fn pause_for(&mut self, ctx: &mut Ctx<'_>, a: &Awaiting, reason: String) {
        let id = a.mission;
        let was = self.missions.get(&id).map(|m| m.state);
        if was.is_none_or(|s| s == MissionState::Aborted) {
            return;
        }
        tracing::warn!(mission = id, "mission paused: {reason}");
        let repended = self.repend(a);
        let Some(m) = self.missions.get_mut(&id) else {
            return;
        };
        let owner = m.owner;
        let status = match (m.state, was) {
            (MissionState::Running, _) => {
                m.state = MissionState::Paused;
                let _ = ctx.transition(Transition::Pause);
                Some(MissionStatus::Paused)
            }
            // Its last delivery failed after the mission was reported finished: it is
            // pending again, the failed messages not sent (Run Mission sends them).
            (MissionState::Pending, Some(MissionState::Finished)) if repended => {
                Some(MissionStatus::Pending)
            }
            _ => None,
        };
        if let Some(status) = status {
            self.outcomes.stats.paused += 1;
            ctx.send(
                owner,
                ReportMissionStatus {
                    status_type: MissionStatusType::Mission,
                    status,
                    secondary_status: MissionSecondaryStatus::NoError,
                    mission_id: id,
                    task_id: 0,
                    task_msg_id: 0,
                },
            );
        }
        self.outcomes.reasons.insert(id, reason);
        self.touch(id);
    }
}

impl Outcomes {
    fn remember(&mut self, now: Instant, key: (Address, CommandCode, u16), a: Awaiting) {
        while self.awaiting.len() >= MAX_AWAITING {
            let Some((_, old)) = self.order.pop_front() else {
                break;
            };
            if self.awaiting.remove(&old).is_some() {
                self.stats.forgotten_full += 1;
            }
        }
        self.awaiting.insert(key, a);
        self.order.push_back((now, key));
        // The order list holds keys settled since; keep it within bounds too.
        if self.order.len() > 2 * MAX_AWAITING {
            let awaiting = &self.awaiting;
            self.order.retain(|(_, k)| awaiting.contains_key(k));
        }
    }

    fn expire(&mut self, now: Instant) {
        while let Some(&(t, k)) = self.order.front() {
            if now.saturating_duration_since(t) < OUTCOME_TIMEOUT {
                break;
            }
            self.order.pop_front();
            // A redelivered one was remembered again, later: only the latest counts.
            if self
                .awaiting
                .get(&k)
                .is_some_and(|a| now.saturating_duration_since(a.sent) >= OUTCOME_TIMEOUT)
            {
                self.awaiting.remove(&k);
                self.stats.no_outcome += 1;
            }
        }
    }
}
