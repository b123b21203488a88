//! Source positions of YAML nodes, by path (`messages[3].fields[2].bit`).
//!
//! `serde_yaml` reads the typed model but keeps no positions; this index is built from
//! the same text with `yaml-rust2`'s event parser so that every validation error can
//! point at the line and column of the offending key.

use std::collections::HashMap;
use yaml_rust2::parser::{Event, MarkedEventReceiver, Parser};
use yaml_rust2::scanner::Marker;

/// Line and column (both 1-based) of a node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Pos {
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
}

/// Positions of every mapping key and sequence item of one document.
#[derive(Debug, Default)]
pub struct LocationIndex {
    map: HashMap<String, Pos>,
}

enum Frame {
    Map { path: String, key: Option<String> },
    Seq { path: String, idx: usize },
}

#[derive(Default)]
struct Builder {
    stack: Vec<Frame>,
    map: HashMap<String, Pos>,
}

fn pos(m: Marker) -> Pos {
    Pos {
        line: m.line(),
        column: m.col() + 1,
    }
}

impl Builder {
    fn child_path(&self) -> String {
        match self.stack.last() {
            Some(Frame::Map { path, key: Some(k) }) if path.is_empty() => k.clone(),
            Some(Frame::Map { path, key: Some(k) }) => format!("{path}.{k}"),
            Some(Frame::Map { path, key: None }) => path.clone(),
            Some(Frame::Seq { path, idx }) => format!("{path}[{idx}]"),
            None => String::new(),
        }
    }

    fn advance(&mut self) {
        match self.stack.last_mut() {
            Some(Frame::Map { key, .. }) => *key = None,
            Some(Frame::Seq { idx, .. }) => *idx += 1,
            None => {}
        }
    }

    fn record(&mut self, path: String, m: Marker) {
        self.map.entry(path).or_insert(pos(m));
    }
}

impl MarkedEventReceiver for Builder {
    fn on_event(&mut self, ev: Event, mark: Marker) {
        match ev {
            Event::Scalar(value, ..) => {
                if let Some(Frame::Map {
                    key: key @ None,
                    path,
                }) = self.stack.last_mut()
                {
                    let p = if path.is_empty() {
                        value.clone()
                    } else {
                        format!("{path}.{value}")
                    };
                    let own = path.clone();
                    *key = Some(value);
                    self.record(own, mark);
                    self.record(p, mark);
                } else {
                    let p = self.child_path();
                    self.record(p, mark);
                    self.advance();
                }
            }
            Event::Alias(_) => {
                let p = self.child_path();
                self.record(p, mark);
                self.advance();
            }
            Event::MappingStart(..) => {
                // The mapping itself is located at its first key (recorded below): the
                // parser's mark for a block mapping start is not where the text begins.
                let path = self.child_path();
                self.stack.push(Frame::Map { path, key: None });
            }
            Event::SequenceStart(..) => {
                let path = self.child_path();
                self.record(path.clone(), mark);
                self.stack.push(Frame::Seq { path, idx: 0 });
            }
            Event::MappingEnd | Event::SequenceEnd => {
                self.stack.pop();
                self.advance();
            }
            _ => {}
        }
    }
}

impl LocationIndex {
    /// Indexes `src`. Text that does not parse yields an empty index (the serde error
    /// carries its own position).
    pub fn build(src: &str) -> Self {
        let mut b = Builder::default();
        let mut parser = Parser::new_from_str(src);
        if parser.load(&mut b, false).is_err() {
            return Self::default();
        }
        Self { map: b.map }
    }

    /// Position of `path`, or of its nearest indexed ancestor.
    pub fn find(&self, path: &str) -> Pos {
        let mut p = path;
        loop {
            if let Some(pos) = self.map.get(p) {
                return *pos;
            }
            match p.rfind(['.', '[']) {
                Some(i) => p = &p[..i],
                None => return Pos { line: 1, column: 1 },
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_nested_keys() {
        let src =
            "group: g\nmessages:\n  - name: A\n    fields:\n      - name: x\n        bit: 3\n";
        let idx = LocationIndex::build(src);
        assert_eq!(
            idx.find("messages[0].fields[0].bit"),
            Pos { line: 6, column: 9 }
        );
        assert_eq!(idx.find("messages[0].name"), Pos { line: 3, column: 5 });
        // A missing key falls back to its parent.
        assert_eq!(
            idx.find("messages[0].fields[0].scale"),
            Pos { line: 5, column: 9 }
        );
    }
}
