//! The ROS 2 side: one thread owning a ROS 2 node (ros2-client on RustDDS) that reads
//! `odom`, `fix`, `scan` and the camera ([`crate::sensors`]) into shared state and publishes `cmd_vel` from a one-slot mailbox
//! (the latest command wins; superseded ones are counted), and the ROS-silence
//! watchdog. The thread sleeps in a mio poll on the DDS readers and the mailbox, so a
//! sample or a command is handled as soon as it arrives.

use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use jaus::stock::nalgebra::UnitQuaternion;
use mio::{Events, Poll, PollOpt, Ready, Registration, Token};
use ros2_client::ros2::{policy, QosPolicies, QosPolicyBuilder};
use ros2_client::{
    Context, ContextOptions, MessageTypeName, Name, Node, NodeName, NodeOptions, Publisher,
    Subscription,
};

use crate::config::{Qos, Reliability, Ros2Config};
use crate::convert::{fix_to_jaus, odometry_to_jaus};
use crate::error::Ros2Error;
use crate::msg::{CompressedImage, Image, LaserScan, NavSatFix, Odometry, RosMessage, Twist};
use crate::sensors;
use crate::state::{lock, Frame, Shared, Tap};
pub use crate::state::{BridgeStats, OdomSample, WatchdogEvent};

/// The longest the thread sleeps without an event (it checks the watchdog then).
const IDLE: Duration = Duration::from_millis(10);
/// Samples taken from one reader in one round (the rest wait for the next round).
const MAX_TAKE: usize = 64;

/// The running ROS 2 side of a bridge. Dropping it publishes a zero twist and stops
/// the ROS 2 node.
#[derive(Debug)]
pub struct Ros2Link {
    tap: Tap,
    thread: Option<JoinHandle<()>>,
    topics: [String; 3],
    scan_topic: Option<String>,
    camera_topic: Option<String>,
}

impl Ros2Link {
    /// Starts the ROS 2 node of `config` (its DDS participant joins the domain) and
    /// waits until its publisher and readers exist.
    pub fn start(config: &Ros2Config) -> Result<Ros2Link, Ros2Error> {
        config.validate()?;
        let topics = [
            dds_topic_name(&config.namespace, &config.topics.cmd_vel)?,
            dds_topic_name(&config.namespace, &config.topics.odom)?,
            dds_topic_name(&config.namespace, &config.topics.fix)?,
        ];
        let (scan_topic, camera_topic) = sensor_topics(config)?;
        let (registration, bell) = Registration::new2();
        let tap = Tap {
            shared: Arc::new(Mutex::new(Shared::default())),
            bell,
        };
        let (ready_tx, ready_rx) = std::sync::mpsc::sync_channel(1);
        let thread_tap = tap.clone();
        let config = config.clone();
        let thread = std::thread::Builder::new()
            .name("jaus-ros2".into())
            .spawn(move || {
                let side = match RosSide::open(&config, registration) {
                    Ok(side) => {
                        let _ = ready_tx.send(Ok(()));
                        side
                    }
                    Err(e) => {
                        let _ = ready_tx.send(Err(e));
                        return;
                    }
                };
                side.run(&config, &thread_tap);
            })
            .map_err(|e| Ros2Error::Dds(format!("cannot start the ROS 2 thread: {e}")))?;
        match ready_rx.recv() {
            Ok(Ok(())) => Ok(Ros2Link {
                tap,
                thread: Some(thread),
                topics,
                scan_topic,
                camera_topic,
            }),
            Ok(Err(e)) => Err(e),
            Err(_) => Err(Ros2Error::Dds(
                "the ROS 2 thread ended during set-up".into(),
            )),
        }
    }

    pub(crate) fn tap(&self) -> Tap {
        self.tap.clone()
    }

    /// The DDS topic names of `cmd_vel`, `odom` and `fix` (`rt/cmd_vel`, ...).
    pub fn dds_topics(&self) -> [&str; 3] {
        [&self.topics[0], &self.topics[1], &self.topics[2]]
    }

    /// The DDS topic names of the lidar's `scan` and of the camera (`image_raw`, or
    /// `image_raw/compressed`), each when its sensor is on ([`crate::config::Sensors`]).
    pub fn sensor_topics(&self) -> (Option<&str>, Option<&str>) {
        (self.scan_topic.as_deref(), self.camera_topic.as_deref())
    }

    /// Counters.
    pub fn stats(&self) -> BridgeStats {
        lock(&self.tap.shared).stats
    }

    /// The latest odometry, if any.
    pub fn odom(&self) -> Option<OdomSample> {
        lock(&self.tap.shared).odom
    }

    /// The twist published last.
    pub fn last_published(&self) -> Option<Twist> {
        lock(&self.tap.shared).last_published
    }

    /// Whether the ROS side is silent (no `odom` within the watchdog time).
    pub fn ros_silent(&self) -> bool {
        lock(&self.tap.shared).silent
    }

    /// Takes the watchdog events so far, oldest first.
    pub fn events(&self) -> Vec<WatchdogEvent> {
        lock(&self.tap.shared).events.drain(..).collect()
    }

    /// Publishes a zero twist and stops the ROS 2 node (as dropping does).
    pub fn stop(mut self) {
        self.shut();
    }

    fn shut(&mut self) {
        lock(&self.tap.shared).stop = true;
        let _ = self.tap.bell.set_readiness(Ready::readable());
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

impl Drop for Ros2Link {
    fn drop(&mut self) {
        self.shut();
    }
}

/// The DDS names of the scan and camera topics read, each when its sensor is on.
pub(crate) fn sensor_topics(c: &Ros2Config) -> Result<(Option<String>, Option<String>), Ros2Error> {
    let t = &c.topics;
    let camera = if c.sensors.compressed {
        &t.compressed_image
    } else {
        &t.image
    };
    Ok((
        c.sensors
            .range
            .then(|| dds_topic_name(&c.namespace, &t.scan))
            .transpose()?,
        c.sensors
            .visual
            .then(|| dds_topic_name(&c.namespace, camera))
            .transpose()?,
    ))
}

/// The DDS name of ROS topic `topic` in `namespace`: `rt` and the absolute name.
pub fn dds_topic_name(namespace: &str, topic: &str) -> Result<String, Ros2Error> {
    Ok(format!("rt{}", absolute(namespace, topic)?.1))
}

/// The topic as ros2-client's [`Name`] and as its absolute string.
pub(crate) fn absolute(namespace: &str, topic: &str) -> Result<(Name, String), Ros2Error> {
    let full = if topic.starts_with('/') {
        topic.to_string()
    } else {
        format!("{}/{topic}", namespace.trim_end_matches('/'))
    };
    let full = if full.starts_with('/') {
        full
    } else {
        format!("/{full}")
    };
    Name::parse(&full)
        .map(|n| (n, full.clone()))
        .map_err(|e| Ros2Error::Config(format!("topic {full:?}: {e:?}")))
}

pub(crate) fn qos_of(q: Qos) -> QosPolicies {
    let reliability = match q.reliability {
        Reliability::Reliable => policy::Reliability::Reliable {
            max_blocking_time: ros2_client::ros2::Duration::from_millis(100),
        },
        Reliability::BestEffort => policy::Reliability::BestEffort,
    };
    QosPolicyBuilder::new()
        .reliability(reliability)
        .history(policy::History::KeepLast { depth: q.depth })
        .durability(policy::Durability::Volatile)
        .build()
}

/// The ROS 2 node and its endpoints (owned by the thread: none of it crosses threads).
struct RosSide {
    _node: Node,
    cmd_vel: Publisher<Twist>,
    odom: Subscription<Odometry>,
    fix: Subscription<NavSatFix>,
    scan: Option<Subscription<LaserScan>>,
    image: Option<Subscription<Image>>,
    compressed: Option<Subscription<CompressedImage>>,
    poll: Poll,
    _registration: Registration,
}

const ODOM: Token = Token(0);
const FIX: Token = Token(1);
const BELL: Token = Token(2);
const SCAN: Token = Token(3);
const IMAGE: Token = Token(4);

impl RosSide {
    fn open(c: &Ros2Config, registration: Registration) -> Result<RosSide, Ros2Error> {
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
        let cmd_topic = topic(
            &c.topics.cmd_vel,
            (Twist::PACKAGE, Twist::NAME),
            c.qos_commands,
        )?;
        let odom_topic = topic(
            &c.topics.odom,
            (Odometry::PACKAGE, Odometry::NAME),
            c.qos_sensors,
        )?;
        let fix_topic = topic(
            &c.topics.fix,
            (NavSatFix::PACKAGE, NavSatFix::NAME),
            c.qos_sensors,
        )?;
        let sn = c.sensors;
        let scan_topic = sn
            .range
            .then(|| {
                topic(
                    &c.topics.scan,
                    (LaserScan::PACKAGE, LaserScan::NAME),
                    c.qos_sensors,
                )
            })
            .transpose()?;
        let image_topic = (sn.visual && !sn.compressed)
            .then(|| {
                topic(
                    &c.topics.image,
                    (Image::PACKAGE, Image::NAME),
                    c.qos_sensors,
                )
            })
            .transpose()?;
        let compressed_topic = (sn.visual && sn.compressed)
            .then(|| {
                topic(
                    &c.topics.compressed_image,
                    (CompressedImage::PACKAGE, CompressedImage::NAME),
                    c.qos_sensors,
                )
            })
            .transpose()?;
        let cmd_vel = node
            .create_publisher::<Twist>(&cmd_topic, None)
            .map_err(|e| dds("cmd_vel publisher", &e))?;
        let odom = node
            .create_subscription::<Odometry>(&odom_topic, None)
            .map_err(|e| dds("odom reader", &e))?;
        let fix = node
            .create_subscription::<NavSatFix>(&fix_topic, None)
            .map_err(|e| dds("fix reader", &e))?;
        let scan = scan_topic
            .map(|t| node.create_subscription::<LaserScan>(&t, None))
            .transpose()
            .map_err(|e| dds("scan reader", &e))?;
        let image = image_topic
            .map(|t| node.create_subscription::<Image>(&t, None))
            .transpose()
            .map_err(|e| dds("image reader", &e))?;
        let compressed = compressed_topic
            .map(|t| node.create_subscription::<CompressedImage>(&t, None))
            .transpose()
            .map_err(|e| dds("compressed image reader", &e))?;
        let poll = Poll::new().map_err(|e| dds("poll", &e))?;
        let edge = PollOpt::edge();
        let (r, e) = (Ready::readable(), edge);
        poll.register(&odom, ODOM, r, e)
            .and_then(|_| poll.register(&fix, FIX, r, e))
            .and_then(|_| poll.register(&registration, BELL, r, e))
            .and_then(|_| {
                scan.as_ref()
                    .map_or(Ok(()), |s| poll.register(s, SCAN, r, e))
            })
            .and_then(|_| {
                image
                    .as_ref()
                    .map_or(Ok(()), |s| poll.register(s, IMAGE, r, e))
            })
            .and_then(|_| {
                compressed
                    .as_ref()
                    .map_or(Ok(()), |s| poll.register(s, IMAGE, r, e))
            })
            .map_err(|e| dds("poll registration", &e))?;
        Ok(RosSide {
            _node: node,
            cmd_vel,
            odom,
            fix,
            scan,
            image,
            compressed,
            poll,
            _registration: registration,
        })
    }

    /// Publishes `t` (without holding the shared state: a DDS write may take a while)
    /// and counts it.
    fn publish(&self, shared: &Mutex<Shared>, t: Twist) {
        let r = self.cmd_vel.publish(t);
        let mut s = lock(shared);
        match r {
            Ok(()) => {
                s.stats.published += 1;
                if t.is_zero() {
                    s.stats.published_zero += 1;
                }
                s.last_published = Some(t);
            }
            Err(e) => {
                s.stats.publish_errors += 1;
                if s.stats.publish_errors % 100 == 1 {
                    tracing::warn!(
                        errors = s.stats.publish_errors,
                        "jaus-ros2: cmd_vel not published: {e:?}"
                    );
                }
            }
        }
    }

    fn run(self, c: &Ros2Config, tap: &Tap) {
        let started = Instant::now();
        let watchdog = c.watchdog();
        let mut events = Events::with_capacity(16);
        loop {
            if let Err(e) = self.poll.poll(&mut events, Some(IDLE)) {
                tracing::warn!("jaus-ros2: poll failed: {e}");
                std::thread::sleep(IDLE);
            }
            // Re-arm the doorbell before emptying the mailbox: a command put after this
            // rings again.
            let _ = tap.bell.set_readiness(Ready::empty());
            self.read_odom(c, tap);
            self.read_fix(tap);
            self.read_sensors(c, tap);
            let now = Instant::now();
            // What to publish, decided under the lock, published after it.
            let (stop, went_silent, command) = {
                let mut s = lock(&tap.shared);
                let last = s.odom.map_or(started, |o| o.received);
                let silent = now.saturating_duration_since(last) > watchdog;
                let went_silent = silent && !s.silent;
                if went_silent {
                    s.silent = true;
                    tracing::warn!(
                        "jaus-ros2: no {} for {watchdog:?}: zero twist, commands held",
                        c.topics.odom
                    );
                    s.event(WatchdogEvent::RosSilent { at: now });
                } else if !silent && s.silent {
                    s.silent = false;
                    tracing::info!("jaus-ros2: {} is back", c.topics.odom);
                    s.event(WatchdogEvent::RosResumed { at: now });
                }
                let command = s.pending.take().map(|t| {
                    if s.silent && !t.is_zero() {
                        s.stats.held += 1;
                        Twist::ZERO
                    } else {
                        t
                    }
                });
                (s.stop, went_silent, command)
            };
            if stop {
                self.publish(&tap.shared, Twist::ZERO);
                return;
            }
            if went_silent {
                self.publish(&tap.shared, Twist::ZERO);
            }
            if let Some(t) = command {
                self.publish(&tap.shared, t);
            }
        }
    }

    fn read_odom(&self, c: &Ros2Config, tap: &Tap) {
        for _ in 0..MAX_TAKE {
            let (o, _info) = match self.odom.take() {
                Ok(Some(x)) => x,
                Ok(None) => return,
                Err(e) => {
                    lock(&tap.shared).stats.refused += 1;
                    tracing::debug!("jaus-ros2: odom not read: {e:?}");
                    continue;
                }
            };
            let received = Instant::now();
            let frames = &c.frames;
            let foreign = (!frames.odom.is_empty() && o.header.frame_id != frames.odom)
                || (!frames.base.is_empty() && o.child_frame_id != frames.base);
            let mut s = lock(&tap.shared);
            if foreign {
                if s.stats.foreign_frames == 0 {
                    tracing::warn!(
                        "jaus-ros2: odom in frames {:?}/{:?}, expected {:?}/{:?}: ignored",
                        o.header.frame_id,
                        o.child_frame_id,
                        frames.odom,
                        frames.base
                    );
                }
                s.stats.foreign_frames += 1;
                continue;
            }
            match odometry_to_jaus(&o, c.odom_axes) {
                Some((pose, velocity)) => {
                    s.stats.odom += 1;
                    s.odom = Some(OdomSample {
                        pose,
                        velocity,
                        received,
                        stamp: o.header.stamp,
                    });
                }
                None => s.stats.refused += 1,
            }
        }
    }

    /// Takes the lidar's and the camera's samples: each checked and kept as the latest,
    /// or dropped and counted (an image is converted when the Visual Sensor asks).
    fn read_sensors(&self, c: &Ros2Config, tap: &Tap) {
        let refused = |what: &str, e: &dyn std::fmt::Debug, images: bool| {
            let mut s = lock(&tap.shared);
            if images {
                s.stats.images_refused += 1;
            } else {
                s.stats.scans_refused += 1;
            }
            tracing::debug!("jaus-ros2: {what} not read: {e:?}");
        };
        if let Some(r) = &self.scan {
            for _ in 0..MAX_TAKE {
                match r.take() {
                    Ok(Some((scan, _))) => sensors::on_scan(&tap.shared, &scan, &c.topics.scan),
                    Ok(None) => break,
                    Err(e) => refused("scan", &e, false),
                }
            }
        }
        let max = c.sensors.max_image_bytes;
        if let Some(r) = &self.image {
            for _ in 0..MAX_TAKE {
                match r.take() {
                    Ok(Some((i, _))) => {
                        sensors::on_frame(&tap.shared, Frame::Raw(i), max, &c.topics.image)
                    }
                    Ok(None) => break,
                    Err(e) => refused("image", &e, true),
                }
            }
        }
        if let Some(r) = &self.compressed {
            let topic = &c.topics.compressed_image;
            for _ in 0..MAX_TAKE {
                match r.take() {
                    Ok(Some((i, _))) => sensors::on_compressed(&tap.shared, i, max, topic),
                    Ok(None) => break,
                    Err(e) => refused("compressed image", &e, true),
                }
            }
        }
    }

    fn read_fix(&self, tap: &Tap) {
        for _ in 0..MAX_TAKE {
            let f = match self.fix.take() {
                Ok(Some((f, _))) => f,
                Ok(None) => return,
                Err(e) => {
                    lock(&tap.shared).stats.refused += 1;
                    tracing::debug!("jaus-ros2: fix not read: {e:?}");
                    continue;
                }
            };
            let mut s = lock(&tap.shared);
            let attitude = s
                .odom
                .map_or(UnitQuaternion::identity(), |o| o.pose.attitude);
            match fix_to_jaus(&f, attitude) {
                Some(g) => {
                    s.stats.fix += 1;
                    s.fix = Some((g, Instant::now()));
                }
                None => s.stats.refused += 1,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn topic_names_get_rt_and_the_namespace() {
        assert_eq!(dds_topic_name("/", "odom").unwrap(), "rt/odom");
        assert_eq!(
            dds_topic_name("/robot1", "cmd_vel").unwrap(),
            "rt/robot1/cmd_vel"
        );
        assert_eq!(dds_topic_name("/robot1/", "/fix").unwrap(), "rt/fix");
        assert!(dds_topic_name("/", "bad-name").is_err());
    }
}
