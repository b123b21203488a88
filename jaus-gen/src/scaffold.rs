//! `jaus-gen new`: writes a vendor crate that builds on the SDK, ready to build, test and
//! run: `Cargo.toml` (the SDK and the generator), `build.rs` (generation and the lock
//! file), `defs/NAME.yaml` (experimental messages with their classes and a component
//! with modes, extending the SDK's definitions), `src/lib.rs` (the component's
//! implementation and a node hosting it beside the SDK's stock Global Pose Sensor),
//! `src/main.rs` (that node on UDP) and `tests/bus.rs` (a test on the in-process bus).
//!
//! `jaus-gen new --as4` writes an AS-4 crate instead: `defs/NAME.yaml` (`extends: as4`:
//! vendor messages and a service inheriting Access Control), `build.rs` (generation on
//! jaus-as4's definitions), `src/lib.rs` (the service's own guards and actions, a
//! component and a UDP node hosting it), `src/main.rs` and `tests/udp.rs` (an AS-4
//! client takes control and drives the service over UDP).

use std::path::{Path, PathBuf};

use minijinja::Environment;

use crate::error::Error;

/// The files of a new crate: (path in the crate, template name, template text).
const FILES: &[(&str, &str, &str)] = &[
    (
        "Cargo.toml",
        "Cargo.toml.j2",
        include_str!("../templates/new/Cargo.toml.j2"),
    ),
    (
        "build.rs",
        "build.rs.j2",
        include_str!("../templates/new/build.rs.j2"),
    ),
    (
        "defs/{snake}.yaml",
        "defs.yaml.j2",
        include_str!("../templates/new/defs.yaml.j2"),
    ),
    (
        "src/lib.rs",
        "lib.rs.j2",
        include_str!("../templates/new/lib.rs.j2"),
    ),
    (
        "src/main.rs",
        "main.rs.j2",
        include_str!("../templates/new/main.rs.j2"),
    ),
    (
        "tests/bus.rs",
        "test.rs.j2",
        include_str!("../templates/new/test.rs.j2"),
    ),
];

/// The files of a new AS-4 crate (`jaus-gen new --as4`): (path, template name, text).
const FILES_AS4: &[(&str, &str, &str)] = &[
    (
        "Cargo.toml",
        "as4/Cargo.toml.j2",
        include_str!("../templates/new-as4/Cargo.toml.j2"),
    ),
    (
        "build.rs",
        "as4/build.rs.j2",
        include_str!("../templates/new-as4/build.rs.j2"),
    ),
    (
        "defs/{snake}.yaml",
        "as4/defs.yaml.j2",
        include_str!("../templates/new-as4/defs.yaml.j2"),
    ),
    (
        "src/lib.rs",
        "as4/lib.rs.j2",
        include_str!("../templates/new-as4/lib.rs.j2"),
    ),
    (
        "src/main.rs",
        "as4/main.rs.j2",
        include_str!("../templates/new-as4/main.rs.j2"),
    ),
    (
        "tests/udp.rs",
        "as4/test.rs.j2",
        include_str!("../templates/new-as4/test.rs.j2"),
    ),
];

/// Where the new crate takes the SDK from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Sdk {
    /// A published version of `jaus` and `jaus-gen`.
    Version(String),
    /// A checkout of this workspace (`DIR/sdk` and `DIR/jaus-gen`), as a path
    /// relative to the new crate or absolute.
    Path(PathBuf),
}

/// A crate to write.
#[derive(Debug, Clone)]
pub struct NewCrate {
    /// Crate name (`vendor-rover`): lowercase letters, digits, `-` and `_`.
    pub name: String,
    /// Where the SDK comes from.
    pub sdk: Sdk,
    /// Add an empty `[workspace]` table so that the crate builds on its own inside
    /// another workspace's directory tree (off for a member of a workspace).
    pub standalone: bool,
    /// An AS-4 crate: a service of its own on jaus-as4's definitions (`extends: as4`,
    /// inheriting Access Control), hosted on an AS-4 component, tested over UDP with an
    /// AS-4 client; instead of RA 3.3 messages and a component.
    pub as4: bool,
}

impl NewCrate {
    /// A standalone crate named `name` on this version of the SDK.
    pub fn new(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            sdk: Sdk::Version(env!("CARGO_PKG_VERSION").to_string()),
            standalone: true,
            as4: false,
        }
    }

    /// The files, rendered: (path in the crate, content).
    pub fn render(&self) -> Result<Vec<(PathBuf, String)>, Error> {
        let n = &self.name;
        let valid = n.chars().next().is_some_and(|c| c.is_ascii_lowercase())
            && n.chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-' || c == '_');
        if !valid {
            return Err(Error::Config(format!(
                "`{n}` is not a crate name for `jaus-gen new`: start with a lowercase letter, then lowercase letters, digits, `-` or `_`"
            )));
        }
        let snake = n.replace('-', "_");
        let title = snake
            .split('_')
            .filter(|w| !w.is_empty())
            .map(|w| {
                let mut c = w.chars();
                c.next()
                    .map(|f| f.to_ascii_uppercase().to_string() + c.as_str())
                    .unwrap_or_default()
            })
            .collect::<Vec<_>>()
            .join(" ");
        let (jaus_dep, gen_dep, as4_dep) = match &self.sdk {
            Sdk::Version(v) => (
                format!("version = \"{v}\""),
                format!("version = \"{v}\""),
                format!("version = \"{v}\""),
            ),
            Sdk::Path(p) => {
                let p = p.to_string_lossy().replace('\\', "/");
                (
                    format!("path = \"{p}/sdk/jaus\""),
                    format!("path = \"{p}/jaus-gen\""),
                    format!("path = \"{p}/sdk/as4\""),
                )
            }
        };
        let files = if self.as4 { FILES_AS4 } else { FILES };
        let mut env = Environment::new();
        env.set_keep_trailing_newline(true);
        for (_, name, text) in files {
            env.add_template(name, text)?;
        }
        let ctx = minijinja::context! {
            name => n, snake => &snake, title => &title, jaus_dep => jaus_dep,
            gen_dep => gen_dep, as4_dep => as4_dep, standalone => self.standalone,
        };
        files
            .iter()
            .map(|(path, name, _)| {
                let text = env.get_template(name)?.render(&ctx)?;
                Ok((PathBuf::from(path.replace("{snake}", &snake)), text))
            })
            .collect()
    }

    /// Writes the crate into `dir` (created; existing files are not overwritten: an
    /// error names the first one).
    pub fn write(&self, dir: &Path) -> Result<Vec<PathBuf>, Error> {
        let files = self.render()?;
        for (p, _) in &files {
            let path = dir.join(p);
            if path.exists() {
                return Err(Error::Config(format!(
                    "{} exists: `jaus-gen new` writes only into a new crate",
                    path.display()
                )));
            }
        }
        let mut written = Vec::new();
        for (p, text) in files {
            let path = dir.join(p);
            if let Some(parent) = path.parent() {
                std::fs::create_dir_all(parent).map_err(|source| Error::Io {
                    path: parent.to_path_buf(),
                    source,
                })?;
            }
            std::fs::write(&path, text).map_err(|source| Error::Io {
                path: path.clone(),
                source,
            })?;
            written.push(path);
        }
        Ok(written)
    }
}
