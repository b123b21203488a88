//! # jaus-client — a JAUS client's place in a system
//!
//! What every client of a JAUS system needs, whatever it is written in: the `jaus` CLI,
//! the conformance tester and the Python package all speak through it.
//!
//! * [`place`]: the client is a real component (a System Commander at `--me`), never a
//!   second voice for a node manager it is not: it **joins** the node it talks to
//!   when `--me` is on that node ([`jaus::net::Attached`]: no node manager of its own),
//!   or runs **a node of its own** beside the peers; control of a component is kept by
//!   the one [`jaus::stock::commander::ControlKeeper`];
//! * [`port`]: the client's socket over UDP, JTCP or JSerial ([`Carrier`]);
//! * [`session`]: an operator's script of sends, queries and watches ([`Script`]),
//!   each command's effect confirmed ([`confirm`]);
//! * [`tree`]: the system tree as text and JSON;
//! * [`catalogue`] and [`describe`]: the messages spoken, the SDK's and a vendor's
//!   overlays, by name;
//! * [`capture`] and [`traffic`]: pcap/pcapng captures written, read, decoded to JSON
//!   lines and replayed;
//! * [`as4_link`]: an AS-4 client over AS5669A for definitions loaded at run time, on
//!   [`as4_socket`]'s socket (an AS-4 client on the SDK's one I/O loop).
//!
//! # Sockets
//!
//! JUDP peers such as OpenJAUS send every reply to **port 3794 of the sender's IP
//! address**. The default bind is therefore `auto`: port 3794 on a loopback address of
//! its own (127.0.0.2, .3, ...) when the peers are on loopback, else `0.0.0.0:3794`
//! ([`bind_socket`]).

pub mod as4_link;
pub mod as4_socket;
pub mod capture;
pub mod catalogue;
pub mod confirm;
pub mod describe;
mod output;
pub mod place;
pub mod port;
pub mod session;
pub mod traffic;
pub mod tree;

pub use catalogue::parse_message;
pub use place::{default_me, flush, flush_seen, Client, Commander, Link, Mode, Tool};
pub use port::{bind_socket, carrier_of, silence_hint, Carrier, Port, SERIAL_FAR_END};
pub use session::{Outcome, Script};
pub use tree::{tree_json, TreePrinter};
