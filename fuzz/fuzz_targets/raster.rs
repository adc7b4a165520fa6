//! The `raster` target: see `shadowlab_fuzz::raster`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| shadowlab_fuzz::raster(data));
