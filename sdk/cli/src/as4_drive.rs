//! `jaus as4-drive`: an AS-4 operator in one command. It finds an AS-4 vehicle's
//! component (Query Identification, Query Services), takes control, resumes it, loads a
//! waypoint list into its List Manager (Set Element), executes it with the Local or
//! Global Waypoint List Driver, follows the active element and the pose until the list
//! is done, then puts the vehicle in standby and gives control back. With `--effort` it
//! drives with Primitive Driver efforts for a while instead, printing the velocity. Over AS5669A on
//! UDP; prints one line per step and per second of progress.

use std::io::Write;
use std::net::SocketAddr;
use std::time::{Duration, Instant};

use jaus::net::as5669a::{As4Config, As4Id, As4Message};
use jaus::CommandCode;
use jaus_as4::{
    ComponentState, ControlConfirmation, Element, ExecuteList, Message, NodeServicesQuery,
    QueryActiveElement, QueryGlobalPose, QueryIdentification, QueryLocalPose, QueryServices,
    QueryStatus, QueryVelocityState, ReleaseControl, RequestControl, Resume, SetElement,
    SetGlobalWaypoint, SetLocalWaypoint, SetWrenchEffort, Standby,
};
use jaus_client::as4_link::parse_id;
use jaus_client::as4_socket::As4Socket;

/// Options of `jaus as4-drive`.
#[derive(Debug, clap::Args)]
pub struct As4DriveArgs {
    /// The AS-4 vehicle's address (its node's AS5669A socket).
    #[arg(long)]
    pub peer: SocketAddr,
    /// Local address to send from.
    #[arg(long, default_value = "0.0.0.0:0")]
    pub bind: SocketAddr,
    /// This operator's AS-4 id.
    #[arg(long, default_value = "42.1.1")]
    pub me: String,
    /// The vehicle component's AS-4 id (default: whichever answers Query
    /// Identification).
    #[arg(long)]
    pub target: Option<String>,
    /// Waypoints in the local frame, `X,Y` metres (Local Waypoint List Driver).
    #[arg(long = "local", value_name = "X,Y", conflicts_with = "global")]
    pub local: Vec<String>,
    /// Waypoints in WGS 84, `LAT,LON` degrees (Global Waypoint List Driver).
    #[arg(long = "global", value_name = "LAT,LON")]
    pub global: Vec<String>,
    /// Speed along the list, m/s.
    #[arg(long, default_value_t = 1.0)]
    pub speed: f64,
    /// How close counts as reaching each waypoint, metres (the elements' waypoint
    /// tolerance, 0–100). A vehicle whose own driver stops short of that (OpenJAUS 3.3's
    /// waypoint driver moves on 3 m before a waypoint) needs a wider one.
    #[arg(long, default_value_t = 1.0, value_parser = tolerance)]
    pub tolerance: f64,
    /// Authority of the request for control.
    #[arg(long, default_value_t = 255)]
    pub authority: u8,
    /// Longest wait for the list to be driven, seconds.
    #[arg(long, default_value_t = 120)]
    pub timeout: u64,
    /// Instead of waypoints: drive with efforts through the Primitive Driver,
    /// `LINEAR,ROTATIONAL` percent (propulsive linear X, rotational Z; the brake, the
    /// resistive linear effort, at 0), sent every 0.2 s for `--for` seconds while the
    /// velocity state is printed, then zero with the brake on.
    #[arg(long, value_name = "LINEAR,ROTATIONAL", conflicts_with_all = ["local", "global"])]
    pub effort: Option<String>,
    /// How long to drive with `--effort`, seconds.
    #[arg(long = "for", default_value_t = 5.0)]
    pub effort_for: f64,
}

/// The operator's socket ([`As4Socket`]: acknowledgements, commands resent on the
/// transport's timer, reassembly) and who it talks to.
struct Link {
    socket: As4Socket,
    me: As4Id,
    target: As4Id,
}

impl Link {
    fn send(&mut self, m: impl Into<Message>) -> Result<(), String> {
        let m: Message = m.into();
        let body = m
            .body()
            .to_bytes()
            .map_err(|e| format!("{}: {e}", m.name()))?;
        self.socket
            .send(&[As4Message::new(m.code().0, self.target, self.me, body)])
    }

    /// The next message from the target within `wait` for which `want` says yes.
    fn wait_for<T>(
        &mut self,
        wait: Duration,
        mut want: impl FnMut(&Message) -> Option<T>,
    ) -> Option<T> {
        let until = Instant::now() + wait;
        while let Ok(Some(m)) = self.socket.next(until) {
            if self.target != As4Id::new(0xFFFF, 0xFF, 0xFF) && m.source != self.target {
                continue;
            }
            let Ok(msg) = Message::decode(CommandCode(m.message_id), &m.body) else {
                continue;
            };
            if self.target == As4Id::new(0xFFFF, 0xFF, 0xFF) {
                self.target = m.source;
            }
            if let Some(t) = want(&msg) {
                return Some(t);
            }
        }
        None
    }

    fn ask<T>(
        &mut self,
        q: impl Into<Message>,
        mut want: impl FnMut(&Message) -> Option<T>,
    ) -> Result<T, String> {
        let q: Message = q.into();
        let name = q.name();
        for _ in 0..3 {
            self.send(q.clone())?;
            if let Some(t) = self.wait_for(Duration::from_secs(1), &mut want) {
                return Ok(t);
            }
        }
        Err(format!(
            "{name} to {} at {}: no answer in 3 s",
            self.target,
            self.socket.peer()
        ))
    }
}

fn pair(text: &str, what: &str) -> Result<(f64, f64), String> {
    let (a, b) = text
        .split_once(',')
        .ok_or_else(|| format!("{what} `{text}`: two numbers separated by a comma"))?;
    let p = |s: &str| {
        s.trim()
            .parse::<f64>()
            .map_err(|e| format!("{what} `{text}`: {e}"))
    };
    Ok((p(a)?, p(b)?))
}

/// Runs `jaus as4-drive`.
pub fn as4_drive(args: &As4DriveArgs, out: &mut impl Write) -> Result<(), String> {
    let global = !args.global.is_empty();
    let effort = args
        .effort
        .as_deref()
        .map(|e| pair(e, "--effort"))
        .transpose()?;
    let points: Vec<(f64, f64)> = if global {
        args.global
            .iter()
            .map(|t| pair(t, "--global"))
            .collect::<Result<_, _>>()?
    } else {
        args.local
            .iter()
            .map(|t| pair(t, "--local"))
            .collect::<Result<_, _>>()?
    };
    if points.is_empty() && effort.is_none() {
        return Err(
            "give the waypoints (--local X,Y ... or --global LAT,LON ...) or --effort".into(),
        );
    }
    if points.len() > 200 {
        return Err(format!("{} waypoints: at most 200", points.len()));
    }
    let me = parse_id(&args.me)?;
    let target = match &args.target {
        Some(t) => parse_id(t)?,
        None => As4Id::new(0xFFFF, 0xFF, 0xFF),
    };
    let mut link = Link {
        // Commands acknowledged and resent until they arrive (docs/wire.md §1.7).
        socket: As4Socket::bind(
            args.bind,
            args.peer,
            As4Config {
                reliable: Some(jaus::net::reliable::RetryPolicy::default()),
                ..As4Config::default()
            },
        )?,
        me,
        target,
    };
    let t0 = Instant::now();
    let mut say = |text: String| {
        let _ = writeln!(out, "{:6.1} s  {text}", t0.elapsed().as_secs_f64());
        let _ = out.flush();
    };

    let name = link.ask(
        QueryIdentification {
            query_type: jaus_as4::IdentificationType::Component,
        },
        |m| match m {
            Message::ReportIdentification(r) => Some(r.identification.clone()),
            _ => None,
        },
    )?;
    say(format!(
        "found {} \"{name}\" at {}",
        link.target,
        link.socket.peer()
    ));
    let services = link.ask(
        QueryServices {
            nodes: vec![NodeServicesQuery {
                node_id: 255,
                component_ids: vec![255],
            }],
        },
        |m| match m {
            Message::ReportServices(r) => Some(
                r.nodes
                    .iter()
                    .flat_map(|n| &n.components)
                    .flat_map(|c| &c.services)
                    .map(|s| s.uri.clone())
                    .collect::<Vec<_>>(),
            ),
            _ => None,
        },
    )?;
    let driver = if effort.is_some() {
        "urn:jaus:jss:mobility:PrimitiveDriver"
    } else if global {
        "urn:jaus:jss:mobility:GlobalWaypointListDriver"
    } else {
        "urn:jaus:jss:mobility:LocalWaypointListDriver"
    };
    if !services.iter().any(|s| s == driver) {
        return Err(format!(
            "{} offers no {driver}; its services: {}",
            link.target,
            services.join(", ")
        ));
    }
    say(format!("{} services, {driver} among them", services.len()));

    let granted = link.ask(
        RequestControl {
            authority_code: args.authority,
        },
        |m| match m {
            Message::ConfirmControl(c) => Some(c.response_code),
            _ => None,
        },
    )?;
    if granted != ControlConfirmation::ControlAccepted {
        return Err(format!("control of {} refused: {granted:?}", link.target));
    }
    say("control granted".into());
    let result = match effort {
        Some(e) => teleoperate(&mut link, args, e, &mut say),
        None => drive(&mut link, args, global, &points, &mut say),
    };
    // Whatever happened: standby and control given back.
    let _ = link.send(Standby {});
    let _ = link.send(ReleaseControl {});
    say("standby, control released".into());
    result
}

fn resume(link: &mut Link, say: &mut impl FnMut(String)) -> Result<(), String> {
    link.send(Resume {})?;
    let status = link.ask(QueryStatus {}, |m| match m {
        Message::ReportStatus(s) => Some(s.status),
        _ => None,
    })?;
    if status != ComponentState::Ready {
        return Err(format!("{} is {status:?} after Resume", link.target));
    }
    say("ready".into());
    Ok(())
}

fn teleoperate(
    link: &mut Link,
    args: &As4DriveArgs,
    (linear, rotational): (f64, f64),
    say: &mut impl FnMut(String),
) -> Result<(), String> {
    resume(link, say)?;
    let until = Instant::now() + Duration::from_secs_f64(args.effort_for.clamp(0.0, 600.0));
    let mut next_print = Instant::now();
    let result = loop {
        if Instant::now() >= until {
            break Ok(());
        }
        link.send(SetWrenchEffort {
            propulsive_linear_effort_x: Some(linear),
            propulsive_rotational_effort_z: Some(rotational),
            // The brake off: a Primitive Driver keeps the efforts a message leaves out
            // (OpenJAUS's kept its waypoint driver's braking and the vehicle never moved).
            resistive_linear_effort_x: Some(0.0),
            ..Default::default()
        })?;
        if Instant::now() >= next_print {
            next_print += Duration::from_secs(1);
            match link.ask(
                QueryVelocityState {
                    presence_vector: 0x41,
                },
                |m| match m {
                    Message::ReportVelocityState(v) => Some((v.velocity_x, v.yaw_rate)),
                    _ => None,
                },
            ) {
                Ok((vx, wz)) => say(format!(
                    "effort {linear}/{rotational} %: velocity x {:.2} m/s, yaw rate {:.2} rad/s",
                    vx.unwrap_or(f64::NAN),
                    wz.unwrap_or(f64::NAN)
                )),
                Err(e) => break Err(e),
            }
        }
        std::thread::sleep(Duration::from_millis(200));
    };
    link.send(SetWrenchEffort {
        propulsive_linear_effort_x: Some(0.0),
        propulsive_rotational_effort_z: Some(0.0),
        resistive_linear_effort_x: Some(100.0),
        ..Default::default()
    })?;
    say("efforts zero, brake on".into());
    result
}

fn drive(
    link: &mut Link,
    args: &As4DriveArgs,
    global: bool,
    points: &[(f64, f64)],
    say: &mut impl FnMut(String),
) -> Result<(), String> {
    resume(link, say)?;
    let n = points.len() as u16;
    let mut elements = Vec::with_capacity(points.len());
    for (i, (a, b)) in points.iter().enumerate() {
        let uid = i as u16 + 1;
        let m: Message = if global {
            SetGlobalWaypoint {
                latitude: *a,
                longitude: *b,
                waypoint_tolerance: Some(args.tolerance),
                ..Default::default()
            }
            .into()
        } else {
            SetLocalWaypoint {
                x: *a,
                y: *b,
                waypoint_tolerance: Some(args.tolerance),
                ..Default::default()
            }
            .into()
        };
        let next = if uid == n { 0 } else { uid + 1 };
        elements.push(Element::holding(uid, uid - 1, next, &m).map_err(|e| e.to_string())?);
    }
    let answer = link.ask(
        SetElement {
            request_id: 1,
            elements,
        },
        |m| match m {
            Message::ConfirmElementRequest(_) => Some(Ok(())),
            Message::RejectElementRequest(r) => Some(Err(format!("{:?}", r.response_code))),
            _ => None,
        },
    )?;
    answer.map_err(|code| format!("Set Element refused: {code}"))?;
    say(format!("{n} waypoint(s) stored"));
    link.send(ExecuteList {
        speed: args.speed,
        element_uid: Some(1),
    })?;
    say(format!("executing at {} m/s", args.speed));
    let until = Instant::now() + Duration::from_secs(args.timeout);
    let mut started = false;
    loop {
        let active = link.ask(QueryActiveElement {}, |m| match m {
            Message::ReportActiveElement(a) => Some(a.element_uid),
            _ => None,
        })?;
        let at = if global {
            link.ask(
                QueryGlobalPose {
                    presence_vector: 0x3,
                },
                |m| match m {
                    Message::ReportGlobalPose(p) => Some(format!(
                        "lat {:.7} lon {:.7}",
                        p.latitude.unwrap_or(f64::NAN),
                        p.longitude.unwrap_or(f64::NAN)
                    )),
                    _ => None,
                },
            )?
        } else {
            link.ask(
                QueryLocalPose {
                    presence_vector: 0x3,
                },
                |m| match m {
                    Message::ReportLocalPose(p) => Some(format!(
                        "x {:.2} y {:.2}",
                        p.x.unwrap_or(f64::NAN),
                        p.y.unwrap_or(f64::NAN)
                    )),
                    _ => None,
                },
            )?
        };
        say(format!("active element {active}, {at}"));
        started |= active != 0;
        if started && active == 0 {
            say("list done".into());
            return Ok(());
        }
        if Instant::now() >= until {
            return Err(format!(
                "the list was not done within {} s (active element {active})",
                args.timeout
            ));
        }
        std::thread::sleep(Duration::from_secs(1));
    }
}

/// A waypoint tolerance within the field's range (0–100 m).
fn tolerance(text: &str) -> Result<f64, String> {
    let v: f64 = text.parse().map_err(|e| format!("{e}"))?;
    if (0.0..=100.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!("{v} m is outside the waypoint tolerance's 0–100 m"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Debug, clap::Parser)]
    struct Cli {
        #[command(flatten)]
        args: As4DriveArgs,
    }

    /// The JAUS Tool Set reads an id byte of 0 as "every": the operator's default id has
    /// no 0 part (nor a broadcast one).
    #[test]
    fn the_default_operator_id_has_no_zero_or_broadcast_part() {
        let cli = Cli::try_parse_from(["as4-drive", "--peer", "127.0.0.1:3794"]).unwrap();
        let me = cli.args.me.parse::<As4Id>().unwrap();
        assert_eq!(me, As4Id::new(42, 1, 1));
        assert!(me.subsystem != 0 && me.node != 0 && me.component != 0 && !me.is_broadcast());
    }
}
