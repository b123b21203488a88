//! Reading definitions (the built-in set, directories, files, texts, a vendor's
//! overlay) and handing them to validation; the errors it reports.

use crate::location::{LocationIndex, Pos};
use crate::model::SpecFile;
use crate::resolved::{Component, Group, Part, Service, Spec};
use crate::source::{Source, SpecError, SpecErrors};
use crate::validate;
use std::path::{Path, PathBuf};

/// Directory holding the RA 3.3 definitions shipped with this crate.
pub fn defs_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("defs")
}

/// The RA 3.3 definitions of [`defs_dir`], built into this crate (file name, text;
/// sorted by name, the order [`load_dirs`] reads them in): a program that loads a
/// vendor's overlay at run time needs no copy of the directory beside it.
pub const SDK_DEFS: &[(&str, &str)] = &[
    (
        "communications.yaml",
        include_str!("../defs/communications.yaml"),
    ),
    ("core.yaml", include_str!("../defs/core.yaml")),
    ("core_states.yaml", include_str!("../defs/core_states.yaml")),
    (
        "dynamic_configuration.yaml",
        include_str!("../defs/dynamic_configuration.yaml"),
    ),
    ("environment.yaml", include_str!("../defs/environment.yaml")),
    ("events.yaml", include_str!("../defs/events.yaml")),
    ("manipulator.yaml", include_str!("../defs/manipulator.yaml")),
    ("payload.yaml", include_str!("../defs/payload.yaml")),
    ("planning.yaml", include_str!("../defs/planning.yaml")),
    ("platform.yaml", include_str!("../defs/platform.yaml")),
    ("world_model.yaml", include_str!("../defs/world_model.yaml")),
];

/// The built-in definitions as `(path, text)` pairs, each path inside [`defs_dir`].
pub fn sdk_texts() -> Vec<(PathBuf, String)> {
    SDK_DEFS
        .iter()
        .map(|(name, text)| (defs_dir().join(name), (*text).to_string()))
        .collect()
}

/// Loads and validates the built-in definitions ([`SDK_DEFS`]).
pub fn load_sdk() -> Result<Spec, SpecErrors> {
    load_texts(sdk_texts())
}

/// Loads every `*.yaml` file of `dirs` (sorted by name within each directory) and
/// validates the set.
pub fn load_dirs<P: AsRef<Path>>(dirs: &[P]) -> Result<Spec, SpecErrors> {
    load(dirs, &[] as &[PathBuf])
}

/// Loads the `*.yaml` files of `dirs`, then the `overlays` files (which may add types,
/// messages and components to existing groups, or new groups), and validates the set.
pub fn load<P: AsRef<Path>, Q: AsRef<Path>>(
    dirs: &[P],
    overlays: &[Q],
) -> Result<Spec, SpecErrors> {
    let mut files = yaml_files(dirs)?;
    files.extend(overlays.iter().map(|p| p.as_ref().to_path_buf()));
    load_texts(read_files(files)?)
}

/// The `*.yaml` files of `dirs`, sorted by name within each directory.
fn yaml_files<P: AsRef<Path>>(dirs: &[P]) -> Result<Vec<PathBuf>, SpecErrors> {
    let mut files = Vec::new();
    let mut errors = Vec::new();
    for d in dirs {
        let d = d.as_ref();
        match std::fs::read_dir(d) {
            Ok(rd) => {
                let mut v: Vec<PathBuf> = rd
                    .filter_map(|e| e.ok().map(|e| e.path()))
                    .filter(|p| p.extension().is_some_and(|x| x == "yaml" || x == "yml"))
                    .collect();
                v.sort();
                files.extend(v);
            }
            Err(e) => errors.push(SpecError {
                file: d.to_path_buf(),
                pos: Pos { line: 0, column: 0 },
                context: String::new(),
                message: format!("cannot read definition directory: {e}"),
            }),
        }
    }
    if errors.is_empty() {
        Ok(files)
    } else {
        Err(SpecErrors(errors))
    }
}

/// Reads every file.
fn read_files(files: Vec<PathBuf>) -> Result<Vec<(PathBuf, String)>, SpecErrors> {
    let mut errors = Vec::new();
    let mut texts = Vec::new();
    for f in files {
        match std::fs::read_to_string(&f) {
            Ok(t) => texts.push((f, t)),
            Err(e) => errors.push(SpecError {
                file: f,
                pos: Pos { line: 0, column: 0 },
                context: String::new(),
                message: format!("cannot read definition file: {e}"),
            }),
        }
    }
    if errors.is_empty() {
        Ok(texts)
    } else {
        Err(SpecErrors(errors))
    }
}

/// Loads a vendor's overlay files on the definitions they extend: the SDK's own
/// ([`defs_dir`]) unless a file says `extends: none`. The overlay's types, messages and
/// components may use every type and message of the base; names and codes may not
/// repeat the base's (an error naming both positions); [`Spec::is_own`] tells the
/// overlay's items from the base's, and [`Spec::warnings`] lists overlay messages
/// outside the experimental code range.
pub fn load_overlays<Q: AsRef<Path>>(overlays: &[Q]) -> Result<Spec, SpecErrors> {
    let own = read_files(overlays.iter().map(|p| p.as_ref().to_path_buf()).collect())?;
    load_overlay_texts(own)
}

/// [`load_overlays`] of files already read, as `(path, text)` pairs (the path is used
/// in errors and positions only): a vendor's overlay from a git revision, say.
pub fn load_overlay_texts(own: Vec<(PathBuf, String)>) -> Result<Spec, SpecErrors> {
    match overlay_base(&own, None)? {
        true => load_texts_on(sdk_texts(), own),
        false => load_texts_on(Vec::new(), own),
    }
}

/// Loads a vendor's overlay on other base definitions than the SDK's: `base` (file
/// path, text), named `name` (`as4`: jaus-as4's definitions). Every file of `own`
/// says `extends: NAME` (or `extends: none` for a set of its own); the items of `base`
/// are not generated again ([`Spec::is_own`]).
pub fn load_overlay_texts_on(
    name: &str,
    base: Vec<(PathBuf, String)>,
    own: Vec<(PathBuf, String)>,
) -> Result<Spec, SpecErrors> {
    match overlay_base(&own, Some(name))? {
        true => load_texts_on(base, own),
        false => load_texts_on(Vec::new(), own),
    }
}

/// Whether the overlay `own` extends its base: every file's `extends:` is checked
/// against the base's name (`jaus` when `name` is `None`), `none` meaning it extends
/// nothing.
fn overlay_base(own: &[(PathBuf, String)], name: Option<&str>) -> Result<bool, SpecErrors> {
    let mut extends = true;
    let mut errors = Vec::new();
    for (path, text) in own {
        #[derive(serde::Deserialize)]
        struct Head {
            #[serde(default)]
            extends: Option<String>,
        }
        let Ok(head) = serde_yaml::from_str::<Head>(text) else {
            continue; // the full load reports the syntax error
        };
        let fine = match (head.extends.as_deref(), name) {
            (Some("none"), _) => {
                extends = false;
                true
            }
            (None | Some("jaus"), None) => true,
            (Some(e), Some(n)) => e == n,
            _ => false,
        };
        if !fine {
            let expected = name.unwrap_or("jaus");
            let found = head.extends.as_deref().unwrap_or("jaus (the default)");
            errors.push(SpecError {
                file: path.clone(),
                pos: LocationIndex::build(text).find("extends"),
                context: String::new(),
                message: format!(
                    "`extends: {found}`: this set is loaded on `{expected}`; say `extends: {expected}` (the definitions it builds on) or `none`"
                ),
            });
        }
    }
    if errors.is_empty() {
        Ok(extends)
    } else {
        Err(SpecErrors(errors))
    }
}

/// Loads definitions from `(path, text)` pairs (the path is used in errors only).
pub fn load_texts(texts: Vec<(PathBuf, String)>) -> Result<Spec, SpecErrors> {
    load_texts_on(Vec::new(), texts)
}

/// Loads `own` definitions on `base` ones ([`load_overlays`]).
pub fn load_texts_on(
    base: Vec<(PathBuf, String)>,
    own: Vec<(PathBuf, String)>,
) -> Result<Spec, SpecErrors> {
    let base_sources = base.len();
    let texts = base.into_iter().chain(own);
    let mut draft = validate::Draft {
        base_sources,
        sources: Vec::new(),
        groups: Vec::new(),
        types: Vec::new(),
        messages: Vec::new(),
        components: Vec::new(),
        parts: Vec::new(),
        services: Vec::new(),
    };
    let mut errors = Vec::new();
    for (path, text) in texts {
        let index = LocationIndex::build(&text);
        let source = draft.sources.len();
        match serde_yaml::from_str::<SpecFile>(&text) {
            Ok(file) => {
                if !draft.groups.iter().any(|g| g.name == file.group) {
                    draft.groups.push(Group {
                        name: file.group.clone(),
                        title: file
                            .title
                            .clone()
                            .unwrap_or_else(|| file.group.replace('_', " ")),
                        description: file.description.clone(),
                    });
                }
                for (i, t) in file.types.into_iter().enumerate() {
                    draft.types.push(validate::Parsed {
                        def: t,
                        group: file.group.clone(),
                        source,
                        path: format!("types[{i}]"),
                    });
                }
                for (i, m) in file.messages.into_iter().enumerate() {
                    draft.messages.push(validate::Parsed {
                        def: m,
                        group: file.group.clone(),
                        source,
                        path: format!("messages[{i}]"),
                    });
                }
                for (i, c) in file.components.into_iter().enumerate() {
                    draft.components.push(Component {
                        def: c,
                        group: file.group.clone(),
                        source,
                        path: format!("components[{i}]"),
                    });
                }
                for (i, p) in file.parts.into_iter().enumerate() {
                    draft.parts.push(Part {
                        def: p,
                        group: file.group.clone(),
                        source,
                        path: format!("parts[{i}]"),
                    });
                }
                for (i, s) in file.services.into_iter().enumerate() {
                    draft.services.push(Service {
                        def: s,
                        group: file.group.clone(),
                        source,
                        path: format!("services[{i}]"),
                    });
                }
            }
            Err(e) => {
                let pos = e.location().map_or(Pos { line: 1, column: 1 }, |l| Pos {
                    line: l.line(),
                    column: l.column(),
                });
                let msg = e.to_string();
                // serde_yaml appends " at line N column M"; the position is printed in front.
                let msg = msg.split(" at line ").next().unwrap_or(&msg).to_string();
                errors.push(SpecError {
                    file: path.clone(),
                    pos,
                    context: String::new(),
                    message: msg,
                });
            }
        }
        draft.sources.push(Source { path, text, index });
    }
    if !errors.is_empty() {
        return Err(SpecErrors(errors));
    }
    validate::validate(draft).map_err(SpecErrors)
}
