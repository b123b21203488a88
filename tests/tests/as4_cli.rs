//! `jaus as4-query` / `as4-send` against an AS-4 component over UDP on loopback: a
//! Core query by name with jaus-as4's definitions, and a vendor's own messages by name
//! with the vendor's YAML (`--spec`) under control (`--control`, Resume by name), and
//! refused without it.

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread;
use std::time::{Duration, Instant};

use jaus::net::as5669a::{As4Config, As4Endpoint, As4Id, As4Stack};
use jaus::{CommandCode, RawMessage};
use jaus_as4::component::As4Component;
use jaus_as4::core::CoreConfig;
use jaus_as4::node::As4Node;
use jaus_as4::service::{Cx, Handled, Request, Service, ServiceId};
use jaus_as4::Message;
use jaus_cli::as4_talk::{as4_talk, As4TalkArgs};

const LAMP: As4Id = As4Id::new(30, 1, 5);

/// A vendor's lamp: Set Lamp Level (0xF012, a command) and Query Lamp Level (0xF010)
/// answered by Report Lamp Level (0xF011), none of them in jaus-as4's definitions.
#[derive(Debug, Default)]
struct Lamp {
    level: u8,
}

impl<E: 'static> Service<E> for Lamp {
    fn id(&self) -> ServiceId {
        ServiceId::new("urn:acme:Lamp", 1, 0)
    }
    fn receives(&self, code: CommandCode) -> bool {
        matches!(code.0, 0xF010 | 0xF012)
    }
    fn needs_control(&self, code: CommandCode) -> bool {
        code.0 == 0xF012
    }
    fn handle(&mut self, _: &mut Cx<'_, E>, r: &Request<'_>) -> Handled {
        match r.message {
            Message::Raw(m) if m.code.0 == 0xF012 => {
                self.level = m.body.first().copied().unwrap_or(0);
                Handled::Done
            }
            Message::Raw(m) if m.code.0 == 0xF010 => Handled::Reply(Message::Raw(RawMessage {
                code: CommandCode(0xF011),
                body: vec![self.level],
            })),
            _ => Handled::NotMine,
        }
    }
}

const VENDOR_YAML: &str = r#"
extends: none
group: acme
messages:
  - name: SetLampLevel
    code: 0xF012
    is_command: true
    description: Sets the lamp's level.
    fields:
      - { name: level, type: u8, description: "Level, 0-255." }
  - name: QueryLampLevel
    code: 0xF010
    is_command: false
    description: Asks for the lamp's level.
  - name: ReportLampLevel
    code: 0xF011
    is_command: false
    description: The lamp's level.
    fields:
      - { name: level, type: u8, description: "Level, 0-255." }
"#;

/// The lamp's node on a loopback socket, served by a thread until `stop`.
fn serve(stop: Arc<AtomicBool>) -> SocketAddr {
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let addr = socket.local_addr().unwrap();
    socket
        .set_read_timeout(Some(Duration::from_millis(20)))
        .unwrap();
    thread::spawn(move || {
        let component =
            As4Component::new(LAMP, CoreConfig::named("lamp")).with_service(Lamp::default());
        let mut node: As4Node<()> = As4Node::new(()).with_component(component);
        let mut stack = As4Stack::new(As4Config::default());
        let mut buf = vec![0u8; 65536];
        while !stop.load(Ordering::Relaxed) {
            let now = Instant::now();
            if let Ok((n, from)) = socket.recv_from(&mut buf) {
                if let Ok(messages) = stack.receive(now, from, &buf[..n]) {
                    let replies = node.handle(now, from, messages);
                    stack.send(from, &replies);
                }
            }
            for s in node.handle_timeout(Instant::now()) {
                stack.send(s.to, &[s.message]);
            }
            while let Some(d) = stack.poll_transmit() {
                let _ = socket.send_to(&d.bytes, d.to);
            }
        }
    });
    addr
}

fn args(peer: SocketAddr, spec: Vec<std::path::PathBuf>, messages: &[&str]) -> As4TalkArgs {
    As4TalkArgs {
        peer,
        bind: "127.0.0.1:0".parse().unwrap(),
        me: "42.1.7".into(),
        to: "30.1.5".into(),
        spec,
        jsidl: Vec::new(),
        control: None,
        wait: 2.0,
        messages: messages.iter().map(|m| m.to_string()).collect(),
    }
}

fn lines(out: &[u8]) -> Vec<serde_json::Value> {
    String::from_utf8_lossy(out)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{l}: {e}")))
        .collect()
}

#[test]
fn core_and_vendor_messages_by_name_over_udp() {
    let stop = Arc::new(AtomicBool::new(false));
    let peer = serve(stop.clone());

    // A Core query by name, jaus-as4's definitions.
    let mut out = Vec::new();
    as4_talk(
        &args(peer, Vec::new(), &[r#"{"message": "QueryStatus"}"#]),
        true,
        &mut out,
    )
    .unwrap();
    let got = lines(&out);
    assert_eq!(got.len(), 1, "{got:?}");
    assert_eq!(got[0]["from"], "30.1.5");
    assert_eq!(got[0]["message"], "ReportStatus");
    assert_eq!(got[0]["fields"]["status"], "Standby");

    // The vendor's messages by name, with its YAML, under control.
    let dir = std::env::temp_dir().join(format!("jaus-as4-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("acme.yaml"), VENDOR_YAML).unwrap();
    let mut a = args(
        peer,
        vec![dir.clone()],
        &[
            r#"{"message": "Resume"}"#,
            r#"{"message": "SetLampLevel", "fields": {"level": 7}}"#,
            r#"{"message": "QueryLampLevel"}"#,
            r#"{"message": "QueryStatus"}"#,
        ],
    );
    a.control = Some(10);
    a.wait = 1.0;
    let mut out = Vec::new();
    as4_talk(&a, false, &mut out).unwrap();
    let got = lines(&out);
    let names: Vec<&str> = got.iter().filter_map(|l| l["message"].as_str()).collect();
    assert!(names.contains(&"ConfirmControl"), "{names:?}");
    let report = got
        .iter()
        .find(|l| l["message"] == "ReportLampLevel")
        .unwrap_or_else(|| panic!("no Report Lamp Level in {got:?}"));
    assert_eq!(report["fields"]["level"], 7);
    let status = got.iter().find(|l| l["message"] == "ReportStatus").unwrap();
    assert_eq!(
        status["fields"]["status"], "Ready",
        "Resume by name: {got:?}"
    );
    assert_eq!(
        names.last(),
        Some(&"RejectControl"),
        "control given back: {names:?}"
    );

    // Without control the vendor's command is refused: the level stays.
    let mut out = Vec::new();
    as4_talk(
        &args(
            peer,
            vec![dir.clone()],
            &[
                r#"{"message": "SetLampLevel", "fields": {"level": 99}}"#,
                r#"{"message": "QueryLampLevel"}"#,
            ],
        ),
        false,
        &mut out,
    )
    .unwrap();
    let got = lines(&out);
    let report = got
        .iter()
        .find(|l| l["message"] == "ReportLampLevel")
        .unwrap_or_else(|| panic!("no Report Lamp Level in {got:?}"));
    assert_eq!(report["fields"]["level"], 7);

    // A query nobody answers is an error naming it.
    let e = as4_talk(
        &args(
            peer,
            vec![dir.clone()],
            &[r#"{"message": "ReportLampLevel", "fields": {"level": 1}}"#],
        ),
        true,
        &mut Vec::new(),
    )
    .unwrap_err();
    assert!(e.contains("ReportLampLevel to 30.1.5"), "{e}");
    stop.store(true, Ordering::Relaxed);
    let _ = std::fs::remove_dir_all(&dir);
}
