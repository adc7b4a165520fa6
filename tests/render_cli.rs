//! `shadowlab render` and `shadowlab inspect`: the files, repeatability, JSON, bad input.

use std::fs;

use crate::support::{assert_refused, shadowlab, stderr, stdout};

/// A small scene file: a plane and a box under a sun; `extra` is appended.
fn scene_file(dir: &std::path::Path, extra: &str) -> String {
    let path = dir.join("small.toml");
    fs::write(
        &path,
        format!(
            "[camera]\nposition = [0.0, 6.0, 12.0]\ntarget = [0.0, 0.0, 0.0]\nimage = [160, 120]\n\
             [[light]]\ndirection = [-0.4, -1.0, -0.3]\n\
             [[mesh]]\nshape = \"plane\"\nsize = [20.0, 20.0]\n\
             [[mesh]]\nshape = \"box\"\nsize = [2.0, 2.0, 2.0]\ntranslate = [0.0, 2.0, 0.0]\n{extra}"
        ),
    )
    .unwrap();
    path.display().to_string()
}

#[test]
fn render_writes_the_pictures_and_repeats_exactly() {
    let (first, second) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path(), "");
    for dir in [first.path(), second.path()] {
        let output = shadowlab(
            &[
                "render",
                &scene,
                "--resolution",
                "128",
                "--out",
                dir.to_str().unwrap(),
            ],
            None,
        );
        assert!(output.status.success(), "{}", stderr(&output));
        let text = stdout(&output);
        assert!(
            text.contains("lispsm") && text.contains("% of the visible pixels in shadow"),
            "{text}"
        );
    }
    for file in [
        "eye.png",
        "lightview.png",
        "shadowmap-light0-part0.png",
        "pictures/eye.png",
        "pictures/lightview.png",
    ] {
        let (a, b) = (
            fs::read(first.path().join(file)).unwrap(),
            fs::read(second.path().join(file)).unwrap(),
        );
        assert!(a.starts_with(b"\x89PNG"), "{file} is not a PNG");
        assert_eq!(a, b, "{file} differs between runs");
    }
    // The annotated pictures frame the raw ones: wider and taller (title, settings, legend).
    let size = |file: &str| {
        let bytes = fs::read(first.path().join(file)).unwrap();
        let word = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap());
        (word(16), word(20))
    };
    for (raw, annotated) in [
        ("eye.png", "pictures/eye.png"),
        ("lightview.png", "pictures/lightview.png"),
    ] {
        let ((w, h), (aw, ah)) = (size(raw), size(annotated));
        assert!(aw > w && ah > h, "{annotated}: {aw}×{ah} around {w}×{h}");
    }
}

#[test]
fn partitions_give_one_map_and_light_view_each() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path(), "");
    let output = shadowlab(
        &[
            "render",
            &scene,
            "--technique",
            "uniform",
            "--splits",
            "3",
            "--split-scheme",
            "logarithmic",
            "--resolution",
            "64",
            "--out",
            dir.path().to_str().unwrap(),
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    for p in 0..3 {
        for kind in ["shadowmap", "lightview"] {
            let file = dir.path().join(format!("{kind}-light0-part{p}.png"));
            assert!(file.exists(), "{} missing", file.display());
        }
    }
    assert!(!dir.path().join("lightview.png").exists());
}

#[test]
fn inspect_reports_the_set_up_as_json() {
    let output = shadowlab(
        &[
            "inspect",
            "outdoor",
            "--technique",
            "lispsm",
            "--param",
            "minimax",
            "--json",
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let value: serde_json::Value = serde_json::from_str(&stdout(&output)).unwrap();
    assert_eq!(value["scene"], "outdoor");
    let part = &value["lights"][0]["partitions"][0];
    let gamma = part["gamma_degrees"].as_f64().unwrap();
    assert!((80.0..=90.0).contains(&gamma), "γ {gamma}");
    assert!(part["lambda"].as_f64().unwrap() > 0.0);
    assert_eq!(part["view"].as_array().unwrap().len(), 16);
    assert_eq!(part["projection"].as_array().unwrap().len(), 16);
    assert!(part["focus_body"].as_array().unwrap().len() >= 4);
    let splits = value["lights"][0]["splits"].as_array().unwrap();
    assert_eq!(splits.len(), 2);
    assert_eq!(splits[1].as_f64(), Some(400.0));
    // `--technique TECHNIQUE:PARAMETER` is the same set-up as `--technique` with `--param`.
    let spec = shadowlab(
        &[
            "inspect",
            "outdoor",
            "--technique",
            "lispsm:minimax",
            "--json",
        ],
        None,
    );
    assert!(spec.status.success(), "{}", stderr(&spec));
    assert_eq!(stdout(&spec), stdout(&output));
    // Text output names the same things.
    let text = stdout(&shadowlab(
        &["inspect", "outdoor", "--technique", "psm"],
        None,
    ));
    assert!(
        text.contains("PSM: shift") && text.contains("projection (row-major)"),
        "{text}"
    );
}

/// Claim: for the scene-optimized map, `inspect` reports what the optimizer did per partition —
/// samples by rule and h lowered from its start — and says so in text too.
#[test]
fn inspect_reports_the_optimizer() {
    let output = shadowlab(
        &[
            "inspect",
            "dueling-frusta",
            "--technique",
            "optimal",
            "--splits",
            "2",
            "--json",
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let value: serde_json::Value = serde_json::from_str(&stdout(&output)).unwrap();
    let parts = value["lights"][0]["partitions"].as_array().unwrap();
    assert_eq!(parts.len(), 2);
    for part in parts {
        let report = &part["optimizer"];
        assert_eq!(part["technique"], "optimal");
        assert!(
            report["samples"]["boundary"].as_u64().unwrap() > 0,
            "{report}"
        );
        if let (Some(h), Some(initial)) = (report["h"].as_f64(), report["initial_h"].as_f64()) {
            assert!(h <= initial, "{report}");
        }
    }
    let text = stdout(&shadowlab(
        &["inspect", "dueling-frusta", "--technique", "optimal"],
        None,
    ));
    assert!(
        text.contains("optimizer: ") && text.contains("samples ("),
        "{text}"
    );
    // The optimizer's settings reach it: no iterations take no step, and a smaller read-back
    // finds fewer samples.
    let report = |extra: &[&str]| {
        let mut command = vec![
            "inspect",
            "dueling-frusta",
            "--technique",
            "optimal",
            "--json",
        ];
        command.extend_from_slice(extra);
        let output = shadowlab(&command, None);
        assert!(output.status.success(), "{}", stderr(&output));
        let value: serde_json::Value = serde_json::from_str(&stdout(&output)).unwrap();
        value["lights"][0]["partitions"][0]["optimizer"].clone()
    };
    let still = report(&["--optimal-iterations", "0"]);
    assert_eq!(
        still["steps_degrees"].as_array().map(Vec::len),
        Some(0),
        "{still}"
    );
    assert_eq!(still["h"], still["initial_h"], "{still}");
    let samples = |r: &serde_json::Value| r["samples"]["boundary"].as_u64().unwrap();
    let small = report(&["--optimal-readback", "35x35"]);
    assert!(samples(&small) < samples(&report(&[])), "{small}");
}

#[test]
fn bad_input_exits_with_2_and_names_the_problem() {
    let scenes = tempfile::tempdir().unwrap();
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec!["render".into(), "no-such-scene".into()],
            "no-such-scene",
        ),
        (
            vec![
                "render".into(),
                "outdoor".into(),
                "--technique".into(),
                "vsm".into(),
            ],
            "unknown technique",
        ),
        (
            vec![
                "render".into(),
                "outdoor".into(),
                "--technique".into(),
                "psm".into(),
                "--param".into(),
                "gmnpr".into(),
            ],
            "applies to lispsm, logarithmic, optimal, sdsm and the engines' presets only",
        ),
        (
            vec![
                "render".into(),
                "outdoor".into(),
                "--bias".into(),
                "slope:-1".into(),
            ],
            "--bias",
        ),
        (
            vec![
                "render".into(),
                "outdoor".into(),
                "--filter".into(),
                "pcf:0".into(),
            ],
            "--filter",
        ),
        (
            vec![
                "render".into(),
                "outdoor".into(),
                "--split-scheme".into(),
                "adaptive:1".into(),
            ],
            "--split-scheme",
        ),
        (
            vec![
                "render".into(),
                "outdoor".into(),
                "--format".into(),
                "f16".into(),
            ],
            "--format",
        ),
        (
            vec![
                "inspect".into(),
                "dueling-frusta".into(),
                "--technique".into(),
                "lispsm".into(),
                "--param".into(),
                "glpr".into(),
            ],
            "not defined",
        ),
        (
            vec![
                "inspect".into(),
                "outdoor".into(),
                "--optimal-border".into(),
                "0.7".into(),
            ],
            "--optimal-border",
        ),
        (
            vec![
                "render".into(),
                "outdoor".into(),
                "--optimal-readback".into(),
                "70".into(),
            ],
            "--optimal-readback",
        ),
        (
            vec![
                "render".into(),
                scene_file(scenes.path(), "[shadow]\ntechnique = \"cascaded\"\n"),
            ],
            "shadow.technique",
        ),
    ];
    for (args, expected) in cases {
        assert_refused(&args, expected);
    }
    // A broken scene file names the file and the field.
    let broken = scenes.path().join("broken.toml");
    fs::write(
        &broken,
        "[camera]\nnear = 5.0\nfar = 1.0\n[[mesh]]\nshape = \"box\"\n",
    )
    .unwrap();
    let output = shadowlab(&["render", broken.to_str().unwrap()], None);
    assert_eq!(output.status.code(), Some(2));
    let message = stderr(&output);
    assert!(
        message.contains("broken.toml") && message.contains("camera.near"),
        "{message}"
    );
}
