//! Messages: a `message_def` with its message ID, the standard header (the 16-bit
//! message ID alone), its body and an empty footer.

use crate::error::Result;
use crate::fields::{basic, join, Mode};
use crate::import::{At, Importer};
use crate::names::pascal;
use crate::xml::{child, description, elements, tag};
use jaus_spec::model::{Code, MessageDef};

impl<'a> Importer<'a> {
    /// The name of a `message_def` (or a `declared_message_def` naming one), converting
    /// it the first time.
    pub fn message(&mut self, el: At<'a>) -> Result<String> {
        let def = self.resolve(el)?;
        if tag(def.node) != "message_def" {
            return Err(self.err(
                el,
                format!(
                    "the reference names a <{}>, not a <message_def>",
                    tag(def.node)
                ),
            ));
        }
        if let Some(n) = self.messages.get(&def.key()) {
            return Ok(n.clone());
        }
        let name = pascal(self.req(def, "name")?);
        self.claim_message(def, &name)?;
        self.messages.insert(def.key(), name.clone());
        let id = self.req(def, "message_id")?;
        let code = u16::from_str_radix(id.trim(), 16).map_err(|_| {
            self.err(
                def,
                format!("message_id `{id}` is not a 16-bit hexadecimal number"),
            )
        })?;
        let part = |n: &str| {
            elements(def.node)
                .find(|c| tag(*c) == n || tag(*c) == format!("declared_{n}"))
                .map(|c| self.at(def, c))
                .ok_or_else(|| self.err(def, format!("the <{n}> is missing")))
        };
        let (header, body, footer) = (part("header")?, part("body")?, part("footer")?);
        self.check_header(header)?;
        let footer = self.resolve(footer)?;
        if elements(footer.node).next().is_some() {
            return Err(self.err(
                footer,
                "a footer with fields is not supported (a message is its header and body)",
            ));
        }
        let (presence, fields) = self.body_fields(body, &name, Mode::Wire)?;
        let deprecated = matches!(def.node.attribute("deprecated"), Some("true" | "1"))
            .then(|| "Deprecated.".to_string());
        let is_command = match def.node.attribute("is_command") {
            Some("true" | "1") => Some(true),
            Some("false" | "0") => Some(false),
            _ => None,
        };
        let m = MessageDef {
            name: name.clone(),
            code: Code(code),
            title: None,
            description: join(&[deprecated, description(def.node)]),
            presence,
            report: None,
            no_report: false,
            readback: None,
            access: None,
            experimental: false,
            class: None,
            interop: None,
            is_command,
            runtime: Vec::new(),
            fields,
        };
        self.out[def.doc].messages.push((def.offset(), m));
        Ok(name)
    }

    /// The header is the standard one: a record of one unsigned short integer (the
    /// message ID), which the definition language carries as the message's `code`.
    fn check_header(&self, header: At<'a>) -> Result<()> {
        let h = self.resolve(header)?;
        let items: Vec<_> = elements(h.node).collect();
        let ok = match items[..] {
            [rec] if tag(rec) == "record" || tag(rec) == "declared_record" => {
                let rec = self.resolve(self.at(h, rec))?;
                let fields: Vec<_> = elements(rec.node).collect();
                match fields[..] {
                    [f] => {
                        let f = self.resolve(self.at(rec, f))?;
                        tag(f.node) == "fixed_field"
                            && f.node.attribute("field_type").and_then(basic) == Some("u16")
                            && child(f.node, "scale_range").is_none()
                    }
                    _ => false,
                }
            }
            _ => false,
        };
        if ok {
            Ok(())
        } else {
            Err(self.err(
                header,
                "only the standard header (the 16-bit message ID alone) is supported",
            ))
        }
    }
}
