//! The node manager component (id 1): identification, configuration and subsystem list
//! of its node, heartbeats, the system tree built by discovery ([`SystemTree`];
//! docs/wire.md §8), and its node's configuration told to the node managers that hold
//! it without a subscription (docs/wire.md §8.3).

mod announce;
mod tree;

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

pub use tree::{ComponentInfo, NodeInfo, Subscription, SubsystemInfo, SystemTree};

use crate::codec::Encode;
use crate::component::Refused;
use crate::components::node_manager::{Ctx, NodeManager};
use crate::messages::*;
use crate::{Address, JausMessage};

/// Settings of the node manager.
#[derive(Debug, Clone)]
pub struct ManagerConfig {
    /// Subsystem name (answer to Query Identification, subsystem). Default
    /// `"jaus-rs subsystem"`.
    pub subsystem_name: String,
    /// Node name (answer to Query Identification, node). Default `"jaus-rs node"`.
    pub node_name: String,
    /// Heartbeat period. Default 1 s.
    pub heartbeat: Duration,
    /// A node not heard from for this long is removed. Default 5 s.
    pub node_timeout: Duration,
    /// Where heartbeats go. Default 255.255.1.1 (every node manager of the system).
    pub heartbeat_to: Address,
    /// Every other node's configuration is asked for again at this period, whatever
    /// its events say (an Event lost on the network is repaired within this time).
    /// Default 10 s.
    pub config_refresh: Duration,
    /// A heartbeat arriving after a silence longer than this (the node may have
    /// restarted and forgotten our subscription) makes the manager ask for the node's
    /// configuration and subscribe to it again. Default 2.5 s.
    pub heartbeat_gap: Duration,
    /// An unanswered Create Event is sent again after this long. Default 3 s.
    pub subscribe_retry: Duration,
    /// The node manager of another node that has neither asked for this node's
    /// configuration nor subscribed to it this long after its node was first heard is
    /// sent the configuration as a report (it may hold it from an earlier run of this
    /// node: OpenJAUS subscribes only when it discovers a node), and every change after
    /// that. Default 3 s (external components, heartbeating every second, are back in
    /// the configuration by then).
    pub announce_after: Duration,
}

/// The defaults the field documentation states:
///
/// ```
/// use std::time::Duration;
/// let m = jaus::net::ManagerConfig::default();
/// assert_eq!((m.subsystem_name.as_str(), m.node_name.as_str()), ("jaus-rs subsystem", "jaus-rs node"));
/// assert_eq!((m.heartbeat, m.node_timeout), (Duration::from_secs(1), Duration::from_secs(5)));
/// assert_eq!(m.heartbeat_to, jaus::Address::new(255, 255, 1, 1));
/// assert_eq!((m.config_refresh, m.heartbeat_gap, m.subscribe_retry),
///     (Duration::from_secs(10), Duration::from_millis(2500), Duration::from_secs(3)));
/// assert_eq!(m.announce_after, Duration::from_secs(3));
/// ```
impl Default for ManagerConfig {
    fn default() -> Self {
        Self {
            subsystem_name: "jaus-rs subsystem".into(),
            node_name: "jaus-rs node".into(),
            heartbeat: Duration::from_secs(1),
            node_timeout: Duration::from_secs(5),
            heartbeat_to: Address::new(255, 255, 1, 1),
            config_refresh: Duration::from_secs(10),
            heartbeat_gap: Duration::from_millis(2500),
            subscribe_retry: Duration::from_secs(3),
            announce_after: Duration::from_secs(3),
        }
    }
}

/// The node manager's behaviour: answers for its node and discovers the others.
#[derive(Debug)]
pub struct StockNodeManager {
    config: ManagerConfig,
    me: Address,
    locals: Vec<Address>,
    tree: SystemTree,
    next_heartbeat: Option<Instant>,
    next_requery: Option<Instant>,
    gone: Vec<Address>,
    changes: u64,
    request_id: u8,
    announcer: announce::Announcer,
}

impl StockNodeManager {
    /// For the node manager at `me` (component 1).
    pub fn new(me: Address, config: ManagerConfig) -> Self {
        Self {
            config,
            me,
            // The node manager is a component of its node (OpenJAUS lists it too).
            locals: vec![me],
            tree: SystemTree::default(),
            next_heartbeat: None,
            next_requery: None,
            gone: Vec::new(),
            changes: 0,
            request_id: 0,
            announcer: announce::Announcer::default(),
        }
    }

    /// Registers a local component (the node layer calls this).
    pub fn add_local(&mut self, a: Address) {
        if !self.locals.contains(&a) {
            self.locals.push(a);
            self.locals.sort();
            self.changes += 1;
        }
    }

    /// Unregisters a local component (an external one that timed out).
    pub fn remove_local(&mut self, a: Address) {
        self.locals.retain(|x| *x != a);
        self.changes += 1;
        if let Some(n) = self
            .tree
            .subsystems
            .get_mut(&a.subsystem)
            .and_then(|s| s.nodes.get_mut(&a.node))
        {
            n.components.remove(&(a.component, a.instance));
        }
        self.gone.push(a);
    }

    /// The system tree.
    pub fn tree(&self) -> &SystemTree {
        &self.tree
    }

    /// A counter that moves whenever the tree may have changed (a node or component
    /// added or removed, a name or service list learned): compare it instead of the
    /// tree to know when to show the tree again.
    pub fn tree_version(&self) -> u64 {
        self.changes
    }

    /// Components that disappeared since the last call.
    pub fn take_gone(&mut self) -> Vec<Address> {
        std::mem::take(&mut self.gone)
    }

    fn own_node(&self) -> NodeConfiguration {
        NodeConfiguration {
            node_id: self.me.node,
            components: self
                .locals
                .iter()
                .map(|a| ComponentConfiguration {
                    component_id: a.component,
                    instance_id: a.instance,
                })
                .collect(),
        }
    }

    /// This node's configuration (node level: its components; subsystem level: every
    /// node of the subsystem in the tree), the answer to Query Configuration.
    fn configuration(&self, level: QueryLevel) -> Option<ReportConfiguration> {
        let nodes = match level {
            QueryLevel::Node => vec![self.own_node()],
            QueryLevel::Subsystem => self
                .tree
                .subsystems
                .get(&self.me.subsystem)
                .map(|s| {
                    s.nodes
                        .iter()
                        .map(|(n, info)| NodeConfiguration {
                            node_id: *n,
                            components: info
                                .components
                                .keys()
                                .map(|(c, i)| ComponentConfiguration {
                                    component_id: *c,
                                    instance_id: *i,
                                })
                                .collect(),
                        })
                        .collect()
                })
                .unwrap_or_default(),
            _ => return None,
        };
        Some(ReportConfiguration { nodes })
    }

    /// The node of `a`, if it is in the tree.
    fn known_node_mut(&mut self, a: Address) -> Option<&mut NodeInfo> {
        self.tree
            .subsystems
            .get_mut(&a.subsystem)
            .and_then(|s| s.nodes.get_mut(&a.node))
    }

    fn node_mut(&mut self, ss: u8, node: u8, now: Instant) -> &mut NodeInfo {
        self.tree
            .subsystems
            .entry(ss)
            .or_default()
            .nodes
            .entry(node)
            .or_insert_with(|| NodeInfo {
                name: None,
                components: BTreeMap::new(),
                configured: false,
                last_heard: now,
                subscription: Subscription::None,
                config_asked: None,
            })
    }

    /// Asks node `ss.node` for its configuration (node level) and, unless already
    /// subscribed or refused, subscribes to its configuration events (every change),
    /// as OpenJAUS node managers do for each other (docs/wire.md §7.3, §8.3).
    fn track_configuration(&mut self, ctx: &mut Ctx<'_>, ss: u8, node: u8, resubscribe: bool) {
        let now = ctx.now();
        let request_id = self.request_id;
        let retry = self.config.subscribe_retry;
        let info = self.node_mut(ss, node, now);
        info.config_asked = Some(now);
        let subscribe = match info.subscription {
            Subscription::None | Subscription::Rejected => {
                resubscribe || info.subscription == Subscription::None
            }
            Subscription::Requested(at) => {
                resubscribe || now.saturating_duration_since(at) >= retry
            }
            Subscription::Confirmed(_) => resubscribe,
        };
        let old = match info.subscription {
            Subscription::Confirmed(id) if subscribe => Some(id),
            _ => None,
        };
        if subscribe {
            info.subscription = Subscription::Requested(now);
        }
        let nm = Address::new(ss, node, 1, 1);
        ctx.send(
            nm,
            QueryConfiguration {
                query_field: QueryLevel::Node,
            },
        );
        if let Some(id) = old {
            // The node may still hold the old event (it did not restart): end it so that
            // it does not send every change twice. OpenJAUS matches the query's code.
            ctx.send_core(
                nm,
                CancelEvent {
                    request_id,
                    message_code: Some(QueryConfiguration::CODE.0),
                    event_id: Some(id),
                },
            );
        }
        if subscribe {
            self.request_id = self.request_id.wrapping_add(1);
            ctx.send(
                nm,
                CreateEvent {
                    request_id,
                    report_message_code: ReportConfiguration::CODE.0,
                    event_type: EventType::EveryChange,
                    query_message: QueryConfiguration {
                        query_field: QueryLevel::Node,
                    }
                    .to_bytes()
                    .ok(),
                    ..Default::default()
                },
            );
        }
    }

    fn refresh_self(&mut self, now: Instant) {
        let (ss, n) = (self.me.subsystem, self.me.node);
        let name = self.config.node_name.clone();
        let sname = self.config.subsystem_name.clone();
        let locals = self.locals.clone();
        let node = self.node_mut(ss, n, now);
        node.name = Some(name);
        node.configured = true;
        node.last_heard = now;
        for a in locals {
            let c = node
                .components
                .entry((a.component, a.instance))
                .or_default();
            if a.component == 1 {
                c.name = Some("NodeManager".into());
                c.services = Some(vec![0, 1]);
            }
        }
        if let Some(s) = self.tree.subsystems.get_mut(&ss) {
            s.name = Some(sname);
        }
    }
}

impl NodeManager for StockNodeManager {
    fn on_query_identification(
        &mut self,
        _ctx: &mut Ctx<'_>,
        q: &QueryIdentification,
    ) -> Result<ReportIdentification, Refused> {
        let name = match q.query_field {
            QueryLevel::Subsystem => self.config.subsystem_name.clone(),
            QueryLevel::Node => self.config.node_name.clone(),
            QueryLevel::System => return Err(Refused::Unsupported),
            _ => return Err(Refused::Invalid("unknown identification level".into())),
        };
        Ok(ReportIdentification {
            query_type: q.query_field,
            authority: 0,
            identification_type: 0,
            identification: name,
        })
    }

    fn on_query_configuration(
        &mut self,
        ctx: &mut Ctx<'_>,
        q: &QueryConfiguration,
    ) -> Result<ReportConfiguration, Refused> {
        let now = ctx.now();
        self.refresh_self(now);
        let report = self
            .configuration(q.query_field)
            .ok_or(Refused::Unsupported)?;
        if let Some(src) = ctx.source() {
            self.announcer
                .answered(self.me, src, q.query_field, &report, now);
        }
        Ok(report)
    }

    fn on_query_subsystem_list(
        &mut self,
        ctx: &mut Ctx<'_>,
        _q: &QuerySubsystemList,
    ) -> Result<ReportSubsystemList, Refused> {
        self.refresh_self(ctx.now());
        let subsystems = self
            .tree
            .subsystems
            .iter()
            .filter_map(|(ss, s)| {
                s.nodes.keys().next().map(|n| SubsystemEntry {
                    subsystem_id: *ss,
                    node_id: *n,
                    component_id: 1,
                    instance_id: 1,
                })
            })
            .collect();
        Ok(ReportSubsystemList { subsystems })
    }

    fn on_report_heartbeat_pulse(
        &mut self,
        ctx: &mut Ctx<'_>,
        _r: &ReportHeartbeatPulse,
    ) -> Result<(), Refused> {
        let Some(src) = ctx.source() else {
            return Ok(());
        };
        let now = ctx.now();
        if src.subsystem == self.me.subsystem && src.node == self.me.node {
            return Ok(());
        }
        let gap = self.config.heartbeat_gap;
        let node = self.node_mut(src.subsystem, src.node, now);
        let known = node.components.contains_key(&(src.component, src.instance));
        let silent_for = now.saturating_duration_since(node.last_heard);
        node.last_heard = now;
        let (named, configured, asked) = (node.name.is_some(), node.configured, node.config_asked);
        if !configured {
            // Until the node answers, any component that heartbeats stands for it.
            node.components
                .entry((src.component, src.instance))
                .or_default();
        }
        let nm = Address::new(src.subsystem, src.node, 1, 1);
        if !named {
            ctx.send(
                nm,
                QueryIdentification {
                    query_field: QueryLevel::Node,
                },
            );
        }
        let recently =
            asked.is_some_and(|t| now.saturating_duration_since(t) < Duration::from_secs(1));
        if asked.is_some() && silent_for > gap {
            // After a silence the node may have restarted: ask again and subscribe anew.
            tracing::debug!(node = %nm, gap = ?silent_for, "heartbeat after a gap: configuration asked again");
            self.track_configuration(ctx, src.subsystem, src.node, true);
        } else if (!configured || !known) && !recently {
            // Not configured yet, or a component the configuration does not list.
            self.track_configuration(ctx, src.subsystem, src.node, false);
        }
        if src.subsystem != self.me.subsystem
            && self
                .tree
                .subsystems
                .get(&src.subsystem)
                .is_some_and(|s| s.name.is_none())
        {
            ctx.send(
                nm,
                QueryIdentification {
                    query_field: QueryLevel::Subsystem,
                },
            );
        }
        Ok(())
    }

    fn on_report_identification(
        &mut self,
        ctx: &mut Ctx<'_>,
        r: &ReportIdentification,
    ) -> Result<(), Refused> {
        let Some(src) = ctx.source() else {
            return Ok(());
        };
        let now = ctx.now();
        let name = r.identification.trim_end_matches('\0').to_string();
        match r.query_type {
            QueryLevel::Subsystem => {
                self.tree.subsystems.entry(src.subsystem).or_default().name = Some(name);
                self.changes += 1;
            }
            QueryLevel::Node => {
                self.node_mut(src.subsystem, src.node, now).name = Some(name);
                self.changes += 1;
            }
            QueryLevel::Component => {
                let node = self.node_mut(src.subsystem, src.node, now);
                // Only components the configuration lists (a late answer from one that
                // left does not bring it back).
                if let Some(c) = node.components.get_mut(&(src.component, src.instance)) {
                    c.name = Some(name);
                    self.changes += 1;
                }
            }
            _ => {}
        }
        Ok(())
    }

    fn on_report_configuration(
        &mut self,
        ctx: &mut Ctx<'_>,
        r: &ReportConfiguration,
    ) -> Result<(), Refused> {
        let Some(src) = ctx.source() else {
            return Ok(());
        };
        let now = ctx.now();
        for n in &r.nodes {
            if src.subsystem == self.me.subsystem && n.node_id == self.me.node {
                continue;
            }
            let node = self.node_mut(src.subsystem, n.node_id, now);
            node.configured = true;
            let listed: Vec<(u8, u8)> = n
                .components
                .iter()
                .map(|c| (c.component_id, c.instance_id))
                .collect();
            let removed: Vec<(u8, u8)> = node
                .components
                .keys()
                .copied()
                .filter(|k| !listed.contains(k))
                .collect();
            for k in &removed {
                node.components.remove(k);
                tracing::info!(component = %Address::new(src.subsystem, n.node_id, k.0, k.1), "left the configuration of its node");
            }
            if !removed.is_empty() {
                self.changes += 1;
            }
            self.gone.extend(
                removed
                    .iter()
                    .map(|k| Address::new(src.subsystem, n.node_id, k.0, k.1)),
            );
            let node = self.node_mut(src.subsystem, n.node_id, now);
            let mut new = Vec::new();
            for k in listed {
                if let std::collections::btree_map::Entry::Vacant(e) = node.components.entry(k) {
                    e.insert(ComponentInfo::default());
                    new.push(Address::new(src.subsystem, n.node_id, k.0, k.1));
                }
            }
            if !new.is_empty() {
                self.changes += 1;
            }
            for a in new {
                tracing::info!(component = %a, "joined the configuration of its node");
                ctx.send(
                    a,
                    QueryIdentification {
                        query_field: QueryLevel::Component,
                    },
                );
                ctx.send(a, QueryServices {});
            }
        }
        Ok(())
    }

    fn on_report_services(&mut self, ctx: &mut Ctx<'_>, r: &ReportServices) -> Result<(), Refused> {
        let Some(src) = ctx.source() else {
            return Ok(());
        };
        let now = ctx.now();
        if let Some(c) = self
            .node_mut(src.subsystem, src.node, now)
            .components
            .get_mut(&(src.component, src.instance))
        {
            c.services = Some(r.services.iter().map(|s| s.service_type).collect());
            c.inputs = r
                .services
                .iter()
                .flat_map(|s| s.input_commands.iter().map(|m| m.command_code))
                .collect();
            c.outputs = r
                .services
                .iter()
                .flat_map(|s| s.output_commands.iter().map(|m| m.command_code))
                .collect();
            self.changes += 1;
        }
        Ok(())
    }

    fn on_confirm_event_request(
        &mut self,
        ctx: &mut Ctx<'_>,
        m: &ConfirmEventRequest,
    ) -> Result<(), Refused> {
        // Matched by sender and report code: OpenJAUS does not echo the request id.
        let Some(src) = ctx.source() else {
            return Ok(());
        };
        if m.message_code != ReportConfiguration::CODE.0 || (src.component, src.instance) != (1, 1)
        {
            return Ok(());
        }
        if let Some(node) = self.known_node_mut(src) {
            node.subscription = if m.response_code == EventResponseCode::Successful {
                Subscription::Confirmed(m.event_id)
            } else {
                Subscription::Rejected
            };
        }
        Ok(())
    }

    fn on_reject_event_request(
        &mut self,
        ctx: &mut Ctx<'_>,
        m: &RejectEventRequest,
    ) -> Result<(), Refused> {
        let Some(src) = ctx.source() else {
            return Ok(());
        };
        let refresh = self.config.config_refresh;
        if let Some(node) = self.known_node_mut(src) {
            if matches!(node.subscription, Subscription::Requested(_)) {
                tracing::info!(node = %src, reason = ?m.response_code, "configuration events refused; the configuration is re-queried every {refresh:?}");
                node.subscription = Subscription::Rejected;
            }
        }
        Ok(())
    }

    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        let now = ctx.now();
        self.refresh_self(now);
        // Node managers holding this node's configuration without a subscription are
        // told of a change before anything else is sent (a component that just joined
        // is asked its identification below).
        let me = self.me;
        let others: Vec<(u8, u8)> = self
            .tree
            .subsystems
            .iter()
            .flat_map(|(ss, s)| s.nodes.keys().map(move |n| (*ss, *n)))
            .filter(|&(ss, n)| (ss, n) != (me.subsystem, me.node))
            .collect();
        let mut announcer = std::mem::take(&mut self.announcer);
        announcer.run(
            ctx,
            &others,
            |level| self.configuration(level).unwrap_or_default(),
            self.config.announce_after,
        );
        self.announcer = announcer;
        if self.next_heartbeat.is_none_or(|t| now >= t) {
            self.next_heartbeat = Some(now + self.config.heartbeat);
            ctx.send(self.config.heartbeat_to, ReportHeartbeatPulse {});
        }
        // Components (here or elsewhere) not yet identified: ask, again every heartbeat
        // period while unanswered (queries and answers may be lost).
        if self.next_requery.is_none_or(|t| now >= t) {
            self.next_requery = Some(now + self.config.heartbeat);
            let pending: Vec<Address> = self
                .tree
                .components()
                .into_iter()
                .filter(|a| *a != me)
                .filter(|a| {
                    let n = &self.tree.subsystems[&a.subsystem].nodes[&a.node];
                    let c = &n.components[&(a.component, a.instance)];
                    c.name.is_none() || c.services.is_none()
                })
                .collect();
            for a in pending {
                ctx.send(
                    a,
                    QueryIdentification {
                        query_field: QueryLevel::Component,
                    },
                );
                ctx.send(a, QueryServices {});
            }
            // Configuration of every other node: asked again every `config_refresh`
            // (events may be lost), and an unanswered subscription sent again.
            let (refresh, retry) = (self.config.config_refresh, self.config.subscribe_retry);
            let due: Vec<(u8, u8)> = self
                .tree
                .subsystems
                .iter()
                .flat_map(|(ss, s)| s.nodes.iter().map(move |(n, info)| (*ss, *n, info)))
                .filter(|(ss, n, _)| !(*ss == me.subsystem && *n == me.node))
                .filter(|(_, _, info)| {
                    info.config_asked.is_some_and(|t| now.saturating_duration_since(t) >= refresh)
                        || matches!(info.subscription, Subscription::Requested(t) if now.saturating_duration_since(t) >= retry)
                })
                .map(|(ss, n, _)| (ss, n))
                .collect();
            for (ss, n) in due {
                self.track_configuration(ctx, ss, n, false);
            }
        }
        // Staleness: remote nodes not heard from within the timeout are removed, with
        // their components.
        let timeout = self.config.node_timeout;
        let mut gone = Vec::new();
        for (ss, s) in &mut self.tree.subsystems {
            s.nodes.retain(|n, info| {
                let stale = !(*ss == me.subsystem && *n == me.node)
                    && now.saturating_duration_since(info.last_heard) > timeout;
                if stale {
                    for (c, i) in info.components.keys() {
                        gone.push(Address::new(*ss, *n, *c, *i));
                    }
                    tracing::info!(node = %Address::new(*ss, *n, 1, 1), "node timed out; removed from the system tree");
                }
                !stale
            });
        }
        self.tree.subsystems.retain(|_, s| !s.nodes.is_empty());
        if !gone.is_empty() {
            self.changes += 1;
        }
        self.gone.extend(gone);
    }
}
