//! What can go wrong while generating, each naming the file and line to fix.

use std::path::PathBuf;

use jaus_spec::SpecErrors;

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
    /// A revision to compare could not be read (a missing path, a git error, a
    /// malformed lock file); the text names the argument, file and line.
    #[error("{0}")]
    Revision(String),
    /// The definitions' wire layout differs from the lock file ([`Builder::lock`](crate::Builder::lock)); the
    /// text lists every change and the command that updates the lock file.
    #[error("{0}")]
    Lock(String),
    /// The services cannot be generated (a parent outside the definitions, a guard that
    /// does not parse, a target that is not a state): the text names the service and
    /// the file and line.
    #[error("{0}")]
    Services(String),
    /// JSIDL could not be imported ([`Builder::jsidl`](crate::Builder::jsidl)): the file, line and element.
    #[error("{0}")]
    Jsidl(#[from] jaus_jsidl::Error),
}
