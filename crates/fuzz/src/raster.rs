//! The rasterizer target: arbitrary triangles and matrices into small targets.

use arbitrary::{Arbitrary, Unstructured};
use glam::DVec3;
use shadowlab_raster::{
    CullMode, DepthCompare, DepthFormat, DepthPairTarget, DepthTarget, DrawStats, EyeTarget,
    NO_TRIANGLE, RasterOptions, Rasterizer, TargetSize, Triangles, image_out,
};

use crate::num::{Matrix, Num, V3};

/// The largest side tried: three 64-pixel tiles and a part, so inputs stay fast.
const MAX_SIDE: u8 = 160;

/// A vertex index: mostly small (in range for small meshes), sometimes any value.
#[derive(Clone, Copy, Debug, Arbitrary)]
enum Index {
    Small(u8),
    Any(u32),
}

impl Index {
    fn get(self) -> u32 {
        match self {
            Self::Small(i) => u32::from(i),
            Self::Any(i) => i,
        }
    }
}

/// Which target a draw goes to.
#[derive(Clone, Copy, Debug, Arbitrary)]
enum Kind {
    Depth,
    Pair,
    /// An eye target, resolved with normals afterwards: one per position, or one too many.
    Eye {
        extra_normal: bool,
    },
    Fragments,
}

/// One fuzz input.
#[derive(Debug, Arbitrary)]
struct Input {
    kind: Kind,
    /// Sides are `side % (MAX_SIDE + 1)`: 0 is a refused size.
    width: u8,
    height: u8,
    format: u8,
    compare: u8,
    cull: u8,
    /// What a depth target is cleared to before the first draw, if anything.
    clear: Option<Num>,
    /// Draws into the same target with the same rasterizer (its scratch memory reused).
    draws: Vec<Draw>,
    /// Whether to encode the last depth image as PNG, NPY and EXR.
    encode: bool,
}

/// One draw call.
#[derive(Debug, Arbitrary)]
struct Draw {
    matrix: Matrix,
    positions: Vec<V3>,
    triangles: Vec<[Index; 3]>,
    normals: Vec<V3>,
}

/// See [`crate::raster`].
pub(crate) fn raster(data: &[u8]) {
    let Ok(input) = Input::arbitrary_take_rest(Unstructured::new(data)) else {
        return;
    };
    let side = |s: u8| u32::from(s % (MAX_SIDE + 1));
    let (width, height) = (side(input.width), side(input.height));
    let format = DepthFormat::ALL[usize::from(input.format) % DepthFormat::ALL.len()];
    let options = RasterOptions {
        compare: COMPARES[usize::from(input.compare) % COMPARES.len()],
        cull: [CullMode::None, CullMode::Back, CullMode::Front][usize::from(input.cull) % 3],
    };
    let mut rasterizer = Rasterizer::new(options);
    let depths = match input.kind {
        Kind::Depth => {
            let Ok(mut target) = DepthTarget::new(width, height, format) else {
                return;
            };
            // NaN is not tried: `clear(NaN)` stores NaN in the reversed-f32 format (found by this
            // target and reported, docs/fuzzing.md); every other value is.
            if let Some(depth) = input.clear.map(Num::get).filter(|z| !z.is_nan()) {
                target.clear(depth);
            }
            for draw in &input.draws {
                let (positions, triangles) = draw.mesh();
                let mesh = Triangles::new(&positions, &triangles);
                check_stats(rasterizer.draw_depth(&mut target, mesh, &draw.matrix.get()));
            }
            assert_eq!(target.keys().len(), pixels(width, height));
            target.depths()
        }
        Kind::Pair => {
            let Ok(mut target) = DepthPairTarget::new(width, height, format) else {
                return;
            };
            for draw in &input.draws {
                let (positions, triangles) = draw.mesh();
                let mesh = Triangles::new(&positions, &triangles);
                check_stats(rasterizer.draw_depth_pair(&mut target, mesh, &draw.matrix.get()));
            }
            let (nearest, second) = (target.nearest(), target.second());
            for (n, s) in nearest.iter().zip(&second) {
                assert!(n <= s, "the nearest depth {n} lies behind the second {s}");
            }
            nearest
        }
        Kind::Eye { extra_normal } => {
            let Ok(mut target) = EyeTarget::new(width, height, format) else {
                return;
            };
            let mut most_triangles = 0;
            for draw in &input.draws {
                let (positions, triangles) = draw.mesh();
                let mesh = Triangles::new(&positions, &triangles);
                if check_stats(rasterizer.draw_eye(&mut target, mesh, &draw.matrix.get())) {
                    most_triangles = most_triangles.max(triangles.len());
                }
            }
            let ids = target.triangles();
            assert_eq!(ids.len(), pixels(width, height));
            assert!(
                ids.iter()
                    .all(|&id| id == NO_TRIANGLE || (id as usize) < most_triangles),
                "triangle ids index a draw's triangles"
            );
            // `resolve` needs the mesh and matrix the target was drawn with: one draw only.
            if let [draw] = input.draws.as_slice() {
                let (positions, triangles) = draw.mesh();
                let mut normals: Vec<DVec3> = draw.normals.iter().map(|n| n.get()).collect();
                normals.resize(positions.len() + usize::from(extra_normal), DVec3::Y);
                let mesh = Triangles::new(&positions, &triangles);
                if let Ok(image) = target.resolve(mesh, &normals, &draw.matrix.get()) {
                    assert_eq!(image.position.len(), pixels(width, height));
                }
            }
            target.depths()
        }
        Kind::Fragments => {
            let Ok(size) = TargetSize::new(width, height) else {
                return;
            };
            for draw in &input.draws {
                let (positions, triangles) = draw.mesh();
                let mesh = Triangles::new(&positions, &triangles);
                let count = triangles.len();
                let result = rasterizer.for_each_fragment(size, mesh, &draw.matrix.get(), |f| {
                    assert!(f.x < width && f.y < height, "fragment outside: {f:?}");
                    assert!(
                        (f.triangle as usize) < count,
                        "fragment of no triangle: {f:?}"
                    );
                });
                check_stats(result);
            }
            return;
        }
    };
    assert_eq!(depths.len(), pixels(width, height));
    for z in &depths {
        assert!((0.0..=1.0).contains(z), "stored depth {z} outside [0, 1]");
    }
    if input.encode {
        for encoded in [
            image_out::depth_png16(&depths, width, height),
            image_out::depth_npy(&depths, width, height),
            image_out::depth_exr(&depths, width, height),
        ] {
            assert!(
                encoded.is_ok_and(|bytes| !bytes.is_empty()),
                "encoding failed"
            );
        }
    }
}

/// Every depth compare.
const COMPARES: [DepthCompare; 8] = [
    DepthCompare::Never,
    DepthCompare::Less,
    DepthCompare::Equal,
    DepthCompare::LessEqual,
    DepthCompare::Greater,
    DepthCompare::NotEqual,
    DepthCompare::GreaterEqual,
    DepthCompare::Always,
];

impl Draw {
    /// The draw's positions and index triples.
    fn mesh(&self) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let positions = self.positions.iter().map(|p| p.get()).collect();
        let triangles = self.triangles.iter().map(|t| t.map(Index::get)).collect();
        (positions, triangles)
    }
}

/// `width × height` as a length.
fn pixels(width: u32, height: u32) -> usize {
    width as usize * height as usize
}

/// Checks what `DrawStats` documents: every triangle counted exactly once. Returns whether the
/// draw succeeded.
fn check_stats(result: Result<DrawStats, shadowlab_raster::RasterError>) -> bool {
    let Ok(stats) = result else {
        return false;
    };
    assert_eq!(
        stats.triangles,
        stats.drawn + stats.degenerate + stats.culled + stats.empty + stats.outside + stats.clipped,
        "every triangle is counted once: {stats:?}"
    );
    true
}
