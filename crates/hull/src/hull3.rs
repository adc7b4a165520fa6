//! The 3-D convex hull of a point set: quickhull with exact orientation tests.
//!
//! # Algorithm
//! 1. Points within the snap distance of an earlier point (in lexicographic order) are dropped, so the
//!    hull's vertices are pairwise farther apart than the snap distance, and every dropped point lies
//!    within it of a kept one.
//! 2. A first tetrahedron is chosen from extreme points; if the points are coincident, collinear or
//!    coplanar within the snap distance, the result is [`HullError::DegeneratePoints`] naming which.
//! 3. Quickhull (Barber, Dobkin & Huhdanpaa 1996): each face keeps the points strictly above it; the
//!    farthest is added, the faces it sees strictly are replaced by a fan to their horizon, and their
//!    points are handed to the new faces. "Strictly above" is `robust::orient3d` (Shewchuk's
//!    adaptive-exact predicate), evaluated on the points rescaled by a power of two (an exact
//!    operation: no sign changes, no underflow or overflow for tiny or huge coordinates). Translation,
//!    which would round, is deliberately not applied.
//! 4. Adjacent triangles that are exactly coplanar (orient3d = 0) are merged into one face, and
//!    vertices left on only two faces (exactly on an edge, so not extreme) are removed.
//!
//! The result's vertices are exactly (bit for bit) input points, the extreme points of the deduplicated
//! set; nearly coplanar faces stay separate faces, since each is a true face of the exact hull.

use std::collections::HashMap;

use glam::DVec3;
use robust::{Coord3D, orient3d};

use crate::area::loop_normal;
use crate::error::{Degeneracy, HullError};
use crate::finite::{flush_tiny, rescale_for};
use crate::mesh::Face;
use crate::plane::Plane;
use crate::polyhedron::ConvexPolyhedron;
use crate::tolerance::{Scale, Tolerances, distance};

impl ConvexPolyhedron {
    /// The convex hull of `points`, by quickhull with exact predicates.
    ///
    /// Points within the snap distance of an earlier point (lexicographic order) are dropped; a set
    /// coincident, collinear or coplanar within the snap distance is an error naming which. Every
    /// "is this point above this face" is `robust::orient3d` (exact) on the points rescaled by a
    /// power of two (exact; no translation, which would round). Exactly coplanar adjacent triangles
    /// are merged into one face and vertices left on only two faces dropped, so the vertices are
    /// exactly (bit for bit) the extreme input points; nearly coplanar faces stay separate, each a
    /// true face of the exact hull.
    ///
    /// # Errors
    /// [`HullError::NonFinite`] naming `points`; [`HullError::DegeneratePoints`] if the points are
    /// empty, coincident, collinear or coplanar within the snap distance.
    pub fn from_points(points: &[DVec3], tolerances: &Tolerances) -> Result<Self, HullError> {
        if points.iter().any(|p| !p.is_finite()) {
            return Err(HullError::NonFinite {
                parameter: "points",
            });
        }
        let snap = tolerances.snap_distance(Scale::of_points(points));
        hull_with_snap(points, snap, tolerances)
    }
}

/// The hull of finite `points` with a given snap distance.
pub(crate) fn hull_with_snap(
    points: &[DVec3],
    snap: f64,
    tolerances: &Tolerances,
) -> Result<ConvexPolyhedron, HullError> {
    let kept = deduplicate(points, snap);
    let degenerate = |degeneracy| Err(HullError::DegeneratePoints { degeneracy });
    if kept.is_empty() {
        return degenerate(Degeneracy::Empty);
    }
    let p: Vec<DVec3> = kept.iter().map(|&i| points[i]).collect();
    let largest = p
        .iter()
        .map(|v| v.abs().max_element())
        .fold(0.0_f64, f64::max);
    let factor = rescale_for(largest);
    let scaled: Vec<Coord3D<f64>> = p
        .iter()
        .map(|v| Coord3D {
            x: flush_tiny(v.x * factor),
            y: flush_tiny(v.y * factor),
            z: flush_tiny(v.z * factor),
        })
        .collect();
    // The flatness tests measure lengths, cross products and distances: on the rescaled points
    // (an exact scaling, with the snap distance scaled alike), so tiny or huge coordinates neither
    // underflow nor overflow.
    let rescaled: Vec<DVec3> = scaled.iter().map(|c| DVec3::new(c.x, c.y, c.z)).collect();
    let rescaled_snap = snap * factor;
    let Some(simplex) = initial_simplex(&rescaled, rescaled_snap) else {
        let degeneracy = if p.len() == 1 {
            Degeneracy::Coincident
        } else {
            classify_flat(&rescaled, rescaled_snap)
        };
        return degenerate(degeneracy);
    };
    let mut hull = Quickhull::new(scaled, simplex);
    hull.run();
    let body = hull.into_polyhedron(&p);
    debug_assert_eq!(body.validate(tolerances), Ok(()));
    Ok(body)
}

/// Indices of the points kept after dropping each point within `snap` of an earlier kept one (in
/// lexicographic order).
fn deduplicate(points: &[DVec3], snap: f64) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| {
        let (p, q) = (points[a], points[b]);
        p.x.total_cmp(&q.x)
            .then(p.y.total_cmp(&q.y))
            .then(p.z.total_cmp(&q.z))
            .then(a.cmp(&b))
    });
    let mut kept: Vec<usize> = Vec::with_capacity(points.len());
    for &i in &order {
        let p = points[i];
        let duplicate = kept
            .iter()
            .rev()
            .take_while(|&&k| p.x - points[k].x <= snap)
            .any(|&k| distance(points[k], p) <= snap);
        if !duplicate {
            kept.push(i);
        }
    }
    kept
}

/// Four points spanning a tetrahedron thicker than `snap`, chosen as extreme points, or `None`.
fn initial_simplex(p: &[DVec3], snap: f64) -> Option<[usize; 4]> {
    let argmax = |f: &dyn Fn(DVec3) -> f64| -> (usize, f64) {
        p.iter()
            .enumerate()
            .map(|(i, v)| (i, f(*v)))
            .fold(
                (0, f64::NEG_INFINITY),
                |best, c| if c.1 > best.1 { c } else { best },
            )
    };
    let a = 0;
    let (b, ab) = argmax(&|v| v.distance(p[a]));
    if ab <= snap {
        return None;
    }
    let axis = (p[b] - p[a]) / ab;
    let (c, from_line) = argmax(&|v| (v - p[a]).cross(axis).length());
    if from_line <= snap {
        return None;
    }
    let normal = (p[b] - p[a]).cross(p[c] - p[a]).normalize();
    let (d, from_plane) = argmax(&|v| (v - p[a]).dot(normal).abs());
    (from_plane > snap).then_some([a, b, c, d])
}

/// Which flat degeneracy the (more than one) points have.
fn classify_flat(p: &[DVec3], snap: f64) -> Degeneracy {
    let far = p.iter().map(|v| v.distance(p[0])).fold(0.0, f64::max);
    if far <= snap {
        return Degeneracy::Coincident;
    }
    let b = p.iter().copied().fold(p[0], |best, v| {
        if v.distance(p[0]) > best.distance(p[0]) {
            v
        } else {
            best
        }
    });
    let axis = (b - p[0]).normalize();
    let off_line = p
        .iter()
        .map(|v| (*v - p[0]).cross(axis).length())
        .fold(0.0, f64::max);
    if off_line > snap {
        Degeneracy::Coplanar
    } else {
        Degeneracy::Collinear
    }
}

/// A hull triangle: vertices counter-clockwise seen from outside; `neighbor[k]` is across the edge
/// `vertices[k] → vertices[k + 1]`; `outside` holds the points strictly above it.
struct Triangle {
    vertices: [usize; 3],
    neighbor: [usize; 3],
    alive: bool,
    outside: Vec<usize>,
}

struct Quickhull {
    points: Vec<Coord3D<f64>>,
    triangles: Vec<Triangle>,
    pending: Vec<usize>,
    /// Per-triangle marks for the visibility search: the epoch in which it was found visible or not.
    visible_mark: Vec<u64>,
    hidden_mark: Vec<u64>,
    epoch: u64,
}

impl Quickhull {
    fn new(points: Vec<Coord3D<f64>>, simplex: [usize; 4]) -> Self {
        let [a, mut b, mut c, d] = simplex;
        // Make (a, b, c) counter-clockwise seen from outside: d below it.
        if orient3d(points[a], points[b], points[c], points[d]) < 0.0 {
            std::mem::swap(&mut b, &mut c);
        }
        let faces = [[a, b, c], [a, d, b], [b, d, c], [c, d, a]];
        let mut hull = Self {
            points,
            triangles: Vec::new(),
            pending: Vec::new(),
            visible_mark: Vec::new(),
            hidden_mark: Vec::new(),
            epoch: 0,
        };
        for vertices in faces {
            hull.push_triangle(vertices, [usize::MAX; 3]);
        }
        for t in 0..4 {
            for k in 0..3 {
                let (from, to) = hull.edge(t, k);
                let across = (0..4)
                    .find(|&u| u != t && (0..3).any(|j| hull.edge(u, j) == (to, from)))
                    .expect("a tetrahedron's faces are pairwise adjacent");
                hull.triangles[t].neighbor[k] = across;
            }
        }
        for i in 0..hull.points.len() {
            if simplex.contains(&i) {
                continue;
            }
            if let Some(t) = (0..4).find(|&t| hull.above(t, i) < 0.0) {
                hull.triangles[t].outside.push(i);
            }
        }
        hull.pending = (0..4).collect();
        hull
    }

    fn push_triangle(&mut self, vertices: [usize; 3], neighbor: [usize; 3]) -> usize {
        self.triangles.push(Triangle {
            vertices,
            neighbor,
            alive: true,
            outside: Vec::new(),
        });
        self.visible_mark.push(0);
        self.hidden_mark.push(0);
        self.triangles.len() - 1
    }

    fn edge(&self, t: usize, k: usize) -> (usize, usize) {
        let v = self.triangles[t].vertices;
        (v[k], v[(k + 1) % 3])
    }

    /// `orient3d` of triangle `t` and point `i`: negative iff `i` is strictly above (outside) `t`.
    fn above(&self, t: usize, i: usize) -> f64 {
        let [a, b, c] = self.triangles[t].vertices;
        orient3d(
            self.points[a],
            self.points[b],
            self.points[c],
            self.points[i],
        )
    }

    fn run(&mut self) {
        while let Some(t) = self.pending.pop() {
            if !self.triangles[t].alive || self.triangles[t].outside.is_empty() {
                continue;
            }
            // The farthest point above t (orient3d is proportional to the distance for a fixed t).
            let eye = self.triangles[t]
                .outside
                .iter()
                .copied()
                .map(|i| (i, self.above(t, i)))
                .fold(
                    (usize::MAX, 0.0),
                    |best, c| if c.1 < best.1 { c } else { best },
                )
                .0;
            self.add_point(t, eye);
        }
    }

    fn add_point(&mut self, start: usize, eye: usize) {
        self.epoch += 1;
        let epoch = self.epoch;
        let mut visible = vec![start];
        self.visible_mark[start] = epoch;
        let mut horizon: Vec<(usize, usize, usize)> = Vec::new();
        let mut k = 0;
        while k < visible.len() {
            let t = visible[k];
            k += 1;
            for j in 0..3 {
                let n = self.triangles[t].neighbor[j];
                if self.visible_mark[n] == epoch {
                    continue;
                }
                let hidden = self.hidden_mark[n] == epoch || {
                    let seen = self.above(n, eye) < 0.0;
                    if seen {
                        self.visible_mark[n] = epoch;
                        visible.push(n);
                    } else {
                        self.hidden_mark[n] = epoch;
                    }
                    !seen
                };
                if hidden {
                    let (from, to) = self.edge(t, j);
                    horizon.push((from, to, n));
                }
            }
        }
        let mut orphans = Vec::new();
        for &t in &visible {
            let triangle = &mut self.triangles[t];
            triangle.alive = false;
            orphans.append(&mut triangle.outside);
        }
        // A fan from the eye to each horizon edge (from, to), keeping the removed faces' winding.
        let mut starting_at = HashMap::with_capacity(horizon.len());
        let mut ending_at = HashMap::with_capacity(horizon.len());
        let mut fan = Vec::with_capacity(horizon.len());
        for &(from, to, across) in &horizon {
            let t = self.push_triangle([from, to, eye], [across, usize::MAX, usize::MAX]);
            let slot = (0..3)
                .find(|&j| self.edge(across, j) == (to, from))
                .expect("the hidden neighbour shares the horizon edge");
            self.triangles[across].neighbor[slot] = t;
            starting_at.insert(from, t);
            ending_at.insert(to, t);
            fan.push(t);
        }
        for &t in &fan {
            let [from, to, _] = self.triangles[t].vertices;
            self.triangles[t].neighbor[1] = starting_at[&to];
            self.triangles[t].neighbor[2] = ending_at[&from];
        }
        for i in orphans {
            if i == eye {
                continue;
            }
            if let Some(&t) = fan.iter().find(|&&t| self.above(t, i) < 0.0) {
                self.triangles[t].outside.push(i);
            }
        }
        self.pending.extend(
            fan.iter()
                .filter(|&&t| !self.triangles[t].outside.is_empty()),
        );
    }

    /// Merges exactly coplanar neighbours, drops non-extreme vertices and maps indices back to the
    /// original points `p`.
    fn into_polyhedron(self, p: &[DVec3]) -> ConvexPolyhedron {
        let alive: Vec<usize> = (0..self.triangles.len())
            .filter(|&t| self.triangles[t].alive)
            .collect();
        let mut group: Vec<usize> = (0..self.triangles.len()).collect();
        fn root(group: &mut [usize], mut i: usize) -> usize {
            while group[i] != i {
                group[i] = group[group[i]];
                i = group[i];
            }
            i
        }
        for &t in &alive {
            for k in 0..3 {
                let n = self.triangles[t].neighbor[k];
                let opposite = self.triangles[n]
                    .vertices
                    .into_iter()
                    .find(|v| !self.triangles[t].vertices.contains(v))
                    .expect("neighbouring hull triangles share exactly one edge");
                if self.above(t, opposite) == 0.0 {
                    let (a, b) = (root(&mut group, t), root(&mut group, n));
                    group[a.max(b)] = a.min(b);
                }
            }
        }
        let roots: Vec<usize> = (0..group.len()).map(|t| root(&mut group, t)).collect();
        let mut members: Vec<Vec<usize>> = Vec::new();
        let mut slot_of_root = HashMap::new();
        for &t in &alive {
            let r = roots[t];
            let slot = *slot_of_root.entry(r).or_insert_with(|| {
                members.push(Vec::new());
                members.len() - 1
            });
            members[slot].push(t);
        }
        // Each group's boundary, chained into one loop.
        let mut loops: Vec<Vec<usize>> = members
            .iter()
            .map(|ts| {
                let mut next = HashMap::new();
                for &t in ts {
                    for k in 0..3 {
                        let n = self.triangles[t].neighbor[k];
                        if roots[n] != roots[t] {
                            let (from, to) = self.edge(t, k);
                            next.insert(from, to);
                        }
                    }
                }
                let start = *next.keys().min().expect("a face has a boundary");
                let mut loop_ = vec![start];
                let mut v = next[&start];
                while v != start {
                    loop_.push(v);
                    v = next[&v];
                }
                loop_
            })
            .collect();
        let mut face_count = vec![0_usize; p.len()];
        for loop_ in &loops {
            for &v in loop_ {
                face_count[v] += 1;
            }
        }
        for loop_ in &mut loops {
            loop_.retain(|&v| face_count[v] > 2);
        }
        let mut new_index = vec![usize::MAX; p.len()];
        let mut vertices = Vec::new();
        for loop_ in &mut loops {
            for v in loop_.iter_mut() {
                if new_index[*v] == usize::MAX {
                    new_index[*v] = vertices.len();
                    vertices.push(p[*v]);
                }
                *v = new_index[*v];
            }
        }
        let faces = loops
            .into_iter()
            .map(|loop_| {
                let plane = loop_plane(&vertices, &loop_);
                Face::new(plane, loop_)
            })
            .collect();
        ConvexPolyhedron::from_parts(vertices, faces)
    }
}

/// The plane of a planar loop: its normal from the loop's area vector in double-double arithmetic
/// ([`crate::area::loop_normal`], accurate for slivers and for tiny or huge faces), through the
/// loop's centroid.
fn loop_plane(vertices: &[DVec3], loop_: &[usize]) -> Plane {
    let center = loop_
        .iter()
        .map(|&i| vertices[i] / loop_.len() as f64)
        .sum::<DVec3>();
    let normal = loop_normal(vertices, loop_);
    debug_assert!(normal.is_finite(), "a hull face has a positive area");
    Plane::from_unit_normal_point(normal, center)
}
