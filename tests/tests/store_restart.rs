//! A `jaus node` process with `store:` killed with SIGKILL and restarted (issue 35):
//! every VKS object whose creation was acknowledged, and every spooled mission, is
//! there after the restart, with the same ids and content, the mission paused; and a
//! kill in the middle of a storm of creates loses nothing that was acknowledged and
//! loads nothing half-written.

mod common;

use std::collections::BTreeMap;
use std::net::{SocketAddr, UdpSocket};
use std::process::Command;
use std::time::{Duration, Instant};

use common::jaus_bin;
use common::process::NodeProcess as Node;
use jaus::codec::Encode;
use jaus::messages::*;
use jaus::net::Framing;
use jaus::stock::spooler::{command, leaf_task, mission_of};
use jaus::wire::{Header, PacketRef};
use jaus::{Address, JausMessage};

const WM: Address = Address::new(1, 1, 61, 1);
const SPOOLER: Address = Address::new(1, 1, 36, 1);
const ME: Address = Address::new(1, 2, 40, 1);
const N: usize = 200;

struct Client {
    sock: UdpSocket,
    node: SocketAddr,
}

impl Client {
    fn new(node: SocketAddr) -> Client {
        let sock = UdpSocket::bind("127.0.0.1:0").unwrap();
        sock.set_read_timeout(Some(Duration::from_millis(20)))
            .unwrap();
        Client { sock, node }
    }

    fn send<M: JausMessage + Encode>(&self, to: Address, msg: &M) {
        let body = msg.to_bytes().unwrap();
        let h = Header::new(M::CODE, to, ME);
        let packet = [h.encode_with_size(body.len()).unwrap().as_slice(), &body].concat();
        self.sock
            .send_to(&Framing::Judp.encode(&packet), self.node)
            .unwrap();
    }

    /// The next message received before `until`.
    fn recv(&self, until: Instant) -> Option<Message> {
        let mut buf = [0u8; 9000];
        while Instant::now() < until {
            let Ok((n, _)) = self.sock.recv_from(&mut buf) else {
                continue;
            };
            let Ok(p) = Framing::Judp.decode(&buf[..n]) else {
                continue;
            };
            let Ok(p) = PacketRef::parse(p) else { continue };
            if let Ok(m) = Message::decode(p.header.command_code, p.body) {
                return Some(m);
            }
        }
        None
    }

    /// Sends `msg` and waits up to 2 s for the answer `pick` takes.
    fn ask<M: JausMessage + Encode, R>(
        &self,
        to: Address,
        msg: &M,
        pick: impl Fn(Message) -> Option<R>,
    ) -> Option<R> {
        self.send(to, msg);
        let until = Instant::now() + Duration::from_secs(2);
        while let Some(m) = self.recv(until) {
            if let Some(r) = pick(m) {
                return Some(r);
            }
        }
        None
    }

    /// Waits until the node answers (its socket is bound after it loaded the store).
    fn wait_for_node(&self, node: &Node) {
        let until = Instant::now() + Duration::from_secs(30);
        while Instant::now() < until {
            self.send(WM, &QueryHeartbeatPulse {});
            if let Some(Message::ReportHeartbeatPulse(_)) =
                self.recv(Instant::now() + Duration::from_millis(200))
            {
                return;
            }
        }
        panic!("the node never answered:\n{}", node.output());
    }

    /// Control of `to` (the spooler takes commands only from its controller).
    fn take_control(&self, to: Address) {
        let r = RequestComponentControl {
            authority_code: 100,
        };
        let ok = self.ask(to, &r, |m| match m {
            Message::ConfirmComponentControl(c) => Some(c),
            _ => None,
        });
        assert!(ok.is_some(), "no Confirm Component Control from {to}");
    }

    fn mission_status(&self, mission_id: u16) -> Option<MissionStatus> {
        let q = QueryMissionStatus {
            presence_vector: 1,
            status_type: MissionStatusType::Mission,
            mission_id,
            task_id: 0,
            task_msg_id: 0,
        };
        self.ask(SPOOLER, &q, |m| match m {
            Message::ReportMissionStatus(r) if r.mission_id == mission_id => Some(r.status),
            _ => None,
        })
    }

    /// The objects with these ids that the store holds, by id.
    fn objects(&self, ids: &[u32]) -> BTreeMap<u32, VksStoredObject> {
        let mut out = BTreeMap::new();
        for (k, chunk) in ids.chunks(20).enumerate() {
            let q = QueryVksObjects {
                response_presence_vector: 1,
                request_id: k as u8,
                object_ids: Some(chunk.to_vec()),
                ..Default::default()
            };
            let got = self
                .ask(WM, &q, |m| match m {
                    Message::ReportVksObjects(r) if r.request_id == k as u8 => {
                        Some(r.objects.unwrap_or_default())
                    }
                    _ => None,
                })
                .expect("Report VKS Objects");
            out.extend(got.into_iter().map(|o| (o.object_id, o)));
        }
        out
    }
}

/// Object `i`: a point whose position and feature class attribute say `i`.
fn object(i: usize) -> VksObject {
    VksObject {
        object_type: VksObjectType::Point,
        buffer: None,
        feature_classes: vec![VksFeatureClass {
            id: 3,
            attribute: VksAttribute::Integer(i as i32),
        }],
        points: vec![VksPoint {
            latitude: 30.0 + (i / 100) as f64 * 0.001,
            longitude: -80.0 + (i % 100) as f64 * 0.001,
        }],
    }
}

fn is_object(o: &VksStoredObject, i: usize) -> bool {
    let want = object(i);
    o.feature_classes == want.feature_classes
        && o.points.len() == 1
        && (o.points[0].latitude - want.points[0].latitude).abs() < 1e-6
        && (o.points[0].longitude - want.points[0].longitude).abs() < 1e-6
}

fn create(i: usize, request_id: u8) -> CreateVksObjects {
    CreateVksObjects {
        buffered: false,
        message_properties: 1,
        request_id,
        objects: vec![object(i)],
    }
}

fn setup(tag: &str) -> (std::path::PathBuf, SocketAddr) {
    let dir = std::env::temp_dir().join(format!("jaus-store-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let addr: SocketAddr = format!("127.0.0.1:{}", common::free_port())
        .parse()
        .unwrap();
    let cfg = dir.join("node.yaml");
    std::fs::write(
        &cfg,
        format!(
            "subsystem: 1\nnode: 1\nbind: {addr}\nhost: [world_model, mission_spooler]\nstore: vehicle.jstore\n"
        ),
    )
    .unwrap();
    (cfg, addr)
}

#[test]
fn acknowledged_objects_and_a_spooled_mission_survive_kill_9() {
    let (cfg, addr) = setup("kill");
    let node = Node::start(&cfg);
    let client = Client::new(addr);
    client.wait_for_node(&node);

    // N objects, each acknowledged with its id.
    let mut ids = Vec::new();
    for i in 0..N {
        let request_id = (i % 256) as u8;
        let id = client
            .ask(WM, &create(i, request_id), |m| match m {
                Message::ReportVksObjectsCreation(r) if r.request_id == request_id => {
                    Some(r.object_ids)
                }
                _ => None,
            })
            .expect("Report VKS Objects Creation");
        assert_eq!(id.len(), 1);
        assert_ne!(id[0], 0, "object {i} refused:\n{}", node.output());
        ids.push(id[0]);
    }
    let before = client.objects(&ids);
    assert_eq!(before.len(), N);

    // A mission of two messages for a driver, spooled (not run) and confirmed pending.
    let pd = Address::new(1, 1, 33, 1);
    let wrench = Message::from(SetWrenchEffort {
        propulsive_linear_effort_x: Some(10.0),
        ..Default::default()
    });
    let m = mission_of(
        7,
        vec![leaf_task(
            1,
            vec![
                command(1, SPOOLER, pd, &wrench, true).unwrap(),
                command(2, SPOOLER, pd, &Message::from(Resume {}), false).unwrap(),
            ],
        )],
    );
    client.take_control(SPOOLER);
    client.send(SPOOLER, &m);
    assert_eq!(client.mission_status(7), Some(MissionStatus::Pending));

    node.kill();
    let node = Node::start(&cfg);
    client.wait_for_node(&node);

    // Every object, same id and content; the mission, paused.
    let after = client.objects(&ids);
    assert_eq!(after.len(), N, "{:?}", node.output());
    assert_eq!(after, before);
    for (i, id) in ids.iter().enumerate() {
        assert!(is_object(&after[id], i), "object {id}: {:?}", after[id]);
    }
    assert_eq!(client.mission_status(7), Some(MissionStatus::Paused));
    // The operator takes control of the new process again; the mission stays paused
    // until told.
    client.take_control(SPOOLER);
    assert_eq!(client.mission_status(7), Some(MissionStatus::Paused));
    // New ids continue after the highest.
    let next = client
        .ask(WM, &create(N, 99), |m| match m {
            Message::ReportVksObjectsCreation(r) if r.request_id == 99 => Some(r.object_ids),
            _ => None,
        })
        .expect("Report VKS Objects Creation");
    assert_eq!(next, vec![ids.iter().max().unwrap() + 1]);
    node.kill();
    let _ = std::fs::remove_dir_all(cfg.parent().unwrap());
}

#[test]
fn a_kill_in_a_storm_of_creates_loses_nothing_acknowledged() {
    let (cfg, addr) = setup("storm");
    let node = Node::start(&cfg);
    let client = Client::new(addr);
    client.wait_for_node(&node);

    // Creates pipelined 16 deep; killed while some are in flight.
    const WINDOW: usize = 16;
    let mut acked: BTreeMap<u32, usize> = BTreeMap::new();
    let mut in_flight: BTreeMap<u8, usize> = BTreeMap::new();
    let mut sent = 0usize;
    let start = Instant::now();
    let kill_at = Duration::from_millis(1500);
    let mut recv_until;
    while start.elapsed() < kill_at {
        while in_flight.len() < WINDOW {
            let request_id = (sent % 256) as u8;
            client.send(WM, &create(sent, request_id));
            in_flight.insert(request_id, sent);
            sent += 1;
        }
        recv_until = Instant::now() + Duration::from_millis(5);
        while let Some(m) = client.recv(recv_until) {
            if let Message::ReportVksObjectsCreation(r) = m {
                if let Some(i) = in_flight.remove(&r.request_id) {
                    assert_eq!(r.object_ids.len(), 1);
                    assert_ne!(r.object_ids[0], 0);
                    acked.insert(r.object_ids[0], i);
                }
            }
        }
    }
    // One more window sent, and the node killed at once: creates in flight.
    for _ in 0..WINDOW {
        client.send(WM, &create(sent, (sent % 256) as u8));
        sent += 1;
    }
    node.kill();
    assert!(
        acked.len() > 50,
        "only {} creates acknowledged",
        acked.len()
    );

    let node = Node::start(&cfg);
    let client = Client::new(addr);
    client.wait_for_node(&node);
    // Every acknowledged object is there, whole.
    let ids: Vec<u32> = acked.keys().copied().collect();
    let found = client.objects(&ids);
    for (id, i) in &acked {
        let o = found
            .get(id)
            .unwrap_or_else(|| panic!("acknowledged object {id} lost"));
        assert!(is_object(o, *i), "object {id}: {o:?}");
    }
    // Nothing else but whole objects that were sent (committed, their report lost in
    // the kill): every id the store could have given is looked up.
    let all: Vec<u32> = (1..=sent as u32 + 1).collect();
    let everything = client.objects(&all);
    for (id, o) in &everything {
        let Some(i) = (0..sent).find(|i| is_object(o, *i)) else {
            panic!("object {id} is no object that was sent: {o:?}");
        };
        if let Some(j) = acked.get(id) {
            assert_eq!(*j, i);
        }
    }
    assert!(everything.len() >= acked.len() && everything.len() <= sent);
    println!(
        "storm: {sent} creates sent, {} acknowledged before the kill, {} in the store after",
        acked.len(),
        everything.len()
    );
    node.kill();
    let _ = std::fs::remove_dir_all(cfg.parent().unwrap());
}

#[test]
fn a_store_that_does_not_load_stops_the_node_with_its_file() {
    let (cfg, _) = setup("bad");
    let file = cfg.parent().unwrap().join("vehicle.jstore");
    std::fs::write(&file, vec![0x5Au8; 8192]).unwrap();
    let out = Command::new(jaus_bin())
        .args(["node", "--config"])
        .arg(&cfg)
        .args(["--seconds", "5"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "the node started: {err}");
    assert!(
        err.contains("store") && err.contains(&file.display().to_string()),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(cfg.parent().unwrap());
}
