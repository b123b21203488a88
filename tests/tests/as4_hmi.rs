//! The HMI service set (`sdk/as4/defs/hmi.yaml`, `hmi_services.yaml`) on its generated
//! machines, with a test service: an operator panel (buttons and a joystick) that no
//! stock core stands behind. The panel writes only the Digital Control's and Analog
//! Control's own actions; the inherited Access Control and Events are the component's
//! Core. Checked: a remote asset asks which analog devices the panel has and how far the
//! joystick is deflected (any client, no control), asks the last button action, sets
//! how a button is shown only while it controls the panel, and an event on the
//! joystick's query reports its deflection. And `jaus conform --as4 --plan` against it
//! (in memory): every required check of both services passes.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;
use jaus_as4::component::As4Component;
use jaus_as4::core::CoreConfig;
use jaus_as4::messages::services::transport::event::Receive;
use jaus_as4::messages::services::{analog_control, digital_control};
use jaus_as4::service::Outbox;
use jaus_as4::{
    AnalogDevice, AnalogValue, CreateEvent, DigitalControlState, DigitalControlStateFlags,
    EventType, Message, QueryAnalogAction, QueryAnalogDevices, QueryDcm, ReportAnalogAction,
    ReportAnalogDevices, ReportDcm, RequestControl, SetDcm,
};

const PANEL: As4Id = As4Id::new(60, 1, 1);
const ASSET: As4Id = As4Id::new(61, 1, 1);
const OTHER: As4Id = As4Id::new(62, 1, 1);

/// The panel: its buttons (how each is shown, the last press or release) and its
/// joystick's deflection, shared by its two services.
#[derive(Debug, Default)]
struct Panel {
    shown: BTreeMap<u16, DigitalControlStateFlags>,
    last_action: Option<(u16, DigitalControlState)>,
    stick: (i16, i16),
}

type Shared = std::sync::Arc<std::sync::Mutex<Panel>>;

const STICK: u16 = 7;

/// The Digital Control service's own actions over the panel's buttons; the generated
/// `Hosted` adapter runs them on the service's machines.
#[derive(Debug, Default)]
struct Buttons {
    panel: Shared,
    outbox: Outbox,
}

impl AsMut<Outbox> for Buttons {
    fn as_mut(&mut self) -> &mut Outbox {
        &mut self.outbox
    }
}

impl digital_control::DigitalControl for Buttons {
    fn send_report_dcm(&mut self, _msg: &QueryDcm, transport_data: &Receive) {
        // Before any press there is no action to report: nothing is sent.
        if let Some((reference, state)) = self.panel.lock().unwrap().last_action {
            self.outbox
                .reply(transport_data, &ReportDcm { reference, state });
        }
    }

    fn set_dcm(&mut self, msg: &SetDcm) {
        self.panel
            .lock()
            .unwrap()
            .shown
            .insert(msg.reference, msg.state);
    }
}

/// The Analog Control service's own actions over the panel's joystick.
#[derive(Debug, Default)]
struct Joystick {
    panel: Shared,
    outbox: Outbox,
}

impl AsMut<Outbox> for Joystick {
    fn as_mut(&mut self) -> &mut Outbox {
        &mut self.outbox
    }
}

impl analog_control::AnalogControl for Joystick {
    fn send_report_analog_devices(&mut self, _msg: &QueryAnalogDevices, transport_data: &Receive) {
        let devices = vec![AnalogDevice {
            reference: STICK,
            name: "drive stick".into(),
        }];
        self.outbox
            .reply(transport_data, &ReportAnalogDevices { devices });
    }

    fn send_report_analog_action(&mut self, msg: &QueryAnalogAction, transport_data: &Receive) {
        if msg.analog_reference != STICK {
            // A device the panel has not: its report carries no axis (the query's
            // transition is unguarded, so it is answered).
            let none = ReportAnalogAction {
                reference: msg.analog_reference,
                ..Default::default()
            };
            return self.outbox.reply(transport_data, &none);
        }
        // The axes asked for (bit 0 longitudinal, bit 1 lateral) that the stick has.
        let asked = msg.presence_vector as u8;
        let stick = self.panel.lock().unwrap().stick;
        let report = ReportAnalogAction {
            reference: STICK,
            longitudinal: (asked & 1 != 0).then_some(AnalogValue::I16(stick.0)),
            lateral: (asked & 2 != 0).then_some(AnalogValue::I16(stick.1)),
            ..Default::default()
        };
        self.outbox.reply(transport_data, &report);
    }
}

fn panel() -> (As4Component<()>, Shared) {
    let shared = Shared::default();
    let c = As4Component::new(PANEL, CoreConfig::named("panel"))
        .with_service(digital_control::Hosted::new(Buttons {
            panel: shared.clone(),
            outbox: Outbox::new(),
        }))
        .with_service(analog_control::Hosted::new(Joystick {
            panel: shared.clone(),
            outbox: Outbox::new(),
        }));
    (c, shared)
}

fn ask(c: &mut As4Component<()>, t: Instant, from: As4Id, m: impl Into<Message>) -> Vec<Message> {
    c.handle(t, from, &m.into(), &mut ())
        .into_iter()
        .filter(|o| o.to == from)
        .map(|o| o.message)
        .collect()
}

#[test]
fn the_panel_serves_digital_and_analog_control_on_the_generated_machines() {
    let t = Instant::now();
    let (mut c, shared) = panel();
    let ids: Vec<String> = c.service_ids().iter().map(|s| s.to_string()).collect();
    for uri in [
        "urn:jaus:jss:HMI:DigitalControl v1.0",
        "urn:jaus:jss:HMI:AnalogControl v1.0",
    ] {
        assert!(ids.contains(&uri.to_string()), "{ids:?}");
    }

    // Any client asks the devices and the deflection.
    let out = ask(&mut c, t, OTHER, QueryAnalogDevices {});
    let Some(Message::ReportAnalogDevices(d)) = out.first() else {
        panic!("Report Analog Devices expected: {out:?}")
    };
    assert_eq!(d.devices.len(), 1);
    assert_eq!(
        (d.devices[0].reference, d.devices[0].name.as_str()),
        (STICK, "drive stick")
    );
    shared.lock().unwrap().stick = (-1200, 300);
    let out = ask(
        &mut c,
        t,
        OTHER,
        QueryAnalogAction {
            presence_vector: 1,
            analog_reference: STICK,
        },
    );
    let Some(Message::ReportAnalogAction(a)) = out.first() else {
        panic!("Report Analog Action expected: {out:?}")
    };
    assert_eq!(a.longitudinal, Some(AnalogValue::I16(-1200)));
    assert_eq!(a.lateral, None, "only the axis asked for");

    // The last button action: none yet, then a press.
    assert!(ask(&mut c, t, OTHER, QueryDcm {}).is_empty());
    shared.lock().unwrap().last_action = Some((3, DigitalControlState::Pressed));
    let out = ask(&mut c, t, OTHER, QueryDcm {});
    assert_eq!(
        out.first(),
        Some(&Message::ReportDcm(ReportDcm {
            reference: 3,
            state: DigitalControlState::Pressed
        }))
    );

    // How a button is shown: only under control (Set DCM's transition is under
    // Controlled), from the controller.
    let flashing = DigitalControlStateFlags {
        active: true,
        flash: true,
        flash_rate: 2,
        ..Default::default()
    };
    let refused = c.stats().refused;
    ask(
        &mut c,
        t,
        ASSET,
        SetDcm {
            reference: 3,
            state: flashing,
        },
    );
    assert!(shared.lock().unwrap().shown.is_empty());
    assert_eq!(c.stats().refused, refused + 1);
    let out = ask(&mut c, t, ASSET, RequestControl { authority_code: 5 });
    assert!(
        matches!(out.first(), Some(Message::ConfirmControl(_))),
        "{out:?}"
    );
    ask(
        &mut c,
        t,
        ASSET,
        SetDcm {
            reference: 3,
            state: flashing,
        },
    );
    assert_eq!(shared.lock().unwrap().shown.get(&3), Some(&flashing));
}

#[test]
fn an_event_on_the_joysticks_query_reports_its_deflection() {
    let t0 = Instant::now();
    let (mut c, shared) = panel();
    shared.lock().unwrap().stick = (500, -40);
    let query = jaus_as4::embedded::encode(&Message::from(QueryAnalogAction {
        presence_vector: 3,
        analog_reference: STICK,
    }))
    .unwrap();
    let out = ask(
        &mut c,
        t0,
        ASSET,
        CreateEvent {
            request_id: 1,
            event_type: EventType::Periodic,
            requested_periodic_rate: 5.0,
            query_message: query,
        },
    );
    assert!(
        matches!(out.first(), Some(Message::ConfirmEventRequest(_))),
        "{out:?}"
    );
    // Within a second at 5 Hz, events carrying Report Analog Action with both axes.
    let mut reports = Vec::new();
    let mut t = t0;
    while t < t0 + Duration::from_secs(1) {
        t += Duration::from_millis(50);
        for o in c.handle_timeout(t, &mut ()) {
            if let (true, Message::Event(e)) = (o.to == ASSET, &o.message) {
                reports.push(e.report().unwrap());
            }
        }
    }
    assert!(reports.len() >= 4, "{} events", reports.len());
    assert!(reports.iter().all(|r| matches!(
        r,
        Message::ReportAnalogAction(a)
            if a.longitudinal == Some(AnalogValue::I16(500)) && a.lateral == Some(AnalogValue::I16(-40))
    )), "{reports:?}");
}

#[test]
fn the_planned_conformance_checks_pass_against_the_panel() {
    use jaus_conform::as4::planned::{run_planned, Definitions};
    use jaus_conform::as4::{As4Host, As4Options, MemoryAs4Session};
    use jaus_conform::Verdict;

    let t0 = Instant::now();
    let (component, shared) = panel();
    shared.lock().unwrap().last_action = Some((3, DigitalControlState::Pressed));
    let node: jaus_as4::node::As4Node<(), std::net::SocketAddr> =
        jaus_as4::node::As4Node::new(()).with_component(component);
    let mut session = MemoryAs4Session::new(As4Host::new(node), t0);
    let defs = Definitions::as4().expect("jaus-as4's definitions");
    let run = run_planned(
        &mut session,
        &defs,
        &As4Options {
            target: Some(PANEL),
            ..As4Options::default()
        },
    );
    let outcomes = &run.components[0].outcomes;
    for o in outcomes {
        println!("{} {:?}: {}", o.check.id, o.verdict, o.detail);
    }
    let listed = &outcomes[0].detail;
    for uri in [
        "urn:jaus:jss:HMI:DigitalControl",
        "urn:jaus:jss:HMI:AnalogControl",
    ] {
        assert!(listed.contains(uri), "{uri} not listed: {listed}");
    }
    let hmi: Vec<_> = outcomes
        .iter()
        .filter(|o| {
            o.check.id.starts_with("as4.digital_control.")
                || o.check.id.starts_with("as4.analog_control.")
        })
        .collect();
    assert!(hmi.len() >= 5, "{} HMI checks", hmi.len());
    let failed: Vec<String> = outcomes
        .iter()
        .filter(|o| o.verdict == Verdict::Fail)
        .map(|o| format!("{}: {}", o.check.id, o.detail))
        .collect();
    assert!(failed.is_empty(), "failed:\n{}", failed.join("\n"));
    assert!(run.passed());
    // Set DCM's `state` (flags: how a button is shown) is not Report DCM's (pressed or
    // released): Query DCM is not its read-back, so no `.controller` check.
    assert!(!outcomes
        .iter()
        .any(|o| o.check.id == "as4.digital_control.command.SetDcm.controller"));
    let passed = outcomes
        .iter()
        .filter(|o| o.verdict == Verdict::Pass)
        .count();
    println!("panel: {passed} of {} checks passed", outcomes.len());
}
