//! What the node thread and the web server share: the page's commands on their way to
//! the station (bounded, drops counted), the latest published view, the view with trails,
//! and the message log.

use std::collections::VecDeque;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};

use tokio::sync::watch;

use crate::log::MessageLog;

/// Page messages waiting for the node thread (more are refused with an error notice).
pub const INBOX_MAX: usize = 256;

/// What the node thread publishes for the web server.
#[derive(Debug, Default)]
pub struct Published {
    /// The station's view without trails, as JSON.
    pub view: String,
    /// Number of the last logged message.
    pub log_seq: u64,
    /// When it was published, ms since the Unix epoch.
    pub unix_ms: f64,
}

/// State shared by the node thread and the web server.
#[derive(Debug)]
pub struct Shared {
    pub(crate) inbox: Mutex<VecDeque<String>>,
    pub(crate) dropped: AtomicU64,
    /// Requests the web server refused (guard).
    pub(crate) refused: AtomicU64,
    /// The latest view, new at most every [`ConsoleOptions::publish_period`].
    pub view: watch::Sender<Arc<Published>>,
    /// The latest view with trails, refreshed at most once a second and when asked.
    pub(crate) trails: Mutex<Arc<String>>,
    pub(crate) trails_wanted: AtomicBool,
    /// The message log.
    pub log: Mutex<MessageLog>,
}

pub(crate) fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    // A panic while holding the lock leaves data that is still consistent here
    // (every writer replaces whole values), so the lock is taken over.
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

impl Shared {
    pub(crate) fn new(log: MessageLog) -> Arc<Self> {
        Arc::new(Self {
            inbox: Mutex::new(VecDeque::new()),
            dropped: 0.into(),
            refused: 0.into(),
            view: watch::Sender::new(Arc::new(Published::default())),
            trails: Mutex::new(Arc::new(String::from("{}"))),
            trails_wanted: AtomicBool::new(true),
            log: Mutex::new(log),
        })
    }

    /// Queues a page message for the node thread; false (and counted) when the queue is
    /// full.
    pub fn submit(&self, text: String) -> bool {
        let mut q = lock(&self.inbox);
        if q.len() >= INBOX_MAX {
            self.dropped.fetch_add(1, Ordering::Relaxed);
            return false;
        }
        q.push_back(text);
        true
    }

    /// The web server's counters as JSON: requests refused by the guard, page
    /// messages waiting and dropped.
    pub fn stats_json(&self) -> String {
        serde_json::json!({
            "refused": self.refused.load(Ordering::Relaxed),
            "inbox": lock(&self.inbox).len(),
            "dropped": self.dropped.load(Ordering::Relaxed),
        })
        .to_string()
    }

    /// The latest view with trails (JSON); asks the node thread for a fresh one.
    pub fn trails(&self) -> Arc<String> {
        self.trails_wanted.store(true, Ordering::Relaxed);
        lock(&self.trails).clone()
    }

    /// Log entries after `after`, at most `max`, as a JSON array.
    pub fn log_since(&self, after: u64, max: usize) -> (String, u64) {
        let log = lock(&self.log);
        let entries = log.since(after, max);
        let last = entries.last().map_or(after, |e| e.seq);
        (
            serde_json::to_string(&entries).unwrap_or_else(|_| "[]".into()),
            last,
        )
    }
}
