//! Shared test support: seeded configuration and generators, meshes, and the brute-force
//! reference. Every random choice comes from a fixed seed.

use std::collections::HashMap;

use glam::DVec3;
use proptest::test_runner::{Config, RngSeed};
use shadowlab_trace::{Bvh, Hit, Ray};

/// A reproducible proptest configuration: a fixed seed (documented at each use), no persistence of
/// failures (a failing case becomes a named regression test instead).
pub(crate) fn config(seed: u64, cases: u32) -> Config {
    Config {
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        cases,
        ..Config::default()
    }
}

/// A small deterministic generator (SplitMix64), for geometry derived from a proptest seed.
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
        (self.next_u64() >> 11) as f64 / (1_u64 << 53) as f64
    }

    /// Uniform in [lo, hi).
    pub(crate) fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform integer in [lo, hi].
    pub(crate) fn int(&mut self, lo: i64, hi: i64) -> i64 {
        let span = u64::try_from(hi - lo + 1).expect("lo <= hi");
        lo + i64::try_from(self.next_u64() % span).expect("below the span")
    }

    /// Uniform index in [0, len).
    pub(crate) fn index(&mut self, len: usize) -> usize {
        let len = u64::try_from(len).expect("fits u64");
        usize::try_from(self.next_u64() % len).expect("below len")
    }

    /// A point uniform in the cube [−1, 1]³.
    pub(crate) fn cube_point(&mut self) -> DVec3 {
        DVec3::new(
            self.range(-1.0, 1.0),
            self.range(-1.0, 1.0),
            self.range(-1.0, 1.0),
        )
    }

    /// A uniform unit vector.
    pub(crate) fn direction(&mut self) -> DVec3 {
        let z = self.range(-1.0, 1.0);
        let a = std::f64::consts::TAU * self.unit();
        let r = (1.0 - z * z).sqrt();
        DVec3::new(r * a.cos(), r * a.sin(), z)
    }
}

/// Positions and index triples.
#[derive(Clone, Debug, Default)]
pub(crate) struct Mesh {
    pub(crate) positions: Vec<DVec3>,
    pub(crate) triangles: Vec<[u32; 3]>,
}

impl Mesh {
    pub(crate) fn bvh(&self) -> Bvh {
        Bvh::new(&self.positions, &self.triangles).expect("valid test mesh")
    }

    /// Every undirected edge used by two or more triangles, as vertex pairs (lower index first),
    /// in a deterministic order.
    pub(crate) fn shared_edges(&self) -> Vec<[u32; 2]> {
        let mut uses: HashMap<[u32; 2], usize> = HashMap::new();
        for t in &self.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *uses.entry([a.min(b), a.max(b)]).or_default() += 1;
            }
        }
        let mut shared: Vec<[u32; 2]> = uses
            .into_iter()
            .filter(|&(_, n)| n >= 2)
            .map(|(e, _)| e)
            .collect();
        shared.sort_unstable();
        shared
    }

    /// Applies `f` to every position.
    pub(crate) fn map(mut self, f: impl Fn(DVec3) -> DVec3) -> Self {
        for p in &mut self.positions {
            *p = f(*p);
        }
        self
    }
}

/// A closed UV sphere of `rings` latitude bands and `segments` longitudes, outward and
/// counter-clockwise, centred at the origin.
pub(crate) fn uv_sphere(rings: u32, segments: u32, radius: f64) -> Mesh {
    let mut mesh = Mesh::default();
    mesh.positions.push(DVec3::new(0.0, 0.0, radius));
    for r in 1..rings {
        let polar = std::f64::consts::PI * f64::from(r) / f64::from(rings);
        for s in 0..segments {
            let azimuth = std::f64::consts::TAU * f64::from(s) / f64::from(segments);
            mesh.positions.push(
                DVec3::new(
                    polar.sin() * azimuth.cos(),
                    polar.sin() * azimuth.sin(),
                    polar.cos(),
                ) * radius,
            );
        }
    }
    mesh.positions.push(DVec3::new(0.0, 0.0, -radius));
    let south = u32::try_from(mesh.positions.len() - 1).expect("small");
    let ring = |r: u32, s: u32| 1 + (r - 1) * segments + s % segments;
    for s in 0..segments {
        mesh.triangles.push([0, ring(1, s), ring(1, s + 1)]);
        mesh.triangles
            .push([south, ring(rings - 1, s + 1), ring(rings - 1, s)]);
    }
    for r in 1..rings - 1 {
        for s in 0..segments {
            let (a, b, c, d) = (
                ring(r, s),
                ring(r + 1, s),
                ring(r + 1, s + 1),
                ring(r, s + 1),
            );
            mesh.triangles.push([a, b, c]);
            mesh.triangles.push([a, c, d]);
        }
    }
    mesh
}

/// The closed surface of the cube [−1, 1]³ with every face an `n × n` grid (vertices at
/// multiples of 2/n: exact for powers of two), welded along the cube's edges, outward; diagonals
/// alternate in a checkerboard so that vertices have 4 to 8 triangles around them.
pub(crate) fn tessellated_cube(n: i32) -> Mesh {
    let mut mesh = Mesh::default();
    let mut index: HashMap<[i32; 3], u32> = HashMap::new();
    let step = 2.0 / f64::from(n);
    let mut vertex = |mesh: &mut Mesh, c: [i32; 3]| {
        *index.entry(c).or_insert_with(|| {
            mesh.positions.push(DVec3::new(
                f64::from(c[0]) * step - 1.0,
                f64::from(c[1]) * step - 1.0,
                f64::from(c[2]) * step - 1.0,
            ));
            u32::try_from(mesh.positions.len() - 1).expect("small")
        })
    };
    // Each face: the fixed axis, its level (0 or n), and the two in-face axes ordered so that
    // (u, v, outward) is right-handed.
    for (axis, level) in [(0, 0), (0, n), (1, 0), (1, n), (2, 0), (2, n)] {
        let (mut a, mut b) = ((axis + 1) % 3, (axis + 2) % 3);
        if level == 0 {
            std::mem::swap(&mut a, &mut b);
        }
        for i in 0..n {
            for j in 0..n {
                let corner = |di: i32, dj: i32| {
                    let mut c = [0; 3];
                    c[axis] = level;
                    c[a] = i + di;
                    c[b] = j + dj;
                    c
                };
                let p00 = vertex(&mut mesh, corner(0, 0));
                let p10 = vertex(&mut mesh, corner(1, 0));
                let p11 = vertex(&mut mesh, corner(1, 1));
                let p01 = vertex(&mut mesh, corner(0, 1));
                if (i + j) % 2 == 0 {
                    mesh.triangles.push([p00, p10, p11]);
                    mesh.triangles.push([p00, p11, p01]);
                } else {
                    mesh.triangles.push([p00, p10, p01]);
                    mesh.triangles.push([p10, p11, p01]);
                }
            }
        }
    }
    mesh
}

/// An `n × n` height field over [0, n]² with jittered vertices: x, y moved by up to 12/64 and
/// heights in [−1/2, 1/2], all multiples of 1/64 (so sums and differences of nearby points are
/// exact); each cell split along a random diagonal. Vertex `(i, j)` has index `i·(n + 1) + j`.
pub(crate) fn jittered_grid(n: u32, seed: u64) -> Mesh {
    let mut rng = Rng::new(seed);
    let mut mesh = Mesh::default();
    let jitter = |rng: &mut Rng, limit: i64| rng.int(-limit, limit) as f64 / 64.0;
    for i in 0..=n {
        for j in 0..=n {
            let dx = if i == 0 || i == n {
                0.0
            } else {
                jitter(&mut rng, 12)
            };
            let dy = if j == 0 || j == n {
                0.0
            } else {
                jitter(&mut rng, 12)
            };
            mesh.positions.push(DVec3::new(
                f64::from(i) + dx,
                f64::from(j) + dy,
                jitter(&mut rng, 32),
            ));
        }
    }
    let v = |i: u32, j: u32| i * (n + 1) + j;
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
            if rng.next_u64().is_multiple_of(2) {
                mesh.triangles.push([a, b, c]);
                mesh.triangles.push([a, c, d]);
            } else {
                mesh.triangles.push([a, b, d]);
                mesh.triangles.push([b, c, d]);
            }
        }
    }
    mesh
}

/// `count` independent triangles with vertices uniform in [−1, 1]³ (a soup: no shared edges).
pub(crate) fn soup(count: usize, rng: &mut Rng) -> Mesh {
    let mut mesh = Mesh::default();
    for _ in 0..count {
        let base = u32::try_from(mesh.positions.len()).expect("small");
        let center = rng.cube_point();
        for _ in 0..3 {
            mesh.positions.push(center + rng.cube_point() * 0.4);
        }
        mesh.triangles.push([base, base + 1, base + 2]);
    }
    mesh
}

/// The brute-force closest hit: [`Bvh::intersect_triangle`] over every triangle, smallest `t`,
/// then smallest index.
pub(crate) fn brute_closest(bvh: &Bvh, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for i in 0..bvh.triangle_count() {
        let i = u32::try_from(i).expect("small");
        if let Some(hit) = bvh.intersect_triangle(ray, i, t_min, t_max)
            && best.is_none_or(|b| hit.t < b.t)
        {
            best = Some(hit);
        }
    }
    best
}

/// The brute-force any-hit query.
pub(crate) fn brute_occluded(bvh: &Bvh, ray: &Ray, t_min: f64, t_max: f64) -> bool {
    (0..bvh.triangle_count()).any(|i| {
        bvh.intersect_triangle(ray, u32::try_from(i).expect("small"), t_min, t_max)
            .is_some()
    })
}

/// Runs `f` on a fresh rayon pool of `threads` threads.
pub(crate) fn with_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
        .install(f)
}
