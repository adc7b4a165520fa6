//! Reading depth images back: the inverses of [`crate::image_out`]'s depth writers, so that a map
//! another renderer made (a GPU's depth buffer read back) can be looked up as it is.
//!
//! Every reader takes the file's bytes and the size the image must have, checks that size from
//! the file's header **before** decoding any pixel (so a wrong or hostile file never makes the
//! reader allocate more than the stated size), and returns window depths row-major with **row 0
//! at the bottom**, the library's order. Orientation follows the writers (and so `render-mesh`):
//!
//! | reader | file | rows | values |
//! |---|---|---|---|
//! | [`depth_from_exr`] | OpenEXR, one f32 channel `Z` (or a single f32 channel of any name) | top row first, as image files store them | the f32 samples |
//! | [`depth_from_png16`] | PNG, 16-bit greyscale | top row first | `k/65535` for the stored `k`: exactly a unorm16 depth |
//! | [`depth_from_npy`] | NumPy `.npy` (versions 1–3), `<f4`, `>f4`, `<f8` or `>f8`, shape `(height, width)`, C or Fortran order | **row 0 at the bottom**, as `glReadPixels` returns them | the samples |
//!
//! The values are returned as they are: checking that they are depths (finite, in `[0, 1]`) is
//! the caller's, who knows which map and texel they belong to.

use std::fmt;
use std::io::Cursor;

/// Why a depth image could not be read.
#[non_exhaustive]
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DepthImageError {
    /// The bytes are not a well-formed file of the kind: the decoder's message.
    Decode {
        /// `"EXR"`, `"PNG"` or `"NPY"`.
        kind: &'static str,
        /// What the decoder said.
        message: String,
    },
    /// A well-formed file that holds something other than a depth image as the reader takes it.
    Content {
        /// `"EXR"`, `"PNG"` or `"NPY"`.
        kind: &'static str,
        /// What it holds, e.g. `"8-bit RGB"`, `"channels R, G, B"`, `"dtype '<i4'"`.
        found: String,
        /// What a depth image is, e.g. `"16-bit greyscale (L16)"`.
        expected: &'static str,
    },
    /// The image is not the size it must have.
    Size {
        /// `"EXR"`, `"PNG"` or `"NPY"`.
        kind: &'static str,
        /// The size it must have, width × height.
        expected: (u32, u32),
        /// The size its header states, width × height.
        found: (u64, u64),
    },
}

impl fmt::Display for DepthImageError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Decode { kind, message } => write!(f, "not a readable {kind} file: {message}"),
            Self::Content {
                kind,
                found,
                expected,
            } => write!(
                f,
                "the {kind} file holds {found}; a depth image is {expected}"
            ),
            Self::Size {
                kind,
                expected,
                found,
            } => write!(
                f,
                "the {kind} image is {}×{} but the map is {}×{}",
                found.0, found.1, expected.0, expected.1
            ),
        }
    }
}

impl std::error::Error for DepthImageError {}

/// `Ok` if the header's `found` size is `width × height`.
fn check_size(
    kind: &'static str,
    found: (u64, u64),
    width: u32,
    height: u32,
) -> Result<(), DepthImageError> {
    if found == (u64::from(width), u64::from(height)) {
        Ok(())
    } else {
        Err(DepthImageError::Size {
            kind,
            expected: (width, height),
            found,
        })
    }
}

/// Rows given top row first, returned with row 0 at the bottom.
fn bottom_up(values: &[f64], width: usize, height: usize) -> Vec<f64> {
    (0..height)
        .rev()
        .flat_map(|row| values[row * width..(row + 1) * width].iter().copied())
        .collect()
}

/// Window depths from an OpenEXR file of `width × height` pixels ([`crate::image_out::depth_exr`]
/// writes them): the first layer's f32 channel named `Z`, or its only channel if it has one,
/// top row first.
///
/// # Errors
/// [`DepthImageError::Decode`] for bytes that are not EXR; [`DepthImageError::Size`] if the first
/// layer is not `width × height`; [`DepthImageError::Content`] for deep data, no `Z` among
/// several channels, or samples that are not f32.
pub fn depth_from_exr(bytes: &[u8], width: u32, height: u32) -> Result<Vec<f64>, DepthImageError> {
    use exr::prelude::*;
    const KIND: &str = "EXR";
    let decode = |e: exr::error::Error| DepthImageError::Decode {
        kind: KIND,
        message: e.to_string(),
    };
    let meta =
        exr::meta::MetaData::read_from_buffered(Cursor::new(bytes), false).map_err(decode)?;
    let Some(header) = meta.headers.first() else {
        return Err(DepthImageError::Content {
            kind: KIND,
            found: "no layer".into(),
            expected: "a layer with a depth channel",
        });
    };
    check_size(
        KIND,
        (header.layer_size.0 as u64, header.layer_size.1 as u64),
        width,
        height,
    )?;
    if header.deep {
        return Err(DepthImageError::Content {
            kind: KIND,
            found: "deep data".into(),
            expected: "a flat image",
        });
    }
    let channels = &header.channels.list;
    let names = || {
        let names: Vec<String> = channels.iter().map(|c| c.name.to_string()).collect();
        format!("channels {}", names.join(", "))
    };
    let index = channels
        .iter()
        .position(|c| c.name.eq("Z"))
        .or((channels.len() == 1).then_some(0))
        .ok_or_else(|| DepthImageError::Content {
            kind: KIND,
            found: names(),
            expected: "a layer of one channel, or with a channel named Z",
        })?;
    let description = &channels[index];
    if description.sample_type != SampleType::F32 {
        return Err(DepthImageError::Content {
            kind: KIND,
            found: format!(
                "{:?} samples in channel {}",
                description.sample_type, description.name
            ),
            expected: "of 32-bit float (F32) samples",
        });
    }
    let name = description.name.clone();
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(Cursor::new(bytes))
        .map_err(decode)?;
    let layer = image.layer_data;
    check_size(
        KIND,
        (layer.size.0 as u64, layer.size.1 as u64),
        width,
        height,
    )?;
    let samples = layer
        .channel_data
        .list
        .into_iter()
        .find(|c| c.name == name)
        .map(|c| c.sample_data);
    let Some(FlatSamples::F32(samples)) = samples else {
        return Err(DepthImageError::Content {
            kind: KIND,
            found: names(),
            expected: "of 32-bit float samples",
        });
    };
    let values: Vec<f64> = samples.into_iter().map(f64::from).collect();
    Ok(bottom_up(&values, width as usize, height as usize))
}

/// Window depths from a 16-bit greyscale PNG of `width × height` pixels
/// ([`crate::image_out::depth_png16`] writes them): `k/65535` for each stored `k`, which is the
/// unorm16 depth `k` stands for exactly; top row first.
///
/// # Errors
/// [`DepthImageError::Decode`] for bytes that are not PNG; [`DepthImageError::Size`] if the
/// header states another size (checked before the pixels are decoded);
/// [`DepthImageError::Content`] for any colour type but 16-bit greyscale.
pub fn depth_from_png16(
    bytes: &[u8],
    width: u32,
    height: u32,
) -> Result<Vec<f64>, DepthImageError> {
    const KIND: &str = "PNG";
    let decode = |e: png::DecodingError| DepthImageError::Decode {
        kind: KIND,
        message: e.to_string(),
    };
    // No memory limit of the codec's own: the size is checked against the one asked for first.
    let mut decoder =
        png::Decoder::new_with_limits(Cursor::new(bytes), png::Limits { bytes: usize::MAX });
    // Palettes and bit depths below 8 expanded, 16 bits kept.
    decoder.set_transformations(png::Transformations::EXPAND);
    let header = decoder.read_header_info().map_err(decode)?;
    check_size(
        KIND,
        (u64::from(header.width), u64::from(header.height)),
        width,
        height,
    )?;
    let mut reader = decoder.read_info().map_err(decode)?;
    let (colour, depth) = reader.output_color_type();
    if (colour, depth) != (png::ColorType::Grayscale, png::BitDepth::Sixteen) {
        return Err(DepthImageError::Content {
            kind: KIND,
            found: format!("{colour:?} pixels of {} bits", depth as u8),
            expected: "16-bit greyscale (L16)",
        });
    }
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| DepthImageError::Decode {
            kind: KIND,
            message: "its pixels do not fit in memory".into(),
        })?;
    // Decoded serially, once: nothing for the workers to fill.
    let mut samples = vec![0; size];
    reader.next_frame(&mut samples).map_err(decode)?;
    let values: Vec<f64> = samples
        .as_chunks::<2>()
        .0
        .iter()
        .map(|&pair| f64::from(u16::from_be_bytes(pair)) / 65535.0)
        .collect();
    Ok(bottom_up(&values, width as usize, height as usize))
}

/// The longest NPY header read: 64 KiB. NumPy pads its headers to 64 bytes and writes about a
/// hundred; the bound only stops a corrupt length from being believed.
pub const MAX_NPY_HEADER_BYTES: usize = 1 << 16;

/// What an NPY header says about its array.
struct NpyHeader {
    /// The dtype, e.g. `<f4`.
    descr: String,
    /// Column-major (`fortran_order: True`).
    fortran: bool,
    /// The shape.
    shape: Vec<u64>,
}

/// Window depths from a NumPy `.npy` file of shape `(height, width)`
/// ([`crate::image_out::depth_npy`] writes them): f32 or f64 samples of either byte order, in C
/// or Fortran order, **row 0 at the bottom** (as `glReadPixels` reads a framebuffer back).
///
/// # Errors
/// [`DepthImageError::Decode`] for a bad magic, version, header or length;
/// [`DepthImageError::Size`] for another shape; [`DepthImageError::Content`] for a dtype other
/// than `<f4`, `>f4`, `<f8`, `>f8`, or an array that is not two-dimensional.
pub fn depth_from_npy(bytes: &[u8], width: u32, height: u32) -> Result<Vec<f64>, DepthImageError> {
    const KIND: &str = "NPY";
    let bad = |message: &str| DepthImageError::Decode {
        kind: KIND,
        message: message.into(),
    };
    let rest = bytes
        .strip_prefix(b"\x93NUMPY")
        .ok_or_else(|| bad("it does not start with \\x93NUMPY"))?;
    let (length, rest) = match rest {
        [1, 0, a, b, rest @ ..] => (usize::from(u16::from_le_bytes([*a, *b])), rest),
        [2 | 3, 0, a, b, c, d, rest @ ..] => (
            usize::try_from(u32::from_le_bytes([*a, *b, *c, *d])).unwrap_or(usize::MAX),
            rest,
        ),
        [major, minor, ..] => {
            return Err(bad(&format!(
                "format version {major}.{minor}; versions 1.0, 2.0 and 3.0 are read"
            )));
        }
        _ => return Err(bad("the file ends inside its preamble")),
    };
    if length > MAX_NPY_HEADER_BYTES || length > rest.len() {
        return Err(bad(&format!(
            "a header of {length} bytes in a file of {} bytes (at most {MAX_NPY_HEADER_BYTES} are read)",
            bytes.len()
        )));
    }
    let (header, data) = rest.split_at(length);
    let header = std::str::from_utf8(header).map_err(|_| bad("the header is not UTF-8"))?;
    let header = npy_header(header).map_err(|message| bad(&message))?;
    let (big_endian, size) = match header.descr.as_str() {
        "<f4" => (false, 4),
        ">f4" => (true, 4),
        "<f8" => (false, 8),
        ">f8" => (true, 8),
        other => {
            return Err(DepthImageError::Content {
                kind: KIND,
                found: format!("dtype '{other}'"),
                expected: "of dtype '<f4', '>f4', '<f8' or '>f8'",
            });
        }
    };
    let [rows, columns] = header.shape[..] else {
        return Err(DepthImageError::Content {
            kind: KIND,
            found: format!("an array of shape {:?}", header.shape),
            expected: "a two-dimensional array, shape (height, width)",
        });
    };
    check_size(KIND, (columns, rows), width, height)?;
    let (w, h) = (width as usize, height as usize);
    if data.len() != w * h * size {
        return Err(bad(&format!(
            "{} bytes of data for {h}×{w} samples of {size} bytes",
            data.len()
        )));
    }
    let samples: Vec<f64> = match (size, big_endian) {
        (4, false) => data
            .chunks_exact(4)
            .map(|b| f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])))
            .collect(),
        (4, true) => data
            .chunks_exact(4)
            .map(|b| f64::from(f32::from_be_bytes([b[0], b[1], b[2], b[3]])))
            .collect(),
        (_, false) => data
            .chunks_exact(8)
            .map(|b| f64::from_le_bytes(b.try_into().expect("eight bytes")))
            .collect(),
        (_, true) => data
            .chunks_exact(8)
            .map(|b| f64::from_be_bytes(b.try_into().expect("eight bytes")))
            .collect(),
    };
    if header.fortran {
        // Column-major: sample (row, column) at column·height + row.
        return Ok((0..h)
            .flat_map(|row| (0..w).map(move |column| (row, column)))
            .map(|(row, column)| samples[column * h + row])
            .collect());
    }
    Ok(samples)
}

/// The dtype, order and shape of an NPY header: a Python dict literal such as
/// `{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }`.
fn npy_header(text: &str) -> Result<NpyHeader, String> {
    let body = text
        .trim()
        .strip_prefix('{')
        .and_then(|t| t.strip_suffix('}'))
        .ok_or_else(|| format!("the header {text:?} is not a dict literal"))?;
    let (mut descr, mut fortran, mut shape) = (None, None, None);
    let mut rest = body.trim_start();
    while !rest.is_empty() {
        let (key, after) = quoted(rest).ok_or_else(|| format!("a key expected at {rest:?}"))?;
        let after = after
            .trim_start()
            .strip_prefix(':')
            .ok_or_else(|| format!("':' expected after {key:?}"))?
            .trim_start();
        let after = match key {
            "descr" => {
                let (value, after) = quoted(after)
                    .ok_or_else(|| format!("a string expected for 'descr' at {after:?}"))?;
                descr = Some(value.to_owned());
                after
            }
            "fortran_order" => {
                let (value, after) = if let Some(after) = after.strip_prefix("True") {
                    (true, after)
                } else if let Some(after) = after.strip_prefix("False") {
                    (false, after)
                } else {
                    return Err(format!(
                        "True or False expected for 'fortran_order' at {after:?}"
                    ));
                };
                fortran = Some(value);
                after
            }
            "shape" => {
                let inner = after
                    .strip_prefix('(')
                    .ok_or_else(|| format!("a tuple expected for 'shape' at {after:?}"))?;
                let close = inner
                    .find(')')
                    .ok_or_else(|| "the shape tuple is not closed".to_string())?;
                let dims = inner[..close]
                    .split(',')
                    .map(str::trim)
                    .filter(|d| !d.is_empty())
                    .map(|d| {
                        d.parse::<u64>()
                            .map_err(|_| format!("{d:?} in 'shape' is not a size"))
                    })
                    .collect::<Result<Vec<_>, _>>()?;
                shape = Some(dims);
                &inner[close + 1..]
            }
            other => return Err(format!("unknown key {other:?} in the header")),
        };
        let after = after.trim_start();
        rest = after.strip_prefix(',').unwrap_or(after).trim_start();
        if !after.starts_with(',') && !rest.is_empty() {
            return Err(format!("',' expected at {after:?}"));
        }
    }
    Ok(NpyHeader {
        descr: descr.ok_or("the header has no 'descr'")?,
        fortran: fortran.ok_or("the header has no 'fortran_order'")?,
        shape: shape.ok_or("the header has no 'shape'")?,
    })
}

/// A single-quoted (or double-quoted) Python string at the start of `text`, and what follows it.
fn quoted(text: &str) -> Option<(&str, &str)> {
    let quote = text.chars().next().filter(|c| *c == '\'' || *c == '"')?;
    let inner = &text[1..];
    let end = inner.find(quote)?;
    Some((&inner[..end], &inner[end + 1..]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_out::{depth_exr, depth_npy, depth_png16};

    /// Six depths of a 3 × 2 image, row 0 at the bottom; exact in f32 and as unorm16 keys.
    const DEPTHS: [f64; 6] = [0.0, 0.25, 0.5, 1.0, 0.75, 0.125];

    #[test]
    fn the_writers_files_read_back_exactly_with_row_0_at_the_bottom() {
        let exr = depth_exr(&DEPTHS, 3, 2).unwrap();
        assert_eq!(depth_from_exr(&exr, 3, 2).unwrap(), DEPTHS);
        let npy = depth_npy(&DEPTHS, 3, 2).unwrap();
        assert_eq!(depth_from_npy(&npy, 3, 2).unwrap(), DEPTHS);
        let unorm: Vec<f64> = (0..6).map(|k| f64::from(k * 9000) / 65535.0).collect();
        let png = depth_png16(&unorm, 3, 2).unwrap();
        assert_eq!(depth_from_png16(&png, 3, 2).unwrap(), unorm);
    }

    #[test]
    fn sizes_are_checked_before_pixels_are_decoded() {
        let exr = depth_exr(&DEPTHS, 3, 2).unwrap();
        let error = depth_from_exr(&exr, 2, 3).unwrap_err();
        assert_eq!(
            error,
            DepthImageError::Size {
                kind: "EXR",
                expected: (2, 3),
                found: (3, 2)
            }
        );
        assert_eq!(error.to_string(), "the EXR image is 3×2 but the map is 2×3");
        let png = depth_png16(&DEPTHS, 3, 2).unwrap();
        assert!(matches!(
            depth_from_png16(&png, 3, 3),
            Err(DepthImageError::Size { .. })
        ));
        let npy = depth_npy(&DEPTHS, 3, 2).unwrap();
        assert!(matches!(
            depth_from_npy(&npy, 2, 3),
            Err(DepthImageError::Size { found: (3, 2), .. })
        ));
    }

    /// An NPY file with `header` (padded as NumPy pads it) and `data`.
    fn npy(header: &str, data: &[u8]) -> Vec<u8> {
        let mut header = header.to_string();
        while !(10 + header.len() + 1).is_multiple_of(64) {
            header.push(' ');
        }
        header.push('\n');
        let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
        bytes.extend_from_slice(&u16::try_from(header.len()).unwrap().to_le_bytes());
        bytes.extend_from_slice(header.as_bytes());
        bytes.extend_from_slice(data);
        bytes
    }

    #[test]
    fn npy_reads_f64_big_endian_and_fortran_order() {
        let le: Vec<u8> = DEPTHS.iter().flat_map(|v| v.to_le_bytes()).collect();
        let file = npy(
            "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }",
            &le,
        );
        assert_eq!(depth_from_npy(&file, 3, 2).unwrap(), DEPTHS);
        // The six depths are exact in f32.
        #[expect(clippy::cast_possible_truncation, reason = "exact in f32")]
        let be: Vec<u8> = DEPTHS
            .iter()
            .flat_map(|v| (*v as f32).to_be_bytes())
            .collect();
        let file = npy(
            "{'descr': '>f4', 'fortran_order': False, 'shape': (2, 3), }",
            &be,
        );
        assert_eq!(depth_from_npy(&file, 3, 2).unwrap(), DEPTHS);
        // The same array in column-major order: columns (0, 1.0), (0.25, 0.75), (0.5, 0.125).
        let columns = [0.0f64, 1.0, 0.25, 0.75, 0.5, 0.125];
        let data: Vec<u8> = columns.iter().flat_map(|v| v.to_le_bytes()).collect();
        let file = npy(
            "{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3), }",
            &data,
        );
        assert_eq!(depth_from_npy(&file, 3, 2).unwrap(), DEPTHS);
    }

    #[test]
    fn npy_refuses_other_dtypes_shapes_and_lengths_by_name() {
        let data = [0u8; 24];
        let dtype = npy(
            "{'descr': '<i4', 'fortran_order': False, 'shape': (2, 3), }",
            &data,
        );
        let error = depth_from_npy(&dtype, 3, 2).unwrap_err();
        assert!(matches!(error, DepthImageError::Content { .. }), "{error}");
        assert!(error.to_string().contains("dtype '<i4'"), "{error}");
        let three = npy(
            "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3, 1), }",
            &data,
        );
        assert!(matches!(
            depth_from_npy(&three, 3, 2),
            Err(DepthImageError::Content { .. })
        ));
        let short = npy(
            "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }",
            &data[..20],
        );
        let message = depth_from_npy(&short, 3, 2).unwrap_err().to_string();
        assert!(message.contains("20 bytes of data"), "{message}");
        assert!(matches!(
            depth_from_npy(b"\x93NUMPY\x01\x00\xff\xff", 3, 2),
            Err(DepthImageError::Decode { .. })
        ));
        assert!(matches!(
            depth_from_npy(b"P6\n", 3, 2),
            Err(DepthImageError::Decode { .. })
        ));
    }

    #[test]
    fn png_refuses_8_bit_and_colour_images() {
        let rgb = crate::image_out::rgb_png(&[[255, 0, 0]; 6], 3, 2).unwrap();
        let error = depth_from_png16(&rgb, 3, 2).unwrap_err();
        assert!(matches!(error, DepthImageError::Content { .. }), "{error}");
        assert!(error.to_string().contains("16-bit greyscale"), "{error}");
        assert!(matches!(
            depth_from_png16(b"not a png", 3, 2),
            Err(DepthImageError::Decode { .. })
        ));
    }

    #[test]
    fn exr_refuses_garbage_and_half_floats() {
        assert!(matches!(
            depth_from_exr(b"not an exr", 3, 2),
            Err(DepthImageError::Decode { .. })
        ));
        use exr::prelude::*;
        let half: Vec<f16> = DEPTHS.iter().map(|v| f16::from_f64(*v)).collect();
        let channel = AnyChannel::new("Z", FlatSamples::F16(half));
        let image =
            Image::from_channels((3, 2), AnyChannels::sort(SmallVec::from_vec(vec![channel])));
        let mut bytes = Cursor::new(Vec::new());
        image.write().to_buffered(&mut bytes).unwrap();
        let error = depth_from_exr(&bytes.into_inner(), 3, 2).unwrap_err();
        assert!(error.to_string().contains("F16"), "{error}");
    }
}
