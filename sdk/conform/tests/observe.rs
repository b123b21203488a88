//! The outsider checks watch the target for the whole settle time
//! ([`jaus_conform::memory::MemorySession`], virtual time): a component that carries
//! out a command from a component not in control and undoes it 10 ms later fails the
//! matching check, the change and its times named in the detail.

use std::any::Any;
use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use jaus::component::{Endpoint, Outgoing};
use jaus::net::{Framing, Node, NodeConfig};
use jaus::{Address, CommandCode, Header};
use jaus_conform::memory::{MemorySession, TESTER};
use jaus_conform::session::Voices;
use jaus_conform::udp::UdpSession;
use jaus_conform::{report, ComponentReport, Options, Outcome, RunReport, Verdict};
use jaus_node::host::{Host, Stock};

/// Standby (core state command).
const STANDBY: CommandCode = CommandCode(0x0003);
/// Resume.
const RESUME: CommandCode = CommandCode(0x0004);
/// Set Travel Speed (a waypoint driver's command, read back by Query Travel Speed).
const SET_TRAVEL_SPEED: CommandCode = CommandCode(0x040A);

/// How long the component keeps what the outsider commanded.
const UNDO_AFTER: Duration = Duration::from_millis(10);

/// Carries out the commands `codes` from `outsider` as if its controller `controller`
/// sent them, and undoes them `UNDO_AFTER` later: Standby by Resume, Set Travel Speed
/// by the controller's last Set Travel Speed.
struct Undoes {
    inner: Box<dyn Endpoint>,
    codes: Vec<CommandCode>,
    controller: Address,
    outsider: Address,
    /// The controller's last Set Travel Speed body.
    speed: Option<Vec<u8>>,
    /// The undo due, and what it sends.
    due: Option<(Instant, CommandCode, Vec<u8>)>,
}

impl Endpoint for Undoes {
    fn address(&self) -> Address {
        self.inner.address()
    }
    fn handle(&mut self, now: Instant, header: &Header, body: &[u8]) {
        let code = header.command_code;
        if header.source == self.controller && code == SET_TRAVEL_SPEED {
            self.speed = Some(body.to_vec());
        }
        if header.source == self.outsider && self.codes.contains(&code) {
            let undo = match code {
                STANDBY => Some((RESUME, Vec::new())),
                SET_TRAVEL_SPEED => self.speed.clone().map(|b| (SET_TRAVEL_SPEED, b)),
                _ => None,
            };
            let mut h = *header;
            h.source = self.controller;
            self.inner.handle(now, &h, body);
            if let Some((c, b)) = undo {
                self.due = Some((now + UNDO_AFTER, c, b));
            }
            return;
        }
        self.inner.handle(now, header, body);
    }
    fn handle_timeout(&mut self, now: Instant) {
        if self.due.as_ref().is_some_and(|(at, _, _)| *at <= now) {
            if let Some((_, code, body)) = self.due.take() {
                let mut h = Header::new(code, self.inner.address(), self.controller);
                h.data_size = body.len() as u16;
                self.inner.handle(now, &h, &body);
            }
        }
        self.inner.handle_timeout(now);
    }
    fn poll_transmit(&mut self) -> Option<Outgoing> {
        self.inner.poll_transmit()
    }
    fn poll_timeout(&self) -> Option<Instant> {
        let due = self.due.as_ref().map(|(at, _, _)| *at);
        [self.inner.poll_timeout(), due].into_iter().flatten().min()
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

/// A node 1.1 with `peers` hosting the stock waypoint driver 1.1.45.1 wrapped in
/// [`Undoes`] for `codes`, against the tester's `voices`.
fn node(t0: Instant, peers: Vec<SocketAddr>, voices: &Voices, codes: Vec<CommandCode>) -> Node {
    let stock = Stock::by_id(45).expect("stock component");
    let mut host = Host::new(1, 1, t0);
    let mut node = Node::new(
        NodeConfig {
            peers,
            ..NodeConfig::default()
        },
        t0,
    );
    let built = host
        .build(&Host::entry(stock))
        .expect("stock component builds");
    node.add_boxed(Box::new(Undoes {
        inner: built,
        codes,
        controller: voices.controller,
        outsider: voices.outsider,
        speed: None,
        due: None,
    }))
    .expect("added");
    node
}

/// Runs the tester in memory on 1.1.45.1 wrapped in [`Undoes`] for `codes`.
fn run(codes: Vec<CommandCode>) -> RunReport {
    let t0 = Instant::now();
    let voices = Voices::on(200, 1);
    let node = node(t0, vec![TESTER], &voices, codes);
    let mut session = MemorySession::new(node, &voices, t0).expect("session");
    let spec = jaus_spec::load_sdk().expect("definitions");
    let target = Address::new(1, 1, 45, 1);
    let run = jaus_conform::run(&mut session, &spec, voices, &[target], Options::default());
    println!("{}", report::summary(&run));
    run
}

fn outcome<'r>(c: &'r ComponentReport, id: &str) -> &'r Outcome {
    c.outcomes
        .iter()
        .find(|o| o.check.id == id)
        .unwrap_or_else(|| panic!("{id} not planned"))
}

#[test]
fn a_standby_undone_10_ms_later_fails_the_outsider_check() {
    let run = run(vec![STANDBY]);
    let c = &run.components[0];
    let o = outcome(c, "state.Standby.outsider");
    println!("{}", o.detail);
    assert_eq!(o.verdict, Verdict::Fail, "{}", o.detail);
    assert!(
        o.detail
            .contains("Standby from 200.1.40.4 (not in control), in Ready: the component reported Standby 0.0 ms after it, Ready again at 10.0 ms"),
        "{}",
        o.detail
    );
    assert!(o.detail.contains("at 200 Hz"), "{}", o.detail);
    // The other outsider checks are not affected.
    assert_eq!(outcome(c, "state.Resume.outsider").verdict, Verdict::Pass);
    assert_eq!(outcome(c, "outsider.SetTravelSpeed").verdict, Verdict::Pass);
}

#[test]
fn a_travel_speed_undone_10_ms_later_fails_the_outsider_check() {
    let run = run(vec![SET_TRAVEL_SPEED]);
    let c = &run.components[0];
    let o = outcome(c, "outsider.SetTravelSpeed");
    println!("{}", o.detail);
    assert_eq!(o.verdict, Verdict::Fail, "{}", o.detail);
    assert!(o.detail.contains("0.0 ms after it"), "{}", o.detail);
    assert!(o.detail.contains("again at 10.0 ms"), "{}", o.detail);
    assert!(o.detail.contains("polled QueryTravelSpeed"), "{}", o.detail);
    assert_eq!(outcome(c, "state.Standby.outsider").verdict, Verdict::Pass);
}

#[test]
fn a_standby_undone_10_ms_later_fails_the_outsider_check_over_udp() {
    let target_socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let peer = target_socket.local_addr().unwrap();
    let tester_socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let voices = Voices::on(200, 1);
    let mut node = node(
        Instant::now(),
        vec![tester_socket.local_addr().unwrap()],
        &voices,
        vec![STANDBY],
    );
    let stop = Arc::new(AtomicBool::new(false));
    let s = stop.clone();
    let runner = std::thread::spawn(move || {
        let _ = jaus::net::udp::run_on(
            &mut node,
            &target_socket,
            &s,
            Some(Instant::now() + Duration::from_secs(120)),
            |_| {},
        );
    });
    let mut session =
        UdpSession::new(tester_socket, vec![peer], Framing::Judp, &voices).expect("session");
    session.discover(Duration::from_millis(500));
    let spec = jaus_spec::load_sdk().expect("definitions");
    let target = Address::new(1, 1, 45, 1);
    let run = jaus_conform::run(&mut session, &spec, voices, &[target], Options::default());
    stop.store(true, Ordering::Relaxed);
    let _ = runner.join();
    println!("{}", report::summary(&run));
    let c = &run.components[0];
    let o = outcome(c, "state.Standby.outsider");
    assert_eq!(o.verdict, Verdict::Fail, "{}", o.detail);
    assert!(
        o.detail.contains("the component reported Standby "),
        "{}",
        o.detail
    );
    assert!(o.detail.contains(", Ready again at "), "{}", o.detail);
    // Over UDP the rate reached is lower than planned, never below 50 Hz.
    let rate: f64 = o
        .detail
        .split(" Hz (")
        .next()
        .and_then(|s| s.rsplit(' ').next())
        .and_then(|r| r.parse().ok())
        .expect("rate in the detail");
    assert!(rate >= 50.0, "{}", o.detail);
    let failed: Vec<&str> = c
        .outcomes
        .iter()
        .filter(|o| o.is_required_failure())
        .map(|o| o.check.id.as_str())
        .collect();
    assert_eq!(
        failed,
        vec!["state.Standby.outsider"],
        "{}",
        report::summary(&run)
    );
}
