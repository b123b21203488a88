//! [`StockCommunicator`]: the Communicator's data links, their states and selection,
//! the communications messages, and the bounded per-link queues the subsystem's
//! outgoing packets wait in.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use crate::component::Refused;
use crate::components::communicator as cm;
use crate::link::{DataLink, LinkError};
use crate::messages::*;
use crate::Address;

/// Settings of the Communicator.
#[derive(Debug, Clone)]
pub struct CommunicatorConfig {
    /// A link that is On but has heard nothing from the far side for this long shows
    /// Loss Of Command (as does a link the hardware reports down). Default 3 s (three
    /// of the far communicator's heartbeats).
    pub silence_timeout: Duration,
    /// Most frames waiting per link while the link is busy; more are dropped and
    /// counted ([`LinkStats::dropped_queue_full`]). Default 256.
    pub max_queue: usize,
    /// Most buffers kept for reuse by the queues. Default 64.
    pub max_pool: usize,
    /// Period of the Report Heartbeat Pulse to every subsystem's node manager
    /// (255.255.1.1, docs/wire.md §8.2) that announces this subsystem across the links;
    /// `None`: not sent. Default 1 s.
    pub heartbeat: Option<Duration>,
}

/// The defaults the field documentation states:
///
/// ```
/// use std::time::Duration;
/// let c = jaus::stock::communicator::CommunicatorConfig::default();
/// assert_eq!((c.silence_timeout, c.max_queue), (Duration::from_secs(3), 256));
/// assert_eq!(c.heartbeat, Some(Duration::from_secs(1)));
/// ```
impl Default for CommunicatorConfig {
    fn default() -> Self {
        Self {
            silence_timeout: Duration::from_secs(3),
            max_queue: 256,
            max_pool: 64,
            heartbeat: Some(Duration::from_secs(1)),
        }
    }
}

/// What the Communicator counted on one data link.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LinkStats {
    /// Frames the link took for transmission.
    pub frames_sent: u64,
    /// Bytes of those frames.
    pub bytes_sent: u64,
    /// Frames received from the far side.
    pub frames_received: u64,
    /// Bytes of those frames.
    pub bytes_received: u64,
    /// Dropped: the queue was full (the link busy for too long).
    pub dropped_queue_full: u64,
    /// Dropped: the link was down, in Loss Of Command by the hardware, Off or in
    /// Standby when the frame was to leave.
    pub dropped_link_down: u64,
    /// Dropped: larger than the link carries.
    pub dropped_too_large: u64,
    /// Received while the link was Off or in Standby, and discarded.
    pub discarded_received: u64,
    /// Frames waiting in the queue now.
    pub queued: usize,
}

/// One data link and what the Communicator keeps about it.
#[derive(Debug)]
struct Slot<L> {
    link: L,
    /// The state commanded (Off, On or Standby; Loss Of Command is only reported).
    commanded: DataLinkState,
    /// When something was last heard from the far side (or the link was turned on).
    last_heard: Instant,
    queue: VecDeque<Vec<u8>>,
    stats: LinkStats,
}

/// Why a [`StockCommunicator`] could not be built.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum CommunicatorError {
    /// It needs at least one data link.
    #[error("a communicator needs at least one data link")]
    NoLinks,
    /// Two links have the same id.
    #[error("two data links have id {0}")]
    DuplicateId(u8),
}

/// The Communicator (Part 1 §5.2.1, id 35) over its [`DataLink`]s: every link's state
/// (Off, On, Standby; On shows Loss Of Command when the hardware reports the link down
/// or nothing is heard from the far side for
/// [`CommunicatorConfig::silence_timeout`]), the selected link that the subsystem's
/// outgoing traffic takes, the communications messages (Set Data Link Status sets the
/// selected link's state, Set Selected Data Link State a given link's, Set Data Link
/// Select selects one; unknown link ids and states other than Off, On and Standby are
/// refused), a bounded queue per link, and counters per link.
///
/// Hosted in a node by [`CommunicatorEndpoint`](super::CommunicatorEndpoint), which makes it
/// the node's gateway to other subsystems.
#[derive(Debug)]
pub struct StockCommunicator<L> {
    links: Vec<Slot<L>>,
    selected: usize,
    config: CommunicatorConfig,
    pool: Vec<Vec<u8>>,
    next_heartbeat: Option<Instant>,
    /// The link `receive` asks first (the links take turns).
    next_rx: usize,
    /// When the queues were last offered to the links, and when the links were last
    /// read to the end: a link's wake-up time not after these is not asked for again
    /// (a link that keeps giving a past time cannot make its host spin).
    serviced_at: Option<Instant>,
    drained_at: Option<Instant>,
}

impl<L: DataLink> StockCommunicator<L> {
    /// Over `links` (at least one, distinct ids), all On from `now`, the first
    /// selected.
    pub fn new(
        links: Vec<L>,
        config: CommunicatorConfig,
        now: Instant,
    ) -> Result<Self, CommunicatorError> {
        if links.is_empty() {
            return Err(CommunicatorError::NoLinks);
        }
        for (i, l) in links.iter().enumerate() {
            if links[..i].iter().any(|o| o.id() == l.id()) {
                return Err(CommunicatorError::DuplicateId(l.id()));
            }
        }
        Ok(Self {
            links: links
                .into_iter()
                .map(|link| Slot {
                    link,
                    commanded: DataLinkState::On,
                    last_heard: now,
                    queue: VecDeque::new(),
                    stats: LinkStats::default(),
                })
                .collect(),
            selected: 0,
            config,
            pool: Vec::new(),
            next_heartbeat: None,
            next_rx: 0,
            serviced_at: None,
            drained_at: None,
        })
    }

    /// The settings.
    pub fn config(&self) -> &CommunicatorConfig {
        &self.config
    }

    /// The ids of the links, in the order given.
    pub fn link_ids(&self) -> impl Iterator<Item = u8> + '_ {
        self.links.iter().map(|s| s.link.id())
    }

    /// The selected link's id.
    pub fn selected(&self) -> u8 {
        self.links.get(self.selected).map_or(0, |s| s.link.id())
    }

    /// The state of link `id` as Report Data Link Status gives it at `now`.
    pub fn link_state(&self, id: u8, now: Instant) -> Option<DataLinkState> {
        let s = self.links.iter().find(|s| s.link.id() == id)?;
        Some(self.reported(s, now))
    }

    /// The counters of link `id`.
    pub fn link_stats(&self, id: u8) -> Option<LinkStats> {
        self.links
            .iter()
            .find(|s| s.link.id() == id)
            .map(Self::stats_of)
    }

    /// The link `id` (to read the hardware's own state).
    pub fn link(&self, id: u8) -> Option<&L> {
        self.links
            .iter()
            .find(|s| s.link.id() == id)
            .map(|s| &s.link)
    }

    /// The link `id`, mutably.
    pub fn link_mut(&mut self, id: u8) -> Option<&mut L> {
        self.links
            .iter_mut()
            .find(|s| s.link.id() == id)
            .map(|s| &mut s.link)
    }

    /// Selects link `id` (what Set Data Link Select does); false if there is none.
    pub fn select(&mut self, id: u8) -> bool {
        match self.index(id) {
            Some(i) => {
                self.selected = i;
                true
            }
            None => false,
        }
    }

    /// Commands link `id` to `state` at `now` (what Set Selected Data Link State does):
    /// Off, On or Standby.
    pub fn set_state(&mut self, id: u8, state: DataLinkState, now: Instant) -> Result<(), Refused> {
        let i = self
            .index(id)
            .ok_or_else(|| self.unknown_link("Set Selected Data Link State", id))?;
        self.command(i, state, now, "Set Selected Data Link State")
    }

    fn stats_of(s: &Slot<L>) -> LinkStats {
        LinkStats {
            queued: s.queue.len(),
            ..s.stats
        }
    }

    fn index(&self, id: u8) -> Option<usize> {
        self.links.iter().position(|s| s.link.id() == id)
    }

    fn unknown_link(&self, message: &str, id: u8) -> Refused {
        let ids: Vec<String> = self.link_ids().map(|i| i.to_string()).collect();
        Refused::Invalid(format!(
            "{message}: data_link_id {id} is not a data link of this communicator (its links: {})",
            ids.join(", ")
        ))
    }

    fn reported(&self, s: &Slot<L>, now: Instant) -> DataLinkState {
        match s.commanded {
            DataLinkState::On
                if !s.link.is_up(now)
                    || now.saturating_duration_since(s.last_heard)
                        >= self.config.silence_timeout =>
            {
                DataLinkState::LossOfCommand
            }
            c => c,
        }
    }

    fn command(
        &mut self,
        i: usize,
        state: DataLinkState,
        now: Instant,
        message: &str,
    ) -> Result<(), Refused> {
        if !matches!(
            state,
            DataLinkState::Off | DataLinkState::On | DataLinkState::Standby
        ) {
            return Err(Refused::Invalid(format!(
                "{message}: state {state:?} cannot be commanded (Off, On or Standby; Loss Of Command is what a link shows when it loses the far side)"
            )));
        }
        let Some(s) = self.links.get_mut(i) else {
            return Err(Refused::Invalid(format!("{message}: no such data link")));
        };
        if s.commanded == state {
            return Ok(());
        }
        tracing::info!(link = s.link.id(), from = ?s.commanded, to = ?state, "{message}: data link state changed");
        if state == DataLinkState::On {
            // Give the far side a full timeout to be heard again.
            s.last_heard = now;
        } else {
            let n = s.queue.len() as u64;
            s.stats.dropped_link_down += n;
            self.pool
                .extend(s.queue.drain(..).take(self.config.max_pool));
            self.pool.truncate(self.config.max_pool);
        }
        s.commanded = state;
        s.link.set_powered(now, state == DataLinkState::On);
        Ok(())
    }

    /// A packet leaving the subsystem at `now`: queued on the selected link and sent as
    /// soon as the link takes it; dropped and counted when the link is not usable or
    /// its queue is full.
    pub fn forward(&mut self, now: Instant, packet: &[u8]) {
        let i = self.selected;
        let max_queue = self.config.max_queue;
        let mut buf = self.pool.pop().unwrap_or_default();
        let Some(s) = self.links.get_mut(i) else {
            return;
        };
        if s.commanded != DataLinkState::On || !s.link.is_up(now) {
            s.stats.dropped_link_down += 1;
            self.pool.push(buf);
            return;
        }
        if s.queue.len() >= max_queue {
            s.stats.dropped_queue_full += 1;
            self.pool.push(buf);
            return;
        }
        buf.clear();
        buf.extend_from_slice(packet);
        s.queue.push_back(buf);
        self.service_link(i, now);
    }

    /// Moves queued frames onto the links as far as they take them (call when a link's
    /// [`DataLink::poll_timeout`] is due).
    pub fn service(&mut self, now: Instant) {
        for i in 0..self.links.len() {
            self.service_link(i, now);
        }
        self.serviced_at = Some(now);
    }

    fn service_link(&mut self, i: usize, now: Instant) {
        let Some(s) = self.links.get_mut(i) else {
            return;
        };
        while let Some(frame) = s.queue.front() {
            match s.link.send(now, frame) {
                Ok(()) => {
                    s.stats.frames_sent += 1;
                    s.stats.bytes_sent += frame.len() as u64;
                }
                Err(LinkError::Busy) => return,
                Err(LinkError::Down) => s.stats.dropped_link_down += 1,
                Err(e @ LinkError::TooLarge { .. }) => {
                    s.stats.dropped_too_large += 1;
                    tracing::warn!(link = s.link.id(), "frame dropped: {e}");
                }
            }
            if let Some(done) = s.queue.pop_front() {
                if self.pool.len() < self.config.max_pool {
                    self.pool.push(done);
                }
            }
        }
    }

    /// The next packet received from another subsystem by `now` on a link that is On,
    /// written into `buf`; `Err(buf)` when there is none. Frames arriving on links Off or
    /// in Standby are discarded and counted.
    pub fn receive(&mut self, now: Instant, mut buf: Vec<u8>) -> Result<Vec<u8>, Vec<u8>> {
        let n = self.links.len();
        for k in 0..n {
            let i = (self.next_rx + k) % n;
            let Some(s) = self.links.get_mut(i) else {
                continue;
            };
            while s.link.recv(now, &mut buf) {
                if s.commanded != DataLinkState::On {
                    s.stats.discarded_received += 1;
                    continue;
                }
                s.stats.frames_received += 1;
                s.stats.bytes_received += buf.len() as u64;
                s.last_heard = now;
                self.next_rx = (i + 1) % n;
                return Ok(buf);
            }
        }
        self.drained_at = Some(now);
        Err(buf)
    }

    /// When a link next wants attention: a frame arriving, or room for the frames that
    /// wait for it.
    pub fn poll_timeout(&self) -> Option<Instant> {
        self.links
            .iter()
            .flat_map(|s| {
                let ready = (!s.queue.is_empty())
                    .then(|| s.link.ready_at())
                    .flatten()
                    .filter(|t| self.serviced_at.is_none_or(|a| *t > a));
                let arrival = s
                    .link
                    .poll_timeout()
                    .filter(|t| self.drained_at.is_none_or(|a| *t > a));
                [arrival, ready]
            })
            .flatten()
            .min()
    }
}

impl<L: DataLink> cm::Communicator for StockCommunicator<L> {
    fn tick(&mut self, ctx: &mut cm::Ctx<'_>) {
        let Some(period) = self.config.heartbeat else {
            return;
        };
        let now = ctx.now();
        if self.next_heartbeat.is_some_and(|t| now < t) {
            return;
        }
        self.next_heartbeat = Some(now + period);
        // Announce the subsystem to every other subsystem's node manager.
        ctx.send(Address::new(255, 255, 1, 1), ReportHeartbeatPulse {});
    }

    fn on_set_data_link_status(
        &mut self,
        ctx: &mut cm::Ctx<'_>,
        msg: &SetDataLinkStatus,
    ) -> Result<(), Refused> {
        let i = self.selected;
        self.command(i, msg.state, ctx.now(), "Set Data Link Status")
    }

    fn on_set_data_link_select(
        &mut self,
        _ctx: &mut cm::Ctx<'_>,
        msg: &SetDataLinkSelect,
    ) -> Result<(), Refused> {
        if self.select(msg.data_link_id) {
            tracing::info!(
                link = msg.data_link_id,
                "Set Data Link Select: data link selected"
            );
            Ok(())
        } else {
            Err(self.unknown_link("Set Data Link Select", msg.data_link_id))
        }
    }

    fn on_set_selected_data_link_state(
        &mut self,
        ctx: &mut cm::Ctx<'_>,
        msg: &SetSelectedDataLinkState,
    ) -> Result<(), Refused> {
        self.set_state(msg.data_link_id, msg.state, ctx.now())
    }

    fn on_query_data_link_status(
        &mut self,
        ctx: &mut cm::Ctx<'_>,
        msg: &QueryDataLinkStatus,
    ) -> Result<ReportDataLinkStatus, Refused> {
        let state = self
            .link_state(msg.data_link_id, ctx.now())
            .ok_or_else(|| self.unknown_link("Query Data Link Status", msg.data_link_id))?;
        Ok(ReportDataLinkStatus {
            data_link_id: msg.data_link_id,
            data_link_state: state,
        })
    }

    fn on_query_selected_data_link_status(
        &mut self,
        _ctx: &mut cm::Ctx<'_>,
        _msg: &QuerySelectedDataLinkStatus,
    ) -> Result<ReportSelectedDataLinkStatus, Refused> {
        Ok(ReportSelectedDataLinkStatus {
            data_link_id: self.selected(),
        })
    }
}
