//! The bodies of grainpack's fuzz targets, as plain functions of the input bytes.
//!
//! `fuzz_targets/*.rs` hand them to libFuzzer; `tests/fuzz_corpus.rs` at the
//! repository root replays the committed corpus through the same functions and feeds
//! them from proptest, so `cargo test` catches a regression without an instrumented
//! build. Each function panics only when a property fails (see `checks`).

#[path = "checks/mod.rs"]
pub mod checks;
