//! Checks as data: what each one tests, the rule it cites, whether it is required, and
//! what it found (a verdict with the messages exchanged as evidence).

use serde::Serialize;

/// How much a check counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Level {
    /// A failure is a conformance failure (`jaus conform` exits with status 1).
    Required,
    /// A failure is reported, not counted against the component.
    Advisory,
}

/// What a check found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// The target behaved as the rule says.
    Pass,
    /// The target broke the rule (the detail says how).
    Fail,
    /// The check could not decide (a precondition the target did not meet, e.g. no
    /// answer to the query the check reads back with, or an authority at its maximum).
    Inconclusive,
}

/// A rule of Part 1 or of the core message behaviour, in this tool's own words.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Rule {
    /// Short identifier (`control.preempt`), shared by every check testing it.
    pub id: &'static str,
    /// Where the rule comes from (`Part 1 §4.3`, `core rule`).
    pub source: &'static str,
    /// The rule, paraphrased.
    pub text: &'static str,
}

/// What a check does, for the engine.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Kind {
    /// Query Identification is answered with the component's identification.
    Identification,
    /// Report Services lists the core service and the component's own.
    ServicesListed,
    /// Report Services lists every message the definitions say the component takes.
    ServicesInputs,
    /// Query Component Status is answered.
    Status,
    /// Query Heartbeat Pulse is answered.
    Heartbeat,
    /// Query Component Authority is answered.
    Authority,
    /// Request Component Control is confirmed when nobody holds control.
    ControlGrant,
    /// Query Component Control names the controller.
    ControlReport,
    /// A second requester at the same authority is not given control.
    ControlEqual,
    /// A request below the component's own authority is refused.
    ControlBelow,
    /// A requester at a higher authority takes control; the old controller is told.
    ControlPreempt,
    /// Release Component Control frees the component.
    ControlRelease,
    /// A core state command from the controller is carried out.
    StateFromController(StateCommand),
    /// A core state command from a component not in control is refused.
    StateFromOutsider(StateCommand),
    /// Set Emergency is accepted from a component not in control.
    EmergencySet,
    /// Clear Emergency is accepted from a component not in control.
    EmergencyClear,
    /// The command's value is read back by its query (`readback:` in the definitions).
    Readback {
        /// The command's name.
        command: String,
        /// The query reading it back.
        query: String,
    },
    /// The command from a component not in control leaves the value read back as it
    /// was.
    OutsiderCommand {
        /// The command's name.
        command: String,
        /// The query reading it back.
        query: String,
    },
    /// After a malformed packet the target still answers Query Identification.
    Robust(Malformed),
    /// A service connection is confirmed, streams, suspends, resumes and ends.
    ServiceConnection,
    /// A periodic event on Report Component Status runs its course.
    EventPeriodic,
    /// An every-change event on Report Component Status reports state changes.
    EventEveryChange,
    /// Query Time is answered with the time of day.
    Time,
    /// A query the component's definition accepts is answered.
    QueryAnswered {
        /// The query's name.
        query: String,
    },
    /// The tester's clean-up on an RA 3.3 component: control released, the core state
    /// restored ([`crate::ra33::teardown_check`]).
    Teardown,
    /// A step of the AS-4 IOP scenario ([`crate::as4`]), run by that module, not by the
    /// RA 3.3 engine.
    As4,
    /// A finding on recorded traffic ([`crate::offline`]), judged from a capture, not
    /// run on a component.
    Offline,
}

/// The core state commands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum StateCommand {
    /// Ready → Standby.
    Standby,
    /// Standby → Ready.
    Resume,
    /// To Shutdown (never sent by the controller: it cannot be undone).
    Shutdown,
    /// To Initialize.
    Reset,
}

impl StateCommand {
    /// Its name in messages and check ids.
    pub fn name(self) -> &'static str {
        match self {
            StateCommand::Standby => "Standby",
            StateCommand::Resume => "Resume",
            StateCommand::Shutdown => "Shutdown",
            StateCommand::Reset => "Reset",
        }
    }
}

/// A malformed packet sent by a robustness check.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Malformed {
    /// Query Identification without its one-byte body (the header's size agrees).
    TruncatedBody,
    /// Query Component Status whose header announces more bytes than it carries.
    WrongDataSize,
    /// A command code no definition knows.
    UnknownCode,
    /// A field value outside the values its type defines.
    OutOfRange,
    /// Multi-packet sequences that do not complete (a first packet alone, a last
    /// packet without its first).
    IncompleteSequence,
}

/// One check: what it tests, against which rule, how much it counts.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Check {
    /// Unique within a component's run (`control.preempt`, `readback.SetTravelSpeed`).
    pub id: String,
    /// One line saying what is tested.
    pub title: String,
    /// The rule cited.
    pub rule: Rule,
    /// Required or advisory.
    pub level: Level,
    /// What the engine does.
    #[serde(skip)]
    pub kind: Kind,
}

/// A message as it crossed between the tester and the target.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Exchange {
    /// Milliseconds since the check began.
    pub t_ms: f64,
    /// `sent` or `received`.
    pub dir: &'static str,
    /// Source address.
    pub from: String,
    /// Destination address.
    pub to: String,
    /// The message's name (`ack`, `nak` for acknowledgements, `raw` for a malformed
    /// packet or one that did not decode).
    pub message: String,
    /// Its fields as JSON, or `{"hex": ...}` for raw bytes.
    pub fields: serde_json::Value,
}

/// What one check found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Outcome {
    /// The check.
    #[serde(flatten)]
    pub check: Check,
    /// Its verdict.
    pub verdict: Verdict,
    /// Why, in a sentence.
    pub detail: String,
    /// The messages exchanged while it ran.
    pub evidence: Vec<Exchange>,
}

impl Outcome {
    /// A required check that failed.
    pub fn is_required_failure(&self) -> bool {
        self.verdict == Verdict::Fail && self.check.level == Level::Required
    }
}
