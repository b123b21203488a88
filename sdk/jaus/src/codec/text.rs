//! Strings and blobs. JAUS strings are 8-bit characters; they are decoded as
//! ISO-8859-1 so that every byte sequence maps to a `String` and back losslessly.

use super::{DecodeError, DecodeErrorKind, EncodeError, Reader, Writer};

/// Converts wire bytes to a string (ISO-8859-1).
pub fn latin1_to_string(bytes: &[u8]) -> String {
    if bytes.is_ascii() {
        // ASCII is valid UTF-8.
        String::from_utf8(bytes.to_vec()).unwrap_or_default()
    } else {
        bytes.iter().map(|&b| b as char).collect()
    }
}

/// Number of wire bytes of `s` (one per character).
pub fn latin1_len(s: &str) -> usize {
    if s.is_ascii() {
        s.len()
    } else {
        s.chars().count()
    }
}

/// `s` made to fit a fixed-length string field of `len` bytes: at most `len`
/// characters, those above U+00FF (which ISO-8859-1 cannot carry) replaced by `?`.
/// For text a component chooses itself (names, descriptions), which should be cut
/// rather than make its report fail to encode.
pub fn fit_latin1(s: &str, len: usize) -> String {
    s.chars()
        .take(len)
        .map(|c| if u32::from(c) <= 0xFF { c } else { '?' })
        .collect()
}

/// Writes `s` as ISO-8859-1, failing on characters above U+00FF.
pub fn put_latin1(w: &mut Writer<'_>, s: &str, field: &'static str) -> Result<(), EncodeError> {
    if s.is_ascii() {
        return w.put(s.as_bytes());
    }
    for c in s.chars() {
        let b = u8::try_from(u32::from(c)).map_err(|_| EncodeError::NotLatin1 { field, ch: c })?;
        w.put(&[b])?;
    }
    Ok(())
}

/// Writes a fixed-length, NUL-padded string field.
pub fn put_fixed_string(
    w: &mut Writer<'_>,
    s: &str,
    len: usize,
    field: &'static str,
) -> Result<(), EncodeError> {
    let n = latin1_len(s);
    if n > len {
        return Err(EncodeError::TooLong {
            field,
            len: n,
            max: len,
        });
    }
    put_latin1(w, s, field)?;
    w.zeros(len - n)
}

/// Reads a fixed-length string field, stopping at the first NUL. With `accept_short`,
/// a body that ends early yields the bytes that are there.
pub fn get_fixed_string(
    r: &mut Reader<'_>,
    len: usize,
    accept_short: bool,
) -> Result<String, DecodeError> {
    let n = if accept_short {
        len.min(r.remaining())
    } else {
        len
    };
    let raw = r.take(n)?;
    let end = raw.iter().position(|&b| b == 0).unwrap_or(raw.len());
    Ok(latin1_to_string(&raw[..end]))
}

/// Writes a fixed-length blob, zero padded.
pub fn put_fixed_bytes(
    w: &mut Writer<'_>,
    b: &[u8],
    len: usize,
    field: &'static str,
) -> Result<(), EncodeError> {
    if b.len() > len {
        return Err(EncodeError::TooLong {
            field,
            len: b.len(),
            max: len,
        });
    }
    w.put(b)?;
    w.zeros(len - b.len())
}

/// Writes a NUL-terminated string (the text may not contain NUL).
pub fn put_cstring(w: &mut Writer<'_>, s: &str, field: &'static str) -> Result<(), EncodeError> {
    if s.contains('\0') {
        return Err(EncodeError::NulInText { field });
    }
    put_latin1(w, s, field)?;
    w.put(&[0])
}

/// Reads a NUL-terminated string.
pub fn get_cstring(r: &mut Reader<'_>) -> Result<String, DecodeError> {
    let at = r.offset();
    let rest = r.peek_rest();
    let Some(end) = rest.iter().position(|&b| b == 0) else {
        return Err(DecodeError::new(
            DecodeErrorKind::Truncated {
                needed: rest.len() + 1,
                available: rest.len(),
            },
            at,
        ));
    };
    let text = latin1_to_string(&rest[..end]);
    r.take(end + 1)?;
    Ok(text)
}

/// Reads a string that runs to the end of the body; trailing NULs are dropped.
pub fn get_rest_string(r: &mut Reader<'_>) -> String {
    let raw = r.rest();
    let end = raw.iter().rposition(|&b| b != 0).map_or(0, |i| i + 1);
    latin1_to_string(&raw[..end])
}
