//! The Mission Spooler (Part 1 §5.6.2, component 36).
//!
//! A mission is an N-ary tree of tasks, each holding JAUS messages and child tasks; the
//! spooler keeps missions by id and, when one runs, parcels its messages out in tree
//! order (a task's messages, then its children, depth first). Rules:
//!
//! * It never sends past a **blocking** message until a Report Mission Status "finished"
//!   for that message's uid arrives.
//! * Delivery to each destination is chosen once, by asking it Query Spooling Preference
//!   and Query Services: a component that answers the preference gets Spool Mission
//!   with up to its message-count limit per batch; one that answers only its services
//!   and lists Spool Mission gets Spool Mission one message at a time (Part 1's fallback
//!   when the preference is not answered); one that lists no Spool Mission, or answers
//!   neither within [`SpoolerConfig::probe_timeout`], gets the raw messages one at a time.
//! * Messages for another subsystem whose Mission Spooler is known
//!   ([`SpoolerConfig::remote_spoolers`]) go to that spooler as Spool Mission + Run
//!   Mission (Part 1 Figure 5-31); its "finished" reports come back here.
//! * Every "finished" (message or mission) is reported to the component that spooled the
//!   mission.
//! * Control of a destination is requested (with the spooler's authority) before its
//!   first message and released once no mission has a message for it left to send or a
//!   blocking message it is still executing (a driver stops when it loses control), so
//!   the component's usual controller gets it back.
//! * With the node making commands arrive (`jaus::net::NodeConfig::reliable`), each
//!   delivery to another node is acknowledged, resent, or its failure acted on: a
//!   refusal pauses the mission with a reason ([`StockMissionSpooler::pause_reason`]), a
//!   delivery given up is sent again or pauses the mission (`outcomes`,
//!   [`DeliveryStats`]).
//! * Pause and abort apply to a whole mission (task 0) or one task; Remove and Replace
//!   Messages change only messages not yet sent.
//!
//! Only one mission runs at a time; the component modes follow it (Idle, Running,
//! Paused).
//!
//! The spooler's parts, one file each: the mission model (`mission`: the task tree
//! flattened into messages and their states), delivery (`delivery`: how and when each
//! destination gets its messages, control of destinations), the component (`component`:
//! the Mission Spooler's messages) and the builders other modules use to make missions
//! ([`command`], [`leaf_task`], [`mission_of`]), and the persistence seam (`journal`:
//! [`MissionJournal`], every accepted change committed; [`StockMissionSpooler::restore`]
//! after a restart).

mod build;
mod component;
mod delivery;
mod journal;
mod mission;
mod outcomes;

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::time::{Duration, Instant};

use crate::component::Refused;
use crate::components::mission_spooler::Ctx;
use crate::messages::*;
use crate::Address;
use mission::{wire_status, Mission};

pub use build::{command, leaf_task, mission_of};
pub use delivery::Delivery;
pub use journal::{JournalError, MissionJournal, MissionMessage, MissionRecord};
pub use mission::{ItemState, MissionState};
pub use outcomes::{DeliveryStats, MAX_AWAITING, OUTCOME_TIMEOUT};

/// Settings of the spooler.
#[derive(Debug, Clone)]
pub struct SpoolerConfig {
    /// How long to wait for a destination to answer Query Spooling Preference / Query
    /// Services.
    pub probe_timeout: Duration,
    /// How often control of a destination is asked for again while refused.
    pub control_retry: Duration,
    /// Mission Spoolers of other subsystems.
    pub remote_spoolers: Vec<Address>,
    /// Most missions stored.
    pub max_missions: usize,
    /// Most messages stored over all missions.
    pub max_messages: usize,
    /// Deepest task tree accepted.
    pub max_depth: usize,
    /// The message-count limit this spooler reports in Report Spooling Preference.
    pub preference: i32,
    /// Most messages sent per tick (keeps the component's outgoing queue from
    /// overflowing on long non-blocking stretches).
    pub max_per_tick: usize,
    /// Times a delivery to a destination that acknowledges is sent in all (the node
    /// resends each one until it gives up) before its mission is paused. Default 3.
    pub max_deliveries: u32,
}

impl Default for SpoolerConfig {
    fn default() -> Self {
        Self {
            probe_timeout: Duration::from_secs(1),
            control_retry: Duration::from_secs(1),
            remote_spoolers: Vec::new(),
            max_missions: 64,
            max_messages: 1_000_000,
            max_depth: 64,
            preference: 1000,
            max_per_tick: 128,
            max_deliveries: 3,
        }
    }
}

/// The Mission Spooler.
#[derive(Debug)]
pub struct StockMissionSpooler {
    config: SpoolerConfig,
    missions: BTreeMap<u16, Mission>,
    running: Option<u16>,
    delivery: HashMap<Address, Delivery>,
    preferences: HashMap<Address, i32>,
    spool_capable: HashMap<Address, bool>,
    control_asked: HashMap<Address, (Instant, Instant)>,
    refused_control: Vec<Address>,
    stored: usize,
    sent: u64,
    journal: Option<Box<dyn MissionJournal>>,
    /// Missions changed since the last commit.
    dirty: BTreeSet<u16>,
    /// Missions paused by a restart (Resume or Run runs them again).
    restored: BTreeSet<u16>,
    journal_failures: u64,
    /// Deliveries to other nodes waiting for their outcome.
    outcomes: outcomes::Outcomes,
}

impl StockMissionSpooler {
    /// With `config`.
    pub fn new(config: SpoolerConfig) -> Self {
        Self {
            config,
            missions: BTreeMap::new(),
            running: None,
            delivery: HashMap::new(),
            preferences: HashMap::new(),
            spool_capable: HashMap::new(),
            control_asked: HashMap::new(),
            refused_control: Vec::new(),
            stored: 0,
            sent: 0,
            journal: None,
            dirty: BTreeSet::new(),
            restored: BTreeSet::new(),
            journal_failures: 0,
            outcomes: outcomes::Outcomes::default(),
        }
    }

    /// Number of missions stored.
    pub fn missions(&self) -> usize {
        self.missions.len()
    }

    /// The delivery chosen for `dest`, if any.
    pub fn delivery(&self, dest: Address) -> Option<Delivery> {
        self.delivery.get(&dest).copied()
    }

    /// Messages sent to destinations so far.
    pub fn sent(&self) -> u64 {
        self.sent
    }

    /// The status of mission `id`: (status, messages finished or sent, total).
    pub fn status(&self, id: u16) -> Option<(MissionStatus, usize, usize)> {
        let m = self.missions.get(&id)?;
        let done = m
            .items
            .iter()
            .filter(|i| matches!(i.state, ItemState::Sent | ItemState::Finished))
            .count();
        Some((wire_status(m.state), done, m.items.len()))
    }

    fn mission(&mut self, id: u16) -> Result<&mut Mission, Refused> {
        self.missions
            .get_mut(&id)
            .ok_or_else(|| Refused::Invalid(format!("no mission {id}")))
    }

    fn report(
        ctx: &mut Ctx<'_>,
        to: Address,
        kind: MissionStatusType,
        status: MissionStatus,
        mission: u16,
        task: u16,
        uid: u16,
    ) {
        ctx.send(
            to,
            ReportMissionStatus {
                status_type: kind,
                status,
                secondary_status: MissionSecondaryStatus::NoError,
                mission_id: mission,
                task_id: task,
                task_msg_id: uid,
            },
        );
    }
}
