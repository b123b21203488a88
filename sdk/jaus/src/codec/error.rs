//! The typed errors of decoding and encoding, and the presence-vector checks.

use std::fmt;

use super::ScaledField;

/// What went wrong while decoding, and where.
///
/// Boxed, so that `Result<T, DecodeError>` stays one word wider than `T` on the hot
/// path; the allocation happens only when decoding fails.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DecodeError(Box<DecodeErrorInner>);

#[derive(Debug, Clone, PartialEq, Eq)]
struct DecodeErrorInner {
    kind: DecodeErrorKind,
    offset: usize,
    /// The fields being decoded, innermost first (`Record.field`, then the field of
    /// the enclosing record or message that holds it, ...).
    path: Vec<&'static str>,
    message: Option<&'static str>,
}

/// The kinds of decoding failure.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum DecodeErrorKind {
    /// The buffer ended before the field did.
    Truncated {
        /// Bytes the field needed.
        needed: usize,
        /// Bytes that were left.
        available: usize,
    },
    /// A count prefix promises more elements than the remaining bytes can hold.
    CountBeyondBuffer {
        /// The count read.
        count: usize,
        /// Bytes left after it.
        remaining: usize,
    },
    /// A size prefix does not match the size of what it wraps.
    SizeMismatch {
        /// Size announced by the prefix.
        announced: usize,
        /// Size actually consumed.
        consumed: usize,
    },
    /// Records nest deeper than [`MAX_DEPTH`](super::MAX_DEPTH).
    TooDeep {
        /// The limit.
        max: u16,
    },
    /// A field depends on an earlier field (a count or flag) that was not decoded.
    MissingVariable {
        /// The variable name.
        name: &'static str,
    },
    /// The body is longer than the message's fields (and no presence bit the
    /// definition does not know is set).
    TrailingBytes {
        /// Bytes left over.
        count: usize,
    },
    /// A presence bit the definition does not define is set where the fields a newer
    /// revision adds under it cannot be skipped (see [`check_presence`]).
    UndefinedPresenceBit {
        /// The lowest such bit.
        bit: u32,
        /// Why its fields cannot be skipped.
        why: UndefinedBit,
    },
    /// A tag of a tagged union, or a value of a closed enumeration, that the
    /// definition does not name.
    UndefinedValue {
        /// The value read.
        value: u64,
    },
    /// A command code that no known message has.
    UnknownCommandCode {
        /// The code.
        code: u16,
    },
    /// The packet is shorter than the 16-byte header.
    TruncatedHeader {
        /// Bytes present.
        len: usize,
    },
    /// The header's data size disagrees with the bytes that follow it.
    DataSizeMismatch {
        /// Size in the header.
        header: usize,
        /// Bytes actually present after the header.
        actual: usize,
    },
}

/// Why the fields under an undefined presence bit cannot be skipped
/// ([`DecodeErrorKind::UndefinedPresenceBit`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum UndefinedBit {
    /// The presence vector is a nested record's: the end of that record is not known.
    InRecord,
    /// The bit is below this defined bit: newer fields are only known to come after
    /// the known ones when their bits are above every defined bit.
    BelowDefinedBit(u32),
    /// The message's last field runs to the end of the body (`rest`) and is present.
    RestField,
}

/// Checks the presence vector `pv` of a message body (`outermost`) or of a nested
/// record against the bits its definition defines (`known`); `rest_present` says
/// whether the last field runs to the end of the body and is present. `at` is the
/// offset of the presence vector.
///
/// The forward-compatibility rule: a newer revision of a message appends optional
/// fields at the end of the body, under presence bits above every bit the older
/// revision defines. So when bits the definition does not define are set in a message
/// body, the known fields come first and the decoder skips the rest of the body (whose
/// size the header gives): `Ok(true)`. Where that cannot be known to hold, the
/// undefined bit is a [`DecodeErrorKind::UndefinedPresenceBit`]: in a nested record
/// (where the end of the record is not known), below a defined bit, or when the last
/// field runs to the end of the body. `Ok(false)`: every set bit is defined.
#[inline]
pub fn check_presence(
    pv: u64,
    known: u64,
    outermost: bool,
    rest_present: bool,
    at: usize,
) -> Result<bool, DecodeError> {
    let unknown = pv & !known;
    if unknown == 0 {
        return Ok(false);
    }
    undefined_presence(unknown, known, outermost, rest_present, at)
}

#[cold]
#[inline(never)]
fn undefined_presence(
    unknown: u64,
    known: u64,
    outermost: bool,
    rest_present: bool,
    at: usize,
) -> Result<bool, DecodeError> {
    let bit = unknown.trailing_zeros();
    // The lowest defined bit above the lowest undefined one, if any.
    let above = known & !((2u64 << bit).wrapping_sub(1));
    let why = if !outermost {
        UndefinedBit::InRecord
    } else if above != 0 {
        UndefinedBit::BelowDefinedBit(above.trailing_zeros())
    } else if rest_present {
        UndefinedBit::RestField
    } else {
        return Ok(true);
    };
    Err(DecodeError::new(
        DecodeErrorKind::UndefinedPresenceBit { bit, why },
        at,
    ))
}

impl DecodeError {
    /// A new error without field context.
    #[cold]
    pub fn new(kind: DecodeErrorKind, offset: usize) -> Self {
        Self(Box::new(DecodeErrorInner {
            kind,
            offset,
            path: Vec::new(),
            message: None,
        }))
    }

    /// Attaches the field being decoded: the first call names the innermost field,
    /// later calls the fields that enclose it (see [`DecodeError::path`]).
    #[cold]
    pub fn in_field(mut self, field: &'static str) -> Self {
        if self.0.path.last() != Some(&field) {
            self.0.path.push(field);
        }
        self
    }

    /// Attaches the message being decoded, keeping an inner one.
    #[cold]
    pub fn in_message(mut self, message: &'static str) -> Self {
        self.0.message.get_or_insert(message);
        self
    }

    /// The kind of failure.
    pub fn kind(&self) -> &DecodeErrorKind {
        &self.0.kind
    }

    /// Byte offset within the body (or packet, for header errors).
    pub fn offset(&self) -> usize {
        self.0.offset
    }

    /// `Type.field` where decoding failed (innermost), if known.
    pub fn field(&self) -> Option<&'static str> {
        self.0.path.first().copied()
    }

    /// Where decoding failed, innermost field first, then each field that holds it:
    /// `["VksPoint.latitude", "VksObject.points", "ReportVksObjects.objects"]`.
    pub fn path(&self) -> &[&'static str] {
        &self.0.path
    }

    /// Name of the message being decoded, if known.
    pub fn message(&self) -> Option<&'static str> {
        self.0.message
    }
}

impl fmt::Display for DecodeErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Truncated { needed, available } => {
                write!(f, "truncated: needs {needed} byte(s), {available} left")
            }
            Self::CountBeyondBuffer { count, remaining } => {
                write!(f, "count {count} beyond buffer ({remaining} byte(s) left)")
            }
            Self::SizeMismatch {
                announced,
                consumed,
            } => {
                write!(
                    f,
                    "size prefix says {announced} byte(s) but content is {consumed}"
                )
            }
            Self::TrailingBytes { count } => write!(f, "{count} unexpected trailing byte(s)"),
            Self::UndefinedPresenceBit { bit, why } => {
                write!(f, "presence bit {bit} is not defined by this revision: ")?;
                match why {
                    UndefinedBit::InRecord => write!(
                        f,
                        "the size of what a newer revision adds under it inside a nested \
                         record is unknown, so nothing after it can be decoded"
                    ),
                    UndefinedBit::BelowDefinedBit(k) => write!(
                        f,
                        "it lies below defined bit {k}, so a newer revision may place its \
                         field before known ones, whose positions are then unknown"
                    ),
                    UndefinedBit::RestField => write!(
                        f,
                        "the body ends with a field that runs to its end, which would \
                         swallow what a newer revision appends"
                    ),
                }
            }
            Self::MissingVariable { name } => write!(f, "no earlier field sets `{name}`"),
            Self::TooDeep { max } => write!(f, "records nested deeper than {max} levels"),
            Self::UndefinedValue { value } => write!(f, "undefined value {value}"),
            Self::UnknownCommandCode { code } => write!(f, "unknown command code 0x{code:04X}"),
            Self::TruncatedHeader { len } => {
                write!(f, "truncated header: {len} byte(s), a header needs 16")
            }
            Self::DataSizeMismatch { header, actual } => write!(
                f,
                "data size mismatch: header says {header} byte(s), {actual} follow the header"
            ),
        }
    }
}

impl fmt::Display for DecodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(m) = self.0.message {
            write!(f, "{m}: ")?;
        }
        write!(f, "{}", self.0.kind)?;
        if let Some((field, outer)) = self.0.path.split_first() {
            write!(f, " in field `{field}`")?;
            for o in outer {
                write!(f, " of `{o}`")?;
            }
        }
        // A command code is not a position in the body.
        if matches!(self.0.kind, DecodeErrorKind::UnknownCommandCode { .. }) {
            return Ok(());
        }
        write!(f, " at byte {}", self.0.offset)
    }
}

impl std::error::Error for DecodeError {}

/// Why a value could not be encoded.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum EncodeError {
    /// The output buffer is too small.
    #[error("buffer too small: needs {needed} byte(s), has {capacity}")]
    BufferTooSmall {
        /// Bytes needed so far.
        needed: usize,
        /// Buffer capacity.
        capacity: usize,
    },
    /// A list or blob has more elements than its count prefix can express.
    #[error("field `{field}`: {count} element(s) do not fit a count of at most {max}")]
    CountOverflow {
        /// Field path.
        field: &'static str,
        /// Elements present.
        count: usize,
        /// Largest count.
        max: usize,
    },
    /// A string or blob is longer than its fixed length.
    #[error("field `{field}`: {len} byte(s) exceed the fixed length {max}")]
    TooLong {
        /// Field path.
        field: &'static str,
        /// Length given.
        len: usize,
        /// Fixed length.
        max: usize,
    },
    /// A scaled value is beyond its field's limits, or NaN or infinite (see
    /// [`scale_to`](super::scale_to) for the exact rule; [`Encode::clamp_to_range`](super::Encode::clamp_to_range) saturates instead).
    #[error("{}", OutOfRangeText { scaled, value: *value, message: *message })]
    OutOfRange {
        /// The field, its limits and unit.
        scaled: &'static ScaledField,
        /// The value given.
        value: f64,
        /// The message being encoded, when the field belongs to a record inside it.
        message: Option<&'static str>,
    },
    /// A field depends on an earlier field (a count or flag) that was not encoded.
    #[error("field `{field}`: no earlier field sets `{name}`")]
    MissingVariable {
        /// Field path.
        field: &'static str,
        /// The variable name.
        name: &'static str,
    },
    /// A list's length disagrees with the field that carries its count.
    #[error("field `{field}`: {len} element(s) but `{count_field}` says {expected}")]
    CountMismatch {
        /// Field path.
        field: &'static str,
        /// Elements present.
        len: usize,
        /// The field holding the count.
        count_field: &'static str,
        /// Its value.
        expected: u64,
    },
    /// An optional field is present (or absent) against the flag that governs it.
    #[error("field `{field}`: presence disagrees with `{flag}` (the field must be {})", if *expected { "present" } else { "absent" })]
    PresenceMismatch {
        /// Field path.
        field: &'static str,
        /// The governing flag.
        flag: &'static str,
        /// Whether the field must be present.
        expected: bool,
    },
    /// A union's tag disagrees with the field that carries it.
    #[error("field `{field}`: the value is of type code {tag} but `{tag_field}` says {expected}")]
    TagMismatch {
        /// Field path.
        field: &'static str,
        /// Tag of the value.
        tag: u64,
        /// The field carrying the tag.
        tag_field: &'static str,
        /// Its value.
        expected: u64,
    },
    /// A NUL-terminated string contains a NUL.
    #[error("field `{field}`: a NUL-terminated string cannot contain NUL")]
    NulInText {
        /// Field path.
        field: &'static str,
    },
    /// A value does not fit the bits of its bit field.
    #[error("field `{field}`: value {value} does not fit in {width} bit(s)")]
    BitsOverflow {
        /// Field path.
        field: &'static str,
        /// The value.
        value: u64,
        /// Width of the bit field.
        width: u32,
    },
    /// A string holds a character outside ISO-8859-1.
    #[error("field `{field}`: character {ch:?} is not an 8-bit character")]
    NotLatin1 {
        /// Field path.
        field: &'static str,
        /// The character.
        ch: char,
    },
    /// A value built at run time (`jaus-dynamic`) is not of its field's type, or a
    /// field that is not optional is missing from it.
    #[error("field `{field}`: missing, or not a value of the field's type")]
    ValueKind {
        /// Field path.
        field: &'static str,
    },
    /// A whole message is larger than a body can be.
    #[error("message body of {len} byte(s) exceeds the maximum of {max}")]
    BodyTooLarge {
        /// Body length.
        len: usize,
        /// Maximum.
        max: usize,
    },
}

impl EncodeError {
    /// Attaches the message being encoded to an error in a field of a record inside it
    /// (the path of a message's own field already names the message).
    #[cold]
    pub fn in_message(mut self, name: &'static str) -> Self {
        if let Self::OutOfRange { message, .. } = &mut self {
            message.get_or_insert(name);
        }
        self
    }
}

/// `ReportGlobalPose.latitude: 129.5 outside [-90, 90] deg`, with `Message: ` in front
/// when the field belongs to a record inside the message.
struct OutOfRangeText<'a> {
    scaled: &'a ScaledField,
    value: f64,
    message: Option<&'static str>,
}

impl fmt::Display for OutOfRangeText<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = self.scaled;
        if let Some(m) = self.message {
            let own = s.field.strip_prefix(m).is_some_and(|r| r.starts_with('.'));
            if !own {
                write!(f, "{m}: ")?;
            }
        }
        let is = if self.value.is_nan() {
            "is not in"
        } else {
            "outside"
        };
        write!(f, "{}: {} {is} [{}, {}]", s.field, self.value, s.lo, s.hi)?;
        if !s.unit.is_empty() {
            write!(f, " {}", s.unit)?;
        }
        Ok(())
    }
}
