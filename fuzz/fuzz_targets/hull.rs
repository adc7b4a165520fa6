//! The `hull` target: see `shadowlab_fuzz::hull`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| shadowlab_fuzz::hull(data));
