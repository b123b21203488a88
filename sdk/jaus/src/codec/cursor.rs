//! Byte cursors: [`Reader`] over a received body, [`Writer`] into a caller's buffer.

use super::lists::count_fits;
use super::{DecodeError, DecodeErrorKind, EncodeError};

/// A cursor over the bytes of one message body (or any part of it).
#[derive(Debug, Clone)]
pub struct Reader<'a> {
    buf: &'a [u8],
    pos: usize,
    /// Offset of `buf[0]` within the outermost buffer, so errors report absolute offsets.
    base: usize,
    /// Values of fields that later (possibly nested) fields depend on.
    vars: Vars,
    /// Nesting depth of records being decoded (bounded: recursive types such as task
    /// trees must not exhaust the stack on hostile input).
    depth: u16,
}

/// Deepest nesting of records a decoder accepts.
pub const MAX_DEPTH: u16 = 64;

/// Named integer values set while encoding/decoding, read by later fields: a count kept
/// in another field (`count_var`) or a flag deciding whether a nested field is present
/// (`present_if`). Small and fixed-size: no allocation.
#[derive(Debug, Clone, Copy, Default)]
pub struct Vars {
    names: [&'static str; 8],
    values: [u64; 8],
    len: usize,
}

impl Vars {
    /// Sets `name` (replacing an earlier value).
    #[inline]
    pub fn set(&mut self, name: &'static str, value: u64) {
        if let Some(i) = self.names[..self.len].iter().position(|n| *n == name) {
            self.values[i] = value;
        } else if self.len < self.names.len() {
            self.names[self.len] = name;
            self.values[self.len] = value;
            self.len += 1;
        } else {
            // Definitions never nest more than a few such fields; keep the newest.
            self.names.rotate_left(1);
            self.values.rotate_left(1);
            self.names[self.len - 1] = name;
            self.values[self.len - 1] = value;
        }
    }

    /// The value of `name`, if set.
    #[inline]
    pub fn get(&self, name: &'static str) -> Option<u64> {
        self.names[..self.len]
            .iter()
            .rposition(|n| *n == name)
            .map(|i| self.values[i])
    }
}

impl<'a> Reader<'a> {
    /// Starts reading at the first byte of `buf`.
    #[inline]
    pub fn new(buf: &'a [u8]) -> Self {
        Self {
            buf,
            pos: 0,
            base: 0,
            vars: Vars::default(),
            depth: 0,
        }
    }

    /// Variables set by fields decoded so far.
    #[inline]
    pub fn vars(&mut self) -> &mut Vars {
        &mut self.vars
    }

    /// Enters a nested record; fails beyond [`MAX_DEPTH`].
    #[inline]
    pub fn enter(&mut self) -> Result<(), DecodeError> {
        if self.depth >= MAX_DEPTH {
            return Err(DecodeError::new(
                DecodeErrorKind::TooDeep { max: MAX_DEPTH },
                self.offset(),
            ));
        }
        self.depth += 1;
        Ok(())
    }

    /// Leaves a nested record.
    #[inline]
    pub fn leave(&mut self) {
        self.depth = self.depth.saturating_sub(1);
    }

    /// The value of variable `name`, or a typed error if no earlier field set it.
    pub fn var(&self, name: &'static str) -> Result<u64, DecodeError> {
        self.vars.get(name).ok_or_else(|| {
            DecodeError::new(DecodeErrorKind::MissingVariable { name }, self.offset())
        })
    }

    /// Bytes not yet consumed.
    #[inline]
    pub fn remaining(&self) -> usize {
        self.buf.len() - self.pos
    }

    /// Absolute offset of the next byte to read.
    #[inline]
    pub fn offset(&self) -> usize {
        self.base + self.pos
    }

    /// Consumes exactly `n` bytes.
    #[inline]
    pub fn take(&mut self, n: usize) -> Result<&'a [u8], DecodeError> {
        match self.buf.get(self.pos..self.pos.saturating_add(n)) {
            Some(s) if n <= self.remaining() => {
                self.pos += n;
                Ok(s)
            }
            _ => Err(DecodeError::new(
                DecodeErrorKind::Truncated {
                    needed: n,
                    available: self.remaining(),
                },
                self.offset(),
            )),
        }
    }

    /// Consumes a fixed-size array.
    #[inline]
    pub fn array<const N: usize>(&mut self) -> Result<[u8; N], DecodeError> {
        // One bounds check on the hot path; the error is built out of line.
        match self.buf.get(self.pos..).and_then(<[u8]>::first_chunk::<N>) {
            Some(a) => {
                self.pos += N;
                Ok(*a)
            }
            None => Err(self.truncated(N)),
        }
    }

    #[cold]
    #[inline(never)]
    fn truncated(&self, needed: usize) -> DecodeError {
        DecodeError::new(
            DecodeErrorKind::Truncated {
                needed,
                available: self.remaining(),
            },
            self.offset(),
        )
    }

    /// The remaining bytes, without consuming them.
    #[inline]
    pub fn peek_rest(&self) -> &'a [u8] {
        &self.buf[self.pos..]
    }

    /// Consumes every remaining byte.
    #[inline]
    pub fn rest(&mut self) -> &'a [u8] {
        let s = &self.buf[self.pos..];
        self.pos = self.buf.len();
        s
    }

    /// Splits off a reader over the next `n` bytes (for size-prefixed fields) and
    /// advances past them.
    pub fn sub(&mut self, n: usize) -> Result<Reader<'a>, DecodeError> {
        let base = self.offset();
        let buf = self.take(n)?;
        Ok(Reader {
            buf,
            pos: 0,
            base,
            vars: self.vars,
            depth: self.depth,
        })
    }

    /// Checks a count kept in another field against the bytes left (elements take at
    /// least `min_elem` bytes each).
    pub fn check_count(&self, n: u64, min_elem: usize) -> Result<usize, DecodeError> {
        let n = usize::try_from(n).unwrap_or(usize::MAX);
        if !count_fits(n, min_elem, self.remaining()) {
            return Err(DecodeError::new(
                DecodeErrorKind::CountBeyondBuffer {
                    count: n,
                    remaining: self.remaining(),
                },
                self.offset(),
            ));
        }
        Ok(n)
    }

    /// Fails with [`DecodeErrorKind::TrailingBytes`] unless every byte was consumed.
    #[inline]
    pub fn finish(&self) -> Result<(), DecodeError> {
        if self.remaining() == 0 {
            Ok(())
        } else {
            Err(DecodeError::new(
                DecodeErrorKind::TrailingBytes {
                    count: self.remaining(),
                },
                self.offset(),
            ))
        }
    }
}

/// A cursor writing into a caller-provided buffer. Never reallocates.
#[derive(Debug)]
pub struct Writer<'a> {
    buf: &'a mut [u8],
    pos: usize,
    /// Set by the first field that publishes a variable: a body without such fields
    /// (most messages) never pays for clearing them.
    vars: Option<Vars>,
}

impl<'a> Writer<'a> {
    /// Starts writing at the first byte of `buf`.
    #[inline]
    pub fn new(buf: &'a mut [u8]) -> Self {
        Self {
            buf,
            pos: 0,
            vars: None,
        }
    }

    /// Variables set by fields encoded so far.
    #[inline]
    pub fn vars(&mut self) -> &mut Vars {
        self.vars.get_or_insert_with(Vars::default)
    }

    /// The value of variable `name`, or a typed error if no earlier field set it.
    pub fn var(&self, name: &'static str, field: &'static str) -> Result<u64, EncodeError> {
        self.vars
            .as_ref()
            .and_then(|v| v.get(name))
            .ok_or(EncodeError::MissingVariable { field, name })
    }

    /// Bytes written so far.
    #[inline]
    pub fn position(&self) -> usize {
        self.pos
    }

    /// Appends `bytes`.
    #[inline]
    pub fn put(&mut self, bytes: &[u8]) -> Result<(), EncodeError> {
        let end = self.pos + bytes.len();
        match self.buf.get_mut(self.pos..end) {
            Some(dst) => {
                dst.copy_from_slice(bytes);
                self.pos = end;
                Ok(())
            }
            None => Err(EncodeError::BufferTooSmall {
                needed: end,
                capacity: self.buf.len(),
            }),
        }
    }

    /// The next `N` bytes, to be written at constant offsets and then counted with
    /// [`Writer::advance`], or `None` when fewer than `N` bytes are left (the derive
    /// then writes field by field, which reports the field that does not fit). One
    /// bounds check for a run of fixed-size fields.
    #[inline]
    pub fn chunk_mut<const N: usize>(&mut self) -> Option<&mut [u8; N]> {
        self.buf
            .get_mut(self.pos..)
            .and_then(<[u8]>::first_chunk_mut::<N>)
    }

    /// Counts `n` more bytes as written (bytes written through [`Writer::chunk_mut`]);
    /// never beyond the end of the buffer.
    #[inline]
    pub fn advance(&mut self, n: usize) {
        self.pos = self.buf.len().min(self.pos.wrapping_add(n));
    }

    /// The next `N` bytes, counted as written, or `None` (and nothing counted) when
    /// fewer are left: [`Writer::chunk_mut`] then [`Writer::advance`] by `N`.
    #[inline]
    pub fn array_mut<const N: usize>(&mut self) -> Option<&mut [u8; N]> {
        let chunk = self
            .buf
            .get_mut(self.pos..)
            .and_then(<[u8]>::first_chunk_mut::<N>)?;
        self.pos += N;
        Some(chunk)
    }

    /// The next `n` bytes, counted as written, or `None` (and nothing counted) when
    /// fewer are left.
    #[inline]
    pub fn slice_mut(&mut self, n: usize) -> Option<&mut [u8]> {
        let end = self.pos.checked_add(n)?;
        let dst = self.buf.get_mut(self.pos..end)?;
        self.pos = end;
        Some(dst)
    }

    /// Appends `n` zero bytes (padding of fixed-length fields).
    pub fn zeros(&mut self, n: usize) -> Result<(), EncodeError> {
        let end = self.pos + n;
        match self.buf.get_mut(self.pos..end) {
            Some(dst) => {
                dst.fill(0);
                self.pos = end;
                Ok(())
            }
            None => Err(EncodeError::BufferTooSmall {
                needed: end,
                capacity: self.buf.len(),
            }),
        }
    }

    /// Reserves `n` bytes to be filled later with [`Writer::patch`]; returns their offset.
    pub fn reserve(&mut self, n: usize) -> Result<usize, EncodeError> {
        let at = self.pos;
        self.zeros(n)?;
        Ok(at)
    }

    /// Overwrites bytes previously reserved at `at`.
    pub fn patch(&mut self, at: usize, bytes: &[u8]) {
        self.buf[at..at + bytes.len()].copy_from_slice(bytes);
    }
}
