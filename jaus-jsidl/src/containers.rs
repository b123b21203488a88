//! Containers: records (with presence vectors and optional fields), sequences, lists
//! (with their count field) and variants (with their vtag field), as named types or as
//! fields, and message and event bodies.

use crate::error::Result;
use crate::fields::{basic, join, Mode};
use crate::import::{At, Importer};
use crate::names::{pascal, snake};
use crate::xml::{child, elements, interpretation, optional, tag};
use jaus_spec::model::{ElemDef, FieldDef, TypeDef, TypeKind, VariantDef};

/// Elements that are containers.
const CONTAINERS: &[&str] = &["record", "list", "variant", "sequence"];

impl<'a> Importer<'a> {
    /// The presence vector type of a record or sequence, if it has one.
    fn presence(&self, c: At<'a>) -> Result<Option<String>> {
        match child(c.node, "presence_vector") {
            None => Ok(None),
            Some(pv) => {
                let pv = self.at(c, pv);
                let ty = self.req(pv, "field_type_unsigned")?;
                match basic(ty) {
                    Some(t @ ("u8" | "u16" | "u32")) => Ok(Some(t.to_string())),
                    _ => Err(self.err(
                        pv,
                        format!("`{ty}` is not a presence vector type (u8, u16 or u32)"),
                    )),
                }
            }
        }
    }

    /// The presence bit of the next child: optional children take bits in order.
    fn next_bit(&self, c: At<'a>, pv: &Option<String>, n: &mut u32) -> Result<Option<u32>> {
        if !optional(c.node) {
            return Ok(None);
        }
        if pv.is_none() {
            return Err(self.err(
                c,
                "an optional item needs a presence vector in the record or sequence that holds it",
            ));
        }
        *n += 1;
        Ok(Some(*n - 1))
    }

    /// The presence vector type and the fields of a record.
    pub fn record_fields(
        &mut self,
        rec: At<'a>,
        owner: &str,
        mode: Mode,
    ) -> Result<(Option<String>, Vec<FieldDef>)> {
        let pv = self.presence(rec)?;
        let mut n = 0;
        let mut fields = Vec::new();
        for c in elements(rec.node).filter(|c| tag(*c) != "presence_vector") {
            let c = self.at(rec, c);
            let bit = self.next_bit(c, &pv, &mut n)?;
            fields.extend(self.record_field(c, owner, bit, mode)?);
        }
        Ok((pv, fields))
    }

    /// The presence vector type and the fields (one per container) of a sequence.
    pub fn sequence_fields(
        &mut self,
        seq: At<'a>,
        owner: &str,
        mode: Mode,
    ) -> Result<(Option<String>, Vec<FieldDef>)> {
        let pv = self.presence(seq)?;
        let mut n = 0;
        let mut fields = Vec::new();
        for c in elements(seq.node).filter(|c| tag(*c) != "presence_vector") {
            let c = self.at(seq, c);
            let bit = self.next_bit(c, &pv, &mut n)?;
            fields.push(self.container_field(c, owner, bit, mode)?);
        }
        Ok((pv, fields))
    }

    /// Resolves a container element (or a `declared_*` reference to one), checking it
    /// is one.
    fn container(&self, el: At<'a>) -> Result<At<'a>> {
        let def = self.resolve(el)?;
        if CONTAINERS.contains(&tag(def.node)) {
            Ok(def)
        } else {
            Err(self.err(
                el,
                format!(
                    "expected a record, list, variant or sequence, found <{}>",
                    tag(def.node)
                ),
            ))
        }
    }

    /// A container as a field of a sequence or body: a named record, sequence or variant
    /// type, or a list.
    pub fn container_field(
        &mut self,
        el: At<'a>,
        owner: &str,
        bit: Option<u32>,
        mode: Mode,
    ) -> Result<FieldDef> {
        let def = self.container(el)?;
        let mut f = FieldDef {
            name: snake(self.req(el, "name")?),
            description: interpretation(el.node).or_else(|| interpretation(def.node)),
            bit,
            ..FieldDef::default()
        };
        if tag(def.node) == "list" {
            self.list_into(def, owner, mode, &mut f)?;
        } else {
            f.ty = self.container_type(el, owner)?;
        }
        Ok(f)
    }

    /// A list's count and element into `f`.
    fn list_into(&mut self, list: At<'a>, owner: &str, mode: Mode, f: &mut FieldDef) -> Result<()> {
        f.ty = "list".into();
        self.count(list, mode, f)?;
        if mode == Mode::Event && f.count.is_none() {
            // An event's list is not sent: no count.
        } else if f.count.is_none() {
            return Err(self.err(list, "the list's count is missing"));
        }
        let items: Vec<_> = elements(list.node)
            .filter(|c| tag(*c) != "count_field")
            .collect();
        let [item] = items[..] else {
            return Err(self.err(
                list,
                format!("a list holds one kind of element, found {}", items.len()),
            ));
        };
        let item = self.at(list, item);
        // A list of lists is a list of records holding one list each (the same bytes):
        // the generated codec takes named element types.
        let elem = FieldDef {
            ty: self.container_type(item, owner)?,
            ..FieldDef::default()
        };
        f.of = Some(Box::new(ElemDef(elem)));
        Ok(())
    }

    /// The named type of a container (a list is wrapped in a record of one field, which
    /// has the same bytes).
    pub fn container_type(&mut self, el: At<'a>, owner: &str) -> Result<String> {
        let def = self.container(el)?;
        let name = self.req(def, "name")?;
        let key = def.key();
        let tname = self.type_name(def, owner, name);
        if self.types_done(key) {
            if self.busy.contains(&key) {
                return Err(self.err(el, format!("`{name}` contains itself")));
            }
            return Ok(tname);
        }
        self.busy.push(key);
        let description = interpretation(def.node);
        let mut t = TypeDef {
            name: tname.clone(),
            kind: TypeKind::Record,
            repr: None,
            description,
            presence: None,
            fields: Vec::new(),
            values: Vec::new(),
            bits: Vec::new(),
            variants: Vec::new(),
        };
        match tag(def.node) {
            "record" => (t.presence, t.fields) = self.record_fields(def, &tname, Mode::Wire)?,
            "sequence" => (t.presence, t.fields) = self.sequence_fields(def, &tname, Mode::Wire)?,
            "list" => {
                let mut f = FieldDef {
                    name: snake(name),
                    ..FieldDef::default()
                };
                self.list_into(def, &tname, Mode::Wire, &mut f)?;
                t.fields.push(f);
            }
            _ => {
                t.kind = TypeKind::Union;
                let vt = child(def.node, "vtag_field")
                    .map(|v| self.at(def, v))
                    .ok_or_else(|| self.err(def, "the <vtag_field> is missing"))?;
                let ty = self.req(vt, "field_type_unsigned")?;
                t.repr = Some(
                    basic(ty)
                        .ok_or_else(|| self.err(vt, format!("`{ty}` is not a tag type")))?
                        .to_string(),
                );
                let first: u64 = match vt.node.attribute("min_count") {
                    Some(m) => m
                        .trim()
                        .parse()
                        .map_err(|_| self.err(vt, format!("min_count `{m}` is not a number")))?,
                    None => 0,
                };
                t.description = join(&[t.description.take(), interpretation(vt.node)]);
                let alts: Vec<_> = elements(def.node)
                    .filter(|c| tag(*c) != "vtag_field")
                    .collect();
                if alts.is_empty() {
                    // A variant of no alternatives (a "nothing here" alternative of
                    // another): its tag alone is on the wire, a record of that field.
                    t.kind = TypeKind::Record;
                    let repr = t.repr.take().unwrap_or_else(|| "u8".into());
                    t.fields.push(FieldDef {
                        name: "vtag".into(),
                        ty: repr,
                        description: Some(format!(
                            "The tag of a variant of no alternatives ({first})."
                        )),
                        ..FieldDef::default()
                    });
                }
                for (i, a) in alts.into_iter().enumerate() {
                    let a = self.at(def, a);
                    let ty = self.container_type(a, &tname)?;
                    t.variants.push(VariantDef {
                        name: pascal(self.req(a, "name")?),
                        tag: first.checked_add(i as u64).ok_or_else(|| {
                            self.err(
                                vt,
                                "the vtag's min_count leaves no room for the alternatives",
                            )
                        })?,
                        ty: Some(ty),
                        description: interpretation(a.node),
                    });
                }
            }
        }
        self.busy.retain(|k| *k != key);
        self.add_type(def, t);
        Ok(tname)
    }

    /// The presence vector type and fields of a message or event body (a `body` or
    /// `declared_body`): a record or sequence gives its fields, a list or variant one
    /// field.
    pub fn body_fields(
        &mut self,
        body: At<'a>,
        owner: &str,
        mode: Mode,
    ) -> Result<(Option<String>, Vec<FieldDef>)> {
        let body = self.resolve(body)?;
        let items: Vec<_> = elements(body.node).collect();
        match items[..] {
            [] => Ok((None, Vec::new())),
            [item] => {
                let item = self.at(body, item);
                if optional(item.node) {
                    return Err(self.err(
                        item,
                        "an optional body (no presence vector to say so) is not supported",
                    ));
                }
                let def = self.container(item)?;
                match tag(def.node) {
                    "record" => self.record_fields(def, owner, mode),
                    "sequence" => self.sequence_fields(def, owner, mode),
                    _ => Ok((None, vec![self.container_field(item, owner, None, mode)?])),
                }
            }
            _ => Err(self.err(body, "a body holds one record, list, variant or sequence")),
        }
    }
}

/// The most elements an array may have: each is a field of its record.
const MAX_ARRAY: usize = 256;

impl<'a> Importer<'a> {
    /// A fixed-count array (`array` with its `dimension`s) as a named record of one
    /// field per element, in row-major order (`position_0`, `position_1`, …; `cell_1_2`
    /// for two dimensions): the same bytes as the array, as the definition language has
    /// no list of a fixed element count.
    pub fn array(&mut self, def: At<'a>, owner: &str, mode: Mode) -> Result<String> {
        let name = self.req(def, "name")?;
        let key = def.key();
        let tname = self.type_name(def, owner, name);
        if self.types_done(key) {
            if self.busy.contains(&key) {
                return Err(self.err(def, format!("`{name}` contains itself")));
            }
            return Ok(tname);
        }
        let mut dims = Vec::new();
        for d in elements(def.node).filter(|c| tag(*c) == "dimension") {
            let d = self.at(def, d);
            let n = self.number(d, "size")?;
            if n == 0 {
                return Err(self.err(d, "a dimension of size 0"));
            }
            dims.push(n);
        }
        let total = dims
            .iter()
            .try_fold(1usize, |acc, n| acc.checked_mul(*n))
            .filter(|n| *n <= MAX_ARRAY);
        let Some(total) = total.filter(|_| !dims.is_empty()) else {
            return Err(self.err(
                def,
                format!("an array has 1 to {MAX_ARRAY} elements in one or more <dimension>s, found dimensions {dims:?}"),
            ));
        };
        let items: Vec<_> = elements(def.node)
            .filter(|c| tag(*c) != "dimension")
            .collect();
        let [item] = items[..] else {
            return Err(self.err(
                def,
                format!("an array holds one kind of element, found {}", items.len()),
            ));
        };
        let item = self.at(def, item);
        self.busy.push(key);
        let elem_tag = tag(item.node)
            .strip_prefix("declared_")
            .unwrap_or(tag(item.node));
        let mut elem = if CONTAINERS.contains(&elem_tag) {
            FieldDef {
                name: snake(self.req(item, "name")?),
                ty: self.container_type(item, &tname)?,
                ..FieldDef::default()
            }
        } else {
            let mut v = self.record_field(item, &tname, None, mode)?;
            match v.len() {
                1 => v.remove(0),
                _ => {
                    return Err(self.err(
                        item,
                        "an array element is one field (a variable format field is two)",
                    ))
                }
            }
        };
        self.busy.retain(|k| *k != key);
        let what = elem.description.take();
        let mut fields = Vec::with_capacity(total);
        for i in 0..total {
            // The index of each dimension, the last one varying fastest.
            let mut rest = i;
            let mut idx = vec![0; dims.len()];
            for (slot, n) in idx.iter_mut().zip(dims.iter()).rev() {
                *slot = rest % n;
                rest /= n;
            }
            let suffix: Vec<String> = idx.iter().map(ToString::to_string).collect();
            fields.push(FieldDef {
                name: format!("{}_{}", elem.name, suffix.join("_")),
                ..elem.clone()
            });
        }
        let shape: Vec<String> = dims.iter().map(ToString::to_string).collect();
        let t = TypeDef {
            name: tname.clone(),
            kind: TypeKind::Record,
            repr: None,
            description: join(&[
                interpretation(def.node),
                Some(format!(
                    "An array of {} `{}` ({}), in row-major order.",
                    total,
                    elem.name,
                    shape.join(" × ")
                )),
                what,
            ]),
            presence: None,
            fields,
            values: Vec::new(),
            bits: Vec::new(),
            variants: Vec::new(),
        };
        self.add_type(def, t);
        Ok(tname)
    }
}
