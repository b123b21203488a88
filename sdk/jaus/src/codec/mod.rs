//! The wire codec runtime: byte cursors, the [`Encode`]/[`Decode`] traits, scaled
//! integers and typed errors.
//!
//! The derive macros of `jaus-derive` expand to calls into this module; nothing here
//! knows about any particular message. Every read is bounds-checked and returns a
//! [`DecodeError`] that names the offending field and byte offset: no input makes a
//! decoder panic.
//!
//! All multi-byte values are little-endian (docs/wire.md §2.1).

mod cursor;
mod error;
mod lists;
mod scaled;
#[cfg(test)]
mod tests;
mod text;

/// Floats in JSON: finite values as numbers; non-finite ones as text, so that every value
/// decoded from the wire encodes back to the same bytes.
#[cfg(feature = "serde")]
pub mod serde_float;

pub use cursor::*;
pub use error::*;
pub use lists::*;
pub use scaled::*;
pub use text::*;

/// A value with a JAUS wire encoding.
pub trait Encode {
    /// Number of bytes [`Encode::encode`] writes.
    fn encoded_len(&self) -> usize;

    /// Writes the value.
    fn encode(&self, w: &mut Writer<'_>) -> Result<(), EncodeError>;

    /// The length of every encoding of this type when it never varies, else 0. The
    /// derive sets it for records made only of numbers and scaled values; lists of
    /// such records are then written through one bounds check.
    #[inline(always)]
    fn fixed_len() -> usize
    where
        Self: Sized,
    {
        0
    }

    /// Writes the value into `out`, which holds [`Encode::fixed_len`] bytes (used only
    /// when that is not 0); the same bytes and errors as [`Encode::encode`].
    #[inline]
    fn encode_fixed(&self, out: &mut [u8]) -> Result<(), EncodeError> {
        self.encode(&mut Writer::new(out))
    }

    /// Encodes into a new vector of exactly [`Encode::encoded_len`] bytes.
    fn to_bytes(&self) -> Result<Vec<u8>, EncodeError> {
        let mut out = vec![0u8; self.encoded_len()];
        let mut w = Writer::new(&mut out);
        self.encode(&mut w)?;
        debug_assert_eq!(w.position(), out.len(), "encoded_len disagrees with encode");
        Ok(out)
    }

    /// Clamps every scaled field of the value to its limits, through nested records,
    /// lists, optional fields and unions; NaN is left as it is (and stays an encode
    /// error). Encoding refuses a value beyond its field's limits
    /// ([`EncodeError::OutOfRange`], see [`scale_to`]); call this first to saturate
    /// instead. Values received are never clamped.
    ///
    /// The derives implement it for messages, records and unions; every other type
    /// has no scaled field and keeps this default, which does nothing.
    #[inline]
    fn clamp_to_range(&mut self) {}

    /// The value with every scaled field clamped to its limits
    /// ([`Encode::clamp_to_range`]).
    #[inline]
    fn clamped(mut self) -> Self
    where
        Self: Sized,
    {
        self.clamp_to_range();
        self
    }

    /// Leaves out every optional field whose presence bit is clear in
    /// `presence_vector` (sets it to `None`; a `flag` field to `false`): what a
    /// component does when a query's presence vector asks for some fields of its report.
    /// The derives implement it for messages and records with a presence vector; every
    /// other type has no optional field and keeps this default, which does nothing.
    ///
    /// ```
    /// use jaus::codec::Encode;
    /// use jaus::messages::ReportVelocityState;
    ///
    /// let mut r = ReportVelocityState { velocity_x: Some(1.0), yaw_rate: Some(0.5), ..Default::default() };
    /// r.keep_present(1 << 6); // the yaw rate only
    /// assert_eq!((r.velocity_x, r.yaw_rate), (None, Some(0.5)));
    /// ```
    #[inline]
    fn keep_present(&mut self, presence_vector: u64) {
        let _ = presence_vector;
    }
}

/// A value that can be read back from its JAUS wire encoding.
pub trait Decode: Sized {
    /// The fewest bytes any encoding of this type occupies (used to reject impossible
    /// element counts before allocating).
    const MIN_LEN: usize;

    /// Reads one value.
    fn decode(r: &mut Reader<'_>) -> Result<Self, DecodeError>;

    /// Decodes a whole buffer, failing if bytes are left over.
    #[inline]
    fn from_bytes(bytes: &[u8]) -> Result<Self, DecodeError> {
        let mut r = Reader::new(bytes);
        let v = Self::decode(&mut r)?;
        r.finish()?;
        Ok(v)
    }
}

macro_rules! primitive {
    ($($t:ty),*) => {$(
        impl Encode for $t {
            #[inline]
            fn encoded_len(&self) -> usize { std::mem::size_of::<$t>() }
            #[inline]
            fn encode(&self, w: &mut Writer<'_>) -> Result<(), EncodeError> {
                w.put(&self.to_le_bytes())
            }
        }
        impl Decode for $t {
            const MIN_LEN: usize = std::mem::size_of::<$t>();
            #[inline]
            fn decode(r: &mut Reader<'_>) -> Result<Self, DecodeError> {
                Ok(<$t>::from_le_bytes(r.array()?))
            }
        }
    )*};
}
primitive!(u8, u16, u32, u64, i8, i16, i32, i64, f32, f64);

/// Writes `bytes` at offset `at` of a chunk from [`Writer::chunk_mut`] (the derive's
/// offsets lie within it; with a constant offset the compiler removes every check).
#[inline(always)]
pub fn put_at<const N: usize, const K: usize>(chunk: &mut [u8; N], at: usize, bytes: [u8; K]) {
    if let Some(dst) = chunk.get_mut(at..).and_then(<[u8]>::first_chunk_mut::<K>) {
        *dst = bytes;
    }
}

/// True when `v` equals its type's default (used to omit zero reserved bits in JSON).
pub fn is_default<T: Default + PartialEq>(v: &T) -> bool {
    *v == T::default()
}
