//! What crosses between the client's I/O thread and Python: the commands, their
//! answers, the bounded queues of a watch's reports, and the counters of `stats()`.

use std::collections::VecDeque;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{mpsc, Condvar, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use jaus::{Address, CommandCode};
use jaus_dynamic::DynMessage;

/// The answer to a command: sent once by the I/O thread.
pub(crate) type Reply<T> = mpsc::SyncSender<Result<T, Failure>>;

/// Why a command failed: the text, and for a control request the response code.
#[derive(Debug, Clone)]
pub(crate) struct Failure {
    pub(crate) text: String,
    /// `ControlAccepted`-style name of the refusal (control requests only).
    pub(crate) response_code: Option<String>,
}

impl Failure {
    pub(crate) fn new(text: impl Into<String>) -> Failure {
        Failure {
            text: text.into(),
            response_code: None,
        }
    }
}

/// A request from Python to the I/O thread.
#[derive(Debug)]
pub(crate) enum Cmd {
    /// A message to send; `ack`: wait for its ACK or NAK; `confirm`: confirm it by its
    /// effect ([`jaus_client::confirm`]).
    Send {
        to: Address,
        code: CommandCode,
        name: &'static str,
        body: Vec<u8>,
        ack: Option<(Duration, Reply<()>)>,
        /// Confirm it by its effect, reading back for at most this long: how it ended.
        confirm: Option<(Duration, Reply<jaus_client::confirm::Confirmation>)>,
    },
    /// A query; the answer is the message with code `answer` from `to`.
    Query {
        to: Address,
        code: CommandCode,
        name: &'static str,
        body: Vec<u8>,
        answer: CommandCode,
        wait: Duration,
        reply: Reply<DynMessage>,
    },
    /// Take and keep control of `to`.
    Keep {
        to: Address,
        authority: Option<u8>,
        wait: Duration,
        reply: Reply<()>,
    },
    /// Give control of `to` back.
    Release { to: Address, reply: Reply<()> },
    /// Reports of `report` from `to` into `feed`: a service connection at `periodic_hz`,
    /// or an event on every change when `None`.
    Watch {
        id: u64,
        to: Address,
        query: CommandCode,
        query_body: Vec<u8>,
        report: CommandCode,
        periodic_hz: Option<f64>,
        presence: u32,
        feed: std::sync::Arc<Feed>,
        wait: Duration,
        reply: Reply<()>,
    },
    /// End watch `id` (its service connection or event).
    Unwatch { id: u64 },
    /// The system tree as `jaus discover --json` prints it.
    Tree { reply: Reply<serde_json::Value> },
    /// End everything and stop the thread.
    Close,
}

/// The counters of `Client.stats()`.
#[derive(Debug, Default)]
pub(crate) struct Stats {
    pub(crate) datagrams_received: AtomicU64,
    pub(crate) messages_sent: AtomicU64,
    pub(crate) messages_received: AtomicU64,
    pub(crate) unclaimed: AtomicU64,
    pub(crate) reports_dropped: AtomicU64,
    pub(crate) decode_errors: AtomicU64,
    pub(crate) naks: AtomicU64,
    pub(crate) control_lost: AtomicU64,
    pub(crate) commands_dropped: AtomicU64,
    pub(crate) send_errors: AtomicU64,
}

impl Stats {
    pub(crate) fn add(counter: &AtomicU64) {
        counter.fetch_add(1, Ordering::Relaxed);
    }

    /// Every counter by name.
    pub(crate) fn snapshot(&self) -> Vec<(&'static str, u64)> {
        let g = |c: &AtomicU64| c.load(Ordering::Relaxed);
        vec![
            ("datagrams_received", g(&self.datagrams_received)),
            ("messages_sent", g(&self.messages_sent)),
            ("messages_received", g(&self.messages_received)),
            ("unclaimed", g(&self.unclaimed)),
            ("reports_dropped", g(&self.reports_dropped)),
            ("decode_errors", g(&self.decode_errors)),
            ("naks", g(&self.naks)),
            ("control_lost", g(&self.control_lost)),
            ("commands_dropped", g(&self.commands_dropped)),
            ("send_errors", g(&self.send_errors)),
        ]
    }
}

/// One item of a watch: a report, or a report that did not decode.
pub(crate) type Item = Result<DynMessage, String>;

#[derive(Debug, Default)]
struct FeedState {
    items: VecDeque<Item>,
    /// Why the feed ended (`None`: still open).
    ended: Option<String>,
}

/// The bounded queue of one watch: the oldest report is dropped (and counted) when
/// Python does not keep up.
#[derive(Debug)]
pub(crate) struct Feed {
    state: Mutex<FeedState>,
    ready: Condvar,
    capacity: usize,
    dropped: AtomicU64,
}

/// What [`Feed::pop`] found.
#[derive(Debug)]
pub(crate) enum Pop {
    Item(Item),
    /// Nothing within the time given.
    Empty,
    /// The feed ended (and is empty).
    Ended,
}

impl Feed {
    pub(crate) fn new(capacity: usize) -> Feed {
        Feed {
            state: Mutex::new(FeedState::default()),
            ready: Condvar::new(),
            capacity: capacity.max(1),
            dropped: AtomicU64::new(0),
        }
    }

    fn lock(&self) -> MutexGuard<'_, FeedState> {
        // A panic while holding the lock leaves plain data behind: keep using it.
        self.state.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Adds `item`; returns false when the oldest was dropped to make room.
    pub(crate) fn push(&self, item: Item) -> bool {
        let mut s = self.lock();
        if s.ended.is_some() {
            return true;
        }
        let mut kept = true;
        if s.items.len() >= self.capacity {
            s.items.pop_front();
            self.dropped.fetch_add(1, Ordering::Relaxed);
            kept = false;
        }
        s.items.push_back(item);
        self.ready.notify_all();
        kept
    }

    /// Ends the feed (the reports queued stay readable).
    pub(crate) fn end(&self, why: &str) {
        let mut s = self.lock();
        if s.ended.is_none() {
            s.ended = Some(why.to_string());
        }
        self.ready.notify_all();
    }

    /// Whether the feed ended.
    pub(crate) fn ended(&self) -> Option<String> {
        self.lock().ended.clone()
    }

    /// Reports dropped because the queue was full.
    pub(crate) fn dropped(&self) -> u64 {
        self.dropped.load(Ordering::Relaxed)
    }

    /// The next report, waiting up to `wait` (`None`: until one comes or the feed ends).
    pub(crate) fn pop(&self, wait: Option<Duration>) -> Pop {
        let deadline = wait.map(|w| Instant::now() + w);
        let mut s = self.lock();
        loop {
            if let Some(item) = s.items.pop_front() {
                return Pop::Item(item);
            }
            if s.ended.is_some() {
                return Pop::Ended;
            }
            // Woken at least every 100 ms so that Python's signals (Ctrl-C) are seen.
            let step = Duration::from_millis(100);
            let left = match deadline {
                Some(d) => match d.checked_duration_since(Instant::now()) {
                    Some(l) if !l.is_zero() => l.min(step),
                    _ => return Pop::Empty,
                },
                None => step,
            };
            s = match self.ready.wait_timeout(s, left) {
                Ok((g, _)) => g,
                Err(p) => p.into_inner().0,
            };
            if wait.is_none() && s.items.is_empty() && s.ended.is_none() {
                return Pop::Empty;
            }
        }
    }
}
