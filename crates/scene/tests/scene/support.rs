//! Shared test helpers.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use glam::DVec3;
use proptest::test_runner::{Config, RngAlgorithm, RngSeed};
use shadowlab_scene::Mesh;

/// The seed of every property test (the bytes of "scene" as a number): each run checks the same
/// cases.
pub(crate) const SEED: u64 = 0x73_63_65_6e_65;

/// A proptest configuration with a fixed seed, no failure persistence and `cases` cases.
pub(crate) fn config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(SEED),
        rng_algorithm: RngAlgorithm::ChaCha,
        failure_persistence: None,
        ..Config::default()
    }
}

/// A temporary directory holding the OBJ and scene files written by a test.
pub(crate) struct ObjDir(tempfile::TempDir);

impl ObjDir {
    pub(crate) fn new() -> Self {
        Self(tempfile::tempdir().expect("a temporary directory"))
    }

    /// The directory.
    pub(crate) fn path(&self) -> &Path {
        self.0.path()
    }

    /// Writes `text` to `name` in the directory and returns its path.
    pub(crate) fn write(&self, name: &str, text: &str) -> PathBuf {
        let path = self.0.path().join(name);
        std::fs::write(&path, text).expect("write a test file");
        path
    }
}

/// The path of a file of the repository's `data/` directory, e.g. `data_path("scenes/bunny.toml")`.
pub(crate) fn data_path(relative: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(relative)
}

/// Identifies a position by its exact bits, so that vertices split for their normals compare equal.
fn key(p: DVec3) -> [u64; 3] {
    p.to_array().map(f64::to_bits)
}

/// Directed edges between positions (by exact bits), counted.
fn directed_edges(mesh: &Mesh) -> BTreeMap<([u64; 3], [u64; 3]), usize> {
    let mut edges = BTreeMap::new();
    for t in 0..mesh.triangle_count() {
        let corners = mesh.triangle_positions(t).map(key);
        for k in 0..3 {
            *edges.entry((corners[k], corners[(k + 1) % 3])).or_default() += 1;
        }
    }
    edges
}

/// Whether the mesh is closed and consistently oriented: every edge (between positions) is
/// traversed exactly once in each direction, i.e. shared by exactly two triangles of opposite
/// orientation. Returns the first offending edge, if any.
pub(crate) fn first_open_edge(mesh: &Mesh) -> Option<(DVec3, DVec3)> {
    let edges = directed_edges(mesh);
    let point = |k: [u64; 3]| DVec3::from_array(k.map(f64::from_bits));
    edges.iter().find_map(|(&(a, b), &count)| {
        (count != 1 || edges.get(&(b, a)) != Some(&1)).then(|| (point(a), point(b)))
    })
}

/// Asserts that `actual` is within `relative` of `expected` (relative to |expected|).
pub(crate) fn assert_close(actual: f64, expected: f64, relative: f64, what: &str) {
    let error = (actual - expected).abs();
    assert!(
        error <= relative * expected.abs(),
        "{what}: {actual} differs from {expected} by {error} \
         (relative {:.3e}, allowed {relative:.1e})",
        error / expected.abs()
    );
}

/// Asserts that every normal of the mesh has unit length to within a few ulps.
pub(crate) fn assert_unit_normals(mesh: &Mesh) {
    for (i, n) in mesh.normals().iter().enumerate() {
        assert!(
            (n.length() - 1.0).abs() <= 4.0 * f64::EPSILON,
            "normal {i} = {n} has length {}",
            n.length()
        );
    }
}
