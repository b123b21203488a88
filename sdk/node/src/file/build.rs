//! Building what a node file describes: its hosted components (stock cores over one
//! simulated vehicle or arm, the communicator and its data links) and the node.

use std::path::Path;
use std::time::Instant;

use jaus::net::Node;
use jaus::Address;

use crate::links_file::{links_at, LinkFile, QuicLinkFile};

use super::as4::NativeServices;
use super::*;

impl NodeFile {
    /// The subsystem's Communicator: the one hosted here, else `communicator:`, checked
    /// (`at` gives the file:line:column of a YAML path).
    pub(super) fn communicator_at(
        &self,
        hosted: &[Hosted],
        at: &dyn Fn(&str) -> String,
    ) -> Result<Option<jaus::Address>, String> {
        let entries = hosted.iter().filter_map(|h| match h {
            Hosted::Stock(e) => Some(e),
            Hosted::Vehicle | Hosted::Arm => None,
        });
        let here = crate::host::Host::communicator_of(self.subsystem, self.node, entries);
        let Some(text) = &self.communicator else {
            return Ok(here);
        };
        let a: jaus::Address = text.parse().map_err(|_| {
            format!(
                "{}: communicator: `{text}` is not an address subsystem.node.component.instance",
                at("communicator")
            )
        })?;
        if a.subsystem != self.subsystem || a.node == 0 || a.node == 255 {
            return Err(format!(
                "{}: communicator: {a} is not a component of this subsystem ({}): a node reaches other subsystems only through its own subsystem's communicator",
                at("communicator"),
                self.subsystem
            ));
        }
        match here {
            Some(h) if h != a => Err(format!(
                "{}: communicator: {a}, but this node hosts the communicator {h}",
                at("communicator")
            )),
            None if a.node == self.node => Err(format!(
                "{}: communicator: {a} is on this node but not hosted here (add `communicator` with its `links:` to `host:`)",
                at("communicator")
            )),
            _ => Ok(Some(a)),
        }
    }

    /// The subsystem's Communicator (checked by [`NodeFile::load`]): the one this
    /// node hosts, else `communicator:`.
    pub fn communicator(&self) -> Option<jaus::Address> {
        let hosted = self.hosted();
        self.communicator_at(&hosted, &|k| k.to_string())
            .ok()
            .flatten()
    }

    /// The `host:` entries, checked (`at` gives the file:line:column of a YAML path).
    pub(super) fn hosted_at(&self, at: &dyn Fn(&str) -> String) -> Result<Vec<Hosted>, String> {
        let known = || {
            let mut k = vec!["vehicle", "arm"];
            k.extend(crate::host::Stock::names());
            k.join(", ")
        };
        let mut out = Vec::new();
        for (i, h) in self.host.iter().enumerate() {
            let (name, key) = match h {
                HostItem::Name(n) => (n, format!("host[{i}]")),
                HostItem::Component { component, .. } => {
                    (component, format!("host[{i}].component"))
                }
            };
            if name == "vehicle" {
                out.push(Hosted::Vehicle);
                continue;
            }
            if name == "arm" {
                out.push(Hosted::Arm);
                continue;
            }
            let Some(stock) = crate::host::Stock::by_name(name) else {
                return Err(format!(
                    "{}: unknown component `{name}` (known: {})",
                    at(&key),
                    known()
                ));
            };
            let mut e = crate::host::Host::entry(stock);
            let is_communicator = stock.id() == jaus::components::communicator::ID;
            let mut has_links = false;
            if let HostItem::Component {
                instance,
                output,
                pose,
                authority,
                links,
                ..
            } = h
            {
                if let Some(n) = instance {
                    if *n == 0 || *n == 255 {
                        return Err(format!(
                            "{}: instance {n} is not in 1..=254",
                            at(&format!("host[{i}].instance"))
                        ));
                    }
                    e.instance = *n;
                }
                let addr =
                    |v: &Option<String>, key: &str| -> Result<Option<jaus::Address>, String> {
                        v.as_deref()
                            .map(|s| {
                                s.parse().map_err(|_| {
                                    format!(
                                    "{}: `{s}` is not an address subsystem.node.component.instance",
                                    at(&format!("host[{i}].{key}"))
                                )
                                })
                            })
                            .transpose()
                    };
                e.output = addr(output, "output")?;
                e.pose = addr(pose, "pose")?;
                e.authority = authority.unwrap_or(0);
                match links {
                    Some(v) if is_communicator => {
                        let all = links_at(v, i, at)?;
                        has_links = !all.is_empty();
                        // The UDP links are built by the host; the others by build_node.
                        e.links = all.into_iter().filter_map(LinkFile::into_udp).collect();
                    }
                    Some(_) => {
                        return Err(format!(
                            "{}: host[{i}].links: `links` is for the communicator, not `{name}`",
                            at(&format!("host[{i}].links"))
                        ))
                    }
                    None => {}
                }
            }
            if is_communicator && !has_links {
                return Err(format!(
                    "{}: host[{i}]: `communicator` needs its data links: `{{ component: communicator, links: [{{ id: 1, udp: {{ bind: IP:PORT, peer: IP:PORT }} }}] }}`",
                    at(&format!("host[{i}]"))
                ));
            }
            if is_communicator
                && out
                    .iter()
                    .any(|o| matches!(o, Hosted::Stock(p) if p.stock == stock))
            {
                return Err(format!(
                    "{}: host[{i}]: a second `communicator`: a node hosts at most one (the subsystem's gateway)",
                    at(&key)
                ));
            }
            let clash = out.iter().any(|o| match o {
                Hosted::Stock(p) => p.stock == e.stock && p.instance == e.instance,
                Hosted::Vehicle | Hosted::Arm => false,
            });
            if clash {
                return Err(format!(
                    "{}: `{name}` instance {} is hosted twice",
                    at(&key),
                    e.instance
                ));
            }
            out.push(Hosted::Stock(e));
        }
        Ok(out)
    }

    /// The `host:` entries (checked by [`NodeFile::load`]).
    pub fn hosted(&self) -> Vec<Hosted> {
        self.hosted_at(&|k| k.to_string()).unwrap_or_default()
    }

    /// The data links of the communicator this node hosts (none if it hosts none).
    pub fn communicator_links(&self) -> Vec<LinkFile> {
        self.communicator_link_files()
            .map(|(_, links)| links)
            .unwrap_or_default()
    }

    /// The `links:` of the communicator this node hosts, and the index of its `host:`
    /// entry (checked by [`NodeFile::load`]).
    pub(super) fn communicator_link_files(&self) -> Option<(usize, Vec<LinkFile>)> {
        use crate::host::Stock;
        self.host.iter().enumerate().find_map(|(i, h)| match h {
            HostItem::Component {
                component,
                links: Some(v),
                ..
            } if Stock::by_name(component).map(Stock::id)
                == Some(jaus::components::communicator::ID) =>
            {
                Some((i, links_at(v, i, &|k| k.to_string()).unwrap_or_default()))
            }
            _ => None,
        })
    }

    /// The QUIC links' key files (relative to the directory of the node file `path`)
    /// read and their configurations checked, before anything is bound (`at` gives the
    /// file:line:column of a YAML path).
    pub(super) fn check_quic_links(
        &self,
        path: &Path,
        at: &dyn Fn(&str) -> String,
    ) -> Result<(), String> {
        let Some((i, links)) = self.communicator_link_files() else {
            return Ok(());
        };
        let dir = path.parent().unwrap_or_else(|| Path::new("."));
        for (j, link) in links.iter().enumerate() {
            let LinkFile::Quic(q) = link else { continue };
            let here = format!("host[{i}].links[{j}].quic");
            let c = q.config(dir).map_err(|(field, e)| {
                let f = format!("{here}.{field}");
                format!("{}: {f}: {e}", at(&f))
            })?;
            c.check()
                .map_err(|e| format!("{}: {here}: {e}", at(&here)))?;
        }
        Ok(())
    }

    /// The communicator of entry `e` over its links, UDP ones built by the host as for
    /// any stock component, QUIC ones (key files relative to the directory of the node
    /// file `path`) here.
    pub(super) fn build_communicator(
        &self,
        host: &mut crate::host::Host,
        e: &crate::host::Entry,
        path: &Path,
    ) -> Result<Box<dyn jaus::component::Endpoint>, String> {
        use jaus::stock::communicator::DataLink;
        let links = self.communicator_links();
        let dir = path.parent().unwrap_or_else(|| Path::new("."));
        let quic = |q: &QuicLinkFile| -> Result<jaus_quic::QuicLink, String> {
            let c = q
                .config(dir)
                .map_err(|(_, e)| format!("communicator: data link {}: {e}", q.id))?;
            jaus_quic::QuicLink::bind(c).map_err(|e| format!("communicator: {e}"))
        };
        let built = if links.iter().all(|l| matches!(l, LinkFile::Udp(_))) {
            // A communicator over UDP links only: `CommunicatorEndpoint<UdpLink>`.
            host.build(e)
        } else if links.iter().all(|l| matches!(l, LinkFile::Quic(_))) {
            // Over QUIC links only: `CommunicatorEndpoint<QuicLink>`.
            let mut made = Vec::new();
            for l in &links {
                if let LinkFile::Quic(q) = l {
                    made.push(quic(q)?);
                }
            }
            host.build_communicator(e, made)
        } else {
            // A mix: `CommunicatorEndpoint<Box<dyn DataLink>>`.
            let mut made: Vec<Box<dyn DataLink>> = Vec::new();
            for l in &links {
                made.push(match l {
                    LinkFile::Udp(c) => Box::new(
                        jaus::net::udp::link::UdpLink::bind(c.clone())
                            .map_err(|e| format!("communicator: {e}"))?,
                    ),
                    LinkFile::Quic(q) => Box::new(quic(q)?),
                });
            }
            host.build_communicator(e, made)
        };
        built.map_err(|e| e.to_string())
    }
    /// `ros2:`, checked (`at` gives the file:line:column of a YAML path): its values
    /// (`Ros2Config::validate`), robot mode only, and none of the robot's components
    /// (`jaus_ros2::robot_parts`) at an address a `host:` entry or an `as4_vehicles:`
    /// proxy takes.
    pub(super) fn check_ros2(
        &self,
        hosted: &[Hosted],
        path: &Path,
        at: &dyn Fn(&str) -> String,
    ) -> Result<(), String> {
        use jaus_as4::proxy::Role;
        let Some(r) = &self.ros2 else {
            return Ok(());
        };
        if let Err(jaus_ros2::Ros2Error::Config(e)) = r.validate() {
            // The message starts with the key it is about (`effort.max_linear ...`).
            let key = e.split_whitespace().next().unwrap_or_default();
            return Err(format!("{}: ros2: {e}", at(&format!("ros2.{key}"))));
        }
        if r.vehicle.subsystem.is_some() {
            return Err(format!(
                "{}: ros2: vehicle mode (a JAUS vehicle in ROS 2) is `jaus ros2 --vehicle`'s; a node file's `ros2:` hosts a ROS 2 robot (leave out `vehicle.subsystem`)",
                at("ros2.vehicle.subsystem")
            ));
        }
        let robot = |id: u8| Address::new(self.subsystem, self.node, id, jaus_ros2::ids::INSTANCE);
        let parts = jaus_ros2::robot_parts(r);
        let ids: Vec<u8> = parts.iter().map(|(id, _)| *id).collect();
        let ros2_part = |id: u8| {
            let name = parts
                .iter()
                .find(|(i, _)| *i == id)
                .map_or("component", |(_, name)| *name);
            format!("`ros2:` hosts the ROS 2 robot's {name} there")
        };
        for (i, h) in hosted.iter().enumerate() {
            let clash = match h {
                Hosted::Vehicle => Some((
                    "`vehicle` (the demo's simulated vehicle)".to_string(),
                    jaus_ros2::ids::PRIMITIVE_DRIVER,
                    "leave out `vehicle`: the ROS 2 robot is this node's vehicle",
                )),
                Hosted::Arm => None,
                Hosted::Stock(e) => ids
                    .iter()
                    .copied()
                    .find(|id| e.stock.id() == *id && e.instance == jaus_ros2::ids::INSTANCE)
                    .map(|id| {
                        (
                            format!("`{}` instance {}", e.stock.name(), e.instance),
                            id,
                            "leave the entry out, or give it another `instance`",
                        )
                    }),
            };
            if let Some((what, id, hint)) = clash {
                return Err(format!(
                    "{}: host[{i}]: {what} takes {}, and {}: {hint}",
                    at(&format!("host[{i}]")),
                    robot(id),
                    ros2_part(id)
                ));
            }
        }
        for (i, (v, _)) in self.as4_vehicles(path)?.iter().enumerate() {
            let taken = v.roles.iter().find_map(|role| {
                let id = match role {
                    Role::PrimitiveDriver => jaus_ros2::ids::PRIMITIVE_DRIVER,
                    Role::GlobalPoseSensor => jaus_ros2::ids::GLOBAL_POSE_SENSOR,
                    Role::LocalPoseSensor => jaus_ros2::ids::LOCAL_POSE_SENSOR,
                    Role::VelocityStateSensor => jaus_ros2::ids::VELOCITY_STATE_SENSOR,
                    _ => return None,
                };
                (v.instance == jaus_ros2::ids::INSTANCE).then_some(id)
            });
            if let Some(id) = taken {
                return Err(format!(
                    "{}: as4_vehicles[{i}]: its proxy takes {}, and {}: give the entry another `instance`",
                    at(&format!("as4_vehicles[{i}]")),
                    robot(id),
                    ros2_part(id)
                ));
            }
        }
        Ok(())
    }

    /// With `ros2:`, starts the ROS 2 side (the robot's DDS domain joined) and adds the
    /// robot's components (`jaus_ros2::robot_components`) to `node`; the link
    /// must live as long as the node runs (dropping it publishes a zero twist). `None`
    /// without `ros2:` (`path`: the file, for the errors).
    pub fn start_ros2(
        &self,
        path: &Path,
        node: &mut Node,
        t0: Instant,
    ) -> Result<Option<jaus_ros2::Ros2Link>, String> {
        let Some(config) = &self.ros2 else {
            return Ok(None);
        };
        // `Ros2Error`s and the node's say `ros2 (...)` themselves.
        let err = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
        let link = jaus_ros2::Ros2Link::start(config).map_err(|e| err(&e))?;
        let component = self.node_config().component;
        for c in
            jaus_ros2::robot_components(&link, config, self.subsystem, self.node, &component, t0)
        {
            node.add_boxed(c)
                .map_err(|e| format!("{}: ros2: {e}", path.display()))?;
        }
        Ok(Some(link))
    }

    /// The file of `store:`, relative to the directory of the node file `path`.
    pub fn store_path(&self, path: &Path) -> Option<std::path::PathBuf> {
        let dir = path.parent().unwrap_or_else(|| Path::new("."));
        self.store.as_ref().map(|s| dir.join(s))
    }

    /// The node this file describes, its `host:` entries built and added, starting at
    /// `t0` (`path`: the file, for the errors).
    pub fn build_node(&self, path: &Path, t0: Instant) -> Result<Node, String> {
        self.build_node_and_as4(path, t0).map(|(node, _)| node)
    }

    /// [`build_node`](Self::build_node), with the AS-4 services its `host:` entries
    /// offer natively for the gateway of `as4:` to host (`DualNode::with_service`):
    /// `vehicle`'s Illumination over the simulated vehicle's lamps, and the Range
    /// Sensor over the scanner of the first entry that has one (`vehicle`'s, or the
    /// one a `range_sensor` entry reads), the same scanner its RA 3.3 Range Sensor reads.
    pub fn build_node_and_as4(
        &self,
        path: &Path,
        t0: Instant,
    ) -> Result<(Node, As4Native), String> {
        let mut node = Node::new(self.node_config(), t0);
        let mut native = NativeServices::default();
        let hosted = self.hosted();
        let mut host = crate::host::Host::new(self.subsystem, self.node, t0);
        if let Some(file) = self.store_path(path) {
            let store = jaus_store::Store::open(&file)
                .map_err(|e| format!("{}: store: {e}", path.display()))?;
            host.use_store(store);
        }
        if hosted.iter().any(
            |h| matches!(h, Hosted::Stock(e) if e.stock.id() == jaus::components::reflexive_driver::ID),
        ) {
            host.expect_reflexive_driver();
        }
        // One `Hosted` per `host:` entry, in order.
        for (i, h) in hosted.into_iter().enumerate() {
            let parts = match h {
                Hosted::Vehicle => {
                    let (parts, vehicle, scanner) = jaus_sim::demo::vehicle_with_scanner_at(
                        t0,
                        &jaus_sim::demo::Options {
                            local_waypoint_driver: true,
                            ..jaus_sim::demo::Options::default()
                        },
                        self.subsystem,
                        self.node,
                    );
                    let lights = crate::sim_lights::SimLights(vehicle);
                    native.push(Box::new(jaus_as4::ugv::IlluminationService::over(lights)));
                    native.add_range_sensor(scanner);
                    parts
                }
                Hosted::Arm => jaus_sim::arm_demo::arm_components(
                    &jaus_sim::SimArm::new(jaus_sim::ArmParams::six_axis()),
                    self.subsystem,
                    self.node,
                    t0,
                ),
                Hosted::Stock(e) if e.stock.id() == jaus::components::communicator::ID => {
                    vec![self
                        .build_communicator(&mut host, &e, path)
                        .map_err(|e| format!("{}: host[{i}]: {e}", path.display()))?]
                }
                Hosted::Stock(e) => {
                    let built = host
                        .build(&e)
                        .map_err(|e| format!("{}: host[{i}]: {e}", path.display()))?;
                    if e.stock.id() == jaus::components::range_sensor::ID {
                        native.add_range_sensor(host.scanner().clone());
                    }
                    vec![built]
                }
            };
            for p in parts {
                node.add_boxed(p)
                    .map_err(|e| format!("{}: host[{i}]: {e}", path.display()))?;
            }
        }
        Ok((node, native.services))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `ros2:` is a `Ros2Config`: its keys checked, its values validated, robot mode
    /// only, and none of the robot's components where a `host:` entry or an
    /// `as4_vehicles:` proxy is; each error names the file and the key.
    #[test]
    fn ros2_is_read_with_the_bridge_settings_and_errors_name_the_file_and_key() {
        let dir = std::env::temp_dir().join(format!("jaus-node-ros2-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("robot.yaml");
        let load = |tail: &str| {
            std::fs::write(
                &path,
                format!("subsystem: 1\nnode: 1\nbind: 127.0.0.1:0\n{tail}"),
            )
            .unwrap();
            NodeFile::load(&path)
        };
        let f = load(
            "host: [local_waypoint_driver, { component: primitive_driver, instance: 2 }]\nas4: {}\nros2:\n  domain_id: 7\n  effort: { max_linear: 0.5 }\n",
        )
        .unwrap();
        let r = f.ros2.as_ref().unwrap();
        assert_eq!((r.domain_id, r.effort.max_linear), (7, 0.5));
        assert_eq!(r.topics.odom, "odom");
        assert!(load("").unwrap().ros2.is_none());

        let e = load("ros2: { domian_id: 7 }\n").unwrap_err();
        assert!(
            e.contains("robot.yaml") && e.contains("ros2") && e.contains("domian_id"),
            "{e}"
        );
        let e = load("ros2:\n  topics: { odom: a//b }\n").unwrap_err();
        assert!(
            e.contains("robot.yaml:5:") && e.contains("topics.odom"),
            "{e}"
        );
        let e = load("ros2:\n  domain_id: 300\n").unwrap_err();
        assert!(
            e.contains("robot.yaml:5:") && e.contains("domain_id 300"),
            "{e}"
        );
        let e = load("ros2: { vehicle: { subsystem: 2 } }\n").unwrap_err();
        assert!(e.contains("jaus ros2 --vehicle"), "{e}");

        let e = load("host: [global_pose_sensor]\nros2: {}\n").unwrap_err();
        assert!(
            e.contains("robot.yaml:4:")
                && e.contains("host[0]: `global_pose_sensor` instance 1 takes 1.1.38.1")
                && e.contains("`ros2:` hosts the ROS 2 robot's Global Pose Sensor there"),
            "{e}"
        );
        // The lidar and camera only when on.
        assert!(load("host: [range_sensor, visual_sensor]\nros2: {}\n").is_ok());
        let e = load("host: [visual_sensor]\nros2: { sensors: { visual: true } }\n").unwrap_err();
        assert!(
            e.contains("host[0]: `visual_sensor` instance 1 takes 1.1.37.1")
                && e.contains("`ros2:` hosts the ROS 2 robot's Visual Sensor there"),
            "{e}"
        );
        let e = load("host: [vehicle]\nros2: {}\n").unwrap_err();
        assert!(
            e.contains("host[0]: `vehicle`")
                && e.contains("1.1.33.1")
                && e.contains("leave out `vehicle`"),
            "{e}"
        );
        let e = load("as4_vehicles: [{ peer: 127.0.0.1:9 }]\nros2: {}\n").unwrap_err();
        assert!(
            e.contains("as4_vehicles[0]: its proxy takes 1.1.42.1")
                && e.contains("Velocity State Sensor"),
            "{e}"
        );
        load("as4_vehicles: [{ peer: 127.0.0.1:9, instance: 2 }]\nros2: {}\n").unwrap();
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn as4_beside_an_access_policy_is_refused_with_where() {
        let dir = std::env::temp_dir().join(format!("jaus-as4-policy-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("n.yaml");
        let base = "subsystem: 1\nnode: 1\nbind: 127.0.0.1:0\nas4: {}\n";
        std::fs::write(&path, format!("{base}policy: {{ default: query }}\n")).unwrap();
        let e = NodeFile::load(&path).unwrap_err();
        assert!(
            e.contains("n.yaml:4:1: as4: the access policy does not cover AS-4"),
            "{e}"
        );
        // Without a policy (open, as announced when the node starts) it loads.
        std::fs::write(&path, base).unwrap();
        assert!(NodeFile::load(&path).unwrap().as4.is_some());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
