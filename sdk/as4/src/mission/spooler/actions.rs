//! The Mission Spooler's guards and actions: the generated `MissionSpooler` trait over
//! [`Spooler`]'s data.

use std::collections::BTreeMap;
use std::time::Duration;

use jaus::net::as5669a::As4Id;

use super::{Dest, Issued, Outcome, Raise, Record, Spooler, Stage};
use crate::messages::services::mission_spooler as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::services::Arg;
use crate::messages::{
    CommandEvent, CommandResult, ConfirmControl, ConfirmEventRequest, ControlConfirmation,
    InsertMessages, InsertMissionTask, MissionState, MissionStatusLevel, MissionStatusReason,
    MissionTask, QueryMissionPlan, QueryMissionStatus, QuerySpoolingPreferences,
    QueryStoredMissions, QueryTimeout, RejectControl, RejectEventRequest, ReleaseControl,
    RemoveMessages, RemoveMissionTask, ReportMissionPlan, ReportMissionStatus,
    ReportSpoolingPreferences, ReportStoredMissions, ReportTimeout, RequestControl, ResumeMission,
    RunMission, SpoolMission, SpoolingPreference, StoredMission,
};
use crate::mission::plan::{address_of, id_of, Plan};
use crate::outgoing::sender_of;
use crate::service::Outbox;

impl generated::MissionSpooler for Spooler {
    fn is_abort_complete(&self) -> bool {
        true
    }

    fn is_blocking(&self) -> bool {
        self.current
            .as_ref()
            .and_then(Record::next)
            .is_some_and(|n| n.2)
    }

    fn is_blocking_event(&self, msg: &CommandEvent, transport_data: &Receive) -> bool {
        let d = sender_of(transport_data);
        self.current.as_ref().is_some_and(|r| {
            r.by_event(d, msg.event_id)
                .is_some_and(|u| r.waited() == Some(u))
        })
    }

    fn is_blocking_mission_or_task(&self) -> bool {
        false
    }

    fn is_end_of_mission(&self) -> bool {
        self.current.as_ref().and_then(Record::next).is_none()
    }

    fn is_mission_delegated(&self) -> bool {
        false
    }

    fn is_mission_spooled(&self) -> bool {
        self.current.is_some()
    }

    fn is_mission_valid(&self, msg: &SpoolMission) -> bool {
        Plan::new(msg.tasks.clone(), &self.bounds()).is_ok()
    }

    fn is_pause_complete(&self) -> bool {
        true
    }

    fn is_release_control_pending(&self) -> bool {
        false
    }

    fn is_request_control_pending(&self) -> bool {
        false
    }

    fn is_status_known(&self, msg: &QueryMissionStatus) -> bool {
        self.record(msg.mission_id)
            .is_some_and(|r| match (msg.message_uid, msg.task_id) {
                (Some(uid), _) => r.plan.find(uid).is_some(),
                (None, Some(t)) => r.plan.task(t).is_some(),
                (None, None) => true,
            })
    }

    fn is_run_valid(&self, msg: &RunMission) -> bool {
        self.run_refusal(msg).is_none()
    }

    fn is_spooler_present(&self) -> bool {
        // Nothing is delegated: every message goes as a command event.
        false
    }

    fn is_update_valid(&self, args: &[Arg<'_>]) -> bool {
        let Some(r) = self.current.as_ref() else {
            return false;
        };
        let (issued, b) = (r.issued_uids(), self.bounds());
        args.iter().all(|a| match a {
            Arg::RemoveMessages(m) => {
                m.mission_id == r.id && r.plan.remove_messages(m, &issued, &b).is_ok()
            }
            Arg::InsertMessages(m) => {
                m.mission_id == r.id && r.plan.insert_messages(m, &issued, &b).is_ok()
            }
            Arg::RemoveMissionTask(m) => {
                m.mission_id == r.id && r.plan.remove_task(m, &issued, &b).is_ok()
            }
            Arg::InsertMissionTask(m) => {
                m.mission_id == r.id && r.plan.insert_task(m, &issued, &b).is_ok()
            }
            _ => true,
        })
    }

    fn is_valid_event(&self, msg: &CommandEvent, transport_data: &Receive) -> bool {
        let d = sender_of(transport_data);
        self.current
            .as_ref()
            .is_some_and(|r| r.by_event(d, msg.event_id).is_some())
    }

    fn clear_mission(&mut self) {
        for (d, _) in std::mem::take(&mut self.dests) {
            self.outbox.send(d, &ReleaseControl {});
        }
        if let Some(r) = self.current.take() {
            while self.retained.len() >= self.config.max_missions.max(1) {
                self.retained.pop_front();
            }
            self.retained.push_back(r);
        }
        self.raised.retain(|r| *r == Raise::ControlRegained);
    }

    fn confirm_pending_release(&mut self) {}

    fn grant_pending_request(&mut self) {}

    fn insert_messages(&mut self, msg: &InsertMessages) {
        self.edit("InsertMessages", msg.mission_id, |p, i, b| {
            p.insert_messages(msg, i, b)
        });
    }

    fn insert_mission_task(&mut self, msg: &InsertMissionTask) {
        self.edit("InsertMissionTask", msg.mission_id, |p, i, b| {
            p.insert_task(msg, i, b)
        });
    }

    fn next_iteration(&mut self) {
        match self.current.as_ref() {
            Some(r) if r.next().is_some() => self.raise(Raise::NextMessage),
            Some(r) if r.complete() => self.raise(Raise::MissionCompleted),
            _ => {}
        }
    }

    fn pause_current_message_execution(&mut self) {
        // What went out stays with its destination; its outcome is still recorded.
        // Nothing further is sent until the mission runs again.
        tracing::debug!("Mission Spooler: mission paused");
    }

    fn pause_current_mission_execution(&mut self) {
        tracing::debug!("Mission Spooler: mission held");
    }

    fn record_command_event(&mut self, msg: &CommandEvent, transport_data: &Receive) {
        let d = sender_of(transport_data);
        match self
            .current
            .as_ref()
            .and_then(|r| r.by_event(d, msg.event_id))
        {
            Some(uid) => {
                let o = if msg.command_result == CommandResult::Successful {
                    Outcome::Successful
                } else {
                    Outcome::Unsuccessful
                };
                self.finish(uid, o);
            }
            None => {
                self.stats.unmatched_answers += 1;
                tracing::debug!(from = %d, event = msg.event_id, "Mission Spooler: a Command Event of no message awaited");
            }
        }
    }

    fn record_control_answer(&mut self, msg: &ConfirmControl, transport_data: &Receive) {
        let d = sender_of(transport_data);
        let accepted = msg.response_code == ControlConfirmation::ControlAccepted;
        match self.dests.get_mut(&d) {
            Some(dest) if accepted => {
                let first = !dest.held;
                dest.held = true;
                dest.deadline = None;
                if first {
                    self.outbox.send(d, &QueryTimeout {});
                    let waiting: Vec<u16> = self
                        .current
                        .iter()
                        .flat_map(|r| {
                            r.plan.run_order().into_iter().filter_map(|p| {
                                let m = r.plan.message(p)?;
                                let i = r.issued.get(&m.uid)?;
                                (i.dest == d && i.stage == Stage::WaitingControl).then_some(m.uid)
                            })
                        })
                        .collect();
                    for uid in waiting {
                        self.send_command(uid);
                    }
                }
            }
            Some(_) => {
                let why = format!("refused control ({:?})", msg.response_code);
                self.lose(d, &why);
            }
            None => {
                self.stats.unmatched_answers += 1;
                if accepted {
                    // Control the mission no longer needs (released before the answer).
                    self.outbox.send(d, &ReleaseControl {});
                }
            }
        }
    }

    fn record_control_lost(&mut self, msg: &RejectControl, transport_data: &Receive) {
        let d = sender_of(transport_data);
        if self.dests.contains_key(&d) {
            let why = format!("ended control ({:?})", msg.response_code);
            self.lose(d, &why);
        }
    }

    fn record_control_timeout(&mut self, msg: &ReportTimeout, transport_data: &Receive) {
        let d = sender_of(transport_data);
        let now = self.now;
        if let Some(dest) = self.dests.get_mut(&d).filter(|x| x.held) {
            dest.refresh = if msg.timeout > 0 {
                let period = Duration::from_millis(u64::from(msg.timeout) * 500);
                now.and_then(|n| n.checked_add(period))
                    .map(|at| (period, at))
            } else {
                None
            };
        }
    }

    fn record_event_confirmed(&mut self, msg: &ConfirmEventRequest, transport_data: &Receive) {
        let d = sender_of(transport_data);
        let uid = self
            .current
            .as_ref()
            .and_then(|r| r.by_request(d, msg.request_id));
        match uid.and_then(|u| self.current.as_mut()?.issued.get_mut(&u)) {
            Some(Issued {
                stage: Stage::Out { event, .. },
                ..
            }) if event.is_none() => *event = Some(msg.event_id),
            _ => {
                self.stats.unmatched_answers += 1;
                tracing::debug!(from = %d, request = msg.request_id, "Mission Spooler: a Confirm Event Request of no command awaited");
            }
        }
    }

    fn record_event_rejected(&mut self, msg: &RejectEventRequest, transport_data: &Receive) {
        let d = sender_of(transport_data);
        let uid = self
            .current
            .as_ref()
            .and_then(|r| r.by_request(d, msg.request_id));
        match uid {
            Some(uid) => {
                tracing::warn!(uid, from = %d, code = ?msg.response_code, reason = msg.error_message.as_deref().unwrap_or(""), "Mission Spooler: the destination rejected the command");
                self.finish(uid, Outcome::Rejected);
            }
            None => self.stats.unmatched_answers += 1,
        }
    }

    fn record_mission_status(&mut self, msg: &ReportMissionStatus) {
        // Nothing is delegated: a status from another spooler is only logged.
        tracing::debug!(?msg, "Mission Spooler: a mission status not awaited");
    }

    fn remove_messages(&mut self, msg: &RemoveMessages) {
        self.edit("RemoveMessages", msg.mission_id, |p, i, b| {
            p.remove_messages(msg, i, b)
        });
    }

    fn remove_mission_task(&mut self, msg: &RemoveMissionTask) {
        self.edit("RemoveMissionTask", msg.mission_id, |p, i, b| {
            p.remove_task(msg, i, b)
        });
    }

    fn report_mission_aborted(&mut self) {
        self.end_last(MissionState::Aborted, MissionStatusReason::NoError);
    }

    fn report_mission_finished(&mut self) {
        self.end_last(MissionState::Finished, MissionStatusReason::NoError);
    }

    fn report_mission_paused(&mut self) {
        let reason = self
            .current
            .as_ref()
            .and_then(|r| r.failure)
            .unwrap_or(MissionStatusReason::NoError);
        self.report_to_creator(MissionState::Paused, reason);
    }

    fn report_status_to_parent(&mut self) {
        let Some(uid) = self.changed.take() else {
            return;
        };
        let Some(r) = self.current.as_ref() else {
            return;
        };
        let (status, secondary_status) = Self::message_status(r, uid);
        let to = r.creator;
        self.outbox.send(
            to,
            &ReportMissionStatus {
                level: MissionStatusLevel::Message,
                id: uid,
                status,
                secondary_status,
            },
        );
    }

    fn resume_mission(&mut self, msg: &ResumeMission) {
        let Some(r) = self.current.as_mut() else {
            return;
        };
        if msg.mission_id != r.id {
            tracing::warn!(
                asked = msg.mission_id,
                stored = r.id,
                "Mission Spooler: Resume Mission names another mission; the one stored resumes"
            );
        }
        r.started = true;
        if r.waited().is_none() {
            self.raise(Raise::Unblocked);
        }
        self.next_iteration();
    }

    fn send_abort_mission(&mut self) {}

    fn send_next_message(&mut self) {
        let Some((uid, dest, blocking)) = self.current.as_ref().and_then(Record::next) else {
            return;
        };
        let held = self.dests.get(&dest).is_some_and(|d| d.held);
        if let Some(r) = self.current.as_mut() {
            r.issued.insert(
                uid,
                Issued {
                    dest,
                    blocking,
                    stage: Stage::WaitingControl,
                },
            );
        }
        if held {
            self.send_command(uid);
        } else if !self.dests.contains_key(&dest) {
            let deadline = self.after(self.config.control_timeout);
            self.dests.insert(
                dest,
                Dest {
                    held: false,
                    deadline,
                    refresh: None,
                },
            );
            let authority_code = self.request_authority();
            self.outbox.send(dest, &RequestControl { authority_code });
        }
    }

    fn send_pause_mission(&mut self) {}

    fn send_report_mission_plan(&mut self, msg: &QueryMissionPlan, transport_data: &Receive) {
        let report = match self.record(Some(msg.mission_id)) {
            Some(r) if r.end.is_none() => {
                let mut task = r.plan.tasks.first().cloned().unwrap_or_default();
                task.messages.retain(|m| !r.issued.contains_key(&m.uid));
                ReportMissionPlan {
                    mission_id: r.id,
                    source_id: r.source,
                    task,
                }
            }
            Some(r) => ReportMissionPlan {
                mission_id: r.id,
                source_id: r.source,
                task: MissionTask::default(),
            },
            None => ReportMissionPlan {
                mission_id: msg.mission_id,
                ..Default::default()
            },
        };
        self.outbox.reply(transport_data, &report);
    }

    fn send_report_mission_status(&mut self, msg: &QueryMissionStatus, transport_data: &Receive) {
        let Some(r) = self.record(msg.mission_id) else {
            tracing::debug!(?msg.mission_id, "Mission Spooler: status of no mission held: not answered");
            return;
        };
        let (level, id, (status, secondary_status)) = if let Some(uid) = msg.message_uid {
            if r.plan.find(uid).is_none() {
                return;
            }
            (
                MissionStatusLevel::Message,
                uid,
                Self::message_status(r, uid),
            )
        } else if let Some(t) = msg.task_id {
            let Some(i) = r.plan.task(t) else {
                return;
            };
            (MissionStatusLevel::Task, t, self.task_status(r, i))
        } else {
            (MissionStatusLevel::Mission, r.id, self.mission_status(r))
        };
        self.outbox.reply(
            transport_data,
            &ReportMissionStatus {
                level,
                id,
                status,
                secondary_status,
            },
        );
    }

    fn send_report_spooling_preferences(
        &mut self,
        _msg: &QuerySpoolingPreferences,
        transport_data: &Receive,
    ) {
        let n = u16::try_from(self.config.bounds.max_messages).unwrap_or(u16::MAX);
        self.outbox.reply(
            transport_data,
            &ReportSpoolingPreferences {
                preference: SpoolingPreference::MessageCount(n),
            },
        );
    }

    fn send_report_stored_missions(
        &mut self,
        _msg: &QueryStoredMissions,
        transport_data: &Receive,
    ) {
        let missions = self
            .current
            .iter()
            .chain(self.retained.iter().rev())
            .take(usize::from(u16::MAX))
            .map(|r| StoredMission {
                mission_id: r.id,
                creator_id: address_of(r.creator),
            })
            .collect();
        self.outbox
            .reply(transport_data, &ReportStoredMissions { missions });
    }

    fn set_release_control_pending(&mut self, _msg: &ReleaseControl, _transport_data: &Receive) {}

    fn set_request_control_pending(&mut self, _msg: &RequestControl, _transport_data: &Receive) {}

    fn set_timer(&mut self) {
        self.timer = self.after(self.config.control_timeout);
    }

    fn spool_next_message(&mut self) {
        tracing::warn!("Mission Spooler: delegation to another spooler is not served");
    }

    fn start_mission(&mut self, msg: &RunMission) {
        let Some(r) = self.current.as_mut() else {
            return;
        };
        r.started = true;
        let order = r.plan.run_order();
        let start = match (msg.message_uid, msg.task_id) {
            (Some(uid), _) => r.plan.find(uid),
            (None, Some(t)) => r
                .plan
                .task(t)
                .and_then(|i| order.iter().copied().find(|p| p.0 == i)),
            _ => None,
        };
        if let Some(start) = start {
            let skipped: Vec<(u16, As4Id)> = order
                .iter()
                .take_while(|p| **p != start)
                .filter_map(|p| r.plan.message(*p))
                .filter(|m| !r.issued.contains_key(&m.uid))
                .map(|m| (m.uid, id_of(&m.destination_id)))
                .collect();
            for (uid, dest) in skipped {
                r.issued.insert(
                    uid,
                    Issued {
                        dest,
                        blocking: false,
                        stage: Stage::Done(Outcome::Skipped),
                    },
                );
            }
        }
        self.next_iteration();
    }

    fn store_mission(&mut self, msg: &SpoolMission, transport_data: &Receive) {
        let plan = match Plan::new(msg.tasks.clone(), &self.bounds()) {
            Ok(p) => p,
            Err(r) => {
                self.stats.refused += 1;
                tracing::warn!(field = %r.field, "Mission Spooler: mission not stored: {}", r.why);
                return;
            }
        };
        self.retained.retain(|r| r.id != msg.mission_id);
        self.stats.spooled += 1;
        self.current = Some(Record {
            id: msg.mission_id,
            source: msg.source_id,
            creator: sender_of(transport_data),
            plan,
            issued: BTreeMap::new(),
            started: false,
            failure: None,
            end: None,
        });
    }
}

impl AsMut<Outbox> for Spooler {
    fn as_mut(&mut self) -> &mut Outbox {
        &mut self.outbox
    }
}
