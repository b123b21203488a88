//! JSIDL documents read with `roxmltree` (which keeps byte positions, turned into
//! line:column for errors), and small helpers over their elements: the local name,
//! attributes, element children, and description text with its whitespace collapsed.

use crate::error::{Error, Result};
use std::path::PathBuf;

/// An element of a document.
pub(crate) type Node<'a> = roxmltree::Node<'a, 'a>;

/// One parsed JSIDL file.
#[derive(Debug)]
pub(crate) struct Doc<'a> {
    /// Its path.
    pub path: PathBuf,
    /// Its path relative to the directory it was found in (`MessageSet/BasicTypes.xml`).
    pub rel: String,
    /// Index of the directory (the group) it came from.
    pub dir: usize,
    /// The tree.
    pub tree: roxmltree::Document<'a>,
}

impl<'a> Doc<'a> {
    /// Parses `text`.
    pub fn parse(path: PathBuf, rel: String, dir: usize, text: &'a str) -> Result<Self> {
        let opts = roxmltree::ParsingOptions {
            allow_dtd: false,
            ..Default::default()
        };
        match roxmltree::Document::parse_with_options(text, opts) {
            Ok(tree) => Ok(Doc {
                path,
                rel,
                dir,
                tree,
            }),
            Err(e) => {
                let p = e.pos();
                Err(Error::Xml {
                    file: path,
                    line: p.row,
                    column: p.col,
                    message: e.to_string(),
                })
            }
        }
    }

    /// The root element.
    pub fn root(&self) -> Node<'_> {
        self.tree.root_element()
    }

    /// An error about `node`.
    pub fn err(&self, node: Node<'_>, message: impl Into<String>) -> Error {
        let p = self.tree.text_pos_at(node.range().start);
        Error::At {
            file: self.path.clone(),
            line: p.row,
            column: p.col,
            element: element(node),
            message: message.into(),
        }
    }

    /// `file:line:column` of `node`.
    pub fn position(&self, node: Node<'_>) -> String {
        let p = self.tree.text_pos_at(node.range().start);
        format!("{}:{}:{}", self.path.display(), p.row, p.col)
    }

    /// The attribute `name` of `node`, or an error saying it is missing.
    pub fn req<'n>(&self, node: Node<'n>, name: &str) -> Result<&'n str> {
        node.attribute(name)
            .ok_or_else(|| self.err(node, format!("the attribute `{name}` is missing")))
    }
}

/// The element's name without its namespace (`internal` for `ns2:internal`).
pub(crate) fn tag<'n>(node: Node<'n>) -> &'n str {
    node.tag_name().name()
}

/// An element as errors name it: `fixed_field name="Speed"`.
pub(crate) fn element(node: Node<'_>) -> String {
    match node.attribute("name") {
        Some(n) => format!("{} name=\"{n}\"", tag(node)),
        None => tag(node).to_string(),
    }
}

/// The element children of `node`, in order.
pub(crate) fn elements<'n>(node: Node<'n>) -> impl Iterator<Item = Node<'n>> {
    node.children().filter(|c| c.is_element())
}

/// The first element child named `name`.
pub(crate) fn child<'n>(node: Node<'n>, name: &str) -> Option<Node<'n>> {
    elements(node).find(|c| tag(*c) == name)
}

/// `true` for the attribute `optional="true"` (or `1`).
pub(crate) fn optional(node: Node<'_>) -> bool {
    matches!(node.attribute("optional"), Some("true" | "1"))
}

/// Text with runs of whitespace collapsed to one space and trimmed; `None` if empty.
pub(crate) fn collapse(text: &str) -> Option<String> {
    let t = text.split_whitespace().collect::<Vec<_>>().join(" ");
    (!t.is_empty()).then_some(t)
}

/// The collapsed text of the `description` child of `node`.
pub(crate) fn description(node: Node<'_>) -> Option<String> {
    let d = child(node, "description")?;
    let text: String = d
        .descendants()
        .filter(|n| n.is_text())
        .filter_map(|n| n.text())
        .collect();
    collapse(&text)
}

/// The collapsed `interpretation` attribute of `node`.
pub(crate) fn interpretation(node: Node<'_>) -> Option<String> {
    node.attribute("interpretation").and_then(collapse)
}
