//! The settings of one component.

use std::time::Duration;

use crate::Address;

/// Who may send the controlled commands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ControlPolicy {
    /// Only the component in control (none when nobody holds control).
    #[default]
    ControllerOnly,
    /// The component in control, or anyone while nobody holds control (OpenJAUS 3.3).
    Open,
}

/// Settings of one component.
#[derive(Debug, Clone)]
pub struct Config {
    /// The component's own authority (Set Component Authority changes it). Default 0.
    pub authority: u8,
    /// Who may send controlled commands. Default [`ControlPolicy::ControllerOnly`].
    pub control: ControlPolicy,
    /// Period of Report Heartbeat Pulse to the node manager (`None`: no heartbeat).
    /// Default 1 s.
    pub heartbeat: Option<Duration>,
    /// Where heartbeats go (`None`, the default: component 1, instance 1 of this node).
    pub node_manager: Option<Address>,
    /// Period of [`Behaviour::tick`](super::Behaviour::tick) and of the "every change" event checks. Default
    /// 50 ms.
    pub tick: Duration,
    /// Highest rate granted to a service connection or periodic event, Hz. Default
    /// 100 Hz (the wire carries up to 1092 Hz).
    pub max_rate_hz: f64,
    /// Most service connections served at once. Default 32.
    pub max_service_connections: usize,
    /// Most events served at once. Default 32.
    pub max_events: usize,
    /// Most service connections this component requests at once. Default 32.
    pub max_subscriptions: usize,
    /// Most messages waiting in the outgoing queue (more are dropped and counted in
    /// `Stats::outbox_dropped`). Default 1024.
    pub outbox_capacity: usize,
    /// Most distinct emergency senders remembered (more are counted in
    /// `Stats::emergency_overflow`; the emergency still holds). Default 16.
    pub max_emergency_senders: usize,
    /// Identification text (`None`, the default: the component name).
    pub identification: Option<String>,
    /// UTC (since 1970-01-01) at the first instant the component sees, if known.
    /// Default `None`: the I/O shell's wall clock when it runs on a real network
    /// ([`Component::wall_clock`](super::Component::wall_clock), e.g. `jaus::net::udp::run`), else Set Time.
    pub utc: Option<Duration>,
}

/// The defaults the field documentation states:
///
/// ```
/// use std::time::Duration;
/// use jaus::component::{Config, ControlPolicy};
///
/// let c = Config::default();
/// assert_eq!((c.authority, c.control), (0, ControlPolicy::ControllerOnly));
/// assert_eq!((c.heartbeat, c.node_manager), (Some(Duration::from_secs(1)), None));
/// assert_eq!((c.tick, c.max_rate_hz), (Duration::from_millis(50), 100.0));
/// assert_eq!((c.max_service_connections, c.max_events, c.max_subscriptions), (32, 32, 32));
/// assert_eq!((c.outbox_capacity, c.max_emergency_senders), (1024, 16));
/// assert_eq!((c.identification, c.utc), (None, None));
/// ```
impl Default for Config {
    fn default() -> Self {
        Self {
            authority: 0,
            control: ControlPolicy::ControllerOnly,
            heartbeat: Some(Duration::from_secs(1)),
            node_manager: None,
            tick: Duration::from_millis(50),
            max_rate_hz: 100.0,
            max_service_connections: 32,
            max_events: 32,
            max_subscriptions: 32,
            outbox_capacity: 1024,
            max_emergency_senders: 16,
            identification: None,
            utc: None,
        }
    }
}
