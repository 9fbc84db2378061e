#![no_main]
//! libFuzzer target: [`grainpack_fuzz::checks::measured_table`].

libfuzzer_sys::fuzz_target!(|data: &[u8]| grainpack_fuzz::checks::measured_table(data));
