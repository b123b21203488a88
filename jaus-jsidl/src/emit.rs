//! The imported definitions written as YAML of the definition language, keys in a fixed
//! order and nothing left to chance: the same JSIDL gives the same bytes.

use jaus_spec::model::{
    ActionDef, BehaviourDef, DefaultStateDef, Embeds, EnumValue, EventDef, FieldDef, Length,
    MessageDef, ServiceDef, ServiceRef, ServiceTransitionDef, StateDef, TransitionKind, TypeDef,
    TypeKind,
};
use serde_yaml::{Mapping, Value};

/// A mapping built key by key, leaving out what is absent or empty.
#[derive(Default)]
struct Map(Mapping);

impl Map {
    fn put(mut self, key: &str, v: impl Into<Value>) -> Self {
        self.0.insert(Value::String(key.into()), v.into());
        self
    }
    fn opt(self, key: &str, v: Option<impl Into<Value>>) -> Self {
        match v {
            Some(v) => self.put(key, v),
            None => self,
        }
    }
    fn list(self, key: &str, v: Vec<Value>) -> Self {
        if v.is_empty() {
            self
        } else {
            self.put(key, Value::Sequence(v))
        }
    }
    fn flag(self, key: &str, on: bool) -> Self {
        if on {
            self.put(key, true)
        } else {
            self
        }
    }
    fn done(self) -> Value {
        Value::Mapping(self.0)
    }
}

fn strings(v: &[String]) -> Vec<Value> {
    v.iter().map(|s| Value::String(s.clone())).collect()
}

/// A field definition.
fn field(f: &FieldDef) -> Value {
    field_map(Map::default().put("name", f.name.as_str()), f)
}

/// A list element given in full (a list of lists): a field without a name.
fn elem(f: &FieldDef) -> Value {
    field_map(Map::default(), f)
}

/// The keys of a field after its name.
fn field_map(m: Map, f: &FieldDef) -> Value {
    m.put("type", f.ty.as_str())
        .opt("bit", f.bit.map(u64::from))
        .opt("count", f.count.as_deref())
        .opt(
            "length",
            f.length.map(|l| match l {
                Length::Fixed(n) => Value::from(n as u64),
                Length::Rest => Value::from("rest"),
                Length::Nul => Value::from("nul"),
            }),
        )
        .opt(
            "of",
            f.of.as_ref().map(|e| {
                if e.0.count.is_none() && e.0.of.is_none() {
                    Value::from(e.0.ty.as_str())
                } else {
                    elem(&e.0)
                }
            }),
        )
        .opt(
            "scale",
            f.scale
                .map(|[lo, hi]| Value::Sequence(vec![lo.into(), hi.into()])),
        )
        .opt("unit", f.unit.as_deref())
        .opt(
            "embeds",
            f.embeds.map(|e| match e {
                Embeds::Message => "message",
            }),
        )
        .opt("embeds_if", f.embeds_if.as_deref())
        .opt("description", f.description.as_deref())
        .done()
}

fn value(v: &EnumValue) -> Value {
    Map::default()
        .put("name", v.name.as_str())
        .put("value", v.value)
        .opt("description", v.description.as_deref())
        .done()
}

/// A named type.
pub(crate) fn type_def(t: &TypeDef) -> Value {
    let kind = match t.kind {
        TypeKind::Record => "record",
        TypeKind::Enum => "enum",
        TypeKind::Bitfield => "bitfield",
        TypeKind::Union => "union",
    };
    Map::default()
        .put("name", t.name.as_str())
        .put("kind", kind)
        .opt("repr", t.repr.as_deref())
        .opt("presence", t.presence.as_deref())
        .opt("description", t.description.as_deref())
        .list("fields", t.fields.iter().map(field).collect())
        .list("values", t.values.iter().map(value).collect())
        .list(
            "bits",
            t.bits
                .iter()
                .map(|b| {
                    Map::default()
                        .put("name", b.name.as_str())
                        .opt("bit", b.bit.map(u64::from))
                        .opt(
                            "bits",
                            b.bits.map(|[l, h]| {
                                Value::Sequence(vec![u64::from(l).into(), u64::from(h).into()])
                            }),
                        )
                        .opt("description", b.description.as_deref())
                        .done()
                })
                .collect(),
        )
        .list(
            "variants",
            t.variants
                .iter()
                .map(|v| {
                    Map::default()
                        .put("name", v.name.as_str())
                        .put("tag", v.tag)
                        .opt("type", v.ty.as_deref())
                        .opt("description", v.description.as_deref())
                        .done()
                })
                .collect(),
        )
        .done()
}

/// A message.
pub(crate) fn message(m: &MessageDef) -> Value {
    Map::default()
        .put("name", m.name.as_str())
        .put("code", format!("0x{:04X}", m.code.0))
        .opt("is_command", m.is_command)
        .opt("presence", m.presence.as_deref())
        .opt("description", m.description.as_deref())
        .list("fields", m.fields.iter().map(field).collect())
        .done()
}

fn service_ref(r: &ServiceRef) -> Value {
    Map::default()
        .put("name", r.name.as_str())
        .put("id", r.id.as_str())
        .put("version", r.version.as_str())
        .done()
}

fn event(e: &EventDef) -> Value {
    Map::default()
        .put("name", e.name.as_str())
        .opt("description", e.description.as_deref())
        .list("fields", e.fields.iter().map(field).collect())
        .done()
}

fn action(a: &ActionDef) -> Value {
    Map::default()
        .put("name", a.name.as_str())
        .list("args", strings(&a.args))
        .flag("send", a.send)
        .opt("description", a.description.as_deref())
        .done()
}

fn transition(t: &ServiceTransitionDef) -> Value {
    let kind = match t.kind {
        TransitionKind::Internal => "internal",
        TransitionKind::Simple => "simple",
        TransitionKind::Push => "push",
        TransitionKind::Pop => "pop",
    };
    Map::default()
        .opt("on", t.on.as_deref())
        .list(
            "parameters",
            t.parameters
                .iter()
                .map(|p| {
                    Map::default()
                        .put("type", p.ty.as_str())
                        .put("name", p.name.as_str())
                        .opt("description", p.description.as_deref())
                        .done()
                })
                .collect(),
        )
        .opt(
            "guard",
            t.guard.as_ref().map(|g| {
                Map::default()
                    .put("condition", g.condition.as_str())
                    .opt("description", g.description.as_deref())
                    .done()
            }),
        )
        .put("kind", kind)
        .opt("to", t.to.as_deref())
        .opt("pop", t.pop.as_ref().map(action))
        .list("actions", t.actions.iter().map(action).collect())
        .opt("description", t.description.as_deref())
        .done()
}

fn default_state(d: &DefaultStateDef) -> Value {
    Map::default()
        .opt("description", d.description.as_deref())
        .list(
            "transitions",
            d.transitions.iter().map(transition).collect(),
        )
        .list(
            "default_transitions",
            d.default_transitions.iter().map(transition).collect(),
        )
        .done()
}

fn state(s: &StateDef) -> Value {
    Map::default()
        .put("name", s.name.as_str())
        .opt("initial", s.initial.as_deref())
        .flag("redefine", s.redefine)
        .opt("description", s.description.as_deref())
        .list("entry", s.entry.iter().map(action).collect())
        .list("exit", s.exit.iter().map(action).collect())
        .list(
            "transitions",
            s.transitions.iter().map(transition).collect(),
        )
        .list(
            "default_transitions",
            s.default_transitions.iter().map(transition).collect(),
        )
        .list("states", s.states.iter().map(state).collect())
        .opt("default", s.default.as_ref().map(default_state))
        .done()
}

fn behaviour(b: &BehaviourDef) -> Value {
    Map::default()
        .flag("stateless", b.stateless)
        .list(
            "start",
            b.start
                .iter()
                .map(|s| {
                    Map::default()
                        .put("machine", s.machine.as_str())
                        .put("state", s.state.as_str())
                        .done()
                })
                .collect(),
        )
        .list(
            "machines",
            b.machines
                .iter()
                .map(|m| {
                    Map::default()
                        .put("name", m.name.as_str())
                        .flag("extends", m.extends)
                        .opt("description", m.description.as_deref())
                        .list("states", m.states.iter().map(state).collect())
                        .opt("default", m.default.as_ref().map(default_state))
                        .done()
                })
                .collect(),
        )
        .done()
}

/// A service.
pub(crate) fn service(s: &ServiceDef) -> Value {
    Map::default()
        .put("name", s.name.as_str())
        .put("id", s.id.as_str())
        .put("version", s.version.as_str())
        .opt("description", s.description.as_deref())
        .opt("assumptions", s.assumptions.as_deref())
        .opt("inherits", s.inherits.as_ref().map(service_ref))
        .list("client_of", s.client_of.iter().map(service_ref).collect())
        .list("inputs", strings(&s.inputs))
        .list("outputs", strings(&s.outputs))
        .list("events", s.events.iter().map(event).collect())
        .opt("behaviour", s.behaviour.as_ref().map(behaviour))
        .done()
}

/// A whole file: header comment, then `extends: none`, the group, and the items.
pub(crate) fn file(
    source: &str,
    group: &str,
    types: &[TypeDef],
    messages: &[MessageDef],
    services: &[ServiceDef],
) -> Result<String, serde_yaml::Error> {
    let doc = Map::default()
        .put("extends", "none")
        .put("group", group)
        .list("types", types.iter().map(type_def).collect())
        .list("messages", messages.iter().map(message).collect())
        .list("services", services.iter().map(service).collect())
        .done();
    let body = serde_yaml::to_string(&doc)?;
    Ok(format!(
        "# Imported from the JSIDL file {source} by `jaus-gen jsidl`: regenerate, do not edit.\n{body}"
    ))
}
