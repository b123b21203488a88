//! Requests waiting for their answer: queries for their report, packets asking for an
//! acknowledgement for their ACK or NAK. Bounded: past [`Pairs::cap`] requests waiting
//! at once, further ones are counted, not tracked.

use std::collections::{BTreeMap, HashMap, VecDeque};
use std::hash::Hash;
use std::time::Duration;

/// Packet numbers kept per list (the rest are counted).
pub(crate) const LIST_CAP: usize = 1000;

/// One request waiting.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Pending<A> {
    /// Its packet number.
    pub number: u64,
    /// When it was seen.
    pub time: Duration,
    /// Its command code.
    pub code: u16,
    /// Who asked.
    pub asker: A,
}

/// What one component did with the requests it was sent, in one group.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Answers<A> {
    /// Latency of each request answered.
    pub latencies: Vec<Duration>,
    /// Requests not answered within the window (up to [`LIST_CAP`]).
    pub unanswered: Vec<Pending<A>>,
    /// Requests not answered beyond those listed.
    pub unanswered_more: u64,
    /// Requests the capture ended less than a window after (cannot tell).
    pub cut: Vec<Pending<A>>,
    /// Answers by kind (for acknowledgements: NAKs).
    pub negative: u64,
}

impl<A> Default for Answers<A> {
    fn default() -> Self {
        Answers {
            latencies: Vec::new(),
            unanswered: Vec::new(),
            unanswered_more: 0,
            cut: Vec::new(),
            negative: 0,
        }
    }
}

impl<A> Answers<A> {
    /// Requests judged (answered or not; cut ones aside).
    pub fn judged(&self) -> u64 {
        self.latencies.len() as u64 + self.unanswered.len() as u64 + self.unanswered_more
    }

    /// Requests not answered.
    pub fn missing(&self) -> u64 {
        self.unanswered.len() as u64 + self.unanswered_more
    }

    /// "p50 1.2 ms, max 4.0 ms" of the answered ones, or `None`.
    pub fn latency_text(&self) -> Option<String> {
        if self.latencies.is_empty() {
            return None;
        }
        let mut v = self.latencies.clone();
        v.sort();
        let p50 = v[(v.len() - 1) / 2];
        let max = v[v.len() - 1];
        Some(format!(
            "latency p50 {:.1} ms, max {:.1} ms",
            p50.as_secs_f64() * 1e3,
            max.as_secs_f64() * 1e3
        ))
    }
}

/// The requests waiting for one answer: the group they are judged in, oldest first.
type Waiting<A> = (bool, VecDeque<Pending<A>>);

/// The requests waiting, keyed by asker, receiver and the code of the answer expected.
#[derive(Debug)]
pub(crate) struct Pairs<A: Hash + Eq + Ord + Copy> {
    /// Per asker, receiver and answer code: the group judged in, the requests.
    waiting: HashMap<(A, A, u16), Waiting<A>>,
    /// Requests waiting now.
    count: usize,
    /// The most requests waiting at once.
    pub cap: usize,
    /// Requests not tracked because `cap` were waiting.
    pub dropped: u64,
    /// How long an answer may take.
    window: Duration,
    /// When the next sweep of the expired is due ([`Pairs::expire`] sweeps at most
    /// eight times a window; [`Pairs::answer`] sees to those not swept yet).
    next_sweep: Duration,
    /// Per receiver and group (`true`: required), what it answered.
    pub results: BTreeMap<(A, bool), Answers<A>>,
}

impl<A: Hash + Eq + Ord + Copy> Pairs<A> {
    /// Nothing waiting; at most `cap` at once, answers due within `window`.
    pub fn new(cap: usize, window: Duration) -> Self {
        Pairs {
            window,
            next_sweep: Duration::ZERO,
            waiting: HashMap::new(),
            count: 0,
            cap,
            dropped: 0,
            results: BTreeMap::new(),
        }
    }

    /// `asker` sent request `req` to `receiver`, which answers with code `answer`;
    /// `required` is the group it is judged in.
    pub fn ask(&mut self, receiver: A, answer: u16, req: Pending<A>, required: bool) {
        if self.count >= self.cap {
            self.dropped += 1;
            return;
        }
        let key = (req.asker, receiver, answer);
        let entry = self.waiting.entry(key).or_default();
        entry.0 = required;
        entry.1.push_back(req);
        self.results.entry((receiver, required)).or_default();
        self.count += 1;
    }

    /// `receiver` answered `asker` with code `answer` at `time`: the oldest request it
    /// answers, if one waits (its latency kept; `negative` counts it as a NAK).
    pub fn answer(
        &mut self,
        asker: A,
        receiver: A,
        answer: u16,
        time: Duration,
        negative: bool,
    ) -> Option<Pending<A>> {
        let key = (asker, receiver, answer);
        let (group, q) = self.waiting.get_mut(&key)?;
        let group = *group;
        let r = self.results.entry((receiver, group)).or_default();
        // Requests older than the window not swept yet were not answered in time.
        let mut found = None;
        while let Some(p) = q.pop_front() {
            self.count -= 1;
            if time.saturating_sub(p.time) <= self.window {
                found = Some(p);
                break;
            }
            if r.unanswered.len() < LIST_CAP {
                r.unanswered.push(p);
            } else {
                r.unanswered_more += 1;
            }
        }
        if q.is_empty() {
            self.waiting.remove(&key);
        }
        let req = found?;
        r.latencies.push(time.saturating_sub(req.time));
        if negative {
            r.negative += 1;
        }
        Some(req)
    }

    /// Moves the requests older than the window at `now` to the unanswered (when a
    /// sweep is due).
    pub fn expire(&mut self, now: Duration) {
        if now < self.next_sweep {
            return;
        }
        self.next_sweep = now + self.window / 8;
        let window = self.window;
        self.sweep(|p| now.saturating_sub(p.time) > window, false);
    }

    /// The capture ended at `end`: requests a whole window old are unanswered, the
    /// others cut.
    pub fn finish(&mut self, end: Duration) {
        let window = self.window;
        self.sweep(|p| end.saturating_sub(p.time) >= window, false);
        self.sweep(|_| true, true);
    }

    fn sweep(&mut self, old: impl Fn(&Pending<A>) -> bool, cut: bool) {
        let mut emptied = Vec::new();
        for (key, (group, q)) in self.waiting.iter_mut() {
            let group = *group;
            while let Some(p) = q.front().copied() {
                if !old(&p) {
                    break;
                }
                q.pop_front();
                self.count -= 1;
                let r = self.results.entry((key.1, group)).or_default();
                if cut {
                    if r.cut.len() < LIST_CAP {
                        r.cut.push(p);
                    }
                } else if r.unanswered.len() < LIST_CAP {
                    r.unanswered.push(p);
                } else {
                    r.unanswered_more += 1;
                }
            }
            if q.is_empty() {
                emptied.push(*key);
            }
        }
        for key in emptied {
            self.waiting.remove(&key);
        }
        if cut {
            for r in self.results.values_mut() {
                r.unanswered.sort_by_key(|p| p.number);
                r.cut.sort_by_key(|p| p.number);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(number: u64, ms: u64) -> Pending<u8> {
        Pending {
            number,
            time: Duration::from_millis(ms),
            code: 0x2002,
            asker: 1,
        }
    }

    #[test]
    fn answered_expired_cut_and_dropped() {
        let w = Duration::from_secs(1);
        let mut pairs = Pairs::new(3, w);
        pairs.ask(2, 0x4002, p(1, 0), true);
        pairs.ask(2, 0x4002, p(2, 10), true);
        pairs.ask(2, 0x4002, p(3, 1900), true);
        pairs.ask(2, 0x4002, p(4, 1950), true); // over the cap
        assert!(pairs
            .answer(1, 2, 0x4002, Duration::from_millis(5), false)
            .is_some_and(|r| r.number == 1));
        pairs.expire(Duration::from_millis(1500));
        pairs.finish(Duration::from_millis(2000));
        let r = &pairs.results[&(2, true)];
        assert_eq!(r.latencies, vec![Duration::from_millis(5)]);
        assert_eq!(
            r.unanswered.iter().map(|p| p.number).collect::<Vec<_>>(),
            [2]
        );
        assert_eq!(r.cut.iter().map(|p| p.number).collect::<Vec<_>>(), [3]);
        assert_eq!(pairs.dropped, 1);
        assert_eq!(r.latency_text().unwrap(), "latency p50 5.0 ms, max 5.0 ms");
    }

    #[test]
    fn an_answer_after_the_window_is_late_even_before_a_sweep() {
        let w = Duration::from_secs(1);
        let mut pairs = Pairs::new(10, w);
        pairs.expire(Duration::ZERO); // the next sweep is 125 ms on
        pairs.ask(2, 0x4002, p(1, 0), true);
        pairs.ask(2, 0x4002, p(2, 1050), true);
        // 1.1 s: no sweep since, the first request is late, the second is answered.
        let got = pairs.answer(1, 2, 0x4002, Duration::from_millis(1100), false);
        assert_eq!(got.map(|p| p.number), Some(2));
        pairs.finish(Duration::from_millis(5000));
        let r = &pairs.results[&(2, true)];
        assert_eq!(
            r.unanswered.iter().map(|p| p.number).collect::<Vec<_>>(),
            [1]
        );
        assert_eq!(r.latencies, vec![Duration::from_millis(50)]);
    }
}
