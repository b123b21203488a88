//! # jaus-jsidl — JSIDL (SAE AS5684) into the JAUS definition language
//!
//! The SAE AS-4 JAUS service sets are defined in JSIDL: XML service definitions
//! (`service_def`) and declared type sets (`declared_type_set`) that refer to each
//! other by URI and version. This crate reads a set of such files into the model of
//! [`jaus_spec`] and writes it as YAML of that language, one file per JSIDL file, which
//! the normal pipeline (`jaus-spec` validation, `jaus-gen`) consumes like any other
//! definitions.
//!
//! What it reads, and the mapping of each JSIDL construct, is in `docs/as4.md`. What
//! the model cannot represent is an [`Error`] naming the file, line, column and
//! element: nothing is skipped silently.
//!
//! ```no_run
//! let import = jaus_jsidl::import(&["jsidl/urn.jaus.jss.core-v1.1"]).unwrap();
//! let spec = import.load().unwrap(); // validated as the YAML would be
//! println!("{} messages", spec.messages.len());
//! import.write("defs/core").unwrap();
//! ```

mod alike;
mod containers;
mod emit;
mod error;
mod expr;
mod fields;
mod import;
mod messages;
mod names;
mod same;
mod services;
mod xml;

pub use error::{Error, Result};

use import::{At, Importer};
use std::path::{Path, PathBuf};
use xml::{elements, tag, Doc};

/// One YAML file of an import: what one JSIDL file gave.
#[derive(Debug, Clone)]
pub struct ImportedFile {
    /// The YAML file's name (`message_set_basic_types.yaml`).
    pub name: String,
    /// The JSIDL file it came from.
    pub source: PathBuf,
    /// Its group (one per directory imported).
    pub group: String,
    /// Number of named types in it.
    pub types: usize,
    /// Number of messages in it.
    pub messages: usize,
    /// Number of services in it.
    pub services: usize,
    /// The YAML text.
    pub yaml: String,
}

/// The result of an import: a YAML file per JSIDL file that contributed something.
#[derive(Debug, Clone)]
pub struct Import {
    /// The files, by group then JSIDL path.
    pub files: Vec<ImportedFile>,
}

impl Import {
    /// `(path, text)` pairs of the YAML, each path `dir/name`, as
    /// [`jaus_spec::load_texts`] takes them.
    pub fn texts(&self, dir: &Path) -> Vec<(PathBuf, String)> {
        self.files
            .iter()
            .map(|f| (dir.join(&f.name), f.yaml.clone()))
            .collect()
    }

    /// Validates the YAML as `jaus-spec` would load it from a directory.
    pub fn load(&self) -> Result<jaus_spec::Spec> {
        Ok(jaus_spec::load_texts(self.texts(Path::new("jsidl")))?)
    }

    /// Writes the YAML files into `out` (created if missing; a file already holding the
    /// same text is left alone) and returns their paths.
    pub fn write(&self, out: impl AsRef<Path>) -> Result<Vec<PathBuf>> {
        let out = out.as_ref();
        std::fs::create_dir_all(out).map_err(|source| Error::Io {
            path: out.to_path_buf(),
            source,
        })?;
        let mut written = Vec::new();
        for (path, text) in self.texts(out) {
            if std::fs::read_to_string(&path).ok().as_deref() != Some(text.as_str()) {
                std::fs::write(&path, text).map_err(|source| Error::Io {
                    path: path.clone(),
                    source,
                })?;
            }
            written.push(path);
        }
        Ok(written)
    }
}

/// Every `*.xml` file under `dir`, recursively, as paths relative to it, sorted.
fn xml_files(dir: &Path) -> Result<Vec<String>> {
    let mut out = Vec::new();
    let mut stack = vec![PathBuf::new()];
    while let Some(rel) = stack.pop() {
        let full = dir.join(&rel);
        let rd = std::fs::read_dir(&full).map_err(|source| Error::Io {
            path: full.clone(),
            source,
        })?;
        for e in rd {
            let e = e.map_err(|source| Error::Io {
                path: full.clone(),
                source,
            })?;
            let r = rel.join(e.file_name());
            if e.path().is_dir() {
                stack.push(r);
            } else if r.extension().is_some_and(|x| x == "xml") {
                out.push(r.to_string_lossy().replace('\\', "/"));
            }
        }
    }
    out.sort();
    Ok(out)
}

/// Imports every JSIDL file (`*.xml`, recursively) of `dirs`: each directory is one
/// group, named after it (`urn.jaus.jss.core-v1.1` → `jaus_jss_core_v1_1`). References
/// between files resolve across all the directories.
pub fn import<P: AsRef<Path>>(dirs: &[P]) -> Result<Import> {
    let mut texts = Vec::new();
    let mut groups = Vec::new();
    for (i, d) in dirs.iter().enumerate() {
        let d = d.as_ref();
        let name = d
            .canonicalize()
            .ok()
            .and_then(|c| c.file_name().map(|n| n.to_string_lossy().into_owned()))
            .unwrap_or_else(|| d.display().to_string());
        groups.push(names::group(&name));
        for rel in xml_files(d)? {
            let path = d.join(&rel);
            let text = std::fs::read_to_string(&path).map_err(|source| Error::Io {
                path: path.clone(),
                source,
            })?;
            texts.push((path, rel, i, text));
        }
    }
    let mut docs = Vec::new();
    let mut errors = Vec::new();
    for (path, rel, dir, text) in &texts {
        match Doc::parse(path.clone(), rel.clone(), *dir, text) {
            Ok(d) => docs.push(d),
            Err(e) => errors.push(e),
        }
    }
    if let Some(e) = Error::of(errors) {
        return Err(e);
    }
    run(&docs, &groups)
}

/// Converts the parsed documents.
fn run(docs: &[Doc<'_>], groups: &[String]) -> Result<Import> {
    let mut im = Importer::new(docs);
    // Every error is reported: each message, declaration and service is converted on
    // its own, and the run goes on after one fails.
    let mut errors = std::mem::take(&mut im.errors);
    let read: Vec<usize> = (0..docs.len()).filter(|i| !im.is_copy(*i)).collect();
    // Messages keep their names: claim them all before any type takes one.
    for &i in &read {
        let d = &docs[i];
        for n in d.root().descendants().filter(|n| tag(*n) == "message_def") {
            let at = At { doc: i, node: n };
            let claimed = im
                .req(at, "name")
                .and_then(|name| im.claim_message(at, &names::pascal(name)));
            errors.extend(claimed.err());
        }
    }
    for &i in &read {
        let d = &docs[i];
        let root = At {
            doc: i,
            node: d.root(),
        };
        match tag(root.node) {
            "service_def" => {
                let r = im.service(root);
                im.keep(r, &mut errors);
            }
            "declared_type_set" => top_level(&mut im, root, &mut errors),
            // Constants are not types: a reference to one where a number is wanted is
            // reported there.
            "declared_const_set" => {}
            other => errors.push(d.err(
                root.node,
                format!("<{other}> is not a JSIDL service definition or declared type set"),
            )),
        }
    }
    if let Some(e) = Error::of(dedup(errors)) {
        return Err(e);
    }
    let mut files = Vec::new();
    let mut names_seen = std::collections::HashSet::new();
    for (i, d) in docs.iter().enumerate() {
        let c = std::mem::take(&mut im.out[i]);
        if c.types.is_empty() && c.messages.is_empty() && c.services.is_empty() {
            continue;
        }
        let types = by_offset(c.types);
        let messages = by_offset(c.messages);
        let services = by_offset(c.services);
        let mut name = names::yaml_file(&d.rel);
        if !names_seen.insert(name.clone()) {
            name = format!("{}.{name}", groups[d.dir]);
            names_seen.insert(name.clone());
        }
        let yaml =
            emit::file(&d.rel, &groups[d.dir], &types, &messages, &services).map_err(|source| {
                Error::Yaml {
                    file: name.clone(),
                    source,
                }
            })?;
        files.push(ImportedFile {
            name,
            source: d.path.clone(),
            group: groups[d.dir].clone(),
            types: types.len(),
            messages: messages.len(),
            services: services.len(),
            yaml,
        });
    }
    Ok(Import { files })
}

/// Items in the order of their offsets in the file.
fn by_offset<T>(mut v: Vec<(usize, T)>) -> Vec<T> {
    v.sort_by_key(|(o, _)| *o);
    v.into_iter().map(|(_, x)| x).collect()
}

/// Errors once each (a declaration several messages use fails once per use), by file
/// and position.
fn dedup(errors: Vec<Error>) -> Vec<Error> {
    let mut seen = std::collections::HashSet::new();
    let mut v: Vec<Error> = errors
        .into_iter()
        .filter(|e| seen.insert(e.to_string()))
        .collect();
    v.sort_by(|a, b| position(a).cmp(&position(b)));
    v
}

/// Where an error is, for sorting: sets declared twice differently first (what follows
/// from them comes after), then by file and position.
fn position(e: &Error) -> (u8, Option<&Path>, u32, u32) {
    match e {
        Error::Duplicate { file, .. } => (0, Some(file.as_path()), 0, 0),
        Error::Io { path, .. } => (0, Some(path.as_path()), 0, 0),
        Error::Xml {
            file, line, column, ..
        }
        | Error::At {
            file, line, column, ..
        } => (1, Some(file.as_path()), *line, *column),
        _ => (2, None, 0, 0),
    }
}

/// The top-level declarations of a declared type set: messages, and every record,
/// list, variant, sequence, array, bit field, enumerated fixed field and variable field
/// as a named type (plain fields and strings are written where they are used).
fn top_level<'a>(im: &mut Importer<'a>, set: At<'a>, errors: &mut Vec<Error>) {
    for c in elements(set.node) {
        let at = im.at(set, c);
        match tag(c) {
            "message_def" => {
                let r = im.message(at);
                im.keep(r, errors);
            }
            "record" | "list" | "variant" | "sequence" => {
                let r = im.container_type(at, "");
                im.keep(r, errors);
            }
            "bit_field" | "fixed_field" | "variable_field" | "array" => {
                let r = im.record_field(at, "", None, fields::Mode::Wire);
                im.keep(r, errors);
            }
            _ => {}
        }
    }
}
