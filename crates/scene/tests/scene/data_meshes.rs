//! The meshes committed in data/meshes load with their documented counts (data/meshes/README.md),
//! finite bounds and unit normals; the two bunnies are closed and wound outward.

use shadowlab_scene::{Mesh, load_obj};

use crate::support::{assert_unit_normals, data_path, first_open_edge};

fn load(name: &str) -> Mesh {
    let path = data_path(&format!("meshes/{name}"));
    load_obj(&path).unwrap_or_else(|error| panic!("{error}"))
}

/// Checks a committed mesh's counts, bounds and normals, and whether it is closed and outward.
fn check(name: &str, triangles: usize, vertices: usize, closed: bool) {
    let mesh = load(name);
    assert_eq!(mesh.triangle_count(), triangles, "{name}");
    assert_eq!(mesh.vertex_count(), vertices, "{name}");
    let bounds = mesh.bounds();
    assert!(
        bounds.min.is_finite() && bounds.max.is_finite(),
        "{name}: {bounds:?}"
    );
    assert!(bounds.diagonal() > 0.0, "{name}");
    assert_unit_normals(&mesh);
    assert_eq!(first_open_edge(&mesh).is_none(), closed, "{name}: closed?");
    if closed {
        assert!(mesh.signed_volume() > 0.0, "{name}: wound inward");
    }
}

#[test]
fn stanford_bunny() {
    check("bunny.obj", 69_666, 34_835, true);
}

#[test]
fn small_bunny() {
    check("bunny-small.obj", 3_674, 1_839, true);
}

#[test]
fn teapot() {
    check("teapot.obj", 992, 792, false);
}
