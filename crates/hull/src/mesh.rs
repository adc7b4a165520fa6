//! Mesh bookkeeping shared by the polyhedron builders: faces, merging close vertices, finding close
//! pairs, and the topological checks (closed, oriented 2-manifold, single fans, Euler
//! characteristic).

use glam::DVec3;

use crate::error::ValidationError;
use crate::plane::Plane;

/// One face: an outward plane and the loop of vertex indices on it, counter-clockwise seen from
/// outside (i.e. around the plane's normal).
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    pub(crate) plane: Plane,
    pub(crate) vertices: Vec<usize>,
}

impl Face {
    pub(crate) fn new(plane: Plane, vertices: Vec<usize>) -> Self {
        Self { plane, vertices }
    }

    /// The outward plane.
    #[must_use]
    pub fn plane(&self) -> &Plane {
        &self.plane
    }

    /// The vertex loop (indices into [`crate::ConvexPolyhedron::vertices`]), counter-clockwise seen from
    /// outside.
    #[must_use]
    pub fn vertices(&self) -> &[usize] {
        &self.vertices
    }
}

/// Vertex indices sorted by x (ties by index), for sweep-line proximity searches.
fn sorted_by_x(points: &[DVec3]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| points[a].x.total_cmp(&points[b].x).then(a.cmp(&b)));
    order
}

/// For each vertex, the representative it merges into: vertices within `distance` of each other are
/// joined (transitively), and each group is represented by its smallest index.
pub(crate) fn merge_close(points: &[DVec3], distance: f64) -> Vec<usize> {
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut parent: Vec<usize> = (0..points.len()).collect();
    let order = sorted_by_x(points);
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if points[j].x - points[i].x > distance {
                break;
            }
            if crate::tolerance::distance(points[i], points[j]) <= distance {
                let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                let (low, high) = (a.min(b), a.max(b));
                parent[high] = low;
            }
        }
    }
    (0..points.len()).map(|i| root(&mut parent, i)).collect()
}

/// The first pair (in x-sweep order) of points within `distance` of each other, if any.
pub(crate) fn closest_pair_within(points: &[DVec3], distance: f64) -> Option<(usize, usize)> {
    let order = sorted_by_x(points);
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if points[j].x - points[i].x > distance {
                break;
            }
            if crate::tolerance::distance(points[i], points[j]) <= distance {
                return Some((i.min(j), i.max(j)));
            }
        }
    }
    None
}

/// A directed face edge: `(from, to, face, position of from in the face loop)`.
type DirectedEdge = (usize, usize, usize, usize);

/// The sorted directed edges of `faces`.
fn directed_edges(faces: &[Face]) -> Vec<DirectedEdge> {
    let mut edges = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        let loop_ = face.vertices();
        for (k, &from) in loop_.iter().enumerate() {
            edges.push((from, loop_[(k + 1) % loop_.len()], f, k));
        }
    }
    edges.sort_unstable();
    edges
}

fn find_edge(edges: &[DirectedEdge], from: usize, to: usize) -> Option<&DirectedEdge> {
    edges
        .binary_search_by(|e| (e.0, e.1).cmp(&(from, to)))
        .ok()
        .map(|i| &edges[i])
}

/// Checks that the faces form a closed, consistently oriented 2-manifold of genus 0 over vertices
/// `0..vertex_count`: every directed edge once with its opposite once, every vertex used and
/// surrounded by a single fan, and V − E + F = 2. Face loops must be well formed (checked by the
/// caller).
pub(crate) fn check_topology(vertex_count: usize, faces: &[Face]) -> Result<(), ValidationError> {
    let edges = directed_edges(faces);
    for pair in edges.windows(2) {
        if (pair[0].0, pair[0].1) == (pair[1].0, pair[1].1) {
            return Err(ValidationError::RepeatedEdge {
                from: pair[0].0,
                to: pair[0].1,
            });
        }
    }
    for e in &edges {
        if find_edge(&edges, e.1, e.0).is_none() {
            return Err(ValidationError::OpenEdge { from: e.0, to: e.1 });
        }
    }
    // Outgoing edges of vertex v are the contiguous run starting at `first_out[v]`.
    let mut first_out = vec![usize::MAX; vertex_count];
    let mut out_degree = vec![0_usize; vertex_count];
    for (i, e) in edges.iter().enumerate() {
        if e.0 >= vertex_count || e.1 >= vertex_count {
            return Err(ValidationError::MalformedFace { face: e.2 });
        }
        if first_out[e.0] == usize::MAX {
            first_out[e.0] = i;
        }
        out_degree[e.0] += 1;
    }
    for vertex in 0..vertex_count {
        if out_degree[vertex] == 0 {
            return Err(ValidationError::UnusedVertex { vertex });
        }
        // Walk the fan: from outgoing edge (v, a) in face f, the previous vertex p of v in f gives the
        // next outgoing edge (v, p), in the neighbouring face.
        let start = edges[first_out[vertex]];
        let mut current = start;
        let mut steps = 0;
        loop {
            let loop_ = faces[current.2].vertices();
            let previous = loop_[(current.3 + loop_.len() - 1) % loop_.len()];
            current = *find_edge(&edges, vertex, previous)
                .ok_or(ValidationError::NonManifoldVertex { vertex })?;
            steps += 1;
            if current == start || steps > out_degree[vertex] {
                break;
            }
        }
        if steps != out_degree[vertex] {
            return Err(ValidationError::NonManifoldVertex { vertex });
        }
    }
    let edge_count = edges.len() / 2;
    if vertex_count + faces.len() != edge_count + 2 {
        return Err(ValidationError::EulerCharacteristic {
            vertices: vertex_count,
            edges: edge_count,
            faces: faces.len(),
        });
    }
    Ok(())
}
