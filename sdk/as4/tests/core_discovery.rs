//! Discovery, Time and Liveness of the Core runtime.

mod core_common;

use std::time::{Duration, Instant};

use core_common::*;
use jaus_as4::core::CoreConfig;
use jaus_as4::{
    ComponentServiceFilter, ConfigurationType, DateStamp, EntityType, IdentificationType, Message,
    NodeServiceListQuery, NodeServicesQuery, QueryConfiguration, QueryHeartbeatPulse,
    QueryIdentification, QueryServiceList, QueryServices, QuerySubsystemList, QueryTime,
    RegisterServices, ReportHeartbeatPulse, ReportIdentification, ReportTime, RequestControl,
    ServiceInfo, SetTime, SubsystemServiceListQuery, TimeStamp,
};

fn uris(report: &Message) -> Vec<(String, u8, u8)> {
    let Message::ReportServices(r) = report else {
        panic!("{report:?}");
    };
    r.nodes
        .iter()
        .flat_map(|n| &n.components)
        .flat_map(|c| &c.services)
        .map(|s| (s.uri.clone(), s.major_version, s.minor_version))
        .collect()
}

#[test]
fn report_services_lists_the_core_and_the_service_with_versions() {
    let t = Instant::now();
    let (mut c, _) = component(CoreConfig::named("rover"));
    let q = QueryServices {
        nodes: vec![NodeServicesQuery {
            node_id: 1,
            component_ids: vec![1],
        }],
    };
    let got = uris(&only_for(&send(&mut c, t, A, q), A));
    let want = [
        "Transport",
        "Events",
        "AccessControl",
        "Management",
        "Time",
        "Liveness",
        "Discovery",
        "ListManager",
    ];
    for name in want {
        let uri = format!("urn:jaus:jss:core:{name}");
        assert!(
            got.contains(&(uri.clone(), 1, 1)),
            "{uri} missing in {got:?}"
        );
    }
    assert!(got.contains(&("urn:test:Speedo".into(), 2, 3)));
    assert_eq!(got.len(), 9);
    // Without the List Manager, it is not listed.
    let config = CoreConfig {
        list_manager: false,
        ..CoreConfig::named("rover")
    };
    let (mut c, _) = component(config);
    let q = QueryServices {
        nodes: vec![NodeServicesQuery {
            node_id: 255,
            component_ids: vec![255],
        }],
    };
    let got = uris(&only_for(&send(&mut c, t, A, q), A));
    assert_eq!(got.len(), 8);
    assert!(!got.iter().any(|(u, _, _)| u.ends_with("ListManager")));
}

#[test]
fn report_identification_by_query_type() {
    let t = Instant::now();
    let mut config = CoreConfig::named("rover");
    config.identification.node = "rover-pc".into();
    config.identification.component = "rover-core".into();
    let (mut c, _) = component(config);
    let ask = |c: &mut _, query_type| send(c, t, A, QueryIdentification { query_type });
    let want = |query_type, entity_type, name: &str| -> Message {
        ReportIdentification {
            query_type,
            entity_type,
            identification: name.into(),
        }
        .into()
    };
    assert_eq!(
        only_for(&ask(&mut c, IdentificationType::Subsystem), A),
        want(IdentificationType::Subsystem, EntityType::Vehicle, "rover")
    );
    assert_eq!(
        only_for(&ask(&mut c, IdentificationType::Node), A),
        want(IdentificationType::Node, EntityType::Node, "rover-pc")
    );
    assert_eq!(
        only_for(&ask(&mut c, IdentificationType::Component), A),
        want(
            IdentificationType::Component,
            EntityType::Component,
            "rover-core"
        )
    );
    // No system name configured: not answered, counted.
    assert!(ask(&mut c, IdentificationType::System).is_empty());
    assert_eq!(c.stats().refused, 1);
}

#[test]
fn registrations_feed_configuration_service_list_and_subsystem_list() {
    let t = Instant::now();
    let config = CoreConfig {
        max_registrations: 2,
        ..CoreConfig::named("rover")
    };
    let (mut c, _) = component(config);
    let svc = |uri: &str| ServiceInfo {
        uri: uri.into(),
        major_version: 1,
        minor_version: 0,
    };
    // Another component of the subsystem (node 2) and one of subsystem 43.
    let sibling = jaus::net::as5669a::As4Id::new(7, 2, 5);
    send(
        &mut c,
        t,
        sibling,
        RegisterServices {
            services: vec![svc("urn:jaus:jss:mobility:PrimitiveDriver")],
        },
    );
    send(
        &mut c,
        t,
        C,
        RegisterServices {
            services: vec![svc("urn:jaus:jss:mobility:LocalPoseSensor")],
        },
    );
    // The bound: a third is refused and counted.
    send(&mut c, t, A, RegisterServices { services: vec![] });
    assert_eq!(c.stats().bounds, 1);

    let Message::ReportConfiguration(r) = only_for(
        &send(
            &mut c,
            t,
            A,
            QueryConfiguration {
                query_type: ConfigurationType::Subsystem,
            },
        ),
        A,
    ) else {
        panic!()
    };
    let nodes: Vec<(u8, Vec<u8>)> = r
        .nodes
        .iter()
        .map(|n| {
            (
                n.node_id,
                n.components.iter().map(|c| c.component_id).collect(),
            )
        })
        .collect();
    assert_eq!(nodes, vec![(1, vec![1]), (2, vec![5])]);
    let Message::ReportConfiguration(r) = only_for(
        &send(
            &mut c,
            t,
            A,
            QueryConfiguration {
                query_type: ConfigurationType::Node,
            },
        ),
        A,
    ) else {
        panic!()
    };
    assert_eq!(r.nodes.len(), 1);

    let Message::ReportSubsystemList(r) = only_for(&send(&mut c, t, A, QuerySubsystemList {}), A)
    else {
        panic!()
    };
    let subsystems: Vec<u16> = r.subsystems.iter().map(|a| a.subsystem_id).collect();
    assert_eq!(subsystems, vec![7, 43]);

    // Every subsystem, every node, every component, URIs containing "mobility".
    let q = QueryServiceList {
        subsystems: vec![SubsystemServiceListQuery {
            subsystem_id: 0xFFFF,
            nodes: vec![NodeServiceListQuery {
                node_id: 255,
                components: vec![ComponentServiceFilter {
                    component_id: 255,
                    search_filter: Some("mobility".into()),
                }],
            }],
        }],
    };
    let Message::ReportServiceList(r) = only_for(&send(&mut c, t, A, q), A) else {
        panic!()
    };
    let found: Vec<(u16, String)> = r
        .subsystems
        .iter()
        .flat_map(|s| {
            s.nodes.iter().flat_map(move |n| {
                n.components.iter().flat_map(move |c| {
                    c.services
                        .iter()
                        .map(move |x| (s.subsystem_id, x.uri.clone()))
                })
            })
        })
        .collect();
    assert_eq!(
        found,
        vec![
            (7, "urn:jaus:jss:mobility:PrimitiveDriver".to_string()),
            (43, "urn:jaus:jss:mobility:LocalPoseSensor".to_string()),
        ]
    );
}

#[test]
fn report_time_from_the_utc_set_and_set_time_by_the_controller_only() {
    let t = Instant::now();
    let (mut c, _) = component(CoreConfig::named("rover"));
    let both = QueryTime { presence_vector: 3 };
    // Unknown clock: neither field.
    assert_eq!(
        only_for(&send(&mut c, t, A, both.clone()), A),
        ReportTime::default().into()
    );
    // 2026-11-22 03:06:07.250 UTC.
    let utc = Duration::from_millis(20_779 * 86_400_000 + ((3 * 60 + 6) * 60 + 7) * 1000 + 250);
    c.set_utc(t, utc);
    let later = t + Duration::from_millis(1_000);
    let Message::ReportTime(r) = only_for(&send(&mut c, later, A, both.clone()), A) else {
        panic!()
    };
    let (ts, ds) = (r.time_stamp.unwrap(), r.date_stamp.unwrap());
    assert_eq!(
        (ts.hour, ts.minute, ts.second, ts.millisecond, ts.day),
        (3, 6, 8, 250, 22)
    );
    assert_eq!((ds.year, ds.month, ds.day), (26, 11, 22));
    // Only the date asked for.
    let Message::ReportTime(r) =
        only_for(&send(&mut c, later, A, QueryTime { presence_vector: 2 }), A)
    else {
        panic!()
    };
    assert!(r.time_stamp.is_none() && r.date_stamp.is_some());

    let set = SetTime {
        time_stamp: Some(TimeStamp {
            millisecond: 0,
            second: 0,
            minute: 30,
            hour: 12,
            day: 1,
            reserved: 0,
        }),
        date_stamp: Some(DateStamp {
            day: 1,
            month: 1,
            year: 27,
            reserved: 0,
        }),
    };
    // Not the controller: ignored.
    send(&mut c, later, B, set.clone());
    assert_eq!(c.stats().not_controller, 1);
    let Message::ReportTime(r) = only_for(&send(&mut c, later, A, both.clone()), A) else {
        panic!()
    };
    assert_eq!(r.date_stamp.unwrap().year, 26);
    // The controller sets it (control suffices, Standby is fine).
    send(&mut c, later, A, RequestControl { authority_code: 0 });
    send(&mut c, later, A, set);
    let Message::ReportTime(r) =
        only_for(&send(&mut c, later + Duration::from_secs(2), B, both), B)
    else {
        panic!()
    };
    let (ts, ds) = (r.time_stamp.unwrap(), r.date_stamp.unwrap());
    assert_eq!((ts.hour, ts.minute, ts.second), (12, 30, 2));
    assert_eq!((ds.year, ds.month, ds.day), (27, 1, 1));
}

#[test]
fn heartbeat_pulse_in_every_state() {
    let t = Instant::now();
    let (mut c, _) = component(CoreConfig::named("rover"));
    assert_eq!(
        only_for(&send(&mut c, t, C, QueryHeartbeatPulse {}), C),
        ReportHeartbeatPulse {}.into()
    );
    send(&mut c, t, A, RequestControl { authority_code: 0 });
    send(&mut c, t, A, jaus_as4::Shutdown {});
    assert_eq!(
        only_for(&send(&mut c, t, C, QueryHeartbeatPulse {}), C),
        ReportHeartbeatPulse {}.into()
    );
}
