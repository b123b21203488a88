//! Discovery (`urn:jaus:jss:core:Discovery` 1.1): who this component is, which services
//! it and the components it knows offer.
//!
//! Every component of this runtime answers Discovery's queries itself, from what it
//! knows: its own services (the Core's and its [`Service`](crate::service::Service)s),
//! the components that sent it Register Services, and the other components of its node
//! (an [`As4Node`](crate::node::As4Node) registers them with each other). The registry
//! holds at most [`CoreConfig::max_registrations`](super::CoreConfig::max_registrations)
//! components; more are refused and counted.
//!
//! * Query Identification: subsystem, node and component are answered with the names of
//!   [`Identification`]; a system only when a system name is configured.
//! * Query Configuration: the nodes and components of the subsystem, or of this node.
//!   Instance ids are 0 (one instance per component id).
//! * Query Subsystem List: this subsystem (with this component as the one to contact)
//!   and the others learnt from registrations.
//! * Query Services / Query Service List: the services of the components asked for (255
//!   = every node or component, 65535 = every subsystem; the search filter of Query
//!   Service List keeps the URIs containing it).

use std::collections::BTreeMap;

use jaus::net::as5669a::As4Id;

use crate::messages::{
    ComponentAddress, ComponentInstance, ComponentServices, ConfigurationType, EntityType,
    IdentificationType, NodeConfiguration, NodeServices, QueryServiceList, QueryServices,
    ReportConfiguration, ReportIdentification, ReportServiceList, ReportServices,
    ReportSubsystemList, ServiceInfo, SubsystemServices,
};
use crate::outgoing::ServiceId;

/// Names Report Identification gives.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Identification {
    /// The system's name; `None`: queries about the system are not answered.
    pub system: Option<String>,
    /// The subsystem's name (the vehicle's, the OCU's).
    pub subsystem: String,
    /// What the subsystem is (default [`EntityType::Vehicle`]).
    pub subsystem_type: EntityType,
    /// The node's name.
    pub node: String,
    /// The component's name.
    pub component: String,
}

impl Identification {
    /// `name` for the subsystem, node and component, a vehicle, no system.
    pub fn named(name: &str) -> Self {
        Self {
            system: None,
            subsystem: name.to_string(),
            subsystem_type: EntityType::Vehicle,
            node: name.to_string(),
            component: name.to_string(),
        }
    }
}

/// The service record of a [`ServiceId`].
pub fn service_info(id: &ServiceId) -> ServiceInfo {
    ServiceInfo {
        uri: id.uri.to_string(),
        major_version: id.major,
        minor_version: id.minor,
    }
}

/// What Discovery knows.
#[derive(Debug, Clone)]
pub struct Discovery {
    me: As4Id,
    ident: Identification,
    known: BTreeMap<As4Id, Vec<ServiceInfo>>,
    max_registrations: usize,
}

impl Discovery {
    /// Discovery of component `me`, whose own services are `own`.
    pub fn new(me: As4Id, ident: Identification, own: Vec<ServiceInfo>, max: usize) -> Self {
        Self {
            me,
            ident,
            known: BTreeMap::from([(me, own)]),
            max_registrations: max,
        }
    }

    /// The names it reports.
    pub fn identification(&self) -> &Identification {
        &self.ident
    }

    /// Replaces this component's own services.
    pub fn set_own(&mut self, own: Vec<ServiceInfo>) {
        self.known.insert(self.me, own);
    }

    /// Register Services from `from` (or a sibling the node registers): replaces what
    /// was known of it. `Err` when the registry is full.
    pub fn register(&mut self, from: As4Id, services: Vec<ServiceInfo>) -> Result<(), String> {
        let others = self.known.len() - 1;
        if from != self.me && !self.known.contains_key(&from) && others >= self.max_registrations {
            return Err(format!(
                "registry full ({} components)",
                self.max_registrations
            ));
        }
        self.known.insert(from, services);
        Ok(())
    }

    /// The components known (this one included) and their services.
    pub fn known(&self) -> impl Iterator<Item = (As4Id, &[ServiceInfo])> + '_ {
        self.known.iter().map(|(id, s)| (*id, s.as_slice()))
    }

    /// Report Identification for `query_type` (`None`: not answered).
    pub fn identify(&self, query_type: IdentificationType) -> Option<ReportIdentification> {
        let (entity_type, name) = match query_type {
            IdentificationType::System => (EntityType::OtherSubsystem, self.ident.system.clone()?),
            IdentificationType::Subsystem => {
                (self.ident.subsystem_type, self.ident.subsystem.clone())
            }
            IdentificationType::Node => (EntityType::Node, self.ident.node.clone()),
            IdentificationType::Component => (EntityType::Component, self.ident.component.clone()),
            _ => return None,
        };
        let mut identification = name;
        truncate(&mut identification, 255);
        Some(ReportIdentification {
            query_type,
            entity_type,
            identification,
        })
    }

    /// Report Configuration for `scope` (`None`: not answered).
    pub fn configuration(&self, scope: ConfigurationType) -> Option<ReportConfiguration> {
        let only_node = match scope {
            ConfigurationType::Subsystem => None,
            ConfigurationType::Node => Some(self.me.node),
            _ => return None,
        };
        let mut nodes: BTreeMap<u8, Vec<ComponentInstance>> = BTreeMap::new();
        for id in self
            .known
            .keys()
            .filter(|id| id.subsystem == self.me.subsystem)
        {
            if only_node.is_none_or(|n| n == id.node) {
                nodes.entry(id.node).or_default().push(ComponentInstance {
                    component_id: id.component,
                    instance_id: 0,
                });
            }
        }
        let nodes = nodes
            .into_iter()
            .map(|(node_id, components)| NodeConfiguration {
                node_id,
                components,
            })
            .collect();
        Some(ReportConfiguration { nodes })
    }

    /// Report Subsystem List.
    pub fn subsystems(&self) -> ReportSubsystemList {
        let mut contact: BTreeMap<u16, As4Id> = BTreeMap::new();
        for id in self.known.keys() {
            contact.entry(id.subsystem).or_insert(*id);
        }
        contact.insert(self.me.subsystem, self.me);
        ReportSubsystemList {
            subsystems: contact.values().map(|id| address(*id)).collect(),
        }
    }

    /// Report Services for Query Services (this subsystem only).
    pub fn services(&self, q: &QueryServices) -> ReportServices {
        let mut nodes = Vec::new();
        for nq in &q.nodes {
            let ids = |c: u8| nq.component_ids.contains(&255) || nq.component_ids.contains(&c);
            nodes.extend(
                self.node_services(self.me.subsystem, nq.node_id, |c| ids(c).then_some(None)),
            );
        }
        ReportServices { nodes }
    }

    /// Report Service List for Query Service List.
    pub fn service_list(&self, q: &QueryServiceList) -> ReportServiceList {
        let mut subsystems = Vec::new();
        let all_subsystems: Vec<u16> = {
            let mut s: Vec<u16> = self.known.keys().map(|id| id.subsystem).collect();
            s.dedup();
            s
        };
        for sq in &q.subsystems {
            let targets: Vec<u16> = if sq.subsystem_id == 0xFFFF {
                all_subsystems.clone()
            } else {
                vec![sq.subsystem_id]
            };
            for subsystem_id in targets {
                let mut nodes = Vec::new();
                for nq in &sq.nodes {
                    nodes.extend(self.node_services(subsystem_id, nq.node_id, |c| {
                        nq.components
                            .iter()
                            .find(|f| f.component_id == 255 || f.component_id == c)
                            .map(|f| f.search_filter.clone())
                    }));
                }
                if !nodes.is_empty() {
                    subsystems.push(SubsystemServices {
                        subsystem_id,
                        nodes,
                    });
                }
            }
        }
        ReportServiceList { subsystems }
    }

    /// The services of the components of `node` (255: every node) of `subsystem` that
    /// `pick` selects (`Some(filter)`: selected, services whose URI contains the filter).
    fn node_services(
        &self,
        subsystem: u16,
        node: u8,
        pick: impl Fn(u8) -> Option<Option<String>>,
    ) -> Vec<NodeServices> {
        let mut by_node: BTreeMap<u8, Vec<ComponentServices>> = BTreeMap::new();
        for (id, services) in &self.known {
            if id.subsystem != subsystem || (node != 255 && id.node != node) {
                continue;
            }
            let Some(filter) = pick(id.component) else {
                continue;
            };
            let services = services
                .iter()
                .filter(|s| filter.as_deref().is_none_or(|f| s.uri.contains(f)))
                .cloned()
                .collect();
            by_node.entry(id.node).or_default().push(ComponentServices {
                component_id: id.component,
                instance_id: 0,
                services,
            });
        }
        by_node
            .into_iter()
            .map(|(node_id, components)| NodeServices {
                node_id,
                components,
            })
            .collect()
    }
}

fn address(id: As4Id) -> ComponentAddress {
    ComponentAddress {
        subsystem_id: id.subsystem,
        node_id: id.node,
        component_id: id.component,
    }
}

fn truncate(s: &mut String, max: usize) {
    if s.len() > max {
        let mut end = max;
        while !s.is_char_boundary(end) {
            end -= 1;
        }
        s.truncate(end);
    }
}
