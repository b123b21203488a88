//! Component control: grant, report, equal authority, a request below the component's
//! authority, preemption, release.

use jaus::messages::{Message, QueryComponentAuthority, ReleaseComponentControl};
use jaus::Address;

use super::talk::ControlAnswer;
use super::Ra33Voice;
use crate::check::Verdict;

use crate::engine::Found;

impl Ra33Voice<'_> {
    /// Whether `voice` received Reject Component Control during this check.
    fn rejected(&self, voice: Address) -> bool {
        let (from, to) = (self.target.to_string(), voice.to_string());
        self.evidence.iter().any(|e| {
            e.dir == "received"
                && e.message == "RejectComponentControl"
                && e.from == from
                && e.to == to
        })
    }

    pub(super) fn control_grant(&mut self) -> Found {
        let c = self.voices.controller;
        match self.acquire(c, self.authority) {
            Some(ControlAnswer::Accepted) => (
                Verdict::Pass,
                format!("{c} at authority {} confirmed", self.authority),
            ),
            Some(ControlAnswer::Refused(why)) => match self.held_by_another() {
                Some(held) => (Verdict::Inconclusive, held),
                None => (Verdict::Fail, format!("refused: {why}")),
            },
            None => (
                Verdict::Fail,
                format!(
                    "no answer to Request Component Control within {:?}",
                    self.opts.wait
                ),
            ),
        }
    }

    /// When a component that is not one of the tester's voices holds control (the
    /// rule then does not apply: control is granted while nobody holds it), says so.
    fn held_by_another(&mut self) -> Option<String> {
        match self.controller() {
            Some(Some((a, auth))) if !self.voices.all().contains(&a) => Some(format!(
                "{a} holds control at authority {auth} (the tester asked at {}); the rule applies while nobody holds control",
                self.authority
            )),
            _ => None,
        }
    }

    pub(super) fn control_report(&mut self) -> Found {
        if let Err(e) = self.hold_control() {
            return (Verdict::Inconclusive, e);
        }
        let c = self.voices.controller;
        match self.controller() {
            Some(Some((a, _))) if a == c => (Verdict::Pass, format!("names {c}")),
            Some(other) => (
                Verdict::Fail,
                format!(
                    "names {} instead of {c}",
                    super::describe_controller(Some(other))
                ),
            ),
            None => (
                Verdict::Fail,
                format!(
                    "no answer to Query Component Control within {:?}",
                    self.opts.wait
                ),
            ),
        }
    }

    pub(super) fn control_equal(&mut self) -> Found {
        if let Err(e) = self.hold_control() {
            return (Verdict::Inconclusive, e);
        }
        let (c, r) = (self.voices.controller, self.voices.rival);
        let answer = self.acquire(r, self.authority);
        // The controller must not have been told it lost control.
        self.drain(self.opts.settle);
        let rejected = self.rejected(c);
        match (answer, rejected) {
            (Some(ControlAnswer::Accepted), _) => (
                Verdict::Fail,
                format!(
                    "{r} at the same authority {} was given control",
                    self.authority
                ),
            ),
            (_, true) => (
                Verdict::Fail,
                format!("the controller {c} received Reject Component Control"),
            ),
            (Some(ControlAnswer::Refused(why)), false) => (
                Verdict::Pass,
                format!("{r} refused: {why}; {c} kept control"),
            ),
            (None, false) => (
                Verdict::Pass,
                format!("{r} got no answer (not given control); {c} kept control"),
            ),
        }
    }

    pub(super) fn control_preempt(&mut self) -> Found {
        if self.authority == u8::MAX {
            return (
                Verdict::Inconclusive,
                "the component's authority is 255: no higher authority exists".into(),
            );
        }
        if let Err(e) = self.hold_control() {
            return (Verdict::Inconclusive, e);
        }
        let (c, s) = (self.voices.controller, self.voices.senior);
        let answer = self.acquire(s, self.authority + 1);
        if !self.rejected(c) {
            let target = self.target;
            self.wait_for(self.opts.wait, |p| {
                p.header.source == target
                    && p.header.destination == c
                    && p.header.command_code.0 == 0x0010
            });
        }
        let rejected = self.rejected(c);
        let verdict = match (&answer, rejected) {
            (Some(ControlAnswer::Accepted), true) => (
                Verdict::Pass,
                format!("{s} at authority {} took control; {c} was rejected", self.authority + 1),
            ),
            (Some(ControlAnswer::Accepted), false) => (
                Verdict::Fail,
                format!("{s} took control but the old controller {c} received no Reject Component Control"),
            ),
            (Some(ControlAnswer::Refused(why)), _) => (
                Verdict::Fail,
                format!("{s} at the higher authority {} was refused: {why}", self.authority + 1),
            ),
            (None, _) => (
                Verdict::Fail,
                format!("no answer to {s}'s Request Component Control within {:?}", self.opts.wait),
            ),
        };
        self.send(s, &Message::from(ReleaseComponentControl {}), false);
        self.drain(self.opts.settle);
        verdict
    }

    pub(super) fn control_release(&mut self) -> Found {
        if let Err(refused) = self.hold_control() {
            // A voice of the tester may still hold control from the checks before (the
            // senior after control.preempt, which released it): each releases, and
            // the controller asks again. Refused again, a release had no effect.
            let (s, r, c) = (
                self.voices.senior,
                self.voices.rival,
                self.voices.controller,
            );
            for v in [s, r] {
                self.send(v, &ReleaseComponentControl {}.into(), false);
            }
            self.drain(self.opts.settle);
            if let Err(again) = self.hold_control() {
                let ours = [s, r, c];
                return match self.controller() {
                    Some(Some((holder, auth))) if ours.contains(&holder) => (
                        Verdict::Fail,
                        format!(
                            "{holder} (authority {auth}) still in control after its Release Component Control; {c}'s request: {again}"
                        ),
                    ),
                    Some(Some((holder, auth))) => (
                        Verdict::Inconclusive,
                        format!("{holder} (authority {auth}), not the tester, holds control: {refused}"),
                    ),
                    Some(None) => (Verdict::Inconclusive, format!("{refused}; then {again}, with nobody in control")),
                    // Granted to the tester earlier in this run: since then only its
                    // voices took control, and all of them released it.
                    None if self.granted && again.contains("Reject") => (
                        Verdict::Fail,
                        format!(
                            "{s} and {r} released control (the component granted the tester control earlier in this run; only the tester's voices took it since), yet {c}'s request was refused: {again}; Query Component Control is not answered, so the holder cannot be named"
                        ),
                    ),
                    None => (Verdict::Inconclusive, again),
                };
            }
        }
        self.send(
            self.voices.controller,
            &ReleaseComponentControl {}.into(),
            false,
        );
        self.drain(self.opts.settle);
        match self.controller() {
            Some(None) => (Verdict::Pass, "nobody in control after the release".into()),
            Some(Some((a, auth))) => (
                Verdict::Fail,
                format!("{a} (authority {auth}) still in control after the release"),
            ),
            None => (
                Verdict::Inconclusive,
                "Query Component Control not answered: the release cannot be seen".into(),
            ),
        }
    }

    /// Asks for control below the component's own authority (read afresh with Query
    /// Component Authority) while nobody holds it: the request must be refused.
    pub(super) fn control_below(&mut self) -> Found {
        let own = match self.ask(self.voices.outsider, QueryComponentAuthority {}.into()) {
            Some(Message::ReportComponentAuthority(r)) => r.authority_code,
            _ => {
                return (
                    Verdict::Inconclusive,
                    format!(
                        "no answer to Query Component Authority within {:?}: the component's authority is unknown",
                        self.opts.wait
                    ),
                )
            }
        };
        if own == 0 {
            return (
                Verdict::Inconclusive,
                "the component's authority is 0: no lower authority exists".into(),
            );
        }
        // Nobody in control, so that only the authority decides (the tester's
        // controller may still hold control from an earlier check).
        let c = self.voices.controller;
        self.send(c, &ReleaseComponentControl {}.into(), false);
        self.drain(self.opts.settle);
        if let Some(held) = self.held_by_another() {
            return (Verdict::Inconclusive, held);
        }
        let r = self.voices.rival;
        let below = own - 1;
        let answer = self.acquire(r, below);
        let holder = self.controller();
        let found = match (answer, holder) {
            (Some(ControlAnswer::Accepted), _) => (
                Verdict::Fail,
                format!(
                    "{r} at authority {below}, below the component's own {own}, was given control (Control Accepted)"
                ),
            ),
            (_, Some(Some((a, auth)))) if a == r => (
                Verdict::Fail,
                format!(
                    "{r} at authority {below}, below the component's own {own}, is named in control (authority {auth})"
                ),
            ),
            (Some(ControlAnswer::Refused(why)), _) => (
                Verdict::Pass,
                format!("{r} at authority {below} (the component's is {own}) refused: {why}"),
            ),
            (None, Some(_)) => (
                Verdict::Pass,
                format!(
                    "{r} at authority {below} (the component's is {own}) got no answer and is not named in control"
                ),
            ),
            (None, None) => (
                Verdict::Inconclusive,
                format!(
                    "no answer to {r}'s Request Component Control at authority {below} nor to Query Component Control: whether it was refused cannot be seen"
                ),
            ),
        };
        if found.0 == Verdict::Fail {
            self.send(r, &ReleaseComponentControl {}.into(), false);
            self.drain(self.opts.settle);
        }
        found
    }
}
