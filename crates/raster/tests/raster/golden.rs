//! Golden images: small scenes whose every depth bit and triangle id is pinned by a file in
//! data/golden/raster/. Depth is stored as OpenEXR (f32, exact for the f32 and 16-bit formats used
//! here), triangle ids as RGBA8 PNG (the id's four little-endian bytes). Set `UPDATE_GOLDEN=1` to
//! rewrite the files after an intended change; never otherwise.

use std::path::PathBuf;

use glam::DVec3;
use shadowlab_raster::{
    CullMode, DepthFormat, DepthPairTarget, EyeTarget, RasterOptions, Rasterizer, Triangles,
    image_out,
};

fn golden_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/golden/raster")
}

fn updating() -> bool {
    std::env::var_os("UPDATE_GOLDEN").is_some_and(|v| v == "1")
}

/// A box `[lo, hi]` as 12 counter-clockwise (outward) triangles.
fn cuboid(positions: &mut Vec<DVec3>, triangles: &mut Vec<[u32; 3]>, lo: DVec3, hi: DVec3) {
    let base = u32::try_from(positions.len()).unwrap();
    for k in 0..8u32 {
        positions.push(DVec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        ));
    }
    let faces = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    for [a, b, c, d] in faces {
        triangles.push([base + a, base + b, base + c]);
        triangles.push([base + a, base + c, base + d]);
    }
}

/// A ground quad and three boxes, one partly behind the eye.
fn boxes() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
    positions.extend([
        DVec3::new(-10.0, 0.0, 10.0),
        DVec3::new(10.0, 0.0, 10.0),
        DVec3::new(10.0, 0.0, -10.0),
        DVec3::new(-10.0, 0.0, -10.0),
    ]);
    triangles.extend([[0, 1, 2], [0, 2, 3]]);
    cuboid(
        &mut positions,
        &mut triangles,
        DVec3::new(-1.0, 0.0, -2.0),
        DVec3::new(0.5, 1.5, -0.5),
    );
    cuboid(
        &mut positions,
        &mut triangles,
        DVec3::new(1.0, 0.0, -4.0),
        DVec3::new(2.0, 0.4, -3.0),
    );
    cuboid(
        &mut positions,
        &mut triangles,
        DVec3::new(-0.2, 0.0, 2.2),
        DVec3::new(0.4, 2.0, 3.5),
    );
    (positions, triangles)
}

fn check_depth(name: &str, depths: &[f64], width: u32, height: u32) {
    let path = golden_dir().join(format!("{name}.exr"));
    if updating() {
        std::fs::create_dir_all(golden_dir()).unwrap();
        std::fs::write(&path, image_out::depth_exr(depths, width, height).unwrap()).unwrap();
        return;
    }
    let image = exr::prelude::read_first_flat_layer_from_file(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (create it with UPDATE_GOLDEN=1)", path.display()));
    let samples = image.layer_data.channel_data.list[0]
        .sample_data
        .values_as_f32()
        .collect::<Vec<f32>>();
    let (w, h) = (width as usize, height as usize);
    assert_eq!(samples.len(), w * h, "{name}: size");
    let mut differ = 0;
    for row in 0..h {
        for x in 0..w {
            // The file is top row first; depths are bottom row first.
            #[expect(clippy::cast_possible_truncation, reason = "the file holds f32")]
            let ours = depths[(h - 1 - row) * w + x] as f32;
            differ += usize::from(samples[row * w + x].to_bits() != ours.to_bits());
        }
    }
    assert_eq!(
        differ, 0,
        "{name}: {differ} depths differ from the golden image"
    );
}

fn check_ids(name: &str, ids: &[u32], width: u32, height: u32) {
    let path = golden_dir().join(format!("{name}.png"));
    let pixels: Vec<u8> = {
        let (w, h) = (width as usize, height as usize);
        (0..h)
            .rev()
            .flat_map(|row| {
                ids[row * w..(row + 1) * w]
                    .iter()
                    .flat_map(|id| id.to_le_bytes())
            })
            .collect()
    };
    if updating() {
        std::fs::create_dir_all(golden_dir()).unwrap();
        let file = std::io::BufWriter::new(std::fs::File::create(&path).unwrap());
        let mut encoder = png::Encoder::new(file, width, height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().unwrap();
        writer.write_image_data(&pixels).unwrap();
        writer.finish().unwrap();
        return;
    }
    let golden = read_rgba8(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (create it with UPDATE_GOLDEN=1)", path.display()));
    assert_eq!(
        golden, pixels,
        "{name}: triangle ids differ from the golden image"
    );
}

/// The pixels of an 8-bit RGBA PNG, rows top first.
fn read_rgba8(path: &std::path::Path) -> Result<Vec<u8>, String> {
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .map_err(|e| e.to_string())?;
    let format = reader.output_color_type();
    if format != (png::ColorType::Rgba, png::BitDepth::Eight) {
        return Err(format!("{format:?} pixels, not 8-bit RGBA"));
    }
    let mut pixels = vec![0; reader.output_buffer_size().ok_or("too large")?];
    let frame = reader.next_frame(&mut pixels).map_err(|e| e.to_string())?;
    pixels.truncate(frame.buffer_size());
    Ok(pixels)
}

#[test]
fn boxes_in_perspective() {
    let (positions, triangles) = boxes();
    let (w, h) = (96u32, 64u32);
    let view = glam::dcamera::rh::view::look_at_mat4(
        DVec3::new(0.5, 1.8, 3.0),
        DVec3::new(0.0, 0.5, -2.0),
        DVec3::Y,
    );
    let m = glam::dcamera::rh::proj::opengl::perspective(1.1, 1.5, 0.3, 30.0) * view;
    let mesh = Triangles::new(&positions, &triangles);
    let mut eye = EyeTarget::new(w, h, DepthFormat::F32).unwrap();
    let stats = Rasterizer::new(RasterOptions {
        cull: CullMode::Back,
        ..RasterOptions::default()
    })
    .draw_eye(&mut eye, mesh, &m)
    .unwrap();
    assert!(stats.clipped > 0, "the scene exercises clipping: {stats:?}");
    check_depth("boxes-perspective-depth", &eye.depths(), w, h);
    check_ids("boxes-perspective-triangles", &eye.triangles(), w, h);
}

#[test]
fn boxes_from_a_light_nearest_and_second_depth() {
    let (positions, triangles) = boxes();
    let (w, h) = (64u32, 64u32);
    let view =
        glam::dcamera::rh::view::look_at_mat4(DVec3::new(4.0, 8.0, 3.0), DVec3::ZERO, DVec3::NEG_Z);
    let m = glam::dcamera::rh::proj::opengl::orthographic(-6.0, 6.0, -6.0, 6.0, 1.0, 20.0) * view;
    let mut pair = DepthPairTarget::new(w, h, DepthFormat::Unorm16).unwrap();
    Rasterizer::new(RasterOptions::default())
        .draw_depth_pair(&mut pair, Triangles::new(&positions, &triangles), &m)
        .unwrap();
    check_depth("boxes-light-nearest", &pair.nearest(), w, h);
    check_depth("boxes-light-second", &pair.second(), w, h);
}
