//! A wire form as Rust: its type, derive attributes and documentation.

use jaus_spec::{Field, Len, Spec, TypeKind, Wire};

use super::items::FieldCtx;
use super::{doc_lines, fmt_f64};

pub(super) struct Mapped {
    pub(super) ty: String,
    pub(super) attr: Vec<String>,
    pub(super) serde: Vec<String>,
    pub(super) doc: Vec<String>,
}

/// Rust type, derive attributes and documentation of a wire form.
pub(super) fn map_wire(w: &Wire, rt: &str) -> Mapped {
    let mut m = Mapped {
        ty: String::new(),
        attr: Vec::new(),
        serde: Vec::new(),
        doc: Vec::new(),
    };
    match w {
        Wire::Int(i) => m.ty = i.rust().into(),
        Wire::F32 | Wire::F64 => {
            m.ty = if *w == Wire::F32 { "f32" } else { "f64" }.into();
            m.serde.push(format!("with = \"{rt}::codec::serde_float\""));
        }
        Wire::Scaled { int, lo, hi } => {
            m.ty = "f64".into();
            m.attr.push(format!(
                "scaled({}, {}, {})",
                int.rust(),
                fmt_f64(*lo),
                fmt_f64(*hi)
            ));
            let d = int.divisor();
            m.doc.push(format!(
                "Range `[{lo}, {hi}]`, carried as a scaled `{}` (resolution {:.3e}).",
                int.rust(),
                (hi - lo) / d
            ));
        }
        Wire::Named {
            name,
            size,
            tag_field,
            ..
        } => {
            m.ty = name.clone();
            if let Some(s) = size {
                m.attr.push(format!("size = {}", s.rust()));
            }
            if let Some(t) = tag_field {
                m.attr.push(format!("tag_var = \"{t}\""));
                m.doc.push(format!(
                    "Its tag is the field `{t}`, not sent with the value."
                ));
            }
        }
        Wire::Str(len) => {
            m.ty = "String".into();
            len_attrs(&mut m, *len, "string");
        }
        Wire::Bytes(len) => {
            m.ty = "Vec<u8>".into();
            len_attrs(&mut m, *len, "blob");
            m.serde.push(format!("with = \"{rt}::hex::serde\""));
        }
        Wire::Packet { size } => {
            m.ty = format!("{rt}::Packet");
            m.doc.push("A whole JAUS message, header included.".into());
            if let Some(s) = size {
                m.attr.push(format!("size = {}", s.rust()));
                m.doc.push(format!(
                    "Preceded on the wire by its byte length as `{}`.",
                    s.rust()
                ));
            }
        }
        Wire::List { count, elem } => {
            let e = map_wire(elem, rt);
            m.ty = format!("Vec<{}>", e.ty);
            match count {
                Some(c) => {
                    m.attr.push(format!("count = {}", c.rust()));
                    m.doc.push(format!(
                        "Preceded on the wire by its element count as `{}`.",
                        c.rust()
                    ));
                }
                None => {
                    m.attr.push("rest".into());
                    m.doc.push("Elements run to the end of the body.".into());
                }
            }
            // Element attributes (scaled) apply to each element.
            m.attr
                .extend(e.attr.into_iter().filter(|a| a.starts_with("scaled")));
            m.doc
                .extend(e.doc.into_iter().map(|d| format!("Each element: {d}")));
        }
        Wire::ListField {
            field,
            elem,
            offsets_of,
        } => {
            let e = map_wire(elem, rt);
            m.ty = format!("Vec<{}>", e.ty);
            m.attr.push(format!("count_var = \"{field}\""));
            m.doc
                .push(format!("Its element count is the field `{field}`."));
            if let Some(t) = offsets_of {
                m.attr.push(format!("offsets = \"{t}\""));
                m.doc.push(format!(
                    "Byte offsets of the elements of `{t}` from the start of the body: computed on encode, informational on decode."
                ));
            }
            m.attr
                .extend(e.attr.into_iter().filter(|a| a.starts_with("scaled")));
            m.doc
                .extend(e.doc.into_iter().map(|d| format!("Each element: {d}")));
        }
        Wire::Flag => m.ty = "bool".into(),
    }
    m
}

fn len_attrs(m: &mut Mapped, len: Len, what: &str) {
    match len {
        Len::Fixed { n, accept_short } => {
            m.attr.push(format!("fixed = {n}"));
            m.doc.push(format!("A fixed {n}-byte {what}, NUL padded."));
            if accept_short {
                m.attr.push("accept_short".into());
                m.doc.push("A shorter field is accepted on receive.".into());
            }
        }
        Len::Prefix(c) => {
            m.attr.push(format!("size = {}", c.rust()));
            m.doc.push(format!(
                "Preceded on the wire by its length as `{}`.",
                c.rust()
            ));
        }
        Len::Nul => {
            m.attr.push("nul_terminated".into());
            m.doc.push(format!("A NUL-terminated {what}."));
        }
        Len::Rest { nul } => {
            m.attr.push("rest".into());
            m.doc.push("Runs to the end of the body.".into());
            if nul {
                m.attr.push("nul".into());
                m.doc.push("Sent with a terminating NUL.".into());
            }
        }
    }
}

pub(super) fn field_ctx(spec: &Spec, field: &Field, rt: &str) -> FieldCtx {
    let (f, w) = (&field.def, &field.wire);
    let mut m = map_wire(w, rt);
    // The unit of a scaled value (of the field, or of each element of a list) goes into
    // the encoder's error messages.
    let unit = f
        .unit
        .as_ref()
        .or(f.of.as_ref().and_then(|e| e.0.unit.as_ref()));
    if let Some(u) = unit {
        if let Some(i) = m.attr.iter().position(|a| a.starts_with("scaled(")) {
            m.attr.insert(i + 1, format!("unit = {u:?}"));
        }
    }
    if spec.vars().contains(&f.name) {
        m.attr.push(format!("var = \"{}\"", f.name));
    }
    let mut doc = doc_lines(f.description.as_deref());
    if let Some(u) = &f.unit {
        doc.push(String::new());
        doc.push(format!("Unit: {u}."));
    } else if !m.doc.is_empty() {
        doc.push(String::new());
    }
    doc.append(&mut m.doc);
    let mut attr = m.attr;
    let mut serde = m.serde;
    let ty = match (f.bit, &f.present_if) {
        (Some(b), _) if *w == Wire::Flag => {
            attr.insert(0, format!("flag = {b}"));
            doc.push(format!("Presence-vector bit {b} (no bytes of its own)."));
            m.ty
        }
        (None, Some(flag)) => {
            attr.insert(0, format!("present_if = \"{flag}\""));
            doc.push(format!("Present exactly when `{flag}` is set."));
            if serde.iter().any(|s| s.contains("hex::serde")) {
                serde = vec![format!("with = \"{rt}::hex::serde_opt\"")];
            }
            if serde.iter().any(|s| s.contains("serde_float")) {
                serde = vec![format!("with = \"{rt}::codec::serde_float::option\"")];
            }
            serde.insert(
                0,
                "default, skip_serializing_if = \"Option::is_none\"".into(),
            );
            format!("Option<{}>", m.ty)
        }
        (Some(b), _) => {
            attr.insert(0, format!("bit = {b}"));
            doc.push(format!("Optional: presence bit {b}."));
            if serde.iter().any(|s| s.contains("hex::serde")) {
                serde = vec![format!("with = \"{rt}::hex::serde_opt\"")];
            }
            if serde.iter().any(|s| s.contains("serde_float")) {
                serde = vec![format!("with = \"{rt}::codec::serde_float::option\"")];
            }
            serde.insert(
                0,
                "default, skip_serializing_if = \"Option::is_none\"".into(),
            );
            format!("Option<{}>", m.ty)
        }
        (None, None) => m.ty,
    };
    FieldCtx {
        name: f.name.clone(),
        ty,
        attr: attr.join(", "),
        serde: serde.join(", "),
        doc,
    }
}

/// Whether a struct of these fields can derive `Default`.
pub(super) fn all_default(spec: &Spec, fields: &[Field]) -> bool {
    fields.iter().all(|f| has_default(spec, f))
}

/// Whether values of this field have a `Default`.
fn has_default(spec: &Spec, f: &Field) -> bool {
    if f.def.bit.is_some() {
        return true;
    }
    match &f.wire {
        Wire::Named { name, kind, .. } => match kind {
            TypeKind::Union => false,
            TypeKind::Enum | TypeKind::Bitfield => true,
            TypeKind::Record => spec.ty(name).is_some_and(|t| all_default(spec, t.fields())),
        },
        Wire::Packet { .. } => false,
        _ => true,
    }
}
