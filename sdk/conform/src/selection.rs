//! What a conformance profile selects, checked against the catalogue: the checks by id
//! or prefix and the level each is reported at. The engine plans with it; profile files
//! ([`crate::profile`]) are read into it.

use serde::Deserialize;

use crate::check::Level;

/// One entry of a profile.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pick {
    /// A check id, or a prefix of ids ending with `*`.
    pub id: String,
    /// The level the checks it selects are reported at, instead of their own.
    #[serde(default)]
    pub level: Option<LevelName>,
    /// The entry's line in its file (1-based), when read from one.
    #[serde(skip)]
    pub line: Option<usize>,
}

/// A level as a profile file spells it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LevelName {
    /// [`Level::Required`].
    Required,
    /// [`Level::Advisory`].
    Advisory,
}

impl From<LevelName> for Level {
    fn from(l: LevelName) -> Level {
        match l {
            LevelName::Required => Level::Required,
            LevelName::Advisory => Level::Advisory,
        }
    }
}

impl Pick {
    pub(crate) fn of(id: &str) -> Pick {
        Pick {
            id: id.to_string(),
            level: None,
            line: None,
        }
    }

    /// How specifically this entry selects `id`: `None` when it does not; an exact id
    /// beats any prefix, a longer prefix a shorter one.
    pub(crate) fn matches(&self, id: &str) -> Option<usize> {
        match self.id.strip_suffix('*') {
            Some(prefix) => id.starts_with(prefix).then_some(prefix.len()),
            None => (self.id == id).then_some(usize::MAX),
        }
    }
}

/// A profile checked against the catalogue: what a run plans and reports.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Selection {
    /// The profile's name.
    pub name: String,
    /// What it is for.
    pub description: String,
    pub(crate) picks: Vec<Pick>,
    /// The catalogue ids selected, in catalogue order.
    pub ids: Vec<String>,
}

impl Selection {
    /// `None` when the check `id` is not selected; else its level: the one of the most
    /// specific entry giving one, or `own`.
    pub fn level_of(&self, id: &str, own: Level) -> Option<Level> {
        let mut matching: Vec<(usize, usize, &Pick)> = self
            .picks
            .iter()
            .enumerate()
            .filter_map(|(i, p)| p.matches(id).map(|m| (m, i, p)))
            .collect();
        if matching.is_empty() {
            return None;
        }
        // Most specific first; among equals, the later entry.
        matching.sort_by_key(|&(specific, index, _)| std::cmp::Reverse((specific, index)));
        Some(
            matching
                .iter()
                .find_map(|(_, _, p)| p.level)
                .map_or(own, Level::from),
        )
    }

    /// Whether the check `id` is selected.
    pub fn selects(&self, id: &str) -> bool {
        self.level_of(id, Level::Advisory).is_some()
    }

    /// Whether it selects an AS-4 judge's check.
    pub fn has_as4(&self) -> bool {
        self.ids.iter().any(|id| id.starts_with("as4."))
    }

    /// Whether it selects an RA 3.3 check.
    pub fn has_ra33(&self) -> bool {
        self.ids.iter().any(|id| !id.starts_with("as4."))
    }
}
