//! Defects the fuzz targets found (`fuzz/README.md`), each a test named after what
//! broke, with the input that showed it, in one file per part of the crate.

#[path = "fuzz_regressions/bounds.rs"]
mod bounds;
#[path = "fuzz_regressions/corrector.rs"]
mod corrector;
#[path = "fuzz_regressions/overlap.rs"]
mod overlap;
#[path = "fuzz_regressions/robust.rs"]
mod robust;
#[path = "fuzz_regressions/scale.rs"]
mod scale;
#[path = "fuzz_regressions/scale_2d.rs"]
mod scale_2d;
#[path = "fuzz_regressions/scenes.rs"]
mod scenes;
