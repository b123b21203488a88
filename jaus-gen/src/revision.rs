//! One side of a diff: a revision of a definition set, named on the command line.
//!
//! | argument | revision |
//! |---|---|
//! | `DIR` | every `*.yaml` of the directory, in name order (like [`jaus_spec::load_dirs`]) |
//! | `FILE.yaml` | that file |
//! | `A,B,...` | the directories and files in that order (a definition set and a vendor overlay: `jaus-spec/defs,acme.yaml`) |
//! | `REV:PATH` | the directory or file `PATH` at git revision `REV` (`HEAD~1:jaus-spec/defs`), read with `git ls-tree` and `git cat-file` in the current directory's repository; `PATH` is from the repository root, or `./…` from the current directory, as git reads it |
//! | `FILE.lock` or `REV:FILE.lock` | the layout stored in a lock file ([`crate::lock`]) |
//! | `DIR` of JSIDL | a directory holding JSIDL `*.xml` files (recursively) and no `*.yaml`, or any directory with `--jsidl` ([`load_with`]): imported as `jaus-gen jsidl` imports it; several (`core-v1.1,manipulator-v2.0`) resolve references across each other; YAML files named with them are overlays on the import; positions are in the `.xml` files |
//!
//! A path that exists is read from disk even when it contains a colon. Definitions are
//! validated and resolved by `jaus-spec`; the first problem set is returned as the
//! error, with file and line.
//!
//! ## A vendor's overlay alone
//!
//! YAML is read the way the build reads it ([`yaml_snapshot`]):
//!
//! * files that hold the SDK's definitions themselves (one of them defines the group
//!   `core`: `jaus-spec/defs`, `HEAD~1:jaus-spec/defs`, `jaus-spec/defs,acme.yaml`) or
//!   that say `extends: none` are a definition set of their own, and every item of it is
//!   compared;
//! * any other YAML is a vendor's overlay, loaded on the SDK's definitions built into
//!   jaus-gen (`jaus_spec::load_overlay_texts`, as `Builder::overlay`, `jaus-gen lock
//!   --overlay` and `jaus --spec` load it): it may use the SDK's types and messages
//!   (`TimeStamp`), and only its own items are compared, which is also what the lock
//!   file of such a build holds. So `jaus-gen diff HEAD:defs/my.yaml defs/my.yaml` and
//!   `jaus-gen diff defs/my.lock defs/my.yaml` compare like with like.

use crate::error::Error;
use crate::lock;
use crate::snapshot::{label, JsidlPositions, Snapshot};
use std::path::{Path, PathBuf};
use std::process::Command;

fn is_yaml(p: &Path) -> bool {
    p.extension().is_some_and(|x| x == "yaml" || x == "yml")
}

fn is_lock(p: &Path) -> bool {
    p.extension().is_some_and(|x| x == "lock")
}

fn err(arg: &str, msg: impl std::fmt::Display) -> Error {
    Error::Revision(format!("{arg}: {msg}"))
}

/// Runs git in the current directory; its stdout, or what it said on stderr.
fn git(arg: &str, args: &[&str]) -> Result<Vec<u8>, Error> {
    let out = Command::new("git")
        .args(args)
        .output()
        .map_err(|e| err(arg, format!("cannot run git: {e}")))?;
    if out.status.success() {
        return Ok(out.stdout);
    }
    let stderr = String::from_utf8_lossy(&out.stderr).trim().to_string();
    if stderr.contains("not a git repository") {
        return Err(err(
            arg,
            format!("`REV:PATH` reads a git revision, but the current directory is not in a git repository ({stderr})"),
        ));
    }
    Err(err(arg, format!("git cannot read it: {stderr}")))
}

fn git_text(arg: &str, object: &str) -> Result<String, Error> {
    let bytes = git(arg, &["cat-file", "blob", object])?;
    String::from_utf8(bytes).map_err(|_| err(arg, format!("{object} is not UTF-8 text")))
}

/// The `(path, text)` of the YAML files of `REV:PATH`, or the lock file it names.
fn from_git(arg: &str, rev: &str, path: &str) -> Result<Loaded, Error> {
    let object = format!("{rev}:{path}");
    let kind = git(arg, &["cat-file", "-t", &object])?;
    match String::from_utf8_lossy(&kind).trim() {
        "blob" => {
            let text = git_text(arg, &object)?;
            if is_lock(Path::new(path)) {
                return Ok(Loaded::Lock(object, text));
            }
            Ok(Loaded::Yaml(vec![(PathBuf::from(&object), text)]))
        }
        "tree" => {
            let list = git(arg, &["ls-tree", "--full-tree", "-z", &object])?;
            let mut files = Vec::new();
            for entry in list.split(|&b| b == 0).filter(|e| !e.is_empty()) {
                let entry = String::from_utf8_lossy(entry);
                let Some((meta, name)) = entry.split_once('\t') else {
                    continue;
                };
                if meta.split_whitespace().nth(1) != Some("blob") || !is_yaml(Path::new(name)) {
                    continue;
                }
                let file = if path.is_empty() || path.ends_with('/') {
                    format!("{rev}:{path}{name}")
                } else {
                    format!("{rev}:{path}/{name}")
                };
                let text = git_text(arg, &file)?;
                files.push((PathBuf::from(file), text));
            }
            files.sort_by(|a, b| a.0.cmp(&b.0));
            if files.is_empty() {
                return Err(err(arg, "no *.yaml file in that directory"));
            }
            Ok(Loaded::Yaml(files))
        }
        other => Err(err(
            arg,
            format!("{object} is a git {other}, not a file or directory"),
        )),
    }
}

enum Loaded {
    Yaml(Vec<(PathBuf, String)>),
    Lock(String, String),
    Jsidl(PathBuf),
}

/// Whether `dir` holds JSIDL: `*.xml` files (at any depth) and no `*.yaml` of its own.
fn is_jsidl_dir(dir: &Path) -> bool {
    let entries = |d: &Path| -> Vec<PathBuf> {
        std::fs::read_dir(d)
            .map(|rd| rd.filter_map(|e| e.ok().map(|e| e.path())).collect())
            .unwrap_or_default()
    };
    let top = entries(dir);
    if top.iter().any(|f| is_yaml(f)) {
        return false;
    }
    let mut todo = top;
    while let Some(p) = todo.pop() {
        if p.is_dir() {
            todo.extend(entries(&p));
        } else if p.extension().is_some_and(|x| x == "xml") {
            return true;
        }
    }
    false
}

fn read(arg: &str, p: &Path) -> Result<String, Error> {
    std::fs::read_to_string(p).map_err(|e| err(arg, format!("{}: {e}", p.display())))
}

fn part(arg: &str, part: &str, jsidl: bool) -> Result<Loaded, Error> {
    let p = Path::new(part);
    if p.is_dir() && (jsidl || is_jsidl_dir(p)) {
        return Ok(Loaded::Jsidl(p.to_path_buf()));
    }
    if p.is_dir() {
        let mut files: Vec<PathBuf> = std::fs::read_dir(p)
            .map_err(|e| err(arg, format!("{part}: {e}")))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|f| is_yaml(f))
            .collect();
        files.sort();
        if files.is_empty() {
            return Err(err(
                arg,
                format!("{part}: no *.yaml file in that directory"),
            ));
        }
        return files
            .into_iter()
            .map(|f| read(arg, &f).map(|t| (f, t)))
            .collect::<Result<_, _>>()
            .map(Loaded::Yaml);
    }
    if p.is_file() {
        let text = read(arg, p)?;
        if is_lock(p) {
            return Ok(Loaded::Lock(part.to_string(), text));
        }
        return Ok(Loaded::Yaml(vec![(p.to_path_buf(), text)]));
    }
    match part.split_once(':') {
        Some((rev, path)) if !rev.is_empty() => from_git(arg, rev, path),
        _ => Err(err(
            arg,
            "no such file or directory (a git revision is written REV:PATH)",
        )),
    }
}

/// Loads the revision named by `arg` (see the module documentation).
pub fn load(arg: &str) -> Result<Snapshot, Error> {
    load_with(arg, false)
}

/// Loads the revision named by `arg`; with `jsidl`, every directory in it is JSIDL
/// (`jaus-gen diff --jsidl`), whatever else it holds.
pub fn load_with(arg: &str, jsidl: bool) -> Result<Snapshot, Error> {
    let mut yaml = Vec::new();
    let mut xml = Vec::new();
    let mut lock = None;
    let parts: Vec<&str> = arg.split(',').filter(|s| !s.is_empty()).collect();
    if parts.is_empty() {
        return Err(err(arg, "no definitions named"));
    }
    for p in &parts {
        match part(arg, p, jsidl)? {
            Loaded::Yaml(v) => yaml.extend(v),
            Loaded::Lock(name, text) => lock = Some((name, text)),
            Loaded::Jsidl(d) => xml.push(d),
        }
    }
    if let Some((name, text)) = lock {
        if parts.len() > 1 {
            return Err(err(arg, "a lock file is a whole revision: name it alone"));
        }
        return lock::parse(&text, &label(Path::new(&name))).map_err(Error::Revision);
    }
    if !xml.is_empty() {
        return jsidl_snapshot(&xml, yaml);
    }
    yaml_snapshot(yaml)
}

/// The snapshot of JSIDL directories imported together (as `jaus-gen jsidl` imports
/// them), with YAML overlays on them; positions of imported items are in the JSIDL
/// files.
pub fn jsidl_snapshot(
    dirs: &[PathBuf],
    overlays: Vec<(PathBuf, String)>,
) -> Result<Snapshot, Error> {
    let import = jaus_jsidl::import(dirs)?;
    if import.files.is_empty() {
        let names: Vec<String> = dirs.iter().map(|d| d.display().to_string()).collect();
        return Err(err(
            &names.join(","),
            "no JSIDL service definition or declared type set (`*.xml`) in it",
        ));
    }
    // The imported YAML exists in memory only: its paths are never shown.
    let root = Path::new("jsidl");
    let origins: Vec<(PathBuf, PathBuf)> = import
        .files
        .iter()
        .map(|f| (root.join(&f.name), f.source.clone()))
        .collect();
    let mut texts = import.texts(root);
    texts.extend(overlays);
    let spec = jaus_spec::load_texts(texts)?;
    let at = JsidlPositions::new(&spec, &origins)?;
    Ok(Snapshot::from_jsidl(&spec, &at))
}

/// Why a set of YAML files is a definition set of its own rather than a vendor's
/// overlay on the SDK's definitions (see the module documentation), or `None`.
pub fn own_set(files: &[(PathBuf, String)]) -> Option<&'static str> {
    #[derive(serde::Deserialize)]
    struct Head {
        #[serde(default)]
        group: Option<String>,
        #[serde(default)]
        extends: Option<String>,
    }
    let heads: Vec<Head> = files
        .iter()
        .filter_map(|(_, text)| serde_yaml::from_str::<Head>(text).ok())
        .collect();
    if heads.iter().any(|h| h.group.as_deref() == Some("core")) {
        Some("it holds the SDK's definitions (group `core`)")
    } else if heads.iter().any(|h| h.extends.as_deref() == Some("none")) {
        Some("`extends: none`")
    } else {
        None
    }
}

/// The snapshot of YAML files: a definition set of its own, or a vendor's overlay on
/// the SDK's built-in definitions with only its own items (see the module
/// documentation).
pub fn yaml_snapshot(files: Vec<(PathBuf, String)>) -> Result<Snapshot, Error> {
    let spec = if own_set(&files).is_some() {
        jaus_spec::load_texts(files)?
    } else {
        jaus_spec::load_overlay_texts(files)?
    };
    Ok(Snapshot::from_spec(&spec))
}

/// The snapshot of the directories and files `paths` on disk, in order, read as
/// [`yaml_snapshot`] reads them (what `jaus-gen lock --spec DIR --overlay FILE` locks);
/// directories of JSIDL are imported ([`jsidl_snapshot`]).
pub fn load_paths(paths: &[PathBuf]) -> Result<Snapshot, Error> {
    let mut yaml = Vec::new();
    let mut xml = Vec::new();
    for p in paths {
        let arg = p.display().to_string();
        if !p.exists() {
            return Err(err(&arg, "no such file or directory"));
        }
        match part(&arg, &arg, false)? {
            Loaded::Yaml(v) => yaml.extend(v),
            Loaded::Lock(..) => return Err(err(&arg, "a lock file is not a definition")),
            Loaded::Jsidl(d) => xml.push(d),
        }
    }
    if !xml.is_empty() {
        return jsidl_snapshot(&xml, yaml);
    }
    yaml_snapshot(yaml)
}
