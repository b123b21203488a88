//! The importer's state: the documents, the sets they declare (by URI and version),
//! references between them (`declared_type_ref="core.commandClass.RequestControl"`),
//! the names given to types and messages, and what each file contributes.

use crate::error::{Error, Result};
use crate::names::pascal;
use crate::xml::{elements, tag, Doc, Node};
use jaus_spec::model::{MessageDef, ServiceDef, TypeDef};
use std::collections::{HashMap, HashSet};

/// An element of one of the documents.
#[derive(Debug, Clone, Copy)]
pub(crate) struct At<'a> {
    /// Index of its document.
    pub doc: usize,
    /// The element.
    pub node: Node<'a>,
}

/// What identifies an element across documents.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) struct Key(usize, roxmltree::NodeId);

impl At<'_> {
    pub fn key(&self) -> Key {
        Key(self.doc, self.node.id())
    }
    /// Its byte offset in its file (the order items are written in).
    pub fn offset(&self) -> usize {
        self.node.range().start
    }
}

/// What one JSIDL file contributes, each item with its offset in the file.
#[derive(Debug, Default)]
pub(crate) struct Contribution {
    pub types: Vec<(usize, TypeDef)>,
    pub messages: Vec<(usize, MessageDef)>,
    pub services: Vec<(usize, ServiceDef)>,
}

/// The importer.
#[derive(Debug)]
pub(crate) struct Importer<'a> {
    pub docs: &'a [Doc<'a>],
    /// What each document contributes (same index as `docs`).
    pub out: Vec<Contribution>,
    /// Declared type and constant sets by URI and version.
    sets: HashMap<(String, String), usize>,
    /// The type made of an element.
    pub types: HashMap<Key, String>,
    /// The message made of a `message_def`.
    pub messages: HashMap<Key, String>,
    /// Elements being converted (a type that contains itself).
    pub busy: Vec<Key>,
    /// Every type and message name given, and to what.
    taken: HashMap<String, Key>,
    /// Elements whose type has been written (or is being written).
    pub written: HashSet<Key>,
}

impl<'a> Importer<'a> {
    /// Indexes the sets the documents declare.
    pub fn new(docs: &'a [Doc<'a>]) -> Result<Self> {
        let mut sets: HashMap<(String, String), usize> = HashMap::new();
        for (i, d) in docs.iter().enumerate() {
            let root = d.root();
            if !matches!(tag(root), "declared_type_set" | "declared_const_set") {
                continue;
            }
            if let (Some(id), Some(v)) = (root.attribute("id"), root.attribute("version")) {
                if let Some(first) = sets.insert((id.to_string(), v.to_string()), i) {
                    return Err(Error::Duplicate {
                        file: d.path.clone(),
                        first: docs[first].path.clone(),
                        id: id.to_string(),
                        version: v.to_string(),
                    });
                }
            }
        }
        Ok(Importer {
            docs,
            out: docs.iter().map(|_| Contribution::default()).collect(),
            sets,
            types: HashMap::new(),
            messages: HashMap::new(),
            busy: Vec::new(),
            taken: HashMap::new(),
            written: HashSet::new(),
        })
    }

    /// The document of `at`.
    pub fn doc(&self, at: At<'_>) -> &'a Doc<'a> {
        &self.docs[at.doc]
    }

    /// An error about `at`.
    pub fn err(&self, at: At<'_>, message: impl Into<String>) -> Error {
        self.docs[at.doc].err(at.node, message)
    }

    /// A required attribute of `at`.
    pub fn req(&self, at: At<'a>, name: &str) -> Result<&'a str> {
        self.docs[at.doc].req(at.node, name)
    }

    /// A child element of `at` with the same document.
    pub fn at(&self, at: At<'a>, node: Node<'a>) -> At<'a> {
        At { doc: at.doc, node }
    }

    /// The declared type set whose names `at` sees: the nearest enclosing one, or the
    /// one of the enclosing service.
    pub fn scope(&self, at: At<'a>) -> Option<At<'a>> {
        for n in at.node.ancestors().filter(|n| n.is_element()) {
            match tag(n) {
                "declared_type_set" | "declared_const_set" => return Some(self.at(at, n)),
                "service_def" => {
                    return elements(n)
                        .find(|c| tag(*c) == "declared_type_set")
                        .map(|c| self.at(at, c))
                }
                _ => {}
            }
        }
        None
    }

    /// Resolves `at`'s `declared_type_ref` (following declared aliases) to the element
    /// that defines the type.
    pub fn resolve(&self, at: At<'a>) -> Result<At<'a>> {
        let mut cur = at;
        for _ in 0..32 {
            let Some(r) = cur.node.attribute("declared_type_ref") else {
                return Ok(cur);
            };
            let scope = self.scope(cur).ok_or_else(|| {
                self.err(
                    cur,
                    format!("`{r}`: no declared type set encloses this reference"),
                )
            })?;
            cur = self.lookup(cur, scope, r)?;
        }
        Err(self.err(at, "declared type references go round in a circle"))
    }

    /// Looks `reference` up in the set `scope`: a plain name among its elements, or
    /// `ref.rest` through its `declared_type_set_ref` named `ref`.
    pub fn lookup(&self, from: At<'a>, scope: At<'a>, reference: &str) -> Result<At<'a>> {
        let set_name = scope.node.attribute("name").unwrap_or("?");
        match reference.split_once('.') {
            None => elements(scope.node)
                .find(|c| {
                    c.attribute("name") == Some(reference)
                        && !matches!(tag(*c), "declared_type_set_ref" | "declared_const_set_ref")
                })
                .map(|n| self.at(scope, n))
                .ok_or_else(|| {
                    self.err(
                        from,
                        format!("`{reference}` is not declared in the type set `{set_name}`"),
                    )
                }),
            Some((head, rest)) => {
                let r = elements(scope.node)
                    .find(|c| {
                        matches!(tag(*c), "declared_type_set_ref" | "declared_const_set_ref")
                            && c.attribute("name") == Some(head)
                    })
                    .ok_or_else(|| {
                        self.err(
                            from,
                            format!("`{head}` (of `{reference}`) names no declared_type_set_ref of the type set `{set_name}`"),
                        )
                    })?;
                let r_at = self.at(scope, r);
                let id = self.req(r_at, "id")?;
                let version = self.req(r_at, "version")?;
                let doc = self
                    .sets
                    .get(&(id.to_string(), version.to_string()))
                    .copied()
                    .ok_or_else(|| {
                        self.err(
                            from,
                            format!("`{reference}`: the set {id} version {version} is not among the imported files"),
                        )
                    })?;
                let root = At {
                    doc,
                    node: self.docs[doc].root(),
                };
                self.lookup(from, root, rest)
            }
        }
    }

    /// Claims a message name (an error if it is taken: messages keep their names).
    pub fn claim_message(&mut self, at: At<'a>, name: &str) -> Result<()> {
        match self.taken.get(name) {
            Some(k) if *k != at.key() => Err(self.err(
                at,
                format!("a message or type named `{name}` is already defined: message names must be unique in an import"),
            )),
            _ => {
                self.taken.insert(name.to_string(), at.key());
                Ok(())
            }
        }
    }

    /// The type name of the element `at`: its own name for a type declared at the top
    /// of a set, else `owner` followed by it; on a clash the set's name goes in front,
    /// then a number after.
    pub fn type_name(&mut self, at: At<'a>, owner: &str, name: &str) -> String {
        if let Some(n) = self.types.get(&at.key()) {
            return n.clone();
        }
        let top = at
            .node
            .parent_element()
            .is_some_and(|p| tag(p) == "declared_type_set");
        let base = if top {
            pascal(name)
        } else {
            format!("{owner}{}", pascal(name))
        };
        let set = pascal(self.doc(at).root().attribute("name").unwrap_or("Set"));
        let mut candidates = vec![base.clone(), format!("{set}{base}")];
        candidates.extend((2..).take(1000).map(|i| format!("{base}{i}")));
        let name = candidates
            .into_iter()
            .find(|c| !self.taken.contains_key(c) && !RESERVED.contains(&c.as_str()))
            .unwrap_or(base);
        self.taken.insert(name.clone(), at.key());
        self.types.insert(at.key(), name.clone());
        name
    }

    /// Adds a type to the file of `at`.
    pub fn add_type(&mut self, at: At<'_>, def: TypeDef) {
        self.out[at.doc].types.push((at.offset(), def));
    }
}

/// Names the SDK gives its own types: no imported type takes them.
const RESERVED: &[&str] = &["Message", "Header", "Packet", "Address", "CommandCode"];
