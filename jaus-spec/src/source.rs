//! A definition file as read ([`Source`]: its text and where each node stands) and
//! the problems found in definitions ([`SpecError`]: file:line:column, what is
//! concerned, what to do).

use std::fmt;
use std::path::PathBuf;

use crate::location::{LocationIndex, Pos};

/// One problem found in the definitions.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SpecError {
    /// File the problem is in.
    pub file: PathBuf,
    /// Where in the file.
    pub pos: Pos,
    /// The message/type/field concerned, e.g. `message ReportGlobalPose, field latitude`.
    pub context: String,
    /// What is wrong and what to do.
    pub message: String,
}

impl fmt::Display for SpecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}: ",
            self.file.display(),
            self.pos.line,
            self.pos.column
        )?;
        if !self.context.is_empty() {
            write!(f, "{}: ", self.context)?;
        }
        f.write_str(&self.message)
    }
}

/// Every problem found, in file order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SpecErrors(pub Vec<SpecError>);

impl fmt::Display for SpecErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, e) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{e}")?;
        }
        Ok(())
    }
}

impl std::error::Error for SpecErrors {}

/// A loaded source file.
#[derive(Debug)]
pub struct Source {
    /// Its path.
    pub path: PathBuf,
    /// Its text.
    pub text: String,
    /// Node positions.
    pub index: LocationIndex,
}
