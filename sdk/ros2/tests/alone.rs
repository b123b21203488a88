//! The bridge with nobody on the ROS side (RustDDS alone in its domain; no Python, no
//! ROS): the silence watchdog fires from the start, commands are held at zero, the
//! Primitive Driver's command timeout and the loss of control are reported, and no
//! local pose is invented.

use std::time::{Duration, Instant};

use jaus::component::local::Probe;
use jaus::messages::*;
use jaus::net::{Node, NodeConfig};
use jaus::stock::hardware::Wrench;
use jaus::stock::motion::wrench_message;
use jaus::{Address, Header, JausMessage};
use jaus_ros2::{ids, robot_node, Ros2Config, Ros2Error, WatchdogEvent};

fn pump(node: &mut Node, d: Duration) {
    let end = Instant::now() + d;
    while Instant::now() < end {
        node.handle_timeout(Instant::now());
        while let Some(dg) = node.poll_transmit() {
            node.recycle(dg.bytes);
        }
        std::thread::sleep(Duration::from_millis(5));
    }
}

fn send<M: JausMessage>(node: &mut Node, from: Address, id: u8, m: &M) {
    let to = Address::new(from.subsystem, from.node, id, ids::INSTANCE);
    node.send(
        Instant::now(),
        Header::new(M::CODE, to, from),
        m.to_bytes().unwrap(),
    );
}

#[test]
fn with_a_silent_ros_side_the_watchdogs_hold_the_robot() {
    let config = Ros2Config {
        domain_id: 200 + (std::process::id() % 30) as u16,
        node_name: "jaus_alone".into(),
        watchdog_ms: 200,
        ..Ros2Config::default()
    };
    let node_config = NodeConfig {
        subsystem: 4,
        node: 2,
        ..NodeConfig::default()
    };
    let (mut node, link) = robot_node(&config, node_config, Instant::now()).unwrap();
    let me = Address::new(4, 2, 200, 1);
    node.add(Probe::new(me)).unwrap();
    let pd = ids::PRIMITIVE_DRIVER;

    // No odom within 200 ms: silent, one zero twist.
    pump(&mut node, Duration::from_millis(400));
    assert!(link.ros_silent());
    let events = link.events();
    assert!(
        matches!(events[..], [WatchdogEvent::RosSilent { .. }]),
        "{events:?}"
    );
    assert_eq!(link.last_published(), Some(jaus_ros2::msg::Twist::ZERO));

    // Control, Resume, one effort: held at zero; not refreshed: command timeout.
    send(
        &mut node,
        me,
        pd,
        &RequestComponentControl { authority_code: 5 },
    );
    send(&mut node, me, pd, &Resume {});
    let mut w = Wrench::ZERO;
    w.linear.x = 80.0;
    send(&mut node, me, pd, &wrench_message(&w));
    pump(&mut node, Duration::from_millis(600));
    let stats = link.stats();
    assert!(stats.held >= 1, "{stats:?}");
    assert_eq!(stats.published, stats.published_zero, "{stats:?}");
    let events = link.events();
    assert!(
        events.iter().any(|e| matches!(
            e,
            WatchdogEvent::JausStop {
                reason: "command timeout",
                controller: None,
                ..
            }
        )),
        "{events:?}"
    );

    // Release: reported with the controller.
    send(&mut node, me, pd, &ReleaseComponentControl {});
    pump(&mut node, Duration::from_millis(100));
    let events = link.events();
    assert!(
        events.iter().any(|e| matches!(
            e,
            WatchdogEvent::JausStop { reason: "control lost", controller: Some(a), .. } if *a == me
        )),
        "{events:?}"
    );

    // No odometry: Query Local Pose and Query Velocity State get no report.
    let p: &mut Probe = node.get_mut(me).unwrap();
    p.clear();
    send(
        &mut node,
        me,
        ids::LOCAL_POSE_SENSOR,
        &QueryLocalPose {
            presence_vector: 0x47,
        },
    );
    send(
        &mut node,
        me,
        ids::VELOCITY_STATE_SENSOR,
        &QueryVelocityState { presence_vector: 1 },
    );
    send(
        &mut node,
        me,
        ids::GLOBAL_POSE_SENSOR,
        &QueryGlobalPose { presence_vector: 3 },
    );
    pump(&mut node, Duration::from_millis(100));
    let p: &Probe = node.get(me).unwrap();
    assert!(
        !p.messages().any(|m| matches!(
            m,
            Message::ReportLocalPose(_)
                | Message::ReportVelocityState(_)
                | Message::ReportGlobalPose(_)
        )),
        "{:?}",
        p.received()
    );
    assert_eq!(link.stats().odom, 0);
}

#[test]
fn bad_settings_are_refused_before_joining_dds() {
    let bad = Ros2Config {
        domain_id: 999,
        ..Ros2Config::default()
    };
    let r = robot_node(&bad, NodeConfig::default(), Instant::now());
    assert!(matches!(r, Err(Ros2Error::Config(_))), "{r:?}");
    let bad = Ros2Config {
        node_name: "not a name".into(),
        ..Ros2Config::default()
    };
    let r = robot_node(&bad, NodeConfig::default(), Instant::now());
    assert!(r.is_err(), "{r:?}");
}
