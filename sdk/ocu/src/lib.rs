//! The operator console in the browser (`jaus ocu`): Part 1's System Commander with its
//! human-computer interface.
//!
//! A node of its own hosts a System Commander whose operator logic is
//! [`jaus::stock::commander::Station`] (the console adds no JAUS logic of its own); a local
//! web server (127.0.0.1 by default) serves one page, embedded in the binary, that shows
//! the live system tree, each vehicle on a local map with its trail, its velocity, state
//! and emergency, and a log of every message sent and received, and lets the operator
//! take and release control with an authority, stop and clear an emergency, click
//! waypoints for a waypoint driver or path segments, and spool, run, pause and abort a
//! mission.
//!
//! | module | job |
//! |---|---|
//! | [`console`] | the node thread: component, system tree → station, publishing |
//! | [`protocol`] | the page's JSON commands → station commands, with field-naming errors |
//! | [`log`] | the message log (decoded JSON of what was sent and received) |
//! | [`server`] | HTTP and WebSocket (axum) |
//! | [`guard`] | who may use the server: Host, Origin, the run's key, JSON commands |
//! | [`map`] | the map's optional background: a georeferenced image, local tiles |
//! | [`shared`] | what the node thread and the server share (commands, views, log) |

pub mod console;
pub mod guard;
pub mod log;
pub mod map;
pub mod protocol;
pub mod server;
pub mod shared;

pub use console::{run, Bound, ConsoleError, ConsoleOptions};
pub use map::{BackgroundSource, MapOptions, Placement};
