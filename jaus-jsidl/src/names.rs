//! JSIDL names turned into the definition language's: `PascalCase` for types,
//! messages, enumeration values and services, `snake_case` for fields, and group names.

/// Rust keywords: a field named like one gets a trailing `_`.
const KEYWORDS: &[&str] = &[
    "as", "async", "await", "break", "const", "continue", "crate", "dyn", "else", "enum", "extern",
    "false", "fn", "for", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub",
    "ref", "return", "self", "static", "struct", "super", "trait", "true", "type", "unsafe", "use",
    "where", "while", "abstract", "become", "box", "do", "final", "macro", "override", "priv",
    "typeof", "unsized", "virtual", "yield", "try", "gen",
];

/// The words of a name: split at anything not a letter or digit, at a lower-case
/// letter or digit followed by an upper-case one (`authorityRec`), and before the last
/// capital of an acronym followed by a lower-case letter (`UIDValue` → `UID`, `Value`).
fn words(name: &str) -> Vec<String> {
    let mut out = Vec::new();
    for part in name.split(|c: char| !c.is_ascii_alphanumeric()) {
        let chars: Vec<char> = part.chars().collect();
        let mut cur = String::new();
        for (i, &c) in chars.iter().enumerate() {
            let prev = i.checked_sub(1).map(|j| chars[j]);
            let next = chars.get(i + 1).copied();
            let boundary = match prev {
                Some(p) if c.is_ascii_uppercase() => {
                    p.is_ascii_lowercase()
                        || p.is_ascii_digit()
                        || (p.is_ascii_uppercase() && next.is_some_and(|n| n.is_ascii_lowercase()))
                }
                _ => false,
            };
            if boundary && !cur.is_empty() {
                out.push(std::mem::take(&mut cur));
            }
            cur.push(c);
        }
        if !cur.is_empty() {
            out.push(cur);
        }
    }
    out
}

/// `PascalCase` of a JSIDL name or constant (`authorityRec` → `AuthorityRec`,
/// `CONTROL_ACCEPTED` → `ControlAccepted`, `not supported` → `NotSupported`); a name
/// that would start with a digit gets a `V` in front.
pub(crate) fn pascal(name: &str) -> String {
    let mut s = String::new();
    for w in words(name) {
        let all_upper = w.chars().all(|c| !c.is_ascii_lowercase());
        let mut cs = w.chars();
        if let Some(first) = cs.next() {
            s.push(first.to_ascii_uppercase());
            let rest: String = cs.collect();
            if all_upper {
                s.push_str(&rest.to_ascii_lowercase());
            } else {
                s.push_str(&rest);
            }
        }
    }
    if s.is_empty() {
        s.push_str("Value");
    }
    if s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, 'V');
    }
    s
}

/// `snake_case` of a JSIDL name (`ElementUID` → `element_uid`, `MessageID` →
/// `message_id`); a Rust keyword gets a trailing `_`, a leading digit an `n_`.
pub(crate) fn snake(name: &str) -> String {
    let mut s = words(name)
        .iter()
        .map(|w| w.to_ascii_lowercase())
        .collect::<Vec<_>>()
        .join("_");
    if s.is_empty() {
        s.push_str("value");
    }
    if s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert_str(0, "n_");
    }
    if KEYWORDS.contains(&s.as_str()) {
        s.push('_');
    }
    s
}

/// The group of a directory of JSIDL files: its name in `snake_case` without a leading
/// `urn` (`urn.jaus.jss.core-v1.1` → `jaus_jss_core_v1_1`).
pub(crate) fn group(dir_name: &str) -> String {
    let lower: String = dir_name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    let mut g = lower
        .split('_')
        .filter(|w| !w.is_empty())
        .collect::<Vec<_>>()
        .join("_");
    if let Some(rest) = g.strip_prefix("urn_") {
        g = rest.to_string();
    }
    if !g.starts_with(|c: char| c.is_ascii_lowercase()) {
        g.insert_str(0, "jsidl_");
    }
    g
}

/// The YAML file name of a JSIDL file (`MessageSet/BasicTypes.xml` →
/// `message_set_basic_types.yaml`).
pub(crate) fn yaml_file(rel: &str) -> String {
    let stem = rel.strip_suffix(".xml").unwrap_or(rel);
    format!("{}.yaml", snake(stem).trim_end_matches('_'))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cases() {
        assert_eq!(pascal("authorityRec"), "AuthorityRec");
        assert_eq!(pascal("CONTROL_ACCEPTED"), "ControlAccepted");
        assert_eq!(
            pascal("periodic events not supported"),
            "PeriodicEventsNotSupported"
        );
        assert_eq!(pascal("2D"), "V2D");
        assert_eq!(snake("ElementUID"), "element_uid");
        assert_eq!(snake("MessageID"), "message_id");
        assert_eq!(snake("UIDValue"), "uid_value");
        assert_eq!(snake("Type"), "type_");
        assert_eq!(group("urn.jaus.jss.core-v1.1"), "jaus_jss_core_v1_1");
        assert_eq!(
            yaml_file("MessageSet/BasicTypes.xml"),
            "message_set_basic_types.yaml"
        );
    }
}
