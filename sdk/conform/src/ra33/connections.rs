//! Service connections: Report Component Status (every component answers its query)
//! streamed to the outsider, then suspended, activated and terminated.

use std::time::Duration;

use jaus::messages::{
    ActivateServiceConnection, CreateServiceConnection, Message, ServiceConnectionResponse,
    SuspendServiceConnection, TerminateServiceConnection,
};
use jaus::Address;

use super::Ra33Voice;
use crate::check::Verdict;

/// Report Component Status.
const REPORT: u16 = 0x4002;
/// The rate asked for, Hz.
const RATE: f64 = 10.0;

impl Ra33Voice<'_> {
    /// How long each phase is watched: five settle times, at least 250 ms.
    fn window(&self) -> Duration {
        (self.opts.settle * 5).max(Duration::from_millis(250))
    }

    /// Reports of the connection arriving at `voice` within `window`, with the
    /// service-connection flag (and without it).
    fn count_reports(&mut self, voice: Address, window: Duration) -> (usize, usize) {
        let deadline = self.session.now() + window;
        let (mut flagged, mut plain) = (0, 0);
        while let Some(p) = self.next(deadline) {
            if p.header.source == self.target
                && p.header.destination == voice
                && p.header.command_code.0 == REPORT
            {
                if p.header.service_connection {
                    flagged += 1;
                } else {
                    plain += 1;
                }
            }
        }
        (flagged, plain)
    }

    pub(super) fn service_connection(&mut self) -> (Verdict, String) {
        let o = self.voices.outsider;
        let create = CreateServiceConnection {
            service_connection_command_code: REPORT,
            requested_periodic_update_rate: RATE,
            presence_vector: 0,
        };
        self.send(o, &create.into(), false);
        let target = self.target;
        let Some(p) = self.wait_for(self.opts.wait, |p| {
            p.header.source == target
                && p.header.destination == o
                && p.header.command_code.0 == 0x0009
        }) else {
            return (
                Verdict::Fail,
                format!("no Confirm Service Connection within {:?}", self.opts.wait),
            );
        };
        let Ok(Message::ConfirmServiceConnection(c)) =
            Message::decode_known(p.header.command_code, &p.body)
        else {
            return (
                Verdict::Fail,
                "Confirm Service Connection does not decode".into(),
            );
        };
        if c.response_code != ServiceConnectionResponse::Successful {
            return (
                Verdict::Fail,
                format!(
                    "Report Component Status at {RATE} Hz refused: {:?}",
                    c.response_code
                ),
            );
        }
        let (code, instance_id) = (REPORT, c.instance_id);
        let rate = c.confirmed_periodic_update_rate;
        let window = self.window();
        // At least half the reports the confirmed rate promises, and one.
        let expected = ((rate * window.as_secs_f64() * 0.5).floor() as usize).max(1);
        let mut problems = Vec::new();
        let (flagged, plain) = self.count_reports(o, window);
        if flagged < expected {
            problems.push(format!(
                "{flagged} flagged reports in {window:?} at a confirmed {rate:.2} Hz (at least {expected} expected{})",
                if plain > 0 { format!("; {plain} without the flag") } else { String::new() }
            ));
        }
        self.send(
            o,
            &SuspendServiceConnection {
                service_connection_command_code: code,
                instance_id,
            }
            .into(),
            false,
        );
        self.drain(self.opts.settle);
        let (suspended, _) = self.count_reports(o, window);
        if suspended > 1 {
            problems.push(format!("{suspended} reports while suspended"));
        }
        self.send(
            o,
            &ActivateServiceConnection {
                service_connection_command_code: code,
                instance_id,
            }
            .into(),
            false,
        );
        let (active, _) = self.count_reports(o, window);
        if active < expected {
            problems.push(format!(
                "{active} reports after Activate (at least {expected} expected)"
            ));
        }
        self.send(
            o,
            &TerminateServiceConnection {
                service_connection_command_code: code,
                instance_id,
            }
            .into(),
            false,
        );
        self.drain(self.opts.settle);
        let (after, _) = self.count_reports(o, window);
        if after > 1 {
            problems.push(format!("{after} reports after Terminate"));
        }
        if problems.is_empty() {
            (
                Verdict::Pass,
                format!("confirmed at {rate:.2} Hz: {flagged} reports, none while suspended, {active} after Activate, none after Terminate"),
            )
        } else {
            (Verdict::Fail, problems.join("; "))
        }
    }
}
