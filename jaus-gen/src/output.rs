//! Writing generated code: formatted, and written only when it changed (so that a
//! build that regenerates the same code does not rebuild what depends on it).

use std::path::Path;

use crate::error::Error;

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
