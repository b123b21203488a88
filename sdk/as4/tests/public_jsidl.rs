//! The wire layout of our YAML against the public JSIDL, message by message.
//!
//! Runs only when `JAUS_JSIDL_DIR` names the `GUI/resources/xml` directory of the JAUS
//! Tool Set repository (it holds `urn.jaus.jss.core-v1.1`, `urn.jaus.jss.core-v1.0`,
//! `urn.jaus.jss.mobility`, `urn.jaus.jss.manipulator-v2.0`,
//! `urn.jaus.jss.manipulator-v1.0`, `urn.jaus.jss.environmentSensing`,
//! `urn.jaus.jss.ugv`, `urn.jaus.jss.missionSpooler` and `urn.jaus.jss.hmi`); otherwise
//! it says that it skipped and passes:
//!
//! ```sh
//! JAUS_JSIDL_DIR=/path/to/jaustoolset/GUI/resources/xml \
//!     cargo test -p jaus-as4 --test public_jsidl -- --nocapture
//! ```
//!
//! Core v1.1 is imported on its own; Mobility with Core v1.0, whose services it inherits,
//! and without its own copy of the Core basic types (`MessageSet/CoreBasicTypes.xml`,
//! which declares the set Core v1.0 declares), as docs/as4.md describes; Manipulator v2.0,
//! UGV and Mission Spooling with Core v1.1, whose services they inherit; Environment
//! Sensing with Core v1.1; HMI with Core v1.0, whose services it inherits. Both sides are
//! reduced to their [`Snapshot`] (the wire layout `jaus-gen diff` and the lock files
//! compare), then every message of the import is flattened into the sequence of what is
//! on the wire: records are expanded where they are used (a record of one field is that
//! field), an enumeration or bit field is its integer. Names, descriptions and how the
//! layout is split into named types may differ; the bytes may not. Where both sides
//! name the values of an enumeration, the members of a bit field or a unit, those must
//! agree too, and so must `is_command`.
//!
//! The first revisions kept for `jaus-gen diff` (`revisions/core-v1.0/` with
//! `revisions/manipulator-v1.0/`) are compared the same way with Core v1.0 and
//! Manipulator v1.0 (imported with Core v1.0).

use jaus_gen::snapshot::{wire_text, FieldSnap, FormSnap, MessageSnap, Snapshot, TypeSnap};
use jaus_spec::{Bits, Spec, Wire};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

mod jsidl_common;
use jsidl_common::copy_without;

/// Messages the public JSIDL marks `is_command="false"` although they command: Manipulator
/// v2.0's (and v1.0's) Execute List (0x061E) starts the list driver's motion, as
/// Mobility's Execute List (0x041E, a command in its JSIDL) does. Ours are commands; only
/// the flag differs.
const COMMAND_AS_PUBLISHED_IS_NOT: &[u16] = &[0x061E];

/// One item of a flattened layout.
#[derive(Debug, Clone)]
struct Item {
    /// What decides the bytes: `u16`, `scaled u32 [-90, 90]`, `list count u8 of (`.
    wire: String,
    /// The values of an enumeration or the members of a bit field, when named.
    detail: Option<String>,
    /// The unit of a value.
    unit: Option<String>,
    /// Where it is: the field path and the definition's file and line.
    at: String,
}

struct Flattener<'a> {
    types: BTreeMap<&'a str, &'a TypeSnap>,
}

impl<'a> Flattener<'a> {
    fn new(s: &'a Snapshot) -> Self {
        Self {
            types: s.types.iter().map(|t| (t.name.as_str(), t)).collect(),
        }
    }

    fn push(out: &mut Vec<Item>, wire: String, at: &str) {
        out.push(Item {
            wire,
            detail: None,
            unit: None,
            at: at.to_string(),
        });
    }

    fn message(&self, m: &MessageSnap) -> Vec<Item> {
        let mut out = Vec::new();
        if let Some(p) = m.presence {
            Self::push(&mut out, format!("presence {}", p.rust()), &m.name);
        }
        self.fields(&m.fields, &m.name, &mut out);
        out
    }

    fn fields(&self, fields: &[FieldSnap], owner: &str, out: &mut Vec<Item>) {
        for f in fields {
            let at = format!("{owner}.{} ({})", f.name, f.at);
            if let Some(b) = f.bit {
                Self::push(out, format!("optional bit {b} ("), &at);
            }
            if let Some(p) = &f.present_if {
                Self::push(out, format!("present if {p} ("), &at);
            }
            self.wire(
                &f.wire,
                f.unit.as_deref(),
                &format!("{owner}.{}", f.name),
                &at,
                out,
            );
            if f.bit.is_some() || f.present_if.is_some() {
                Self::push(out, ")".into(), &at);
            }
        }
    }

    fn wire(&self, w: &Wire, unit: Option<&str>, path: &str, at: &str, out: &mut Vec<Item>) {
        match w {
            Wire::Named {
                name,
                size,
                tag_field,
                ..
            } => {
                if let Some(s) = size {
                    Self::push(out, format!("size {} (", s.rust()), at);
                }
                if let Some(t) = tag_field {
                    Self::push(out, format!("tag in field {t}"), at);
                }
                let Some(ty) = self.types.get(name.as_str()) else {
                    Self::push(out, format!("unknown type {name}"), at);
                    return;
                };
                self.named(ty, unit, path, at, out);
                if size.is_some() {
                    Self::push(out, ")".into(), at);
                }
            }
            Wire::List { count, elem } => {
                let count = count.map_or("rest".to_string(), |c| format!("count {}", c.rust()));
                Self::push(out, format!("list {count} of ("), at);
                self.wire(elem, unit, &format!("{path}[]"), at, out);
                Self::push(out, ")".into(), at);
            }
            Wire::ListField { field, elem, .. } => {
                Self::push(out, format!("list count_field {field} of ("), at);
                self.wire(elem, unit, &format!("{path}[]"), at, out);
                Self::push(out, ")".into(), at);
            }
            leaf => out.push(Item {
                wire: wire_text(leaf),
                detail: None,
                unit: unit.map(String::from),
                at: at.to_string(),
            }),
        }
    }

    fn named(&self, ty: &TypeSnap, unit: Option<&str>, path: &str, at: &str, out: &mut Vec<Item>) {
        match &ty.form {
            FormSnap::Record { presence, fields } => {
                if let Some(p) = presence {
                    Self::push(out, format!("presence {}", p.rust()), at);
                }
                self.fields(fields, path, out);
            }
            FormSnap::Enum { repr, values } => {
                let v: Vec<String> = values.iter().map(|v| v.value.to_string()).collect();
                out.push(Item {
                    wire: repr.rust().into(),
                    detail: Some(format!("values {}", v.join(", "))),
                    unit: unit.map(String::from),
                    at: at.to_string(),
                });
            }
            FormSnap::Bitfield { repr, members } => {
                let m: Vec<String> = members
                    .iter()
                    .map(|m| match m.bits {
                        Bits::Flag(b) => format!("bit {b}"),
                        Bits::Range { lo, hi } => format!("bits {lo}-{hi}"),
                    })
                    .collect();
                out.push(Item {
                    wire: repr.rust().into(),
                    detail: Some(format!("members {}", m.join(", "))),
                    unit: None,
                    at: at.to_string(),
                });
            }
            FormSnap::Union { repr, variants } => {
                Self::push(out, format!("union tag {} {{", repr.rust()), at);
                for v in variants {
                    Self::push(out, format!("tag {}:", v.tag), at);
                    match &v.wire {
                        Some(w) => self.wire(w, None, &format!("{path}.{}", v.name), at, out),
                        None => Self::push(out, "no value".into(), at),
                    }
                }
                Self::push(out, "}".into(), at);
            }
        }
    }
}

/// Every difference between our flattened message and the import's: the first item
/// whose bytes differ (what follows it would only repeat the shift), and before it every
/// named value, bit-field member or unit that disagrees.
fn compare(ours: &[Item], theirs: &[Item]) -> Vec<String> {
    let mut diffs = Vec::new();
    for (i, (o, t)) in ours.iter().zip(theirs).enumerate() {
        if o.wire != t.wire {
            diffs.push(format!(
                "item {i}: ours `{}` at {}, the JSIDL's `{}` at {}",
                o.wire, o.at, t.wire, t.at
            ));
            return diffs;
        }
        if let (Some(a), Some(b)) = (&o.detail, &t.detail) {
            if a != b {
                diffs.push(format!("{}: ours {a}, the JSIDL's {b} ({})", o.at, t.at));
            }
        }
        if let (Some(a), Some(b)) = (&o.unit, &t.unit) {
            if a != b {
                diffs.push(format!(
                    "{}: unit ours `{a}`, the JSIDL's `{b}` ({})",
                    o.at, t.at
                ));
            }
        }
    }
    if ours.len() != theirs.len() {
        let (longer, who) = if ours.len() > theirs.len() {
            (&ours[theirs.len()], "ours")
        } else {
            (&theirs[ours.len()], "the JSIDL's")
        };
        diffs.push(format!(
            "{who} goes on with `{}` at {} ({} items against {})",
            longer.wire,
            longer.at,
            ours.len(),
            theirs.len()
        ));
    }
    diffs
}

/// `is_command` of every message of `spec`, by code.
fn commands(spec: &Spec) -> BTreeMap<u16, Option<bool>> {
    spec.messages
        .iter()
        .map(|m| (m.def.code.0, m.def.is_command))
        .collect()
}

/// What one imported set gave: its snapshot, `is_command` by code, and the codes of the
/// messages to compare.
struct Imported {
    label: &'static str,
    snap: Snapshot,
    commands: BTreeMap<u16, Option<bool>>,
    codes: BTreeSet<u16>,
}

fn import(label: &'static str, dirs: &[PathBuf], group: &str) -> Imported {
    let spec = jaus_jsidl::import(dirs)
        .and_then(|i| i.load())
        .unwrap_or_else(|e| panic!("importing {label}: {e}"));
    let codes = spec
        .messages
        .iter()
        .filter(|m| m.group == group)
        .map(|m| m.def.code.0)
        .collect();
    Imported {
        label,
        snap: Snapshot::from_spec(&spec),
        commands: commands(&spec),
        codes,
    }
}

#[test]
fn our_yaml_has_the_wire_layout_of_the_public_jsidl() {
    let Some(root) = std::env::var_os("JAUS_JSIDL_DIR").map(PathBuf::from) else {
        println!(
            "skipped: set JAUS_JSIDL_DIR to the JAUS Tool Set's GUI/resources/xml directory \
             to compare our YAML with the public JSIDL"
        );
        return;
    };
    let defs = Path::new(env!("CARGO_MANIFEST_DIR")).join("defs");
    let spec = jaus_spec::load_dirs(&[&defs]).expect("our definitions validate");

    let core = import(
        "Core v1.1",
        &[root.join("urn.jaus.jss.core-v1.1")],
        "jaus_jss_core_v1_1",
    );
    // Core v1.0: what a client of the older revision (the JAUS Tool Set's own examples)
    // sends and expects; its messages must be ours byte for byte (v1.1 only adds).
    let core_v1_0 = import(
        "Core v1.0",
        &[root.join("urn.jaus.jss.core-v1.0")],
        "jaus_jss_core_v1_0",
    );
    let tmp = std::env::temp_dir().join(format!("jaus-as4-jsidl-{}", std::process::id()));
    let mobility_dir = tmp.join("urn.jaus.jss.mobility");
    copy_without(
        &root.join("urn.jaus.jss.mobility"),
        &mobility_dir,
        Path::new("MessageSet/CoreBasicTypes.xml"),
    );
    let mobility = import(
        "Mobility v1.0",
        &[root.join("urn.jaus.jss.core-v1.0"), mobility_dir],
        "jaus_jss_mobility",
    );
    let _ = std::fs::remove_dir_all(&tmp);
    let environment = import(
        "Environment Sensing",
        &[
            root.join("urn.jaus.jss.core-v1.1"),
            root.join("urn.jaus.jss.environmentSensing"),
        ],
        "jaus_jss_environmentsensing",
    );
    let manipulator = import(
        "Manipulator v2.0",
        &[
            root.join("urn.jaus.jss.core-v1.1"),
            root.join("urn.jaus.jss.manipulator-v2.0"),
        ],
        "jaus_jss_manipulator_v2_0",
    );
    let ugv = import(
        "UGV",
        &[
            root.join("urn.jaus.jss.core-v1.1"),
            root.join("urn.jaus.jss.ugv"),
        ],
        "jaus_jss_ugv",
    );
    let mission_spooling = import(
        "Mission Spooling",
        &[
            root.join("urn.jaus.jss.core-v1.1"),
            root.join("urn.jaus.jss.missionSpooler"),
        ],
        "jaus_jss_missionspooler",
    );
    // HMI: with Core v1.0, whose services the published set inherits.
    let hmi = import(
        "HMI",
        &[
            root.join("urn.jaus.jss.core-v1.0"),
            root.join("urn.jaus.jss.hmi"),
        ],
        "jaus_jss_hmi",
    );

    assert_same_layouts(
        &spec,
        &[
            &core,
            &core_v1_0,
            &mobility,
            &manipulator,
            &environment,
            &ugv,
            &mission_spooling,
            &hmi,
        ],
    );
}

/// Our first revisions of Core and Manipulator (`revisions/core-v1.0/` and
/// `revisions/manipulator-v1.0/`, loaded together as `jaus-gen diff` loads them) against
/// the public JSIDL of Core v1.0 and of Manipulator v1.0 (imported with Core v1.0): every
/// message of both, byte for byte, as the test above compares `defs/`.
#[test]
fn our_v1_0_revisions_have_the_wire_layout_of_the_public_jsidl() {
    let Some(root) = std::env::var_os("JAUS_JSIDL_DIR").map(PathBuf::from) else {
        println!("skipped: set JAUS_JSIDL_DIR to compare our v1.0 revisions with the public JSIDL");
        return;
    };
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("revisions");
    let spec = jaus_spec::load_dirs(&[dir.join("core-v1.0"), dir.join("manipulator-v1.0")])
        .expect("our v1.0 definitions validate");
    let core_v1_0 = import(
        "Core v1.0",
        &[root.join("urn.jaus.jss.core-v1.0")],
        "jaus_jss_core_v1_0",
    );
    let manipulator_v1_0 = import(
        "Manipulator v1.0",
        &[
            root.join("urn.jaus.jss.core-v1.0"),
            root.join("urn.jaus.jss.manipulator-v1.0"),
        ],
        "jaus_jss_manipulator_v1_0",
    );
    assert_same_layouts(&spec, &[&core_v1_0, &manipulator_v1_0]);
}

/// [`compare_sets`], and every message of `spec` compared: fails on any problem.
fn assert_same_layouts(spec: &Spec, sets: &[&Imported]) {
    let (problems, covered, compared) = compare_sets(spec, sets);
    println!(
        "{compared} comparisons, {} distinct messages, {} of ours",
        covered.len(),
        spec.messages.len()
    );
    assert!(
        problems.is_empty(),
        "{} difference(s) from the public JSIDL:\n{}",
        problems.len(),
        problems.join("\n")
    );
    assert_eq!(covered.len(), spec.messages.len());
}

/// The flattening itself: a record of one field is that field, an enumeration is its
/// integer, and a moved field is found.
#[test]
fn flattening_ignores_names_and_records_but_not_bytes() {
    let load = |yaml: &str| {
        let spec = jaus_spec::load_texts(vec![(PathBuf::from("t.yaml"), yaml.to_string())])
            .expect("test YAML validates");
        Snapshot::from_spec(&spec)
    };
    let a = load(
        "extends: none\ngroup: t\ntypes:\n  - { name: Id, kind: record, fields: [{ name: id, type: u8 }] }\n  - { name: Kind, kind: enum, repr: u8, values: [{ name: A, value: 0 }] }\nmessages:\n  - { name: SetThing, code: 0x0D00, fields: [{ name: r, type: Id }, { name: k, type: Kind }, { name: n, type: u16 }] }\n",
    );
    let b = load(
        "extends: none\ngroup: t\nmessages:\n  - { name: SetOther, code: 0x0D00, fields: [{ name: id, type: u8 }, { name: kind, type: u8 }, { name: count, type: u16 }] }\n",
    );
    let c = load(
        "extends: none\ngroup: t\nmessages:\n  - { name: SetOther, code: 0x0D00, fields: [{ name: count, type: u16 }, { name: id, type: u8 }, { name: kind, type: u8 }] }\n",
    );
    let flat = |s: &Snapshot| Flattener::new(s).message(&s.messages[0]);
    assert!(compare(&flat(&a), &flat(&b)).is_empty());
    let d = compare(&flat(&a), &flat(&c));
    assert_eq!(d.len(), 1, "{d:?}");
    assert!(
        d[0].contains("ours `u8`") && d[0].contains("JSIDL's `u16`"),
        "{d:?}"
    );
}

/// Compares the messages of each imported set (those of its group) with ours, by code:
/// a message missing here, a difference of layout and a differing `is_command` are
/// problems. Returns the problems, the codes compared and the number of comparisons.
fn compare_sets(spec: &Spec, sets: &[&Imported]) -> (Vec<String>, BTreeSet<u16>, usize) {
    let ours = Snapshot::from_spec(spec);
    let our_commands = commands(spec);
    let our_flat = Flattener::new(&ours);
    let by_code: BTreeMap<u16, &MessageSnap> = ours.messages.iter().map(|m| (m.code, m)).collect();
    let mut problems = Vec::new();
    let mut covered = BTreeSet::new();
    let mut compared = 0;
    for set in sets {
        let flat = Flattener::new(&set.snap);
        let mut n = 0;
        for m in set
            .snap
            .messages
            .iter()
            .filter(|m| set.codes.contains(&m.code))
        {
            let Some(o) = by_code.get(&m.code) else {
                problems.push(format!(
                    "{} 0x{:04X} {} ({}): not in our YAML",
                    set.label, m.code, m.name, m.at
                ));
                continue;
            };
            covered.insert(m.code);
            n += 1;
            for d in compare(&our_flat.message(o), &flat.message(m)) {
                problems.push(format!("{} 0x{:04X} {}: {d}", set.label, m.code, o.name));
            }
            let (a, b) = (our_commands[&m.code], set.commands[&m.code]);
            if a != b && !COMMAND_AS_PUBLISHED_IS_NOT.contains(&m.code) {
                problems.push(format!(
                    "{} 0x{:04X} {}: is_command ours {a:?}, the JSIDL's {b:?}",
                    set.label, m.code, o.name
                ));
            }
        }
        println!("{}: {n} messages compared", set.label);
        compared += n;
    }
    for m in &ours.messages {
        if !covered.contains(&m.code) {
            problems.push(format!(
                "0x{:04X} {} ({}): in our YAML but in neither imported set",
                m.code, m.name, m.at
            ));
        }
    }
    (problems, covered, compared)
}
