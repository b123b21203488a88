//! Vendor Lamp: an AS-4 service of its own (`defs/vendor_lamp.yaml`), generated at build
//! time on jaus-as4's definitions, its guards and actions implemented here, hosted on an
//! AS-4 component whose Core (Access Control, Management, Events, Discovery, ...) comes
//! with jaus-as4.
//!
//! What is written by hand is [`Bulb`]: the service's own guards (`is_level_valid`) and
//! actions (`set_level`, `send_report_lamp_level`). The generated `Hosted` runs the
//! service's machine; the inherited guard `isControllingClient` is the Core's.

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use jaus::net::as5669a::{As4Config, As4Id, As4Mux};
use jaus::net::node::{Node, NodeConfig};
use jaus_as4::component::As4Component;
use jaus_as4::core::CoreConfig;
use jaus_as4::messages::services::transport::event::Receive;
use jaus_as4::node::As4Node;
use jaus_as4::service::Outbox;

/// The generated messages (this crate's own; jaus-as4's are `Message::Jaus`) and, in
/// `services`, the service's trait, triggers, state machines and `Hosted` adapter.
#[allow(clippy::all)]
pub mod messages {
    include!(concat!(env!("OUT_DIR"), "/messages.rs"));

    /// The generated service.
    pub mod services {
        include!(concat!(env!("OUT_DIR"), "/services.rs"));
    }
}

use messages::services::lamp;
pub use messages::{QueryLampLevel, ReportLampLevel, SetLampLevel};

/// The lamp's own guards and actions: here a level in memory. Replace it with your
/// hardware.
#[derive(Debug, Default)]
pub struct Bulb {
    /// The level, %.
    pub level: u8,
    /// What the actions send.
    outbox: Outbox,
}

impl AsMut<Outbox> for Bulb {
    fn as_mut(&mut self) -> &mut Outbox {
        &mut self.outbox
    }
}

impl lamp::Lamp for Bulb {
    fn is_level_valid(&self, msg: &SetLampLevel) -> bool {
        msg.level <= 100
    }

    fn send_report_lamp_level(&mut self, transport_data: &Receive) {
        let report = ReportLampLevel { level: self.level };
        self.outbox.reply(transport_data, &report);
    }

    fn set_level(&mut self, msg: &SetLampLevel) {
        self.level = msg.level;
    }
}

/// The lamp as an AS-4 component `id`: the Core services and the lamp.
pub fn component(id: As4Id) -> As4Component<()> {
    As4Component::new(id, CoreConfig::named("vendor-lamp"))
        .with_service(lamp::Hosted::new(Bulb::default()))
}

/// Serves the lamp component `id` on `socket` (AS5669A over UDP, beside an empty RA 3.3
/// node on the same socket) until `stop` is set.
pub fn serve(socket: &UdpSocket, id: As4Id, stop: &AtomicBool) -> std::io::Result<()> {
    // The RA 3.3 node shares the socket and hosts nothing: it only answers RA 3.3 peers
    // that find the address.
    let ra33: Node = Node::new(NodeConfig::default(), Instant::now());
    let as4: As4Node<(), SocketAddr> = As4Node::new(()).with_component(component(id));
    let mut mux = As4Mux::new(ra33, as4, As4Config::default());
    jaus::net::udp::run_on(&mut mux, socket, stop, None, |_| {})
}
