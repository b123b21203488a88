//! Where a Digital Video service's frames go: a [`VideoHub`] holds, per sensor, the
//! stream's state and its latest frame (one frame, nothing queued: a viewer slower than
//! the stream skips frames, counted), and wakes the viewers ([`Viewer::next`]) when a
//! frame or a state change comes. The service publishes (sans-IO: no socket, no clock of
//! its own); the node's I/O shell serves the frames (`jaus-node`'s MJPEG over HTTP).

use std::collections::BTreeMap;
use std::fmt;
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::{Duration, Instant};

/// The state of a sensor's stream (Control Digital Video Sensor Stream).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StreamState {
    /// No frames; viewers are told the stream ended.
    Stopped,
    /// Frames at the configured rate.
    Playing,
    /// No new frames; viewers wait.
    Paused,
}

/// One frame of a stream: a baseline JPEG image.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Frame {
    /// Its number in the stream, from 1.
    pub seq: u64,
    /// When the camera's image reached the service.
    pub at: Instant,
    /// The JPEG file.
    pub jpeg: Arc<[u8]>,
}

/// What a stream counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct StreamStats {
    /// Frames published.
    pub published: u64,
    /// Camera images that did not become frames (a format not transcoded, bytes that do
    /// not decode, a frame over the size limit).
    pub dropped: u64,
    /// Frames viewers skipped, being slower than the stream.
    pub skipped: u64,
    /// Viewers watching now.
    pub viewers: usize,
    /// Viewers refused (the hub's viewer limit reached).
    pub viewers_refused: u64,
}

/// Why [`VideoHub::watch`] refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum WatchError {
    /// No stream of that sensor id.
    #[error("no video stream of sensor {0}")]
    Unknown(u16),
    /// The hub's viewer limit is reached.
    #[error("{0} viewers already watch (the limit)")]
    Full(usize),
}

/// What [`Viewer::next`] gives.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Next {
    /// A frame newer than the viewer's last.
    Frame(Frame),
    /// The stream is stopped.
    Stopped,
    /// No frame within the time given (the stream paused, or slow).
    TimedOut,
}

#[derive(Debug)]
struct Slot {
    state: StreamState,
    latest: Option<Frame>,
    stats: StreamStats,
}

#[derive(Debug)]
struct Shared {
    streams: Mutex<BTreeMap<u16, Slot>>,
    changed: Condvar,
    max_viewers: usize,
}

/// The frames of the Digital Video services of a node, shared between the services
/// (publishing) and the viewers (the node's stream transport). Cloning shares it.
#[derive(Clone)]
pub struct VideoHub(Arc<Shared>);

impl fmt::Debug for VideoHub {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("VideoHub")
            .field("sensors", &self.sensors())
            .field("max_viewers", &self.0.max_viewers)
            .finish()
    }
}

impl VideoHub {
    /// A hub serving `max_viewers` viewers at once at most (all streams together).
    pub fn new(max_viewers: usize) -> Self {
        Self(Arc::new(Shared {
            streams: Mutex::new(BTreeMap::new()),
            changed: Condvar::new(),
            max_viewers,
        }))
    }

    fn lock(&self) -> MutexGuard<'_, BTreeMap<u16, Slot>> {
        // A panic while holding the lock left plain data behind: still usable.
        self.0.streams.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The sensor ids with a stream.
    pub fn sensors(&self) -> Vec<u16> {
        self.lock().keys().copied().collect()
    }

    /// The state of sensor `sensor`'s stream, if it has one.
    pub fn state(&self, sensor: u16) -> Option<StreamState> {
        self.lock().get(&sensor).map(|s| s.state)
    }

    /// What sensor `sensor`'s stream counted, if it has one.
    pub fn stats(&self, sensor: u16) -> Option<StreamStats> {
        self.lock().get(&sensor).map(|s| s.stats)
    }

    /// The latest frame of sensor `sensor` (none while stopped).
    pub fn latest(&self, sensor: u16) -> Option<Frame> {
        self.lock().get(&sensor).and_then(|s| s.latest.clone())
    }

    /// A viewer of sensor `sensor`'s stream (its first frame: the latest, if playing).
    pub fn watch(&self, sensor: u16) -> Result<Viewer, WatchError> {
        let mut streams = self.lock();
        let watching: usize = streams.values().map(|s| s.stats.viewers).sum();
        let slot = streams
            .get_mut(&sensor)
            .ok_or(WatchError::Unknown(sensor))?;
        if watching >= self.0.max_viewers {
            slot.stats.viewers_refused += 1;
            return Err(WatchError::Full(self.0.max_viewers));
        }
        slot.stats.viewers += 1;
        Ok(Viewer {
            hub: self.clone(),
            sensor,
            seen: 0,
        })
    }

    /// Adds sensor `sensor`'s stream, stopped (a Digital Video service does, for each
    /// sensor it streams; a vendor's own service over its own camera too).
    pub fn add_stream(&self, sensor: u16) {
        self.lock().entry(sensor).or_insert(Slot {
            state: StreamState::Stopped,
            latest: None,
            stats: StreamStats::default(),
        });
    }

    /// Sets the state of sensor `sensor`'s stream (stopping forgets its frame).
    pub fn set_state(&self, sensor: u16, state: StreamState) {
        if let Some(s) = self.lock().get_mut(&sensor) {
            s.state = state;
            if state == StreamState::Stopped {
                s.latest = None;
            }
        }
        self.0.changed.notify_all();
    }

    /// Publishes a frame of sensor `sensor`, taken at `at`.
    pub fn publish(&self, sensor: u16, at: Instant, jpeg: Vec<u8>) {
        if let Some(s) = self.lock().get_mut(&sensor) {
            s.stats.published += 1;
            s.latest = Some(Frame {
                seq: s.stats.published,
                at,
                jpeg: jpeg.into(),
            });
        }
        self.0.changed.notify_all();
    }

    /// Counts a camera image of sensor `sensor` that did not become a frame.
    pub fn dropped(&self, sensor: u16) {
        if let Some(s) = self.lock().get_mut(&sensor) {
            s.stats.dropped += 1;
        }
    }
}

/// One viewer of a stream ([`VideoHub::watch`]); dropping it frees its place.
#[derive(Debug)]
pub struct Viewer {
    hub: VideoHub,
    sensor: u16,
    seen: u64,
}

impl Viewer {
    /// The sensor watched.
    pub fn sensor(&self) -> u16 {
        self.sensor
    }

    /// The next frame newer than the last one this viewer got, waiting up to `timeout`
    /// for it; [`Next::Stopped`] once the stream is stopped.
    pub fn next(&mut self, timeout: Duration) -> Next {
        let deadline = Instant::now() + timeout;
        let mut streams = self.hub.lock();
        loop {
            let Some(slot) = streams.get_mut(&self.sensor) else {
                return Next::Stopped;
            };
            if slot.state == StreamState::Stopped {
                return Next::Stopped;
            }
            if let Some(f) = slot.latest.as_ref().filter(|f| f.seq > self.seen) {
                if self.seen > 0 {
                    slot.stats.skipped += f.seq - self.seen - 1;
                }
                self.seen = f.seq;
                return Next::Frame(f.clone());
            }
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return Next::TimedOut;
            }
            streams = self
                .hub
                .0
                .changed
                .wait_timeout(streams, left)
                .unwrap_or_else(|e| e.into_inner())
                .0;
        }
    }
}

impl Drop for Viewer {
    fn drop(&mut self) {
        if let Some(s) = self.hub.lock().get_mut(&self.sensor) {
            s.stats.viewers = s.stats.viewers.saturating_sub(1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viewers_get_the_latest_frame_skip_what_they_were_too_slow_for_and_are_bounded() {
        let hub = VideoHub::new(2);
        assert_eq!(hub.watch(1).unwrap_err(), WatchError::Unknown(1));
        hub.add_stream(1);
        let mut a = hub.watch(1).unwrap();
        let _b = hub.watch(1).unwrap();
        assert_eq!(hub.watch(1).unwrap_err(), WatchError::Full(2));
        // Stopped: the viewer is told at once.
        assert_eq!(a.next(Duration::from_secs(5)), Next::Stopped);
        hub.set_state(1, StreamState::Playing);
        assert_eq!(a.next(Duration::from_millis(10)), Next::TimedOut);
        let t = Instant::now();
        for i in 0..3u8 {
            hub.publish(1, t, vec![i]);
        }
        // Only the latest is held: frames 1 and 2 were skipped, but a first frame
        // skips nothing.
        let Next::Frame(f) = a.next(Duration::ZERO) else {
            panic!("a frame")
        };
        assert_eq!((f.seq, &*f.jpeg), (3, [2u8].as_slice()));
        hub.publish(1, t, vec![3]);
        hub.publish(1, t, vec![4]);
        let Next::Frame(f) = a.next(Duration::ZERO) else {
            panic!("a frame")
        };
        assert_eq!(f.seq, 5);
        let s = hub.stats(1).unwrap();
        assert_eq!(
            (s.published, s.skipped, s.viewers, s.viewers_refused),
            (5, 1, 2, 1)
        );
        // A frame published from another thread wakes a waiting viewer.
        let h = hub.clone();
        let t2 = std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(50));
            h.publish(1, Instant::now(), vec![9]);
        });
        assert!(matches!(a.next(Duration::from_secs(5)), Next::Frame(f) if f.seq == 6));
        t2.join().unwrap();
        // Stopping forgets the frame and ends the viewers; dropping frees the place.
        hub.set_state(1, StreamState::Stopped);
        assert_eq!(hub.latest(1), None);
        assert_eq!(a.next(Duration::from_secs(5)), Next::Stopped);
        drop(a);
        assert_eq!(hub.stats(1).unwrap().viewers, 1);
        assert!(hub.watch(1).is_ok());
    }
}
