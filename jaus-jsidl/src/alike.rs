//! Whether two sets' messages of the same name are one message: the same message ID,
//! the same body on the wire and the same names, each `declared_*` reference compared
//! by what it names (the published sets of Core v1.1 and of Mobility each define
//! `SetElement`, on types of their own that say the same). Descriptions do not count;
//! the header and footer are each checked to be the standard ones when converted.

use crate::error::Result;
use crate::import::{At, Importer};
use crate::xml::{element, elements, tag};

/// Attributes that do not change a message: documentation, and how a reference is
/// written.
const IGNORED: &[&str] = &["interpretation", "declared_type_ref", "xml:space", "space"];

/// Elements that do not change a message on the wire.
const SKIPPED: &[&str] = &[
    "description",
    "header",
    "declared_header",
    "footer",
    "declared_footer",
];

impl<'a> Importer<'a> {
    /// The element a key stands for.
    pub fn node_of(&self, key: crate::import::Key) -> Option<At<'a>> {
        let node = self.docs[key.0].tree.get_node(key.1)?;
        Some(At { doc: key.0, node })
    }

    /// `None` when the `message_def`s `a` and `b` are one message, else where and how
    /// they first differ.
    pub fn message_difference(&self, a: At<'a>, b: At<'a>) -> Result<Option<String>> {
        self.differ(a, b, 0)
    }

    fn differ(&self, a: At<'a>, b: At<'a>, depth: usize) -> Result<Option<String>> {
        if depth > 64 {
            return Ok(Some("nested too deeply to compare".into()));
        }
        // A reference stands for what it names, under its own name.
        let (da, db) = (self.resolve(a)?, self.resolve(b)?);
        let here = |what: String| {
            Some(format!(
                "<{}> at {} and at {}: {what}",
                element(a.node),
                self.doc(a).position(a.node),
                self.doc(b).position(b.node),
            ))
        };
        if tag(da.node) != tag(db.node) {
            return Ok(here(format!(
                "<{}> against <{}>",
                tag(da.node),
                tag(db.node)
            )));
        }
        for attr in ["name", "optional"] {
            let (x, y) = (a.node.attribute(attr), b.node.attribute(attr));
            if x != y {
                return Ok(here(format!("`{attr}` {x:?} against {y:?}")));
            }
        }
        let attrs = |n: At<'a>| {
            let mut v: Vec<(String, String)> = n
                .node
                .attributes()
                .filter(|x| {
                    !IGNORED.contains(&x.name()) && !matches!(x.name(), "name" | "optional")
                })
                .map(|x| {
                    (
                        x.name().to_string(),
                        x.value().split_whitespace().collect::<Vec<_>>().join(" "),
                    )
                })
                .collect();
            v.sort();
            v
        };
        let (xa, xb) = (attrs(da), attrs(db));
        if xa != xb {
            return Ok(here(format!("attributes {xa:?} against {xb:?}")));
        }
        let kids = |n: At<'a>| -> Vec<At<'a>> {
            elements(n.node)
                .filter(|c| !SKIPPED.contains(&tag(*c)))
                .map(|c| self.at(n, c))
                .collect()
        };
        let (ka, kb) = (kids(da), kids(db));
        if ka.len() != kb.len() {
            return Ok(here(format!("{} items against {}", ka.len(), kb.len())));
        }
        for (x, y) in ka.into_iter().zip(kb) {
            if let Some(d) = self.differ(x, y, depth + 1)? {
                return Ok(Some(d));
            }
        }
        Ok(None)
    }
}
