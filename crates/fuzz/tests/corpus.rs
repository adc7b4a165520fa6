//! Replays the committed corpus (`fuzz/corpus/<target>/`) through each target: what CI runs as the
//! fuzzers' smoke test on the stable toolchain. A target that panics on any file fails its test,
//! naming the files; a missing or empty corpus fails too.

use std::fs;
use std::panic::{self, AssertUnwindSafe};
use std::path::{Path, PathBuf};

/// Runs every file of `fuzz/corpus/<name>/` through `target`.
fn replay(name: &str, target: fn(&[u8])) {
    let directory = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/corpus")
        .join(name);
    let mut files: Vec<PathBuf> = fs::read_dir(&directory)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", directory.display()))
        .map(|entry| entry.expect("a directory entry").path())
        .collect();
    files.sort();
    assert!(!files.is_empty(), "{} holds no corpus", directory.display());
    let failed: Vec<String> = files
        .iter()
        .filter(|file| {
            let data = fs::read(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
            panic::catch_unwind(AssertUnwindSafe(|| target(&data))).is_err()
        })
        .map(|file| file.display().to_string())
        .collect();
    assert!(
        failed.is_empty(),
        "{name}: {} of {} inputs panicked: {failed:?}",
        failed.len(),
        files.len()
    );
}

#[test]
fn obj_corpus() {
    replay("obj", shadowlab_fuzz::obj);
}

#[test]
fn scene_corpus() {
    replay("scene", shadowlab_fuzz::scene);
}

#[test]
fn cli_corpus() {
    replay("cli", shadowlab_fuzz::cli);
}

#[test]
fn raster_corpus() {
    replay("raster", shadowlab_fuzz::raster);
}

#[test]
fn hull_corpus() {
    replay("hull", shadowlab_fuzz::hull);
}
