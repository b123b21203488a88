//! The polls of the RA 3.3 side: queries sent on a schedule to keep reports fresh, per
//! (component, query), backing off when left unanswered and stopped after
//! [`GIVE_UP_AFTER`] unanswered ones, until the component answers that query or is
//! discovered again. Sans-IO: time is the `now` the caller passes.

use std::time::{Duration, Instant};

use jaus::messages::Message as Ra33Message;
use jaus::{Address, CommandCode};

use super::Ra33Stats;

/// A poll left unanswered this many times in a row starts backing off: each further
/// unanswered poll doubles its period, up to [`MAX_POLL_PERIOD`].
pub const BACKOFF_AFTER: u32 = 3;

/// The longest period a backed-off poll waits.
pub const MAX_POLL_PERIOD: Duration = Duration::from_secs(30);

/// A poll left unanswered this many times in a row stops (counted, logged): the
/// component never answers that query (OpenJAUS 3.3's primitive driver and Query Wrench
/// Effort). A report of its kind from the component, or the component discovered
/// again, starts it again.
pub const GIVE_UP_AFTER: u32 = 10;

/// A query sent on a schedule, to keep a report fresh.
#[derive(Debug, Clone)]
struct Poll {
    to: Address,
    query: Ra33Message,
    every: Duration,
    due: Instant,
    /// Polls sent since the last report of the query's kind from `to`.
    unanswered: u32,
    /// Stopped after [`GIVE_UP_AFTER`] unanswered polls.
    given_up: bool,
}

impl Poll {
    /// Back to the normal rate, due at `due`.
    fn restart(&mut self, period: Duration, due: Instant) {
        self.unanswered = 0;
        self.given_up = false;
        self.every = period;
        self.due = due;
    }
}

/// The polls of one RA 3.3 side (one per (component, query) pair; their number is
/// bounded by the services that ask for them, not by the network).
#[derive(Debug, Clone)]
pub(super) struct Polls {
    period: Duration,
    list: Vec<Poll>,
}

impl Polls {
    /// No polls yet; each one runs every `period` while answered.
    pub(super) fn new(period: Duration) -> Self {
        Self {
            period,
            list: Vec::new(),
        }
    }

    /// Keeps `query` to `to` going from `now` on (once per pair).
    pub(super) fn keep(&mut self, now: Instant, to: Address, query: Ra33Message) {
        if self
            .list
            .iter()
            .any(|p| p.to == to && p.query.code() == query.code())
        {
            return;
        }
        self.list.push(Poll {
            to,
            query,
            every: self.period,
            due: now,
            unanswered: 0,
            given_up: false,
        });
    }

    /// A report with code `report` came from `from` at `now`: the polls it answers go
    /// back to the normal rate (a stopped one starts again one period later).
    pub(super) fn answered(
        &mut self,
        now: Instant,
        from: Address,
        report: CommandCode,
        stats: &mut Ra33Stats,
    ) {
        let period = self.period;
        for p in &mut self.list {
            if p.to != from || p.query.code().complement() != Some(report) {
                continue;
            }
            if p.given_up {
                stats.polls_resumed += 1;
                tracing::info!(component = %p.to, query = p.query.name(), "RA 3.3 component answered a query it was no longer asked: polling resumes");
                p.restart(period, now + period);
            } else {
                let due = p.due.min(now + period);
                p.restart(period, due);
            }
        }
    }

    /// `component` was discovered again (it left the system tree and came back, or
    /// announced itself anew): every poll of it starts again at the normal rate, now.
    pub(super) fn rediscovered(&mut self, now: Instant, component: Address, stats: &mut Ra33Stats) {
        let period = self.period;
        for p in self.list.iter_mut().filter(|p| p.to == component) {
            if p.given_up {
                stats.polls_resumed += 1;
                tracing::info!(%component, query = p.query.name(), "RA 3.3 component discovered again: polling resumes");
            }
            if p.given_up || p.unanswered > 0 {
                p.restart(period, now);
            }
        }
    }

    /// The polls due at `now`, to send; a poll left unanswered backs off, then stops.
    pub(super) fn due(
        &mut self,
        now: Instant,
        me: Address,
        stats: &mut Ra33Stats,
    ) -> Vec<(Address, Ra33Message)> {
        let mut out = Vec::new();
        for p in self.list.iter_mut().filter(|p| !p.given_up) {
            if p.due > now {
                continue;
            }
            if p.unanswered > 0 {
                stats.polls_unanswered += 1;
            }
            if p.unanswered >= GIVE_UP_AFTER {
                p.given_up = true;
                stats.polls_given_up += 1;
                tracing::info!(gateway = %me, component = %p.to, query = p.query.name(), unanswered = p.unanswered,
                    "the RA 3.3 component never answers this query: no longer asked until it answers or is discovered again");
                continue;
            }
            if p.unanswered >= BACKOFF_AFTER {
                p.every = (p.every * 2).min(MAX_POLL_PERIOD);
            }
            p.unanswered += 1;
            p.due = now + p.every;
            stats.polls_sent += 1;
            out.push((p.to, p.query.clone()));
        }
        out
    }

    /// When the next poll is due.
    pub(super) fn next_due(&self) -> Option<Instant> {
        self.list
            .iter()
            .filter(|p| !p.given_up)
            .map(|p| p.due)
            .min()
    }

    /// The (component, query code) pairs no longer polled.
    pub(super) fn given_up(&self) -> impl Iterator<Item = (Address, CommandCode)> + '_ {
        self.list
            .iter()
            .filter(|p| p.given_up)
            .map(|p| (p.to, p.query.code()))
    }

    /// The codes of the reports that answer the polls.
    pub(super) fn reports(&self) -> impl Iterator<Item = CommandCode> + '_ {
        self.list.iter().filter_map(|p| p.query.code().complement())
    }
}
