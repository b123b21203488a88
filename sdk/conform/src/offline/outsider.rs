//! Component control as the capture shows it, and what commands from clients not in
//! control did: who controls each component (Confirm Component Control granted,
//! Release and Reject Component Control, Report Component Control), its last reported
//! state, and for each state command from another client whether a Report Component
//! Status within the window shows its effect.

use std::collections::{BTreeMap, HashMap};
use std::time::Duration;

use jaus::messages::{ComponentState, ControlResponse, Message};
use jaus::{Address, Header};

/// What a state command does, as a status report shows it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Expect {
    /// The component reports this state.
    State(ComponentState),
    /// The component reports another state than before (Reset).
    Change,
}

/// A packet, for the findings.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Sent {
    pub number: u64,
    pub time: Duration,
    pub from: Address,
    pub to: Address,
    pub name: &'static str,
}

/// A state command from a client not in control, watched for its effect.
#[derive(Debug, Clone)]
struct Watch {
    cmd: Sent,
    controller: Address,
    expect: Expect,
    before: Option<ComponentState>,
    reports: u64,
}

/// An outsider's command that the component carried out.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Obeyed {
    /// The command.
    pub cmd: Sent,
    /// Who was in control.
    pub controller: Address,
    /// The state before it, if reported.
    pub before: Option<ComponentState>,
    /// The report showing its effect: packet number, time, state.
    pub report: (u64, Duration, ComponentState),
}

/// What the outsiders' commands to one component did.
#[derive(Debug, Default)]
pub(crate) struct Findings {
    /// State commands carried out.
    pub obeyed: Vec<Obeyed>,
    /// State commands after which the component reported its state unchanged.
    pub refused: Vec<u64>,
    /// State commands followed by no Report Component Status within the window.
    pub unseen: Vec<u64>,
    /// State commands whose effect cannot show (already in that state; state unknown
    /// for Reset) or that the controller's own command followed within the window.
    pub undecided: u64,
    /// Other commands from clients not in control (not judged offline: their effect
    /// needs a read-back).
    pub other: u64,
    /// Commands from clients not in control acknowledged with ACK: the command and the
    /// ACK's packet number.
    pub acked: Vec<(Sent, u64)>,
    /// Those answered with NAK.
    pub naked: u64,
}

/// The control state and the watches.
#[derive(Debug, Default)]
pub(crate) struct Outsider {
    controllers: HashMap<Address, Address>,
    state: HashMap<Address, ComponentState>,
    watching: Vec<Watch>,
    /// Outsiders' commands asking for an acknowledgement.
    ack_waiting: Vec<Sent>,
    /// Per component commanded.
    pub findings: BTreeMap<Address, Findings>,
    /// Commands not watched (the bound was reached).
    pub dropped: u64,
    cap: usize,
    window: Duration,
    /// When [`Outsider::expire`] next sweeps (eight times a window at most).
    next_sweep: Duration,
}

/// A list bounded at `cap`: false (and nothing kept) when full.
fn keep<T>(v: &mut Vec<T>, x: T, cap: usize) -> bool {
    if v.len() >= cap {
        return false;
    }
    v.push(x);
    true
}

impl Outsider {
    /// Nothing known; at most `cap` commands watched at once.
    pub fn new(window: Duration, cap: usize) -> Self {
        Outsider {
            cap,
            window,
            ..Outsider::default()
        }
    }

    /// A decoded message `msg` under `h`, packet `number` seen at `time`.
    pub fn message(&mut self, number: u64, time: Duration, h: &Header, msg: &Message) {
        let (from, to) = (h.source, h.destination);
        match msg {
            Message::ConfirmComponentControl(c)
                if c.response_code == ControlResponse::ControlAccepted =>
            {
                self.controllers.insert(from, to);
            }
            Message::RejectComponentControl(_) if self.controllers.get(&from) == Some(&to) => {
                self.controllers.remove(&from);
            }
            Message::ReleaseComponentControl(_) if self.controllers.get(&to) == Some(&from) => {
                self.controllers.remove(&to);
            }
            Message::ReportComponentControl(r) => {
                let c = Address::new(r.subsystem_id, r.node_id, r.component_id, r.instance_id);
                if c == Address::new(0, 0, 0, 0) {
                    self.controllers.remove(&from);
                } else {
                    self.controllers.insert(from, c);
                }
            }
            Message::ReportComponentStatus(r) => {
                self.status(number, time, from, r.primary_status_code);
            }
            _ => {}
        }
        self.command(number, time, h, msg);
    }

    /// Judges a command: from the controller it ends the watches on its receiver (what
    /// follows may be its effect); from another client it is watched.
    fn command(&mut self, number: u64, time: Duration, h: &Header, msg: &Message) {
        let code = msg.code();
        let Some(info) = jaus::MessageInfo::of(code) else {
            return;
        };
        // Control requests and emergencies are for anyone to send.
        let exempt = matches!(
            msg,
            Message::RequestComponentControl(_)
                | Message::SetEmergency(_)
                | Message::ClearEmergency(_)
        );
        if info.class != jaus::wire::MessageClass::Command || info.read_only || exempt {
            return;
        }
        let (from, to) = (h.source, h.destination);
        let Some(&controller) = self.controllers.get(&to) else {
            return;
        };
        if controller == from {
            // What follows may be the controller's doing: the watches end here, refused
            // when a status report came between and did not show the effect.
            let findings = &mut self.findings;
            self.watching.retain(|w| {
                if w.cmd.to != to {
                    return true;
                }
                let f = findings.entry(to).or_default();
                if w.reports > 0 {
                    f.refused.push(w.cmd.number);
                } else {
                    f.undecided += 1;
                }
                false
            });
            return;
        }
        let cmd = Sent {
            number,
            time,
            from,
            to,
            name: msg.name(),
        };
        if h.ack_nak == jaus::wire::AckNak::Request
            && !keep(&mut self.ack_waiting, cmd.clone(), self.cap)
        {
            self.dropped += 1;
        }
        let before = self.state.get(&to).copied();
        let expect = match msg {
            Message::Standby(_) => Expect::State(ComponentState::Standby),
            Message::Resume(_) => Expect::State(ComponentState::Ready),
            Message::Shutdown(_) => Expect::State(ComponentState::Shutdown),
            Message::Reset(_) => Expect::Change,
            _ => {
                self.findings.entry(to).or_default().other += 1;
                return;
            }
        };
        let f = self.findings.entry(to).or_default();
        let observable = match expect {
            Expect::State(s) => before != Some(s),
            Expect::Change => before.is_some(),
        };
        if !observable {
            f.undecided += 1;
            return;
        }
        let w = Watch {
            cmd,
            controller,
            expect,
            before,
            reports: 0,
        };
        if !keep(&mut self.watching, w, self.cap) {
            self.dropped += 1;
        }
    }

    /// `from` reported `state`.
    fn status(&mut self, number: u64, time: Duration, from: Address, state: ComponentState) {
        self.state.insert(from, state);
        let findings = &mut self.findings;
        let window = self.window;
        self.watching.retain_mut(|w| {
            // Watches past their window not swept yet ([`Outsider::expire`]) see no more.
            if w.cmd.to != from || time < w.cmd.time || time - w.cmd.time > window {
                return true;
            }
            w.reports += 1;
            let shows = match w.expect {
                Expect::State(s) => state == s,
                Expect::Change => Some(state) != w.before,
            };
            if shows {
                findings.entry(from).or_default().obeyed.push(Obeyed {
                    cmd: w.cmd.clone(),
                    controller: w.controller,
                    before: w.before,
                    report: (number, time, state),
                });
            }
            !shows
        });
    }

    /// An ACK or NAK under `h`, packet `number`.
    pub fn answer(&mut self, number: u64, time: Duration, h: &Header) {
        let window = self.window;
        let name = jaus::MessageInfo::of(h.command_code).map(|i| i.name);
        let pos = self.ack_waiting.iter().position(|c| {
            c.to == h.source
                && c.from == h.destination
                && name == Some(c.name)
                && time.saturating_sub(c.time) <= window
        });
        if let Some(i) = pos {
            let cmd = self.ack_waiting.remove(i);
            let f = self.findings.entry(cmd.to).or_default();
            if h.ack_nak == jaus::wire::AckNak::Ack {
                f.acked.push((cmd, number));
            } else {
                f.naked += 1;
            }
        }
    }

    /// Ends the watches older than the window at `now` (all of them when `all`).
    pub fn expire(&mut self, now: Duration, all: bool) {
        if !all && now < self.next_sweep {
            return;
        }
        self.next_sweep = now + self.window / 8;
        let window = self.window;
        let findings = &mut self.findings;
        self.watching.retain(|w| {
            if !all && now.saturating_sub(w.cmd.time) <= window {
                return true;
            }
            let f = findings.entry(w.cmd.to).or_default();
            if w.reports > 0 {
                f.refused.push(w.cmd.number);
            } else {
                f.unseen.push(w.cmd.number);
            }
            false
        });
        self.ack_waiting
            .retain(|c| !all && now.saturating_sub(c.time) <= window);
    }
}
