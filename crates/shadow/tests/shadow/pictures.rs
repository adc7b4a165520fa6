//! The annotated frame pictures hold the raw ones pixel for pixel, are larger (title, legend) and
//! repeat byte for byte.

use shadowlab_raster::DepthFormat;
use shadowlab_scene::builtin_scene;
use shadowlab_shadow::{
    Bias, Filter, FrameOptions, Lookup, PlanOptions, Technique, render_frame, scene_eye, view,
};

/// A PNG's size and pixels, top row first.
fn decode(png: &[u8]) -> (usize, usize, Vec<[u8; 3]>) {
    let pixmap = tiny_skia::Pixmap::decode_png(png).expect("a PNG");
    let pixels = pixmap
        .pixels()
        .iter()
        .map(|p| {
            let c = p.demultiply();
            [c.red(), c.green(), c.blue()]
        })
        .collect();
    (pixmap.width() as usize, pixmap.height() as usize, pixels)
}

/// Whether `inner` (rows from the bottom, `w × h`) lies somewhere in `outer` pixel for pixel.
fn holds(outer: &(usize, usize, Vec<[u8; 3]>), inner: &[[u8; 3]], w: usize, h: usize) -> bool {
    let rows: Vec<&[[u8; 3]]> = inner.chunks(w).rev().collect();
    let (ow, oh, o) = outer;
    (0..=oh - h)
        .any(|y| (0..=ow - w).any(|x| (0..h).all(|r| o[(y + r) * ow + x..][..w] == *rows[r])))
}

/// Claim: the annotated eye view and light view hold the raw pictures unchanged in a larger
/// canvas, and drawing them again gives the same bytes.
#[test]
fn annotated_frame_pictures_hold_the_raw_ones() {
    let mut scene = builtin_scene("outdoor").unwrap();
    (scene.camera.width, scene.camera.height) = (80, 60);
    let options = FrameOptions {
        plan: PlanOptions::new(Technique::Lispsm(shadowlab_shadow::WarpChoice::PAPER)),
        resolution: 64,
        format: DepthFormat::F32,
        lookup: Lookup::new(Bias::DEFAULT, Filter::Nearest),
        snap_texels: 0,
    };
    let frame = render_frame(&scene, &options).unwrap();
    let settings = "64² shadow map, filter nearest";
    let eye_png = view::eye_picture(&frame, &scene, settings).unwrap();
    assert_eq!(
        eye_png,
        view::eye_picture(&frame, &scene, settings).unwrap()
    );
    let eye = decode(&eye_png);
    assert!(eye.0 > 80 && eye.1 > 60);
    assert!(holds(&eye, &view::shade(&frame, &scene), 80, 60));

    let map = &frame.lights[0].maps[0].1;
    let light_png =
        view::light_view_picture(map, &scene_eye(&scene), &scene.name, settings).unwrap();
    let light = decode(&light_png);
    assert!(holds(
        &light,
        &view::light_view(map, &scene_eye(&scene)),
        64,
        64
    ));
}
