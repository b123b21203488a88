//! Commands that arrive, sans-IO: one mechanism for RA 3.3 and AS-4 alike.
//!
//! * [`Sender`]: a message sent with an acknowledgement requested is kept until its
//!   ACK or NAK comes back, resent with exponential backoff when it does not, and given
//!   up after a bounded number of attempts and time. Each ends as a [`Delivery`] value
//!   ([`Outcome::Acknowledged`], [`Outcome::Refused`], [`Outcome::GaveUp`]) for the
//!   caller to take. Messages to one peer go one at a time, in the order given: a
//!   later one is held until the one before it is settled, so that a reordering
//!   network cannot turn "Resume, then Set Travel Speed" into the reverse. A peer that
//!   never acknowledged anything and let
//!   [`RetryPolicy::learn_after`] messages go unanswered is remembered as one that does
//!   not acknowledge ([`Sender::acknowledges`]): its later messages go once, untracked,
//!   as OpenJAUS 3.3's components never send ACK/NAK.
//! * [`Receiver`]: a retransmitted message (same sender, command code, sequence number
//!   and content within [`RetryPolicy::duplicate_window`]) is carried out once: the
//!   duplicate is dropped and the answer already given to the first copy is given
//!   again, since it is the answer that was lost.
//!
//! Both are bounded (outstanding messages, remembered receptions, outcomes waiting to
//! be taken) and count everything ([`ReliableStats`]). The keys are the caller's: the
//! RA 3.3 node keys by JAUS address, command code and sequence number (a receiver
//! also by a hash of the body, and a sender starts its numbers at a random point, so
//! that a restarted sender reusing numbers is not taken for a retransmission); the
//! AS-4 stack by peer, AS-4 id and sequence number likewise.

/// A hash of message bytes, for the receiver's key: the same in every process (a
/// restarted sender's retransmission is compared with what the receiver kept).
pub fn content_hash(bytes: &[u8]) -> u64 {
    // FNV-1a, 64 bits.
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(*b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// A sequence number to start from, different in every process (std's randomly keyed
/// hasher; no clock read).
pub fn random_start() -> u16 {
    use std::hash::{BuildHasher, Hasher};
    let h = std::collections::hash_map::RandomState::new()
        .build_hasher()
        .finish();
    (h as u16).max(1)
}

use std::collections::{HashMap, VecDeque};
use std::hash::Hash;
use std::time::{Duration, Instant};

/// How hard a [`Sender`] tries, and how long a [`Receiver`] remembers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RetryPolicy {
    /// Wait for the acknowledgement of the first copy. Default 200 ms.
    pub first_timeout: Duration,
    /// Longest wait between two copies (the wait doubles up to it). Default 1.6 s.
    pub max_timeout: Duration,
    /// Copies sent in all, the first included. Default 6 (within about 5 s).
    pub max_attempts: u32,
    /// Most messages waiting for an acknowledgement at once; more are sent once,
    /// untracked, and counted. Default 1024.
    pub max_outstanding: usize,
    /// A peer that never acknowledged and let this many messages go unanswered is not
    /// asked again (its messages go once). Default 2; 0 never gives up on a peer.
    pub learn_after: u32,
    /// How long a receiver remembers a message to drop its retransmissions. Default
    /// 10 s: longer than a sender keeps trying (about 6 s), short enough that a sender
    /// restarted with the same numbers is not taken for itself for long.
    pub duplicate_window: Duration,
    /// Most receptions remembered (the oldest are forgotten first). Default 4096.
    pub max_remembered: usize,
    /// How long a message to a peer not yet known to acknowledge waits behind the one
    /// before it at most (a peer known to acknowledge gets its messages strictly one at
    /// a time). Default 2 s: an answering peer's acknowledgement is back well before,
    /// even after three lost copies (order kept); a silent one's messages are not held
    /// up for the whole retry time of each.
    pub hold_unknown: Duration,
    /// Whether a message to a peer not yet known to acknowledge is resent. Default
    /// true (the SDK's components acknowledge and drop retransmissions, Part 1). False
    /// ([`RetryPolicy::cautious`]): one copy, whose acknowledgement is awaited for
    /// [`hold_unknown`](Self::hold_unknown); a peer is known once it acknowledged
    /// anything, and from then on its messages are resent until acknowledged. A peer
    /// that neither acknowledges nor drops retransmissions (OpenJAUS 3.3 carried out
    /// each of six copies of one Set Global Waypoint from a client: six waypoints)
    /// then carries out each command once; the price is that a first command lost on
    /// the way to a peer not yet heard acknowledging is not sent again.
    pub retry_unknown: bool,
}

impl Default for RetryPolicy {
    fn default() -> Self {
        Self {
            first_timeout: Duration::from_millis(200),
            max_timeout: Duration::from_millis(1600),
            max_attempts: 6,
            max_outstanding: 1024,
            learn_after: 2,
            duplicate_window: Duration::from_secs(10),
            max_remembered: 4096,
            hold_unknown: Duration::from_secs(2),
            retry_unknown: true,
        }
    }
}

impl RetryPolicy {
    /// The defaults, but a peer not yet known to acknowledge gets one copy of each
    /// message ([`retry_unknown`](Self::retry_unknown) false): for a client on a system
    /// that may hold components which neither acknowledge nor drop retransmissions
    /// (OpenJAUS 3.3's), such as the command line's, Python's and the console's node.
    pub fn cautious() -> Self {
        Self {
            retry_unknown: false,
            ..Self::default()
        }
    }

    /// The wait after copy number `attempt` (1 for the first): doubling from
    /// [`first_timeout`](Self::first_timeout) up to [`max_timeout`](Self::max_timeout).
    pub fn wait_after(&self, attempt: u32) -> Duration {
        let doublings = attempt.saturating_sub(1).min(16);
        self.first_timeout
            .saturating_mul(1 << doublings)
            .min(self.max_timeout)
    }
}

/// How a message sent with an acknowledgement requested ended (defined with the
/// component runtime, which hands it to the component that sent the message:
/// [`crate::component::Settled`]).
pub use crate::component::Outcome;

/// The end of one tracked message: its key, how it ended, the copies sent and the
/// time from the first copy to the end.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Delivery<K> {
    /// The caller's key of the message.
    pub key: K,
    /// How it ended.
    pub outcome: Outcome,
    /// Copies sent (1 when the first was acknowledged).
    pub attempts: u32,
    /// From the first copy to the acknowledgement or the giving up.
    pub elapsed: Duration,
}

/// Counters of both sides.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ReliableStats {
    /// Messages tracked (sent with an acknowledgement requested).
    pub tracked: u64,
    /// Copies resent.
    pub retried: u64,
    /// Messages acknowledged.
    pub acknowledged: u64,
    /// Messages refused (NAK).
    pub refused: u64,
    /// Messages given up on.
    pub given_up: u64,
    /// Messages sent once, untracked, because their peer does not acknowledge.
    pub untracked_peer: u64,
    /// Messages sent once, untracked, because too many waited already.
    pub untracked_full: u64,
    /// Acknowledgements that matched nothing waiting (late, or duplicated).
    pub stray_answers: u64,
    /// Retransmitted messages received and dropped (carried out once).
    pub duplicates_dropped: u64,
    /// Answers given again to a retransmission.
    pub answers_repeated: u64,
    /// Outcomes dropped because nobody took them (the oldest go first).
    pub outcomes_dropped: u64,
}

/// What a peer does with acknowledgement requests, as learnt.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct Habit {
    acknowledged: u64,
    unanswered: u32,
}

#[derive(Debug)]
struct Waiting<K, P, M> {
    key: K,
    peer: P,
    message: M,
    first: Instant,
    /// When the next copy is due; `None` while it waits behind an earlier message to
    /// the same peer.
    next: Option<Instant>,
    /// Copies sent (0 while held).
    attempts: u32,
}

/// What [`Sender::track`] decided for a message.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tracked {
    /// Tracked, and to be sent now (its first copy).
    Send,
    /// Tracked, and held: an earlier message to the same peer waits for its answer.
    /// The sender hands its first copy to [`Sender::poll`]'s `send` once that one is
    /// settled (or, for a peer not yet known to answer, after
    /// [`RetryPolicy::hold_unknown`] at most), so that a peer gets its commands in the
    /// order they were given, however the network reorders them (a Resume before the
    /// Set Travel Speed it would reset, a Spool Mission before its Run Mission).
    Held,
    /// Not tracked (the peer does not acknowledge, or too many wait): to be sent now,
    /// once.
    Untracked,
}

/// The sending side: messages waiting for their acknowledgement. `K` keys a message,
/// `P` names its peer (whose habit is learnt and whose messages keep their order), `M`
/// is what is resent.
#[derive(Debug)]
pub struct Sender<K, P, M> {
    policy: RetryPolicy,
    waiting: Vec<Waiting<K, P, M>>,
    habits: HashMap<P, Habit>,
    outcomes: VecDeque<Delivery<K>>,
    stats: ReliableStats,
}

/// Most outcomes kept for the caller to take.
const MAX_OUTCOMES: usize = 4096;

/// Most peers whose habit is remembered (a peer beyond it is simply asked again).
const MAX_HABITS: usize = 4096;

impl<K: Copy + Eq + std::fmt::Debug, P: Copy + Eq + Hash, M> Sender<K, P, M> {
    /// A sender trying as `policy` says.
    pub fn new(policy: RetryPolicy) -> Self {
        Self {
            policy,
            waiting: Vec::new(),
            habits: HashMap::new(),
            outcomes: VecDeque::new(),
            stats: ReliableStats::default(),
        }
    }

    /// The policy.
    pub fn policy(&self) -> &RetryPolicy {
        &self.policy
    }

    /// Whether `peer` is to be asked for acknowledgements: false once it let
    /// [`RetryPolicy::learn_after`] messages go unanswered without ever acknowledging.
    pub fn acknowledges(&self, peer: P) -> bool {
        self.policy.learn_after == 0
            || self
                .habits
                .get(&peer)
                .is_none_or(|h| h.acknowledged > 0 || h.unanswered < self.policy.learn_after)
    }

    /// Whether to ask `peer` for an acknowledgement of a message that did not ask for
    /// one itself: [`acknowledges`](Self::acknowledges), and when not, the message is
    /// counted as sent once, untracked.
    pub fn ask(&mut self, peer: P) -> bool {
        let ask = self.acknowledges(peer);
        if !ask {
            self.stats.untracked_peer += 1;
        }
        ask
    }

    /// Tracks `message` to `peer`, given at `now`: whether to send it now, hold it, or
    /// send it once untracked (counted).
    pub fn track(&mut self, now: Instant, key: K, peer: P, message: M) -> Tracked {
        if !self.acknowledges(peer) {
            self.stats.untracked_peer += 1;
            return Tracked::Untracked;
        }
        if self.waiting.len() >= self.policy.max_outstanding {
            self.stats.untracked_full += 1;
            return Tracked::Untracked;
        }
        self.stats.tracked += 1;
        // One at a time per peer, in the order given; behind a peer not yet known to
        // answer, for `hold_unknown` at most.
        let behind = self.waiting.iter().any(|w| w.peer == peer);
        let known = self.known(peer);
        let next = match (behind, known) {
            (false, _) => Some(now + self.wait_after(peer, 1)),
            (true, true) => None,
            (true, false) => Some(now + self.policy.hold_unknown),
        };
        self.waiting.push(Waiting {
            key,
            peer,
            message,
            first: now,
            next,
            attempts: u32::from(!behind),
        });
        if behind {
            Tracked::Held
        } else {
            Tracked::Send
        }
    }

    /// An ACK (`ok`) or NAK from `peer` for the message `key` (or, when the peer's
    /// answer does not carry the key exactly, the oldest sent message `matches`
    /// accepts). True when it settled a waiting message.
    pub fn answered(
        &mut self,
        now: Instant,
        key: K,
        peer: P,
        ok: bool,
        matches: impl Fn(&K) -> bool,
    ) -> bool {
        let sent = |w: &Waiting<K, P, M>| w.attempts > 0;
        let i = self
            .waiting
            .iter()
            .position(|w| sent(w) && w.key == key)
            .or_else(|| self.waiting.iter().position(|w| sent(w) && matches(&w.key)));
        let Some(i) = i else {
            self.stats.stray_answers += 1;
            return false;
        };
        let w = self.waiting.remove(i);
        if self.habits.len() < MAX_HABITS || self.habits.contains_key(&peer) {
            let h = self.habits.entry(peer).or_default();
            h.acknowledged += 1;
            h.unanswered = 0;
        }
        let outcome = if ok {
            self.stats.acknowledged += 1;
            Outcome::Acknowledged
        } else {
            self.stats.refused += 1;
            Outcome::Refused
        };
        self.release(now, w.peer);
        self.finish(Delivery {
            key: w.key,
            outcome,
            attempts: w.attempts,
            elapsed: now.saturating_duration_since(w.first),
        });
        true
    }

    /// The messages due at `now`, handed to `send` (a held one's first copy, or another
    /// copy); those out of attempts are given up (an outcome each).
    pub fn poll(&mut self, now: Instant, mut send: impl FnMut(&K, &M)) {
        let mut i = 0;
        while i < self.waiting.len() {
            if self.waiting[i].next.is_none_or(|t| t > now) {
                i += 1;
                continue;
            }
            let peer = self.waiting[i].peer;
            let last = if self.known(peer) || self.policy.retry_unknown {
                self.policy.max_attempts
            } else {
                1
            };
            if self.waiting[i].attempts >= last {
                let w = self.waiting.remove(i);
                self.stats.given_up += 1;
                if self.habits.len() < MAX_HABITS || self.habits.contains_key(&w.peer) {
                    let h = self.habits.entry(w.peer).or_default();
                    h.unanswered = h.unanswered.saturating_add(1);
                }
                self.release(now, w.peer);
                if !self.acknowledges(w.peer) {
                    // Learnt never to answer: what was held for it goes now.
                    for h in self
                        .waiting
                        .iter_mut()
                        .filter(|h| h.peer == w.peer && h.attempts == 0)
                    {
                        h.next = Some(now);
                    }
                }
                self.finish(Delivery {
                    key: w.key,
                    outcome: Outcome::GaveUp,
                    attempts: w.attempts,
                    elapsed: now.saturating_duration_since(w.first),
                });
                // The released message may sit before `i`: look again from the start.
                i = 0;
                continue;
            }
            let wait = self.wait_after(peer, self.waiting[i].attempts + 1);
            // A held message's first copy, to a peer still asked for answers.
            let by_hold = self.waiting[i].attempts == 0 && self.acknowledges(peer);
            let w = &mut self.waiting[i];
            if w.attempts > 0 {
                self.stats.retried += 1;
            }
            w.attempts += 1;
            w.next = Some(now + wait);
            send(&w.key, &w.message);
            if by_hold {
                // A held message goes (by its hold, or the one before it settled):
                // the ones held behind it wait their hold again from now, so that they go one after another, not
                // all at once (a Release Component Control held behind a spooled
                // mission's messages would overtake some of them).
                let hold = now + self.policy.hold_unknown;
                for later in self.waiting[i + 1..]
                    .iter_mut()
                    .filter(|l| l.peer == peer && l.attempts == 0)
                {
                    if let Some(t) = later.next.as_mut() {
                        *t = (*t).max(hold);
                    }
                }
            }
            i += 1;
        }
    }

    /// When [`poll`](Self::poll) must next run.
    pub fn next_timeout(&self) -> Option<Instant> {
        self.waiting.iter().filter_map(|w| w.next).min()
    }

    /// Messages waiting for their acknowledgement (held ones included).
    pub fn waiting(&self) -> usize {
        self.waiting.len()
    }

    /// The next outcome, oldest first.
    pub fn poll_delivery(&mut self) -> Option<Delivery<K>> {
        self.outcomes.pop_front()
    }

    /// The counters.
    pub fn stats(&self) -> ReliableStats {
        self.stats
    }

    /// Whether `peer` has acknowledged (or refused) anything: it answers, and drops
    /// retransmissions (Part 1), so a message sent to it again is carried out once.
    pub fn known_to_answer(&self, peer: P) -> bool {
        self.known(peer)
    }

    /// Whether `peer` acknowledged anything (it is then resent to: a peer that
    /// acknowledges drops retransmissions, Part 1).
    fn known(&self, peer: P) -> bool {
        self.habits.get(&peer).is_some_and(|h| h.acknowledged > 0)
    }

    /// The wait after copy `attempt` to `peer`: the policy's backoff, or, for the one
    /// copy to a peer not yet known to acknowledge, `hold_unknown`.
    fn wait_after(&self, peer: P, attempt: u32) -> Duration {
        if self.known(peer) || self.policy.retry_unknown {
            self.policy.wait_after(attempt)
        } else {
            self.policy.hold_unknown
        }
    }

    fn release(&mut self, now: Instant, peer: P) {
        if self
            .waiting
            .iter()
            .any(|w| w.peer == peer && w.attempts > 0)
        {
            return;
        }
        if let Some(w) = self
            .waiting
            .iter_mut()
            .find(|w| w.peer == peer && w.attempts == 0)
        {
            w.next = Some(now);
        }
    }

    fn finish(&mut self, d: Delivery<K>) {
        tracing::debug!(key = ?d.key, outcome = ?d.outcome, attempts = d.attempts, "delivery");
        if self.outcomes.len() >= MAX_OUTCOMES {
            self.outcomes.pop_front();
            self.stats.outcomes_dropped += 1;
        }
        self.outcomes.push_back(d);
    }
}

/// What [`Receiver::arrived`] says of a message.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Arrival<A> {
    /// The first copy: carry it out.
    New,
    /// A retransmission: drop it, and send this answer again when there is one (the
    /// answer to the first copy, lost on its way).
    Duplicate(Option<A>),
}

/// The receiving side: messages seen recently, with the answer given to each. `K` keys
/// a message, `A` is its answer.
#[derive(Debug)]
pub struct Receiver<K, A> {
    window: Duration,
    max: usize,
    seen: HashMap<K, (Instant, Option<A>)>,
    order: VecDeque<(Instant, K)>,
    duplicates_dropped: u64,
    answers_repeated: u64,
}

impl<K: Copy + Eq + Hash, A: Clone> Receiver<K, A> {
    /// A receiver remembering messages as `policy` says.
    pub fn new(policy: &RetryPolicy) -> Self {
        Self {
            window: policy.duplicate_window,
            max: policy.max_remembered.max(1),
            seen: HashMap::new(),
            order: VecDeque::new(),
            duplicates_dropped: 0,
            answers_repeated: 0,
        }
    }

    /// A message `key` asking for an acknowledgement arrived at `now`.
    pub fn arrived(&mut self, now: Instant, key: K) -> Arrival<A> {
        self.expire(now);
        if let Some((_, answer)) = self.seen.get(&key) {
            self.duplicates_dropped += 1;
            if answer.is_some() {
                self.answers_repeated += 1;
            }
            return Arrival::Duplicate(answer.clone());
        }
        if self.order.len() >= self.max {
            if let Some((_, old)) = self.order.pop_front() {
                self.seen.remove(&old);
            }
        }
        self.seen.insert(key, (now, None));
        self.order.push_back((now, key));
        Arrival::New
    }

    /// The answer given to message `key` (kept for its retransmissions).
    pub fn answered(&mut self, key: K, answer: A) {
        if let Some((_, a)) = self.seen.get_mut(&key) {
            *a = Some(answer);
        }
    }

    /// The answer given to the latest remembered message `matches` accepts (for an
    /// answer that does not carry the whole key, e.g. not the hash of the content).
    pub fn answered_matching(&mut self, matches: impl Fn(&K) -> bool, answer: A) {
        if let Some((_, k)) = self.order.iter().rev().find(|(_, k)| matches(k)) {
            if let Some((_, a)) = self.seen.get_mut(k) {
                *a = Some(answer);
            }
        }
    }

    /// Whether `key` is remembered (a message seen within the window).
    pub fn remembers(&self, key: &K) -> bool {
        self.seen.contains_key(key)
    }

    /// Adds this side's counters to `stats`.
    pub fn add_stats(&self, stats: &mut ReliableStats) {
        stats.duplicates_dropped += self.duplicates_dropped;
        stats.answers_repeated += self.answers_repeated;
    }

    fn expire(&mut self, now: Instant) {
        while let Some(&(t, k)) = self.order.front() {
            if now.saturating_duration_since(t) < self.window {
                break;
            }
            self.order.pop_front();
            self.seen.remove(&k);
        }
    }
}

#[cfg(test)]
mod tests;
