use std::fs;
use std::path::Path;

use crate::support::{shadowlab, stderr, stdout};

fn bunny() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/meshes/bunny-small.obj")
        .display()
        .to_string()
}

#[test]
fn both_passes_are_written_as_png_and_exr_and_repeat_exactly() {
    let (first, second) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    for dir in [first.path(), second.path()] {
        let args = [
            "render-mesh",
            &bunny(),
            "--size",
            "256",
            "--eye-size",
            "160x120",
            "--out",
            dir.to_str().unwrap(),
        ];
        let output = shadowlab(&args, None);
        assert!(output.status.success(), "{}", stderr(&output));
        let text = stdout(&output);
        assert!(
            text.contains("light: 256x256") && text.contains("eye: 160x120"),
            "{text}"
        );
    }
    for file in [
        "bunny-small-light.png",
        "bunny-small-light.exr",
        "bunny-small-eye.png",
        "bunny-small-eye.exr",
    ] {
        let a = fs::read(first.path().join(file)).unwrap();
        assert_eq!(
            a,
            fs::read(second.path().join(file)).unwrap(),
            "{file} differs between runs"
        );
        let magic: &[u8] = if file.ends_with("png") {
            b"\x89PNG"
        } else {
            &[0x76, 0x2f, 0x31, 0x01]
        };
        assert_eq!(&a[..4], magic, "{file}");
    }
}

#[test]
fn one_pass_only() {
    let dir = tempfile::tempdir().unwrap();
    let output = shadowlab(
        &[
            "render-mesh",
            &bunny(),
            "--eye",
            "--eye-size",
            "64x48",
            "--out",
            dir.path().to_str().unwrap(),
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let mut names: Vec<String> = fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "bunny-small-eye.exr",
            "bunny-small-eye.png",
            "manifest.json"
        ]
    );
}

#[test]
fn a_malformed_mesh_is_named_with_its_line_and_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("bad.obj");
    fs::write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 zero\nf 1 2 3\n").unwrap();
    let out = dir.path().join("out");
    let output = shadowlab(
        &[
            "render-mesh",
            obj.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(output.status.code(), Some(2));
    let message = stderr(&output);
    assert!(message.contains("bad.obj:3"), "{message}");
    assert!(!out.exists(), "nothing is written");
    let output = shadowlab(&["render-mesh", "/no/such/mesh.obj"], None);
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("/no/such/mesh.obj"));
    let output = shadowlab(&["render-mesh", &bunny(), "--eye-size", "64by48"], None);
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("--eye-size"));
}
