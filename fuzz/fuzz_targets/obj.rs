//! The `obj` target: see `shadowlab_fuzz::obj`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| shadowlab_fuzz::obj(data));
