//! What the JAUS thread (the bridge's System Commander component) and the ROS thread
//! share in vehicle mode: the latest reports one way, the latest commands the other,
//! counters and a bounded event queue. Latest-value slots, never queues of data: a
//! stale pose or command is replaced, not delivered late.

use std::collections::{BTreeMap, VecDeque};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use jaus::component::CoreState;
use jaus::messages::{ReportGlobalPose, ReportLocalPose, ReportVelocityState};
use jaus::Address;

use super::core::role;
use crate::msg::{PoseStamped, Twist};

/// Events kept for [`VehicleLink::events`](super::VehicleLink::events).
pub(crate) const MAX_EVENTS: usize = 256;
/// `cmd_vel` → Set Wrench Effort latencies kept.
pub(crate) const MAX_LATENCIES: usize = 1024;

/// What happened in vehicle mode that an operator wants to know.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VehicleEvent {
    /// Control of the component was granted to the bridge.
    ControlGained {
        /// When.
        at: Instant,
        /// The component (Primitive Driver or a waypoint driver).
        component: Address,
    },
    /// Control of the component was lost (another controller with a higher authority,
    /// the component let it go or restarted): the bridge sends it nothing more until a
    /// new `cmd_vel` or `goal_pose` asks for control again.
    ControlLost {
        /// When.
        at: Instant,
        /// The component.
        component: Address,
    },
    /// No `cmd_vel` within the timeout: zero efforts were sent.
    CmdVelSilent {
        /// When.
        at: Instant,
    },
    /// A `goal_pose` was sent to a waypoint driver (Resume, Set Travel Speed, the
    /// waypoint).
    GoalSent {
        /// When.
        at: Instant,
        /// The driver.
        driver: Address,
    },
    /// A `goal_pose` could not be sent: no waypoint driver, no fix yet for a Global
    /// Waypoint Driver, or numbers that are not finite.
    GoalRefused {
        /// When.
        at: Instant,
        /// Why.
        reason: &'static str,
    },
}

/// Counters of vehicle mode.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct VehicleStats {
    /// Report Local Pose received.
    pub local_pose: u64,
    /// Report Velocity State received.
    pub velocity: u64,
    /// Report Global Pose received.
    pub global_pose: u64,
    /// `odom` published.
    pub odom: u64,
    /// `fix` published.
    pub fix: u64,
    /// `jaus/status` published.
    pub status: u64,
    /// Reports that did not convert (not finite, out of range) and were dropped.
    pub refused_reports: u64,
    /// `cmd_vel` taken.
    pub cmd_vel: u64,
    /// `goal_pose` taken.
    pub goals: u64,
    /// ROS samples refused (undecodable, not finite).
    pub refused_ros: u64,
    /// Set Wrench Effort sent (refreshes included).
    pub wrench_sent: u64,
    /// Zero efforts sent by the `cmd_vel` watchdog.
    pub watchdog_stops: u64,
    /// Ticks at which a command was due but control was not held (yet).
    pub not_in_control: u64,
    /// Publications DDS refused.
    pub publish_errors: u64,
    /// Events dropped from the full queue.
    pub events_dropped: u64,
}

/// The last status and controller a component reported.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ComponentStatus {
    /// Core state (Report Component Status).
    pub state: Option<CoreState>,
    /// Controller and its authority (Report Component Control); `None` when it named
    /// none or has not answered.
    pub controller: Option<(Address, u8)>,
}

#[derive(Debug, Default)]
pub(crate) struct VShared {
    /// The vehicle's components in the system tree (the shell fills it).
    pub(crate) tree: Vec<Address>,
    pub(crate) local: Option<ReportLocalPose>,
    pub(crate) local_seq: u64,
    pub(crate) velocity: Option<(ReportVelocityState, Instant)>,
    pub(crate) global: Option<ReportGlobalPose>,
    pub(crate) global_seq: u64,
    pub(crate) status: BTreeMap<Address, ComponentStatus>,
    pub(crate) status_seq: u64,
    /// Components whose control the bridge holds.
    pub(crate) held: Vec<Address>,
    pub(crate) cmd: Option<(Twist, Instant)>,
    pub(crate) cmd_seq: u64,
    pub(crate) goal: Option<PoseStamped>,
    pub(crate) stop: bool,
    pub(crate) stats: VehicleStats,
    pub(crate) events: VecDeque<VehicleEvent>,
    pub(crate) latencies: VecDeque<Duration>,
    pub(crate) me: Option<Address>,
}

impl VShared {
    pub(crate) fn event(&mut self, e: VehicleEvent) {
        if self.events.len() >= MAX_EVENTS {
            self.events.pop_front();
            self.stats.events_dropped += 1;
        }
        self.events.push_back(e);
    }

    pub(crate) fn latency(&mut self, d: Duration) {
        if self.latencies.len() >= MAX_LATENCIES {
            self.latencies.pop_front();
        }
        self.latencies.push_back(d);
    }

    /// The `jaus/status` text: each component of the vehicle, its state and controller.
    pub(crate) fn status_text(&self) -> String {
        let mut parts = Vec::new();
        for (a, s) in &self.status {
            let state = s.state.map_or("?".to_string(), |st| format!("{st:?}"));
            let ctl = match s.controller {
                Some((c, auth)) if Some(c) == self.me => {
                    format!("controller {c} (this bridge, authority {auth})")
                }
                Some((c, auth)) => format!("controller {c} (authority {auth})"),
                None => "no controller".to_string(),
            };
            let name = role(a.component);
            parts.push(format!("{name} {a}: {state}, {ctl}"));
        }
        if parts.is_empty() {
            "no vehicle components found yet".into()
        } else {
            parts.join("; ")
        }
    }
}

/// Locks `m`; a panic elsewhere while it was held leaves plain data, still usable.
pub(crate) fn vlock(m: &Mutex<VShared>) -> MutexGuard<'_, VShared> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

pub(crate) type Shared = Arc<Mutex<VShared>>;
