//! Fields: fixed fields (integers, scaled integers, floats, with value sets), bit
//! fields with their sub-fields, fixed and variable length strings, variable length
//! and variable format fields, variable (type-and-units) fields, and the count fields
//! of all that vary in length.

use crate::error::Result;
use crate::expr;
use crate::import::{At, Importer};
use crate::names::{pascal, snake};
use crate::xml::{child, elements, interpretation, tag};
use jaus_spec::model::{
    BitDef, Embeds, EnumValue, FieldDef, Length, TypeDef, TypeKind, VariantDef,
};

/// The `field_format` of JSIDL data that is a JAUS message (message ID and body).
const JAUS_MESSAGE: &str = "JAUS MESSAGE";

/// Whether the fields go on the wire (a message or a named type) or are the data of an
/// internal event (never sent: counts and lengths are left out).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mode {
    /// Wire data.
    Wire,
    /// An internal event's data.
    Event,
}

/// The definition language's type of a JSIDL `field_type`.
pub(crate) fn basic(field_type: &str) -> Option<&'static str> {
    let words: Vec<&str> = field_type.split_whitespace().collect();
    Some(match words.join(" ").as_str() {
        "unsigned byte" => "u8",
        "byte" => "i8",
        "unsigned short integer" => "u16",
        "unsigned integer" => "u32",
        "unsigned long integer" => "u64",
        "short integer" => "i16",
        "integer" => "i32",
        "long integer" => "i64",
        "float" => "f32",
        "long float" => "f64",
        _ => return None,
    })
}

/// The unsigned type of the size of signed `ty`, and the largest value of `ty`.
fn unsigned_for(ty: &str) -> Option<(&'static str, u64)> {
    Some(match ty {
        "i8" => ("u8", i8::MAX as u64),
        "i16" => ("u16", i16::MAX as u64),
        "i32" => ("u32", i32::MAX as u64),
        "i64" => ("u64", i64::MAX as u64),
        _ => return None,
    })
}

/// The unit of a JSIDL `field_units` (`None` for `one`, the dimensionless unit).
fn unit(units: Option<&str>) -> Option<String> {
    let u = units?.split_whitespace().collect::<Vec<_>>().join(" ");
    Some(
        match u.as_str() {
            "one" => return None,
            "meter" => "m",
            "meter per second" => "m/s",
            "meter per second squared" => "m/s^2",
            "radian" => "rad",
            "radian per second" => "rad/s",
            "radian per second squared" => "rad/s^2",
            "degree" => "deg",
            "second" => "s",
            "minute" => "min",
            "hour" => "h",
            "hertz" => "Hz",
            "percent" => "%",
            "kilogram" => "kg",
            "newton" => "N",
            "newton meter" => "N m",
            "volt" => "V",
            "ampere" => "A",
            "watt" => "W",
            "kelvin" => "K",
            "degree Celsius" => "degC",
            "pascal" => "Pa",
            other => other,
        }
        .to_string(),
    )
}

/// Joins the description parts that are present into sentences.
pub(crate) fn join(parts: &[Option<String>]) -> Option<String> {
    let mut out = String::new();
    for p in parts.iter().flatten() {
        if !out.is_empty() {
            if !out.ends_with(['.', '!', '?', ':']) {
                out.push('.');
            }
            out.push(' ');
        }
        out.push_str(p);
    }
    (!out.is_empty()).then_some(out)
}

impl<'a> Importer<'a> {
    /// One field element of a record (or a `declared_*` reference to one) as the field
    /// definitions it gives (two for a variable format field: its format, then its data).
    pub fn record_field(
        &mut self,
        el: At<'a>,
        owner: &str,
        bit: Option<u32>,
        mode: Mode,
    ) -> Result<Vec<FieldDef>> {
        let name = self.req(el, "name")?;
        let def = self.resolve(el)?;
        let expected = tag(el.node)
            .strip_prefix("declared_")
            .unwrap_or(tag(el.node));
        if tag(def.node) != expected {
            return Err(self.err(
                el,
                format!(
                    "the reference names a <{}>, not a <{expected}>",
                    tag(def.node)
                ),
            ));
        }
        let mut f = FieldDef {
            name: snake(name),
            description: interpretation(el.node).or_else(|| interpretation(def.node)),
            bit,
            ..FieldDef::default()
        };
        match expected {
            "fixed_field" => self.fixed_field(def, owner, &mut f)?,
            "bit_field" => f.ty = self.bit_field(def, owner)?,
            "fixed_length_string" => {
                f.ty = "string".into();
                f.length = Some(Length::Fixed(self.number(def, "string_length")?));
            }
            "variable_length_string" => {
                f.ty = "string".into();
                self.count(def, mode, &mut f)?;
            }
            "variable_length_field" => {
                f.ty = "bytes".into();
                let format = def.node.attribute("field_format");
                if format == Some(JAUS_MESSAGE) {
                    f.embeds = Some(Embeds::Message);
                }
                let format = format.map(|x| format!("Format: {x}."));
                f.description = join(&[f.description.take(), format]);
                self.count(def, mode, &mut f)?;
            }
            "variable_format_field" => return self.variable_format_field(def, f, mode),
            "variable_field" => f.ty = self.variable_field(def, owner)?,
            "array" => f.ty = self.array(def, owner, mode)?,
            other => {
                return Err(self.err(el, format!("<{other}> is not a field of a record")));
            }
        }
        Ok(vec![f])
    }

    /// An unsigned integer attribute: a number, or a declared constant's name.
    pub fn number(&self, at: At<'a>, attr: &str) -> Result<usize> {
        let x = self.real(at, attr)?;
        if x >= 0.0 && x.fract() == 0.0 && x <= f64::from(u32::MAX) {
            Ok(x as usize)
        } else {
            Err(self.err(at, format!("`{attr}` is {x}, not an unsigned integer")))
        }
    }

    /// A real attribute: a number, the name of a declared constant (`constants.PI`),
    /// or a constant expression of them (`-8*constants.PI`, `3.14159265358979323846/2`).
    pub fn real(&self, at: At<'a>, attr: &str) -> Result<f64> {
        Ok(self.real_expr(at, attr)?.0)
    }

    /// A real attribute's value, and its text when it is an expression (more than a
    /// number or a constant's name, possibly negated).
    pub fn real_expr(&self, at: At<'a>, attr: &str) -> Result<(f64, Option<String>)> {
        let v = self.req(at, attr)?.trim();
        if let Ok(x) = v.parse::<f64>() {
            return Ok((x, None));
        }
        let e = expr::parse(v).map_err(|why| {
            self.err(
                at,
                format!("`{attr}=\"{v}\"`: not a constant expression (numbers, constant names, + - * / and parentheses): {why}"),
            )
        })?;
        let x = e
            .eval(&mut |name: &str| self.constant(at, attr, v, name))
            .map_err(|e| match e {
                expr::Eval::Name(e) => e,
                expr::Eval::Math(why) => self.err(at, format!("`{attr}=\"{v}\"`: {why}")),
            })?;
        Ok((x, (!e.is_simple()).then(|| v.to_string())))
    }

    /// The value of the declared constant `name` seen from `at`.
    fn constant(&self, at: At<'a>, attr: &str, v: &str, name: &str) -> Result<f64> {
        let scope = self.scope(at).ok_or_else(|| {
            self.err(
                at,
                format!("`{attr}=\"{v}\"`: no declared type set to look the constant up in"),
            )
        })?;
        let c = self.lookup(at, scope, name)?;
        if tag(c.node) != "const_def" {
            return Err(self.err(
                at,
                format!("`{name}` is a <{}>, not a constant", tag(c.node)),
            ));
        }
        let cv = self.req(c, "const_value")?.trim();
        cv.parse::<f64>()
            .map_err(|_| self.err(c, format!("constant value `{cv}` is not a number")))
    }

    /// The count of a variable length item (its `count_field` child) into `f`; its
    /// limits go into the description.
    pub fn count(&self, def: At<'a>, mode: Mode, f: &mut FieldDef) -> Result<()> {
        let c = child(def.node, "count_field")
            .map(|c| self.at(def, c))
            .ok_or_else(|| self.err(def, "the <count_field> is missing"))?;
        let ty = self.req(c, "field_type_unsigned")?;
        let int = basic(ty).ok_or_else(|| self.err(c, format!("`{ty}` is not a count type")))?;
        let limits = match (c.node.attribute("min_count"), c.node.attribute("max_count")) {
            (None, None) => None,
            (lo, hi) => Some(format!(
                "Count: {} to {}.",
                lo.unwrap_or("0"),
                hi.unwrap_or("the type's maximum")
            )),
        };
        f.description = join(&[f.description.take(), interpretation(c.node), limits]);
        if mode == Mode::Event {
            return Ok(());
        }
        if int == "u64" {
            return Err(self.err(
                c,
                "a count of type `unsigned long integer` has no wire form in the definition language (counts are u8, u16 or u32)",
            ));
        }
        f.count = Some(int.to_string());
        Ok(())
    }

    /// A fixed field: its type, unit, scale or value set.
    fn fixed_field(&mut self, def: At<'a>, owner: &str, f: &mut FieldDef) -> Result<()> {
        let ft = self.req(def, "field_type")?;
        let ty = basic(ft).ok_or_else(|| {
            self.err(
                def,
                format!("field type `{ft}` is not a JSIDL field type (byte, short integer, integer, long integer, their unsigned forms, float, long float)"),
            )
        })?;
        f.ty = ty.to_string();
        f.unit = unit(def.node.attribute("field_units"));
        let is_int = !matches!(ty, "f32" | "f64");
        if let Some(sr) = child(def.node, "scale_range") {
            let sr = self.at(def, sr);
            if !is_int {
                return Err(self.err(sr, "a scale range applies to an integer field"));
            }
            match sr.node.attribute("integer_function") {
                None | Some("round") => {}
                Some(other) => {
                    return Err(self.err(
                        sr,
                        format!("integer_function `{other}`: the definition language's scaled integers round to nearest"),
                    ))
                }
            }
            let (lo, lo_expr) = self.real_expr(sr, "real_lower_limit")?;
            let (hi, hi_expr) = self.real_expr(sr, "real_upper_limit")?;
            let (lo_expr, hi_expr) = (lo_expr.is_some(), hi_expr.is_some());
            f.scale = Some([lo, hi]);
            if lo_expr || hi_expr {
                // The limits as the standard writes them.
                let text = |attr: &str| sr.node.attribute(attr).unwrap_or("").trim().to_string();
                let limits = format!(
                    "Scaled from `{}` to `{}`.",
                    text("real_lower_limit"),
                    text("real_upper_limit")
                );
                f.description = join(&[f.description.take(), Some(limits)]);
            }
        }
        let vs = elements(def.node).find(|c| matches!(tag(*c), "value_set" | "declared_value_set"));
        if let Some(vs) = vs {
            let vs = self.resolve(self.at(def, vs))?;
            let (values, ranges) = self.value_set(vs)?;
            f.description = join(&[f.description.take(), ranges]);
            if !values.is_empty() {
                if !is_int {
                    return Err(self.err(vs, "named values apply to an integer field"));
                }
                let name = self.req(def, "name")?;
                let key = def.key();
                let tname = self.type_name(def, owner, name);
                // An enumeration is unsigned in the definition language. Named values of
                // a signed field (HMI's `byte`s) that are all at most its largest value
                // have the same bytes as the unsigned type of that size; a negative value
                // on the wire arrives as the enumeration's unknown value.
                let (repr, signed_note) = match unsigned_for(ty) {
                    Some((unsigned, max)) if values.iter().all(|v| v.value <= max) => (
                        unsigned,
                        Some(format!(
                            "Signed (`{ft}`) in the JSIDL; its named values are 0 to {max} at most, the same bytes as `{unsigned}`."
                        )),
                    ),
                    Some(_) => {
                        return Err(self.err(
                            vs,
                            format!("named values of a signed `{ft}` beyond its largest value"),
                        ))
                    }
                    None => (ty, None),
                };
                if !self.types_done(key) {
                    self.add_type(
                        def,
                        TypeDef {
                            name: tname.clone(),
                            kind: TypeKind::Enum,
                            repr: Some(repr.to_string()),
                            description: join(&[interpretation(def.node), signed_note]),
                            presence: None,
                            fields: Vec::new(),
                            values,
                            bits: Vec::new(),
                            variants: Vec::new(),
                        },
                    );
                }
                f.ty = tname;
                f.unit = None;
            }
        }
        Ok(())
    }

    /// Marks the type of `key` as written; `true` if it already was.
    pub fn types_done(&mut self, key: crate::import::Key) -> bool {
        !self.written.insert(key)
    }

    /// A value set: its named values (an enumeration) and its ranges, as text.
    fn value_set(&self, vs: At<'a>) -> Result<(Vec<EnumValue>, Option<String>)> {
        let offset = matches!(
            vs.node.attribute("offset_to_lower_limit"),
            Some("true" | "1")
        );
        if offset {
            self.offset_is_zero(vs)?;
        }
        let mut values: Vec<EnumValue> = Vec::new();
        let mut ranges = Vec::new();
        for c in elements(vs.node) {
            let c = self.at(vs, c);
            match tag(c.node) {
                "value_enum" => {
                    let idx = self.req(c, "enum_index")?;
                    let value: u64 = idx.trim().parse().map_err(|_| {
                        self.err(c, format!("enum_index `{idx}` is not an unsigned integer"))
                    })?;
                    let mut name = pascal(self.req(c, "enum_const")?);
                    if name == "Unknown" || values.iter().any(|v| v.name == name) {
                        name = format!("{name}{value}");
                    }
                    values.push(EnumValue {
                        name,
                        value,
                        description: interpretation(c.node),
                    });
                }
                "value_range" => {
                    let lo = self.req(c, "lower_limit")?;
                    let hi = self.req(c, "upper_limit")?;
                    let open = if c.node.attribute("lower_limit_type") == Some("exclusive") {
                        "("
                    } else {
                        "["
                    };
                    let close = if c.node.attribute("upper_limit_type") == Some("exclusive") {
                        ")"
                    } else {
                        "]"
                    };
                    let what = interpretation(c.node)
                        .map(|i| format!(" ({i})"))
                        .unwrap_or_default();
                    ranges.push(format!("{open}{lo}, {hi}{close}{what}"));
                }
                other => return Err(self.err(c, format!("<{other}> is not part of a value set"))),
            }
        }
        let ranges = (!ranges.is_empty()).then(|| format!("Valid values: {}.", ranges.join(", ")));
        Ok((values, ranges))
    }

    /// With `offset_to_lower_limit="true"`, a value is sent as its offset from the lowest
    /// value of the set (the least of its enumerated values and range lower limits, as
    /// the JAUS Tool Set computes it). An offset of 0 sends the values themselves,
    /// which is how the published sets use it; any other has no form in the definition
    /// language (it has no integer sent minus a constant), and is an error.
    fn offset_is_zero(&self, vs: At<'a>) -> Result<()> {
        let mut lowest: Option<f64> = None;
        for c in elements(vs.node) {
            let c = self.at(vs, c);
            let v = match tag(c.node) {
                "value_enum" => self.real(c, "enum_index")?,
                "value_range" => self.real(c, "lower_limit")?,
                _ => continue,
            };
            lowest = Some(lowest.map_or(v, |l| l.min(v)));
        }
        match lowest {
            None | Some(0.0) => Ok(()),
            Some(l) => Err(self.err(
                vs,
                format!("`offset_to_lower_limit=\"true\"` with the lower limit {l}: values sent as offsets from a lower limit other than 0 have no form in the definition language (no integer sent minus a constant)"),
            )),
        }
    }

    /// A bit field as a named bit-field type.
    fn bit_field(&mut self, def: At<'a>, owner: &str) -> Result<String> {
        let name = self.req(def, "name")?;
        let key = def.key();
        let tname = self.type_name(def, owner, name);
        if self.types_done(key) {
            return Ok(tname);
        }
        let ft = self.req(def, "field_type_unsigned")?;
        let repr =
            basic(ft).ok_or_else(|| self.err(def, format!("`{ft}` is not an unsigned type")))?;
        let mut bits = Vec::new();
        for sf in elements(def.node).filter(|c| tag(*c) == "sub_field") {
            let sf = self.at(def, sf);
            let br = child(sf.node, "bit_range")
                .map(|b| self.at(sf, b))
                .ok_or_else(|| self.err(sf, "the <bit_range> is missing"))?;
            let from = self.number(br, "from_index")? as u32;
            let to = self.number(br, "to_index")? as u32;
            let (values, ranges) = match elements(sf.node)
                .find(|c| matches!(tag(*c), "value_set" | "declared_value_set"))
            {
                Some(vs) => {
                    let vs = self.resolve(self.at(sf, vs))?;
                    self.value_set(vs)?
                }
                None => (Vec::new(), None),
            };
            let named = (!values.is_empty()).then(|| {
                let v: Vec<String> = values
                    .iter()
                    .map(|v| format!("{} = {}", v.value, v.name))
                    .collect();
                format!("Values: {}.", v.join(", "))
            });
            let (bit, range) = if from == to {
                (Some(from), None)
            } else {
                (None, Some([from.min(to), from.max(to)]))
            };
            let mut member = snake(self.req(sf, "name")?);
            if member == "reserved" {
                // The language keeps `reserved` for the bits no member names: a member
                // so named is named after its bits.
                member = match range {
                    Some([lo, hi]) => format!("reserved_{lo}_{hi}"),
                    None => format!("reserved_{from}"),
                };
            }
            bits.push(BitDef {
                name: member,
                bit,
                bits: range,
                description: join(&[
                    interpretation(sf.node),
                    interpretation(br.node),
                    named,
                    ranges,
                ]),
            });
        }
        self.add_type(
            def,
            TypeDef {
                name: tname.clone(),
                kind: TypeKind::Bitfield,
                repr: Some(repr.to_string()),
                description: interpretation(def.node),
                presence: None,
                fields: Vec::new(),
                values: Vec::new(),
                bits,
                variants: Vec::new(),
            },
        );
        Ok(tname)
    }

    /// A variable format field: a one-byte format, then the data with its count.
    fn variable_format_field(
        &mut self,
        def: At<'a>,
        mut f: FieldDef,
        mode: Mode,
    ) -> Result<Vec<FieldDef>> {
        if f.bit.is_some() {
            return Err(self.err(def, "an optional variable format field (two fields on the wire under one presence bit) is not supported"));
        }
        let enums: Vec<_> = child(def.node, "format_field")
            .into_iter()
            .flat_map(elements)
            .filter(|c| tag(*c) == "format_enum")
            .collect();
        let formats: Vec<String> = enums
            .iter()
            .map(|c| {
                format!(
                    "{} = {}",
                    c.attribute("index").unwrap_or("?"),
                    c.attribute("field_format").unwrap_or("?")
                )
            })
            .collect();
        // The data is a message exactly when the format says so.
        if let Some(index) = enums
            .iter()
            .find(|c| c.attribute("field_format") == Some(JAUS_MESSAGE))
            .and_then(|c| c.attribute("index"))
        {
            f.embeds = Some(Embeds::Message);
            f.embeds_if = Some(format!("{}_format == {index}", f.name));
        }
        let format = FieldDef {
            name: format!("{}_format", f.name),
            ty: "u8".into(),
            description: Some(format!("Format of `{}`: {}.", f.name, formats.join(", "))),
            ..FieldDef::default()
        };
        f.ty = "bytes".into();
        self.count(def, mode, &mut f)?;
        Ok(vec![format, f])
    }

    /// A variable field (a type-and-units tag, then a value of that type) as a union.
    fn variable_field(&mut self, def: At<'a>, owner: &str) -> Result<String> {
        let name = self.req(def, "name")?;
        let key = def.key();
        let tname = self.type_name(def, owner, name);
        if self.types_done(key) {
            return Ok(tname);
        }
        let tu = child(def.node, "type_and_units_field")
            .map(|c| self.at(def, c))
            .ok_or_else(|| self.err(def, "the <type_and_units_field> is missing"))?;
        let mut variants = Vec::new();
        for e in elements(tu.node) {
            let e = self.at(tu, e);
            let vname = pascal(self.req(e, "name")?);
            // A type-and-units enum reads as a fixed field: a plain type, a scaled
            // integer or a value set.
            let mut v = FieldDef {
                name: "value".into(),
                ..FieldDef::default()
            };
            self.fixed_field(e, &tname, &mut v)?;
            let unit_text = v.unit.as_ref().map(|u| format!("Unit: {u}."));
            let mut notes = None;
            let ty = if v.scale.is_some() {
                // A union variant is a type: a scaled value is a record of one field,
                // which has the same bytes.
                let rname = self.type_name(e, &tname, &vname);
                if !self.types_done(e.key()) {
                    let t = TypeDef {
                        name: rname.clone(),
                        kind: TypeKind::Record,
                        repr: None,
                        description: interpretation(e.node),
                        presence: None,
                        fields: vec![v],
                        values: Vec::new(),
                        bits: Vec::new(),
                        variants: Vec::new(),
                    };
                    self.add_type(e, t);
                }
                rname
            } else {
                notes = v.description;
                v.ty
            };
            let tag = self.number(e, "index")? as u64;
            // Names repeat in published files (HMI's placeholder `rename_me` for every
            // entry of a field): the repeated ones take their index, as enum values do.
            let vname = if variants.iter().any(|v: &VariantDef| v.name == vname) {
                format!("{vname}{tag}")
            } else {
                vname
            };
            variants.push(VariantDef {
                name: vname,
                tag,
                ty: Some(ty),
                description: join(&[interpretation(e.node), notes, unit_text]),
            });
        }
        self.add_type(
            def,
            TypeDef {
                name: tname.clone(),
                kind: TypeKind::Union,
                repr: Some("u8".into()),
                description: interpretation(def.node),
                presence: None,
                fields: Vec::new(),
                values: Vec::new(),
                bits: Vec::new(),
                variants,
            },
        );
        Ok(tname)
    }
}
