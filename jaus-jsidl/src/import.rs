//! The importer's state: the documents, the sets they declare (by URI and version),
//! references between them (`declared_type_ref="core.commandClass.RequestControl"`),
//! the names given to types and messages, and what each file contributes.

use crate::error::{Error, Result};
use crate::names::pascal;
use crate::same;
use crate::xml::{element, elements, tag, Doc, Node};
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
pub(crate) struct Key(pub usize, pub roxmltree::NodeId);

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
    /// Documents declaring a set an earlier one declares (alike, or differently: then
    /// an error), which are not read.
    copies: HashSet<usize>,
    /// Documents that declare a set again with items the first lacks and the items both
    /// declare alike (Manipulator v2.0's copy of the Core basic types names the
    /// application-layer header differently): a name the first document lacks is looked
    /// up in them, by first document.
    supplements: HashMap<usize, Vec<usize>>,
    /// Errors found on indexing the sets (sets declared twice differently).
    pub errors: Vec<Error>,
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
    /// Indexes the sets the documents declare. A set two files declare alike is read
    /// once, from the first; two that differ are an error naming the first difference
    /// (in `errors`).
    pub fn new(docs: &'a [Doc<'a>]) -> Self {
        let mut sets: HashMap<(String, String), usize> = HashMap::new();
        let mut copies = HashSet::new();
        let mut supplements: HashMap<usize, Vec<usize>> = HashMap::new();
        let mut errors = Vec::new();
        for (i, d) in docs.iter().enumerate() {
            let root = d.root();
            if !matches!(tag(root), "declared_type_set" | "declared_const_set") {
                continue;
            }
            let (Some(id), Some(v)) = (root.attribute("id"), root.attribute("version")) else {
                continue;
            };
            let Some(&first) = sets.get(&(id.to_string(), v.to_string())) else {
                sets.insert((id.to_string(), v.to_string()), i);
                continue;
            };
            let f = &docs[first];
            // Either way the second file is not read: a set declared differently is
            // reported, and the run goes on to report the rest.
            copies.insert(i);
            if same::difference(f.root(), root).is_some() && same::supplements(f.root(), root) {
                supplements.entry(first).or_default().push(i);
                continue;
            }
            if let Some(diff) = same::difference(f.root(), root) {
                errors.push(Error::Duplicate {
                    file: d.path.clone(),
                    first: f.path.clone(),
                    id: id.to_string(),
                    version: v.to_string(),
                    difference: format!(
                        "<{}> at {} and at {}: {}",
                        element(diff.a),
                        f.position(diff.a),
                        d.position(diff.b),
                        diff.what,
                    ),
                });
            }
        }
        Importer {
            supplements,
            errors,
            docs,
            out: docs.iter().map(|_| Contribution::default()).collect(),
            sets,
            copies,
            types: HashMap::new(),
            messages: HashMap::new(),
            busy: Vec::new(),
            taken: HashMap::new(),
            written: HashSet::new(),
        }
    }

    /// Whether document `doc` declares a set another document declared alike (it is
    /// read from that one).
    pub fn is_copy(&self, doc: usize) -> bool {
        self.copies.contains(&doc)
    }

    /// The value of a conversion that succeeded; the error of one that failed goes into
    /// `errors` (and what it was converting is forgotten, so the next starts clean).
    pub fn keep<T>(&mut self, r: Result<T>, errors: &mut Vec<Error>) -> Option<T> {
        match r {
            Ok(v) => Some(v),
            Err(e) => {
                self.busy.clear();
                errors.push(e);
                None
            }
        }
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
        let named = |set: At<'a>| {
            elements(set.node)
                .find(|c| {
                    c.attribute("name") == Some(reference)
                        && !matches!(tag(*c), "declared_type_set_ref" | "declared_const_set_ref")
                })
                .map(|n| self.at(set, n))
        };
        match reference.split_once('.') {
            None => named(scope)
                .or_else(|| {
                    // An item a later declaration of the same set adds.
                    let root = self.docs[scope.doc].root();
                    (scope.node == root)
                        .then(|| self.supplements.get(&scope.doc))
                        .flatten()
                        .into_iter()
                        .flatten()
                        .find_map(|&d| {
                            named(At {
                                doc: d,
                                node: self.docs[d].root(),
                            })
                        })
                })
                .ok_or_else(|| {
                    self.err(
                        from,
                        format!("`{reference}` is not declared in the type set `{set_name}`"),
                    )
                }),
            Some((head, rest)) => {
                let r = match self.set_ref(scope, head) {
                    Some(r) => r,
                    // As the JAUS Tool Set does: a set referred to by a set this one
                    // refers to (the published HMI messages name `basicTypes`, which
                    // their types set refers to).
                    None => self.nested_set_ref(scope, head).ok_or_else(|| {
                        self.err(
                            from,
                            format!("`{head}` (of `{reference}`) names no declared_type_set_ref of the type set `{set_name}`, nor of a set it refers to"),
                        )
                    })?,
                };
                let id = self.req(r, "id")?;
                let version = self.req(r, "version")?;
                let doc = self.set_doc(r).ok_or_else(|| {
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

    /// The `declared_type_set_ref` (or `declared_const_set_ref`) named `name` of `set`.
    fn set_ref(&self, set: At<'a>, name: &str) -> Option<At<'a>> {
        elements(set.node)
            .find(|c| {
                matches!(tag(*c), "declared_type_set_ref" | "declared_const_set_ref")
                    && c.attribute("name") == Some(name)
            })
            .map(|n| self.at(set, n))
    }

    /// The document declaring the set a set reference names, if imported.
    fn set_doc(&self, r: At<'a>) -> Option<usize> {
        let id = r.node.attribute("id")?;
        let version = r.node.attribute("version")?;
        self.sets
            .get(&(id.to_string(), version.to_string()))
            .copied()
    }

    /// A set reference named `name` of a set that `set` refers to, breadth first
    /// through the imported sets of sets (the first found, in document order).
    fn nested_set_ref(&self, set: At<'a>, name: &str) -> Option<At<'a>> {
        let mut seen = HashSet::new();
        let mut queue = std::collections::VecDeque::from([set]);
        while let Some(s) = queue.pop_front() {
            for r in elements(s.node)
                .filter(|c| matches!(tag(*c), "declared_type_set_ref" | "declared_const_set_ref"))
            {
                let Some(doc) = self.set_doc(self.at(s, r)) else {
                    continue;
                };
                if !seen.insert(doc) {
                    continue;
                }
                let root = At {
                    doc,
                    node: self.docs[doc].root(),
                };
                if let Some(found) = self.set_ref(root, name) {
                    return Some(found);
                }
                queue.push_back(root);
            }
        }
        None
    }

    /// Claims a message name (messages keep their names). A message of another set
    /// with the name that is the same message (see [`crate::alike`]) is read once, as
    /// the first; any other clash is an error.
    pub fn claim_message(&mut self, at: At<'a>, name: &str) -> Result<()> {
        let Some(&k) = self.taken.get(name) else {
            self.taken.insert(name.to_string(), at.key());
            return Ok(());
        };
        if k == at.key() {
            return Ok(());
        }
        let first = self
            .node_of(k)
            .filter(|f| tag(f.node) == "message_def" && tag(at.node) == "message_def");
        let Some(first) = first else {
            return Err(self.err(
                at,
                format!("a message or type named `{name}` is already defined: message names must be unique in an import"),
            ));
        };
        match self.message_difference(first, at)? {
            None => {
                self.messages.insert(at.key(), name.to_string());
                Ok(())
            }
            Some(diff) => Err(self.err(
                at,
                format!(
                    "a message named `{name}` is already defined at {}, differently ({diff}): the definition language holds one message of a name and message ID in an import",
                    self.doc(first).position(first.node)
                ),
            )),
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
