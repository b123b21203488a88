//! A simulated radio: a pair of connected [`DataLink`] ends for two Communicators, with
//! frame loss (seeded RNG, so a run is reproducible), latency, a bandwidth limit per
//! direction (frames are sent one after another at that bit rate; a full transmit queue
//! refuses more with [`LinkError::Busy`]) and up/down switching through a
//! [`RadioControl`]. On the caller's (virtual) clock, like everything in this crate.
//!
//! ```
//! use std::time::{Duration, Instant};
//! use jaus::stock::communicator::DataLink;
//! use jaus_sim::radio::{radio_pair, RadioParams};
//!
//! let t0 = Instant::now();
//! let params = RadioParams { latency: Duration::from_millis(10), bandwidth_bps: 8_000, ..RadioParams::default() };
//! let (mut a, mut b, control) = radio_pair(1, params);
//! a.send(t0, &[0u8; 100]).unwrap(); // 800 bits at 8 kbit/s: 100 ms on the air
//! let mut buf = Vec::new();
//! assert!(!b.recv(t0 + Duration::from_millis(109), &mut buf));
//! assert!(b.recv(t0 + Duration::from_millis(110), &mut buf));
//! assert_eq!(buf.len(), 100);
//! control.set_up(false);
//! assert!(a.send(t0, &[1]).is_err());
//! ```

use std::collections::VecDeque;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

use jaus::stock::communicator::{DataLink, LinkError};

/// How the radio behaves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadioParams {
    /// Probability that a frame is lost on the air.
    pub loss: f64,
    /// One-way latency added after a frame's transmission time.
    pub latency: Duration,
    /// Bit rate of each direction, bits/s; 0: unlimited (a frame takes no air time).
    pub bandwidth_bps: u64,
    /// Most frames waiting to be sent per direction (the one on the air included); more
    /// are refused with [`LinkError::Busy`].
    pub queue_frames: usize,
    /// Largest frame, bytes (a full JAUS packet is 4,096).
    pub mtu: usize,
    /// Seed of the loss RNG.
    pub seed: u64,
}

/// No loss, 20 ms latency, 1 Mbit/s, 64 frames of queue, 4,096-byte frames, seed 1.
///
/// ```
/// let p = jaus_sim::radio::RadioParams::default();
/// assert_eq!((p.bandwidth_bps, p.queue_frames, p.mtu), (1_000_000, 64, 4096));
/// ```
impl Default for RadioParams {
    fn default() -> Self {
        Self {
            loss: 0.0,
            latency: Duration::from_millis(20),
            bandwidth_bps: 1_000_000,
            queue_frames: 64,
            mtu: 4096,
            seed: 1,
        }
    }
}

/// What one direction of the radio counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RadioStats {
    /// Frames taken for transmission.
    pub sent: u64,
    /// Bytes of those frames.
    pub bytes_sent: u64,
    /// Frames handed to the far end.
    pub delivered: u64,
    /// Frames lost on the air (the loss probability).
    pub lost: u64,
    /// Frames lost in flight or in the queue when the radio went down.
    pub lost_down: u64,
    /// Frames refused: the transmit queue was full.
    pub refused_busy: u64,
    /// Frames refused: the radio was down.
    pub refused_down: u64,
}

#[derive(Debug, Default)]
struct Direction {
    /// Ends of transmission of the frames accepted and not yet fully on the air.
    tx_ends: VecDeque<Instant>,
    /// When the transmitter is free again.
    free_at: Option<Instant>,
    /// Frames on their way, by arrival time (in order: one transmitter, one latency).
    flight: VecDeque<(Instant, Vec<u8>)>,
    stats: RadioStats,
}

#[derive(Debug)]
struct Air {
    params: RadioParams,
    up: bool,
    rng: StdRng,
    /// `dirs[0]`: end 0 to end 1; `dirs[1]`: end 1 to end 0.
    dirs: [Direction; 2],
    pool: Vec<Vec<u8>>,
}

impl Air {
    fn air_time(&self, len: usize) -> Duration {
        match self.params.bandwidth_bps {
            0 => Duration::ZERO,
            bps => Duration::from_secs_f64((len as f64 * 8.0) / bps as f64),
        }
    }

    fn down(&mut self) {
        for d in &mut self.dirs {
            d.stats.lost_down += d.flight.len() as u64;
            self.pool
                .extend(d.flight.drain(..).map(|(_, b)| b).take(POOL));
            d.tx_ends.clear();
            d.free_at = None;
        }
        self.pool.truncate(POOL);
    }
}

/// Most frame buffers the radio keeps for reuse.
const POOL: usize = 256;

fn lock(air: &Mutex<Air>) -> MutexGuard<'_, Air> {
    // A panic while holding the lock leaves nothing half-done that matters to a
    // simulation; keep going with the data.
    air.lock().unwrap_or_else(|e| e.into_inner())
}

/// One end of a simulated radio link (a [`DataLink`]).
#[derive(Debug, Clone)]
pub struct Radio {
    id: u8,
    end: usize,
    air: Arc<Mutex<Air>>,
}

/// Switches a simulated radio up and down and reads its counters.
#[derive(Debug, Clone)]
pub struct RadioControl {
    air: Arc<Mutex<Air>>,
}

/// Two connected ends of a radio link with data link id `id` (the same on both sides),
/// up, and the control of the pair.
pub fn radio_pair(id: u8, params: RadioParams) -> (Radio, Radio, RadioControl) {
    let air = Arc::new(Mutex::new(Air {
        params,
        up: true,
        rng: StdRng::seed_from_u64(params.seed),
        dirs: [Direction::default(), Direction::default()],
        pool: Vec::new(),
    }));
    (
        Radio {
            id,
            end: 0,
            air: air.clone(),
        },
        Radio {
            id,
            end: 1,
            air: air.clone(),
        },
        RadioControl { air },
    )
}

impl RadioControl {
    /// Brings the link up or takes it down (frames on the air or queued are lost).
    pub fn set_up(&self, up: bool) {
        let mut air = lock(&self.air);
        if air.up && !up {
            air.down();
        }
        air.up = up;
    }

    /// Whether the link is up.
    pub fn is_up(&self) -> bool {
        lock(&self.air).up
    }

    /// Changes the loss probability.
    pub fn set_loss(&self, loss: f64) {
        lock(&self.air).params.loss = loss;
    }

    /// The counters of the direction from end `from` (0 or 1) to the other.
    pub fn stats(&self, from: usize) -> RadioStats {
        lock(&self.air).dirs[from.min(1)].stats
    }

    /// The parameters.
    pub fn params(&self) -> RadioParams {
        lock(&self.air).params
    }
}

impl Radio {
    /// Which end this is (0 or 1).
    pub fn end(&self) -> usize {
        self.end
    }
}

impl DataLink for Radio {
    fn id(&self) -> u8 {
        self.id
    }

    fn send(&mut self, now: Instant, frame: &[u8]) -> Result<(), LinkError> {
        let mut guard = lock(&self.air);
        let air = &mut *guard;
        let end = self.end;
        if !air.up {
            air.dirs[end].stats.refused_down += 1;
            return Err(LinkError::Down);
        }
        if frame.len() > air.params.mtu {
            return Err(LinkError::TooLarge {
                len: frame.len(),
                max: air.params.mtu,
            });
        }
        let air_time = air.air_time(frame.len());
        let lost = air.params.loss > 0.0 && air.rng.gen::<f64>() < air.params.loss;
        let latency = air.params.latency;
        let queue = air.params.queue_frames;
        let mut buf = air.pool.pop().unwrap_or_default();
        let d = &mut air.dirs[end];
        while d.tx_ends.front().is_some_and(|t| *t <= now) {
            d.tx_ends.pop_front();
        }
        if d.tx_ends.len() >= queue {
            d.stats.refused_busy += 1;
            air.pool.push(buf);
            return Err(LinkError::Busy);
        }
        let start = d.free_at.map_or(now, |t| t.max(now));
        let done = start + air_time;
        d.free_at = Some(done);
        d.tx_ends.push_back(done);
        d.stats.sent += 1;
        d.stats.bytes_sent += frame.len() as u64;
        if lost {
            d.stats.lost += 1;
            air.pool.push(buf);
        } else {
            buf.clear();
            buf.extend_from_slice(frame);
            d.flight.push_back((done + latency, buf));
        }
        Ok(())
    }

    fn recv(&mut self, now: Instant, buf: &mut Vec<u8>) -> bool {
        let mut guard = lock(&self.air);
        let air = &mut *guard;
        let d = &mut air.dirs[1 - self.end];
        if d.flight.front().is_none_or(|(t, _)| *t > now) {
            return false;
        }
        let Some((_, mut frame)) = d.flight.pop_front() else {
            return false;
        };
        d.stats.delivered += 1;
        std::mem::swap(buf, &mut frame);
        if air.pool.len() < POOL {
            air.pool.push(frame);
        }
        true
    }

    fn is_up(&self, _now: Instant) -> bool {
        lock(&self.air).up
    }

    fn poll_timeout(&self) -> Option<Instant> {
        lock(&self.air).dirs[1 - self.end]
            .flight
            .front()
            .map(|(t, _)| *t)
    }

    fn ready_at(&self) -> Option<Instant> {
        let air = lock(&self.air);
        let ends = &air.dirs[self.end].tx_ends;
        // With n frames waiting, fewer than `queue_frames` are left once the one at
        // index n - queue_frames is on the air. (None: room now.)
        let i = ends.len().checked_sub(air.params.queue_frames.max(1))?;
        ends.get(i).copied()
    }
}
