//! Checks of the `stock:` entries of components: the names `jaus node` files use for
//! the SDK's stock implementations.

use std::collections::HashMap;

use super::Draft;
use crate::source::SpecError;

/// Words of a node file's `host:` list that are not components.
const RESERVED: &[&str] = &["vehicle", "arm"];

/// Every problem with the `stock:` entries of `draft`: a name that is not snake_case,
/// is reserved, or is used twice.
pub(crate) fn check(draft: &Draft) -> Vec<SpecError> {
    let mut errors = Vec::new();
    let mut seen: HashMap<&str, &str> = HashMap::new();
    for c in &draft.components {
        let Some(stock) = &c.def.stock else { continue };
        let name = stock.name.as_str();
        let problem = if !is_snake(name) {
            Some(format!(
                "stock name `{name}` must be snake_case (it is typed in node files' `host:`)"
            ))
        } else if RESERVED.contains(&name) {
            Some(format!(
                "stock name `{name}` is reserved: a node file's `host: [{name}]` means a whole simulated {name}"
            ))
        } else {
            seen.insert(name, &c.def.name)
                .map(|other| format!("stock name `{name}` is already used by `{other}`"))
        };
        if let Some(message) = problem {
            let source = &draft.sources[c.source];
            errors.push(SpecError {
                file: source.path.clone(),
                pos: source.index.find(&format!("{}.stock.name", c.path)),
                context: format!("component `{}`", c.def.name),
                message,
            });
        }
    }
    errors
}

fn is_snake(s: &str) -> bool {
    s.starts_with(|c: char| c.is_ascii_lowercase())
        && s.chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
}
