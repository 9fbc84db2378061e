#![no_main]
//! libFuzzer target: [`grainpack_fuzz::checks::scene_keys`].

libfuzzer_sys::fuzz_target!(|data: &[u8]| grainpack_fuzz::checks::scene_keys(data));
