//! The evidence of the running check: every message exchanged, timed from the check's
//! start, at most [`MAX_EVIDENCE`] of them (a target that floods the tester cannot grow
//! a report without bound; the cut is said in the evidence itself).

use std::time::Instant;

use crate::check::Exchange;

/// Most exchanges kept as the evidence of one check.
pub const MAX_EVIDENCE: usize = 2_000;

/// The messages of one check (or of one background activity), bounded.
#[derive(Debug, Clone)]
pub struct Evidence {
    list: Vec<Exchange>,
    started: Instant,
}

impl Evidence {
    /// An empty log whose clock starts at `now`.
    pub fn new(now: Instant) -> Self {
        Evidence {
            list: Vec::new(),
            started: now,
        }
    }

    /// A check begins at `now`: the log is emptied and its clock restarted.
    pub fn begin(&mut self, now: Instant) {
        self.list.clear();
        self.started = now;
    }

    /// Milliseconds from the start of the log to `now` (0 before it).
    pub fn t_ms(&self, now: Instant) -> f64 {
        now.saturating_duration_since(self.started).as_secs_f64() * 1000.0
    }

    /// Adds `e`, unless [`MAX_EVIDENCE`] are kept already: the first one past the bound
    /// is replaced by a line saying the rest are not kept, later ones are dropped.
    pub fn keep(&mut self, e: Exchange) {
        match self.list.len() {
            n if n < MAX_EVIDENCE => self.list.push(e),
            n if n == MAX_EVIDENCE => self.list.push(Exchange {
                message: format!("(more than {MAX_EVIDENCE} messages: the rest are not kept)"),
                fields: serde_json::Value::Null,
                ..e
            }),
            _ => {}
        }
    }

    /// Adds each of `more` as [`keep`](Evidence::keep) does.
    pub fn extend(&mut self, more: impl IntoIterator<Item = Exchange>) {
        for e in more {
            self.keep(e);
        }
    }

    /// The exchanges kept, leaving the log empty (its clock unchanged).
    pub fn take(&mut self) -> Vec<Exchange> {
        std::mem::take(&mut self.list)
    }

    /// The exchanges kept so far, in order.
    pub fn iter(&self) -> impl Iterator<Item = &Exchange> {
        self.list.iter()
    }

    /// How many exchanges are kept (the line saying the rest were cut included).
    pub fn len(&self) -> usize {
        self.list.len()
    }

    /// Whether nothing is kept.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    fn exchange(i: usize) -> Exchange {
        Exchange {
            t_ms: i as f64,
            dir: "sent",
            from: "a".into(),
            to: "b".into(),
            message: format!("m{i}"),
            fields: serde_json::Value::Null,
        }
    }

    #[test]
    fn the_log_is_bounded_and_says_where_it_was_cut() {
        let t0 = Instant::now();
        let mut ev = Evidence::new(t0);
        ev.extend((0..MAX_EVIDENCE + 10).map(exchange));
        assert_eq!(ev.len(), MAX_EVIDENCE + 1);
        let list = ev.take();
        assert_eq!(
            list[MAX_EVIDENCE - 1].message,
            format!("m{}", MAX_EVIDENCE - 1)
        );
        assert!(list[MAX_EVIDENCE].message.contains("not kept"));
        assert!(ev.is_empty());
    }

    #[test]
    fn begin_empties_the_log_and_restarts_its_clock() {
        let t0 = Instant::now();
        let mut ev = Evidence::new(t0);
        ev.keep(exchange(1));
        let t1 = t0 + Duration::from_millis(500);
        ev.begin(t1);
        assert!(ev.is_empty());
        assert_eq!(ev.t_ms(t1 + Duration::from_millis(20)), 20.0);
        assert_eq!(ev.t_ms(t0), 0.0);
    }
}
