//! Whether two JSIDL elements say the same thing: the same element names, the same
//! attributes (whitespace in values collapsed) and the same text (collapsed), in the
//! same order. Layout, comments, namespace prefixes and declarations do not count. Used
//! to read a declared type set that two files declare (a set shipping its own copy of
//! the Core basic types) once, and to refuse two that differ, naming the first
//! difference.

use crate::xml::{collapse, tag, Node};

/// The first difference between `a` and `b`: the two nodes where it is, and what.
#[derive(Debug)]
pub(crate) struct Difference<'a> {
    /// Where it is in the first tree.
    pub a: Node<'a>,
    /// Where it is in the second tree.
    pub b: Node<'a>,
    /// What differs.
    pub what: String,
}

/// The significant children: elements and non-blank text.
fn children<'a>(n: Node<'a>) -> Vec<Node<'a>> {
    n.children()
        .filter(|c| c.is_element() || (c.is_text() && c.text().and_then(collapse).is_some()))
        .collect()
}

/// The attributes, by local name, values collapsed, sorted.
fn attributes(n: Node<'_>) -> Vec<(String, String)> {
    let mut v: Vec<(String, String)> = n
        .attributes()
        .map(|a| {
            (
                a.name().to_string(),
                collapse(a.value()).unwrap_or_default(),
            )
        })
        .collect();
    v.sort();
    v
}

/// Whether set `b` only adds to set `a`: every item (child element with a name) that
/// both declare is the same in both, and `b` declares at least one that `a` lacks. Such
/// a re-declaration is read for its additions.
pub(crate) fn supplements<'a>(a: Node<'a>, b: Node<'a>) -> bool {
    let (ia, ib) = (items(a), items(b));
    let mut added = false;
    for (name, nb) in &ib {
        match ia.iter().find(|(n, _)| n == name) {
            Some((_, na)) if difference(*na, *nb).is_some() => return false,
            Some(_) => {}
            None => added = true,
        }
    }
    added
}

/// The named child elements of a set, by `tag:name`.
fn items<'a>(n: Node<'a>) -> Vec<(String, Node<'a>)> {
    n.children()
        .filter(|c| c.is_element())
        .filter_map(|c| c.attribute("name").map(|x| (format!("{}:{x}", tag(c)), c)))
        .collect()
}

/// `None` when `a` and `b` are the same, else their first difference (depth first, in
/// document order).
pub(crate) fn difference<'a>(a: Node<'a>, b: Node<'a>) -> Option<Difference<'a>> {
    let diff = |a, b, what: String| Some(Difference { a, b, what });
    if a.is_text() || b.is_text() {
        let (ta, tb) = (
            a.text().and_then(collapse).unwrap_or_default(),
            b.text().and_then(collapse).unwrap_or_default(),
        );
        if a.is_text() != b.is_text() || ta != tb {
            let (pa, pb) = (a.parent().unwrap_or(a), b.parent().unwrap_or(b));
            return diff(
                pa,
                pb,
                format!("text `{}` against `{}`", short(&ta), short(&tb)),
            );
        }
        return None;
    }
    if tag(a) != tag(b) {
        return diff(a, b, format!("<{}> against <{}>", tag(a), tag(b)));
    }
    let (aa, ab) = (attributes(a), attributes(b));
    if aa != ab {
        let first = aa
            .iter()
            .chain(ab.iter())
            .map(|(k, _)| k)
            .find(|k| {
                a.attribute(k.as_str()).map(collapse) != b.attribute(k.as_str()).map(collapse)
            })
            .cloned()
            .unwrap_or_default();
        let show = |n: Node<'_>| match n.attribute(first.as_str()) {
            Some(v) => format!("`{first}=\"{}\"`", short(v)),
            None => format!("no `{first}`"),
        };
        return diff(a, b, format!("{} against {}", show(a), show(b)));
    }
    let (ca, cb) = (children(a), children(b));
    for (x, y) in ca.iter().zip(cb.iter()) {
        if let Some(d) = difference(*x, *y) {
            return Some(d);
        }
    }
    if ca.len() != cb.len() {
        let what = |n: Option<&Node<'_>>| match n {
            Some(n) if n.is_element() => format!("<{}>", tag(*n)),
            Some(_) => "text".to_string(),
            None => "nothing".to_string(),
        };
        let i = ca.len().min(cb.len());
        return diff(
            a,
            b,
            format!(
                "{} against {} after {i} children",
                what(ca.get(i)),
                what(cb.get(i))
            ),
        );
    }
    None
}

/// A value cut to a readable length.
fn short(s: &str) -> String {
    const MAX: usize = 60;
    match s.char_indices().nth(MAX) {
        Some((i, _)) => format!("{}…", &s[..i]),
        None => s.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn first<'a>(a: &'a roxmltree::Document<'a>, b: &'a roxmltree::Document<'a>) -> Option<String> {
        difference(a.root_element(), b.root_element()).map(|d| d.what)
    }

    #[test]
    fn layout_and_comments_do_not_count() {
        let a = roxmltree::Document::parse(
            "<s xmlns=\"urn:x\" a=\"1\"><f n=\"x  y\"/><d>some\n text</d></s>",
        )
        .unwrap();
        let b = roxmltree::Document::parse(
            "<s a=\"1\" xmlns=\"urn:x\" xmlns:p=\"urn:y\">\n  <!-- note -->\n  <f\n n=\"x\n y\"/>\n<d> some text </d>\n</s>",
        )
        .unwrap();
        assert_eq!(first(&a, &b), None);
    }

    #[test]
    fn the_first_difference_is_named() {
        let a = roxmltree::Document::parse("<s><f n=\"1\"/><g/></s>").unwrap();
        let b = roxmltree::Document::parse("<s><f n=\"2\"/><h/></s>").unwrap();
        assert_eq!(first(&a, &b).unwrap(), "`n=\"1\"` against `n=\"2\"`");
        let c = roxmltree::Document::parse("<s><f n=\"1\"/></s>").unwrap();
        assert_eq!(
            first(&a, &c).unwrap(),
            "<g> against nothing after 1 children"
        );
    }
}
