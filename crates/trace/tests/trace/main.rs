//! Integration tests of `shadowlab-trace`, one binary (ripgrep's layout):
//!
//! * `support` — seeded generators, test meshes (UV sphere, tessellated cube, jittered grid,
//!   triangle soup) and the brute-force reference;
//! * `agreement` — the tree returns exactly what brute force returns, on random meshes and hard
//!   rays (at vertices, edge midpoints, along shared edges, in a mesh's plane);
//! * `exact` — the ray–triangle test against exact integer arithmetic and exact orientation
//!   predicates: exact decisions off edges, no leaks through shared edges and fan centres;
//! * `watertight` — no ray escapes a closed sphere or cube, or passes through a height field,
//!   even exactly through its vertices and edge midpoints;
//! * `semantics` — the open interval, the tie rule, back faces, rays in a triangle's plane,
//!   zero-area triangles, the empty mesh, hit points, and the clamp of grazing hits;
//! * `packets` — batches of coherent rays, which the batch queries trace in packets, give the
//!   single-ray and brute-force answers: at vertices, edge midpoints, along and beside shared
//!   edges, through zero-area triangles, and a dense grid of parallel rays;
//! * `grid` — grids of parallel rays answered by the sweep ([`shadowlab_trace::Bvh::closest_hits_grid`])
//!   give brute force's answers: random meshes, rays through vertices and along edges, and grids
//!   the sweep does not take;
//! * `determinism` — the same tree and the same bits for 1, 2 and 8 threads;
//! * `offset` — offset origins lie strictly on the intended side (exact `orient3d`), at
//!   magnitudes 10⁻³ to 10⁶, and rays from them miss their own triangle;
//! * `errors` — bad input gives an error, or a panic, naming the triangle, vertex or parameter.

mod agreement;
mod determinism;
mod errors;
mod exact;
mod grid;
mod offset;
mod packets;
mod semantics;
mod support;
mod watertight;
