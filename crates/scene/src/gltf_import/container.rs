//! The glTF document: the GLB container split into its chunks (glTF 2.0 §4), the JSON parsed into
//! `gltf::json`'s schema types, its version and required extensions checked, and `gltf`'s schema
//! validation run.

use std::path::Path;

use gltf::json::{self, validation::Validate};
use serde::Deserialize;

use super::error::GltfError;

/// The magic number that opens a GLB file (glTF 2.0 §4).
const GLB_MAGIC: &[u8; 4] = b"glTF";
/// The GLB container version of glTF 2.0.
const GLB_VERSION: u32 = 2;
/// The type of the JSON chunk, `JSON` as a little-endian u32.
const CHUNK_JSON: u32 = 0x4E4F_534A;
/// The type of the binary chunk, `BIN\0` as a little-endian u32.
const CHUNK_BIN: u32 = 0x004E_4942;

/// The extensions shadowlab reads; a file that requires any other is refused.
pub(super) const READ_EXTENSIONS: [&str; 1] = ["KHR_lights_punctual"];

/// A parsed and validated glTF document: its JSON and, for a GLB file, its binary chunk.
pub(super) struct Document<'a> {
    /// The JSON, every index in range and every enumeration known (`gltf`'s validation).
    pub(super) root: json::Root,
    /// The GLB binary chunk, which buffer 0 refers to when it has no `uri`.
    pub(super) bin: Option<&'a [u8]>,
}

/// Parses `bytes`, the contents of `path`: a GLB container if it starts with `glTF`, else JSON.
pub(super) fn parse<'a>(bytes: &'a [u8], path: &Path) -> Result<Document<'a>, GltfError> {
    let (json_bytes, bin) = if bytes.starts_with(GLB_MAGIC) {
        split_glb(bytes).map_err(|message| GltfError::Format {
            path: path.to_owned(),
            message,
        })?
    } else {
        (bytes, None)
    };
    let root: json::Root =
        json::deserialize::from_slice(json_bytes).map_err(|error| GltfError::Format {
            path: path.to_owned(),
            message: version_problem(json_bytes).unwrap_or_else(|| error.to_string()),
        })?;
    if let Some(message) = check_version(&root.asset.version, root.asset.min_version.as_deref()) {
        return Err(GltfError::Format {
            path: path.to_owned(),
            message,
        });
    }
    let unsupported: Vec<String> = root
        .extensions_required
        .iter()
        .filter(|name| !READ_EXTENSIONS.contains(&name.as_str()))
        .cloned()
        .collect();
    if !unsupported.is_empty() {
        return Err(GltfError::UnsupportedExtensions {
            path: path.to_owned(),
            extensions: unsupported,
        });
    }
    validate(&root, path)?;
    Ok(Document { root, bin })
}

/// The JSON chunk and the binary chunk (if any) of a GLB file. The header's length must be the
/// file's; the first chunk must be JSON, a second chunk, if there is one, binary; chunks after it
/// are ignored, as glTF 2.0 §4 asks of chunk types a loader does not know.
fn split_glb(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), String> {
    let word = |offset: usize| {
        bytes
            .get(offset..offset + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    };
    let (Some(version), Some(length)) = (word(4), word(8)) else {
        return Err(format!(
            "a GLB file of {} bytes, shorter than its 12-byte header",
            bytes.len()
        ));
    };
    if version != GLB_VERSION {
        return Err(format!(
            "GLB version {version}; glTF 2.0's GLB container is version {GLB_VERSION}"
        ));
    }
    if u64::from(length) != bytes.len() as u64 {
        return Err(format!(
            "the GLB header gives a length of {length} bytes, but the file has {}",
            bytes.len()
        ));
    }
    let mut chunks = Vec::new();
    let mut offset = 12_usize;
    while offset < bytes.len() {
        let (Some(chunk_length), Some(chunk_type)) = (word(offset), word(offset + 4)) else {
            return Err(format!(
                "chunk {} at byte {offset} is cut off in its 8-byte header",
                chunks.len()
            ));
        };
        let start = offset + 8;
        let end = start
            .checked_add(chunk_length as usize)
            .filter(|&end| end <= bytes.len())
            .ok_or_else(|| {
                format!(
                    "chunk {} at byte {offset} claims {chunk_length} bytes, beyond the file's end",
                    chunks.len()
                )
            })?;
        chunks.push((chunk_type, &bytes[start..end]));
        offset = end;
    }
    match chunks.as_slice() {
        [(CHUNK_JSON, json), rest @ ..] => {
            let bin = match rest.first() {
                Some(&(CHUNK_BIN, bin)) => Some(bin),
                Some(&(other, _)) => {
                    return Err(format!(
                        "the second chunk has type {other:#010x}, not BIN (0x004e4942)"
                    ));
                }
                None => None,
            };
            Ok((json, bin))
        }
        [(other, _), ..] => Err(format!(
            "the first chunk has type {other:#010x}, not JSON (0x4e4f534a)"
        )),
        [] => Err("a GLB file without a JSON chunk".to_owned()),
    }
}

/// Why `asset.version` (and `asset.minVersion`) rule out reading the file as glTF 2.0, if they
/// do: the major version must be 2, and a `minVersion` must be 2.0 (glTF 2.0 §2.5).
fn check_version(version: &str, min_version: Option<&str>) -> Option<String> {
    if version.split('.').next() != Some("2") {
        return Some(format!(
            "asset.version is \"{version}\"; only glTF 2.0 is read"
        ));
    }
    match min_version {
        Some(min) if min != "2.0" => Some(format!(
            "asset.minVersion is \"{min}\"; only glTF 2.0 is read"
        )),
        _ => None,
    }
}

/// For JSON that does not fit the glTF 2.0 schema: the version problem, if the file says it is
/// another version (a glTF 1.0 file fails the 2.0 schema long before its version is checked).
fn version_problem(json_bytes: &[u8]) -> Option<String> {
    #[derive(Deserialize)]
    struct Probe {
        asset: AssetProbe,
    }
    #[derive(Deserialize)]
    struct AssetProbe {
        version: serde_json::Value,
    }
    let probe: Probe = serde_json::from_slice(json_bytes).ok()?;
    match probe.asset.version {
        serde_json::Value::String(version) => check_version(&version, None),
        other => Some(format!(
            "asset.version is {other}, not a string; only glTF 2.0 (\"2.0\") is read"
        )),
    }
}

/// `gltf`'s schema validation, reported as [`GltfError::Invalid`]. Two of its rules are not
/// applied: `POSITION` accessors without `min` and `max` are read (shadowlab computes bounds from
/// the data, and many exporters omit them), and required extensions were checked before.
///
/// `gltf`'s validation indexes the accessor of every primitive's `POSITION` without checking it,
/// so that index is checked here first.
fn validate(root: &json::Root, path: &Path) -> Result<(), GltfError> {
    let mut problems = Vec::new();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let position = primitive.attributes.get(&json::validation::Checked::Valid(
                json::mesh::Semantic::Positions,
            ));
            if position.is_some_and(|index| index.value() >= root.accessors.len()) {
                problems.push((
                    format!("meshes[{m}].primitives[{p}].attributes[\"POSITION\"]"),
                    "index out of bounds".to_owned(),
                ));
            }
        }
    }
    if problems.is_empty() {
        root.validate(root, json::Path::new, &mut |json_path, error| {
            let json_path = json_path().as_str().to_owned();
            let bounds_of_positions = json_path.ends_with("[\"POSITION\"].min")
                || json_path.ends_with("[\"POSITION\"].max");
            let required_extension = json_path.starts_with("extensionsRequired");
            if !bounds_of_positions && !required_extension {
                problems.push((json_path, error.to_string()));
            }
        });
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(GltfError::Invalid {
            path: path.to_owned(),
            problems,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glb(chunks: &[(u32, &[u8])]) -> Vec<u8> {
        let mut body = Vec::new();
        for (kind, data) in chunks {
            body.extend_from_slice(&u32::try_from(data.len()).expect("small").to_le_bytes());
            body.extend_from_slice(&kind.to_le_bytes());
            body.extend_from_slice(data);
        }
        let mut file = b"glTF".to_vec();
        file.extend_from_slice(&2_u32.to_le_bytes());
        let length = u32::try_from(12 + body.len()).expect("small");
        file.extend_from_slice(&length.to_le_bytes());
        file.extend_from_slice(&body);
        file
    }

    #[test]
    fn glb_chunks_are_split_and_unknown_later_chunks_ignored() {
        let file = glb(&[(CHUNK_JSON, b"{}  "), (CHUNK_BIN, b"abcd"), (7, b"xyz!")]);
        let (json, bin) = split_glb(&file).expect("a valid container");
        assert_eq!(json, b"{}  ");
        assert_eq!(bin, Some(&b"abcd"[..]));
    }

    #[test]
    fn broken_glb_containers_are_refused_with_the_reason() {
        let message = |bytes: &[u8]| split_glb(bytes).expect_err("broken");
        assert!(message(b"glTF\x02\0\0\0").contains("shorter than its 12-byte header"));
        let mut wrong_version = glb(&[(CHUNK_JSON, b"{}")]);
        wrong_version[4] = 1;
        assert!(message(&wrong_version).contains("GLB version 1"));
        let mut wrong_length = glb(&[(CHUNK_JSON, b"{}")]);
        wrong_length[8] += 1;
        assert!(message(&wrong_length).contains("but the file has"));
        let mut long_chunk = glb(&[(CHUNK_JSON, b"{}")]);
        long_chunk[12] = 200;
        assert!(message(&long_chunk).contains("beyond the file's end"));
        assert!(message(&glb(&[(CHUNK_BIN, b"{}")])).contains("not JSON"));
        assert!(message(&glb(&[(CHUNK_JSON, b"{}"), (9, b"")])).contains("not BIN"));
        assert!(message(&glb(&[])).contains("without a JSON chunk"));
    }

    #[test]
    fn only_version_2_is_read() {
        assert_eq!(check_version("2.0", None), None);
        assert_eq!(check_version("2.1", Some("2.0")), None);
        assert!(check_version("1.0", None).is_some_and(|m| m.contains("\"1.0\"")));
        assert!(check_version("2.1", Some("2.1")).is_some_and(|m| m.contains("minVersion")));
    }
}
