//! # jaus-gen — Rust code from JAUS definitions
//!
//! Loads a definition set with [`jaus_spec`], turns every message and named type into a
//! template context, renders the `minijinja` templates of the crate's `templates/`
//! directory (or an override directory), and formats the result with `prettyplease`.
//! The output is deterministic: the same definitions and templates give byte-identical
//! code.
//!
//! In a `build.rs`:
//!
//! ```no_run
//! jaus_gen::Builder::new()
//!     .spec_dir(jaus_spec::defs_dir())
//!     .overlay("my-experimental-messages.yaml")
//!     .out_dir(std::env::var("OUT_DIR").unwrap())
//!     .generate()
//!     .unwrap();
//! ```
//!
//! then `include!(concat!(env!("OUT_DIR"), "/messages.rs"));` in the crate.
//!
//! Generated structs carry `#[derive(JausMessage)]` and field attributes of
//! `jaus-derive`; templates hold no byte-level code.
//!
//! ## Golden files
//!
//! `tests/golden/` holds one tiny definition file per feature of the language (scaled
//! integers, enums, bit fields, presence vectors, lists, records, strings and blobs,
//! unions, embedded messages, flags, offsets, feature gates, queries, runtime roles) and
//! of the component layer (plain, commands/accepts/emits, modes, `any_message`), each
//! with the code it generates next to it. `cargo test -p jaus-gen --test golden`
//! compares them byte for byte and prints a unified diff of any difference, so every
//! template or generator change is a reviewable diff; after reviewing it,
//!
//! ```sh
//! UPDATE_GOLDEN=1 cargo test -p jaus-gen --test golden
//! ```
//!
//! rewrites them. The workspace's `tests/tests/golden_compile.rs` compiles them against
//! the SDK.

mod components;
mod context;
mod docs;

use jaus_spec::{Spec, SpecErrors};
use minijinja::Environment;
use std::path::{Path, PathBuf};

pub use components::{build_components, ComponentCtx};
pub use context::{build_context, Context};
pub use docs::{render_docs, DOC_TEMPLATES};

/// Templates compiled into the generator (from the crate's `templates/` directory).
pub const DEFAULT_TEMPLATES: &[(&str, &str)] = &[
    (
        "messages.rs.j2",
        include_str!("../templates/messages.rs.j2"),
    ),
    ("items.rs.j2", include_str!("../templates/items.rs.j2")),
    (
        "components.rs.j2",
        include_str!("../templates/components.rs.j2"),
    ),
];

/// What can go wrong while generating.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The definitions do not validate.
    #[error("{0}")]
    Spec(#[from] SpecErrors),
    /// A template failed to load or render.
    #[error("template error: {0:#}")]
    Template(#[from] minijinja::Error),
    /// The rendered code is not valid Rust (a template bug); the raw text was written
    /// to `path` for inspection.
    #[error("generated code does not parse ({path}:{line}:{column}): {message}")]
    Syntax {
        /// File holding the unformatted output.
        path: PathBuf,
        /// Line of the error.
        line: usize,
        /// Column of the error.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The error.
        source: std::io::Error,
    },
    /// A required setting is missing.
    #[error("{0}")]
    Config(String),
}

/// Configures and runs generation. The whole `build.rs` API.
#[derive(Debug, Clone, Default)]
pub struct Builder {
    spec_dirs: Vec<PathBuf>,
    overlays: Vec<PathBuf>,
    out_dir: Option<PathBuf>,
    templates_dir: Option<PathBuf>,
    feature_gates: bool,
    cargo: bool,
    runtime: Option<String>,
    serde_cfg: Option<String>,
}

/// What one generation run produced.
#[derive(Debug)]
pub struct Generated {
    /// The formatted Rust source of the messages (`messages.rs`).
    pub code: String,
    /// The formatted Rust source of the component skeletons (`components.rs`), which
    /// needs the `jaus` component runtime.
    pub components: String,
    /// Files written.
    pub files: Vec<PathBuf>,
    /// Number of messages generated.
    pub messages: usize,
    /// Number of named types generated.
    pub types: usize,
    /// Number of component interfaces generated.
    pub component_count: usize,
}

impl Builder {
    /// A builder with no inputs. Emits `cargo:rerun-if-changed` lines when run by cargo
    /// (`OUT_DIR` set).
    pub fn new() -> Self {
        Self {
            cargo: std::env::var_os("CARGO").is_some() && std::env::var_os("OUT_DIR").is_some(),
            ..Self::default()
        }
    }

    /// Adds a directory of `*.yaml` definitions.
    pub fn spec_dir(mut self, dir: impl Into<PathBuf>) -> Self {
        self.spec_dirs.push(dir.into());
        self
    }

    /// Adds one definition file loaded after the directories (extra groups, messages or
    /// types of a vendor).
    pub fn overlay(mut self, file: impl Into<PathBuf>) -> Self {
        self.overlays.push(file.into());
        self
    }

    /// Where to write `messages.rs`.
    pub fn out_dir(mut self, dir: impl Into<PathBuf>) -> Self {
        self.out_dir = Some(dir.into());
        self
    }

    /// Reads templates from this directory instead of the built-in ones (any template
    /// missing there falls back to the built-in one).
    pub fn templates_dir(mut self, dir: impl Into<PathBuf>) -> Self {
        self.templates_dir = Some(dir.into());
        self
    }

    /// Gates every group except `core` behind a cargo feature of the same name.
    pub fn feature_gates(mut self, on: bool) -> Self {
        self.feature_gates = on;
        self
    }

    /// Path of the SDK runtime in generated code: `::jaus` (the default, for a vendor's
    /// crate depending on the SDK) or `crate` (inside the SDK itself).
    pub fn runtime_path(mut self, path: impl Into<String>) -> Self {
        self.runtime = Some(path.into());
        self
    }

    /// The `cfg` condition under which generated types derive serde's traits:
    /// `feature = "serde"` (the SDK's choice), `all()` (always) or `any()` (never, the
    /// default, so a vendor crate needs no serde dependency).
    pub fn serde_cfg(mut self, cfg: impl Into<String>) -> Self {
        self.serde_cfg = Some(cfg.into());
        self
    }

    /// Turns `cargo:rerun-if-changed` output on or off.
    pub fn emit_rerun_if_changed(mut self, on: bool) -> Self {
        self.cargo = on;
        self
    }

    /// Loads and validates the definitions.
    pub fn load(&self) -> Result<Spec, Error> {
        if self.cargo {
            for d in &self.spec_dirs {
                println!("cargo:rerun-if-changed={}", d.display());
            }
        }
        let spec = jaus_spec::load(&self.spec_dirs, &self.overlays)?;
        if self.cargo {
            for p in spec.source_paths() {
                println!("cargo:rerun-if-changed={}", p.display());
            }
        }
        Ok(spec)
    }

    /// Renders the code without writing it.
    pub fn render(&self) -> Result<Generated, Error> {
        let spec = self.load()?;
        let rt = self.runtime.as_deref().unwrap_or("::jaus");
        let ctx = build_context(&spec, self.feature_gates, rt);
        let mut env = self.environment()?;
        env.add_global("rt", rt);
        env.add_global("serde_cfg", self.serde_cfg.as_deref().unwrap_or("any()"));
        let raw = env.get_template("messages.rs.j2")?.render(&ctx)?;
        let code = format_code(&raw, self.out_dir.as_deref(), "messages")?;
        let comps = build_components(&spec, self.feature_gates);
        let raw = env
            .get_template("components.rs.j2")?
            .render(minijinja::context! { components => &comps })?;
        let components = format_code(&raw, self.out_dir.as_deref(), "components")?;
        Ok(Generated {
            code,
            components,
            files: Vec::new(),
            messages: spec.messages.len(),
            types: spec.types.len(),
            component_count: comps.len(),
        })
    }

    /// Renders and writes `OUT/messages.rs` (only if its content changed, so that
    /// cargo does not rebuild needlessly).
    pub fn generate(&self) -> Result<Generated, Error> {
        let out = self
            .out_dir
            .clone()
            .ok_or_else(|| Error::Config("no output directory: call out_dir()".into()))?;
        let mut g = self.render()?;
        std::fs::create_dir_all(&out).map_err(|source| Error::Io {
            path: out.clone(),
            source,
        })?;
        let path = out.join("messages.rs");
        write_if_changed(&path, &g.code)?;
        g.files.push(path);
        let path = out.join("components.rs");
        write_if_changed(&path, &g.components)?;
        g.files.push(path);
        Ok(g)
    }

    fn environment(&self) -> Result<Environment<'static>, Error> {
        let mut env = Environment::new();
        env.set_trim_blocks(true);
        env.set_lstrip_blocks(true);
        env.set_keep_trailing_newline(true);
        env.set_undefined_behavior(minijinja::UndefinedBehavior::Strict);
        for (name, text) in DEFAULT_TEMPLATES {
            let text = match &self.templates_dir {
                Some(dir) => {
                    let p = dir.join(name);
                    if self.cargo {
                        println!("cargo:rerun-if-changed={}", p.display());
                    }
                    match std::fs::read_to_string(&p) {
                        Ok(t) => t,
                        Err(_) => (*text).to_string(),
                    }
                }
                None => (*text).to_string(),
            };
            env.add_template_owned(name.to_string(), text)?;
        }
        Ok(env)
    }
}

/// Writes `text` to `path` unless the file already holds exactly that.
pub fn write_if_changed(path: &Path, text: &str) -> Result<(), Error> {
    if std::fs::read_to_string(path).is_ok_and(|old| old == text) {
        return Ok(());
    }
    std::fs::write(path, text).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Parses and pretty-prints generated code. On a syntax error the raw text is written
/// next to the output (`NAME.unformatted.rs`) and the error points into it.
pub fn format_code(raw: &str, out_dir: Option<&Path>, name: &str) -> Result<String, Error> {
    match syn::parse_file(raw) {
        Ok(file) => Ok(prettyplease::unparse(&file)),
        Err(e) => {
            let dir = out_dir
                .map(Path::to_path_buf)
                .unwrap_or_else(std::env::temp_dir);
            let path = dir.join(format!("{name}.unformatted.rs"));
            let _ = std::fs::create_dir_all(&dir);
            let _ = std::fs::write(&path, raw);
            let start = e.span().start();
            Err(Error::Syntax {
                path,
                line: start.line,
                column: start.column + 1,
                message: e.to_string(),
            })
        }
    }
}
