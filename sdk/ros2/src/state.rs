//! What the ROS 2 side ([`crate::bridge`]) and the JAUS components share: the
//! [`Shared`] state behind a mutex ([`lock`]) — the latest samples and camera
//! [`Frame`], the command mailbox, the counters ([`BridgeStats`]) and the watchdog
//! events — and the [`Tap`] the components hold on it. The ROS thread fills it; the
//! sensors ([`crate::sensors`]) and the robot's components ([`crate::robot`]) read it.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Instant;

use jaus::stock::hardware::{LocalPose, VelocityState};
use jaus::Address;
use mio::{Ready, SetReadiness};

use crate::msg::{Image, Time, Twist};

/// Watchdog events kept for [`Ros2Link::events`](crate::Ros2Link::events); older ones are dropped and counted.
const MAX_EVENTS: usize = 256;
/// Why the bridge stopped the robot, or that the ROS side came back.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WatchdogEvent {
    /// The JAUS Primitive Driver stopped (control lost, Standby, Emergency, Shutdown,
    /// Failure, or a wrench effort not refreshed within the command timeout): a zero
    /// twist was published.
    JausStop {
        /// When.
        at: Instant,
        /// The controller that released control or vanished, when that was the reason.
        controller: Option<Address>,
        /// `control lost`, `standby`, `emergency`, `shutdown`, `failure` or
        /// `command timeout`.
        reason: &'static str,
    },
    /// No `odom` within the watchdog time: a zero twist was published and commands are
    /// held at zero.
    RosSilent {
        /// When.
        at: Instant,
    },
    /// `odom` arrived again after a silence: commands pass again.
    RosResumed {
        /// When.
        at: Instant,
    },
}

/// Counters of the bridge.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BridgeStats {
    /// `odom` samples used.
    pub odom: u64,
    /// `fix` samples used.
    pub fix: u64,
    /// Samples refused: not finite, no fix, or undecodable (read errors).
    pub refused: u64,
    /// `odom` samples in frames other than the configured ones (ignored).
    pub foreign_frames: u64,
    /// `cmd_vel` messages published.
    pub published: u64,
    /// Zero twists among them.
    pub published_zero: u64,
    /// Publications DDS refused.
    pub publish_errors: u64,
    /// Commands replaced in the mailbox by a newer one before being published.
    pub superseded: u64,
    /// Non-zero commands held at zero while the ROS side was silent.
    pub held: u64,
    /// Watchdog events dropped from the full event queue.
    pub events_dropped: u64,
    /// `scan` sweeps taken.
    pub scans: u64,
    /// `scan` sweeps dropped (too many beams, angles or limits not finite, undecodable).
    pub scans_refused: u64,
    /// Camera images taken.
    pub images: u64,
    /// Camera images dropped (encoding or format not handled, too large, step or data
    /// too short, a PNG that does not decode, undecodable).
    pub images_refused: u64,
}

/// The latest odometry as JAUS sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OdomSample {
    /// Local pose (JAUS local frame).
    pub pose: LocalPose,
    /// Velocity state (JAUS vehicle frame).
    pub velocity: VelocityState,
    /// When the bridge took it from DDS.
    pub received: Instant,
    /// Its `header.stamp`.
    pub stamp: Time,
}

#[derive(Debug, Default)]
pub(crate) struct Shared {
    pub(crate) odom: Option<OdomSample>,
    pub(crate) fix: Option<(jaus::stock::hardware::GlobalPose, Instant)>,
    /// The latest sweep (platform frame) and when it was taken.
    pub(crate) scan: Option<(Vec<jaus::stock::environment::scan::Beam>, Instant)>,
    /// The latest camera message and when it was taken.
    pub(crate) image: Option<(Arc<Frame>, Instant)>,
    pub(crate) pending: Option<Twist>,
    pub(crate) last_published: Option<Twist>,
    pub(crate) silent: bool,
    pub(crate) stop: bool,
    pub(crate) stats: BridgeStats,
    pub(crate) events: VecDeque<WatchdogEvent>,
}

impl Shared {
    pub(crate) fn event(&mut self, e: WatchdogEvent) {
        if self.events.len() >= MAX_EVENTS {
            self.events.pop_front();
            self.stats.events_dropped += 1;
        }
        self.events.push_back(e);
    }
}

/// Locks `m`; a panic elsewhere while it was held leaves plain data, still usable.
pub(crate) fn lock(m: &Mutex<Shared>) -> MutexGuard<'_, Shared> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// What the JAUS components hold: the shared state and the mailbox's doorbell.
#[derive(Debug, Clone)]
pub(crate) struct Tap {
    pub(crate) shared: Arc<Mutex<Shared>>,
    pub(crate) bell: SetReadiness,
}

impl Tap {
    /// Puts `t` in the mailbox and wakes the ROS thread.
    pub(crate) fn command(&self, t: Twist) {
        {
            let mut s = lock(&self.shared);
            if s.pending.replace(t).is_some() {
                s.stats.superseded += 1;
            }
        }
        // Fails only when the thread's poll is gone (it stopped): nothing to wake.
        let _ = self.bell.set_readiness(Ready::readable());
    }
}

#[cfg(test)]
impl Tap {
    /// A tap with no ROS thread behind it.
    pub(crate) fn detached() -> Tap {
        Tap {
            shared: Arc::new(Mutex::new(Shared::default())),
            bell: mio::Registration::new2().1,
        }
    }
}

/// The latest camera message, converted when the Visual Sensor asks for a frame.
#[derive(Debug)]
pub(crate) enum Frame {
    Raw(Image),
    Png(Vec<u8>),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_event_queue_is_bounded() {
        let mut s = Shared::default();
        for _ in 0..MAX_EVENTS + 5 {
            s.event(WatchdogEvent::RosSilent { at: Instant::now() });
        }
        assert_eq!(s.events.len(), MAX_EVENTS);
        assert_eq!(s.stats.events_dropped, 5);
    }
}
