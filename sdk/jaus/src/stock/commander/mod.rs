//! Operator logic for Subsystem and System Commanders (Part 1 §5.2: they coordinate the
//! components of a subsystem or of the system), usable from any component's handlers and
//! sans-IO like the runtime:
//!
//! * [`ControlKeeper`] takes and keeps control of components with the commander's
//!   authority (or one chosen per component), resumes them on gaining control, watches
//!   their core state and says what changed ([`ControlEvent`]).
//! * [`Station`] is an operator station's whole logic over the system tree discovery
//!   builds: per subsystem it finds the pose and velocity sensors, drivers, mission
//!   spooler and world model by their component ids, follows the vehicle's pose and
//!   velocity through service connections, queries every component's status and
//!   controller, the world model's objects and the mission's status, and turns an
//!   operator's [`Command`]s (take or release control, emergency stop and clear,
//!   waypoints, path segments, missions) into JAUS messages after checking them
//!   ([`StationError`]). What it knows is a [`SystemView`] (module [`view`]) that a user
//!   interface draws; the `jaus-ocu` console is one. A `Station` is itself a System
//!   Commander: `system_commander::component(address, station, config, now)`.
//! * [`StockSubsystemCommander`] is a Subsystem Commander core: the subsystem's missions
//!   go through it; it keeps control of the Mission Spooler, hands missions over, passes
//!   the requester's mission commands on, watches the mission and reports its status
//!   back, and deals with lost control and emergencies (module [`subsystem`]).

mod component;
mod keeper;
mod station;
pub mod subsystem;
pub mod view;

pub use keeper::{ControlEvent, ControlKeeper, KeeperConfig};
pub use station::{
    Command, GeoPoint, MissionAction, Station, StationConfig, StationError, TreeInput, MAX_POINTS,
    MAX_RADIUS,
};
pub use subsystem::{StockSubsystemCommander, SubsystemConfig};
pub use view::SystemView;
