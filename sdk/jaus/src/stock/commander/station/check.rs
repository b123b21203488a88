//! Checking an operator's commands before they are queued.

use super::{id, Command, GeoPoint, Station, StationError, MAX_POINTS, MAX_RADIUS};
use crate::Address;

impl Station {
    /// is also recorded as a notice.
    pub fn submit(&mut self, cmd: Command) -> Result<(), StationError> {
        let checked = self.check(&cmd);
        if let Err(e) = &checked {
            self.notice(true, e.to_string());
            return checked;
        }
        if self.pending.len() >= self.config.max_pending {
            let e = StationError::Busy(self.pending.len());
            self.notice(true, e.to_string());
            return Err(e);
        }
        self.pending.push_back(cmd);
        Ok(())
    }

    fn check(&self, cmd: &Command) -> Result<(), StationError> {
        if let Some(t) = cmd.target() {
            if !self.tree.components.contains_key(&t) {
                return Err(StationError::Unknown(t));
            }
        }
        let kind = |target: Address, what, expected, id: u8| {
            if target.component == id {
                Ok(())
            } else {
                Err(StationError::WrongComponent {
                    target,
                    what,
                    expected,
                    id,
                })
            }
        };
        let held = |target: Address, what| {
            if self.keeper.holds(target) {
                Ok(())
            } else {
                Err(StationError::NotInControl { target, what })
            }
        };
        match cmd {
            Command::TakeControl { .. } | Command::ReleaseControl { .. } => Ok(()),
            Command::Emergency { subsystem } | Command::ClearEmergency { subsystem } => {
                if self
                    .tree
                    .components
                    .keys()
                    .any(|a| a.subsystem == *subsystem)
                {
                    Ok(())
                } else {
                    Err(StationError::UnknownSubsystem(*subsystem))
                }
            }
            Command::Resume { target } => held(*target, "Resume"),
            Command::Standby { target } => held(*target, "Standby"),
            Command::Waypoints {
                driver,
                points,
                speed,
            } => {
                kind(
                    *driver,
                    "Set Global Waypoint",
                    "Global Waypoint Driver",
                    id::GLOBAL_WAYPOINT_DRIVER,
                )?;
                self.check_route(points, *speed)?;
                held(*driver, "Set Global Waypoint")
            }
            Command::PathSegments {
                driver,
                points,
                speed,
            } => {
                kind(
                    *driver,
                    "Set Global Path Segment",
                    "Global Path Segment Driver",
                    id::GLOBAL_PATH_SEGMENT_DRIVER,
                )?;
                self.check_route(points, *speed)?;
                held(*driver, "Set Global Path Segment")
            }
            Command::SpoolMission {
                spooler,
                driver,
                points,
                speed,
            } => {
                kind(
                    *spooler,
                    "Spool Mission",
                    "Mission Spooler",
                    id::MISSION_SPOOLER,
                )?;
                kind(
                    *driver,
                    "a mission's moves",
                    "Global Waypoint Driver",
                    id::GLOBAL_WAYPOINT_DRIVER,
                )?;
                if !self.tree.components.contains_key(driver) {
                    return Err(StationError::Unknown(*driver));
                }
                self.check_route(points, *speed)?;
                held(*spooler, "Spool Mission")
            }
            Command::StoreObstacle {
                world_model,
                point,
                radius,
                ..
            } => {
                kind(
                    *world_model,
                    "Create VKS Objects",
                    "World Model Vector Knowledge Store",
                    id::WORLD_MODEL,
                )?;
                self.check_points(std::slice::from_ref(point))?;
                if radius.is_finite() && *radius > 0.0 && *radius <= MAX_RADIUS {
                    Ok(())
                } else {
                    Err(StationError::Radius {
                        value: *radius,
                        max: MAX_RADIUS,
                    })
                }
            }
            Command::Mission { spooler, .. } => {
                held(*spooler, "a mission command")?;
                let spooled = self
                    .vehicles
                    .get(&spooler.subsystem)
                    .and_then(|v| v.mission.as_ref())
                    .is_some_and(|(s, _)| s == spooler);
                if spooled {
                    Ok(())
                } else {
                    Err(StationError::NoMission(*spooler))
                }
            }
        }
    }

    fn check_route(&self, points: &[GeoPoint], speed: f64) -> Result<(), StationError> {
        if points.is_empty() || points.len() > MAX_POINTS {
            return Err(StationError::Points(points.len()));
        }
        self.check_points(points)?;
        if !(speed.is_finite() && speed > 0.0 && speed <= self.config.max_speed) {
            return Err(StationError::Speed {
                value: speed,
                max: self.config.max_speed,
            });
        }
        Ok(())
    }

    fn check_points(&self, points: &[GeoPoint]) -> Result<(), StationError> {
        for (index, p) in points.iter().enumerate() {
            for (field, value, max) in [
                ("latitude", p.latitude, 90.0),
                ("longitude", p.longitude, 180.0),
            ] {
                if !(value.is_finite() && (-max..=max).contains(&value)) {
                    return Err(StationError::Coordinate {
                        index,
                        field,
                        value,
                        min: -max,
                        max,
                    });
                }
            }
        }
        Ok(())
    }
}
