//! `jaus conform --as4`: the judge's side of the IOP challenge scenario (the public
//! IGVC JAUS / IOP rules) as conformance checks on an SAE AS-4 vehicle, over AS5669A.
//!
//! The judge's client (42.1.1 by default) finds the vehicle by Query Identification,
//! reads its services, takes control, drives its Management states, reads its velocity
//! state and local pose, loads a short list of local waypoints, has it driven (only
//! with [`As4Options::allow_motion`]) and, last, gives it back as it found it
//! (Standby, then Release Control), asking Query Identification every 5 s all along.
//! It shuts the component down instead only when asked ([`As4Options::shutdown`]):
//! Shutdown cannot be undone, the component then refuses control until its node
//! restarts. Each step is a [`Check`] with an id, the rule it cites and its
//! evidence (every message sent and received), reported through the same summary,
//! JSON, JUnit and HTML as the RA 3.3 checks ([`crate::report`]).
//!
//! * [`session`]: the seam ([`As4Session`]); [`MemoryAs4Session`] runs a vehicle in
//!   the same process on a virtual clock, [`udp::UdpAs4Session`] talks to a real one;
//! * [`run_as4`]: runs the scenario and returns a [`RunReport`].
//!
//! ```
//! use std::time::Instant;
//! use jaus_conform::as4::{run_as4, As4Options, MemoryAs4Session};
//! use jaus::net::Node;
//!
//! // An RA 3.3 node has no AS-4 side: nothing answers the judge.
//! let t0 = Instant::now();
//! let node = Node::new(Default::default(), t0);
//! let mut session = MemoryAs4Session::new(node, t0);
//! let run = run_as4(&mut session, &As4Options::default());
//! assert!(!run.passed());
//! ```

mod checks;
mod mission;
pub mod planned;
mod sensors;
pub mod session;
mod talk;
pub mod udp;

use std::net::SocketAddr;
use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;

pub use session::{Arrival, As4Host, As4Session, MemoryAs4Session};

use crate::check::{Check, Kind, Level, Rule};
use crate::engine::{check_component, inconclusive, Evidence, Found, RunReport, Subject, Voice};
use crate::selection::Selection;
use talk::Judge;

/// How the scenario runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct As4Options {
    /// The judge's id (the IOP challenge's 42.1.1).
    pub me: As4Id,
    /// The component under test; `None`: whichever answers Query Identification (sent
    /// as a broadcast), then the one whose Report Services lists the Local Waypoint
    /// List Driver.
    pub target: Option<As4Id>,
    /// The vehicle's socket, for the report (and the IOP rule that a team's subsystem
    /// id is the last octet of its IP address, noted when it does not hold).
    pub vehicle: Option<SocketAddr>,
    /// The wait for each answer.
    pub wait: Duration,
    /// The wait after a command before its effect is read.
    pub settle: Duration,
    /// Run Execute List (the vehicle moves) and the checks that need it running.
    pub allow_motion: bool,
    /// The longest wait for the list to be driven to its end.
    pub mission_timeout: Duration,
    /// The interval of the background Query Identification.
    pub periodic: Duration,
    /// Background Query Identifications sent at least (the run waits for them).
    pub periodic_min: u32,
    /// The authority of the judge's Request Control.
    pub authority: u8,
    /// The speed of Execute List, m/s.
    pub speed: f64,
    /// The pose Set Local Pose gives the vehicle: x, y (m), yaw (rad).
    pub pose: (f64, f64, f64),
    /// How far the reported position may be from the one set (m).
    pub pose_tolerance: f64,
    /// Send Shutdown at the end (the scenario's last step, `as4.management.shutdown`).
    /// Off by default: Shutdown cannot be undone, so the run ends with
    /// `as4.control.release` instead, leaving the component as it was found.
    pub shutdown: bool,
}

impl Default for As4Options {
    /// The IOP challenge's: judge 42.1.1, Query Identification every 5 s, 1 s for
    /// answers, 200 ms to settle, 1 m/s, a minute for the list, no motion and no
    /// Shutdown unless asked.
    fn default() -> Self {
        As4Options {
            me: As4Id::new(42, 1, 1),
            target: None,
            vehicle: None,
            wait: Duration::from_secs(1),
            settle: Duration::from_millis(200),
            allow_motion: false,
            mission_timeout: Duration::from_secs(60),
            periodic: Duration::from_secs(5),
            periodic_min: 2,
            authority: 255,
            speed: 1.0,
            pose: (3.0, -2.0, 0.5),
            pose_tolerance: 0.5,
            shutdown: false,
        }
    }
}

/// The rules the AS-4 checks cite, in this tool's words.
pub mod rules {
    use crate::check::Rule;

    /// Discovery by Query Identification.
    pub const IDENTIFICATION: Rule = Rule {
        id: "as4.identification",
        source: "AS5710A Discovery; IOP challenge (Discovery)",
        text: "A component answers Query Identification with Report Identification; the judge takes the id that answers as the vehicle's.",
    };
    /// The periodic Query Identification.
    pub const PERIODIC: Rule = Rule {
        id: "as4.periodic",
        source: "IOP challenge (Discovery)",
        text: "The judge sends Query Identification every 5 s through the run; the vehicle answers every one within the answer wait.",
    };
    /// Services listed.
    pub const SERVICES: Rule = Rule {
        id: "as4.services",
        source: "AS5710A Discovery; IOP challenge (Capabilities)",
        text: "Report Services lists the services the scenario uses: Discovery, Access Control, Management, Velocity State Sensor, Local Pose Sensor, Local Waypoint List Driver and List Manager (core or mobility URI), on one component.",
    };
    /// Access Control.
    pub const ACCESS: Rule = Rule {
        id: "as4.access-control",
        source: "AS5710A Access Control",
        text: "Query Control is answered; Request Control while nobody else holds control is confirmed with Control Accepted, Report Control then names the requester, and control stays with it while it renews the request.",
    };
    /// Release of control, and the judge leaving the component as found.
    pub const RELEASE: Rule = Rule {
        id: "as4.release",
        source: "AS5710A Access Control; jaus conform (leave the target as found)",
        text: "Release Control from the client in control ends its control: the component answers with Reject Control (Control Released) and Report Control no longer names that client. The judge first puts the component back in the state it found it in, and says what it could not restore.",
    };
    /// Management.
    pub const MANAGEMENT: Rule = Rule {
        id: "as4.management",
        source: "AS5710A Management",
        text: "Query Status is answered; from the client in control, Resume takes the component to Ready, Standby to Standby and Shutdown to Shutdown (after which it may stop answering).",
    };
    /// Velocity State Sensor.
    pub const VELOCITY: Rule = Rule {
        id: "as4.velocity",
        source: "AS6009 Velocity State Sensor; IOP challenge (Velocity)",
        text: "Report Velocity State carries exactly the fields the query's presence vector asks for (0x0140: yaw rate and time stamp).",
    };
    /// Local Pose Sensor.
    pub const POSE: Rule = Rule {
        id: "as4.pose",
        source: "AS6009 Local Pose Sensor; IOP challenge (Position)",
        text: "Set Local Pose (presence vector 0x43: x, y, yaw) from the client in control sets the local pose; Report Local Pose carries exactly the fields asked for (0x0103: x, y, time stamp) and reports the position set.",
    };
    /// List Manager.
    pub const LIST: Rule = Rule {
        id: "as4.list-manager",
        source: "AS5710A List Manager; IOP challenge (Waypoints)",
        text: "Set Element is confirmed with its request id; Query Element List gives the elements' UIDs in list order and Query Element Count their number.",
    };
    /// Local Waypoint List Driver.
    pub const DRIVER: Rule = Rule {
        id: "as4.waypoint-list-driver",
        source: "AS6009 Local Waypoint List Driver; IOP challenge (Waypoints)",
        text: "Execute List from the client in control, the component Ready, drives the list from the element given at the speed given: Query Active Element names the element being driven (0 once the list is done), Query Travel Speed the speed, Query Local Waypoint the active element's waypoint.",
    };
}

/// The scenario's checks in the order they run: id, title, rule, level.
#[rustfmt::skip]
pub(crate) const CHECKS: &[(&str, &str, Rule, Level)] = {
    use rules::*;
    use Level::{Advisory, Required};
    &[
        ("as4.discovery.identification", "Query Identification finds the vehicle", IDENTIFICATION, Required),
        ("as4.discovery.services", "Report Services lists the scenario's services", SERVICES, Required),
        ("as4.control.query", "Query Control is answered", ACCESS, Required),
        ("as4.control.request", "Request Control is confirmed; Report Control names the judge", ACCESS, Required),
        ("as4.management.status", "Query Status is answered", MANAGEMENT, Required),
        ("as4.management.resume", "Resume takes the component to Ready", MANAGEMENT, Required),
        ("as4.management.standby", "Standby takes the component to Standby", MANAGEMENT, Required),
        ("as4.velocity.pv0140", "Report Velocity State carries exactly yaw rate and time stamp (0x0140)", VELOCITY, Required),
        ("as4.pose.set_local", "Set Local Pose (0x43) is read back", POSE, Required),
        ("as4.pose.report_local", "Report Local Pose (0x0103) reports the position set", POSE, Required),
        ("as4.waypoints.set_element", "Set Element of local waypoints is confirmed with its request id", LIST, Required),
        ("as4.waypoints.element_list", "Query Element List gives the UIDs in order", LIST, Required),
        ("as4.waypoints.element_count", "Query Element Count gives their number", LIST, Required),
        ("as4.waypoints.execute", "Execute List starts the list at its first element", DRIVER, Required),
        ("as4.waypoints.travel_speed", "Query Travel Speed gives the speed executed", DRIVER, Required),
        ("as4.waypoints.local_waypoint", "Query Local Waypoint gives the active waypoint", DRIVER, Required),
        ("as4.waypoints.active_element", "Query Active Element follows the list to its end", DRIVER, Required),
        ("as4.discovery.periodic", "Query Identification every 5 s is answered each time", PERIODIC, Required),
        ("as4.control.kept", "Control stays with the judge while it renews its request", ACCESS, Advisory),
        ("as4.management.shutdown", "Shutdown takes the component to Shutdown", MANAGEMENT, Required),
        ("as4.control.release", "Release Control ends the judge's control; the component is left as found", RELEASE, Required),
    ]
};

/// The check with id `id` (ids not in [`CHECKS`] are advisory, citing the scenario).
fn check(id: &str) -> Check {
    let (title, rule, level) = CHECKS
        .iter()
        .find(|c| c.0 == id)
        .map_or((id, rules::IDENTIFICATION, Level::Advisory), |c| {
            (c.1, c.2, c.3)
        });
    Check {
        id: id.to_string(),
        title: title.to_string(),
        rule,
        level,
        kind: Kind::As4,
    }
}

/// The ids of the checks a run with `opts` reports, in order: the last is
/// `as4.management.shutdown` when [`As4Options::shutdown`] asks for it, else
/// `as4.control.release`.
pub fn check_ids(opts: &As4Options) -> Vec<&'static str> {
    let left_out = if opts.shutdown {
        "as4.control.release"
    } else {
        "as4.management.shutdown"
    };
    CHECKS
        .iter()
        .map(|c| c.0)
        .filter(|id| *id != left_out)
        .collect()
}

/// The IOP scenario as the engine's AS-4 voice: its state between its checks.
pub(super) struct Scenario<'a> {
    j: Judge<'a>,
    /// The ids of the checks not run yet, in order.
    ids: std::vec::IntoIter<&'static str>,
    /// Whom Query Identification reached (the periodic queries ask it).
    discovered: Option<As4Id>,
    identification: Option<String>,
    /// Whether the component under test is known (discovered or given).
    known: bool,
    /// Whether the judge holds control.
    controlled: bool,
    /// Who held control when the judge first asked (`as4.control.query`), if anybody.
    found_controller: Option<As4Id>,
    /// The state first read (`as4.management.status`): the one the run restores.
    found_state: Option<jaus_as4::messages::ComponentState>,
    /// The position set by Set Local Pose, once read back.
    pose_set: bool,
    /// The waypoints loaded: UID, x, y.
    waypoints: Vec<(u16, f64, f64)>,
    /// Whether Set Element was confirmed.
    listed: bool,
    /// How many UIDs Report Element List gave.
    list_len: Option<usize>,
    /// When Execute List started the list, once it did.
    executed: Option<Instant>,
}

impl Voice for Scenario<'_> {
    fn now(&self) -> Instant {
        self.j.now()
    }

    fn evidence(&mut self) -> &mut Evidence {
        &mut self.j.evidence
    }

    fn next_check(&mut self) -> Option<Check> {
        self.ids.next().map(check)
    }

    fn skip(&mut self, check: &Check) -> Option<String> {
        let id = check.id.as_str();
        if !self.known && id != "as4.discovery.identification" {
            return Some("no AS-4 component answered Query Identification (give the vehicle's id to test it anyway)".into());
        }
        if id.starts_with("as4.waypoints.") && !LIST_CHECKS.contains(&id) {
            return self.mission_blocked(id).map(str::to_string);
        }
        None
    }

    /// The scenario is one sequence whose steps prepare the next: it runs whole.
    fn needed(&self, _check: &Check) -> bool {
        true
    }

    fn run(&mut self, check: &Check) -> Found {
        match check.id.as_str() {
            "as4.discovery.identification" => self.identification(),
            "as4.discovery.services" => self.services(),
            "as4.control.query" => self.control_query(),
            "as4.control.request" => self.control_request(),
            "as4.management.status" => self.status_check(),
            "as4.management.resume" => self.resume(),
            "as4.management.standby" => self.standby(),
            "as4.velocity.pv0140" => self.velocity(),
            "as4.pose.set_local" => self.set_local_pose(),
            "as4.pose.report_local" => self.report_local_pose(),
            "as4.waypoints.set_element" => self.set_element(),
            "as4.waypoints.element_list" => self.element_list(),
            "as4.waypoints.element_count" => self.element_count(),
            "as4.waypoints.execute" => self.execute_list(),
            "as4.waypoints.travel_speed" => self.travel_speed(),
            "as4.waypoints.local_waypoint" => self.local_waypoint(),
            "as4.waypoints.active_element" => self.active_element(),
            "as4.discovery.periodic" => self.periodic(),
            "as4.control.kept" => self.control_kept(),
            "as4.management.shutdown" => self.shutdown(),
            "as4.control.release" => self.release_control(),
            other => inconclusive(format!("{other} is not a step of the IOP scenario")),
        }
    }

    fn subject(&self) -> Subject {
        let peer = self.j.peer;
        Subject {
            address: if self.known {
                peer.to_string()
            } else {
                "(not found)".into()
            },
            component_id: peer.component,
            component_type: Some("AS-4 vehicle (IOP scenario)".into()),
            identification: self.identification.clone(),
        }
    }

    fn dropped(&self) -> u64 {
        self.j.dropped()
    }
}

/// The waypoint checks that load the list (the others drive it).
const LIST_CHECKS: [&str; 3] = [
    "as4.waypoints.set_element",
    "as4.waypoints.element_list",
    "as4.waypoints.element_count",
];

/// Runs the IOP scenario through `session` and reports it as one component's checks
/// (the component under test; its address is its AS-4 id).
pub fn run_as4(session: &mut dyn As4Session, opts: &As4Options) -> RunReport {
    run_as4_selected(session, opts, None)
}

/// [`run_as4`] reporting the checks `selection` selects, at its levels
/// ([`crate::profile::run_as4`]).
pub(crate) fn run_as4_selected(
    session: &mut dyn As4Session,
    opts: &As4Options,
    selection: Option<&Selection>,
) -> RunReport {
    let placeholder = opts.target.unwrap_or(talk::BROADCAST);
    let mut s = Scenario {
        j: Judge::new(session, *opts, placeholder),
        ids: check_ids(opts).into_iter(),
        discovered: None,
        identification: None,
        known: opts.target.is_some(),
        controlled: false,
        found_controller: None,
        found_state: None,
        pose_set: false,
        waypoints: Vec::new(),
        listed: false,
        list_len: None,
        executed: None,
    };
    let component = check_component(&mut s, selection);
    RunReport::new(
        "jaus conform --as4",
        opts.vehicle.map(|v| v.to_string()).unwrap_or_default(),
        vec![component],
        s.dropped(),
        selection,
    )
}
