//! The closed convex polyhedron: vertices, faces as vertex loops, outward face planes; its measures
//! and its validator.
//!
//! Construction from a box or a frustum lives here; from points in [`crate::hull3`]; clipping and
//! intersection in [`crate::clip`]; extrusion toward a light in [`crate::extrude`].

use glam::{DAffine3, DVec3};
use robust::{Coord3D, orient3d};

use crate::aabb::Aabb;
use crate::error::{Degeneracy, HullError, ValidationError};
use crate::finite::{flush_tiny, rescale_for};
use crate::frustum::{FACE_CORNERS, Frustum};
use crate::mesh::{self, Face};
use crate::plane::Plane;
use crate::ray::Ray;
use crate::tolerance::{Scale, Tolerances, UNIT_LENGTH_TOLERANCE};

/// A body's volume and centroid, computed in coordinates multiplied by `factor`, the power of two
/// that brings the largest to about 1 (exact: no orientation changes, and nothing overflows or
/// underflows; coordinates below [`crate::finite::ORIENTATION_FLOOR`] of the largest are taken as
/// 0). Each fan tetrahedron's determinant is `robust::orient3d` of its face triangle and the
/// vertex mean: exact in sign, and in magnitude at least as accurate as the plain triple product
/// (its adaptive stages refine until the error bound is below the estimate). With the vertex mean
/// inside, every determinant is positive, so the sum is too. The naive `a · (b × c)` about the mean has an absolute error of
/// `~ε |a| |b| |c|`: for a sweep 2·10⁹ long and 1 thick (found by the hull fuzzer) that is ten
/// times the volume, and the sum came out negative.
struct Moments {
    /// Six times the volume in the rescaled coordinates: its sign is the volume's.
    scaled_six_volume: f64,
    /// The power of two the coordinates were multiplied by.
    factor: f64,
    /// The centroid of the solid, in world coordinates.
    centroid: DVec3,
}

impl Moments {
    /// The volume in world units (0 or ∞ where it underflows or overflows f64).
    fn volume(&self) -> f64 {
        self.scaled_six_volume / 6.0 / self.factor / self.factor / self.factor
    }
}

/// A closed convex polyhedron with an interior.
///
/// # Guarantees
/// Every value returned by this crate passes [`ConvexPolyhedron::validate`] with the tolerances it
/// was built with (debug builds assert it): at least 4 vertices and 4 faces; every face a loop of ≥ 3
/// distinct vertices winding counter-clockwise around its unit outward normal, its vertices on its
/// plane and every vertex inside every face plane (convexity, within the validation distance); every directed
/// edge has exactly one opposite (closed 2-manifold, consistently oriented, no T-junctions); the faces
/// around each vertex form one fan; V − E + F = 2; no two vertices within the snap distance; positive
/// volume. There is no empty or flat polyhedron: operations that can empty a body return `Option`.
#[derive(Clone, Debug, PartialEq)]
pub struct ConvexPolyhedron {
    vertices: Vec<DVec3>,
    faces: Vec<Face>,
}

impl ConvexPolyhedron {
    /// The box as a polyhedron (8 vertices indexed as [`Aabb::corners`], 6 faces in
    /// [`Aabb::planes`] order).
    ///
    /// # Errors
    /// [`HullError::ZeroSizeBox`] if the box is thinner than the snap distance on some axis.
    pub fn from_aabb(aabb: &Aabb, tolerances: &Tolerances) -> Result<Self, HullError> {
        let corners = aabb.corners();
        let snap = tolerances.snap_distance(Scale::of_points(&corners));
        for axis in 0..3 {
            if aabb.size()[axis] <= snap {
                return Err(HullError::ZeroSizeBox { axis });
            }
        }
        let faces = aabb
            .planes()
            .iter()
            .zip(FACE_CORNERS)
            .map(|(plane, corners)| Face::new(*plane, corners.to_vec()))
            .collect();
        let body = Self {
            vertices: corners.to_vec(),
            faces,
        };
        debug_assert_eq!(body.validate(tolerances), Ok(()));
        Ok(body)
    }

    /// The frustum as a polyhedron, with the frustum's own planes. Corners closer than the snap
    /// distance are merged: a perspective frustum whose near face is smaller than that (near → 0)
    /// becomes a pyramid with its apex at the eye.
    ///
    /// # Errors
    /// [`HullError::DegeneratePoints`] if the frustum is flat within the snap distance;
    /// [`HullError::InconsistentFrustum`] if its corners lie off its planes by more than the
    /// validation distance (a matrix so ill-conditioned that its inverse's corners and its rows'
    /// planes disagree; found by the hull fuzzer, 10 % off for corners spanning 3 to 3.6·10¹⁶).
    pub fn from_frustum(frustum: &Frustum, tolerances: &Tolerances) -> Result<Self, HullError> {
        let corners = frustum.corners();
        let faces = frustum
            .planes()
            .iter()
            .zip(FACE_CORNERS)
            .map(|(plane, loop_)| Face::new(*plane, oriented_loop(corners, &loop_, plane)))
            .collect();
        let snap = tolerances.snap_distance(frustum.scale());
        let body =
            Self::assemble(corners.to_vec(), faces, snap).ok_or(HullError::DegeneratePoints {
                degeneracy: Degeneracy::Coplanar,
            })?;
        body.validate(tolerances)
            .map_err(|_| HullError::InconsistentFrustum)?;
        Ok(body)
    }

    /// Builds a polyhedron from loops whose vertices may need merging: merges vertices within
    /// `merge_distance`, drops faces left with fewer than 3 vertices and unused vertices, then checks
    /// the topology and the volume. `None` if the result is not a closed convex solid.
    pub(crate) fn assemble(
        vertices: Vec<DVec3>,
        faces: Vec<Face>,
        merge_distance: f64,
    ) -> Option<Self> {
        let representative = mesh::merge_close(&vertices, merge_distance);
        let mut merged_faces = Vec::with_capacity(faces.len());
        for face in faces {
            let mut loop_: Vec<usize> = Vec::with_capacity(face.vertices.len());
            for &v in &face.vertices {
                let r = representative[v];
                if loop_.last() != Some(&r) {
                    loop_.push(r);
                }
            }
            while loop_.len() > 1 && loop_.first() == loop_.last() {
                loop_.pop();
            }
            if loop_.len() < 3 {
                continue;
            }
            let mut sorted = loop_.clone();
            sorted.sort_unstable();
            if sorted.windows(2).any(|w| w[0] == w[1]) {
                return None;
            }
            merged_faces.push(Face::new(face.plane, loop_));
        }
        let mut is_used = vec![false; vertices.len()];
        for face in &merged_faces {
            for &v in &face.vertices {
                is_used[v] = true;
            }
        }
        let mut new_index = vec![usize::MAX; vertices.len()];
        let mut used = Vec::new();
        for (old, vertex) in vertices.iter().enumerate() {
            if is_used[old] {
                new_index[old] = used.len();
                used.push(*vertex);
            }
        }
        for face in &mut merged_faces {
            for v in &mut face.vertices {
                *v = new_index[*v];
            }
        }
        if used.len() < 4 || merged_faces.len() < 4 {
            return None;
        }
        mesh::check_topology(used.len(), &merged_faces).ok()?;
        let body = Self {
            vertices: used,
            faces: merged_faces,
        };
        (body.moments().scaled_six_volume > 0.0).then_some(body)
    }

    /// Internal constructor for parts already known to be consistent.
    pub(crate) fn from_parts(vertices: Vec<DVec3>, faces: Vec<Face>) -> Self {
        Self { vertices, faces }
    }

    /// The vertices.
    #[must_use]
    pub fn vertices(&self) -> &[DVec3] {
        &self.vertices
    }

    /// The faces.
    #[must_use]
    pub fn faces(&self) -> &[Face] {
        &self.faces
    }

    /// The outward face planes; the body is their intersection.
    pub fn planes(&self) -> impl Iterator<Item = &Plane> {
        self.faces.iter().map(|f| &f.plane)
    }

    /// The number of edges (half the number of directed face edges).
    #[must_use]
    pub fn edge_count(&self) -> usize {
        self.faces.iter().map(|f| f.vertices.len()).sum::<usize>() / 2
    }

    /// The scale of the vertices, for tolerances.
    #[must_use]
    pub fn scale(&self) -> Scale {
        Scale::of_points(&self.vertices)
    }

    /// The volume (divergence theorem over a fan triangulation of each face, about the vertex
    /// mean, each tetrahedron's determinant by `robust::orient3d` on rescaled coordinates):
    /// positive whenever the vertex mean lies inside, even for bodies so thin and long that the
    /// plain sum of triple products loses every digit and its sign.
    #[must_use]
    pub fn volume(&self) -> f64 {
        self.moments().volume()
    }

    /// The centroid of the solid (not of the vertices).
    #[must_use]
    pub fn centroid(&self) -> DVec3 {
        self.moments().centroid
    }

    fn moments(&self) -> Moments {
        let largest = self
            .vertices
            .iter()
            .map(|v| v.abs().max_element())
            .fold(0.0_f64, f64::max);
        let factor = rescale_for(largest);
        let scaled = |v: DVec3| {
            let v = v * factor;
            Coord3D {
                x: flush_tiny(v.x),
                y: flush_tiny(v.y),
                z: flush_tiny(v.z),
            }
        };
        let reference = self.vertex_mean();
        let r = scaled(reference);
        let relative = |p: Coord3D<f64>| DVec3::new(p.x - r.x, p.y - r.y, p.z - r.z);
        let mut six_volume = 0.0;
        let mut weighted = DVec3::ZERO;
        for face in &self.faces {
            let a = scaled(self.vertices[face.vertices[0]]);
            for pair in face.vertices[1..].windows(2) {
                let (b, c) = (
                    scaled(self.vertices[pair[0]]),
                    scaled(self.vertices[pair[1]]),
                );
                let det = orient3d(a, b, c, r);
                six_volume += det;
                weighted += (relative(a) + relative(b) + relative(c)) * det;
            }
        }
        Moments {
            scaled_six_volume: six_volume,
            factor,
            centroid: reference + weighted / (4.0 * six_volume) / factor,
        }
    }

    /// The mean of the vertices (a point inside the body). Each vertex is divided by the count
    /// before summing, so the partial sums never exceed the largest coordinate: finite for every
    /// body (the plain sum of eight corners near 10³⁰⁸ overflows).
    #[must_use]
    pub fn vertex_mean(&self) -> DVec3 {
        let count = self.vertices.len() as f64;
        self.vertices.iter().map(|v| *v / count).sum::<DVec3>()
    }

    /// The axis-aligned bounds in world space.
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        Aabb::of_finite_points(self.vertices.iter().copied())
    }

    /// The axis-aligned bounds in another frame: of the vertices mapped by `world_to_frame` (e.g. a
    /// light-space transform; exact for affine maps since the body is the hull of its vertices).
    ///
    /// # Errors
    /// [`HullError::Overflow`] if a mapped vertex lies beyond f64's range.
    pub fn bounds_in(&self, world_to_frame: &DAffine3) -> Result<Aabb, HullError> {
        Aabb::of_computed_points(
            self.vertices
                .iter()
                .map(|v| world_to_frame.transform_point3(*v)),
            "bounds_in",
        )
    }

    /// `(min, max)` of `direction · x` over the body (the support function in both directions). With
    /// a unit view direction and the eye subtracted, this is the body's eye-depth range.
    #[must_use]
    pub fn extent_along(&self, direction: DVec3) -> (f64, f64) {
        self.vertices
            .iter()
            .map(|v| direction.dot(*v))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
                (lo.min(d), hi.max(d))
            })
    }

    /// Whether `point` lies inside every face plane, allowing `tolerance` outside.
    #[must_use]
    pub fn contains(&self, point: DVec3, tolerance: f64) -> bool {
        self.planes().all(|p| p.contains(point, tolerance))
    }

    /// The parameter interval `[t0, t1]` (`t0 ≥ 0`) over which `ray` lies in the body, if any
    /// (Cyrus–Beck clipping against the face planes, without tolerance).
    #[must_use]
    pub fn ray_interval(&self, ray: &Ray) -> Option<(f64, f64)> {
        let (mut t0, mut t1) = (0.0_f64, f64::INFINITY);
        for plane in self.planes() {
            let start = plane.signed_distance(ray.origin());
            let rate = plane.normal().dot(ray.direction());
            if rate == 0.0 {
                if start > 0.0 {
                    return None;
                }
            } else {
                let t = -start / rate;
                if rate > 0.0 {
                    t1 = t1.min(t);
                } else {
                    t0 = t0.max(t);
                }
            }
        }
        (t0 <= t1).then_some((t0, t1))
    }

    /// Checks every guarantee listed on [`ConvexPolyhedron`]. Geometric checks allow the validation
    /// distance of `tolerances` for this body's scale; the duplicate-vertex check uses the snap
    /// distance.
    ///
    /// # Errors
    /// The first broken invariant found.
    pub fn validate(&self, tolerances: &Tolerances) -> Result<(), ValidationError> {
        if self.vertices.len() < 4 {
            return Err(ValidationError::TooFew {
                what: "vertices",
                count: self.vertices.len(),
            });
        }
        if self.faces.len() < 4 {
            return Err(ValidationError::TooFew {
                what: "faces",
                count: self.faces.len(),
            });
        }
        if self.vertices.iter().any(|v| !v.is_finite()) {
            return Err(ValidationError::NonFinite);
        }
        for (index, face) in self.faces.iter().enumerate() {
            let mut sorted = face.vertices.clone();
            sorted.sort_unstable();
            if face.vertices.len() < 3
                || sorted.windows(2).any(|w| w[0] == w[1])
                || sorted.last().is_some_and(|&v| v >= self.vertices.len())
            {
                return Err(ValidationError::MalformedFace { face: index });
            }
            let normal = face.plane.normal();
            if !normal.is_finite() || !face.plane.offset().is_finite() {
                return Err(ValidationError::NonFinite);
            }
            if (normal.length() - 1.0).abs() > UNIT_LENGTH_TOLERANCE {
                return Err(ValidationError::NonUnitNormal { face: index });
            }
        }
        let scale = self.scale();
        let limit = tolerances.validation_distance(scale);
        for (index, face) in self.faces.iter().enumerate() {
            for &vertex in &face.vertices {
                let distance = face.plane.signed_distance(self.vertices[vertex]);
                if distance.abs() > limit {
                    return Err(ValidationError::NonPlanarFace {
                        face: index,
                        vertex,
                        distance,
                    });
                }
            }
            for (vertex, v) in self.vertices.iter().enumerate() {
                let distance = face.plane.signed_distance(*v);
                if distance > limit {
                    return Err(ValidationError::NotConvex {
                        face: index,
                        vertex,
                        distance,
                    });
                }
            }
            self.check_face_winding(index, limit)?;
        }
        mesh::check_topology(self.vertices.len(), &self.faces)?;
        if let Some((first, second)) =
            mesh::closest_pair_within(&self.vertices, tolerances.snap_distance(scale))
        {
            return Err(ValidationError::DuplicateVertex { first, second });
        }
        let volume = self.moments().scaled_six_volume;
        if volume.is_nan() || volume <= 0.0 {
            return Err(ValidationError::NotSolid);
        }
        Ok(())
    }

    /// The face loop's area vector (Newell's method about its centroid) points along the outward
    /// normal, within `limit` times its perimeter. Corners are not checked one by one: where a face
    /// plane is nearly parallel to a neighbour, a vertex within the snap distance in space can sit far
    /// off in the plane, so in-plane convexity is not a meaningful tolerance test; convexity in space
    /// is checked against every face plane instead.
    fn check_face_winding(&self, index: usize, limit: f64) -> Result<(), ValidationError> {
        let face = &self.faces[index];
        let n = face.vertices.len();
        let point = |k: usize| self.vertices[face.vertices[k % n]];
        let center = (0..n).map(point).sum::<DVec3>() / n as f64;
        let mut area = DVec3::ZERO;
        let mut perimeter = 0.0;
        for k in 0..n {
            let (a, b) = (point(k), point(k + 1));
            area += (a - center).cross(b - center);
            perimeter += (b - a).length();
        }
        if area.dot(face.plane.normal()) < -limit * perimeter {
            return Err(ValidationError::WrongWinding { face: index });
        }
        Ok(())
    }

    /// Checks that every point lies inside the body within the validation distance of `tolerances`
    /// (scaled to the body and the points together).
    ///
    /// # Errors
    /// [`ValidationError::PointOutside`] for the first point outside.
    pub fn validate_contains(
        &self,
        points: &[DVec3],
        tolerances: &Tolerances,
    ) -> Result<(), ValidationError> {
        let limit =
            tolerances.validation_distance(self.scale().max(Scale::of_points(points.iter())));
        for (point, p) in points.iter().enumerate() {
            let distance = self
                .planes()
                .map(|plane| plane.signed_distance(*p))
                .fold(f64::NEG_INFINITY, f64::max);
            if distance.is_nan() || distance > limit {
                return Err(ValidationError::PointOutside { point, distance });
            }
        }
        Ok(())
    }
}

/// The loop `corners[loop_]` oriented counter-clockwise around `plane`'s normal (Newell's area
/// vector decides; frusta built from a mirrored matrix, or with left-handed corner bits, flip).
fn oriented_loop(corners: &[DVec3; 8], loop_: &[usize; 4], plane: &Plane) -> Vec<usize> {
    let center = loop_.iter().map(|&i| corners[i]).sum::<DVec3>() / 4.0;
    let area: DVec3 = (0..4)
        .map(|k| (corners[loop_[k]] - center).cross(corners[loop_[(k + 1) % 4]] - center))
        .sum();
    let mut loop_ = loop_.to_vec();
    if area.dot(plane.normal()) < 0.0 {
        loop_.reverse();
    }
    loop_
}
