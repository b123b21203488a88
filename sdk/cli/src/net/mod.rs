//! The network commands of the `jaus` CLI: `node`, `discover`, the operator's session
//! (`send`, `query`, `watch`), the demo's operator over UDP, and `attach` (stock
//! components as OpenJAUS component processes).
//!
//! # The CLI's place in a system
//!
//! The CLI is a real component (a System Commander at `--me`), never a second voice for
//! a node manager it is not:
//!
//! * when `--me` is on the node it talks to (e.g. `--me 20.1.40.1` with the peer being
//!   node 20.1), it **joins that node** as one of its components through the node's
//!   socket ([`jaus::net::Attached`]): no node manager of its own, heartbeats to the
//!   node's manager, identification and services answered by its runtime;
//! * otherwise it runs a **node of its own** (`--me`'s subsystem and node, its own node
//!   manager) beside the peers.
//!
//! `--mode auto` (the default) decides by asking the peers for the identification of
//! `--me`'s node before anything else: a node that answers as that node is joined.
//!
//! # Sockets
//!
//! JUDP peers such as OpenJAUS send every reply to **port 3794 of the sender's IP
//! address**. The default bind is therefore `auto`: port 3794 on a loopback address of
//! its own (127.0.0.2, .3, ...) when the peers are on loopback, else `0.0.0.0:3794`.

mod attach;
pub mod confirm;
mod demo;
mod links_file;
mod node;
mod output;
mod place;
mod policy_file;
mod port;
mod session;

pub use attach::{attach_openjaus, OjNodeManager};
pub use demo::demo_operator;
pub use links_file::{LinkFile, QuicLinkFile};
pub use node::{node, tree_json, NodeFile, TreePrinter};
pub use place::{
    bind_socket, default_me, flush, flush_seen, silence_hint, Client, Commander, Link, Mode, Tool,
};
pub use policy_file::{PolicyFile, RuleFile};
pub use port::{carrier_of, Carrier, Port, SERIAL_FAR_END};
pub use session::{parse_message, Outcome, Script};
