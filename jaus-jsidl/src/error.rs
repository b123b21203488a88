//! What can go wrong in an import: a file that cannot be read, XML that does not
//! parse, and a JSIDL element the definition model cannot represent or whose reference
//! does not resolve (each with the file, line, column and element).

use std::path::PathBuf;

/// An import error.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A directory or file could not be read (or an output file written).
    #[error("{}: {source}", path.display())]
    Io {
        /// The path concerned.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A file is not well-formed XML.
    #[error("{}:{line}:{column}: not well-formed XML: {message}", file.display())]
    Xml {
        /// The JSIDL file.
        file: PathBuf,
        /// 1-based line.
        line: u32,
        /// 1-based column.
        column: u32,
        /// What the XML parser said.
        message: String,
    },
    /// An element the importer cannot represent, or a broken reference.
    #[error("{}:{line}:{column}: <{element}>: {message}", file.display())]
    At {
        /// The JSIDL file.
        file: PathBuf,
        /// 1-based line.
        line: u32,
        /// 1-based column.
        column: u32,
        /// The element concerned, with its name (`fixed_field name="Speed"`).
        element: String,
        /// What is wrong, and what the model lacks.
        message: String,
    },
    /// Two JSIDL files declare the same set (URI and version) differently (the same
    /// set declared twice alike is read once).
    #[error("{}: declares {id} version {version}, as {} does, differently: {difference}", file.display(), first.display())]
    Duplicate {
        /// The second file.
        file: PathBuf,
        /// The first file.
        first: PathBuf,
        /// The set's URI.
        id: String,
        /// Its version.
        version: String,
        /// The first difference, with its line and column in each file.
        difference: String,
    },
    /// Every error of a run, in the order of the files (more than one).
    #[error("{} errors:\n{}", .0.len(), .0.iter().map(ToString::to_string).collect::<Vec<_>>().join("\n"))]
    Many(Vec<Error>),
    /// The model could not be written as YAML.
    #[error("{file}: cannot write the YAML: {source}")]
    Yaml {
        /// The output file.
        file: String,
        /// The serializer's error.
        source: serde_yaml::Error,
    },
    /// The imported YAML does not validate (a bug of the importer, or names that clash
    /// across the imported sets).
    #[error("the imported definitions do not validate:\n{0}")]
    Spec(#[from] jaus_spec::SpecErrors),
}

impl Error {
    /// The errors one error stands for: itself, or each of [`Error::Many`].
    pub fn all(&self) -> Vec<&Error> {
        match self {
            Error::Many(v) => v.iter().collect(),
            e => vec![e],
        }
    }

    /// One error for a list of them (`None` for none).
    pub(crate) fn of(mut v: Vec<Error>) -> Option<Error> {
        match v.len() {
            0 => None,
            1 => v.pop(),
            _ => Some(Error::Many(v)),
        }
    }
}

/// Result of the importer.
pub type Result<T> = std::result::Result<T, Error>;
