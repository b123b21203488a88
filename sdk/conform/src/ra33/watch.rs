//! Watching a command's effect: the outsider checks send a command and then poll the
//! target fast for the whole settle time, judging on every answer seen, so a change
//! the target undoes a few milliseconds later is still seen (a single read after the
//! settle time would miss it). Polling is the fallback the target always offers; an
//! event or service connection set up before the command would see every change
//! without asking.

use std::time::Duration;

use jaus::wire::AckNak;
use jaus::{Address, CommandCode};

use super::Ra33Voice;
use crate::session::Incoming;

/// How often the target is asked during a watch: 200 Hz, so that a change undone a few
/// milliseconds later is in at least one answer and its end is timed within 5 ms. The
/// rate reached (lower when the session's waits end late) is reported.
pub(super) const WATCH_PERIOD: Duration = Duration::from_millis(5);

/// What a watch saw.
pub(super) struct Watched<T> {
    /// The acknowledgement of the command, if one came.
    pub ack: Option<AckNak>,
    /// Every answer read, with its time after the command in milliseconds, in order.
    pub seen: Vec<(f64, T)>,
    /// Queries sent during the window (one more is sent after it).
    pub polls: usize,
    /// How long the watch lasted.
    pub window: Duration,
}

impl<T> Watched<T> {
    /// How the target was watched, for the detail: "polled Query Component Status
    /// for 200 ms from the command at 200 Hz (40 queries, then one after; 41 answers)".
    pub fn how(&self, query: &str) -> String {
        let secs = self.window.as_secs_f64();
        let rate = if secs > 0.0 {
            self.polls as f64 / secs
        } else {
            0.0
        };
        format!(
            "polled {query} for {} ms from the command at {rate:.0} Hz ({} queries, then one after; {} answers)",
            self.window.as_millis(),
            self.polls,
            self.seen.len()
        )
    }
}

/// A query to poll with: its code and body, and the code of its report.
pub(super) struct Poll {
    /// The query's command code.
    pub code: CommandCode,
    /// The query's body.
    pub body: Vec<u8>,
    /// The report's command code.
    pub report: CommandCode,
}

/// The times at which the value judged by `bad` appears and goes away again, as text:
/// "reported Standby 0.4 ms after it and Ready again at 10.3 ms"; `None` when no answer
/// shows it.
pub(super) fn changes<T: PartialEq>(
    seen: &[(f64, T)],
    show: impl Fn(&T) -> String,
    bad: impl Fn(&T) -> bool,
) -> Option<String> {
    let first = seen.iter().position(|(_, v)| bad(v))?;
    let mut text = format!(
        "reported {} {:.1} ms after it",
        show(&seen[first].1),
        seen[first].0
    );
    let mut last = &seen[first].1;
    for (t, v) in &seen[first + 1..] {
        if v != last {
            let again = if bad(v) { "" } else { " again" };
            text.push_str(&format!(", {}{again} at {t:.1} ms", show(v)));
            last = v;
        }
    }
    Some(text)
}

impl Ra33Voice<'_> {
    /// Sends command `code` with `body` from `from` (asking for an acknowledgement),
    /// then until the settle time has passed asks the target `poll` from the outsider
    /// every [`WATCH_PERIOD`], and once more after it; every report is read by `read`
    /// and kept with its time after the command.
    pub(super) fn watch<T>(
        &mut self,
        from: Address,
        code: CommandCode,
        body: Vec<u8>,
        poll: &Poll,
        read: impl Fn(&Self, &[u8]) -> Option<T>,
    ) -> Watched<T> {
        let (target, outsider) = (self.target, self.voices.outsider);
        let at = self.session.now();
        let window = self.opts.settle;
        let end = at + window;
        self.send_body(from, code, body, true);
        let mut watched = Watched {
            ack: None,
            seen: Vec::new(),
            polls: 0,
            window,
        };
        // Keeps what `p` says; whether it is an answer to the poll.
        let take = |e: &Self, p: &Incoming, w: &mut Watched<T>| -> bool {
            let h = &p.header;
            if h.source != target {
                return false;
            }
            if matches!(h.ack_nak, AckNak::Ack | AckNak::Nak) {
                if h.destination == from && h.command_code == code {
                    w.ack.get_or_insert(h.ack_nak);
                }
                return false;
            }
            if h.destination != outsider || h.command_code != poll.report {
                return false;
            }
            let Some(v) = read(e, &p.body) else {
                return false;
            };
            let t = p.at.saturating_duration_since(at).as_secs_f64() * 1000.0;
            w.seen.push((t, v));
            true
        };
        let mut next_poll = at;
        while self.session.now() < end {
            let now = self.session.now();
            if now >= next_poll {
                self.send_body(outsider, poll.code, poll.body.clone(), false);
                watched.polls += 1;
                next_poll = (next_poll + WATCH_PERIOD).max(now + Duration::from_micros(1));
            }
            while let Some(p) = self.next(next_poll.min(end)) {
                take(self, &p, &mut watched);
            }
        }
        // One more answer after the window: the state the check ends in.
        self.send_body(outsider, poll.code, poll.body.clone(), false);
        let last = self.session.now() + self.opts.wait;
        while let Some(p) = self.next(last) {
            if take(self, &p, &mut watched) {
                break;
            }
        }
        watched
    }
}
