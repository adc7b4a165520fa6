//! Writing results as image files, in memory (the caller writes the bytes atomically).
//!
//! Every writer takes a row-major image with **row 0 at the bottom** (as the targets return them)
//! and writes the **top row first**, as image files expect.
//!
//! * [`depth_exr`]: window depth as one f32 channel `Z` — exactly what an f32 target stores.
//! * [`depth_png16`]: a 16-bit greyscale preview, `round(z·65535)`, far = white.
//! * [`rgb_png`]: 8-bit colour.
//! * [`layers_exr`]: named f32 or u32 channels in one EXR file (the per-pixel exports).
//! * [`depth_npy`], [`array_npy`]: NumPy arrays (f32 depths; any [`NpyElement`], several channels
//!   per pixel), **row 0 at the bottom** (the one exception, so that they line up with
//!   `glReadPixels` dumps).

use std::io::Cursor;

use crate::error::RasterError;

/// Row-major values with row 0 at the bottom, copied top row first, a row at a time (`width` > 0
/// dividing `values.len()`, as [`check_len`] ensures).
fn top_down<T: Copy>(values: &[T], width: usize) -> Vec<T> {
    let mut flipped = Vec::with_capacity(values.len());
    for row in values.chunks_exact(width).rev() {
        flipped.extend_from_slice(row);
    }
    flipped
}

fn check_len(
    len: usize,
    width: u32,
    height: u32,
    per_pixel: usize,
) -> Result<(usize, usize), RasterError> {
    let (w, h) = (width as usize, height as usize);
    if w == 0 || h == 0 || len != w * h * per_pixel {
        return Err(RasterError::ImageSize {
            width,
            height,
            values: len,
        });
    }
    Ok((w, h))
}

/// Window depths as an OpenEXR file with one f32 channel `Z` (each depth rounded to f32, which is
/// exact for depths read from an f32 target).
pub fn depth_exr(depths: &[f64], width: u32, height: u32) -> Result<Vec<u8>, RasterError> {
    #[expect(clippy::cast_possible_truncation, reason = "EXR stores f32 depth")]
    let samples: Vec<f32> = depths.iter().map(|&z| z as f32).collect();
    layers_exr(&[("Z", ExrLayer::F32(&samples))], width, height)
}

/// One channel of an EXR file: row-major, row 0 at the bottom, one value per pixel.
#[derive(Clone, Copy, Debug)]
pub enum ExrLayer<'a> {
    /// 32-bit float samples.
    F32(&'a [f32]),
    /// 32-bit unsigned samples (e.g. triangle ids).
    U32(&'a [u32]),
}

impl ExrLayer<'_> {
    fn len(&self) -> usize {
        match self {
            Self::F32(values) => values.len(),
            Self::U32(values) => values.len(),
        }
    }
}

/// Named channels as one OpenEXR file, top row first (EXR's own order). EXR sorts channels by
/// name, so readers find them by name, not position.
pub fn layers_exr(
    layers: &[(&str, ExrLayer<'_>)],
    width: u32,
    height: u32,
) -> Result<Vec<u8>, RasterError> {
    use exr::prelude::*;
    let mut channels = SmallVec::new();
    for (name, layer) in layers {
        let (w, _) = check_len(layer.len(), width, height, 1)?;
        let samples = match layer {
            ExrLayer::F32(values) => FlatSamples::F32(top_down(values, w)),
            ExrLayer::U32(values) => FlatSamples::U32(top_down(values, w)),
        };
        channels.push(AnyChannel::new(*name, samples));
    }
    if channels.is_empty() {
        return Err(RasterError::Encode("an EXR file needs a channel".into()));
    }
    let image = Image::from_channels(
        (width as usize, height as usize),
        AnyChannels::sort(channels),
    );
    let mut bytes = Cursor::new(Vec::new());
    image
        .write()
        .to_buffered(&mut bytes)
        .map_err(|e| RasterError::Encode(e.to_string()))?;
    Ok(bytes.into_inner())
}

/// Window depths as a 16-bit greyscale PNG preview: `round(z·65535)`, far (1) white.
pub fn depth_png16(depths: &[f64], width: u32, height: u32) -> Result<Vec<u8>, RasterError> {
    let (w, _) = check_len(depths.len(), width, height, 1)?;
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "clamped to [0, 65535.5)"
    )]
    let unorm: Vec<u16> = depths
        .chunks_exact(w)
        .rev()
        .flatten()
        .map(|z| (z.clamp(0.0, 1.0) * 65535.0 + 0.5) as u16)
        .collect();
    // PNG stores 16-bit samples big-endian.
    let samples: Vec<u8> = unorm.iter().flat_map(|v| v.to_be_bytes()).collect();
    encode_png(
        &samples,
        (width, height),
        png::ColorType::Grayscale,
        png::BitDepth::Sixteen,
    )
}

/// 8-bit RGB pixels (`[r, g, b]` per pixel, row 0 at the bottom) as a PNG.
pub fn rgb_png(pixels: &[[u8; 3]], width: u32, height: u32) -> Result<Vec<u8>, RasterError> {
    let (w, _) = check_len(pixels.len(), width, height, 1)?;
    encode_png(
        top_down(pixels, w).as_flattened(),
        (width, height),
        png::ColorType::Rgb,
        png::BitDepth::Eight,
    )
}

/// Window depths as a NumPy `.npy` file (version 1.0, little-endian f32, shape `(height, width)`,
/// row 0 at the bottom as GL reads pixels back).
pub fn depth_npy(depths: &[f64], width: u32, height: u32) -> Result<Vec<u8>, RasterError> {
    #[expect(clippy::cast_possible_truncation, reason = "the file holds f32")]
    let values: Vec<f32> = depths.iter().map(|&z| z as f32).collect();
    array_npy(&values, width, height, 1)
}

/// An element type of a NumPy array file, little-endian.
pub trait NpyElement: Copy {
    /// NumPy's type descriptor (`'<f4'`, …).
    const DESCR: &'static str;
    /// Appends the value's little-endian bytes.
    fn put(self, out: &mut Vec<u8>);
}

macro_rules! npy_element {
    ($($t:ty => $descr:literal),* $(,)?) => {$(
        impl NpyElement for $t {
            const DESCR: &'static str = $descr;
            fn put(self, out: &mut Vec<u8>) {
                out.extend_from_slice(&self.to_le_bytes());
            }
        }
    )*};
}

npy_element!(f32 => "<f4", f64 => "<f8", u32 => "<u4", u8 => "|u1");

/// Row-major values with row 0 at the bottom, `channels` per pixel, as a NumPy `.npy` file
/// (version 1.0): shape `(height, width)` for one channel, else `(height, width, channels)`, rows
/// kept in that order (row 0 at the bottom, as GL reads pixels back).
pub fn array_npy<T: NpyElement>(
    values: &[T],
    width: u32,
    height: u32,
    channels: usize,
) -> Result<Vec<u8>, RasterError> {
    check_len(values.len(), width, height, channels)?;
    let shape = if channels == 1 {
        format!("({height}, {width})")
    } else {
        format!("({height}, {width}, {channels})")
    };
    let mut header = format!(
        "{{'descr': '{}', 'fortran_order': False, 'shape': {shape}, }}",
        T::DESCR
    );
    // Pad so that the data starts on a multiple of 64 bytes, ending the header with a newline.
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let length = u16::try_from(header.len()).map_err(|e| RasterError::Encode(e.to_string()))?;
    let mut bytes = Vec::with_capacity(10 + header.len() + std::mem::size_of_val(values));
    bytes.extend_from_slice(b"\x93NUMPY\x01\x00");
    bytes.extend_from_slice(&length.to_le_bytes());
    bytes.extend_from_slice(header.as_bytes());
    for &value in values {
        value.put(&mut bytes);
    }
    Ok(bytes)
}

/// `data` (rows top first, samples big-endian) as a `width × height` PNG: the `png` crate's fast
/// compression and adaptive filter, the settings of the `image` crate's encoder, which wrote these
/// files before it was dropped from the build — the same bytes.
fn encode_png(
    data: &[u8],
    (width, height): (u32, u32),
    colour: png::ColorType,
    depth: png::BitDepth,
) -> Result<Vec<u8>, RasterError> {
    let encode = |e: png::EncodingError| RasterError::Encode(e.to_string());
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, width, height);
    encoder.set_color(colour);
    encoder.set_depth(depth);
    encoder.set_compression(png::Compression::Fast);
    encoder.set_filter(png::Filter::Adaptive);
    let mut writer = encoder.write_header().map_err(encode)?;
    writer.write_image_data(data).map_err(encode)?;
    writer.finish().map_err(encode)?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_start_with_their_magic_and_sizes_are_checked() {
        let depths = [0.0, 0.25, 0.5, 1.0, 0.75, 0.125];
        let exr = depth_exr(&depths, 3, 2).unwrap();
        assert_eq!(&exr[..4], &[0x76, 0x2f, 0x31, 0x01]);
        let png = depth_png16(&depths, 3, 2).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        assert!(depth_png16(&depths, 4, 2).is_err());
        let rgb = rgb_png(&[[255, 0, 0]; 6], 2, 3).unwrap();
        assert_eq!(&rgb[..4], b"\x89PNG");
    }

    #[test]
    fn npy_has_a_valid_header_and_bottom_row_first() {
        let npy = depth_npy(&[0.0, 0.5, 1.0, 0.25, 0.75, 0.125], 3, 2).unwrap();
        assert_eq!(&npy[..8], b"\x93NUMPY\x01\x00");
        let header_len = usize::from(u16::from_le_bytes([npy[8], npy[9]]));
        assert_eq!((10 + header_len) % 64, 0);
        let header = std::str::from_utf8(&npy[10..10 + header_len]).unwrap();
        assert!(
            header.contains("'shape': (2, 3)") && header.ends_with('\n'),
            "{header}"
        );
        let first = f32::from_le_bytes(npy[10 + header_len..14 + header_len].try_into().unwrap());
        assert_eq!(first, 0.0);
        assert_eq!(npy.len(), 10 + header_len + 6 * 4);
    }

    #[test]
    fn npy_arrays_have_their_type_and_channels() {
        let values: Vec<u8> = (0..12).collect();
        let npy = array_npy(&values, 2, 2, 3).unwrap();
        let header_len = usize::from(u16::from_le_bytes([npy[8], npy[9]]));
        let header = std::str::from_utf8(&npy[10..10 + header_len]).unwrap();
        assert!(
            header.contains("'descr': '|u1'") && header.contains("'shape': (2, 2, 3)"),
            "{header}"
        );
        assert_eq!(&npy[10 + header_len..], &values[..]);
        let wide = array_npy(&[1.5_f64, -2.0], 2, 1, 1).unwrap();
        let header_len = usize::from(u16::from_le_bytes([wide[8], wide[9]]));
        assert_eq!(
            f64::from_le_bytes(wide[10 + header_len + 8..].try_into().unwrap()),
            -2.0
        );
        assert!(array_npy(&values, 2, 2, 2).is_err());
    }

    #[test]
    fn exr_layers_read_back_by_name_top_row_first() {
        use exr::prelude::*;
        let depth = [0.25_f32, 0.5, 0.75, 1.0, 0.0, 0.125];
        let ids = [7_u32, 8, 9, 10, 11, 12];
        let bytes = layers_exr(
            &[("Z", ExrLayer::F32(&depth)), ("id", ExrLayer::U32(&ids))],
            3,
            2,
        )
        .unwrap();
        let image = read()
            .no_deep_data()
            .largest_resolution_level()
            .all_channels()
            .all_layers()
            .all_attributes()
            .from_buffered(std::io::Cursor::new(bytes))
            .unwrap();
        let channels = &image.layer_data[0].channel_data.list;
        let by_name = |name: &str| {
            channels
                .iter()
                .find(|c| c.name.to_string() == name)
                .map(|c| c.sample_data.clone())
                .unwrap()
        };
        assert_eq!(
            by_name("Z"),
            FlatSamples::F32(vec![1.0, 0.0, 0.125, 0.25, 0.5, 0.75])
        );
        assert_eq!(by_name("id"), FlatSamples::U32(vec![10, 11, 12, 7, 8, 9]));
        assert!(layers_exr(&[("Z", ExrLayer::F32(&depth[..4]))], 3, 2).is_err());
        assert!(layers_exr(&[], 3, 2).is_err());
    }

    #[test]
    fn rows_are_flipped_to_top_first() {
        let v: Vec<u8> = top_down(&[1, 2, 3, 4, 5, 6], 3);
        assert_eq!(v, [4, 5, 6, 1, 2, 3]);
    }
}
