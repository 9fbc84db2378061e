#![no_main]
//! libFuzzer target: [`grainpack_fuzz::checks::scene_bytes`].

libfuzzer_sys::fuzz_target!(|data: &[u8]| grainpack_fuzz::checks::scene_bytes(data));
