//! Judging recorded traffic: packets encoded with the SDK's codecs, faults planted, each
//! finding naming its packet numbers.

use std::net::SocketAddr;
use std::time::Duration;

use jaus::codec::Encode;
use jaus::messages::{
    ComponentState, ConfirmComponentControl, ControlResponse, QueryComponentStatus,
    QueryIdentification, QueryLevel, ReleaseComponentControl, ReportComponentStatus,
    ReportIdentification, RequestComponentControl, Resume, Standby,
};
use jaus::wire::AckNak;
use jaus::{Address, Header, JausMessage, Packet};
use jaus_conform::offline::{ids, judge, Carrier, Options, Record};
use jaus_conform::{Outcome, RunReport, Verdict};

const TARGET: Address = Address::new(1, 1, 33, 1);
const CONTROLLER: Address = Address::new(1, 2, 40, 1);
const OUTSIDER: Address = Address::new(1, 2, 40, 4);

/// Builds a capture: each packet numbered from 1 in order.
#[derive(Default)]
struct Capture {
    records: Vec<Record>,
}

impl Capture {
    fn socket(a: Address) -> SocketAddr {
        SocketAddr::from(([10, 0, a.node, 1], 3794))
    }

    fn raw(&mut self, ms: u64, from: Address, to: Address, payload: Vec<u8>) -> u64 {
        let number = self.records.len() as u64 + 1;
        self.records.push(Record {
            number,
            time: Duration::from_secs(1_700_000_000) + Duration::from_millis(ms),
            src: Self::socket(from),
            dst: Self::socket(to),
            carrier: Carrier::Ra33,
            payload,
        });
        number
    }

    fn packet<M: JausMessage>(
        &mut self,
        ms: u64,
        from: Address,
        to: Address,
        m: &M,
        ack: AckNak,
    ) -> u64 {
        let mut h = Header::new(M::CODE, to, from);
        h.ack_nak = ack;
        let p = Packet::new(h, m.to_bytes().unwrap());
        self.raw(ms, from, to, p.to_bytes().unwrap())
    }

    fn send<M: JausMessage>(&mut self, ms: u64, from: Address, to: Address, m: &M) -> u64 {
        self.packet(ms, from, to, m, AckNak::None)
    }

    /// The ACK of a message of `M` from `from` to `to`.
    fn ack<M: JausMessage>(&mut self, ms: u64, from: Address, to: Address) -> u64 {
        let h = Header::new(M::CODE, to, from).acknowledgement(to, true);
        self.raw(ms, to, from, Packet::new(h, Vec::new()).to_bytes().unwrap())
    }

    fn status(&mut self, ms: u64, to: Address, state: ComponentState) -> u64 {
        let r = ReportComponentStatus {
            primary_status_code: state,
            secondary_status_code: 0,
        };
        self.send(ms, TARGET, to, &r)
    }

    /// The controller takes control of the target.
    fn take_control(&mut self, ms: u64) {
        self.send(
            ms,
            CONTROLLER,
            TARGET,
            &RequestComponentControl { authority_code: 0 },
        );
        let ok = ConfirmComponentControl {
            response_code: ControlResponse::ControlAccepted,
        };
        self.send(ms + 1, TARGET, CONTROLLER, &ok);
    }

    fn judge(self) -> RunReport {
        judge(self.records, &Options::default(), "test")
    }
}

/// The outcome `id` of component `who`.
fn outcome<'a>(run: &'a RunReport, who: &str, id: &str) -> &'a Outcome {
    let c = run
        .components
        .iter()
        .find(|c| c.address == who)
        .unwrap_or_else(|| panic!("no component {who} in {run:#?}"));
    c.outcomes
        .iter()
        .find(|o| o.check.id == id)
        .unwrap_or_else(|| panic!("no {id} for {who} in {:#?}", c.outcomes))
}

#[test]
fn planted_faults_are_found_with_their_packets() {
    let mut cap = Capture::default();
    cap.take_control(0); // 1, 2
    cap.send(10, OUTSIDER, TARGET, &QueryComponentStatus {}); // 3
    cap.status(11, OUTSIDER, ComponentState::Ready); // 4
                                                     // The outsider's Standby, acknowledged and carried out.
    let standby = cap.packet(20, OUTSIDER, TARGET, &Standby {}, AckNak::Request); // 5
    let ack = cap.ack::<Standby>(21, OUTSIDER, TARGET); // 6
    let shown = cap.status(25, OUTSIDER, ComponentState::Standby); // 7
                                                                   // A query left unanswered.
    let unanswered = cap.send(100, OUTSIDER, TARGET, &QueryComponentStatus {}); // 8
                                                                                // A report whose header announces one byte more than it carries.
    let mut bytes = Packet::new(
        Header::new(ReportComponentStatus::CODE, OUTSIDER, TARGET),
        ReportComponentStatus::default().to_bytes().unwrap(),
    )
    .to_bytes()
    .unwrap();
    bytes.pop();
    let malformed = cap.raw(200, TARGET, OUTSIDER, bytes); // 9
                                                           // An acknowledgement asked of the target and never given.
    let no_ack = cap.packet(300, CONTROLLER, TARGET, &Resume {}, AckNak::Request); // 10
                                                                                   // A datagram too short for a header.
    let short = cap.raw(400, OUTSIDER, TARGET, vec![0x06, 0x00, 0x02]); // 11
    cap.send(3000, CONTROLLER, TARGET, &ReleaseComponentControl {}); // 12
    let run = cap.judge();
    let target = TARGET.to_string();

    assert!(!run.passed(), "{}", jaus_conform::report::summary(&run));
    let o = outcome(&run, &target, ids::OUTSIDER);
    assert_eq!(o.verdict, Verdict::Fail, "{}", o.detail);
    assert!(
        o.detail
            .contains(&format!("at packet {standby} was carried out")),
        "{}",
        o.detail
    );
    assert!(
        o.detail.contains(&format!("packet {shown} shows Standby")),
        "{}",
        o.detail
    );
    assert!(o.detail.contains(&OUTSIDER.to_string()), "{}", o.detail);

    let o = outcome(&run, &target, ids::OUTSIDER_ACK);
    assert_eq!(o.verdict, Verdict::Fail, "{}", o.detail);
    assert!(
        o.detail.contains(&format!(
            "(packet {standby}) acknowledged with ACK (packet {ack})"
        )),
        "{}",
        o.detail
    );

    let o = outcome(&run, &target, ids::QUERY);
    assert_eq!(o.verdict, Verdict::Fail, "{}", o.detail);
    assert!(o.detail.contains("1 of 2 queries answered"), "{}", o.detail);
    assert!(
        o.detail.contains(&format!(
            "QueryComponentStatus from {OUTSIDER} (packet {unanswered})"
        )),
        "{}",
        o.detail
    );

    let o = outcome(&run, &target, ids::MALFORMED);
    assert_eq!(o.verdict, Verdict::Fail, "{}", o.detail);
    assert!(
        o.detail.contains(&format!(
            "packet {malformed} (to {OUTSIDER}): ReportComponentStatus"
        )),
        "{}",
        o.detail
    );
    assert_eq!(o.evidence.len(), 1);

    let o = outcome(&run, &target, ids::ACKNAK);
    assert_eq!(o.verdict, Verdict::Fail, "{}", o.detail);
    assert!(
        o.detail
            .contains(&format!("Resume from {CONTROLLER} (packet {no_ack})")),
        "{}",
        o.detail
    );
    assert!(
        !o.detail.contains(&format!("packet {standby})")),
        "{}",
        o.detail
    );

    let o = outcome(&run, "10.0.2.1:3794", ids::MALFORMED);
    assert_eq!(o.verdict, Verdict::Fail, "{}", o.detail);
    assert!(
        o.detail.contains(&format!("packet {short} ")),
        "{}",
        o.detail
    );
    assert!(o.detail.contains("header"), "{}", o.detail);

    // The other reports say the same.
    let junit = jaus_conform::report::junit(&run);
    assert!(junit.contains(&format!("packet {unanswered}")), "{junit}");
    assert!(jaus_conform::report::json(&run).contains("offline.control.outsider"));
}

#[test]
fn a_clean_exchange_has_no_required_failure() {
    let mut cap = Capture::default();
    let id = QueryIdentification {
        query_field: QueryLevel::Component,
    };
    cap.send(0, CONTROLLER, TARGET, &id);
    let report = ReportIdentification {
        query_type: QueryLevel::Component,
        identification: "Clean Robot".into(),
        ..Default::default()
    };
    cap.send(2, TARGET, CONTROLLER, &report);
    cap.take_control(10);
    cap.send(20, OUTSIDER, TARGET, &QueryComponentStatus {});
    cap.status(21, OUTSIDER, ComponentState::Ready);
    // The controller's Standby, acknowledged and carried out.
    cap.packet(30, CONTROLLER, TARGET, &Standby {}, AckNak::Request);
    cap.ack::<Standby>(31, CONTROLLER, TARGET);
    cap.send(40, OUTSIDER, TARGET, &QueryComponentStatus {});
    cap.status(41, OUTSIDER, ComponentState::Standby);
    // The outsider's Resume, refused (with NAK): the state stays Standby.
    cap.packet(50, OUTSIDER, TARGET, &Resume {}, AckNak::Request);
    let h = Header::new(Resume::CODE, TARGET, OUTSIDER).acknowledgement(TARGET, false);
    cap.raw(
        51,
        TARGET,
        OUTSIDER,
        Packet::new(h, Vec::new()).to_bytes().unwrap(),
    );
    cap.send(60, OUTSIDER, TARGET, &QueryComponentStatus {});
    cap.status(61, OUTSIDER, ComponentState::Standby);
    cap.send(2000, CONTROLLER, TARGET, &ReleaseComponentControl {});
    let run = cap.judge();
    let summary = jaus_conform::report::summary(&run);
    assert!(run.passed(), "{summary}");
    assert!(
        run.components.iter().all(|c| c.count(Verdict::Fail) == 0),
        "{summary}"
    );
    let target = TARGET.to_string();
    let o = outcome(&run, &target, ids::QUERY);
    assert_eq!(o.verdict, Verdict::Pass);
    assert!(
        o.detail.contains("4 of 4 queries answered") && o.detail.contains("p50"),
        "{}",
        o.detail
    );
    let o = outcome(&run, &target, ids::OUTSIDER);
    assert_eq!(o.verdict, Verdict::Pass, "{}", o.detail);
    let o = outcome(&run, &target, ids::OUTSIDER_ACK);
    assert_eq!(o.verdict, Verdict::Pass, "{}", o.detail);
    assert_eq!(outcome(&run, &target, ids::ACKNAK).verdict, Verdict::Pass);
    let c = run.components.iter().find(|c| c.address == target).unwrap();
    assert_eq!(c.identification.as_deref(), Some("Clean Robot"));
}

#[test]
fn as4_datagrams_are_decoded_and_queries_paired() {
    use jaus::net::as5669a::{split, write_datagrams, As4Id, As4Message};
    let vehicle = As4Id::new(7, 1, 1);
    let ocu = As4Id::new(42, 1, 1);
    let datagram = |m: As4Message| {
        let packets = split(&m.header(), &m.payload(), 0, 1400).unwrap();
        write_datagrams(&packets, 1400).unwrap().remove(0)
    };
    let mut records = Vec::new();
    let mut push = |ms: u64, payload: Vec<u8>| {
        let number = records.len() as u64 + 1;
        records.push(Record {
            number,
            time: Duration::from_millis(ms),
            src: "10.0.0.1:3794".parse().unwrap(),
            dst: "10.0.0.2:3794".parse().unwrap(),
            carrier: Carrier::As5669a,
            payload,
        });
        number
    };
    let status = jaus_as4::messages::QueryStatus::CODE.0;
    let report = jaus_as4::messages::ReportStatus::default()
        .to_bytes()
        .unwrap();
    let report_code = jaus_as4::messages::ReportStatus::CODE.0;
    push(0, datagram(As4Message::new(status, vehicle, ocu, vec![])));
    push(
        5,
        datagram(As4Message::new(report_code, ocu, vehicle, report)),
    );
    let unanswered = push(10, datagram(As4Message::new(status, vehicle, ocu, vec![])));
    let bad = push(20, vec![2, 0xFF]);
    push(
        3000,
        datagram(As4Message::new(status, vehicle, ocu, vec![])),
    );
    let run = judge(records, &Options::default(), "as4");
    let o = outcome(&run, "7.1.1 (AS-4)", ids::AS4_QUERY);
    assert_eq!(o.verdict, Verdict::Fail, "{}", o.detail);
    assert!(
        o.detail
            .contains(&format!("QueryStatus from {ocu} (packet {unanswered})")),
        "{}",
        o.detail
    );
    assert!(
        o.detail.contains("not judged, the capture ending"),
        "{}",
        o.detail
    );
    let o = outcome(&run, "10.0.0.1:3794", ids::AS4_MALFORMED);
    assert_eq!(o.verdict, Verdict::Fail, "{}", o.detail);
    assert!(o.detail.contains(&format!("packet {bad} ")), "{}", o.detail);
    assert!(!run.passed());
}

#[test]
fn the_controllers_own_command_ends_the_watch_and_requests_are_bounded() {
    let mut cap = Capture::default();
    cap.take_control(0); // 1, 2
    cap.status(5, OUTSIDER, ComponentState::Ready); // 3
    let outsider = cap.send(10, OUTSIDER, TARGET, &Standby {}); // 4
    cap.status(15, OUTSIDER, ComponentState::Ready); // 5: unchanged
    cap.send(20, CONTROLLER, TARGET, &Standby {}); // 6: the controller's
    cap.status(25, OUTSIDER, ComponentState::Standby); // 7: its effect
                                                       // Query Identification for a level no level has: no answer is due.
    let odd = QueryIdentification {
        query_field: QueryLevel::Unknown(0xEE),
    };
    cap.send(30, OUTSIDER, TARGET, &odd);
    cap.send(3000, CONTROLLER, TARGET, &ReleaseComponentControl {});
    let run = cap.judge();
    let summary = jaus_conform::report::summary(&run);
    assert!(run.passed(), "{summary}");
    let o = outcome(&run, &TARGET.to_string(), ids::OUTSIDER);
    assert_eq!(o.verdict, Verdict::Pass, "{}", o.detail);
    assert!(
        o.detail.contains(&format!("unchanged: packet {outsider}")),
        "{}",
        o.detail
    );

    // Five queries never answered, two tracked at once: three are counted, not judged.
    let mut cap = Capture::default();
    for i in 0..5 {
        cap.send(i, OUTSIDER, TARGET, &QueryComponentStatus {});
    }
    let opts = Options {
        max_outstanding: 2,
        ..Options::default()
    };
    let mut judge = jaus_conform::offline::Judge::new(opts);
    for r in &cap.records {
        judge.push(r);
    }
    assert_eq!(judge.dropped(), 3);
    let run = judge.finish("bounded");
    let o = outcome(&run, &TARGET.to_string(), ids::QUERY);
    assert_eq!(o.verdict, Verdict::Inconclusive, "{}", o.detail);
    assert!(o.detail.contains("packets 1, 2"), "{}", o.detail);
}

#[test]
fn arbitrary_bytes_are_findings_not_panics() {
    // Valid packets with bytes overwritten, and noise, as either carrier.
    let mut seed = 0x2545_F491_4F6C_DD1Du64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    let base = Packet::new(
        Header::new(ReportComponentStatus::CODE, OUTSIDER, TARGET),
        ReportComponentStatus::default().to_bytes().unwrap(),
    )
    .to_bytes()
    .unwrap();
    let mut records = Vec::new();
    for i in 0..3000u64 {
        let mut payload = if i % 3 == 0 {
            (0..next() % 40).map(|_| next() as u8).collect()
        } else {
            base.clone()
        };
        if !payload.is_empty() {
            let at = (next() as usize) % payload.len();
            payload[at] = next() as u8;
        }
        if i % 5 == 0 {
            payload.insert(0, 2);
        }
        records.push(Record {
            number: i + 1,
            time: Duration::from_millis(i),
            src: "10.0.0.1:3794".parse().unwrap(),
            dst: "10.0.0.2:3794".parse().unwrap(),
            carrier: if i % 5 == 0 {
                Carrier::As5669a
            } else {
                Carrier::Ra33
            },
            payload,
        });
    }
    let run = judge(records, &Options::default(), "noise");
    assert!(!run.passed());
    for format in [
        jaus_conform::report::summary(&run),
        jaus_conform::report::html(&run),
        jaus_conform::report::junit(&run),
    ] {
        assert!(format.contains("packet"));
    }
}
