//! Bad input is an error naming what is wrong.

use glam::{DMat4, DVec3};
use shadowlab_raster::{
    DepthFormat, DepthTarget, RasterError, RasterOptions, Rasterizer, TargetSize, Triangles,
};

#[test]
fn bad_input_is_named() {
    let positions = [
        DVec3::ZERO,
        DVec3::X,
        DVec3::Y,
        DVec3::new(f64::NAN, 0.0, 0.0),
    ];
    let mut target = DepthTarget::new(8, 8, DepthFormat::F32).unwrap();
    let mut raster = Rasterizer::new(RasterOptions::default());
    let draw =
        |raster: &mut Rasterizer, target: &mut DepthTarget, triangles: &[[u32; 3]], m: &DMat4| {
            raster.draw_depth(target, Triangles::new(&positions, triangles), m)
        };
    assert_eq!(
        draw(
            &mut raster,
            &mut target,
            &[[0, 1, 2], [0, 1, 9]],
            &DMat4::IDENTITY
        ),
        Err(RasterError::IndexOutOfRange {
            triangle: 1,
            vertex: 9,
            vertex_count: 4
        })
    );
    assert_eq!(
        draw(
            &mut raster,
            &mut target,
            &[[0, 1, 2], [0, 3, 2]],
            &DMat4::IDENTITY
        ),
        Err(RasterError::NonFiniteVertex { vertex: 3 })
    );
    let nan = DMat4::from_diagonal(glam::DVec4::new(1.0, f64::NAN, 1.0, 1.0));
    assert_eq!(
        draw(&mut raster, &mut target, &[[0, 1, 2]], &nan),
        Err(RasterError::NonFiniteMatrix)
    );
    // A bad draw leaves the target as it was.
    assert!(target.depths().iter().all(|&z| z == 1.0));
    for (w, h, name) in [(0, 8, "width"), (8, 0, "height"), (20_000, 8, "width")] {
        let err = TargetSize::new(w, h).unwrap_err();
        assert_eq!(
            err,
            RasterError::TargetSize {
                name,
                value: if name == "width" { w } else { h }
            }
        );
        assert!(err.to_string().contains(name));
    }
    // An unused NaN vertex does not matter.
    assert!(draw(&mut raster, &mut target, &[[0, 1, 2]], &DMat4::IDENTITY).is_ok());
}
