use std::net::SocketAddr;
use std::time::Duration;

use nalgebra::Vector2;

use super::*;
use jaus::component::Hardware;
use jaus::components::{
    communicator as comm, global_pose_sensor, world_model_vector_knowledge_store as wm,
};
use jaus::net::udp::link::UdpLink;
use jaus::stock::communicator::{CommunicatorEndpoint, DataLink};
use jaus::stock::geo::LocalFrame;
use jaus_sim::scanner::Scene;

fn stock(name: &str) -> Stock {
    Stock::by_name(name).unwrap()
}

#[test]
fn every_stock_component_is_hosted_at_its_id_and_instance() {
    let t0 = Instant::now();
    let mut host = Host::new(7, 3, t0);
    let any: SocketAddr = "127.0.0.1:0".parse().unwrap();
    for s in Stock::all() {
        assert_eq!(Stock::by_name(s.name()), Some(s));
        let mut entry = Host::entry(s).instance(4);
        if s.id() == comm::ID {
            entry.links.push(UdpLinkConfig::new(1, any, any));
        }
        let e = host.build(&entry).unwrap();
        assert_eq!(e.address(), Address::new(7, 3, s.id(), 4), "{s}");
    }
    let again = host.build(&Host::entry(stock("world_model")).instance(4));
    assert!(matches!(again, Err(HostError::Duplicate { .. })));
    let zero = host.build(&Host::entry(stock("world_model")).instance(0));
    assert!(matches!(zero, Err(HostError::Instance { .. })));
}

#[test]
fn each_core_gets_the_hardware_its_definition_says_it_needs() {
    let t0 = Instant::now();
    let mut host = Host::new(7, 3, t0);
    let any: SocketAddr = "127.0.0.1:0".parse().unwrap();
    for s in Stock::all() {
        let mut entry = Host::entry(s);
        if s.id() == comm::ID {
            entry.links.push(UdpLinkConfig::new(1, any, any));
        }
        let (_, used) = host.build_used(&entry).unwrap();
        let want: Vec<Hardware> = match s.needs() {
            Hardware::None => vec![],
            h => vec![h],
        };
        assert_eq!(
            used,
            want,
            "{s}: `stock.needs` in jaus-spec/defs says {}",
            s.needs()
        );
    }
}

#[test]
fn a_default_host_simulates_an_empty_world_and_a_configured_one_its_scene() {
    let t0 = Instant::now();
    let empty = Host::new(1, 1, t0);
    assert_eq!(empty.world(), &World::default());
    assert!(empty.scanner.scene().circles.is_empty());
    let origin = LocalFrame::new(10.0, 20.0, 5.0);
    let scene = Scene {
        circles: vec![(Vector2::new(3.0, 0.0), 0.5)],
    };
    let host = Host::with_world(
        1,
        1,
        t0,
        World {
            origin,
            scene: scene.clone(),
            arm_control_period: Duration::from_millis(20),
        },
    );
    assert_eq!(host.scanner.scene(), scene);
    assert_eq!(host.vehicle().lock().params().origin, origin);
    let e = Host::entry(stock("global_waypoint_driver"));
    let cx = BuildCx::new(&host, &e, Address::new(1, 1, 45, 1));
    assert_eq!(cx.drive(global_pose_sensor::ID).origin, Some(origin));
}

#[test]
fn a_communicator_needs_its_links_and_is_the_nodes_gateway() {
    let t0 = Instant::now();
    let mut host = Host::new(2, 1, t0);
    let any: SocketAddr = "127.0.0.1:0".parse().unwrap();
    let mut e = Host::entry(stock("communicator"));
    let none = host.build(&e).err().unwrap();
    assert_eq!(
        none.to_string(),
        "communicator: a communicator needs at least one data link (give its data links in `links:`; only a node hosts a communicator, as its gateway)"
    );
    e.links = vec![
        UdpLinkConfig::new(3, any, any),
        UdpLinkConfig::new(3, any, any),
    ];
    assert!(matches!(
        host.build(&e),
        Err(HostError::Links {
            error: CommunicatorError::DuplicateId(3),
            ..
        })
    ));
    // A socket that cannot be bound names the link.
    let taken = std::net::UdpSocket::bind(any).unwrap();
    e.links = vec![UdpLinkConfig::new(4, taken.local_addr().unwrap(), any)];
    let busy = host.build(&e).err().unwrap();
    assert!(matches!(busy, HostError::Link { link: 4, .. }), "{busy}");
    assert!(
        busy.to_string()
            .starts_with("communicator: data link 4: cannot use 127.0.0.1:"),
        "{busy}"
    );
    // Failed attempts hosted nothing: the same address takes a good entry.
    e.links = vec![
        UdpLinkConfig::new(1, any, any),
        UdpLinkConfig::new(2, any, any),
    ];
    let c = host.build(&e).unwrap();
    assert_eq!(c.address(), Address::new(2, 1, 35, 1));
    let gw = c
        .as_any()
        .downcast_ref::<CommunicatorEndpoint<UdpLink>>()
        .unwrap();
    assert_eq!(gw.communicator().link_ids().collect::<Vec<_>>(), [1, 2]);
    let other = Host::entry(stock("global_pose_sensor"));
    assert_eq!(
        Host::communicator_of(2, 1, [&other, &e.clone().instance(3)]),
        Some(Address::new(2, 1, 35, 3))
    );
    assert_eq!(Host::communicator_of(2, 1, [&other]), None);
}

#[test]
fn a_communicator_over_links_the_caller_made() {
    let t0 = Instant::now();
    let mut host = Host::new(2, 1, t0);
    let any: SocketAddr = "127.0.0.1:0".parse().unwrap();
    let e = Host::entry(stock("communicator")).instance(2);
    let none: Vec<Box<dyn DataLink>> = Vec::new();
    assert!(matches!(
        host.build_communicator(&e, none),
        Err(HostError::Links {
            error: CommunicatorError::NoLinks,
            ..
        })
    ));
    let links: Vec<Box<dyn DataLink>> = [7, 3]
        .into_iter()
        .map(|id| Box::new(UdpLink::bind(UdpLinkConfig::new(id, any, any)).unwrap()) as _)
        .collect();
    let c = host.build_communicator(&e, links).unwrap();
    assert_eq!(c.address(), Address::new(2, 1, 35, 2));
    let gw = c
        .as_any()
        .downcast_ref::<CommunicatorEndpoint<Box<dyn DataLink>>>()
        .unwrap();
    assert_eq!(gw.communicator().link_ids().collect::<Vec<_>>(), [7, 3]);
    // Hosted: the address is taken.
    let again = vec![UdpLink::bind(UdpLinkConfig::new(1, any, any)).unwrap()];
    assert!(matches!(
        host.build_communicator(&e, again),
        Err(HostError::Duplicate { .. })
    ));
    // Any entry given here builds the communicator.
    let other = Host::entry(stock("world_model")).instance(5);
    let links = vec![UdpLink::bind(UdpLinkConfig::new(1, any, any)).unwrap()];
    let c = host.build_communicator(&other, links).unwrap();
    assert_eq!(c.address(), Address::new(2, 1, comm::ID, 5));
    assert_ne!(wm::ID, comm::ID);
}

#[test]
fn the_demo_passes_its_world_explicitly() {
    let host = Host::with_world(1, 1, Instant::now(), jaus_sim::demo::world());
    assert_eq!(host.scanner.scene(), jaus_sim::demo::scene());
    assert_eq!(host.scanner.scene().circles.len(), 2);
    let o = jaus_sim::demo::ORIGIN;
    assert_eq!(host.world().origin, LocalFrame::new(o.0, o.1, o.2));
    assert_eq!(
        host.world().arm_control_period,
        jaus_sim::arm_demo::CONTROL_PERIOD
    );
}
