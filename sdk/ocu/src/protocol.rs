//! What the page sends: one JSON object per operator action, turned into a
//! [`Command`] for the station. Anything malformed becomes a [`PageError`] that names the
//! field, shown on the page as an error notice.
//!
//! ```json
//! {"op": "take", "target": "1.1.45.1", "authority": 5}
//! {"op": "release", "target": "1.1.45.1"}
//! {"op": "emergency", "subsystem": 1}          {"op": "clear_emergency", "subsystem": 1}
//! {"op": "resume", "target": "1.1.45.1"}       {"op": "standby", "target": "1.1.45.1"}
//! {"op": "waypoints", "driver": "1.1.45.1", "speed": 2.0, "points": [{"x": 10, "y": 5}]}
//! {"op": "path", "driver": "1.1.47.1", "speed": 2.0, "points": [{"lat": 38.9, "lon": -77.0}]}
//! {"op": "spool", "spooler": "1.1.36.1", "driver": "1.1.45.1", "speed": 2.0, "points": [...]}
//! {"op": "mission", "spooler": "1.1.36.1", "action": "run"}   (run, pause, resume, abort)
//! {"op": "obstacle", "world_model": "1.1.61.1", "radius": 0.5, "points": [{"x": 4, "y": 1}]}
//! ```
//!
//! Points are metres east (`x`) and north (`y`) of the map's origin, or WGS 84 degrees
//! (`lat`, `lon`).

use jaus::stock::commander::{Command, GeoPoint, MissionAction};
use jaus::stock::geo::LocalFrame;
use jaus::stock::nalgebra::Vector2;
use jaus::Address;
use serde_json::Value;

/// Why a page message is not a command.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PageError {
    /// Not a JSON object.
    #[error("not a JSON object: {0}")]
    Json(String),
    /// A field is missing or of the wrong type.
    #[error("{op}: field `{field}`: {why}")]
    Field {
        /// The operation.
        op: String,
        /// The field.
        field: String,
        /// What is wrong.
        why: String,
    },
    /// Unknown operation.
    #[error("unknown operation `{0}` (take, release, emergency, clear_emergency, resume, standby, waypoints, path, spool, mission, obstacle)")]
    Op(String),
    /// Points given in map metres before any position arrived.
    #[error("{0}: the map has no origin yet (no position received): give lat/lon")]
    NoOrigin(String),
}

struct Fields<'a> {
    op: &'a str,
    v: &'a Value,
}

impl Fields<'_> {
    fn err(&self, field: &str, why: impl Into<String>) -> PageError {
        PageError::Field {
            op: self.op.to_string(),
            field: field.to_string(),
            why: why.into(),
        }
    }

    fn address(&self, field: &str) -> Result<Address, PageError> {
        let s = self.v[field]
            .as_str()
            .ok_or_else(|| self.err(field, "expected an address such as \"1.1.45.1\""))?;
        s.parse::<Address>()
            .map_err(|e| self.err(field, format!("`{s}`: {e}")))
    }

    fn u8(&self, field: &str) -> Result<u8, PageError> {
        self.v[field]
            .as_u64()
            .and_then(|n| u8::try_from(n).ok())
            .ok_or_else(|| {
                self.err(
                    field,
                    format!("expected an integer 0-255, got {}", self.v[field]),
                )
            })
    }

    fn number(&self, field: &str) -> Result<f64, PageError> {
        self.v[field]
            .as_f64()
            .filter(|x| x.is_finite())
            .ok_or_else(|| self.err(field, format!("expected a number, got {}", self.v[field])))
    }

    fn points(&self, frame: Option<&LocalFrame>) -> Result<Vec<GeoPoint>, PageError> {
        let list = self.v["points"]
            .as_array()
            .ok_or_else(|| self.err("points", "expected a list of {x, y} or {lat, lon}"))?;
        list.iter()
            .enumerate()
            .map(|(i, p)| {
                let num = |k: &str| {
                    p[k].as_f64().filter(|x| x.is_finite()).ok_or_else(|| {
                        self.err(
                            &format!("points[{i}].{k}"),
                            format!("expected a number, got {}", p[k]),
                        )
                    })
                };
                if p.get("lat").is_some() || p.get("lon").is_some() {
                    Ok(GeoPoint {
                        latitude: num("lat")?,
                        longitude: num("lon")?,
                    })
                } else {
                    let (x, y) = (num("x")?, num("y")?);
                    let f = frame.ok_or_else(|| PageError::NoOrigin(self.op.to_string()))?;
                    // The page's (east, north) as the frame's (north, east).
                    let (latitude, longitude) = f.to_global(Vector2::new(y, x));
                    Ok(GeoPoint {
                        latitude,
                        longitude,
                    })
                }
            })
            .collect()
    }
}

/// Reads one page message; `frame` places map metres.
pub fn parse(text: &str, frame: Option<&LocalFrame>) -> Result<Command, PageError> {
    let v: Value = serde_json::from_str(text).map_err(|e| PageError::Json(e.to_string()))?;
    if !v.is_object() {
        return Err(PageError::Json(format!("{v}")));
    }
    let op = v["op"].as_str().unwrap_or("");
    let f = Fields { op, v: &v };
    Ok(match op {
        "take" => Command::TakeControl {
            target: f.address("target")?,
            authority: f.u8("authority")?,
        },
        "release" => Command::ReleaseControl {
            target: f.address("target")?,
        },
        "emergency" => Command::Emergency {
            subsystem: f.u8("subsystem")?,
        },
        "clear_emergency" => Command::ClearEmergency {
            subsystem: f.u8("subsystem")?,
        },
        "resume" => Command::Resume {
            target: f.address("target")?,
        },
        "standby" => Command::Standby {
            target: f.address("target")?,
        },
        "waypoints" => Command::Waypoints {
            driver: f.address("driver")?,
            points: f.points(frame)?,
            speed: f.number("speed")?,
        },
        "path" => Command::PathSegments {
            driver: f.address("driver")?,
            points: f.points(frame)?,
            speed: f.number("speed")?,
        },
        "spool" => Command::SpoolMission {
            spooler: f.address("spooler")?,
            driver: f.address("driver")?,
            points: f.points(frame)?,
            speed: f.number("speed")?,
        },
        "mission" => Command::Mission {
            spooler: f.address("spooler")?,
            action: match v["action"].as_str() {
                Some("run") => MissionAction::Run,
                Some("pause") => MissionAction::Pause,
                Some("resume") => MissionAction::Resume,
                Some("abort") => MissionAction::Abort,
                _ => return Err(f.err("action", "expected run, pause, resume or abort")),
            },
        },
        "obstacle" => {
            let points = f.points(frame)?;
            let [point] = points[..] else {
                return Err(f.err("points", "expected one point"));
            };
            Command::StoreObstacle {
                world_model: f.address("world_model")?,
                point,
                radius: f.number("radius")?,
                class: v["class"]
                    .as_u64()
                    .and_then(|n| u16::try_from(n).ok())
                    .unwrap_or(1),
            }
        }
        other => return Err(PageError::Op(other.to_string())),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_every_operation_and_places_map_points() {
        let frame = LocalFrame::new(38.0, -77.0, 0.0);
        let c = parse(
            r#"{"op":"waypoints","driver":"1.1.45.1","speed":2,"points":[{"x":0,"y":0},{"lat":38.1,"lon":-77.1}]}"#,
            Some(&frame),
        )
        .unwrap();
        let Command::Waypoints {
            driver,
            points,
            speed,
        } = c
        else {
            panic!("{c:?}")
        };
        assert_eq!(driver, Address::new(1, 1, 45, 1));
        assert_eq!(speed, 2.0);
        assert!((points[0].latitude - 38.0).abs() < 1e-9);
        assert!((points[1].longitude + 77.1).abs() < 1e-9);
        assert_eq!(
            parse(
                r#"{"op":"mission","spooler":"1.1.36.1","action":"pause"}"#,
                None
            )
            .unwrap(),
            Command::Mission {
                spooler: Address::new(1, 1, 36, 1),
                action: MissionAction::Pause
            }
        );
        assert_eq!(
            parse(r#"{"op":"emergency","subsystem":3}"#, None).unwrap(),
            Command::Emergency { subsystem: 3 }
        );
        let c = parse(
            r#"{"op":"obstacle","world_model":"1.1.61.1","radius":0.5,"class":7,"points":[{"x":0,"y":0}]}"#,
            Some(&frame),
        )
        .unwrap();
        let Command::StoreObstacle {
            world_model,
            point,
            radius,
            class,
        } = c
        else {
            panic!("{c:?}")
        };
        assert_eq!(
            (world_model, radius, class),
            (Address::new(1, 1, 61, 1), 0.5, 7)
        );
        assert!((point.latitude - 38.0).abs() < 1e-9);
        let e = parse(
            r#"{"op":"obstacle","world_model":"1.1.61.1","radius":0.5,"points":[{"x":0,"y":0},{"x":1,"y":1}]}"#,
            Some(&frame),
        )
        .unwrap_err();
        assert!(e.to_string().contains("points"), "{e}");
    }

    #[test]
    fn malformed_input_names_the_field() {
        let e = parse(
            r#"{"op":"waypoints","driver":"1.1.45.1","speed":2,"points":[{"x":"a","y":0}]}"#,
            Some(&LocalFrame::new(0.0, 0.0, 0.0)),
        )
        .unwrap_err();
        assert!(e.to_string().contains("points[0].x"), "{e}");
        let e = parse(r#"{"op":"take","target":"1.1.x.1","authority":5}"#, None).unwrap_err();
        assert!(e.to_string().contains("target"), "{e}");
        let e = parse(r#"{"op":"take","target":"1.1.45.1","authority":300}"#, None).unwrap_err();
        assert!(e.to_string().contains("authority"), "{e}");
        assert!(matches!(parse("[1]", None), Err(PageError::Json(_))));
        assert!(matches!(
            parse(r#"{"op":"fly"}"#, None),
            Err(PageError::Op(_))
        ));
        assert!(matches!(
            parse(
                r#"{"op":"path","driver":"1.1.47.1","speed":1,"points":[{"x":1,"y":1}]}"#,
                None
            ),
            Err(PageError::NoOrigin(_))
        ));
    }
}
