//! The AS-4 side of a node file: the gateway of `as4:`, the proxies of
//! `as4_vehicles:`, and the AS-4 services its `host:` entries offer natively.

use std::path::Path;

use jaus::Address;

use super::*;

impl NodeFile {
    /// With `as4:`, the settings of the RA 3.3 ↔ AS-4 gateway on this node
    /// (`jaus_as4::gateway::DualNode`); `None` without.
    pub fn as4_config(&self) -> Option<jaus_as4::gateway::GatewayConfig> {
        let a = self.as4.as_ref()?;
        let id = jaus::net::as5669a::As4Id::new(
            a.subsystem.unwrap_or(u16::from(self.subsystem)),
            a.node.unwrap_or(self.node),
            a.component.unwrap_or(1),
        );
        let at = Address::new(self.subsystem, self.node, a.gateway_id.unwrap_or(60), 1);
        let name = a
            .name
            .clone()
            .or_else(|| self.subsystem_name.clone())
            .unwrap_or_else(|| format!("subsystem {}", self.subsystem));
        let mut config = jaus_as4::gateway::GatewayConfig::new(
            id,
            at,
            a.present.unwrap_or(self.subsystem),
            &name,
        );
        if let Some(x) = a.authority {
            config.authority = x;
        }
        config.pan_tilt = a.pan_tilt.as_ref().map(|m| {
            jaus_as4::manipulator::PanTiltMount::new(
                m.camera,
                m.pan_limit.to_radians(),
                m.tilt_limit.to_radians(),
            )
        });
        Some(config)
    }

    /// With `as4: { mission_spooler: … }`, the AS-4 node of the Mission Spooler's
    /// component, to add beside the gateway (`DualNode::with_endpoint`): it knows the
    /// gateway's component at this node's own address and the destinations listed at
    /// theirs (`path`: the file, for the errors).
    pub fn as4_mission_spooler(
        &self,
        path: &Path,
    ) -> Result<Option<jaus_as4::node::As4Node<()>>, String> {
        use jaus_as4::mission::{MissionSpoolerService, SpoolerConfig};
        let (Some(gw), Some(m)) = (
            self.as4_config(),
            self.as4.as_ref().and_then(|a| a.mission_spooler.as_ref()),
        ) else {
            return Ok(None);
        };
        let at =
            |what: &str, e: String| format!("{}: as4.mission_spooler.{what}: {e}", path.display());
        let id =
            jaus::net::as5669a::As4Id::new(gw.as4.subsystem, gw.as4.node, m.component.unwrap_or(5));
        if id == gw.as4 || id.is_broadcast() || id.component == 0 {
            return Err(at(
                "component",
                format!("{id} is the gateway's component, 0 or a broadcast"),
            ));
        }
        let seconds = |what: &str, s: Option<f64>, default: u64| match s {
            None => Ok(Duration::from_secs(default)),
            Some(s) => Duration::try_from_secs_f64(s)
                .ok()
                .filter(|d| !d.is_zero())
                .ok_or_else(|| at(what, format!("{s} is not a number of seconds above 0"))),
        };
        let mut config = SpoolerConfig::default();
        config.authority = m.authority.unwrap_or(config.authority);
        config.control_timeout = seconds("control_timeout", m.control_timeout, 5)?;
        config.command_timeout = seconds("command_timeout", m.command_timeout, 60)?;
        if let Some(n) = m.max_messages {
            config.bounds.max_messages = n;
        }
        let component = jaus_as4::component::As4Component::new(
            id,
            jaus_as4::core::CoreConfig::named("mission spooler"),
        )
        .with_service(MissionSpoolerService::new(config));
        let mut node = jaus_as4::node::As4Node::new(()).with_component(component);
        let mut own = self.bind;
        if own.ip().is_unspecified() {
            own.set_ip(match own {
                std::net::SocketAddr::V4(_) => std::net::Ipv4Addr::LOCALHOST.into(),
                std::net::SocketAddr::V6(_) => std::net::Ipv6Addr::LOCALHOST.into(),
            });
        }
        node.learn_peer(gw.as4, own);
        for (i, d) in m.destinations.iter().enumerate() {
            let did =
                d.id.parse::<jaus::net::as5669a::As4Id>()
                    .map_err(|e| at(&format!("destinations[{i}].id"), e.to_string()))?;
            node.learn_peer(did, d.peer);
        }
        Ok(Some(node))
    }

    /// The proxies of `as4_vehicles:`: each one's settings and the vehicle's address
    /// (`path`: the file, for the errors).
    pub fn as4_vehicles(
        &self,
        path: &Path,
    ) -> Result<Vec<(jaus_as4::proxy::ProxyConfig, std::net::SocketAddr)>, String> {
        use jaus_as4::proxy::{ProxyConfig, Role};
        let mut out = Vec::new();
        for (i, v) in self.as4_vehicles.iter().enumerate() {
            let at = |what: &str, e: String| {
                format!("{}: as4_vehicles[{i}].{what}: {e}", path.display())
            };
            let vehicle =
                v.id.as_deref()
                    .map(|t| {
                        t.parse::<jaus::net::as5669a::As4Id>()
                            .map_err(|e| e.to_string())
                    })
                    .transpose()
                    .map_err(|e| at("id", e))?;
            let me = match &v.proxy_id {
                Some(t) => t
                    .parse::<jaus::net::as5669a::As4Id>()
                    .map_err(|e| at("proxy_id", e.to_string()))?,
                None => {
                    let component = default_proxy_component(i).ok_or_else(|| {
                        at(
                            "proxy_id",
                            format!(
                                "no default left (the first {} entries take components {}-254 of this node): give this entry a proxy_id",
                                254 - FIRST_PROXY_COMPONENT + 1,
                                FIRST_PROXY_COMPONENT
                            ),
                        )
                    })?;
                    jaus::net::as5669a::As4Id::new(u16::from(self.subsystem), self.node, component)
                }
            };
            let mut config = ProxyConfig::new(me, vehicle);
            config.instance = v.instance.unwrap_or(i as u8 + 1);
            if let Some(a) = v.authority {
                config.authority = a;
            }
            if let Some(names) = &v.services {
                config.roles = names
                    .iter()
                    .map(|n| {
                        Role::ALL
                            .into_iter()
                            .find(|r| role_name(*r) == n)
                            .ok_or_else(|| {
                                let all: Vec<&str> = Role::ALL.into_iter().map(role_name).collect();
                                at(
                                    "services",
                                    format!("`{n}` is not one of {}", all.join(", ")),
                                )
                            })
                    })
                    .collect::<Result<_, _>>()?;
            }
            if let Some(f) = v.frame {
                config.frame = jaus_as4::gateway::ra33::Frame {
                    x: f.x,
                    y: f.y,
                    yaw: f.yaw,
                };
            }
            out.push((config, v.peer));
        }
        Ok(out)
    }
}

/// The native services being gathered while a node file's `host:` entries are built.
#[derive(Default)]
pub(super) struct NativeServices {
    /// The services.
    pub(super) services: As4Native,
    /// Whether a Range Sensor is among them (one per component: the first scanner's).
    range_sensor: bool,
}

impl NativeServices {
    /// Adds `s`.
    pub(super) fn push(
        &mut self,
        s: Box<dyn jaus_as4::service::Service<jaus_as4::gateway::Ra33Side>>,
    ) {
        self.services.push(s);
    }

    /// Adds the AS-4 Range Sensor over `scanner`, unless one was added (an AS-4
    /// component offers a service once; its sensor 1 is the first scanner).
    pub(super) fn add_range_sensor(&mut self, scanner: jaus_sim::scanner::SimScanner) {
        if std::mem::replace(&mut self.range_sensor, true) {
            return;
        }
        let service = jaus_as4::environment::RangeSensorService::new(scanner)
            .with_name("simulated range scanner");
        self.services.push(Box::new(service));
    }
}

/// The first AS-4 component id of the proxies' default ids (`proxy_id`).
const FIRST_PROXY_COMPONENT: u8 = 200;

/// The component of the default AS-4 id of the proxy of `as4_vehicles[i]`
/// (`subsystem.node.component` of this node): 200 + i, within 200-254, so that no part
/// is 0 (the JAUS Tool Set reads a 0 byte as "every") or 255 (every component); `None`
/// past the last one.
fn default_proxy_component(i: usize) -> Option<u8> {
    u8::try_from(usize::from(FIRST_PROXY_COMPONENT) + i)
        .ok()
        .filter(|c| *c < u8::MAX)
}

/// The name of a proxy role in `as4_vehicles:` (`services:`).
fn role_name(r: jaus_as4::proxy::Role) -> &'static str {
    use jaus_as4::proxy::Role;
    match r {
        Role::VelocityStateSensor => "velocity_state_sensor",
        Role::LocalPoseSensor => "local_pose_sensor",
        Role::GlobalPoseSensor => "global_pose_sensor",
        Role::PrimitiveDriver => "primitive_driver",
        Role::LocalWaypointDriver => "local_waypoint_driver",
        Role::GlobalWaypointDriver => "global_waypoint_driver",
        Role::GlobalPathSegmentDriver => "global_path_segment_driver",
        Role::LocalPathSegmentDriver => "local_path_segment_driver",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(yaml: &str) -> NodeFile {
        serde_yaml::from_str(yaml).unwrap()
    }

    /// The JAUS Tool Set reads an id byte of 0 as "every": no default AS-4 id of a node
    /// file has a 0 part (nor a 255 or 65535 one, which are broadcasts).
    #[test]
    fn default_as4_ids_have_no_zero_or_broadcast_part() {
        let specific = |id: jaus::net::as5669a::As4Id| {
            id.subsystem != 0 && id.node != 0 && id.component != 0 && !id.is_broadcast()
        };
        let vehicles: String = (0..55)
            .map(|i| format!("  - {{ peer: 127.0.0.1:{} }}\n", 4000 + i))
            .collect();
        for (s, n) in [(1, 1), (254, 254), (7, 200)] {
            let f = file(&format!(
                "subsystem: {s}\nnode: {n}\nbind: 127.0.0.1:0\nas4: {{}}\nas4_vehicles:\n{vehicles}"
            ));
            let gateway = f.as4_config().unwrap().as4;
            assert!(specific(gateway), "gateway {gateway}");
            let proxies = f.as4_vehicles(Path::new("n.yaml")).unwrap();
            assert_eq!(proxies.len(), 55);
            for (p, _) in &proxies {
                assert!(specific(p.me), "proxy {}", p.me);
            }
            assert_eq!(proxies[54].0.me.component, 254);
        }
        // A 56th entry has no default left: it must give its own.
        let f = file(&format!(
            "subsystem: 1\nnode: 1\nbind: 127.0.0.1:0\nas4_vehicles:\n{vehicles}  - {{ peer: 127.0.0.1:5000 }}\n"
        ));
        let e = f.as4_vehicles(Path::new("n.yaml")).unwrap_err();
        assert!(
            e.contains("as4_vehicles[55].proxy_id") && e.contains("components 200-254"),
            "{e}"
        );
        // The AS-4 judge of `jaus conform --as4` (and of `jaus as4-drive`, same default).
        assert!(specific(jaus_conform::as4::As4Options::default().me));
    }

    #[test]
    fn a_mission_spooler_is_its_own_component_knowing_the_gateway_and_its_destinations() {
        use jaus::net::as5669a::As4Id;
        let f = file(
            "subsystem: 3\nnode: 2\nbind: 0.0.0.0:3794\nas4:\n  mission_spooler:\n    command_timeout: 30\n    authority: 90\n    destinations: [{ id: 4.1.1, peer: 10.0.0.4:3794 }]\n",
        );
        let node = f.as4_mission_spooler(Path::new("n.yaml")).unwrap().unwrap();
        let c = node.components().next().unwrap();
        assert_eq!(c.id(), As4Id::new(3, 2, 5));
        let uris: Vec<&str> = c.service_ids().iter().map(|s| s.uri).collect();
        assert!(
            uris.contains(&"urn:jaus:jss:missionSpooler:MissionSpooler"),
            "{uris:?}"
        );
        // The gateway at this node's own socket, the destination at its own.
        assert_eq!(
            node.peer(As4Id::new(3, 2, 1)),
            Some("127.0.0.1:3794".parse().unwrap())
        );
        assert_eq!(
            node.peer(As4Id::new(4, 1, 1)),
            Some("10.0.0.4:3794".parse().unwrap())
        );
        // Without `as4:` or without `mission_spooler:`, none.
        let none = file("subsystem: 3\nnode: 2\nbind: 0.0.0.0:3794\nas4: {}\n");
        assert!(none
            .as4_mission_spooler(Path::new("n.yaml"))
            .unwrap()
            .is_none());
        // Errors name the field.
        let bad = file(
            "subsystem: 3\nnode: 2\nbind: 0.0.0.0:3794\nas4: { mission_spooler: { component: 1 } }\n",
        );
        let e = bad.as4_mission_spooler(Path::new("n.yaml")).unwrap_err();
        assert!(e.contains("as4.mission_spooler.component"), "{e}");
        let bad = file(
            "subsystem: 3\nnode: 2\nbind: 0.0.0.0:3794\nas4: { mission_spooler: { command_timeout: -1 } }\n",
        );
        let e = bad.as4_mission_spooler(Path::new("n.yaml")).unwrap_err();
        assert!(e.contains("as4.mission_spooler.command_timeout"), "{e}");
        let bad = file(
            "subsystem: 3\nnode: 2\nbind: 0.0.0.0:3794\nas4: { mission_spooler: { destinations: [{ id: x, peer: 10.0.0.4:1 }] } }\n",
        );
        let e = bad.as4_mission_spooler(Path::new("n.yaml")).unwrap_err();
        assert!(e.contains("as4.mission_spooler.destinations[0].id"), "{e}");
    }

    #[test]
    fn as4_vehicles_are_read_with_their_defaults_and_errors_name_the_field() {
        let f = file(
            "subsystem: 2\nnode: 3\nbind: 127.0.0.1:0\nas4_vehicles:\n  - { peer: 127.0.0.1:3794, id: 1.1.1 }\n  - { peer: 127.0.0.1:3795, proxy_id: 9.9.9, instance: 7, authority: 10, services: [global_pose_sensor, global_waypoint_driver], frame: { x: 1, yaw: 0.5 } }\n",
        );
        let v = f.as4_vehicles(Path::new("n.yaml")).unwrap();
        assert_eq!(v.len(), 2);
        let (a, peer) = &v[0];
        assert_eq!(peer.port(), 3794);
        assert_eq!(a.vehicle, Some(jaus::net::as5669a::As4Id::new(1, 1, 1)));
        assert_eq!(
            (a.me, a.instance, a.authority, a.roles.len()),
            (jaus::net::as5669a::As4Id::new(2, 3, 200), 1, 200, 8)
        );
        let (b, _) = &v[1];
        assert_eq!(b.vehicle, None);
        assert_eq!(
            (b.me, b.instance, b.authority),
            (jaus::net::as5669a::As4Id::new(9, 9, 9), 7, 10)
        );
        assert_eq!(
            b.roles,
            vec![
                jaus_as4::proxy::Role::GlobalPoseSensor,
                jaus_as4::proxy::Role::GlobalWaypointDriver
            ]
        );
        assert_eq!((b.frame.x, b.frame.y, b.frame.yaw), (1.0, 0.0, 0.5));

        let bad = file(
            "subsystem: 2\nnode: 1\nbind: 127.0.0.1:0\nas4_vehicles: [{ peer: 127.0.0.1:1, services: [sonar] }]\n",
        );
        let e = bad.as4_vehicles(Path::new("n.yaml")).unwrap_err();
        assert!(
            e.contains("as4_vehicles[0].services") && e.contains("`sonar`"),
            "{e}"
        );
        let bad = file(
            "subsystem: 2\nnode: 1\nbind: 127.0.0.1:0\nas4_vehicles: [{ peer: 127.0.0.1:1, id: 1.x.1 }]\n",
        );
        let e = bad.as4_vehicles(Path::new("n.yaml")).unwrap_err();
        assert!(
            e.contains("as4_vehicles[0].id") && e.contains("node"),
            "{e}"
        );
    }
}
