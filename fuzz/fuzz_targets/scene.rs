//! The `scene` target: see `shadowlab_fuzz::scene`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| shadowlab_fuzz::scene(data));
