//! Two [`QuicLink`]s on 127.0.0.1: frames both ways as datagrams and on streams, a far
//! end with the wrong certificate, a far end that goes and comes back, the bounds.

use std::net::{SocketAddr, UdpSocket};
use std::time::{Duration, Instant};

use jaus::stock::communicator::{DataLink, LinkError};

use crate::keys::Identity;
use crate::link::{QuicLink, QuicLinkConfig, QuicLinkError, Role};

/// Everything a test waits for comes within this (no timing is asserted beyond it).
const LIMIT: Duration = Duration::from_secs(10);

fn local(port: u16) -> SocketAddr {
    SocketAddr::from(([127, 0, 0, 1], port))
}

/// A free UDP port on 127.0.0.1 (bound then released).
fn free_port() -> u16 {
    UdpSocket::bind(local(0))
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

/// Quick settings for tests: lost after 1 s of silence, reconnecting within 200 ms.
fn config(
    bind: u16,
    peer: u16,
    me: &Identity,
    far: &rustls::pki_types::CertificateDer<'static>,
) -> QuicLinkConfig {
    let mut c = QuicLinkConfig::new(1, local(bind), local(peer), me.clone(), far.clone());
    c.silence = Duration::from_secs(1);
    c.keepalive = Duration::from_millis(200);
    c.reconnect_min = Duration::from_millis(50);
    c.reconnect_max = Duration::from_millis(200);
    c
}

/// Two identities and the two links between them, on free ports: (a, b), their
/// configurations, and the links.
struct Pair {
    ids: (Identity, Identity),
    ports: (u16, u16),
    a: QuicLink,
    b: QuicLink,
}

fn pair() -> Pair {
    let ids = (
        Identity::generate("a").unwrap(),
        Identity::generate("b").unwrap(),
    );
    let ports = (free_port(), free_port());
    let a = QuicLink::bind(config(ports.0, ports.1, &ids.0, &ids.1.cert)).unwrap();
    let b = QuicLink::bind(config(ports.1, ports.0, &ids.1, &ids.0.cert)).unwrap();
    Pair { ids, ports, a, b }
}

/// Waits until `done`, at most [`LIMIT`].
fn wait_for(what: &str, mut done: impl FnMut() -> bool) {
    let end = Instant::now() + LIMIT;
    while !done() {
        assert!(Instant::now() < end, "not {what} within {LIMIT:?}");
        std::thread::sleep(Duration::from_millis(2));
    }
}

fn up(l: &QuicLink) -> bool {
    l.is_up(Instant::now())
}

/// Reads `link` until `n` frames came (at most [`LIMIT`]).
fn recv_n(link: &mut QuicLink, n: usize) -> Vec<Vec<u8>> {
    let mut got = Vec::new();
    let mut buf = Vec::new();
    wait_for(&format!("{n} frames received"), || {
        while link.recv(Instant::now(), &mut buf) {
            got.push(buf.clone());
        }
        got.len() >= n
    });
    got
}

fn frame(len: usize, tag: u8) -> Vec<u8> {
    (0..len)
        .map(|i| (i as u8).wrapping_mul(7).wrapping_add(tag))
        .collect()
}

/// Sends `frames`, offering each again while the link is busy.
fn send_all(link: &mut QuicLink, frames: &[Vec<u8>]) {
    for f in frames {
        wait_for("the frame taken", || match link.send(Instant::now(), f) {
            Ok(()) => true,
            Err(LinkError::Busy) => false,
            Err(e) => panic!("send: {e}"),
        });
    }
}

#[test]
fn small_frames_cross_as_datagrams_and_full_size_ones_on_streams_both_ways() {
    let Pair { mut a, mut b, .. } = pair();
    wait_for("up", || up(&a) && up(&b));
    let roles = [a.role(), b.role()];
    assert!(roles.contains(&Role::Connect) && roles.contains(&Role::Accept));
    let exchange = |tx: &mut QuicLink, rx: &mut QuicLink, tag: u8| {
        let mut frames: Vec<Vec<u8>> = (0..5).map(|i| frame(64, tag + i)).collect();
        frames.extend((0..3).map(|i| frame(4096, tag + 10 + i)));
        send_all(tx, &frames);
        let mut got = recv_n(rx, frames.len());
        // Datagrams and streams are not ordered with each other: compare as sets.
        got.sort();
        frames.sort();
        assert_eq!(got, frames);
    };
    exchange(&mut a, &mut b, 0);
    exchange(&mut b, &mut a, 100);
    for l in [&a, &b] {
        let s = l.stats();
        assert_eq!(
            (s.datagrams_sent, s.datagram_bytes_sent),
            (5, 5 * 64),
            "{s:?}"
        );
        assert_eq!(
            (s.streams_sent, s.stream_bytes_sent),
            (3, 3 * 4096),
            "{s:?}"
        );
        assert_eq!((s.datagrams_received, s.streams_received), (5, 3), "{s:?}");
        assert_eq!(s.bytes_received(), 5 * 64 + 3 * 4096);
        assert_eq!(s.handshakes_ok, 1, "{s:?}");
        assert_eq!(
            s.handshakes_refused + s.send_errors + s.dropped_queue_full + s.reconnects,
            0,
            "{s:?}"
        );
    }
    // A frame over the MTU is refused and counted; read to the end, the link asks to be
    // read again a poll period later.
    assert_eq!(
        a.send(Instant::now(), &frame(4097, 0)),
        Err(LinkError::TooLarge {
            len: 4097,
            max: 4096
        })
    );
    assert_eq!(a.stats().dropped_oversize_sent, 1);
    let now = Instant::now();
    let mut buf = vec![1];
    assert!(!a.recv(now, &mut buf));
    assert!(buf.is_empty());
    assert_eq!(a.poll_timeout(), Some(now + Duration::from_millis(10)));
    // Powered down: down, nothing taken.
    a.set_powered(now, false);
    assert!(!a.is_up(now));
    assert_eq!(a.send(now, &frame(20, 0)), Err(LinkError::Down));
    a.set_powered(now, true);
    assert!(a.is_up(now));
}

/// The legitimate end `legit` (expecting `far`'s certificate) and an impostor with a
/// key of its own at the far end's address, which pins `legit`'s certificate and takes
/// the far end's role (else the two would both wait, or both call, and never meet).
fn impostor_against(me: &Identity, far: &Identity) {
    let (p, q) = (free_port(), free_port());
    let legit = config(p, q, me, &far.cert);
    let impostor = loop {
        let x = Identity::generate("b").unwrap();
        let c = config(q, p, &x, &me.cert);
        if c.role() != legit.role() {
            break c;
        }
    };
    let mut l = QuicLink::bind(legit).unwrap();
    let mut x = QuicLink::bind(impostor).unwrap();
    wait_for("the impostor refused", || l.stats().handshakes_refused >= 1);
    // It keeps trying (the connecting end) or is waited for: the link never comes up and
    // nothing crosses.
    let end = Instant::now() + Duration::from_millis(600);
    let mut buf = Vec::new();
    while Instant::now() < end {
        assert!(!up(&l) && !up(&x), "{:?} / {:?}", l.stats(), x.stats());
        assert_eq!(x.send(Instant::now(), &frame(32, 1)), Err(LinkError::Down));
        assert_eq!(l.send(Instant::now(), &frame(32, 2)), Err(LinkError::Down));
        assert!(!l.recv(Instant::now(), &mut buf) && !x.recv(Instant::now(), &mut buf));
        std::thread::sleep(Duration::from_millis(5));
    }
    let s = l.stats();
    assert_eq!(s.handshakes_ok, 0, "{s:?}");
    assert!(s.handshakes_failed >= s.handshakes_refused, "{s:?}");
    assert_eq!(s.frames_received() + s.frames_sent(), 0, "{s:?}");
    assert_eq!(x.stats().frames_received(), 0);
    assert_eq!(l.poll_timeout(), None, "down: nothing to read");
}

#[test]
fn a_far_end_with_the_wrong_certificate_never_gets_a_connection() {
    let (a, b) = (
        Identity::generate("a").unwrap(),
        Identity::generate("b").unwrap(),
    );
    // Once with the legitimate end connecting (it refuses the server's certificate),
    // once with it accepting (it refuses the client's).
    impostor_against(&a, &b);
    impostor_against(&b, &a);
}

#[test]
fn the_link_comes_back_when_the_far_end_is_recreated() {
    let Pair { ids, ports, a, b } = pair();
    wait_for("up", || up(&a) && up(&b));
    let config_of = |i: usize| match i {
        0 => config(ports.0, ports.1, &ids.0, &ids.1.cert),
        _ => config(ports.1, ports.0, &ids.1, &ids.0.cert),
    };
    let mut links = [Some(a), Some(b)];
    // The accepting end goes, then the connecting end; each is made again with the
    // same identity on the same address.
    for (round, role) in [(0u8, Role::Accept), (1, Role::Connect)] {
        let gone = links
            .iter()
            .position(|l| l.as_ref().is_some_and(|l| l.role() == role))
            .unwrap();
        let stay = 1 - gone;
        links[gone] = None;
        // Closed by the far end: down at once (not after the silence).
        wait_for("down", || !up(links[stay].as_ref().unwrap()));
        links[gone] = Some(QuicLink::bind(config_of(gone)).unwrap());
        wait_for("up again", || links.iter().all(|l| up(l.as_ref().unwrap())));
        let [x, y] = &mut links;
        let (stay_link, again) = match gone {
            0 => (y.as_mut().unwrap(), x.as_mut().unwrap()),
            _ => (x.as_mut().unwrap(), y.as_mut().unwrap()),
        };
        send_all(stay_link, &[frame(64, round), frame(4096, round)]);
        let mut got = recv_n(again, 2);
        got.sort();
        assert_eq!(got, [frame(64, round), frame(4096, round)]);
        send_all(again, &[frame(100, round)]);
        assert_eq!(recv_n(stay_link, 1), [frame(100, round)]);
        // (The end that stayed in the second round is the one made again in the
        // first: one connection before, one after.)
        let s = stay_link.stats();
        assert_eq!((s.handshakes_ok, s.reconnects), (2, 1), "{s:?}");
    }
}

#[test]
fn a_full_incoming_queue_drops_and_counts_and_busy_is_counted() {
    let ids = (
        Identity::generate("a").unwrap(),
        Identity::generate("b").unwrap(),
    );
    let ports = (free_port(), free_port());
    let mut ca = config(ports.0, ports.1, &ids.0, &ids.1.cert);
    ca.queue = 1;
    let mut cb = config(ports.1, ports.0, &ids.1, &ids.0.cert);
    cb.queue = 4;
    let (mut a, mut b) = (QuicLink::bind(ca).unwrap(), QuicLink::bind(cb).unwrap());
    wait_for("up", || up(&a) && up(&b));
    // 50 frames offered to a one-frame outgoing queue: each taken or answered Busy.
    let mut busy = 0;
    let mut taken = 0;
    while taken < 50 {
        match a.send(Instant::now(), &frame(64, taken as u8)) {
            Ok(()) => taken += 1,
            Err(LinkError::Busy) => {
                busy += 1;
                assert!(a.ready_at().is_some());
                std::thread::sleep(Duration::from_micros(200));
            }
            Err(e) => panic!("{e}"),
        }
    }
    assert_eq!(a.stats().busy, busy);
    // b reads nothing: its queue holds 4, the rest is dropped and counted.
    wait_for("dropped", || {
        let s = b.stats();
        a.stats().datagrams_sent == 50 && s.dropped_queue_full > 0
    });
    assert_eq!(recv_n(&mut b, 4).len(), 4);
    // Read on (frames still inside quinn fill the room made): every frame sent is
    // either received or counted dropped.
    let mut buf = Vec::new();
    wait_for("all counted", || {
        while b.recv(Instant::now(), &mut buf) {}
        let s = b.stats();
        s.datagrams_received + s.dropped_queue_full == 50
    });
}

#[test]
fn frames_over_the_receivers_mtu_are_dropped_and_counted() {
    let ids = (
        Identity::generate("a").unwrap(),
        Identity::generate("b").unwrap(),
    );
    let ports = (free_port(), free_port());
    let ca = config(ports.0, ports.1, &ids.0, &ids.1.cert);
    let mut cb = config(ports.1, ports.0, &ids.1, &ids.0.cert);
    cb.mtu = 1000;
    let (mut a, mut b) = (QuicLink::bind(ca).unwrap(), QuicLink::bind(cb).unwrap());
    wait_for("up", || up(&a) && up(&b));
    // Over b's MTU: one that fits a datagram, one that goes on a stream; then one within.
    send_all(&mut a, &[frame(1100, 1), frame(4096, 2), frame(500, 3)]);
    assert_eq!(recv_n(&mut b, 1), [frame(500, 3)]);
    wait_for("both dropped", || b.stats().dropped_oversize_received == 2);
    let mut buf = Vec::new();
    assert!(!b.recv(Instant::now(), &mut buf));
    assert_eq!(b.stats().frames_received(), 1);
    // The link stays up and carries on.
    send_all(&mut a, &[frame(999, 4)]);
    assert_eq!(recv_n(&mut b, 1), [frame(999, 4)]);
}

#[test]
fn bad_settings_are_refused_before_anything_is_bound() {
    let a = Identity::generate("a").unwrap();
    let b = Identity::generate("b").unwrap();
    let any = local(0);
    let base = QuicLinkConfig::new(3, any, any, a.clone(), b.cert.clone());
    let err = |c: QuicLinkConfig| QuicLink::bind(c).err().unwrap().to_string();
    let mut c = base.clone();
    c.mtu = 15;
    assert_eq!(err(c), "data link 3: mtu 15 is not in 16..=65507");
    let mut c = base.clone();
    c.keepalive = c.silence;
    assert!(err(c).contains("keepalive 3s must be above zero and below silence 3s"));
    let mut c = base.clone();
    c.peer_cert = a.cert.clone();
    assert!(matches!(
        QuicLink::bind(c),
        Err(QuicLinkError::SameCertificate { id: 3 })
    ));
    let mut c = base.clone();
    c.identity.key = b.key.clone_key();
    assert_eq!(
        err(c),
        "data link 3: certificate and key: the private key is not the certificate's"
    );
    let taken = UdpSocket::bind(any).unwrap();
    let mut c = base;
    c.bind = taken.local_addr().unwrap();
    assert!(err(c).starts_with("data link 3: cannot use 127.0.0.1:"));
}
