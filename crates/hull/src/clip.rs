//! Clipping a convex polyhedron by a plane, and intersections built from it (box, frustum, another
//! polyhedron).
//!
//! # Algorithm
//! Each vertex is classified against the plane with the snap distance ε of the body's scale: *in*
//! (`n·x + d < −ε`), *on* (`|n·x + d| ≤ ε`) or *out* (`> ε`). No *out* vertex: the body is returned
//! unchanged. No *in* vertex: the result is empty (or flat within ε): `None`. Otherwise every face
//! with an *in* vertex keeps its *in* and *on* vertices and gains one new vertex per edge from *in* to
//! *out* (shared by both faces of the edge, so the mesh stays watertight); faces keep their planes.
//! The cap face, on the clip plane, is the loop of the directed edges left without an opposite,
//! reversed. Vertices within ε are then merged and the topology checked. If a face's kept vertices do
//! not form one run, or the cap is not one loop, or the merged mesh is not a closed convex solid (all
//! only possible within ε of a degeneracy), or the result does not validate at its own scale (kept
//! planes are only as exact as the tolerances of the larger body they came from, found by the hull
//! fuzzer), the result is rebuilt as the exact convex hull ([`crate::hull3`]) of the kept and new
//! vertices.

use std::borrow::Cow;
use std::collections::BTreeMap;

use glam::DVec3;

use crate::aabb::Aabb;
use crate::frustum::Frustum;
use crate::hull3;
use crate::mesh::Face;
use crate::plane::Plane;
use crate::polyhedron::ConvexPolyhedron;
use crate::tolerance::Tolerances;

#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    In,
    On,
    Out,
}

/// What clipping did.
enum Clipped {
    /// No vertex was outside: the body is its own result.
    Unchanged,
    /// No vertex was inside: the result is empty (or flat within the snap distance).
    Empty,
    /// A new body.
    Cut(ConvexPolyhedron),
}

impl ConvexPolyhedron {
    /// The part of the body in the half-space of `plane` (`n·x + d ≤ 0`), or `None` if that part is
    /// empty or flat within the snap distance of the body's scale. The new face lies on `plane`; every
    /// other face keeps its plane. Vertices within the snap distance of `plane` count as on it; new
    /// vertices are shared by the two faces of each cut edge, and vertices closer than the snap
    /// distance are merged. In the rare cases where this does not give a closed convex solid (found
    /// only for bodies a few snap distances thick) or the inherited planes are off the vertices by
    /// more than the smaller result's tolerances (a cut that shrinks the body a thousandfold), the
    /// result is the exact hull of the kept and new vertices instead.
    #[must_use]
    pub fn clip(&self, plane: &Plane, tolerances: &Tolerances) -> Option<Self> {
        match clip_checked(self, plane, tolerances) {
            Clipped::Unchanged => Some(self.clone()),
            Clipped::Empty => None,
            Clipped::Cut(body) => Some(body),
        }
    }

    /// The intersection of the body with the half-spaces of `planes`, clipped in order (each clip
    /// with the snap distance of the body at that point); `None` if empty (or flat within the snap
    /// distance).
    #[must_use]
    pub fn intersect_planes<'a>(
        &self,
        planes: impl IntoIterator<Item = &'a Plane>,
        tolerances: &Tolerances,
    ) -> Option<Self> {
        let mut body = Cow::Borrowed(self);
        for plane in planes {
            match clip_checked(&body, plane, tolerances) {
                Clipped::Unchanged => {}
                Clipped::Empty => return None,
                Clipped::Cut(cut) => body = Cow::Owned(cut),
            }
        }
        Some(body.into_owned())
    }

    /// The intersection with a box; `None` if empty.
    #[must_use]
    pub fn intersect_aabb(&self, aabb: &Aabb, tolerances: &Tolerances) -> Option<Self> {
        self.intersect_planes(&aabb.planes(), tolerances)
    }

    /// The intersection with a frustum; `None` if empty.
    #[must_use]
    pub fn intersect_frustum(&self, frustum: &Frustum, tolerances: &Tolerances) -> Option<Self> {
        self.intersect_planes(frustum.planes(), tolerances)
    }

    /// The intersection with another convex polyhedron (clipped by its face planes); `None` if empty.
    #[must_use]
    pub fn intersect(&self, other: &Self, tolerances: &Tolerances) -> Option<Self> {
        self.intersect_planes(other.planes(), tolerances)
    }
}

/// [`clip_with`] at the body's snap distance; debug builds validate the result.
fn clip_checked(body: &ConvexPolyhedron, plane: &Plane, tolerances: &Tolerances) -> Clipped {
    let snap = tolerances.snap_distance(body.scale());
    let result = clip_with(body, plane, snap, tolerances);
    if let Clipped::Cut(cut) = &result {
        debug_assert_eq!(
            cut.validate(tolerances),
            Ok(()),
            "clip produced an invalid body"
        );
    }
    result
}

fn clip_with(
    body: &ConvexPolyhedron,
    plane: &Plane,
    snap: f64,
    tolerances: &Tolerances,
) -> Clipped {
    let distance: Vec<f64> = body
        .vertices()
        .iter()
        .map(|v| plane.signed_distance(*v))
        .collect();
    let side: Vec<Side> = distance
        .iter()
        .map(|&d| {
            if d > snap {
                Side::Out
            } else if d < -snap {
                Side::In
            } else {
                Side::On
            }
        })
        .collect();
    if !side.contains(&Side::Out) {
        return Clipped::Unchanged;
    }
    if !side.contains(&Side::In) {
        return Clipped::Empty;
    }
    let mut vertices = body.vertices().to_vec();
    let mut cut_vertex: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    let mut cut = |a: usize, b: usize, vertices: &mut Vec<DVec3>| -> usize {
        let key = (a.min(b), a.max(b));
        *cut_vertex.entry(key).or_insert_with(|| {
            let (p, q) = key;
            let t = distance[p] / (distance[p] - distance[q]);
            vertices.push(vertices[p] + (vertices[q] - vertices[p]) * t);
            vertices.len() - 1
        })
    };
    let mut faces = Vec::with_capacity(body.faces().len() + 1);
    let mut consistent = true;
    for face in body.faces() {
        let loop_ = face.vertices();
        if !loop_.iter().any(|&v| side[v] == Side::In) {
            continue;
        }
        let mut kept = Vec::with_capacity(loop_.len() + 1);
        let mut runs = 0;
        for (k, &a) in loop_.iter().enumerate() {
            let b = loop_[(k + 1) % loop_.len()];
            if side[a] != Side::Out {
                kept.push(a);
                if side[b] == Side::Out {
                    runs += 1;
                }
            }
            if matches!(
                (side[a], side[b]),
                (Side::In, Side::Out) | (Side::Out, Side::In)
            ) {
                kept.push(cut(a, b, &mut vertices));
            }
        }
        consistent &= runs <= 1;
        faces.push(Face::new(*face.plane(), kept));
    }
    let rebuilt = if consistent {
        cap_loop(&faces)
            .and_then(|cap| {
                faces.push(Face::new(*plane, cap));
                ConvexPolyhedron::assemble(vertices.clone(), faces, snap)
            })
            // Kept faces keep their planes, which are only as exact as the tolerances of the body's
            // scale: a cut that shrinks the body a thousandfold can leave them off their vertices by
            // more than the result's own (smaller) tolerances allow.
            .filter(|cut| cut.validate(tolerances).is_ok())
    } else {
        None
    };
    let result = rebuilt.or_else(|| {
        // Fallback: the exact hull of everything the clipped body is made of.
        let points: Vec<DVec3> = side
            .iter()
            .zip(body.vertices())
            .filter(|(s, _)| **s != Side::Out)
            .map(|(_, v)| *v)
            .chain(vertices[body.vertices().len()..].iter().copied())
            .collect();
        hull3::hull_with_snap(&points, snap, tolerances).ok()
    });
    result.map_or(Clipped::Empty, Clipped::Cut)
}

/// The cap loop: directed edges of `faces` without an opposite, reversed and chained. `None` unless
/// they form exactly one simple loop.
fn cap_loop(faces: &[Face]) -> Option<Vec<usize>> {
    let mut edges: Vec<(usize, usize)> = faces
        .iter()
        .flat_map(|f| {
            let l = f.vertices();
            (0..l.len()).map(move |k| (l[k], l[(k + 1) % l.len()]))
        })
        .collect();
    edges.sort_unstable();
    let mut next = BTreeMap::new();
    for &(a, b) in &edges {
        if edges.binary_search(&(b, a)).is_err() && next.insert(b, a).is_some() {
            return None;
        }
    }
    let (&start, _) = next.first_key_value()?;
    let mut cap = vec![start];
    let mut current = next[&start];
    while current != start {
        if cap.len() > next.len() {
            return None;
        }
        cap.push(current);
        current = *next.get(&current)?;
    }
    (cap.len() == next.len() && cap.len() >= 3).then_some(cap)
}
