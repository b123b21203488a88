//! A node's access policy: who may command the components of a node, take control of
//! them and with what authority, and who may only query, checked by the sans-IO node
//! before a message from outside reaches a component.
//!
//! JAUS RA 3.3 authenticates nobody: any host that reaches a node's socket can take
//! control of a component with a high enough authority code. A [`Policy`] narrows that
//! per sender address (subsystem, node, component, instance, with `*` wildcards): the
//! first [`Rule`] whose pattern matches the sender decides; senders no rule names get
//! the policy's default. What a sender may do is a [`Permission`]:
//!
//! | permission | queries, reports, service connections, events | commands | control |
//! |---|---|---|---|
//! | `none` | refused | refused | refused |
//! | `query` | yes | refused | refused |
//! | `command` | yes | yes | up to `max_authority` |
//!
//! Set Emergency and Clear Emergency pass whatever the permission (Part 1: any component
//! may stop a vehicle), unless a rule says `emergency: false`.
//!
//! A refused message never reaches the component. The sender gets the answer a component
//! that refuses would give: Request Component Control is answered with Confirm Component
//! Control (insufficient authority), and a message that asked for an acknowledgement is
//! NAKed. Every refusal is counted per rule ([`PolicyState::counts`]) and logged at warn
//! with the sender, the message and the rule (at most [`WARNINGS_PER_SECOND`] lines a
//! second; the rest at debug, with a count of those left out).
//!
//! Messages between the components of the node itself are never checked; messages from
//! other processes joined to the node (external components) are.

use std::fmt;
use std::time::{Duration, Instant};

use crate::codec::{Decode, Encode};
use crate::component::refusal_report;
use crate::messages::{
    ClearEmergency, ConfirmComponentControl, ControlResponse, RequestComponentControl, SetEmergency,
};
use crate::messages::{RefusalReason, ReportRefusal};
use crate::wire::{AckNak, MessageClass};
use crate::{Address, Header, JausMessage, MessageInfo};

/// Most refusals logged at warn in one second (the rest at debug, and counted).
pub const WARNINGS_PER_SECOND: u32 = 20;

/// What a sender may do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Permission {
    /// Nothing (emergency messages aside).
    None,
    /// Queries, reports, service connections and events; no commands, no control.
    Query,
    /// Everything; control with an authority up to `max_authority`.
    Command {
        /// The highest authority code it may request control with.
        max_authority: u8,
    },
}

impl fmt::Display for Permission {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Permission::None => f.write_str("none"),
            Permission::Query => f.write_str("query only"),
            Permission::Command { max_authority: 255 } => f.write_str("command"),
            Permission::Command { max_authority } => {
                write!(f, "command, authority at most {max_authority}")
            }
        }
    }
}

/// One number of an address pattern: a value or any (`*`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// Any value.
    Any,
    /// This value.
    Is(u8),
}

/// A sender pattern `S.N.C.I` whose parts are numbers or `*` (e.g. `200.*.*.*`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AddressPattern(pub [Part; 4]);

impl AddressPattern {
    /// Whether `a` matches.
    pub fn matches(&self, a: Address) -> bool {
        let v = [a.subsystem, a.node, a.component, a.instance];
        self.0.iter().zip(v).all(|(p, x)| match p {
            Part::Any => true,
            Part::Is(n) => *n == x,
        })
    }
}

impl fmt::Display for AddressPattern {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, p) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(".")?;
            }
            match p {
                Part::Any => f.write_str("*")?,
                Part::Is(n) => write!(f, "{n}")?,
            }
        }
        Ok(())
    }
}

impl std::str::FromStr for AddressPattern {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let parts: Vec<&str> = s.trim().split('.').collect();
        if parts.len() != 4 {
            return Err(format!(
                "`{s}`: expected subsystem.node.component.instance, each a number 0-255 or *"
            ));
        }
        let mut out = [Part::Any; 4];
        for (o, p) in out.iter_mut().zip(parts) {
            *o = match p {
                "*" => Part::Any,
                n => Part::Is(
                    n.parse()
                        .map_err(|_| format!("`{s}`: `{n}` is neither a number 0-255 nor *"))?,
                ),
            };
        }
        Ok(Self(out))
    }
}

/// One rule: the senders it is about and what they may do.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Rule {
    /// The senders.
    pub from: AddressPattern,
    /// What they may do.
    pub may: Permission,
    /// Whether Set/Clear Emergency from them pass even when `may` refuses commands.
    /// Default true (Part 1's safety rule).
    pub emergency: bool,
}

/// A node's access policy (see the [module documentation](self)).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Policy {
    /// First match decides.
    pub rules: Vec<Rule>,
    /// For senders no rule matches.
    pub default: Permission,
    /// Whether Set/Clear Emergency from senders no rule matches always pass.
    pub default_emergency: bool,
}

impl Default for Policy {
    /// Open: everyone may command with any authority (what a node without a policy does).
    fn default() -> Self {
        Self {
            rules: Vec::new(),
            default: Permission::Command { max_authority: 255 },
            default_emergency: true,
        }
    }
}

/// What a message asks of the receiving component, for the policy.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Reads or answers: queries, reports, service connections, events, the replies
    /// that live in the command class, Release Component Control, node management.
    Read,
    /// Set Emergency, Clear Emergency.
    Emergency,
    /// Request Component Control with this authority.
    Control(u8),
    /// Any other command (and experimental messages not defined as queries or reports).
    Command,
}

impl Kind {
    /// The kind of a message: its class, with the core exceptions.
    pub fn of(header: &Header, body: &[u8]) -> Kind {
        let code = header.command_code;
        if code == SetEmergency::CODE || code == ClearEmergency::CODE {
            return Kind::Emergency;
        }
        if code == RequestComponentControl::CODE {
            // An undecodable request asks for the most (the component refuses it anyway).
            let authority =
                RequestComponentControl::from_bytes(body).map_or(255, |r| r.authority_code);
            return Kind::Control(authority);
        }
        let reads = |c: MessageClass| {
            matches!(
                c,
                MessageClass::Query
                    | MessageClass::Inform
                    | MessageClass::EventNotification
                    | MessageClass::NodeManagement
            )
        };
        let class = code.class();
        if reads(class) {
            return Kind::Read;
        }
        // A command (or an experimental code) reads when its definition says
        // `access: read`, or its class (`class:` of an experimental code) is a read.
        let info = MessageInfo::of(code);
        let read = match info {
            Some(i) => i.read_only || (class == MessageClass::Experimental && reads(i.class)),
            None => false,
        };
        if read {
            Kind::Read
        } else {
            Kind::Command
        }
    }
}

/// Which rule decided (for logs and counters).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Decider {
    /// Rule `n` (from 0).
    Rule(usize),
    /// The default.
    Default,
}

impl Policy {
    /// The rule (or default) for `sender`.
    pub fn rule_for(&self, sender: Address) -> (Decider, Permission, bool) {
        self.rules
            .iter()
            .enumerate()
            .find(|(_, r)| r.from.matches(sender))
            .map_or(
                (Decider::Default, self.default, self.default_emergency),
                |(i, r)| (Decider::Rule(i), r.may, r.emergency),
            )
    }

    /// Whether `kind` from `sender` passes, and which rule said so.
    pub fn allows(&self, sender: Address, kind: Kind) -> (bool, Decider) {
        let (by, may, emergency) = self.rule_for(sender);
        let ok = match (kind, may) {
            (Kind::Emergency, _) if emergency => true,
            (_, Permission::None) => false,
            (Kind::Read, _) => true,
            (_, Permission::Query) => false,
            (Kind::Control(a), Permission::Command { max_authority }) => a <= max_authority,
            (Kind::Emergency | Kind::Command, Permission::Command { .. }) => true,
        };
        (ok, by)
    }

    /// Whether the policy lets everyone do everything.
    pub fn is_open(&self) -> bool {
        self.default == (Permission::Command { max_authority: 255 })
            && self.default_emergency
            && self
                .rules
                .iter()
                .all(|r| r.may == (Permission::Command { max_authority: 255 }) && r.emergency)
    }

    /// One line per rule and the default, for a node's start-up message.
    pub fn describe(&self) -> String {
        let mut s = String::new();
        for (i, r) in self.rules.iter().enumerate() {
            s.push_str(&format!(
                "rule {i}: from {} may {}{}; ",
                r.from,
                r.may,
                if r.emergency { "" } else { ", no emergency" }
            ));
        }
        s.push_str(&format!(
            "anyone else may {}{}",
            self.default,
            if self.default_emergency {
                ""
            } else {
                ", no emergency"
            }
        ));
        s
    }
}

/// What the node does with a message from outside.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Verdict {
    /// Deliver it.
    Pass,
    /// Refused: send these answers (header, body) from the destination to the sender.
    Refuse(Vec<(Header, Vec<u8>)>),
}

/// A policy in a running node: the rules, the refusals counted per rule, the rate of
/// warnings.
#[derive(Debug, Clone)]
pub struct PolicyState {
    policy: Policy,
    /// Refusals per rule, then the default's.
    counts: Vec<u64>,
    warn_second: Option<Instant>,
    warned: u32,
    unwarned: u64,
}

impl PolicyState {
    /// A running `policy`.
    pub fn new(policy: Policy) -> Self {
        Self {
            counts: vec![0; policy.rules.len() + 1],
            policy,
            warn_second: None,
            warned: 0,
            unwarned: 0,
        }
    }

    /// The policy.
    pub fn policy(&self) -> &Policy {
        &self.policy
    }

    /// Refusals counted per rule, in order, then those by the default.
    pub fn counts(&self) -> &[u64] {
        &self.counts
    }

    /// Checks a message from outside the node for a component here at `now`.
    pub fn check(&mut self, now: Instant, header: &Header, body: &[u8]) -> Verdict {
        let kind = Kind::of(header, body);
        let (ok, by) = self.policy.allows(header.source, kind);
        if ok {
            return Verdict::Pass;
        }
        let slot = match by {
            Decider::Rule(i) => i,
            Decider::Default => self.policy.rules.len(),
        };
        if let Some(c) = self.counts.get_mut(slot) {
            *c += 1;
        }
        let why = self.why(kind, by);
        self.log(now, header, &why);
        Verdict::Refuse(answers(header, kind, &why))
    }

    /// The refusal in words: the rule and what it lets the sender do.
    fn why(&self, kind: Kind, by: Decider) -> String {
        let (rule, may) = match by {
            Decider::Rule(i) => {
                let r = &self.policy.rules[i];
                (format!("rule {i} (from {})", r.from), r.may)
            }
            Decider::Default => ("the default".to_string(), self.policy.default),
        };
        let what = match kind {
            Kind::Control(a) => format!("control with authority {a}; "),
            Kind::Emergency => "emergency messages refused; ".to_string(),
            Kind::Read | Kind::Command => String::new(),
        };
        format!("refused by the node's policy: {what}{rule} may {may}")
    }

    fn log(&mut self, now: Instant, header: &Header, why: &str) {
        if self
            .warn_second
            .is_none_or(|t| now.saturating_duration_since(t) >= Duration::from_secs(1))
        {
            self.warn_second = Some(now);
            self.warned = 0;
        }
        let message = MessageInfo::of(header.command_code).map_or("(not in this set)", |i| i.name);
        if self.warned < WARNINGS_PER_SECOND {
            self.warned += 1;
            let left_out = std::mem::take(&mut self.unwarned);
            tracing::warn!(
                sender = %header.source,
                destination = %header.destination,
                message,
                code = %header.command_code,
                left_out,
                "{why}"
            );
        } else {
            self.unwarned += 1;
            tracing::debug!(sender = %header.source, message, "{why}");
        }
    }
}

/// What a component that refuses would answer: Confirm Component Control (insufficient
/// authority) to a control request, a NAK to a message that asked for an
/// acknowledgement, preceded by the SDK's Report Refusal with `why`. Nothing for a
/// broadcast.
fn answers(header: &Header, kind: Kind, why: &str) -> Vec<(Header, Vec<u8>)> {
    let me = header.destination;
    if me.subsystem == 255 || me.node == 255 || me.component == 255 || me.instance == 255 {
        return Vec::new();
    }
    let mut out = Vec::new();
    if matches!(kind, Kind::Control(_)) {
        let confirm = ConfirmComponentControl {
            response_code: ControlResponse::InsufficientAuthority,
        };
        if let Ok(body) = confirm.to_bytes() {
            out.push((
                Header::new(ConfirmComponentControl::CODE, header.source, me),
                body,
            ));
        }
    }
    if header.ack_nak == AckNak::Request {
        let report = refusal_report(header.command_code, RefusalReason::Policy, why);
        if let Ok(body) = report.to_bytes() {
            out.push((Header::new(ReportRefusal::CODE, header.source, me), body));
        }
        out.push((header.acknowledgement(me, false), Vec::new()));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::messages::CreateServiceConnection;
    use crate::CommandCode;

    fn a(s: &str) -> Address {
        s.parse().unwrap()
    }

    fn policy() -> Policy {
        Policy {
            rules: vec![
                Rule {
                    from: "200.*.*.*".parse().unwrap(),
                    may: Permission::Command { max_authority: 100 },
                    emergency: true,
                },
                Rule {
                    from: "42.1.*.*".parse().unwrap(),
                    may: Permission::Query,
                    emergency: true,
                },
                Rule {
                    from: "66.*.*.*".parse().unwrap(),
                    may: Permission::None,
                    emergency: false,
                },
            ],
            default: Permission::Query,
            default_emergency: true,
        }
    }

    fn header<M: JausMessage>(from: &str) -> Header {
        Header::new(M::CODE, a("1.1.33.1"), a(from))
    }

    #[test]
    fn patterns_parse_and_match() {
        let p: AddressPattern = "200.*.40.1".parse().unwrap();
        assert!(p.matches(a("200.3.40.1")));
        assert!(!p.matches(a("200.3.40.2")));
        assert_eq!(p.to_string(), "200.*.40.1");
        assert!("200.*.*".parse::<AddressPattern>().is_err());
        let e = "200.x.*.*".parse::<AddressPattern>().unwrap_err();
        assert!(e.contains("`x`"), "{e}");
        assert!("256.*.*.*".parse::<AddressPattern>().is_err());
    }

    #[test]
    fn kinds_follow_the_class_with_the_core_exceptions() {
        use crate::messages::{QueryGlobalPose, ReportGlobalPose, SetWrenchEffort, Standby};
        let h = |c| Header::new(c, a("1.1.33.1"), a("2.1.1.1"));
        assert_eq!(Kind::of(&h(QueryGlobalPose::CODE), &[]), Kind::Read);
        assert_eq!(Kind::of(&h(ReportGlobalPose::CODE), &[]), Kind::Read);
        assert_eq!(Kind::of(&h(SetWrenchEffort::CODE), &[]), Kind::Command);
        assert_eq!(Kind::of(&h(Standby::CODE), &[]), Kind::Command);
        assert_eq!(Kind::of(&h(SetEmergency::CODE), &[]), Kind::Emergency);
        assert_eq!(Kind::of(&h(ClearEmergency::CODE), &[]), Kind::Emergency);
        assert_eq!(Kind::of(&h(CreateServiceConnection::CODE), &[]), Kind::Read);
        assert_eq!(Kind::of(&h(ConfirmComponentControl::CODE), &[]), Kind::Read);
        assert_eq!(
            Kind::of(&h(RequestComponentControl::CODE), &[7]),
            Kind::Control(7)
        );
        // Truncated: asks for the most.
        assert_eq!(
            Kind::of(&h(RequestComponentControl::CODE), &[]),
            Kind::Control(255)
        );
        // An experimental code nobody defined counts as a command.
        assert_eq!(Kind::of(&h(CommandCode(0xD123)), &[]), Kind::Command);
        // Every command the definitions mark `access: read` reads (the subscriptions,
        // event set-up, giving up control), and there are such commands.
        let reads: Vec<_> = crate::messages::MESSAGES
            .iter()
            .filter(|m| m.read_only)
            .collect();
        assert!(reads.len() >= 13, "{}", reads.len());
        for m in reads {
            assert_eq!(Kind::of(&h(m.code), &[]), Kind::Read, "{}", m.name);
        }
    }

    #[test]
    fn the_first_matching_rule_decides() {
        let p = policy();
        assert_eq!(
            p.allows(a("200.1.40.1"), Kind::Command),
            (true, Decider::Rule(0))
        );
        assert!(p.allows(a("200.1.40.1"), Kind::Control(100)).0);
        assert_eq!(
            p.allows(a("200.1.40.1"), Kind::Control(101)),
            (false, Decider::Rule(0))
        );
        assert_eq!(
            p.allows(a("42.1.5.1"), Kind::Read),
            (true, Decider::Rule(1))
        );
        assert_eq!(
            p.allows(a("42.1.5.1"), Kind::Command),
            (false, Decider::Rule(1))
        );
        assert!(!p.allows(a("42.1.5.1"), Kind::Control(1)).0);
        assert!(p.allows(a("42.1.5.1"), Kind::Emergency).0);
        assert_eq!(
            p.allows(a("66.1.1.1"), Kind::Read),
            (false, Decider::Rule(2))
        );
        assert!(!p.allows(a("66.1.1.1"), Kind::Emergency).0);
        assert_eq!(
            p.allows(a("9.1.1.1"), Kind::Command),
            (false, Decider::Default)
        );
        assert_eq!(
            p.allows(a("9.1.1.1"), Kind::Emergency),
            (true, Decider::Default)
        );
        assert!(!p.is_open());
        assert!(Policy::default().is_open());
    }

    #[test]
    fn refusals_are_answered_and_counted() {
        let mut s = PolicyState::new(policy());
        let now = Instant::now();
        let mut h = header::<RequestComponentControl>("200.1.40.1");
        h.ack_nak = AckNak::Request;
        let Verdict::Refuse(answers) = s.check(now, &h, &[150]) else {
            panic!("authority 150 passed");
        };
        assert_eq!(answers.len(), 3);
        let (ch, cb) = &answers[0];
        assert_eq!(ch.command_code, ConfirmComponentControl::CODE);
        assert_eq!(
            (ch.source, ch.destination),
            (a("1.1.33.1"), a("200.1.40.1"))
        );
        assert_eq!(
            ConfirmComponentControl::from_bytes(cb)
                .unwrap()
                .response_code,
            ControlResponse::InsufficientAuthority
        );
        let (rh, rb) = &answers[1];
        assert_eq!(rh.command_code, ReportRefusal::CODE);
        let r = ReportRefusal::from_bytes(rb).unwrap();
        assert_eq!(r.reason, RefusalReason::Policy);
        assert_eq!(r.refused_code, RequestComponentControl::CODE.0);
        assert_eq!(
            r.text,
            "refused by the node's policy: control with authority 150; rule 0 (from 200.*.*.*) may command, authority at most 100"
        );
        assert_eq!(answers[2].0.ack_nak, AckNak::Nak);
        assert_eq!(answers[2].0.command_code, RequestComponentControl::CODE);
        assert_eq!(s.check(now, &h, &[100]), Verdict::Pass);
        // A command without an acknowledgement request: refused, nothing to answer.
        let h = header::<crate::messages::SetWrenchEffort>("9.1.1.1");
        assert_eq!(s.check(now, &h, &[]), Verdict::Refuse(Vec::new()));
        // Broadcasts are refused without answers.
        let mut h = header::<RequestComponentControl>("66.1.1.1");
        h.destination = a("1.1.255.255");
        assert_eq!(s.check(now, &h, &[1]), Verdict::Refuse(Vec::new()));
        assert_eq!(s.counts(), &[1, 0, 1, 1]);
    }

    #[test]
    fn warnings_are_rate_limited_and_the_rest_counted() {
        let mut s = PolicyState::new(policy());
        let now = Instant::now();
        let h = header::<crate::messages::SetWrenchEffort>("9.1.1.1");
        for _ in 0..(WARNINGS_PER_SECOND + 5) {
            let _ = s.check(now, &h, &[]);
        }
        assert_eq!(s.warned, WARNINGS_PER_SECOND);
        assert_eq!(s.unwarned, 5);
        let _ = s.check(now + Duration::from_secs(1), &h, &[]);
        assert_eq!((s.warned, s.unwarned), (1, 0));
        assert_eq!(s.counts()[3], u64::from(WARNINGS_PER_SECOND) + 6);
    }
}
