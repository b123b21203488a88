//! Definitions assembled at run time from built-in texts and a vendor's files: the one
//! loader of every tool that speaks messages it was not built with (`jaus as4-query
//! --as4-spec`, `jaus conform --as4 --plan`, …).

use std::path::{Path, PathBuf};

use jaus_spec::Spec;

/// Built-in definitions (file name and text, e.g. `jaus_as4::DEFS`) with the YAML of
/// the directories `yaml` on them (each directory's `*.yaml`/`*.yml`, in name order);
/// or, when `jsidl` names directories, the JSIDL there imported instead (the import
/// brings its own base sets). `base_dir` names the built-in files in errors
/// (`jaus-as4/defs`). Errors name the file and, from the validation, the line.
pub fn load_overlaid(
    base: &[(&str, &str)],
    base_dir: &str,
    yaml: &[PathBuf],
    jsidl: &[PathBuf],
) -> Result<Spec, String> {
    let loaded = if jsidl.is_empty() {
        let mut texts: Vec<(PathBuf, String)> = base
            .iter()
            .map(|(name, text)| (Path::new(base_dir).join(name), text.to_string()))
            .collect();
        for dir in yaml {
            let entries = std::fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
            let mut files: Vec<PathBuf> = entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "yaml" || x == "yml"))
                .collect();
            files.sort();
            for f in files {
                let text =
                    std::fs::read_to_string(&f).map_err(|e| format!("{}: {e}", f.display()))?;
                texts.push((f, text));
            }
        }
        jaus_spec::load_texts(texts)
    } else {
        let import = jaus_jsidl::import(jsidl).map_err(|e| e.to_string())?;
        jaus_spec::load_texts(import.texts(Path::new("jsidl")))
    };
    loaded.map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_directory_is_named() {
        let err =
            load_overlaid(&[], "base", &[PathBuf::from("/nonexistent/defs")], &[]).unwrap_err();
        assert!(err.starts_with("/nonexistent/defs: "), "{err}");
    }
}
