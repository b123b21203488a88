//! The ROS 2 side of vehicle mode: one thread owning a ROS 2 node that publishes
//! `odom`, `fix` and `jaus/status` from the reports the JAUS component stored, and
//! takes `cmd_vel` and `goal_pose` into latest-value slots the component reads at its
//! next tick. It sleeps in a mio poll on the two readers for at most [`IDLE`], so a
//! command is stored as it arrives and a report is published within [`IDLE`].

use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use mio::{Events, Poll, PollOpt, Ready, Token};
use ros2_client::{
    Context, ContextOptions, MessageTypeName, Node, NodeName, NodeOptions, Publisher, Subscription,
};

use super::core::{nav_sat_fix_of, odometry_of};
use super::shared::{vlock, Shared};
use crate::bridge::{absolute, qos_of};
use crate::config::{Qos, Ros2Config};
use crate::error::Ros2Error;
use crate::msg::{NavSatFix, Odometry, PoseStamped, RosMessage, StdString, Time, Twist};

/// The longest the thread sleeps.
const IDLE: Duration = Duration::from_millis(5);
/// Samples taken from one reader in one round.
const MAX_TAKE: usize = 64;
/// `jaus/status` is published on a change and at least this often.
const STATUS_PERIOD: Duration = Duration::from_secs(1);
/// A velocity report older than this is not used in `odom`'s twist.
const VELOCITY_MAX_AGE: Duration = Duration::from_secs(1);

const CMD_VEL: Token = Token(0);
const GOAL: Token = Token(1);

/// The wall clock as a ROS time stamp.
fn wall_stamp() -> Time {
    let d = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .unwrap_or_default();
    Time {
        sec: i32::try_from(d.as_secs()).unwrap_or(i32::MAX),
        nanosec: d.subsec_nanos(),
    }
}

pub(crate) struct VehicleRos {
    _node: Node,
    odom: Publisher<Odometry>,
    fix: Publisher<NavSatFix>,
    status: Publisher<StdString>,
    cmd_vel: Subscription<Twist>,
    goal: Subscription<PoseStamped>,
    poll: Poll,
}

impl VehicleRos {
    pub(crate) fn open(c: &Ros2Config) -> Result<VehicleRos, Ros2Error> {
        let dds = |what: &str, e: &dyn std::fmt::Debug| Ros2Error::Dds(format!("{what}: {e:?}"));
        let context = Context::with_options(ContextOptions::new().domain_id(c.domain_id))
            .map_err(|e| dds("DDS participant", &e))?;
        let node_name = NodeName::new(&c.namespace, &c.node_name)
            .map_err(|e| Ros2Error::Config(format!("node name: {e:?}")))?;
        let mut node = context
            .new_node(node_name, NodeOptions::new().enable_rosout(false))
            .map_err(|e| dds("ROS 2 node", &e))?;
        let topic = |name: &str, ty: (&str, &str), qos: Qos| {
            let (n, _) = absolute(&c.namespace, name)?;
            node.create_topic(&n, MessageTypeName::new(ty.0, ty.1), &qos_of(qos))
                .map_err(|e| dds(name, &e))
        };
        let t = &c.topics;
        // What the bridge publishes: reliable (matches readers of both kinds); what it
        // reads: best effort (matches writers of both kinds).
        let odom_t = topic(&t.odom, (Odometry::PACKAGE, Odometry::NAME), c.qos_commands)?;
        let fix_t = topic(
            &t.fix,
            (NavSatFix::PACKAGE, NavSatFix::NAME),
            c.qos_commands,
        )?;
        let status_t = topic(
            &t.status,
            (StdString::PACKAGE, StdString::NAME),
            c.qos_commands,
        )?;
        let cmd_t = topic(&t.cmd_vel, (Twist::PACKAGE, Twist::NAME), c.qos_sensors)?;
        let goal_t = topic(
            &t.goal_pose,
            (PoseStamped::PACKAGE, PoseStamped::NAME),
            c.qos_sensors,
        )?;
        let odom = node
            .create_publisher::<Odometry>(&odom_t, None)
            .map_err(|e| dds("odom publisher", &e))?;
        let fix = node
            .create_publisher::<NavSatFix>(&fix_t, None)
            .map_err(|e| dds("fix publisher", &e))?;
        let status = node
            .create_publisher::<StdString>(&status_t, None)
            .map_err(|e| dds("status publisher", &e))?;
        let cmd_vel = node
            .create_subscription::<Twist>(&cmd_t, None)
            .map_err(|e| dds("cmd_vel reader", &e))?;
        let goal = node
            .create_subscription::<PoseStamped>(&goal_t, None)
            .map_err(|e| dds("goal_pose reader", &e))?;
        let poll = Poll::new().map_err(|e| dds("poll", &e))?;
        let edge = PollOpt::edge();
        poll.register(&cmd_vel, CMD_VEL, Ready::readable(), edge)
            .and_then(|_| poll.register(&goal, GOAL, Ready::readable(), edge))
            .map_err(|e| dds("poll registration", &e))?;
        Ok(VehicleRos {
            _node: node,
            odom,
            fix,
            status,
            cmd_vel,
            goal,
            poll,
        })
    }

    fn count_publish<E: std::fmt::Debug>(shared: &Shared, topic: &str, r: Result<(), E>) -> bool {
        match r {
            Ok(()) => true,
            Err(e) => {
                let mut s = vlock(shared);
                s.stats.publish_errors += 1;
                if s.stats.publish_errors % 100 == 1 {
                    // The error's name only: its Debug form carries the whole message.
                    let text = format!("{e:?}");
                    let name = text.split(['{', '(']).next().unwrap_or("").trim();
                    tracing::warn!(
                        topic,
                        errors = s.stats.publish_errors,
                        "jaus-ros2 vehicle: not published: {name}"
                    );
                }
                false
            }
        }
    }

    pub(crate) fn run(self, c: &Ros2Config, shared: &Shared) {
        let mut events = Events::with_capacity(16);
        let (mut local_seq, mut global_seq, mut status_seq) = (0, 0, u64::MAX);
        let mut next_status = Instant::now();
        loop {
            if let Err(e) = self.poll.poll(&mut events, Some(IDLE)) {
                tracing::warn!("jaus-ros2 vehicle: poll failed: {e}");
                std::thread::sleep(IDLE);
            }
            self.take_commands(c, shared);
            let now = Instant::now();
            let stamp = wall_stamp();
            // What to publish, decided under the lock, published after it.
            let (stop, odom, fix, status) = {
                let mut s = vlock(shared);
                let odom = (s.local_seq != local_seq).then(|| {
                    local_seq = s.local_seq;
                    let v = s
                        .velocity
                        .as_ref()
                        .filter(|(_, at)| now.saturating_duration_since(*at) <= VELOCITY_MAX_AGE)
                        .map(|(v, _)| v);
                    s.local
                        .as_ref()
                        .and_then(|p| odometry_of(p, v, stamp, &c.frames.odom, &c.frames.base))
                });
                let odom = odom.and_then(|o| {
                    if o.is_none() {
                        s.stats.refused_reports += 1;
                    }
                    o
                });
                let fix = (s.global_seq != global_seq).then(|| {
                    global_seq = s.global_seq;
                    s.global
                        .as_ref()
                        .and_then(|g| nav_sat_fix_of(g, stamp, &c.frames.base))
                });
                let fix = fix.and_then(|f| {
                    if f.is_none() {
                        s.stats.refused_reports += 1;
                    }
                    f
                });
                let status = (s.status_seq != status_seq || now >= next_status).then(|| {
                    status_seq = s.status_seq;
                    next_status = now + STATUS_PERIOD;
                    s.status_text()
                });
                (s.stop, odom, fix, status)
            };
            if stop {
                return;
            }
            if let Some(o) = odom {
                if Self::count_publish(shared, &c.topics.odom, self.odom.publish(o)) {
                    vlock(shared).stats.odom += 1;
                }
            }
            if let Some(f) = fix {
                if Self::count_publish(shared, &c.topics.fix, self.fix.publish(f)) {
                    vlock(shared).stats.fix += 1;
                }
            }
            if let Some(text) = status {
                let r = self.status.publish(StdString { data: text });
                if Self::count_publish(shared, &c.topics.status, r) {
                    vlock(shared).stats.status += 1;
                }
            }
        }
    }

    fn take_commands(&self, c: &Ros2Config, shared: &Shared) {
        for _ in 0..MAX_TAKE {
            let t = match self.cmd_vel.take() {
                Ok(Some((t, _))) => t,
                Ok(None) => break,
                Err(e) => {
                    vlock(shared).stats.refused_ros += 1;
                    tracing::debug!(topic = %c.topics.cmd_vel, "jaus-ros2 vehicle: Twist not read: {e:?}");
                    continue;
                }
            };
            let at = Instant::now();
            let mut s = vlock(shared);
            let v = [
                t.linear.x,
                t.linear.y,
                t.linear.z,
                t.angular.x,
                t.angular.y,
                t.angular.z,
            ];
            if v.iter().all(|x| x.is_finite()) {
                s.stats.cmd_vel += 1;
                s.cmd = Some((t, at));
                s.cmd_seq += 1;
            } else {
                s.stats.refused_ros += 1;
            }
        }
        for _ in 0..MAX_TAKE {
            let g = match self.goal.take() {
                Ok(Some((g, _))) => g,
                Ok(None) => break,
                Err(e) => {
                    vlock(shared).stats.refused_ros += 1;
                    tracing::debug!(topic = %c.topics.goal_pose, "jaus-ros2 vehicle: PoseStamped not read: {e:?}");
                    continue;
                }
            };
            let mut s = vlock(shared);
            let p = g.pose.position;
            let frame_ok = c.frames.odom.is_empty()
                || g.header.frame_id.is_empty()
                || g.header.frame_id == c.frames.odom;
            if p.x.is_finite() && p.y.is_finite() && frame_ok {
                s.stats.goals += 1;
                s.goal = Some(g);
            } else {
                tracing::warn!(topic = %c.topics.goal_pose, frame = %g.header.frame_id, "jaus-ros2 vehicle: goal refused (not finite, or not in frame {:?})", c.frames.odom);
                s.stats.refused_ros += 1;
            }
        }
    }
}
