//! The buffers a scene's accessors read: the GLB binary chunk, `data:` URIs (base64) and files
//! relative to the glTF file (glTF 2.0 §2.8, §3.6.1), each bounded and checked against its
//! `byteLength`.

use std::borrow::Cow;
use std::path::Path;

use base64::Engine as _;
use base64::engine::{DecodePaddingMode, GeneralPurpose, GeneralPurposeConfig};
use gltf::json;

use super::MAX_GLTF_BYTES;
use super::error::{GltfError, GltfObject, GltfObjectKind, GltfProblem};
use crate::read::read_bounded;

/// Standard base64 (RFC 4648 §4), padded or not: data URIs are written both ways.
const BASE64: GeneralPurpose = GeneralPurpose::new(
    &base64::alphabet::STANDARD,
    GeneralPurposeConfig::new().with_decode_padding_mode(DecodePaddingMode::Indifferent),
);

/// The data of the buffers that are needed, by buffer index (`None` for the others); each is
/// exactly its `byteLength` long.
pub(super) type BufferData<'a> = Vec<Option<Cow<'a, [u8]>>>;

/// Loads the buffers whose indices are in `needed`. The sum of their `byteLength`s must be at
/// most [`MAX_GLTF_BYTES`], checked before any is read.
pub(super) fn load<'a>(
    root: &json::Root,
    bin: Option<&'a [u8]>,
    needed: &[bool],
    path: &Path,
) -> Result<BufferData<'a>, GltfError> {
    let total: u64 = root
        .buffers
        .iter()
        .zip(needed)
        .filter(|(_, needed)| **needed)
        .map(|(buffer, _)| buffer.byte_length.0)
        .fold(0, u64::saturating_add);
    if total > MAX_GLTF_BYTES {
        return Err(GltfError::TooLarge {
            path: path.to_owned(),
            what: "bytes of buffers",
            count: total,
            limit: MAX_GLTF_BYTES,
        });
    }
    root.buffers
        .iter()
        .zip(needed)
        .enumerate()
        .map(|(index, (buffer, &needed))| {
            if !needed {
                return Ok(None);
            }
            let object = GltfObject::new(GltfObjectKind::Buffer, index, buffer.name.as_deref());
            let error = |problem| GltfError::object(path, vec![object.clone()], problem);
            let data = source(buffer, index, bin, path).map_err(error)?;
            let declared = buffer.byte_length.0;
            if (data.len() as u64) < declared {
                return Err(error(GltfProblem::BufferTooShort {
                    declared,
                    found: data.len() as u64,
                }));
            }
            // declared ≤ data.len(), so it fits a usize.
            let length = usize::try_from(declared).map_or(data.len(), |n| n.min(data.len()));
            Ok(Some(match data {
                Cow::Borrowed(data) => Cow::Borrowed(&data[..length]),
                Cow::Owned(mut data) => {
                    data.truncate(length);
                    Cow::Owned(data)
                }
            }))
        })
        .collect()
}

/// The bytes of buffer `index`: the GLB binary chunk for buffer 0 without a `uri` (glTF 2.0
/// §3.6.1.2), a decoded `data:` URI, or the file the URI names relative to the glTF file.
fn source<'a>(
    buffer: &json::Buffer,
    index: usize,
    bin: Option<&'a [u8]>,
    path: &Path,
) -> Result<Cow<'a, [u8]>, GltfProblem> {
    let Some(uri) = &buffer.uri else {
        return match (index, bin) {
            (0, Some(bin)) => Ok(Cow::Borrowed(bin)),
            (0, None) => Err(GltfProblem::BufferSource {
                reason: "has no `uri`, and the file has no GLB binary chunk for it".to_owned(),
            }),
            _ => Err(GltfProblem::BufferSource {
                reason: "has no `uri`; only buffer 0 of a GLB file may refer to its binary chunk"
                    .to_owned(),
            }),
        };
    };
    if let Some(data) = strip_prefix_ignore_case(uri, "data:") {
        return decode_data_uri(data).map(Cow::Owned);
    }
    let relative = relative_path(uri)?;
    let file = path.parent().unwrap_or(Path::new("")).join(relative);
    read_bounded(&file, MAX_GLTF_BYTES, "a glTF buffer", "MAX_GLTF_BYTES")
        .map(Cow::Owned)
        .map_err(GltfProblem::BufferFile)
}

/// `text` without `prefix`, compared ignoring ASCII case (URI schemes are case-insensitive,
/// RFC 3986 §3.1).
fn strip_prefix_ignore_case<'t>(text: &'t str, prefix: &str) -> Option<&'t str> {
    let head = text.get(..prefix.len())?;
    head.eq_ignore_ascii_case(prefix)
        .then(|| &text[prefix.len()..])
}

/// The bytes of a `data:` URI (after `data:`): `[<media type>];base64,<data>` (RFC 2397). Buffers
/// are binary, so only base64 data is accepted.
fn decode_data_uri(data: &str) -> Result<Vec<u8>, GltfProblem> {
    let Some((header, payload)) = data.split_once(',') else {
        return Err(GltfProblem::BufferSource {
            reason: "has a data: URI without the comma that starts its data".to_owned(),
        });
    };
    if !header.to_ascii_lowercase().ends_with(";base64") {
        return Err(GltfProblem::BufferSource {
            reason: format!(
                "has a data: URI of `{header}` that is not base64; buffers are base64 data URIs"
            ),
        });
    }
    BASE64
        .decode(payload)
        .map_err(|error| GltfProblem::BufferSource {
            reason: format!("has a data: URI whose base64 does not decode: {error}"),
        })
}

/// The file path of a relative URI reference (RFC 3986 §4.2), percent-decoded. A URI with a
/// scheme (`http:`, `file:`) or an absolute path is refused: buffers are read from the glTF
/// file's directory only.
fn relative_path(uri: &str) -> Result<String, GltfProblem> {
    let scheme_end = uri.find(':').filter(|&end| {
        let scheme = &uri[..end];
        scheme.starts_with(|c: char| c.is_ascii_alphabetic())
            && scheme
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
    });
    if let Some(end) = scheme_end {
        return Err(GltfProblem::BufferSource {
            reason: format!(
                "has the URI `{uri}`, whose scheme {}: is not read; buffers are data: URIs or \
                 paths relative to the glTF file",
                &uri[..end]
            ),
        });
    }
    if uri.starts_with('/') || uri.starts_with('\\') {
        return Err(GltfProblem::BufferSource {
            reason: format!(
                "has the URI `{uri}`, an absolute path; buffers are data: URIs or paths \
                 relative to the glTF file"
            ),
        });
    }
    percent_decode(uri).ok_or_else(|| GltfProblem::BufferSource {
        reason: format!(
            "has the URI `{uri}`, whose percent-encoding is malformed or not UTF-8 (RFC 3986 §2.1)"
        ),
    })
}

/// `text` with every `%XY` replaced by the byte 0xXY (RFC 3986 §2.1); `None` if a `%` is not
/// followed by two hexadecimal digits or the result is not UTF-8.
fn percent_decode(text: &str) -> Option<String> {
    let bytes = text.as_bytes();
    let mut decoded = Vec::with_capacity(bytes.len());
    let mut k = 0;
    while k < bytes.len() {
        if bytes[k] == b'%' {
            let hex = text.get(k + 1..k + 3)?;
            decoded.push(u8::from_str_radix(hex, 16).ok()?);
            k += 3;
        } else {
            decoded.push(bytes[k]);
            k += 1;
        }
    }
    String::from_utf8(decoded).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_uris_decode_with_and_without_padding() {
        assert_eq!(
            decode_data_uri("application/octet-stream;base64,AAEC").expect("valid"),
            [0, 1, 2]
        );
        assert_eq!(
            decode_data_uri("application/gltf-buffer;BASE64,AAE=").expect("padded"),
            [0, 1]
        );
        assert_eq!(decode_data_uri(";base64,AAE").expect("unpadded"), [0, 1]);
        for (uri, message) in [
            ("application/octet-stream,AAEC", "not base64"),
            ("application/octet-stream;base64", "without the comma"),
            (";base64,A!!", "does not decode"),
        ] {
            match decode_data_uri(uri) {
                Err(GltfProblem::BufferSource { reason }) => {
                    assert!(reason.contains(message), "{uri}: {reason}");
                }
                other => panic!("{uri}: {other:?}"),
            }
        }
    }

    #[test]
    fn relative_uris_are_percent_decoded_and_others_refused() {
        assert_eq!(
            relative_path("Box%20With%20Spaces.bin").expect("relative"),
            "Box With Spaces.bin"
        );
        assert_eq!(
            relative_path("sub/dir/a.bin").expect("relative"),
            "sub/dir/a.bin"
        );
        assert_eq!(relative_path("%E2%82%AC.bin").expect("UTF-8"), "€.bin");
        for uri in [
            "http://example.com/a.bin",
            "file:///tmp/a.bin",
            "/tmp/a.bin",
            "a%2.bin",
            "%FF.bin",
        ] {
            assert!(relative_path(uri).is_err(), "{uri}");
        }
    }

    #[test]
    fn the_data_scheme_is_case_insensitive() {
        assert_eq!(strip_prefix_ignore_case("DATA:xyz", "data:"), Some("xyz"));
        assert_eq!(strip_prefix_ignore_case("dat", "data:"), None);
        assert_eq!(strip_prefix_ignore_case("é", "data:"), None);
    }
}
