//! Compile-time tests only: the cases are in `ui/`, run by `tests/ui.rs` (trybuild).
