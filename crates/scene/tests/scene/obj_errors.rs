//! Every class of malformed OBJ file is an error naming the file and the line, never a panic.

use shadowlab_scene::{ObjElement, ObjError, ObjProblem, ReadError, load_obj};

use crate::support::ObjDir;

/// Loads `text` from a file and returns the line and problem of the error, checking that the
/// message starts with `path:line: `.
fn obj_error(text: &str) -> (usize, ObjProblem) {
    let dir = ObjDir::new();
    let path = dir.write("bad.obj", text);
    match load_obj(&path) {
        Err(error @ ObjError::Line { .. }) => {
            let message = error.to_string();
            let ObjError::Line {
                path: named,
                line,
                problem,
            } = error
            else {
                unreachable!("matched above")
            };
            assert_eq!(named, path);
            let prefix = format!("{}:{line}: ", path.display());
            assert!(message.starts_with(&prefix), "{message:?} lacks {prefix:?}");
            (line, problem)
        }
        other => panic!("expected an OBJ error, got {other:?}"),
    }
}

const TRIANGLE: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

#[test]
fn missing_file_names_the_path() {
    let dir = ObjDir::new();
    let path = dir
        .write("present.obj", TRIANGLE)
        .with_file_name("absent.obj");
    let error = load_obj(&path).unwrap_err();
    assert!(matches!(&error, ObjError::Read(ReadError::Io { path: p, .. }) if *p == path));
    assert!(
        error
            .to_string()
            .starts_with(&format!("{}: ", path.display()))
    );
    assert!(std::error::Error::source(&error).is_some());
}

#[test]
fn file_without_faces() {
    let dir = ObjDir::new();
    let path = dir.write("empty.obj", "# nothing\nv 0 0 0\nl 1 1\n");
    let error = load_obj(&path).unwrap_err();
    assert!(matches!(&error, ObjError::NoFaces { path: p } if *p == path));
    assert_eq!(error.to_string(), format!("{}: no faces", path.display()));
}

#[test]
fn numbers_that_do_not_parse() {
    assert_eq!(
        obj_error("v 0 0 0\n# fine\nv 1 x 0\n"),
        (
            3,
            ObjProblem::NotANumber {
                keyword: "v",
                token: "x".into()
            }
        )
    );
    assert_eq!(
        obj_error(&format!("{TRIANGLE}vn 0 0 1,0\nf 1 2 3\n")),
        (
            4,
            ObjProblem::NotANumber {
                keyword: "vn",
                token: "1,0".into()
            }
        )
    );
    assert_eq!(
        obj_error(&format!("{TRIANGLE}vt 0 u\n")),
        (
            4,
            ObjProblem::NotANumber {
                keyword: "vt",
                token: "u".into()
            }
        )
    );
    assert_eq!(
        obj_error("v 0 0 0 1 0 red\n"),
        (
            1,
            ObjProblem::NotANumber {
                keyword: "v",
                token: "red".into()
            }
        )
    );
}

#[test]
fn numbers_that_are_not_finite() {
    assert_eq!(
        obj_error("v 0 0 0\nv nan 0 0\n"),
        (
            2,
            ObjProblem::NotFinite {
                keyword: "v",
                token: "nan".into()
            }
        )
    );
    assert_eq!(
        obj_error("v 0 -inf 0\n"),
        (
            1,
            ObjProblem::NotFinite {
                keyword: "v",
                token: "-inf".into()
            }
        )
    );
    assert_eq!(
        obj_error("v 0 0 1e999\n"),
        (
            1,
            ObjProblem::NotFinite {
                keyword: "v",
                token: "1e999".into()
            }
        )
    );
    assert_eq!(
        obj_error(&format!("{TRIANGLE}vn 0 0 NaN\n")),
        (
            4,
            ObjProblem::NotFinite {
                keyword: "vn",
                token: "NaN".into()
            }
        )
    );
    // Finite coordinates that overflow when divided by w.
    assert_eq!(
        obj_error("v 1e300 0 0 1e-300\n"),
        (
            1,
            ObjProblem::NotFinite {
                keyword: "v",
                token: "1e300/1e-300".into()
            }
        )
    );
    assert_eq!(obj_error("v 1 2 3 0\n"), (1, ObjProblem::ZeroWeight));
}

#[test]
fn wrong_numbers_of_values() {
    let count =
        |keyword, found| match obj_error(&format!("{TRIANGLE}{keyword}{}\n", " 1".repeat(found))) {
            (
                4,
                ObjProblem::WrongValueCount {
                    keyword: k,
                    found: f,
                    ..
                },
            ) => (k, f),
            other => panic!("{other:?}"),
        };
    assert_eq!(count("v", 2), ("v", 2));
    assert_eq!(count("v", 5), ("v", 5));
    assert_eq!(count("v", 7), ("v", 7));
    assert_eq!(count("vn", 2), ("vn", 2));
    assert_eq!(count("vn", 4), ("vn", 4));
    assert_eq!(count("vt", 1), ("vt", 1));
    // A trailing comment on a `v` line is read as values, by tobj as here.
    let (line, problem) = obj_error("v 0 0 0 # origin\n");
    assert_eq!(line, 1);
    assert_eq!(
        problem.to_string(),
        "`v` takes x y z, x y z w or x y z r g b; found 5 values"
    );
}

#[test]
fn malformed_face_vertices() {
    for token in ["a", "1/2/3/4", "/1", "1.0", "1/x", "1//y", "+"] {
        assert_eq!(
            obj_error(&format!("{TRIANGLE}vt 0 0\nvn 0 0 1\nf 1 2 {token}\n")),
            (
                6,
                ObjProblem::MalformedFaceVertex {
                    token: token.into()
                }
            ),
            "{token}"
        );
    }
}

#[test]
fn face_indices_out_of_range() {
    let bad = |face: &str| obj_error(&format!("{TRIANGLE}vt 0 0\nvn 0 0 1\n{face}\n"));
    let out = |element, index, defined| ObjProblem::IndexOutOfRange {
        element,
        index,
        defined,
    };
    assert_eq!(bad("f 1 2 4"), (6, out(ObjElement::Position, 4, 3)));
    assert_eq!(bad("f 1 2 -4"), (6, out(ObjElement::Position, -4, 3)));
    assert_eq!(bad("f 1 2 3/2"), (6, out(ObjElement::TexCoord, 2, 1)));
    assert_eq!(
        bad("f 1//1 2//1 3//-2"),
        (6, out(ObjElement::Normal, -2, 1))
    );
    assert_eq!(
        bad("f 1 2 0"),
        (
            6,
            ObjProblem::ZeroIndex {
                element: ObjElement::Position
            }
        )
    );
    assert_eq!(
        bad("f 1/0 2/1 3/1"),
        (
            6,
            ObjProblem::ZeroIndex {
                element: ObjElement::TexCoord
            }
        )
    );
    assert_eq!(
        bad("f 1//0 2//1 3//1"),
        (
            6,
            ObjProblem::ZeroIndex {
                element: ObjElement::Normal
            }
        )
    );
    // Indices that would overflow tobj's arithmetic (a panic in debug builds) are errors here.
    assert_eq!(
        bad(&format!("f 1/{} 2/1 3/1", isize::MIN)),
        (6, out(ObjElement::TexCoord, isize::MIN, 1))
    );
    assert_eq!(
        bad(&format!("f 1//{} 2//1 3//1", isize::MAX)),
        (6, out(ObjElement::Normal, isize::MAX, 1))
    );
    // A forward reference: vertex 4 is defined below the face.
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f 1 2 4\nv 1 1 0\n")),
        (4, out(ObjElement::Position, 4, 3))
    );
    // Normals named in a file that has none.
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f 1//1 2//1 3//1\n")),
        (4, out(ObjElement::Normal, 1, 0))
    );
    let message = bad("f 1 2 4").1.to_string();
    assert_eq!(
        message,
        "position index 4 is out of range: 3 positions (`v`) are defined above this line"
    );
}

#[test]
fn faces_with_too_few_vertices() {
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f 1 2\n")),
        (4, ObjProblem::TooFewFaceVertices { found: 2 })
    );
    assert_eq!(
        obj_error(&format!("{TRIANGLE}f\n")),
        (4, ObjProblem::TooFewFaceVertices { found: 0 })
    );
}

#[test]
fn normals_named_for_some_corners_only() {
    let normals = format!("{TRIANGLE}vn 0 0 1\n");
    assert_eq!(
        obj_error(&format!("{normals}f 1//1 2 3//1\n")),
        (5, ObjProblem::MixedNormalsInFace)
    );
    assert_eq!(
        obj_error(&format!("{normals}f 1//1 2//1 3//1\nf 1 3 2\n")),
        (
            6,
            ObjProblem::MixedNormals {
                names_normals: false,
                first_face_line: 5
            }
        )
    );
    assert_eq!(
        obj_error(&format!(
            "{normals}f 1 2 3\n# other faces\nf 1//1 3//1 2//1\n"
        )),
        (
            7,
            ObjProblem::MixedNormals {
                names_normals: true,
                first_face_line: 5
            }
        )
    );
    // Different groups may differ.
    let dir = ObjDir::new();
    let path = dir.write(
        "ok.obj",
        &format!("{normals}f 1 2 3\ng other\nf 1//1 3//1 2//1\n"),
    );
    assert_eq!(load_obj(&path).unwrap().triangle_count(), 2);
}

#[test]
fn vertex_colours_on_some_vertices_only() {
    assert_eq!(
        obj_error("v 0 0 0 1 1 1\nv 1 0 0\n"),
        (
            2,
            ObjProblem::MixedVertexColours {
                first_vertex_line: 1
            }
        )
    );
}

#[test]
fn usemtl_without_a_name() {
    assert_eq!(
        obj_error(&format!("{TRIANGLE}usemtl\n")),
        (4, ObjProblem::MissingMaterialName)
    );
    assert_eq!(
        obj_error(&format!("{TRIANGLE}usemtl   \n")),
        (4, ObjProblem::MissingMaterialName)
    );
}

#[test]
fn invalid_utf8_names_its_line() {
    let dir = ObjDir::new();
    let path = dir.write("latin1.obj", "");
    std::fs::write(&path, b"v 0 0 0\n# caf\xe9\nv 1 0 0\n").unwrap();
    match load_obj(&path) {
        Err(ObjError::Line {
            line: 2,
            problem: ObjProblem::NotUtf8,
            ..
        }) => {}
        other => panic!("{other:?}"),
    }
}

#[test]
fn coordinates_beyond_the_limit_name_their_line_and_the_limit() {
    assert_eq!(
        obj_error("v 0 0 0\nv 1e308 0 0\nv 0 1 0\nf 1 2 3\n"),
        (
            2,
            ObjProblem::CoordinateOutOfRange {
                token: "1e308".to_owned()
            }
        )
    );
    // After the division by w.
    assert_eq!(
        obj_error("v 0 0 0\nv 1 0 0\nv 0 1e30 0 1e-20\nf 1 2 3\n"),
        (
            3,
            ObjProblem::CoordinateOutOfRange {
                token: "1e30/1e-20".to_owned()
            }
        )
    );
    // At the limit itself, the file loads.
    let dir = ObjDir::new();
    let path = dir.write("large.obj", "v 0 0 0\nv 1e40 0 0\nv 0 -1e40 0\nf 1 2 3\n");
    assert!(load_obj(&path).is_ok());
    let dir = ObjDir::new();
    let path = dir.write("bad.obj", "v 0 0 0\nv 1e308 0 0\nv 0 1 0\nf 1 2 3\n");
    let message = load_obj(&path).unwrap_err().to_string();
    assert!(
        message.contains(":2: `v`: `1e308` is beyond ±1e40 (MAX_COORDINATE)"),
        "{message}"
    );
}

#[test]
fn positions_without_extent_are_degenerate() {
    let dir = ObjDir::new();
    for text in [
        "v 0 0 0\nv 1e-310 0 0\nv 0 1e-310 1e-310\nf 1 2 3\n",
        "v 5 5 5\nv 5 5 5\nv 5 5 5\nf 1 2 3\n",
    ] {
        let path = dir.write("tiny.obj", text);
        let error = load_obj(&path).unwrap_err();
        assert!(
            matches!(&error, ObjError::DegenerateExtent { path: p, .. } if *p == path),
            "{error:?}"
        );
        let message = error.to_string();
        assert!(
            message.contains("a mesh must span at least 1e-40 (MIN_EXTENT)"),
            "{message}"
        );
    }
    let path = dir.write("small.obj", "v 0 0 0\nv 1e-40 0 0\nv 0 1e-40 0\nf 1 2 3\n");
    assert!(load_obj(&path).is_ok(), "an extent of MIN_EXTENT is enough");
}

#[test]
fn special_files_are_refused_without_reading_them() {
    let dir = ObjDir::new();
    let error = load_obj(dir.path()).unwrap_err();
    assert!(
        matches!(
            &error,
            ObjError::Read(ReadError::NotRegularFile {
                kind: "a directory",
                ..
            })
        ),
        "{error:?}"
    );
    #[cfg(unix)]
    {
        let zero = std::path::Path::new("/dev/zero");
        let error = load_obj(zero).unwrap_err();
        assert_eq!(
            error.to_string(),
            "/dev/zero: is a character device, not a regular file; only regular files are read as \
             input"
        );
        let fifo = dir.path().join("fifo.obj");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|status| status.success()) {
            // Opening a FIFO would block until a writer came: it must be refused before that.
            let error = load_obj(&fifo).unwrap_err();
            assert!(error.to_string().contains("is a FIFO"), "{error}");
        } else {
            eprintln!("skipped the FIFO case: mkfifo is not available");
        }
    }
}
