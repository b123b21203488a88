//! Profiles: a named set of checks (`jaus conform --profile NAME|FILE`).
//!
//! A profile lists the checks a run plans, by id or by a prefix ending with `*`
//! (`control.*`; `*` alone is every check), each optionally at another level than its
//! own. Built in:
//!
//! * `all`: every check (a run without `--profile`);
//! * `ra33-core`: the Part 1 core rules, the checks every RA 3.3 component gets
//!   whatever its type (what [`crate::plan::plan`] gives a type the definitions do not
//!   know: identification, services, status, heartbeat, time, authority, component
//!   control, the core state commands, emergencies, the read-back of Set Component
//!   Authority, events and a service connection on Report Component Status,
//!   robustness) and the teardown check; not the checks a component type's own
//!   interface brings (`core.services.inputs`, `query.*`, the read-back of its own
//!   commands);
//! * `iop`: the IGVC IOP challenge's AS-4 judge (`as4.*`, what `--as4` runs).
//!
//! A vendor's profile is a YAML file:
//!
//! ```yaml
//! name: acme-pump
//! description: What an Acme pump passes before it is fielded.
//! checks:
//!   - id: core.identification
//!   - id: control.*
//!   - id: events.every-change
//!     level: required
//! ```
//!
//! Every entry must name a check of the catalogue ([`crate::catalogue`]) or a prefix of
//! one: an unknown id is an error naming the file, the entry's line and the closest
//! known id. A check takes its level from the most specific entry that gives one (the
//! entry naming it, else the longest prefix).
//!
//! The engine ([`crate::engine`]) applies a profile the same way to every voice: a
//! check it leaves out is not run (nothing is sent for it), unless the voice needs it
//! run, and then the report leaves it out. The RA 3.3 teardown always runs (the tester
//! leaves the target as found); the AS-4 scenario is one sequence whose steps prepare
//! the next (control, the list loaded), so it runs whole; the checks planned from AS-4
//! definitions need only their first, the services listed.

use std::fmt;
use std::path::Path;

use jaus_spec::Spec;
use serde::Deserialize;

use crate::catalogue::Entry;
use crate::engine::{Options, RunReport};
pub use crate::selection::{LevelName, Pick, Selection};
use crate::session::{Session, Voices};

/// The built-in profiles' names.
pub const BUILTIN: [&str; 3] = ["all", "ra33-core", "iop"];

/// The checks of `ra33-core`: those every RA 3.3 component gets.
const RA33_CORE: &[&str] = &[
    "core.identification",
    "core.services",
    "core.status",
    "core.heartbeat",
    "core.authority",
    "core.time",
    "control.*",
    "state.*",
    "emergency.*",
    "readback.SetComponentAuthority",
    "outsider.SetComponentAuthority",
    "events.*",
    "sc.*",
    "robust.*",
    "teardown.as-found",
];

/// A profile: its name, what it is for, and the checks it selects.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Profile {
    /// Its name (reported with the run).
    pub name: String,
    /// What it is for.
    #[serde(default)]
    pub description: String,
    /// The checks, by id or prefix.
    pub checks: Vec<Pick>,
    /// Where it was read from (a file's path, or `built-in`).
    #[serde(skip)]
    pub origin: String,
}

/// A profile that cannot be read or names what the catalogue does not have.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ProfileError {
    /// The file (or `built-in`, or the name given).
    pub origin: String,
    /// The line, when known.
    pub line: Option<usize>,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for ProfileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(l) => write!(f, "profile {}, line {l}: {}", self.origin, self.message),
            None => write!(f, "profile {}: {}", self.origin, self.message),
        }
    }
}

impl std::error::Error for ProfileError {}

impl Profile {
    /// The built-in profile `name` ([`BUILTIN`]).
    pub fn builtin(name: &str) -> Option<Profile> {
        let (description, ids): (&str, &[&str]) = match name {
            "all" => ("Every check (the default).", &["*"]),
            "ra33-core" => (
                "The Part 1 core rules: the checks every RA 3.3 component gets, whatever its type.",
                RA33_CORE,
            ),
            "iop" => (
                "The IGVC IOP challenge's AS-4 judge (as --as4).",
                &["as4.*"],
            ),
            _ => return None,
        };
        Some(Profile {
            name: name.to_string(),
            description: description.to_string(),
            checks: ids.iter().map(|id| Pick::of(id)).collect(),
            origin: "built-in".into(),
        })
    }

    /// A profile from the YAML `text` of the file `origin`, each entry with its line.
    pub fn parse(text: &str, origin: &str) -> Result<Profile, ProfileError> {
        let mut p: Profile = serde_yaml::from_str(text).map_err(|e| ProfileError {
            origin: origin.to_string(),
            line: e.location().map(|l| l.line()),
            message: e.to_string(),
        })?;
        p.origin = origin.to_string();
        let at = jaus_spec::location::LocationIndex::build(text);
        for (i, pick) in p.checks.iter_mut().enumerate() {
            pick.line = Some(at.find(&format!("checks[{i}].id")).line);
        }
        Ok(p)
    }

    /// The profile in the file `path`.
    pub fn load(path: &Path) -> Result<Profile, ProfileError> {
        let text = std::fs::read_to_string(path).map_err(|e| ProfileError {
            origin: path.display().to_string(),
            line: None,
            message: format!("cannot read it: {e}"),
        })?;
        Profile::parse(&text, &path.display().to_string())
    }

    /// The built-in profile `name_or_file`, else the profile in that file.
    pub fn named(name_or_file: &str) -> Result<Profile, ProfileError> {
        if let Some(p) = Profile::builtin(name_or_file) {
            return Ok(p);
        }
        let path = Path::new(name_or_file);
        if !path.exists() {
            return Err(ProfileError {
                origin: name_or_file.to_string(),
                line: None,
                message: format!(
                    "no built-in profile of that name ({}) and no such file",
                    BUILTIN.join(", ")
                ),
            });
        }
        Profile::load(path)
    }

    /// The checks of `catalogue` this profile selects; `Err` names the first entry
    /// that selects none, with the closest known id.
    pub fn select(&self, catalogue: &[Entry]) -> Result<Selection, ProfileError> {
        for (i, pick) in self.checks.iter().enumerate() {
            if catalogue.iter().any(|e| pick.matches(&e.id).is_some()) {
                continue;
            }
            let closest = closest(&pick.id, catalogue.iter().map(|e| e.id.as_str()));
            return Err(ProfileError {
                origin: self.origin.clone(),
                line: pick.line,
                message: format!(
                    "entry {} names `{}`, which is no check{}{}",
                    i + 1,
                    pick.id,
                    if pick.id.ends_with('*') {
                        " prefix"
                    } else {
                        ""
                    },
                    closest.map_or(String::new(), |c| format!(" (did you mean `{c}`?)")),
                ),
            });
        }
        let ids = catalogue
            .iter()
            .filter(|e| self.picks(&e.id).next().is_some())
            .map(|e| e.id.clone())
            .collect();
        Ok(Selection {
            name: self.name.clone(),
            description: self.description.clone(),
            picks: self.checks.clone(),
            ids,
        })
    }

    fn picks<'a>(&'a self, id: &'a str) -> impl Iterator<Item = &'a Pick> + 'a {
        self.checks.iter().filter(move |p| p.matches(id).is_some())
    }
}

/// The catalogue id closest to `id` (by edit distance, at most a third of its length
/// away), for an error.
fn closest<'a>(id: &str, known: impl Iterator<Item = &'a str>) -> Option<&'a str> {
    let id = id.trim_end_matches('*');
    known
        .map(|k| (jaus::json::distance(id, k), k))
        .filter(|(d, _)| *d <= id.chars().count().max(3) / 3 + 1)
        .min_by_key(|(d, _)| *d)
        .map(|(_, k)| k)
}

/// [`crate::run`] running only the checks `selection` selects, at its levels; the
/// report names the profile.
pub fn run(
    session: &mut dyn Session,
    spec: &Spec,
    voices: Voices,
    targets: &[jaus::Address],
    opts: Options,
    selection: &Selection,
) -> RunReport {
    crate::ra33::run_selected(session, spec, voices, targets, opts, Some(selection))
}

/// [`crate::as4::run_as4`] reporting the checks `selection` selects, at its levels (the
/// scenario runs whole: its steps prepare the next).
pub fn run_as4(
    session: &mut dyn crate::as4::As4Session,
    opts: &crate::as4::As4Options,
    selection: &Selection,
) -> RunReport {
    crate::as4::run_as4_selected(session, opts, Some(selection))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::Level;

    fn catalogue() -> Vec<Entry> {
        crate::catalogue::catalogue(&jaus_spec::load_sdk().unwrap())
    }

    const VENDOR: &str = "name: acme\ndescription: Acme's checks.\nchecks:\n  - id: core.identification\n  - id: control.*\n    level: advisory\n  - id: control.grant\n  - id: events.every-change\n    level: required\n";

    #[test]
    fn a_file_selects_by_id_and_prefix_with_levels() {
        let p = Profile::parse(VENDOR, "acme.yaml").unwrap();
        assert_eq!(p.name, "acme");
        assert_eq!(p.checks[1].line, Some(5));
        let sel = p.select(&catalogue()).unwrap();
        assert!(sel.selects("core.identification") && sel.selects("control.release"));
        assert!(!sel.selects("core.status") && !sel.selects("as4.control.query"));
        // The prefix makes control.* advisory; the entry naming control.grant gives no
        // level, so the prefix's applies.
        assert_eq!(
            sel.level_of("control.equal", Level::Required),
            Some(Level::Advisory)
        );
        assert_eq!(
            sel.level_of("control.grant", Level::Required),
            Some(Level::Advisory)
        );
        assert_eq!(
            sel.level_of("events.every-change", Level::Advisory),
            Some(Level::Required)
        );
        assert_eq!(
            sel.level_of("core.identification", Level::Required),
            Some(Level::Required)
        );
        assert!(sel.has_ra33() && !sel.has_as4());
        let listed = crate::catalogue::selected(&catalogue(), &sel);
        assert_eq!(listed.len(), sel.ids.len());
        assert!(listed
            .iter()
            .any(|e| e.id == "events.every-change" && e.level == Level::Required));
    }

    #[test]
    fn an_unknown_id_names_the_file_the_line_and_the_closest_id() {
        let text = "name: typo\nchecks:\n  - id: core.status\n  - id: control.grnat\n";
        let err = Profile::parse(text, "typo.yaml")
            .unwrap()
            .select(&catalogue())
            .unwrap_err();
        assert_eq!(err.line, Some(4));
        let msg = err.to_string();
        assert!(
            msg.starts_with("profile typo.yaml, line 4: entry 2"),
            "{msg}"
        );
        assert!(msg.contains("`control.grnat`"), "{msg}");
        assert!(msg.contains("did you mean `control.grant`?"), "{msg}");
        // A prefix that selects nothing is as wrong.
        let err = Profile::parse("name: p\nchecks:\n  - id: nothing.*\n", "p.yaml")
            .unwrap()
            .select(&catalogue())
            .unwrap_err();
        assert!(err.to_string().contains("no check prefix"), "{err}");
    }

    #[test]
    fn bad_yaml_and_unknown_keys_are_errors_with_their_line() {
        let err = Profile::parse(
            "name: p\nchecks:\n  - id: core.status\n    levl: required\n",
            "p.yaml",
        )
        .unwrap_err();
        assert_eq!(err.origin, "p.yaml");
        assert!(err.line.is_some(), "{err}");
        assert!(err.to_string().contains("levl"), "{err}");
        let err = Profile::parse(
            "name: p\nchecks:\n  - id: core.status\n    level: optional\n",
            "p.yaml",
        )
        .unwrap_err();
        assert!(err.to_string().contains("optional"), "{err}");
        let err = Profile::named("no-such-profile").unwrap_err();
        assert!(err.to_string().contains("ra33-core"), "{err}");
    }

    #[test]
    fn the_built_in_profiles() {
        let spec = jaus_spec::load_sdk().unwrap();
        let all = crate::catalogue::catalogue(&spec);
        for name in BUILTIN {
            let sel = Profile::named(name).unwrap().select(&all).unwrap();
            assert!(!sel.ids.is_empty(), "{name}");
        }
        let every = Profile::builtin("all").unwrap().select(&all).unwrap();
        assert_eq!(every.ids.len(), all.len());
        let iop = Profile::builtin("iop").unwrap().select(&all).unwrap();
        assert!(iop.has_as4() && !iop.has_ra33());
        assert_eq!(
            iop.ids.len(),
            all.iter().filter(|e| e.id.starts_with("as4.")).count()
        );
        // ra33-core is what every component gets: the plan of a type the definitions
        // do not know (the id no component has), and the teardown.
        let unknown = (0..=255u8)
            .find(|id| spec.components.iter().all(|c| c.def.id != *id))
            .unwrap();
        let mut core: Vec<String> = crate::plan::plan(&spec, unknown)
            .into_iter()
            .map(|c| c.id)
            .collect();
        core.push("teardown.as-found".into());
        core.sort();
        let mut sel = Profile::builtin("ra33-core")
            .unwrap()
            .select(&all)
            .unwrap()
            .ids;
        sel.sort();
        assert_eq!(sel, core);
    }

    #[test]
    fn closest_ids() {
        assert_eq!(jaus::json::distance("kitten", "sitting"), 3);
        let known = ["control.grant", "core.status"];
        assert_eq!(
            closest("contrl.grant", known.iter().copied()),
            Some("control.grant")
        );
        assert_eq!(closest("zzzzzzzz", known.iter().copied()), None);
    }
}
