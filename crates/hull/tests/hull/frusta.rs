//! Frusta from camera parameters and from view-projection matrices (every NDC convention) agree, and
//! validate; the polyhedron of a frustum has its planes.

use glam::{DMat4, DVec3, DVec4};
use proptest::prelude::*;
use shadowlab_hull::{ConvexPolyhedron, Frustum, NdcDepth, Orthographic, ViewPose};

use crate::support::{TOL, camera, config, slack_for};

const NDC: [NdcDepth; 3] = [
    NdcDepth::NegativeOneToOne,
    NdcDepth::ZeroToOne,
    NdcDepth::ReversedZeroToOne,
];

fn assert_same(a: &Frustum, b: &Frustum, slack: f64) {
    for (p, q) in a.corners().iter().zip(b.corners()) {
        assert!(p.distance(*q) <= slack, "corner {p} vs {q}");
    }
    for (p, q) in a.planes().iter().zip(b.planes()) {
        assert!(
            p.normal().distance(q.normal()) <= 1e-9,
            "normal {} vs {}",
            p.normal(),
            q.normal()
        );
        for c in a.corners() {
            assert!((p.signed_distance(*c) - q.signed_distance(*c)).abs() <= slack);
        }
    }
}

proptest! {
    // Seed 0xF2A5_0001: 128 random perspective cameras.
    #![proptest_config(config(0xF2A5_0001, 128))]

    /// A perspective frustum from parameters equals the one from `P(ndc) · view` for every NDC range,
    /// corners in their documented order and planes with outward normals.
    #[test]
    fn perspective_parameters_and_matrices_agree(cam in camera()) {
        let direct = cam.frustum();
        prop_assert_eq!(direct.validate(&TOL), Ok(()));
        let slack = slack_for(&[direct.corners()]) * 1e3 * cam.projection.far() / cam.projection.near();
        for ndc in NDC {
            let m = cam.projection.matrix(ndc) * cam.pose.view_matrix();
            let from_matrix = Frustum::from_view_projection(m, ndc).expect("valid matrix");
            prop_assert_eq!(from_matrix.validate(&TOL.clone()), Ok(()));
            assert_same(&direct, &from_matrix, slack);
            // The NDC cube's corners map to the frustum's corners.
            let (z_near, z_far) = ndc.near_far();
            for (i, c) in direct.corners().iter().enumerate() {
                let clip = m * c.extend(1.0);
                let ndc_point = clip.truncate() / clip.w;
                let expected = DVec3::new(
                    if i & 1 == 0 { -1.0 } else { 1.0 },
                    if i & 2 == 0 { -1.0 } else { 1.0 },
                    if i & 4 == 0 { z_near } else { z_far },
                );
                prop_assert!(ndc_point.distance(expected) <= 1e-6, "{ndc_point} vs {expected}");
            }
        }
        let body = ConvexPolyhedron::from_frustum(&direct, &TOL).expect("solid");
        prop_assert_eq!(body.validate(&TOL), Ok(()));
        prop_assert_eq!(body.vertices().len(), 8);
        prop_assert_eq!(body.faces().len(), 6);
        for (face, plane) in body.faces().iter().zip(direct.planes()) {
            prop_assert_eq!(face.plane(), plane);
        }
    }
}

#[test]
fn orthographic_parameters_and_matrices_agree() {
    let pose = ViewPose::look_at(
        DVec3::new(3.0, 4.0, 5.0),
        DVec3::new(-1.0, 0.5, 0.0),
        DVec3::Y,
    )
    .expect("valid pose");
    let ortho = Orthographic::new(-4.0, 6.0, -2.0, 3.0, -1.0, 30.0).expect("valid");
    let direct = Frustum::orthographic(&pose, &ortho);
    assert_eq!(direct.validate(&TOL), Ok(()));
    let slack = slack_for(&[direct.corners()]);
    for ndc in NDC {
        let m = ortho.matrix(ndc) * pose.view_matrix();
        let from_matrix = Frustum::from_view_projection(m, ndc).expect("valid matrix");
        assert_eq!(from_matrix.validate(&TOL), Ok(()));
        assert_same(&direct, &from_matrix, slack);
    }
    let body = ConvexPolyhedron::from_frustum(&direct, &TOL).expect("solid");
    let expected = 10.0 * 5.0 * 31.0;
    assert!((body.volume() - expected).abs() <= 1e-9 * expected);
}

/// A mirrored view-projection (det < 0) still gives outward planes and counter-clockwise faces.
#[test]
fn mirrored_matrix_gives_a_valid_frustum() {
    let cam = shadowlab_hull::Perspective::new(1.0, 1.3, 0.5, 40.0).expect("valid");
    let pose = ViewPose::look_to(DVec3::ZERO, DVec3::NEG_Z, DVec3::Y).expect("valid");
    let mirror = DMat4::from_cols(-DVec4::X, DVec4::Y, DVec4::Z, DVec4::W);
    let m = cam.matrix(NdcDepth::NegativeOneToOne) * mirror * pose.view_matrix();
    let frustum = Frustum::from_view_projection(m, NdcDepth::NegativeOneToOne).expect("valid");
    assert_eq!(frustum.validate(&TOL), Ok(()));
    let body = ConvexPolyhedron::from_frustum(&frustum, &TOL).expect("solid");
    assert_eq!(body.validate(&TOL), Ok(()));
    assert!(frustum.contains(DVec3::new(0.0, 0.0, -10.0), 0.0));
    assert!(frustum.view_direction().distance(DVec3::NEG_Z) < 1e-12);
}
