//! Well-formed OBJ files load as written: positions, normals, triangulation, relative indices,
//! groups, and the statements that are skipped.

use glam::DVec3;
use shadowlab_scene::{FALLBACK_NORMAL, Mesh, load_obj};

use crate::support::{ObjDir, assert_unit_normals, first_open_edge};

fn load(text: &str) -> Mesh {
    let dir = ObjDir::new();
    let path = dir.write("test.obj", text);
    load_obj(&path).unwrap_or_else(|error| panic!("{error}"))
}

/// The positions of every triangle, in order.
fn triangle_positions(mesh: &Mesh) -> Vec<[DVec3; 3]> {
    (0..mesh.triangle_count())
        .map(|t| mesh.triangle_positions(t))
        .collect()
}

const TETRAHEDRON: &str = "\
# a closed tetrahedron, counter-clockwise seen from outside
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
";

#[test]
fn triangles_without_normals_get_computed_ones() {
    let mesh = load(TETRAHEDRON);
    assert_eq!(mesh.triangle_count(), 4);
    assert_eq!(mesh.vertex_count(), 4);
    assert!(first_open_edge(&mesh).is_none());
    assert!((mesh.signed_volume() - 1.0 / 6.0).abs() < 1e-15);
    // The same normals as Mesh::new on the same data (tobj numbers vertices in order of first use:
    // 1, 3, 2, 4).
    let direct = Mesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
    .unwrap();
    assert_eq!(
        mesh.positions(),
        [DVec3::ZERO, DVec3::Y, DVec3::X, DVec3::Z]
    );
    assert_eq!(mesh.normals(), [0, 2, 1, 3].map(|i| direct.normals()[i]));
    assert_eq!(mesh.group_names(), ["unnamed_object"]);
}

#[test]
fn normals_from_the_file_are_used_and_normalised() {
    let mesh = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 2\nvn 0 3 4\nf 1//1 2//1 3//2\n");
    assert_eq!(mesh.vertex_count(), 3);
    assert_eq!(mesh.normals()[0], DVec3::Z);
    assert_eq!(mesh.normals()[1], DVec3::Z);
    assert!((mesh.normals()[2] - DVec3::new(0.0, 0.6, 0.8)).length() < 1e-15);
    assert_unit_normals(&mesh);
}

#[test]
fn a_zero_normal_in_the_file_is_replaced_by_the_computed_one() {
    let mesh = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nvn 1 0 0\nf 1//1 2//2 3//2\n");
    assert_eq!(
        mesh.normals()[0],
        DVec3::Z,
        "computed: the triangle faces +z"
    );
    assert_eq!(
        mesh.normals()[1],
        DVec3::X,
        "from the file, even if it disagrees"
    );
}

#[test]
fn per_corner_normals_split_vertices() {
    // Two faces share an edge but give it different normals (a hard edge): tobj's single index
    // makes one vertex per (position, normal) pair.
    let mesh = load(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 -1\nvn 0 -1 0\n\
         f 1//1 3//1 2//1\nf 1//2 2//2 4//2\n",
    );
    assert_eq!(mesh.vertex_count(), 6);
    assert_eq!(&mesh.normals()[..3], [DVec3::NEG_Z; 3]);
    assert_eq!(&mesh.normals()[3..], [DVec3::NEG_Y; 3]);
}

#[test]
fn quads_and_polygons_are_fan_triangulated() {
    let mesh = load(
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 3 0 0\nv 3 1 0\nv 2.5 2 0\nv 2 1 0\n\
         f 1 2 3 4\nf 5 6 7 8 9\n",
    );
    assert_eq!(mesh.triangle_count(), 2 + 3);
    let p = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    assert_eq!(
        triangle_positions(&mesh),
        [
            [p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)],
            [p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)],
            [p(2.0, 0.0), p(3.0, 0.0), p(3.0, 1.0)],
            [p(2.0, 0.0), p(3.0, 1.0), p(2.5, 2.0)],
            [p(2.0, 0.0), p(2.5, 2.0), p(2.0, 1.0)],
        ]
    );
    assert!(mesh.normals().iter().all(|&n| n == DVec3::Z));
}

#[test]
fn negative_indices_count_back_from_the_latest_element() {
    let absolute = load(TETRAHEDRON);
    let relative =
        load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -1 -2\nv 0 0 1\nf -4 -3 -1\nf 1 -1 3\nf -3 -2 -1\n");
    assert_eq!(triangle_positions(&relative), triangle_positions(&absolute));
    // Relative normal and texture indices too.
    let mixed = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf -3/-1/-1 -2/1/1 3/-1/-1\n");
    assert_eq!(mixed.triangle_count(), 1);
    assert_eq!(mixed.normals(), [DVec3::Z; 3]);
}

#[test]
fn groups_and_objects_become_groups() {
    let mesh = load(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n\
         f 1 3 2\n\
         g left\nf 1 2 4\nf 1 4 3\n\
         o right\nf 2 3 4\n\
         g left\nf 1 3 4\n\
         g empty\n",
    );
    assert_eq!(mesh.group_names(), ["unnamed_object", "left", "right"]);
    assert_eq!(mesh.groups(), [0, 1, 1, 2, 1]);
    // Vertices are not shared across groups (one tobj model each), so the group seams are index
    // seams; positions are exact copies.
    assert_eq!(mesh.vertex_count(), 3 + 4 + 3 + 3);
    assert_eq!(mesh.triangle_positions(3), [DVec3::X, DVec3::Y, DVec3::Z]);
}

#[test]
fn skipped_statements_and_format_variants() {
    let mesh = load(
        "# comment\r\n\
         mtllib missing.mtl\r\n\
         usemtl nothing\r\n\
         s 1\r\n\
         v 0 0 0\r\n\
         v 2 0 0 2\r\n\
         v 0 1 0\r\n\
         v 5 5 5\r\n\
         vt 0.5 0.5 0\r\n\
         vp 0.1\r\n\
         p 4\r\n\
         l 1 2 3 4\r\n\
         l 1 4\r\n\
         f 1/1 2/1 3/1\r\n",
    );
    // CRLF lines, a missing .mtl, smoothing groups, points and polylines (even ones of three or
    // more vertices, which tobj would read as faces) are no faces; w divides the coordinates.
    assert_eq!(mesh.triangle_count(), 1);
    assert_eq!(
        mesh.triangle_positions(0),
        [DVec3::ZERO, DVec3::X, DVec3::Y]
    );
    // The unused vertex 4 is not in the mesh (tobj keeps referenced vertices only).
    assert_eq!(mesh.vertex_count(), 3);
    assert_eq!(mesh.bounds().max, DVec3::new(1.0, 1.0, 0.0));
}

#[test]
fn a_byte_order_mark_is_skipped() {
    let mesh = load("\u{feff}v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    assert_eq!(
        mesh.triangle_positions(0),
        [DVec3::ZERO, DVec3::X, DVec3::Y]
    );
}

#[test]
fn vertex_colours_are_read_past() {
    let mesh = load("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n");
    assert_eq!(
        mesh.triangle_positions(0),
        [DVec3::ZERO, DVec3::X, DVec3::Y]
    );
}

#[test]
fn fallback_normal_for_a_degenerate_face() {
    let mesh = load("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    assert_eq!(mesh.normals(), [FALLBACK_NORMAL; 3]);
}
