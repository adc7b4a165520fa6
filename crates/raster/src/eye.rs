//! Resolving an eye pass: from the visible triangle of each pixel to the perspective-correct world
//! position and normal of the point it sees.

use glam::{DMat4, DVec3};
use rayon::prelude::*;

use crate::error::RasterError;
use crate::pipeline::Triangles;
use crate::target::{EyeTarget, NO_TRIANGLE};
use crate::vertex::transform;

/// Per-pixel data for shading, row-major with row 0 at the bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct EyeImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Window depth as stored (1 where nothing is visible).
    pub depth: Vec<f64>,
    /// The visible triangle ([`NO_TRIANGLE`] where none).
    pub triangle: Vec<u32>,
    /// World position of the visible point at the pixel centre (zero where none).
    pub position: Vec<DVec3>,
    /// Unit world normal there, interpolated from the vertex normals (zero where none, or where the
    /// interpolated normal vanishes).
    pub normal: Vec<DVec3>,
}

impl EyeTarget {
    /// Resolves this eye pass. `mesh` and `clip_from_world` must be those it was drawn with;
    /// `normals` holds one normal per position.
    ///
    /// The barycentric coordinates of a pixel centre are perspective-correct: with the triangle's
    /// clip-space columns `A = (x, y, w)₀`, `B`, `C` and the centre `p = (x_ndc, y_ndc, 1)`, they are
    /// `(B×C·p, C×A·p, A×B·p)` normalised to sum 1 (the world point maps linearly to clip space, so
    /// these are its barycentrics on the triangle). Computed in f64 from the original triangle, also
    /// for pixels drawn by a clipped piece of it.
    pub fn resolve(
        &self,
        mesh: Triangles<'_>,
        normals: &[DVec3],
        clip_from_world: &DMat4,
    ) -> Result<EyeImage, RasterError> {
        let (positions, triangles) = (mesh.positions(), mesh.triangles());
        if normals.len() != positions.len() {
            return Err(RasterError::NormalCount {
                normals: normals.len(),
                positions: positions.len(),
            });
        }
        let size = self.size();
        let (width, height) = (size.width() as usize, size.height() as usize);
        let depth = self.depths();
        let triangle = self.triangles();
        // Filled by the workers, not `vec!` (docs/CONVENTIONS.md, "Large buffers").
        let zeros =
            || -> Vec<DVec3> { rayon::iter::repeat_n(DVec3::ZERO, width * height).collect() };
        let (mut position, mut normal) = (zeros(), zeros());
        let (fw, fh) = (width as f64, height as f64);
        position
            .par_chunks_mut(width)
            .zip(normal.par_chunks_mut(width))
            .zip(triangle.par_chunks(width))
            .enumerate()
            .for_each(|(j, ((positions_row, normals_row), ids))| {
                let y = (j as f64 + 0.5) / fh * 2.0 - 1.0;
                let mut cached: Option<(u32, [DVec3; 3])> = None;
                for (i, &id) in ids.iter().enumerate() {
                    if id == NO_TRIANGLE {
                        continue;
                    }
                    let Some(&[a, b, c]) = triangles.get(id as usize) else {
                        continue;
                    };
                    let rows = match cached {
                        Some((cached_id, rows)) if cached_id == id => rows,
                        _ => {
                            let clip = [a, b, c].map(|v| {
                                let q = transform(clip_from_world, positions[v as usize]);
                                DVec3::new(q.x, q.y, q.w)
                            });
                            let rows = [
                                clip[1].cross(clip[2]),
                                clip[2].cross(clip[0]),
                                clip[0].cross(clip[1]),
                            ];
                            cached = Some((id, rows));
                            rows
                        }
                    };
                    let p = DVec3::new((i as f64 + 0.5) / fw * 2.0 - 1.0, y, 1.0);
                    let u = DVec3::new(rows[0].dot(p), rows[1].dot(p), rows[2].dot(p));
                    let sum = u.x + u.y + u.z;
                    if sum == 0.0 || !sum.is_finite() {
                        continue;
                    }
                    let l = u / sum;
                    let [pa, pb, pc] = [a, b, c].map(|v| positions[v as usize]);
                    let [na, nb, nc] = [a, b, c].map(|v| normals[v as usize]);
                    positions_row[i] = pa * l.x + pb * l.y + pc * l.z;
                    normals_row[i] = (na * l.x + nb * l.y + nc * l.z).normalize_or_zero();
                }
            });
        Ok(EyeImage {
            width: size.width(),
            height: size.height(),
            depth,
            triangle,
            position,
            normal,
        })
    }
}
