//! Service connections: the connections this component serves (provider table), those
//! it asked for (requester table), Create/Activate/Suspend/Terminate/Confirm Service
//! Connection, and the periodic reports of the connections served.

use std::time::{Duration, Instant};

use super::{Behaviour, Component, Refusal, Refused};
use crate::messages::*;
use crate::{Address, CommandCode, MessageSet};

/// JAUS rates are scaled u16 over [0, 1092] Hz.
pub(super) const MAX_JAUS_RATE: f64 = 1092.0;

pub(super) fn period_of(rate_hz: f64) -> Duration {
    Duration::from_secs_f64(1.0 / rate_hz)
}

/// One service connection this component serves.
#[derive(Debug, Clone)]
struct ServedConnection<M> {
    requester: Address,
    report: CommandCode,
    instance: u8,
    presence: u32,
    query: M,
    period: Duration,
    next_due: Instant,
    active: bool,
    sequence: u16,
}

#[derive(Debug)]
pub(super) struct ProviderTable<M> {
    served: Vec<ServedConnection<M>>,
}

impl<M> Default for ProviderTable<M> {
    fn default() -> Self {
        Self { served: Vec::new() }
    }
}

impl<M> ProviderTable<M> {
    pub(super) fn len(&self) -> usize {
        self.served.len()
    }

    pub(super) fn next_due(&self) -> Option<Instant> {
        self.served
            .iter()
            .filter(|s| s.active)
            .map(|s| s.next_due)
            .min()
    }

    pub(super) fn remove_requester(&mut self, gone: Address) {
        self.served.retain(|s| s.requester != gone);
    }

    fn find(
        &mut self,
        requester: Address,
        report: u16,
        instance: u8,
    ) -> Option<&mut ServedConnection<M>> {
        self.served
            .iter_mut()
            .find(|s| s.requester == requester && s.report.0 == report && s.instance == instance)
    }
}

/// A service connection this component asked for.
#[derive(Debug, Clone)]
struct Subscription {
    provider: Address,
    report: CommandCode,
    instance: Option<u8>,
    rate: f64,
    presence: u32,
    /// When it was asked for or a report last arrived.
    heard: Option<Instant>,
    /// Refusals since the last confirmation: each doubles the wait before it is asked
    /// for again (a sensor with no data yet refuses, then can serve).
    refusals: u32,
}

/// How long a subscription may stay silent before it is asked for again: five periods
/// of the rate asked for, and never less than this.
pub(super) const MIN_SILENCE: Duration = Duration::from_secs(3);

/// Most doublings of the wait after refusals: a connection refused again and again is
/// asked for at most every 32 × the silence allowed (96 s at the least).
const MAX_BACKOFF_SHIFT: u32 = 5;

#[derive(Debug, Default)]
pub(super) struct RequesterTable {
    subs: Vec<Subscription>,
}

impl RequesterTable {
    pub(super) fn add(
        &mut self,
        provider: Address,
        report: CommandCode,
        rate: f64,
        pv: u32,
        max: usize,
    ) -> bool {
        if self
            .subs
            .iter()
            .any(|s| s.provider == provider && s.report == report)
        {
            return true;
        }
        if self.subs.len() >= max {
            return false;
        }
        self.subs.push(Subscription {
            provider,
            report,
            instance: None,
            rate,
            presence: pv,
            heard: None,
            refusals: 0,
        });
        true
    }

    /// A message `code` arrived from `provider` at `now`: a report of one of its
    /// connections keeps that connection alive.
    pub(super) fn heard(&mut self, provider: Address, code: CommandCode, now: Instant) {
        for s in &mut self.subs {
            if s.provider == provider && s.report == code {
                s.heard = Some(now);
            }
        }
    }

    /// `gone` left the system: its connections are to be asked for again.
    pub(super) fn provider_gone(&mut self, gone: Address) {
        for s in &mut self.subs {
            if s.provider == gone {
                s.instance = None;
            }
        }
    }

    /// The next connection silent for too long at `now`, marked as asked for again:
    /// (provider, report, rate, presence vector). Subscriptions never heard of start
    /// their clock here.
    pub(super) fn due_again(&mut self, now: Instant) -> Option<(Address, CommandCode, f64, u32)> {
        for s in &mut self.subs {
            let Some(heard) = s.heard else {
                s.heard = Some(now);
                continue;
            };
            let period = Duration::from_secs_f64(5.0 / s.rate.max(1e-3));
            let wait = period.max(MIN_SILENCE) * (1 << s.refusals.min(MAX_BACKOFF_SHIFT));
            if now.saturating_duration_since(heard) > wait {
                s.instance = None;
                s.heard = Some(now);
                return Some((s.provider, s.report, s.rate, s.presence));
            }
        }
        None
    }

    pub(super) fn remove(&mut self, provider: Address, report: CommandCode) -> Option<u8> {
        let i = self
            .subs
            .iter()
            .position(|s| s.provider == provider && s.report == report)?;
        self.subs.remove(i).instance
    }

    pub(super) fn is_active(&self, provider: Address, report: CommandCode) -> bool {
        self.subs
            .iter()
            .any(|s| s.provider == provider && s.report == report && s.instance.is_some())
    }
}

/// The query whose report a service connection or event streams, built from the
/// report code and a presence vector: the query body is the presence vector in the
/// query's own width (0, 1, 2 or 4 bytes, whichever decodes), so no per-message table
/// is needed.
pub(super) fn query_for<M: MessageSet>(report: CommandCode, presence: u32) -> Option<M> {
    let code = M::query_of(report)?;
    let bytes = presence.to_le_bytes();
    [0usize, 1, 2, 4]
        .into_iter()
        .find_map(|n| M::decode(code, &bytes[..n]).ok())
}

impl<B: Behaviour> Component<B> {
    pub(super) fn create_sc(&mut self, source: Address, m: &CreateServiceConnection) {
        let report = CommandCode(m.service_connection_command_code);
        let rate = m.requested_periodic_update_rate;
        let refuse = |c: &mut Self, code: ServiceConnectionResponse| {
            c.rt.stats.subscriptions_refused += 1;
            let msg = ConfirmServiceConnection {
                service_connection_command_code: report.0,
                instance_id: 0,
                confirmed_periodic_update_rate: 0.0,
                response_code: code,
            };
            c.rt.send(source, msg.into(), true, 0);
        };
        let Some(query) = query_for(report, m.presence_vector) else {
            return refuse(self, ServiceConnectionResponse::ComponentNotCapable);
        };
        if !(rate.is_finite() && rate > 0.0) {
            return refuse(self, ServiceConnectionResponse::InvalidParameter);
        }
        match self.answer(source, &query) {
            Ok(_) => {}
            Err(Refused::Unsupported) => {
                return refuse(self, ServiceConnectionResponse::ComponentNotCapable)
            }
            Err(_) => return refuse(self, ServiceConnectionResponse::InvalidParameter),
        }
        let granted = rate.min(self.rt.config.max_rate_hz).min(MAX_JAUS_RATE);
        let now = self.rt.now;
        let table = &mut self.rt.provider.served;
        // Same requester, code and presence vector: re-initialise that connection.
        let existing = table.iter().position(|s| {
            s.requester == source && s.report == report && s.presence == m.presence_vector
        });
        let instance = match existing {
            Some(i) => table[i].instance,
            None => {
                if table.len() >= self.rt.config.max_service_connections {
                    return refuse(self, ServiceConnectionResponse::ConnectionRefused);
                }
                match (0..=255u8).find(|i| {
                    !table
                        .iter()
                        .any(|s| s.requester == source && s.report == report && s.instance == *i)
                }) {
                    Some(i) => i,
                    None => return refuse(self, ServiceConnectionResponse::ConnectionRefused),
                }
            }
        };
        let served = ServedConnection {
            requester: source,
            report,
            instance,
            presence: m.presence_vector,
            query,
            period: period_of(granted),
            next_due: now,
            active: true,
            sequence: 0,
        };
        match existing {
            Some(i) => table[i] = served,
            None => table.push(served),
        }
        let msg = ConfirmServiceConnection {
            service_connection_command_code: report.0,
            instance_id: instance,
            confirmed_periodic_update_rate: granted,
            response_code: ServiceConnectionResponse::Successful,
        };
        self.rt.send(source, msg.into(), true, 0);
    }

    pub(super) fn sc_set_active(
        &mut self,
        source: Address,
        code: u16,
        instance: u8,
        active: bool,
    ) -> Result<(), Refusal> {
        let now = self.rt.now;
        match self.rt.provider.find(source, code, instance) {
            Some(s) => {
                if active && !s.active {
                    s.next_due = now;
                }
                s.active = active;
                Ok(())
            }
            None => Err(Refusal::Vendor(Refused::Invalid(format!(
                "no service connection 0x{code:04X}/{instance} from {source}"
            )))),
        }
    }

    /// Terminate Service Connection: from the requester, ends the connection this
    /// component serves; from a provider, a connection this component requested.
    pub(super) fn terminate_sc(&mut self, source: Address, m: &TerminateServiceConnection) {
        let (code, inst) = (m.service_connection_command_code, m.instance_id);
        let before = self.rt.provider.served.len();
        self.rt
            .provider
            .served
            .retain(|s| !(s.requester == source && s.report.0 == code && s.instance == inst));
        if before == self.rt.provider.served.len() {
            // A provider ending a connection this component requested.
            self.rt.requester.subs.retain(|s| {
                !(s.provider == source && s.report.0 == code && s.instance == Some(inst))
            });
        }
    }

    pub(super) fn confirm_sc(
        &mut self,
        now: Instant,
        source: Address,
        m: &ConfirmServiceConnection,
    ) {
        let code = CommandCode(m.service_connection_command_code);
        let sub = self
            .rt
            .requester
            .subs
            .iter_mut()
            .find(|s| s.provider == source && s.report == code);
        match (sub, m.response_code) {
            (Some(s), ServiceConnectionResponse::Successful) => {
                s.instance = Some(m.instance_id);
                s.refusals = 0;
            }
            (Some(s), response) => {
                // Kept and asked for again later, each refusal waiting twice as long: a
                // provider that cannot serve yet (a sensor before its first data, a
                // component still initialising) serves later. Ending the subscription
                // is the behaviour's call (`unsubscribe`).
                s.instance = None;
                s.heard = Some(now);
                s.refusals = s.refusals.saturating_add(1);
                tracing::debug!(provider = %source, report = %code, ?response, refusals = s.refusals, "service connection refused; asked for again later");
            }
            (None, ServiceConnectionResponse::Successful) => {
                // A connection nobody here asked for: end it (as OpenJAUS does).
                let t = TerminateServiceConnection {
                    service_connection_command_code: code.0,
                    instance_id: m.instance_id,
                };
                self.rt.send(source, t.into(), true, 0);
            }
            (None, _) => {}
        }
    }

    pub(super) fn run_service_connections(&mut self, now: Instant) {
        for i in 0..self.rt.provider.served.len() {
            let s = &self.rt.provider.served[i];
            if !s.active || s.next_due > now {
                continue;
            }
            let (requester, query) = (s.requester, s.query.clone());
            let result = self.answer(requester, &query);
            let s = &mut self.rt.provider.served[i];
            // Periods that passed without a report (the component was not run in
            // time): the rate is kept, the missed reports are counted, not sent late.
            let late = now.saturating_duration_since(s.next_due);
            if !s.period.is_zero() && late >= s.period {
                self.rt.stats.reports_missed += (late.as_nanos() / s.period.as_nanos()) as u64;
            }
            s.next_due = super::next_after(s.next_due, s.period, now);
            match result {
                Ok(report) => {
                    let seq = s.sequence;
                    s.sequence = s.sequence.wrapping_add(1);
                    self.rt.send_set(requester, report, true, seq);
                }
                Err(_) => self.rt.stats.report_failures += 1,
            }
        }
    }
}
