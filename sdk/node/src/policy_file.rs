//! `policy:` of a node file: the node's access policy (`jaus::net::Policy`), checked
//! rule by rule with file:line:column errors.
//!
//! ```yaml
//! policy:
//!   default: query                  # command (the default: open), query or none
//!   rules:                           # first match decides
//!     - { from: 200.*.*.*, may: command, max_authority: 100 }
//!     - { from: 42.1.*.*, may: query }
//!     - { from: 66.*.*.*, may: none, emergency: false }
//! ```
//!
//! `max_authority` (0-255, default 255) bounds the authority a `command` sender may ask
//! control with. Set/Clear Emergency pass for every sender unless its rule (or
//! `default_emergency`) says `emergency: false`.

use jaus::net::policy::{AddressPattern, Permission, Policy, Rule};

/// `policy:` as written.
#[derive(Debug, Clone, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PolicyFile {
    /// What senders no rule names may do: `command`, `query` or `none`. Default
    /// `command`.
    #[serde(default)]
    pub default: Option<String>,
    /// With `default: command`: the highest authority. Default 255.
    #[serde(default)]
    pub max_authority: Option<u8>,
    /// Whether Set/Clear Emergency pass for senders no rule names. Default true.
    #[serde(default)]
    pub default_emergency: Option<bool>,
    /// The rules, first match decides.
    #[serde(default)]
    pub rules: Vec<RuleFile>,
}

/// One rule as written.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RuleFile {
    /// `S.N.C.I`, each a number or `*`.
    pub from: String,
    /// `command`, `query` or `none`.
    pub may: String,
    /// With `may: command`: the highest authority. Default 255.
    #[serde(default)]
    pub max_authority: Option<u8>,
    /// Whether Set/Clear Emergency pass. Default true.
    #[serde(default)]
    pub emergency: Option<bool>,
}

/// `command`/`query`/`none` with an optional authority bound, checked.
fn permission(
    may: &str,
    max_authority: Option<u8>,
    key: &str,
    at: &dyn Fn(&str) -> String,
) -> Result<Permission, String> {
    match (may, max_authority) {
        ("command", a) => Ok(Permission::Command {
            max_authority: a.unwrap_or(255),
        }),
        ("query", None) => Ok(Permission::Query),
        ("none", None) => Ok(Permission::None),
        ("query" | "none", Some(_)) => Err(format!(
            "{}: max_authority is for `command`; `{may}` may not take control at all",
            at(&format!("{key}.max_authority"))
        )),
        (other, _) => Err(format!(
            "{}: `{other}` is not a permission (command, query or none)",
            at(key)
        )),
    }
}

impl PolicyFile {
    /// The policy, checked (`at` gives the file:line:column of a YAML path).
    pub fn policy(&self, at: &dyn Fn(&str) -> String) -> Result<Policy, String> {
        let default = permission(
            self.default.as_deref().unwrap_or("command"),
            self.max_authority,
            "policy.default",
            at,
        )?;
        let mut rules = Vec::with_capacity(self.rules.len());
        for (i, r) in self.rules.iter().enumerate() {
            let key = format!("policy.rules[{i}]");
            let from: AddressPattern = r
                .from
                .parse()
                .map_err(|e| format!("{}: from: {e}", at(&format!("{key}.from"))))?;
            rules.push(Rule {
                from,
                may: permission(&r.may, r.max_authority, &format!("{key}.may"), at)?,
                emergency: r.emergency.unwrap_or(true),
            });
        }
        Ok(Policy {
            rules,
            default,
            default_emergency: self.default_emergency.unwrap_or(true),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load(yaml: &str) -> Result<Policy, String> {
        let f: PolicyFile = serde_yaml::from_str(yaml).map_err(|e| e.to_string())?;
        f.policy(&|k| format!("node.yaml:{k}"))
    }

    #[test]
    fn rules_and_default_are_read() {
        let p = load(
            "default: query\nrules:\n  - { from: 200.*.*.*, may: command, max_authority: 100 }\n  - { from: 66.*.*.*, may: none, emergency: false }\n",
        )
        .unwrap();
        assert_eq!(p.default, Permission::Query);
        assert_eq!(p.rules.len(), 2);
        assert_eq!(p.rules[0].may, Permission::Command { max_authority: 100 });
        assert!(p.rules[0].emergency && !p.rules[1].emergency);
        assert!(load("{}").unwrap().is_open());
    }

    #[test]
    fn mistakes_name_the_field() {
        let e = load("rules:\n  - { from: 200.*.*, may: command }\n").unwrap_err();
        assert!(
            e.starts_with("node.yaml:policy.rules[0].from: from: `200.*.*`"),
            "{e}"
        );
        let e = load("rules:\n  - { from: 1.*.*.*, may: drive }\n").unwrap_err();
        assert!(
            e.contains("policy.rules[0].may: `drive` is not a permission"),
            "{e}"
        );
        let e = load("default: query\nmax_authority: 3\n").unwrap_err();
        assert!(e.contains("policy.default.max_authority"), "{e}");
        assert!(load("rules:\n  - { from: 1.*.*.*, may: query, colour: red }\n").is_err());
    }
}
