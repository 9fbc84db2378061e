#![no_main]
//! libFuzzer target: [`grainpack_fuzz::checks::contact_bits_2d`].

libfuzzer_sys::fuzz_target!(|data: &[u8]| grainpack_fuzz::checks::contact_bits_2d(data));
