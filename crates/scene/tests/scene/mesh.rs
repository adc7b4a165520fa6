//! `Mesh`: construction, validation, normals, bounds, groups, transforms and merging.

use std::f64::consts::FRAC_PI_2;

use glam::{DAffine3, DMat3, DQuat, DVec3};
use shadowlab_scene::{
    Bounds, DEFAULT_GROUP_NAME, FALLBACK_NORMAL, MAX_COORDINATE, Mesh, MeshError, procedural,
};

use crate::support::{assert_close, assert_unit_normals};

/// A unit right triangle in the xy plane, counter-clockwise seen from +z.
fn triangle() -> Mesh {
    Mesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).expect("valid triangle")
}

#[test]
fn computed_normals_follow_the_winding() {
    let mesh = triangle();
    assert_eq!(mesh.normals(), [DVec3::Z; 3]);
    let flipped = Mesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 2, 1]]).unwrap();
    assert_eq!(flipped.normals(), [DVec3::NEG_Z; 3]);
    assert_eq!(mesh.groups(), [0]);
    assert_eq!(mesh.group_names(), [DEFAULT_GROUP_NAME]);
    assert_eq!(mesh.triangle_count(), 1);
    assert_eq!(mesh.vertex_count(), 3);
    assert_close(mesh.surface_area(), 0.5, 1e-15, "area");
}

#[test]
fn computed_normals_are_area_weighted() {
    // Two triangles share vertex 0: one in the xy plane (area 2, normal +z) and one in the xz plane
    // (area 1/2, normal −y as wound). The shared normal is (0, −1/2, 2) normalised: area-weighted.
    let positions = vec![
        DVec3::ZERO,
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(0.0, 2.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
    ];
    let mesh = Mesh::new(positions, vec![[0, 1, 2], [0, 3, 4]]).unwrap();
    let expected = DVec3::new(0.0, -0.5, 2.0).normalize();
    assert!((mesh.normals()[0] - expected).length() < 1e-15);
    assert_eq!(mesh.normals()[1], DVec3::Z);
    assert_eq!(mesh.normals()[3], DVec3::NEG_Y);
}

#[test]
fn degenerate_and_unused_vertices_get_the_fallback_normal() {
    // A zero-area triangle (collinear corners) is allowed; its vertices have no normal direction.
    let positions = vec![DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0), DVec3::Y];
    let mesh = Mesh::new(positions, vec![[0, 1, 2]]).expect("degenerate triangles are allowed");
    assert_eq!(FALLBACK_NORMAL, DVec3::Z);
    assert_eq!(mesh.normals(), [FALLBACK_NORMAL; 4]);
    assert_eq!(mesh.surface_area(), 0.0);
    // Two coincident triangles of opposite winding cancel.
    let cancelling = Mesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y],
        vec![[0, 1, 2], [0, 2, 1]],
    )
    .unwrap();
    assert_eq!(cancelling.normals(), [FALLBACK_NORMAL; 3]);
}

#[test]
fn normals_survive_extreme_scales() {
    for scale in [1e-300, 1e-160, 1.0, 1e20, MAX_COORDINATE] {
        let positions = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::NEG_X].map(|p| p * scale);
        let mesh = Mesh::new(positions.to_vec(), vec![[0, 1, 2], [0, 2, 3]]).unwrap();
        assert_eq!(mesh.normals(), [DVec3::Z; 4], "scale {scale}");
    }
    // Positions beyond MAX_COORDINATE (whose edges would overflow) are refused.
    let huge = f64::MAX / 2.0;
    assert!(matches!(
        Mesh::new(
            vec![
                DVec3::new(-huge, -huge, 0.0),
                DVec3::new(huge, -huge, 0.0),
                DVec3::new(0.0, huge, 0.0),
            ],
            vec![[0, 1, 2]],
        ),
        Err(MeshError::PositionOutOfRange { vertex: 0, .. })
    ));
}

#[test]
fn bad_geometry_is_rejected_with_the_culprit_named() {
    assert!(matches!(
        Mesh::new(vec![DVec3::ZERO], vec![]),
        Err(MeshError::NoTriangles)
    ));
    let nan = DVec3::new(0.0, f64::NAN, 0.0);
    assert!(matches!(
        Mesh::new(vec![DVec3::ZERO, DVec3::X, nan], vec![[0, 1, 2]]),
        Err(MeshError::NonFinitePosition { vertex: 2 })
    ));
    let infinite = DVec3::new(f64::INFINITY, 0.0, 0.0);
    assert!(matches!(
        Mesh::new(vec![infinite, DVec3::X, DVec3::Y], vec![[0, 1, 2]]),
        Err(MeshError::NonFinitePosition { vertex: 0 })
    ));
    let error = Mesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y],
        vec![[0, 1, 2], [0, 3, 1]],
    )
    .unwrap_err();
    assert!(matches!(
        error,
        MeshError::IndexOutOfRange {
            triangle: 1,
            index: 3,
            vertex_count: 3
        }
    ));
    assert_eq!(
        error.to_string(),
        "triangle 1 refers to vertex 3, but there are 3 vertices"
    );
}

#[test]
fn given_normals_are_normalised_and_checked() {
    let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    let mesh = Mesh::with_normals(
        positions.clone(),
        vec![
            DVec3::new(0.0, 0.0, 3.0),
            DVec3::new(1e-300, 0.0, 1e-300),
            DVec3::splat(1e300),
        ],
        vec![[0, 1, 2]],
    )
    .unwrap();
    assert_eq!(mesh.normals()[0], DVec3::Z);
    assert!((mesh.normals()[1] - DVec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-15);
    assert!((mesh.normals()[2] - DVec3::ONE.normalize()).length() < 1e-15);
    assert_unit_normals(&mesh);
    assert!(matches!(
        Mesh::with_normals(positions.clone(), vec![DVec3::Z; 2], vec![[0, 1, 2]]),
        Err(MeshError::NormalCountMismatch {
            positions: 3,
            normals: 2
        })
    ));
    assert!(matches!(
        Mesh::with_normals(
            positions.clone(),
            vec![DVec3::Z, DVec3::ZERO, DVec3::Z],
            vec![[0, 1, 2]]
        ),
        Err(MeshError::InvalidNormal { vertex: 1 })
    ));
    assert!(matches!(
        Mesh::with_normals(
            positions,
            vec![DVec3::Z, DVec3::Z, DVec3::splat(f64::NAN)],
            vec![[0, 1, 2]]
        ),
        Err(MeshError::InvalidNormal { vertex: 2 })
    ));
}

#[test]
fn bounds_cover_every_position() {
    let mesh = Mesh::new(
        vec![
            DVec3::new(-1.0, 2.0, 3.0),
            DVec3::new(4.0, -5.0, 6.0),
            DVec3::new(0.0, 0.0, -7.0),
        ],
        vec![[0, 1, 2]],
    )
    .unwrap();
    let bounds = mesh.bounds();
    assert_eq!(bounds.min, DVec3::new(-1.0, -5.0, -7.0));
    assert_eq!(bounds.max, DVec3::new(4.0, 2.0, 6.0));
    assert_eq!(bounds.centre(), DVec3::new(1.5, -1.5, -0.5));
    assert_eq!(bounds.size(), DVec3::new(5.0, 7.0, 13.0));
    assert_close(
        bounds.diagonal(),
        (25.0_f64 + 49.0 + 169.0).sqrt(),
        1e-15,
        "diagonal",
    );
    assert!(mesh.positions().iter().all(|&p| bounds.contains(p)));
    assert!(!bounds.contains(DVec3::new(4.5, 0.0, 0.0)));
    // The centre of huge bounds does not overflow.
    let huge = Bounds {
        min: DVec3::splat(-f64::MAX),
        max: DVec3::splat(f64::MAX),
    };
    assert_eq!(huge.centre(), DVec3::ZERO);
}

#[test]
fn groups_are_validated() {
    let quad = Mesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::ONE, DVec3::Y],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap();
    let named = quad
        .clone()
        .with_groups(vec![1, 0], vec!["left".into(), "right".into()])
        .unwrap();
    assert_eq!(named.groups(), [1, 0]);
    assert_eq!(named.group_count(), 2);
    assert!(matches!(
        quad.clone().with_groups(vec![0], vec!["a".into()]),
        Err(MeshError::GroupCountMismatch {
            triangles: 2,
            groups: 1
        })
    ));
    assert!(matches!(
        quad.with_groups(vec![0, 2], vec!["a".into(), "b".into()]),
        Err(MeshError::GroupOutOfRange {
            triangle: 1,
            group: 2,
            group_count: 2
        })
    ));
}

#[test]
fn transforms_move_points_and_normals() {
    let cuboid = procedural::cuboid(DVec3::new(2.0, 4.0, 6.0)).unwrap();
    let transform = DAffine3::from_scale_rotation_translation(
        DVec3::new(1.0, 3.0, 0.5),
        DQuat::from_rotation_y(0.3) * DQuat::from_rotation_x(-1.1),
        DVec3::new(10.0, -20.0, 30.0),
    );
    let moved = cuboid.transformed(&transform);
    for (before, after) in cuboid.positions().iter().zip(moved.positions()) {
        assert_eq!(*after, transform.transform_point3(*before));
    }
    // Normals stay perpendicular to the faces: every edge of a triangle is ⟂ its corners' normals
    // (a box's normals are its face normals).
    for t in 0..moved.triangle_count() {
        let [a, b, c] = moved.triangle_positions(t);
        let n = moved.normals()[moved.triangles()[t][0] as usize];
        let face = (b - a).cross(c - a).normalize();
        assert!((face - n).length() < 1e-12, "triangle {t}: {face} vs {n}");
    }
    assert_unit_normals(&moved);
    assert_eq!(moved.groups(), cuboid.groups());
    assert_close(
        moved.signed_volume(),
        48.0 * 1.5,
        1e-12,
        "volume scales by det",
    );
    assert!(
        moved
            .bounds()
            .contains(transform.transform_point3(DVec3::ZERO))
    );
}

#[test]
fn mirroring_reverses_the_winding() {
    let cuboid = procedural::cuboid(DVec3::ONE).unwrap();
    let mirror = DAffine3::from_mat3(DMat3::from_diagonal(DVec3::new(-1.0, 1.0, 1.0)));
    let mirrored = cuboid.transformed(&mirror);
    assert_close(
        mirrored.signed_volume(),
        1.0,
        1e-15,
        "mirrored volume stays positive",
    );
    for t in 0..mirrored.triangle_count() {
        let [a, b, c] = mirrored.triangle_positions(t);
        let n = mirrored.normals()[mirrored.triangles()[t][0] as usize];
        assert!(
            (b - a).cross(c - a).dot(n) > 0.0,
            "triangle {t} winds against its normal"
        );
    }
}

#[test]
fn bad_transforms_are_errors() {
    let mesh = triangle();
    let singular = DAffine3::from_scale(DVec3::new(1.0, 0.0, 1.0));
    assert!(matches!(
        mesh.try_transformed(&singular),
        Err(MeshError::InvalidTransform { .. })
    ));
    let nan = DAffine3::from_translation(DVec3::new(f64::NAN, 0.0, 0.0));
    assert!(matches!(
        mesh.try_transformed(&nan),
        Err(MeshError::InvalidTransform { .. })
    ));
    let overflowing = DAffine3::from_translation(DVec3::splat(f64::MAX));
    assert!(matches!(
        mesh.try_transformed(&overflowing),
        Err(MeshError::PositionOutOfRange { vertex: 0, .. })
    ));
    // Beyond MAX_COORDINATE, but finite: out of range, named with the vertex and the value.
    let beyond = DAffine3::from_translation(DVec3::new(0.0, 2.0 * MAX_COORDINATE, 0.0));
    assert_eq!(
        mesh.try_transformed(&beyond),
        Err(MeshError::PositionOutOfRange {
            vertex: 0,
            value: 2.0 * MAX_COORDINATE
        })
    );
    let to_the_limit = DAffine3::from_translation(DVec3::new(0.0, MAX_COORDINATE - 1.0, 0.0));
    assert!(mesh.try_transformed(&to_the_limit).is_ok());
    assert!(matches!(
        Mesh::new(
            vec![DVec3::ZERO, DVec3::X, DVec3::new(0.0, 0.0, -1e41)],
            vec![[0, 1, 2]]
        ),
        Err(MeshError::PositionOutOfRange { vertex: 2, .. })
    ));
    assert!(
        mesh.try_transformed(&DAffine3::from_rotation_z(FRAC_PI_2))
            .is_ok()
    );
}

#[test]
#[should_panic(expected = "Mesh::transformed: transform is not invertible")]
fn transformed_panics_where_try_transformed_fails() {
    let _ = triangle().transformed(&DAffine3::ZERO);
}

#[test]
fn merging_keeps_parts_apart() {
    let ground = procedural::plane(10.0, 10.0, 2).unwrap();
    let board = procedural::chess_board(1.0, 0.5).unwrap();
    let merged = Mesh::merged(&[ground.clone(), board.clone(), ground.clone()]);
    assert_eq!(merged.triangle_count(), 8 + 200 + 8);
    assert_eq!(
        merged.vertex_count(),
        2 * ground.vertex_count() + board.vertex_count()
    );
    assert_eq!(
        merged.group_names(),
        ["plane", "dark", "light", "frame", "plane"]
    );
    assert!(merged.groups()[..8].iter().all(|&g| g == 0));
    assert!(merged.groups()[208..].iter().all(|&g| g == 4));
    for (g, original) in merged.groups()[8..208].iter().zip(board.groups()) {
        assert_eq!(*g, original + 1);
    }
    // Triangles still name the same positions.
    for t in 0..board.triangle_count() {
        assert_eq!(
            merged.triangle_positions(8 + t),
            board.triangle_positions(t)
        );
    }
    assert_eq!(merged.bounds(), ground.bounds().union(&board.bounds()));
    assert!(matches!(Mesh::try_merged(&[]), Err(MeshError::NoTriangles)));
    assert_eq!(Mesh::merged(std::slice::from_ref(&ground)), ground);
}
