//! The lamp end to end: in memory (the machine's states as the Core moves) and over UDP,
//! where an AS-4 client takes control, sets the level and reads it back.

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::net::as5669a::{As4Config, As4Id, As4Message, As4Stack};
use jaus::{JausMessage, RawMessage};
use jaus_as4::{Message, ReleaseControl, RequestControl};

use vendor_lamp::{QueryLampLevel, ReportLampLevel, SetLampLevel};

const LAMP: As4Id = As4Id::new(30, 1, 5);
const OPERATOR: As4Id = As4Id::new(42, 1, 1);
const OTHER: As4Id = As4Id::new(43, 1, 1);

/// A message of this crate as the AS-4 node hands it over: undecoded.
fn raw<M: JausMessage>(m: &M) -> Message {
    Message::Raw(RawMessage {
        code: M::CODE,
        body: m.to_bytes().unwrap(),
    })
}

fn level(c: &mut jaus_as4::component::As4Component<()>, now: Instant) -> u8 {
    let out = c.handle(now, OTHER, &raw(&QueryLampLevel {}), &mut ());
    out.iter()
        .find_map(|o| match &o.message {
            Message::Raw(r) if r.code == ReportLampLevel::CODE => {
                Some(ReportLampLevel::decode_body(&r.body).unwrap().level)
            }
            _ => None,
        })
        .unwrap_or_else(|| panic!("no Report Lamp Level in {out:?}"))
}

#[test]
fn only_the_controlling_client_sets_the_level() {
    let now = Instant::now();
    let mut c = vendor_lamp::component(LAMP);
    c.handle(now, OPERATOR, &raw(&SetLampLevel { level: 40 }), &mut ());
    assert_eq!(level(&mut c, now), 0, "not controlled: refused");
    c.handle(
        now,
        OPERATOR,
        &RequestControl { authority_code: 10 }.into(),
        &mut (),
    );
    assert_eq!(c.controller(), Some(OPERATOR));
    c.handle(now, OPERATOR, &raw(&SetLampLevel { level: 40 }), &mut ());
    c.handle(now, OTHER, &raw(&SetLampLevel { level: 90 }), &mut ());
    c.handle(now, OPERATOR, &raw(&SetLampLevel { level: 101 }), &mut ());
    assert_eq!(level(&mut c, now), 40, "only the controller's valid level");
    c.handle(now, OPERATOR, &ReleaseControl {}.into(), &mut ());
    c.handle(now, OPERATOR, &raw(&SetLampLevel { level: 10 }), &mut ());
    assert_eq!(level(&mut c, now), 40, "released: refused");
    assert_eq!(c.stats().refused, 4);
}

/// Sends one message to the lamp; the first answer with ID `want` within 1 s.
fn ask(
    socket: &UdpSocket,
    stack: &mut As4Stack<SocketAddr>,
    peer: SocketAddr,
    (id, body): (u16, Vec<u8>),
    want: u16,
) -> Option<As4Message> {
    stack.send(peer, &[As4Message::new(id, LAMP, OPERATOR, body)]);
    while let Some(d) = stack.poll_transmit() {
        socket.send_to(&d.bytes, d.to).unwrap();
    }
    let deadline = Instant::now() + Duration::from_secs(1);
    let mut buf = vec![0u8; 65536];
    while Instant::now() < deadline {
        if let Ok((n, from)) = socket.recv_from(&mut buf) {
            if let Ok(ms) = stack.receive(Instant::now(), from, &buf[..n]) {
                if let Some(m) = ms.into_iter().find(|m| m.message_id == want) {
                    return Some(m);
                }
            }
        }
    }
    None
}

#[test]
fn an_as4_client_drives_the_lamp_over_udp() {
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let peer = socket.local_addr().unwrap();
    let stop = Arc::new(AtomicBool::new(false));
    let s = stop.clone();
    let node = std::thread::spawn(move || vendor_lamp::serve(&socket, LAMP, &s));

    let client = UdpSocket::bind("127.0.0.1:0").unwrap();
    client
        .set_read_timeout(Some(Duration::from_millis(20)))
        .unwrap();
    let mut stack = As4Stack::new(As4Config::default());
    let request = (
        RequestControl::CODE.0,
        RequestControl { authority_code: 10 }.to_bytes().unwrap(),
    );
    let confirm = ask(&client, &mut stack, peer, request, 0x000F).expect("Confirm Control");
    assert_eq!(confirm.body.first(), Some(&0), "control accepted");
    let set = (
        SetLampLevel::CODE.0,
        SetLampLevel { level: 33 }.to_bytes().unwrap(),
    );
    ask(&client, &mut stack, peer, set, 0xFFFF); // a command has no answer
    let report = ask(
        &client,
        &mut stack,
        peer,
        (QueryLampLevel::CODE.0, Vec::new()),
        ReportLampLevel::CODE.0,
    )
    .expect("Report Lamp Level");
    assert_eq!(
        ReportLampLevel::decode_body(&report.body).unwrap().level,
        33
    );
    stop.store(true, Ordering::Relaxed);
    node.join().unwrap().unwrap();
}
