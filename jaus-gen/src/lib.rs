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
//! The SDK's own `build.rs` also writes the runtime types that jaus-spec's lists
//! define ([`runtime`]: `jaus::component::Hardware`), so that each lives in one place.
//!
//! SAE AS-4 definitions in JSIDL are imported first, with [`Builder::jsidl`] (or
//! `jaus-gen jsidl DIR… --out DIR` once, keeping the YAML): see `jaus_jsidl` and
//! docs/as4.md.
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
//!
//! ## Spec revisions: diff and lock file
//!
//! [`diff::diff`] compares two revisions of a definition set, each reduced to its wire
//! layout ([`snapshot::Snapshot`], from a loaded [`Spec`] or from a lock file), and
//! classifies every change on a three-level scale ([`diff::Severity`]):
//!
//! * `compatible`: peers of either revision interoperate, and vendor code written in the
//!   forward-compatible style still compiles: struct literals and patterns of generated
//!   types end with `..` (`..Default::default()`), a `match` on a generated enum or on
//!   `Message` has a `_` arm (a message, enum value or component added; a field added at
//!   the end of a message under a new presence bit; bits added in unused bits; a unit
//!   changed, flagged);
//! * `source-breaking`: the same bytes, but code written against the old revision may no
//!   longer compile (a message, field, type, member, variant, component or mode renamed;
//!   modes and transitions changed; a message no longer emitted);
//! * `wire-breaking`: peers of the two revisions may misread, reject or not serve each
//!   other (a message removed or recoded; a field removed, moved, retyped, rescaled,
//!   re-bitted or added elsewhere; an enum value removed, renumbered or reused; bits
//!   moved; a union variant added or changed; an accepted message removed).
//!
//! Each [`diff::Change`] carries the positions on both sides, and a change inside a
//! shared type is reported once, at the type, with the messages using it. The whole rule
//! set, the dependency of the compatible field addition on the forward-compatibility
//! rule of the decoders, and the output formats are in `docs/spec-revisions.md` of the
//! repository. `jaus-gen diff OLD NEW` (feature `cli`) prints them as text or JSON and
//! exits 0, 1 (something wire-breaking, or as severe as `--fail-on`) or 2 (a usage or
//! load error); a revision is a directory, files, a git `REV:PATH` ([`revision`]), a
//! lock file or a directory of JSIDL.
//!
//! Services (AS-4) are compared too: services added or removed, their versions and
//! parents, the states and transitions of their machines (trigger, guard, actions,
//! target), and the guard and action methods of their generated traits (a new one breaks
//! a vendor's `impl`: source-breaking). Positions are in the files the vendor edits: the
//! `.xml` files for a set imported from JSIDL ([`snapshot::JsidlPositions`]).
//!
//! [`Builder::lock`] pins the layout in a committed lock file ([`lock`]). Until the
//! vendor pins it (`JAUS_UPDATE_LOCK=1 cargo build` or `jaus-gen lock`, when the
//! definitions are ready for peers) nothing is checked and the build says how to pin;
//! once pinned it is checked on every build, and any difference fails the build with the
//! classified changes and the command that updates it after review,
//! `JAUS_UPDATE_LOCK=1 cargo build`:
//!
//! ```no_run
//! jaus_gen::Builder::new()
//!     .overlay("vendor/acme.yaml")
//!     .lock("vendor/acme.lock")
//!     .out_dir(std::env::var("OUT_DIR").unwrap())
//!     .generate()
//!     .unwrap();
//! ```

mod components;
mod context;
pub mod diff;
mod docs;
mod error;
pub mod lock;
mod output;
pub mod revision;
pub mod runtime;
pub mod scaffold;
mod services;
pub mod snapshot;
pub mod wireshark;

use jaus_spec::Spec;
use minijinja::Environment;
use std::path::{Path, PathBuf};

pub use components::{build_components, build_parts, ComponentCtx, PartCtx, PartRef};
pub use context::{build_context, Context};
pub use docs::{render_docs, DOC_TEMPLATES};
pub use error::Error;
pub use output::{format_code, write_if_changed};
pub use services::{build_services, ServicesCtx};

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
    (
        "services.rs.j2",
        include_str!("../templates/services.rs.j2"),
    ),
];

/// The directory name under which YAML imported from JSIDL is loaded (it is never
/// written there).
const JSIDL_ROOT: &str = "jsidl";

/// Configures and runs generation. The whole `build.rs` API.
#[derive(Debug, Clone, Default)]
pub struct Builder {
    spec_dirs: Vec<PathBuf>,
    overlays: Vec<PathBuf>,
    jsidl_dirs: Vec<PathBuf>,
    out_dir: Option<PathBuf>,
    templates_dir: Option<PathBuf>,
    feature_gates: bool,
    cargo: bool,
    runtime: Option<String>,
    serde_cfg: Option<String>,
    lock: Option<PathBuf>,
    update_lock: Option<bool>,
    base: Option<Base>,
    delegate: Option<String>,
    host: Option<String>,
}

/// Base definitions other than the SDK's that a vendor's set extends
/// ([`Builder::base`]).
#[derive(Debug, Clone, Default)]
struct Base {
    /// The name the vendor's files say in `extends:` (`as4`).
    name: String,
    /// The directory of the base's YAML files.
    dir: PathBuf,
    /// The Rust path of the crate generated from them (`::jaus_as4`): its `messages`
    /// module holds the base's items and `messages::services` its services.
    path: String,
}

/// What one generation run produced.
#[derive(Debug)]
pub struct Generated {
    /// The formatted Rust source of the messages (`messages.rs`).
    pub code: String,
    /// The formatted Rust source of the component skeletons (`components.rs`), which
    /// needs the `jaus` component runtime.
    pub components: String,
    /// The formatted Rust source of the services (`services.rs`: a trait, triggers and
    /// state tables per service of the definitions' `services:`), empty without
    /// services; it needs the `jaus::hsm` engine.
    pub services: String,
    /// Number of services generated.
    pub service_count: usize,
    /// Files written.
    pub files: Vec<PathBuf>,
    /// Number of messages generated.
    pub messages: usize,
    /// Number of named types generated.
    pub types: usize,
    /// Number of component interfaces generated.
    pub component_count: usize,
    /// What the lock file check of [`Builder::lock`] found.
    pub lock: LockState,
}

/// What [`Builder::check_lock`] found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LockState {
    /// No lock file configured.
    Off,
    /// The lock file does not exist: the layout is not pinned yet and nothing is
    /// checked, so a new crate's definitions can be edited freely. Under cargo the build
    /// prints how to pin it ([`lock::unpinned_note`]).
    Unpinned,
    /// The definitions have the layout of the lock file.
    Matches,
    /// The lock file was written: pinned ([`Builder::update_lock`] on a missing file) or
    /// updated after a reviewed change.
    Written,
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
    /// types of a vendor). Without [`spec_dir`](Self::spec_dir), overlays extend the
    /// SDK's own definitions (unless one says `extends: none`): they may use every SDK
    /// type and message, and only their own items are generated, referring to the
    /// SDK's through `::jaus::messages` (see `jaus_spec::load_overlays`).
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

    /// Checks the definitions' wire layout against the lock file at `path` (relative to
    /// the crate's directory in a build script), as Cargo.lock pins dependencies:
    ///
    /// * no file: the layout is not pinned yet, and nothing is checked (a new crate's
    ///   definitions change freely); under cargo the build warns, naming the command that
    ///   pins it when the definitions are ready for peers, `JAUS_UPDATE_LOCK=1 cargo
    ///   build` (or `jaus-gen lock`): commit the file it writes;
    /// * the same layout: nothing happens;
    /// * any difference: [`Builder::render`] and [`Builder::generate`] fail with
    ///   [`Error::Lock`], which lists every change classified as by `jaus-gen diff` (old:
    ///   the lock file's lines, new: the YAML's) and the command that updates the file
    ///   after review, `JAUS_UPDATE_LOCK=1 cargo build` ([`Builder::update_lock`]).
    ///
    /// Every difference fails, compatible ones included: the build never rewrites a
    /// committed file behind the vendor's back, so the lock always holds the layout the
    /// crate was built from and every wire change shows up as a reviewed diff of it.
    /// Under cargo the lock file and `JAUS_UPDATE_LOCK` are watched
    /// (`cargo:rerun-if-changed`, `cargo:rerun-if-env-changed`).
    pub fn lock(mut self, path: impl Into<PathBuf>) -> Self {
        self.lock = Some(path.into());
        self
    }

    /// Rewrites the lock file when the layout differs instead of failing (the changes
    /// are printed as `cargo:warning`s under cargo). Default: on when the environment
    /// variable `JAUS_UPDATE_LOCK` is set to anything but `0` or nothing.
    pub fn update_lock(mut self, on: bool) -> Self {
        self.update_lock = Some(on);
        self
    }

    /// Turns `cargo:rerun-if-changed` output on or off.
    pub fn emit_rerun_if_changed(mut self, on: bool) -> Self {
        self.cargo = on;
        self
    }

    /// Builds the definitions of [`spec_dir`](Self::spec_dir) (which say `extends:
    /// NAME`) on other base definitions than the SDK's: the YAML files of `dir`, whose
    /// generated code is the crate at Rust path `path`. For a vendor's AS-4 services on
    /// jaus-as4, from the vendor's build script (jaus-as4 tells where its definitions
    /// are, `links` metadata):
    ///
    /// ```no_run
    /// let defs = std::env::var("DEP_JAUS_AS4_DEFS").expect("jaus-as4 is a dependency");
    /// jaus_gen::Builder::new()
    ///     .spec_dir("defs")
    ///     .base("as4", defs, "::jaus_as4")
    ///     .out_dir(std::env::var("OUT_DIR").unwrap())
    ///     .generate()
    ///     .unwrap();
    /// ```
    ///
    /// Only the set's own items are generated; the base's messages and types are used
    /// from `PATH::messages`, a service inheriting one of the base's services
    /// (`urn:jaus:jss:core:AccessControl`) gets its machines and runs its inherited
    /// guards and actions on the base's implementation (`PATH::messages::services`).
    pub fn base(
        mut self,
        name: impl Into<String>,
        dir: impl Into<PathBuf>,
        path: impl Into<String>,
    ) -> Self {
        self.base = Some(Base {
            name: name.into(),
            dir: dir.into(),
            path: path.into(),
        });
        self
    }

    /// Services of the set whose ids start with `id_prefix` (`urn:jaus:jss:core:`) are
    /// inherited by delegation, as a base's are ([`Builder::base`]): a service of the
    /// set inheriting one of them gets the merged machines, its trait declares only its
    /// own guards and actions, and its `Machines` take a second implementation for the
    /// inherited ones. One implementation of the delegated services (a component's Core)
    /// then serves every service built on them, each service implemented apart.
    pub fn delegate_inherited(mut self, id_prefix: impl Into<String>) -> Self {
        self.delegate = Some(id_prefix.into());
        self
    }

    /// The generated services are hosted by the crate at `path` (`crate`: jaus-as4
    /// generating its own sets), which has the AS-4 component runtime
    /// (`service::GeneratedService`, `core::machine::Host`): each service built on a
    /// delegated one ([`delegate_inherited`](Self::delegate_inherited)) then gets a
    /// `Hosted<S>` adapter, as a vendor's service on a base does, so its implementation
    /// holds only the service's own guards and actions.
    pub fn hosted_by(mut self, path: impl Into<String>) -> Self {
        self.host = Some(path.into());
        self
    }

    /// Adds a directory of JSIDL (AS5684) files (read recursively) to import instead of
    /// YAML: each directory is one group, and the imported definitions stand alone
    /// (`extends: none`; overlays given with [`overlay`](Self::overlay) are loaded with
    /// them). Cannot be combined with [`spec_dir`](Self::spec_dir). See `jaus_jsidl`.
    pub fn jsidl(mut self, dir: impl Into<PathBuf>) -> Self {
        self.jsidl_dirs.push(dir.into());
        self
    }

    /// The definitions imported from JSIDL, with the overlays.
    fn load_jsidl(&self) -> Result<Spec, Error> {
        if !self.spec_dirs.is_empty() {
            return Err(Error::Config(
                "jsidl() and spec_dir() cannot be combined: an imported set stands alone".into(),
            ));
        }
        if self.cargo {
            for d in &self.jsidl_dirs {
                println!("cargo:rerun-if-changed={}", d.display());
            }
        }
        let import = jaus_jsidl::import(&self.jsidl_dirs)?;
        let mut texts = import.texts(Path::new(JSIDL_ROOT));
        for o in &self.overlays {
            let text = std::fs::read_to_string(o).map_err(|source| Error::Io {
                path: o.clone(),
                source,
            })?;
            texts.push((o.clone(), text));
        }
        Ok(jaus_spec::load_texts(texts)?)
    }

    /// The layout of `spec` for the lock file, positions in the files the vendor edits:
    /// the JSIDL files for definitions imported with [`jsidl`](Self::jsidl) (their YAML
    /// exists in memory only), the YAML files otherwise.
    fn snapshot(&self, spec: &Spec) -> Result<snapshot::Snapshot, Error> {
        if self.jsidl_dirs.is_empty() {
            return Ok(snapshot::Snapshot::from_spec(spec));
        }
        let import = jaus_jsidl::import(&self.jsidl_dirs)?;
        let origins: Vec<(PathBuf, PathBuf)> = import
            .files
            .iter()
            .map(|f| (Path::new(JSIDL_ROOT).join(&f.name), f.source.clone()))
            .collect();
        let at = snapshot::JsidlPositions::new(spec, &origins)?;
        Ok(snapshot::Snapshot::from_jsidl(spec, &at))
    }

    /// The set of [`spec_dir`](Self::spec_dir) and the overlays on [`Builder::base`].
    fn load_on(&self, base: &Base) -> Result<Spec, Error> {
        let read_dir = |dir: &Path| -> Result<Vec<(PathBuf, String)>, Error> {
            let io = |source| Error::Io {
                path: dir.to_path_buf(),
                source,
            };
            let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
                .map_err(io)?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "yaml" || x == "yml"))
                .collect();
            files.sort();
            files
                .into_iter()
                .map(|f| {
                    let text = std::fs::read_to_string(&f).map_err(|source| Error::Io {
                        path: f.clone(),
                        source,
                    })?;
                    Ok((f, text))
                })
                .collect()
        };
        let base_texts = read_dir(&base.dir)?;
        let mut own = Vec::new();
        for d in &self.spec_dirs {
            own.extend(read_dir(d)?);
        }
        for o in &self.overlays {
            let text = std::fs::read_to_string(o).map_err(|source| Error::Io {
                path: o.clone(),
                source,
            })?;
            own.push((o.clone(), text));
        }
        Ok(jaus_spec::load_overlay_texts_on(
            &base.name, base_texts, own,
        )?)
    }

    /// Loads and validates the definitions.
    pub fn load(&self) -> Result<Spec, Error> {
        if !self.jsidl_dirs.is_empty() {
            return self.load_jsidl();
        }
        if self.cargo {
            for d in &self.spec_dirs {
                println!("cargo:rerun-if-changed={}", d.display());
            }
        }
        let spec = if let Some(base) = &self.base {
            self.load_on(base)?
        } else if self.spec_dirs.is_empty() {
            jaus_spec::load_overlays(&self.overlays)?
        } else {
            jaus_spec::load(&self.spec_dirs, &self.overlays)?
        };
        if self.cargo {
            for p in spec.source_paths() {
                println!("cargo:rerun-if-changed={}", p.display());
            }
            for w in &spec.warnings {
                println!("cargo:warning=warning: {w}");
            }
        }
        Ok(spec)
    }

    /// Checks (or pins, or updates) the lock file of [`Builder::lock`] against `spec`;
    /// [`LockState::Off`] without one. [`Builder::render`] calls it.
    pub fn check_lock(&self, spec: &Spec) -> Result<LockState, Error> {
        let Some(path) = &self.lock else {
            return Ok(LockState::Off);
        };
        let exists = path.exists();
        if self.cargo {
            // A missing file would rerun the build script at every build: until the lock
            // is pinned, its directory is watched instead (pinning adds a file to it).
            let watched = match path.parent() {
                Some(dir) if !exists && !dir.as_os_str().is_empty() => dir,
                _ => path.as_path(),
            };
            println!("cargo:rerun-if-changed={}", watched.display());
            println!("cargo:rerun-if-env-changed={}", lock::UPDATE_ENV);
        }
        let update = self.update_lock.unwrap_or_else(|| {
            std::env::var(lock::UPDATE_ENV).is_ok_and(|v| !v.is_empty() && v != "0")
        });
        let snap = self.snapshot(spec)?;
        let text = lock::to_text(&snap);
        let io = |source| Error::Io {
            path: path.clone(),
            source,
        };
        let old_text = match std::fs::read_to_string(path) {
            Ok(t) => t,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                if update {
                    write_if_changed(path, &text)?;
                    if self.cargo {
                        println!("cargo:warning={}: pinned; commit it", path.display());
                    }
                    return Ok(LockState::Written);
                }
                if self.cargo {
                    for line in lock::unpinned_note(path).lines() {
                        println!("cargo:warning={line}");
                    }
                }
                return Ok(LockState::Unpinned);
            }
            Err(e) => return Err(io(e)),
        };
        if old_text == text {
            return Ok(LockState::Matches);
        }
        let name = snapshot::label(path);
        let old = match lock::parse(&old_text, &name) {
            Ok(old) => old,
            Err(_) if update => {
                write_if_changed(path, &text)?;
                return Ok(LockState::Written);
            }
            Err(e) => {
                return Err(Error::Lock(format!(
                    "{e}\nrewrite the lock file from the definitions with: {}",
                    lock::UPDATE_COMMAND
                )))
            }
        };
        let changes = diff::diff(&old, &snap);
        if changes.changes.is_empty() && lock::to_text(&old) == text {
            // Only the file's formatting or comments differ: the layout is the same.
            return Ok(LockState::Matches);
        }
        if update {
            if self.cargo {
                for c in changes.to_text().lines().filter(|l| !l.is_empty()) {
                    println!("cargo:warning={}: {c}", path.display());
                }
            }
            write_if_changed(path, &text)?;
            return Ok(LockState::Written);
        }
        let listing = if changes.changes.is_empty() {
            "(the lock file holds a layout this version of jaus-gen does not classify)\n"
                .to_string()
        } else {
            changes.to_text()
        };
        Err(Error::Lock(format!(
            "{}: the wire layout of the definitions differs from the lock file \
             (old: the lock file, new: the definitions):\n\n{listing}\n\
             If these changes are intended, update the lock file and commit it:\n    {}",
            path.display(),
            lock::UPDATE_COMMAND
        )))
    }

    /// Renders the code without writing it.
    pub fn render(&self) -> Result<Generated, Error> {
        let spec = self.load()?;
        let lock = self.check_lock(&spec)?;
        let rt = self.runtime.as_deref().unwrap_or("::jaus");
        let mut ctx = build_context(&spec, self.feature_gates, rt);
        let base = match &self.base {
            Some(b) => {
                // The SDK's feature groups are a question for sets on the SDK's own.
                ctx.requires.clear();
                format!("{}::messages", b.path)
            }
            None => format!("{rt}::messages"),
        };
        let mut env = self.environment()?;
        env.add_global("rt", rt);
        env.add_global("base", base.clone());
        // A set on other base definitions than the SDK's is no RA 3.3 message set (the
        // component runtime's `MessageSet` wraps the SDK's messages).
        env.add_global("on_base", self.base.is_some());
        env.add_global("serde_cfg", self.serde_cfg.as_deref().unwrap_or("any()"));
        let raw = env.get_template("messages.rs.j2")?.render(&ctx)?;
        let code = format_code(&raw, self.out_dir.as_deref(), "messages")?;
        let comps = build_components(&spec, self.feature_gates);
        let raw = env
            .get_template("components.rs.j2")?
            .render(minijinja::context! {
                components => &comps,
                parts => build_parts(&spec, self.feature_gates),
                vendor => ctx.vendor,
                own_messages => spec
                    .messages
                    .iter()
                    .filter(|m| spec.is_own(m.source))
                    .map(|m| m.def.name.as_str())
                    .collect::<Vec<_>>(),
            })?;
        let components = format_code(&raw, self.out_dir.as_deref(), "components")?;
        let (services, service_count) = if spec.services.is_empty() {
            (String::new(), 0)
        } else {
            let on = self.base.as_ref().map(|_| base.as_str());
            let ctx = build_services(&spec, on, self.delegate.as_deref(), self.host.as_deref())
                .map_err(Error::Services)?;
            let raw = env.get_template("services.rs.j2")?.render(&ctx)?;
            (
                format_code(&raw, self.out_dir.as_deref(), "services")?,
                ctx.services.len(),
            )
        };
        Ok(Generated {
            code,
            components,
            services,
            service_count,
            files: Vec::new(),
            messages: spec.messages.len(),
            types: spec.types.len(),
            component_count: comps.len(),
            lock,
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
        if g.service_count > 0 {
            let path = out.join("services.rs");
            write_if_changed(&path, &g.services)?;
            g.files.push(path);
        }
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
