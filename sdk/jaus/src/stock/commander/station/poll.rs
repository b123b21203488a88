//! What each tick sends: queued commands, control requests and the sensors resumed
//! after an emergency, service connections (or polls where they are not served), status,
//! world-model and mission queries.

use std::time::Duration;

use super::{id, send_std, Station, POSE_PRESENCE, VELOCITY_PRESENCE, VKS_REQUEST};
use crate::component::{Context, CoreState, Interface};
use crate::messages::{
    Message, MissionStatusType, QueryComponentControl, QueryComponentStatus, QueryGlobalPose,
    QueryMissionStatus, QueryVelocityState, QueryVksObjects, ReportGlobalPose, ReportVelocityState,
    Resume,
};
use crate::stock::commander::keeper::ControlEvent;
use crate::{Address, JausMessage};

impl Station {
    /// Sends what is due: queued commands, control requests, service connections (or
    /// polls where they are not served), status, world-model and mission queries.
    pub fn tick<I: Interface>(&mut self, ctx: &mut Context<'_, I>) {
        let now = ctx.now();
        let me = ctx.address();
        self.me = Some(me);
        self.clock = Some(now);
        while let Some(cmd) = self.pending.pop_front() {
            self.execute(ctx, cmd);
        }
        self.wake_sensors(ctx);
        for e in self.keeper.tick(ctx) {
            match e {
                ControlEvent::Gained(a) if self.waking.iter().any(|w| w.0 == a) => {
                    ctx.send_core(a, Resume {});
                }
                ControlEvent::Gained(a) => self.notice(false, format!("{a}: control gained")),
                ControlEvent::Lost(a) => {
                    self.notice(true, format!("{a}: control lost; asking again"));
                }
                ControlEvent::State(..) => {}
            }
        }
        // Follow every pose and velocity sensor.
        let sensors: Vec<(Address, u16, f64, u32)> = self
            .tree
            .components
            .keys()
            .filter_map(|a| match a.component {
                id::GLOBAL_POSE => Some((
                    *a,
                    ReportGlobalPose::CODE.0,
                    self.config.pose_rate,
                    u32::from(POSE_PRESENCE),
                )),
                id::VELOCITY => Some((
                    *a,
                    ReportVelocityState::CODE.0,
                    self.config.pose_rate,
                    VELOCITY_PRESENCE,
                )),
                _ => None,
            })
            .collect();
        let mut poll = Vec::new();
        for (a, code, rate, pv) in sensors {
            match self.subscribed.get(&(a, code)) {
                None => {
                    match ctx.create_service_connection(a, crate::CommandCode(code), rate, pv) {
                        Ok(()) => {
                            self.subscribed.insert((a, code), now);
                        }
                        Err(e) => {
                            self.notice(true, format!("{a}: no service connection: {e}"));
                            self.subscribed.insert((a, code), now);
                        }
                    }
                }
                Some(at) => {
                    if now.saturating_duration_since(*at) > self.config.poll_after
                        && !ctx.service_connection_active(a, crate::CommandCode(code))
                    {
                        poll.push((a, code));
                    }
                }
            }
        }
        let poll_period = Duration::from_secs_f64(1.0 / self.config.pose_rate.max(0.1));
        if !poll.is_empty() && self.next_poll.is_none_or(|t| now >= t) {
            self.next_poll = Some(now + poll_period);
            for (a, code) in poll {
                if code == ReportGlobalPose::CODE.0 {
                    send_std(
                        ctx,
                        a,
                        Message::from(QueryGlobalPose {
                            presence_vector: POSE_PRESENCE,
                        }),
                    );
                } else {
                    send_std(
                        ctx,
                        a,
                        Message::from(QueryVelocityState {
                            presence_vector: VELOCITY_PRESENCE as u16,
                        }),
                    );
                }
            }
        }
        if self.next_status.is_none_or(|t| now >= t) {
            self.next_status = Some(now + self.config.status_period);
            let targets: Vec<Address> = self
                .tree
                .components
                .keys()
                .filter(|a| **a != me && a.component != id::NODE_MANAGER)
                .copied()
                .collect();
            for a in targets {
                ctx.send_core(a, QueryComponentStatus {});
                ctx.send_core(a, QueryComponentControl {});
            }
        }
        if self.next_world.is_none_or(|t| now >= t) {
            self.next_world = Some(now + self.config.world_model_period);
            let stores: Vec<Address> = self
                .tree
                .components
                .keys()
                .filter(|a| a.component == id::WORLD_MODEL)
                .copied()
                .collect();
            for a in stores {
                send_std(
                    ctx,
                    a,
                    Message::from(QueryVksObjects {
                        response_presence_vector: 1,
                        request_id: VKS_REQUEST,
                        ..QueryVksObjects::default()
                    }),
                );
            }
        }
        if self.next_mission.is_none_or(|t| now >= t) {
            self.next_mission = Some(now + self.config.mission_period);
            let missions: Vec<(Address, u16)> = self
                .vehicles
                .values()
                .filter_map(|v| v.mission.as_ref().map(|(s, m)| (*s, m.id)))
                .collect();
            for (s, mission_id) in missions {
                send_std(
                    ctx,
                    s,
                    Message::from(QueryMissionStatus {
                        presence_vector: 1,
                        status_type: MissionStatusType::Mission,
                        mission_id,
                        task_id: 0,
                        task_msg_id: 0,
                    }),
                );
            }
        }
    }

    /// Resumes the sensors that came out of an emergency into Standby: a component runs
    /// core commands only from its controller, so control is taken for the Resume and
    /// given back once the sensor reports Ready (or after 5 s without it).
    fn wake_sensors<I: Interface>(&mut self, ctx: &mut Context<'_, I>) {
        let now = ctx.now();
        for a in std::mem::take(&mut self.wake) {
            let kept = self.keeper.kept().any(|(k, ..)| k == a);
            if kept || self.waking.iter().any(|w| w.0 == a) {
                // The operator keeps it (and resumes it) or it is being resumed already.
                continue;
            }
            self.keeper.keep(a);
            self.waking.push((a, now));
        }
        let ready: Vec<Address> = self
            .waking
            .iter()
            .filter(|w| {
                self.known
                    .get(&w.0)
                    .and_then(|k| k.state)
                    .is_some_and(|(s, at)| s == CoreState::Ready && at >= w.1)
            })
            .map(|w| w.0)
            .collect();
        for a in ready {
            self.waking.retain(|w| w.0 != a);
            self.keeper.release(ctx, a);
            self.notice(false, format!("{a}: sensor resumed after the emergency"));
        }
        let expired: Vec<Address> = self
            .waking
            .iter()
            .filter(|w| now.saturating_duration_since(w.1) >= Duration::from_secs(5))
            .map(|w| w.0)
            .collect();
        for a in expired {
            self.waking.retain(|w| w.0 != a);
            self.keeper.release(ctx, a);
            self.notice(true, format!("{a}: not resumed after the emergency (no control or still not Ready after 5 s)"));
        }
    }
}
