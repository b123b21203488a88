//! Decoding and encoding a fixed-size message makes no heap allocation.
//!
//! A counting global allocator wraps the system allocator; the counter is per thread
//! so that the test harness's own threads do not disturb it.

use jaus::codec::{Decode, Encode, Writer};
use jaus::messages::{ReportGlobalPose, SetGlobalPathSegment, SetWrenchEffort};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    static ALLOCS: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: every method forwards to `System` with the caller's arguments unchanged, so
// `System`'s guarantees hold; the only addition is a thread-local counter update, which
// neither allocates (const-initialised `Cell`) nor touches the memory handed out.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCS.try_with(|c| c.set(c.get() + 1));
        // SAFETY: forwarded unchanged; the caller upholds `alloc`'s contract.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` came from `System.alloc` with this `layout` (via `alloc` above).
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let _ = ALLOCS.try_with(|c| c.set(c.get() + 1));
        // SAFETY: forwarded unchanged; `ptr`/`layout` come from this allocator.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations(f: impl FnOnce()) -> usize {
    let before = ALLOCS.with(Cell::get);
    f();
    ALLOCS.with(Cell::get) - before
}

fn body(hex: &str) -> Vec<u8> {
    jaus::hex::decode(hex).unwrap()[16..].to_vec()
}

#[test]
fn fixed_size_messages_decode_and_encode_without_allocating() {
    let pose = body(jaus::json::REFERENCE_PACKETS[0].1);
    let wrench = body(jaus::json::REFERENCE_PACKETS[1].1);
    let segment = body(jaus::json::REFERENCE_PACKETS[2].1);
    let mut out = [0u8; 64];

    let n = allocations(|| {
        for _ in 0..100 {
            let p = ReportGlobalPose::from_bytes(std::hint::black_box(&pose)).unwrap();
            let w = SetWrenchEffort::from_bytes(std::hint::black_box(&wrench)).unwrap();
            let s = SetGlobalPathSegment::from_bytes(std::hint::black_box(&segment)).unwrap();
            p.encode(&mut Writer::new(&mut out)).unwrap();
            w.encode(&mut Writer::new(&mut out)).unwrap();
            s.encode(&mut Writer::new(&mut out)).unwrap();
            std::hint::black_box((&p, &w, &s, &out));
        }
    });
    assert_eq!(
        n, 0,
        "decoding/encoding fixed-size messages allocated {n} time(s)"
    );

    // The counter does count: a Vec allocates.
    assert!(allocations(|| drop(std::hint::black_box(vec![1u8; 10]))) > 0);
}
