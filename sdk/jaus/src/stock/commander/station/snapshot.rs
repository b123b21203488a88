//! What the station knows, as the [`SystemView`] a user interface draws.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use super::{id, Station};
use crate::stock::commander::view::{
    ComponentView, NodeView, Notice, PoseView, Roles, SubsystemView, SystemView,
};

impl Station {
    /// `unix_now` (the wall clock at `now`, since the Unix epoch) dates the notices and
    /// poses for the user interface: the station itself reads no clock.
    pub fn view(&self, now: Instant, unix_now: Duration, trails: bool) -> SystemView {
        let age = |t: Instant| now.saturating_duration_since(t).as_secs_f64();
        let unix_ms_of = |t: Instant| unix_now.as_secs_f64() * 1e3 - age(t) * 1e3;
        let role = |ss: u8, id: u8| self.find(ss, id).map(|a| a.to_string());
        let part1_name = |id: u8| {
            crate::components::COMPONENTS
                .iter()
                .find(|c| c.id == id)
                .map_or_else(|| format!("component {id}"), |c| c.name.to_string())
        };
        let mut subsystems: BTreeMap<u8, SubsystemView> = BTreeMap::new();
        for (a, name) in &self.tree.components {
            let s = subsystems
                .entry(a.subsystem)
                .or_insert_with(|| SubsystemView {
                    id: a.subsystem,
                    name: self.tree.subsystems.get(&a.subsystem).cloned().flatten(),
                    ..SubsystemView::default()
                });
            if s.nodes.last().is_none_or(|n| n.id != a.node) {
                s.nodes.push(NodeView {
                    id: a.node,
                    name: self
                        .tree
                        .nodes
                        .get(&(a.subsystem, a.node))
                        .cloned()
                        .flatten(),
                    components: Vec::new(),
                });
            }
            let k = self.known.get(a);
            let keeping = self.keeper.kept().find(|k| k.0 == *a);
            if let Some(n) = s.nodes.last_mut() {
                n.components.push(ComponentView {
                    address: a.to_string(),
                    name: name.clone().unwrap_or_else(|| part1_name(a.component)),
                    state: k.and_then(|k| k.state).map(|s| format!("{:?}", s.0)),
                    state_age_s: k.and_then(|k| k.state).map(|s| age(s.1)),
                    controller: k.and_then(|k| k.controller).map(|c| c.0.to_string()),
                    controller_authority: k.and_then(|k| k.controller).map(|c| c.1),
                    held: self.keeper.holds(*a),
                    keeping: keeping.map(|k| k.1.unwrap_or(0)),
                });
            }
        }
        for (id, s) in &mut subsystems {
            s.roles = Roles {
                global_pose: role(*id, id::GLOBAL_POSE),
                local_pose: role(*id, id::LOCAL_POSE),
                velocity: role(*id, id::VELOCITY),
                primitive_driver: role(*id, id::PRIMITIVE_DRIVER),
                waypoint_driver: role(*id, id::GLOBAL_WAYPOINT_DRIVER),
                path_segment_driver: role(*id, id::GLOBAL_PATH_SEGMENT_DRIVER),
                spooler: role(*id, id::MISSION_SPOOLER),
                world_model: role(*id, id::WORLD_MODEL),
            };
            let statuses = self
                .known
                .iter()
                .filter(|(a, _)| a.subsystem == *id)
                .filter_map(|(_, k)| k.state.map(|s| s.1));
            let Some(v) = self.vehicles.get(id) else {
                continue;
            };
            let heard = v
                .pose
                .map(|p| p.1)
                .into_iter()
                .chain(v.velocity.map(|p| p.1))
                .chain(statuses)
                .max();
            s.heard_s = heard.map(age);
            let followed = v.pose.map(|p| p.1).or(heard);
            // The station's own subsystem is not watched, so never stale.
            let own = self.me.is_some_and(|m| m.subsystem == *id);
            s.stale =
                !own && followed.is_none_or(|t| age(t) > self.config.stale_after.as_secs_f64());
            s.pose = v.pose.map(|(p, t)| PoseView {
                age_s: age(t),
                received_unix_ms: unix_ms_of(t),
                ..p
            });
            s.velocity = v.velocity.map(|v| v.0);
            s.emergency = v.emergency;
            s.trail = if trails {
                v.trail.iter().copied().collect()
            } else {
                Vec::new()
            };
            s.pose_count = v.pose_count;
            s.objects.clone_from(&v.objects);
            s.mission = v.mission.as_ref().map(|m| m.1.clone());
            s.route.clone_from(&v.route);
        }
        SystemView {
            origin: self.frame.map(|f| (f.latitude, f.longitude)),
            subsystems: subsystems.into_values().collect(),
            notices: self
                .notices
                .iter()
                .map(|(at, n)| Notice {
                    unix_ms: at.map_or(unix_now.as_millis() as u64, |t| unix_ms_of(t) as u64),
                    ..n.clone()
                })
                .collect(),
            notice_count: self.notice_count,
        }
    }
}
