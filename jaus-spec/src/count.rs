//! The count of a list kept in another field: `count_field: num_joints - 1` in YAML,
//! `count_var = "num_joints - 1"` on a derived type.
//!
//! This is the one parser of that expression. Validation resolves every `count_field`
//! with it into [`crate::Wire::ListField`], and the derive macros read their
//! `count_var` attribute with it (they depend on this crate without its default
//! `yaml` feature, which leaves this module alone, with no dependencies).

use std::fmt;
use std::str::FromStr;

/// A list count that is the value of an earlier field, optionally minus a constant:
/// `num_joints` or `num_joints - 1`.
///
/// ```
/// use jaus_spec::CountRef;
/// let c: CountRef = "num_joints - 1".parse().unwrap();
/// assert_eq!(c, CountRef { field: "num_joints".into(), minus: 1 });
/// assert_eq!(c.to_string(), "num_joints - 1");
/// assert_eq!("n".parse::<CountRef>().unwrap().to_string(), "n");
/// assert!("n - one".parse::<CountRef>().is_err());
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct CountRef {
    /// The field holding the count. The parser takes it as written (trimmed); whether
    /// it names an earlier unsigned field is a rule of validation.
    pub field: String,
    /// The constant subtracted from the field's value (0 when none is written).
    pub minus: u64,
}

impl CountRef {
    /// The count of `field` itself, nothing subtracted.
    pub fn of(field: impl Into<String>) -> Self {
        CountRef {
            field: field.into(),
            minus: 0,
        }
    }

    /// Parses `name` or `name - N` (spaces around `-` optional).
    pub fn parse(expr: &str) -> Result<Self, CountRefError> {
        let (field, minus) = match expr.split_once('-') {
            Some((n, m)) => (n.trim(), Some(m.trim())),
            None => (expr.trim(), None),
        };
        let minus = match minus {
            None => 0,
            Some(m) => m.parse::<u64>().map_err(|_| CountRefError {
                expr: expr.to_string(),
                field: field.to_string(),
            })?,
        };
        Ok(CountRef {
            field: field.to_string(),
            minus,
        })
    }
}

impl FromStr for CountRef {
    type Err = CountRefError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        CountRef::parse(s)
    }
}

/// The YAML form: `field` or `field - N`.
impl fmt::Display for CountRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.minus == 0 {
            f.write_str(&self.field)
        } else {
            write!(f, "{} - {}", self.field, self.minus)
        }
    }
}

/// A count expression that is not `name` or `name - N` (`N` an unsigned integer).
///
/// The error knows no file or attribute; validation reports it as a
/// [`SpecError`](crate::SpecError) (file:line:column, message and field) and the
/// derive macros at the attribute.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CountRefError {
    /// The expression as written.
    pub expr: String,
    /// Its field name part (before the `-`), still worth checking against the fields.
    pub field: String,
}

impl fmt::Display for CountRefError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "`{}` is not a field name optionally minus a constant (`num_joints - 1`)",
            self.expr
        )
    }
}

impl std::error::Error for CountRefError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_a_name_with_or_without_a_constant() {
        assert_eq!(CountRef::parse("n").unwrap(), CountRef::of("n"));
        assert_eq!(CountRef::parse("  n  ").unwrap(), CountRef::of("n"));
        for s in ["n - 1", "n-1", "n -1", " n- 1 "] {
            assert_eq!(
                CountRef::parse(s).unwrap(),
                CountRef {
                    field: "n".into(),
                    minus: 1
                },
                "{s}"
            );
        }
    }

    #[test]
    fn rejects_a_constant_that_is_not_an_unsigned_integer() {
        for s in ["n -", "n - x", "n - 1 - 1", "n - -1", "n - 1.5"] {
            let e = CountRef::parse(s).unwrap_err();
            assert_eq!(e.expr, s);
            assert_eq!(e.field, "n");
            assert!(e.to_string().contains(s), "{e}");
        }
    }

    #[test]
    fn writes_back_the_yaml_form() {
        for s in ["num_joints", "num_joints - 1", "n - 12"] {
            assert_eq!(CountRef::parse(s).unwrap().to_string(), s);
        }
        assert_eq!(CountRef::parse("n-2").unwrap().to_string(), "n - 2");
        assert_eq!(CountRef::parse("n - 0").unwrap().to_string(), "n");
    }
}
