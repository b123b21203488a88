//! Named types: records (by the field rules), enumerations, bit fields and unions.

use super::pair::{bits_text, pair, Body};
use super::{ChangeKind, Differ, Severity};
use crate::lock::type_body;
use crate::snapshot::*;
use jaus_spec::Wire;

impl Differ<'_> {
    pub(super) fn types(&mut self) {
        use ChangeKind::*;
        use Severity::*;
        let p = pair(
            &self.old.types,
            &self.new.types,
            |t| &t.name,
            |a, b| type_body(&a.form) == type_body(&b.form),
        );
        for (t, n, renamed) in &p.both {
            if *renamed {
                self.renames.insert(t.name.clone(), n.name.clone());
            }
        }
        for t in p.removed {
            let users = self.users_of(&t.name, &t.name);
            self.push(
                TypeRemoved,
                SourceBreaking,
                t.name.clone(),
                Some(&t.at),
                None,
                format!(
                    "{} removed (its uses are reported where they changed)",
                    kind_name(t.form.kind())
                ),
                &users,
            );
        }
        for n in p.added {
            let users = self.users_of(&n.name, &n.name);
            self.push(
                TypeAdded,
                Compatible,
                n.name.clone(),
                None,
                Some(&n.at),
                format!("{} added", kind_name(n.form.kind())),
                &users,
            );
        }
        for (t, n, _) in p.both {
            let users = self.users_of(&t.name, &n.name);
            let at = (Some(&t.at), Some(&n.at));
            if t.name != n.name {
                self.push(
                    TypeRenamed,
                    SourceBreaking,
                    n.name.clone(),
                    at.0,
                    at.1,
                    format!("renamed {} → {} (same layout)", t.name, n.name),
                    &users,
                );
                continue;
            }
            let path = n.name.clone();
            match (&t.form, &n.form) {
                (
                    FormSnap::Record {
                        presence: op,
                        fields: of,
                    },
                    FormSnap::Record {
                        presence: np,
                        fields: nf,
                    },
                ) => self.fields(
                    &path,
                    false,
                    Body {
                        presence: *op,
                        fields: of,
                        at: &t.at,
                    },
                    Body {
                        presence: *np,
                        fields: nf,
                        at: &n.at,
                    },
                    &users,
                ),
                (
                    FormSnap::Enum {
                        repr: or,
                        values: ov,
                    },
                    FormSnap::Enum {
                        repr: nr,
                        values: nv,
                    },
                ) => {
                    if or != nr {
                        self.push(
                            EnumReprChanged,
                            WireBreaking,
                            path.clone(),
                            at.0,
                            at.1,
                            format!("repr {} → {}", or.rust(), nr.rust()),
                            &users,
                        );
                    }
                    self.enum_values(&path, t, n, ov, nv, &users);
                }
                (
                    FormSnap::Bitfield {
                        repr: or,
                        members: om,
                    },
                    FormSnap::Bitfield {
                        repr: nr,
                        members: nm,
                    },
                ) => {
                    if or != nr {
                        self.push(
                            BitfieldReprChanged,
                            WireBreaking,
                            path.clone(),
                            at.0,
                            at.1,
                            format!("repr {} → {}", or.rust(), nr.rust()),
                            &users,
                        );
                    }
                    self.members(&path, t, n, om, nm, &users);
                }
                (
                    FormSnap::Union {
                        repr: or,
                        variants: ov,
                    },
                    FormSnap::Union {
                        repr: nr,
                        variants: nv,
                    },
                ) => {
                    if or != nr {
                        self.push(
                            UnionReprChanged,
                            WireBreaking,
                            path.clone(),
                            at.0,
                            at.1,
                            format!("tag {} → {}", or.rust(), nr.rust()),
                            &users,
                        );
                    }
                    self.variants(&path, t, n, ov, nv, &users);
                }
                (a, b) => self.push(
                    TypeKindChanged,
                    WireBreaking,
                    path,
                    at.0,
                    at.1,
                    format!("{} → {}", kind_name(a.kind()), kind_name(b.kind())),
                    &users,
                ),
            }
        }
    }

    fn enum_values(
        &mut self,
        path: &str,
        t: &TypeSnap,
        n: &TypeSnap,
        ov: &[ValueSnap],
        nv: &[ValueSnap],
        users: &[String],
    ) {
        use ChangeKind::*;
        use Severity::*;
        let p = pair(ov, nv, |v| &v.name, |a, b| a.value == b.value);
        for (v, w, reused) in p.both {
            if reused {
                self.push(
                    EnumValueReused,
                    WireBreaking,
                    format!("{path}.{}", w.name),
                    Some(&v.at),
                    Some(&w.at),
                    format!("value {} was {}, now {}", v.value, v.name, w.name),
                    users,
                );
            } else if w.value != v.value {
                self.push(
                    EnumValueChanged,
                    WireBreaking,
                    format!("{path}.{}", v.name),
                    Some(&v.at),
                    Some(&w.at),
                    format!("value {} → {}", v.value, w.value),
                    users,
                );
            }
        }
        for v in p.removed {
            self.push(
                EnumValueRemoved,
                WireBreaking,
                format!("{path}.{}", v.name),
                Some(&v.at),
                Some(&n.at),
                format!("value {} removed", v.value),
                users,
            );
        }
        for w in p.added {
            match ov.iter().find(|v| v.value == w.value) {
                Some(v) => self.push(
                    EnumValueReused,
                    WireBreaking,
                    format!("{path}.{}", w.name),
                    Some(&v.at),
                    Some(&w.at),
                    format!(
                        "value {} was {} (moved away), now {}",
                        w.value, v.name, w.name
                    ),
                    users,
                ),
                None => self.push(
                    EnumValueAdded,
                    Compatible,
                    format!("{path}.{}", w.name),
                    Some(&t.at),
                    Some(&w.at),
                    format!(
                        "value {} added (older decoders keep it as Unknown({})); \
                         a `match` on {path} without a `_` arm no longer compiles",
                        w.value, w.value
                    ),
                    users,
                ),
            }
        }
    }

    fn members(
        &mut self,
        path: &str,
        t: &TypeSnap,
        n: &TypeSnap,
        om: &[MemberSnap],
        nm: &[MemberSnap],
        users: &[String],
    ) {
        use ChangeKind::*;
        use Severity::*;
        let p = pair(om, nm, |m| &m.name, |a, b| a.bits == b.bits);
        for (m, w, renamed) in p.both {
            if renamed {
                self.push(
                    BitsRenamed,
                    SourceBreaking,
                    format!("{path}.{}", w.name),
                    Some(&m.at),
                    Some(&w.at),
                    format!(
                        "renamed `{}` → `{}` ({})",
                        m.name,
                        w.name,
                        bits_text(w.bits)
                    ),
                    users,
                );
            } else if w.bits != m.bits {
                self.push(
                    BitsMoved,
                    WireBreaking,
                    format!("{path}.{}", m.name),
                    Some(&m.at),
                    Some(&w.at),
                    format!("{} → {}", bits_text(m.bits), bits_text(w.bits)),
                    users,
                );
            }
        }
        for m in p.removed {
            self.push(
                BitsRemoved,
                WireBreaking,
                format!("{path}.{}", m.name),
                Some(&m.at),
                Some(&n.at),
                format!("{} removed", bits_text(m.bits)),
                users,
            );
        }
        for w in p.added {
            let (lo, hi) = bit_range(w.bits);
            let overlap = om.iter().find(|m| {
                let (a, b) = bit_range(m.bits);
                a <= hi && lo <= b
            });
            let (sev, detail) = match overlap {
                None => (
                    Compatible,
                    format!(
                        "{} added in unused bits (older decoders keep them as reserved); \
                         struct literals and patterns of {path} without `..` no longer compile",
                        bits_text(w.bits)
                    ),
                ),
                Some(m) => (
                    WireBreaking,
                    format!(
                        "{} added over `{}`'s old {}",
                        bits_text(w.bits),
                        m.name,
                        bits_text(m.bits)
                    ),
                ),
            };
            self.push(
                BitsAdded,
                sev,
                format!("{path}.{}", w.name),
                Some(&t.at),
                Some(&w.at),
                detail,
                users,
            );
        }
    }

    fn variants(
        &mut self,
        path: &str,
        t: &TypeSnap,
        n: &TypeSnap,
        ov: &[VariantSnap],
        nv: &[VariantSnap],
        users: &[String],
    ) {
        use ChangeKind::*;
        use Severity::*;
        let same_value = |a: &Option<Wire>, b: &Option<Wire>| match (a, b) {
            (Some(a), Some(b)) => self.wire_eq(a, b),
            (None, None) => true,
            _ => false,
        };
        let text = |w: &Option<Wire>| w.as_ref().map_or("no value".to_string(), wire_text);
        let p = pair(
            ov,
            nv,
            |v| &v.name,
            |a, b| a.tag == b.tag && same_value(&a.wire, &b.wire),
        );
        let mut changes = Vec::new();
        for (v, w, renamed) in p.both {
            let at = (Some(&v.at), Some(&w.at));
            if renamed {
                changes.push((
                    VariantRenamed,
                    SourceBreaking,
                    &w.name,
                    at,
                    format!("renamed {} → {} (tag {})", v.name, w.name, w.tag),
                ));
                continue;
            }
            if w.tag != v.tag {
                changes.push((
                    VariantTagChanged,
                    WireBreaking,
                    &w.name,
                    at,
                    format!("tag {} → {}", v.tag, w.tag),
                ));
            }
            if !same_value(&v.wire, &w.wire) {
                changes.push((
                    VariantTypeChanged,
                    WireBreaking,
                    &w.name,
                    at,
                    format!("{} → {}", text(&v.wire), text(&w.wire)),
                ));
            }
        }
        for v in p.removed {
            changes.push((
                VariantRemoved,
                WireBreaking,
                &v.name,
                (Some(&v.at), Some(&n.at)),
                format!("tag {} removed", v.tag),
            ));
        }
        for w in p.added {
            changes.push((
                VariantAdded,
                WireBreaking,
                &w.name,
                (Some(&t.at), Some(&w.at)),
                format!(
                    "tag {} added ({}): older decoders reject a value with an unknown tag",
                    w.tag,
                    text(&w.wire)
                ),
            ));
        }
        for (kind, sev, name, (o, n), detail) in changes {
            self.push(kind, sev, format!("{path}.{name}"), o, n, detail, users);
        }
    }
}
