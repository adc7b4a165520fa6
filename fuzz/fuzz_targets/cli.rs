//! The `cli` target: see `shadowlab_fuzz::cli`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| shadowlab_fuzz::cli(data));
