//! Names: of groups, and of the types and messages (which all become Rust types).

use super::Ctx;
use std::collections::HashMap;

/// Rust keywords (strict, reserved and weak ones used as names): no field name.
pub(super) const KEYWORDS: &[&str] = &[
    "as", "async", "await", "break", "const", "continue", "crate", "dyn", "else", "enum", "extern",
    "false", "fn", "for", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub",
    "ref", "return", "self", "Self", "static", "struct", "super", "trait", "true", "type",
    "unsafe", "use", "where", "while", "abstract", "become", "box", "do", "final", "macro",
    "override", "priv", "typeof", "unsized", "virtual", "yield", "try", "gen",
];

/// Names the SDK gives its own types.
const RESERVED: &[&str] = &["Message", "Header", "Packet", "Address", "CommandCode"];

/// `snake_case`: a lower-case letter, then lower-case letters, digits and `_`.
pub(super) fn is_snake(s: &str) -> bool {
    !s.is_empty()
        && s.starts_with(|c: char| c.is_ascii_lowercase())
        && s.chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
}

/// `PascalCase`: an upper-case letter, then letters and digits.
pub(super) fn is_pascal(s: &str) -> bool {
    !s.is_empty()
        && s.starts_with(|c: char| c.is_ascii_uppercase())
        && s.chars().all(|c| c.is_ascii_alphanumeric())
}

/// The group of each file (named by its first message or type) is `snake_case`: it
/// is also a cargo feature.
pub(super) fn check_groups(cx: &mut Ctx<'_>) {
    let spec = cx.spec;
    for si in 0..spec.sources.len() {
        let group = spec
            .messages
            .iter()
            .find(|m| m.source == si)
            .map(|m| m.group.clone())
            .or_else(|| {
                spec.types
                    .iter()
                    .find(|t| t.source == si)
                    .map(|t| t.group.clone())
            });
        if let Some(g) = group {
            if !is_snake(&g) {
                cx.err(
                    si,
                    "group",
                    String::new(),
                    format!("group name `{g}` must be snake_case (it is also a cargo feature)"),
                );
            }
        }
    }
}

/// Type and message names are `PascalCase`, not reserved by the SDK, and unique
/// across both (they all become Rust types).
pub(super) fn check_type_and_message_names(cx: &mut Ctx<'_>) {
    let spec = cx.spec;
    let mut seen: HashMap<&str, (usize, &str)> = HashMap::new();
    let entries = spec
        .types
        .iter()
        .map(|t| (t.def.name.as_str(), t.source, t.path.as_str(), "type"))
        .chain(
            spec.messages
                .iter()
                .map(|m| (m.def.name.as_str(), m.source, m.path.as_str(), "message")),
        );
    for (name, source, path, what) in entries {
        if !is_pascal(name) {
            cx.err(
                source,
                &format!("{path}.name"),
                format!("{what} `{name}`"),
                format!("name `{name}` must be PascalCase"),
            );
        }
        if RESERVED.contains(&name) {
            cx.err(
                source,
                &format!("{path}.name"),
                format!("{what} `{name}`"),
                format!("`{name}` is reserved by the SDK"),
            );
        }
        if let Some((other_src, other_path)) = seen.insert(name, (source, path)) {
            let o = &spec.sources[other_src];
            let pos = o.index.find(other_path);
            cx.err(
                source,
                &format!("{path}.name"),
                format!("{what} `{name}`"),
                format!(
                    "duplicate name `{name}` (first defined at {}:{}:{})",
                    o.path.display(),
                    pos.line,
                    pos.column
                ),
            );
        }
    }
}
