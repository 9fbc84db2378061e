#![no_main]
//! libFuzzer target: [`grainpack_fuzz::checks::orientation_file`].

libfuzzer_sys::fuzz_target!(|data: &[u8]| grainpack_fuzz::checks::orientation_file(data));
