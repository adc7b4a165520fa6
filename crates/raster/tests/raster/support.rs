//! Meshes and helpers shared by the tests. Every random choice comes from a seeded generator.

use glam::{DMat4, DVec3};
use shadowlab_raster::{Fragment, RasterOptions, Rasterizer, TargetSize, Triangles};

/// A small deterministic generator (SplitMix64), so tests need no randomness crate and every
/// sequence is fixed by its seed.
pub(crate) struct Rng(u64);

impl Rng {
    pub(crate) fn new(seed: u64) -> Self {
        Self(seed)
    }

    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub(crate) fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform integer in [0, n).
    pub(crate) fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }
}

/// A mesh given directly in clip space with w = 1 (NDC), drawn with the identity matrix.
#[derive(Clone, Debug, Default)]
pub(crate) struct Mesh {
    pub(crate) positions: Vec<DVec3>,
    pub(crate) triangles: Vec<[u32; 3]>,
}

impl Mesh {
    pub(crate) fn triangles(&self) -> Triangles<'_> {
        Triangles::new(&self.positions, &self.triangles)
    }

    pub(crate) fn vertex(&mut self, p: DVec3) -> u32 {
        self.positions.push(p);
        u32::try_from(self.positions.len() - 1).expect("small mesh")
    }
}

/// The NDC coordinate of window coordinate `window` on a side of `size` pixels (exact for
/// power-of-two sizes and dyadic windows).
pub(crate) fn ndc(window: f64, size: u32) -> f64 {
    window / f64::from(size) * 2.0 - 1.0
}

/// The smallest cell, in pixels, whose vertices [`jittered_grid`] may move to pixel centres. The
/// move is at most half a pixel per axis, within the fifth of a cell per axis that the jitter keeps
/// to (so quads stay convex) once cells are 2.5 pixels wide; smaller cells could fold the grid.
pub(crate) const CENTRE_SNAP_MIN_CELL: f64 = 2.5;

/// A jittered grid of `cells × cells` quads covering `[-extent, extent]²` in NDC, each split along
/// a random diagonal, with random winding. Interior vertices are jittered on the 1/256-pixel grid
/// of a `size × size` target; where cells are at least [`CENTRE_SNAP_MIN_CELL`] pixels wide, some
/// are put exactly on pixel centres, so edges pass through centres.
pub(crate) fn jittered_grid(rng: &mut Rng, cells: usize, extent: f64, size: u32) -> Mesh {
    let mut mesh = Mesh::default();
    let n = cells + 1;
    let step = 2.0 * extent / cells as f64;
    let pixel = 2.0 / f64::from(size);
    for row in 0..n {
        for column in 0..n {
            let (mut x, mut y) = (-extent + step * column as f64, -extent + step * row as f64);
            let interior = row > 0 && row < n - 1 && column > 0 && column < n - 1;
            if interior {
                let centre_snap = step / pixel >= CENTRE_SNAP_MIN_CELL;
                match rng.below(if centre_snap { 3 } else { 2 }) + u64::from(!centre_snap) {
                    // Exactly on a pixel centre near the grid point.
                    0 => {
                        x = ndc(((x + 1.0) / pixel).floor() + 0.5, size);
                        y = ndc(((y + 1.0) / pixel).floor() + 0.5, size);
                    }
                    // Jittered by up to a fifth of a cell (quads stay convex), on the 1/256-pixel grid.
                    _ => {
                        let jitter = |rng: &mut Rng| {
                            ((rng.unit() - 0.5) * step / 2.5 / pixel * 256.0).round() / 256.0
                                * pixel
                        };
                        x += jitter(rng);
                        y += jitter(rng);
                    }
                }
            }
            let z = 0.5 * rng.unit() - 0.25;
            mesh.vertex(DVec3::new(x, y, z));
        }
    }
    let index = |r: usize, c: usize| u32::try_from(r * n + c).expect("small");
    for row in 0..cells {
        for column in 0..cells {
            let (a, b, c, d) = (
                index(row, column),
                index(row, column + 1),
                index(row + 1, column + 1),
                index(row + 1, column),
            );
            let quads = if rng.below(2) == 0 {
                [[a, b, c], [a, c, d]]
            } else {
                [[a, b, d], [b, c, d]]
            };
            for mut t in quads {
                if rng.below(2) == 0 {
                    t.swap(1, 2);
                }
                mesh.triangles.push(t);
            }
        }
    }
    mesh
}

/// How many times each pixel (row-major, row 0 at the bottom) is covered, without a depth test.
pub(crate) fn coverage(size: TargetSize, mesh: &Mesh, m: &DMat4) -> Vec<u32> {
    let mut counts = vec![0u32; size.width() as usize * size.height() as usize];
    let mut raster = Rasterizer::new(RasterOptions::default());
    raster
        .for_each_fragment(size, mesh.triangles(), m, |f: Fragment| {
            counts[f.y as usize * size.width() as usize + f.x as usize] += 1;
        })
        .expect("valid mesh");
    counts
}

/// Which triangle covers each pixel (`u32::MAX` for none), panicking on a pixel covered twice.
pub(crate) fn owners(size: TargetSize, mesh: &Mesh, m: &DMat4) -> Vec<u32> {
    let mut owner = vec![u32::MAX; size.width() as usize * size.height() as usize];
    let mut raster = Rasterizer::new(RasterOptions::default());
    raster
        .for_each_fragment(size, mesh.triangles(), m, |f: Fragment| {
            let slot = &mut owner[f.y as usize * size.width() as usize + f.x as usize];
            assert_eq!(*slot, u32::MAX, "pixel ({}, {}) covered twice", f.x, f.y);
            *slot = f.triangle;
        })
        .expect("valid mesh");
    owner
}

/// FNV-1a over bytes: a stable hash for comparing outputs.
pub(crate) fn fnv1a(bytes: impl IntoIterator<Item = u8>) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}
