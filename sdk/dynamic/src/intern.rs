//! Names and scaled-field limits with a `'static` lifetime, as the SDK's codec runtime
//! takes them (`Vars` keys, field paths of errors, `ScaledField`).
//!
//! Each distinct value is allocated once per process and kept: loading the same
//! definitions again reuses what an earlier load interned, so the memory held is
//! bounded by the distinct names of the definition sets a process loads.

use jaus::codec::ScaledField;
use std::collections::{HashMap, HashSet};
use std::sync::{Mutex, OnceLock, PoisonError};

/// `s` with a `'static` lifetime.
pub(crate) fn name(s: &str) -> &'static str {
    static NAMES: OnceLock<Mutex<HashSet<&'static str>>> = OnceLock::new();
    let mut set = NAMES
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(PoisonError::into_inner);
    if let Some(n) = set.get(s) {
        return n;
    }
    let n: &'static str = Box::leak(s.to_owned().into_boxed_str());
    set.insert(n);
    n
}

/// The scaled field `field` with limits `[lo, hi]` and `unit`, with a `'static`
/// lifetime.
pub(crate) fn scaled(field: &str, lo: f64, hi: f64, unit: &str) -> &'static ScaledField {
    type Key = (&'static str, u64, u64, &'static str);
    static FIELDS: OnceLock<Mutex<HashMap<Key, &'static ScaledField>>> = OnceLock::new();
    let (field, unit) = (name(field), name(unit));
    let key = (field, lo.to_bits(), hi.to_bits(), unit);
    let mut map = FIELDS
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(PoisonError::into_inner);
    map.entry(key).or_insert_with(|| {
        Box::leak(Box::new(ScaledField {
            field,
            lo,
            hi,
            unit,
        }))
    })
}
