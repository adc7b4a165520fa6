//! Every choice a user can state (issue 11 §4): `--lambda`, `--n`, `--focus`, the same in the
//! scene's `[shadow]` table with the optimizer's settings, flags over the table, the rule's inputs
//! and formula in `inspect`, help texts with the library's defaults, and each refusal named.

use std::fs;
use std::path::Path;

use serde_json::Value;
use shadowlab_shadow::optimal::{BORDER, INITIAL_MAP_RESOLUTION, ITERATIONS, READBACK_SIZE};

use crate::support::{assert_refused, shadowlab, stderr, stdout};

/// A small scene in a file of its own in `dir`, with `shadow` as its `[shadow]` table.
fn scene_with(dir: &Path, shadow: &str) -> String {
    static FILES: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let k = FILES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let path = dir.join(format!("stated-{k}.toml"));
    fs::write(
        &path,
        format!(
            "[camera]\nposition = [0.0, 6.0, 12.0]\ntarget = [0.0, 0.0, 0.0]\nimage = [160, 120]\n\
             [[light]]\ndirection = [-0.4, -1.0, -0.3]\n\
             [[mesh]]\nshape = \"plane\"\nsize = [20.0, 20.0]\n\
             [[mesh]]\nshape = \"box\"\nsize = [2.0, 2.0, 2.0]\ntranslate = [0.0, 2.0, 0.0]\n\
             [shadow]\n{shadow}"
        ),
    )
    .unwrap();
    path.display().to_string()
}

/// `inspect ARGS --json`, its first light's first partition.
fn inspect(args: &[&str]) -> (Value, Value) {
    let mut all = vec!["inspect"];
    all.extend_from_slice(args);
    all.push("--json");
    let output = shadowlab(&all, None);
    assert!(output.status.success(), "{all:?}: {}", stderr(&output));
    let value: Value = serde_json::from_str(&stdout(&output)).unwrap();
    let part = value["lights"][0]["partitions"][0].clone();
    (value, part)
}

#[test]
fn stated_warps_are_used_and_reported() {
    let (_, part) = inspect(&["outdoor", "--lambda", "0.3"]);
    assert_eq!(part["lambda"].as_f64(), Some(0.3));
    assert_eq!(part["rule"]["formula"], "λ as stated");
    let (_, part) = inspect(&["outdoor", "--technique", "logarithmic", "--n", "2.5"]);
    assert!((part["n"].as_f64().unwrap() - 2.5).abs() < 1e-12, "{part}");
    // The paper's rule reports its inputs: the camera's near and far.
    let (_, part) = inspect(&["outdoor"]);
    let inputs = &part["rule"]["inputs"];
    assert_eq!(inputs["z_n"].as_f64(), Some(1.0));
    assert_eq!(inputs["z_f"].as_f64(), Some(400.0));
    assert!(
        part["rule"]["formula"]
            .as_str()
            .unwrap()
            .contains("LiSPSM §4.4")
    );
    let text = stdout(&shadowlab(
        &["inspect", "outdoor", "--param", "authors2006"],
        None,
    ));
    assert!(
        text.contains("rule: n = d/(√(z1/z0) − 1)") && text.contains("z0 = "),
        "{text}"
    );
}

#[test]
fn the_focus_flag_chooses_the_body() {
    let (value, light) = inspect(&["outdoor", "--technique", "uniform"]);
    assert_eq!(value["focus"], "light");
    let (value, view) = inspect(&["outdoor", "--technique", "uniform", "--focus", "view"]);
    assert_eq!(value["focus"], "view");
    assert_eq!(view["focus_body"].as_array().unwrap().len(), 8);
    assert_ne!(light["focus_body"], view["focus_body"]);
    let (_, visible) = inspect(&["outdoor", "--technique", "uniform", "--focus", "view-scene"]);
    assert_ne!(visible["focus_body"], light["focus_body"]);
}

#[test]
fn the_scene_table_states_what_the_flags_state_and_flags_win() {
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_with(
        scenes.path(),
        "technique = \"lispsm\"\nlambda = 0.25\nfocus = \"view\"\n",
    );
    let (value, part) = inspect(&[&scene]);
    assert_eq!(part["lambda"].as_f64(), Some(0.25));
    assert_eq!(value["focus"], "view");
    let (value, part) = inspect(&[&scene, "--param", "minimax", "--focus", "light"]);
    assert_eq!(value["focus"], "light");
    assert!(
        part["rule"]["formula"]
            .as_str()
            .unwrap()
            .contains("minimax")
    );

    // The optimizer's settings: a smaller read-back sees fewer samples, as the flag does.
    let samples = |args: &[&str]| {
        let (_, part) = inspect(args);
        let s = &part["optimizer"]["samples"];
        ["boundary", "screen_border", "discontinuity", "grazing"]
            .iter()
            .map(|k| s[k].as_u64().unwrap())
            .sum::<u64>()
    };
    let small = scene_with(
        scenes.path(),
        "technique = \"optimal\"\noptimal_readback = \"35x35\"\noptimal_iterations = 1\n",
    );
    let default = scene_with(scenes.path(), "technique = \"optimal\"\n");
    let fewer = samples(&[&small]);
    let more = samples(&[&default]);
    assert!(fewer < more, "{fewer} vs {more}");
    let flagged = scene_with(scenes.path(), "technique = \"optimal\"\n");
    assert_eq!(samples(&[&flagged, "--optimal-readback", "35x35"]), fewer);
}

#[test]
fn analyze_and_compare_measure_stated_warps_beside_the_techniques() {
    let out = tempfile::tempdir().unwrap();
    let output = shadowlab(
        &[
            "analyze",
            "bunny",
            "--techniques",
            "lispsm,logarithmic:lambda=0.05",
            "--lambda",
            "0.1,0.3",
            "--n",
            "12",
            "--focus",
            "view-scene",
            "--resolutions",
            "128",
            "--out",
            out.path().to_str().unwrap(),
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let csv = fs::read_to_string(out.path().join("results.csv")).unwrap();
    for label in [
        "lispsm/lambda=0.1",
        "lispsm/lambda=0.3",
        "lispsm/n=12",
        "logarithmic/lambda=0.05",
    ] {
        assert!(csv.contains(label), "{label} missing from {csv}");
    }
}

#[test]
fn help_texts_give_the_librarys_defaults() {
    let help = stdout(&shadowlab(&["render", "--help"], None));
    for expected in [
        format!("Default: {INITIAL_MAP_RESOLUTION}"),
        format!("Default: {}x{}", READBACK_SIZE.0, READBACK_SIZE.1),
        format!("Default: {ITERATIONS}"),
        format!("Default: {BORDER}"),
    ] {
        assert!(help.contains(&expected), "{expected} missing from\n{help}");
    }
}

#[test]
fn bad_stated_values_exit_2_and_name_the_flag_or_field() {
    let scenes = tempfile::tempdir().unwrap();
    let file = |shadow: &str| scene_with(scenes.path(), shadow);
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec![
                "inspect".into(),
                "outdoor".into(),
                "--lambda".into(),
                "-1".into(),
            ],
            "--lambda",
        ),
        (
            vec!["inspect".into(), "outdoor".into(), "--n".into(), "0".into()],
            "--n",
        ),
        (
            vec![
                "inspect".into(),
                "outdoor".into(),
                "--technique".into(),
                "psm".into(),
                "--lambda".into(),
                "0.2".into(),
            ],
            "applies to lispsm, logarithmic, optimal, sdsm and the engines' presets only",
        ),
        (
            vec![
                "inspect".into(),
                "outdoor".into(),
                "--param".into(),
                "minimax".into(),
                "--lambda".into(),
                "0.2".into(),
            ],
            "--param",
        ),
        (
            vec![
                "inspect".into(),
                "outdoor".into(),
                "--focus".into(),
                "nowhere".into(),
            ],
            "--focus",
        ),
        (
            vec![
                "inspect".into(),
                "outdoor".into(),
                "--technique".into(),
                "logarithmic".into(),
                "--lambda".into(),
                "1e-12".into(),
            ],
            "reference point on B",
        ),
        (
            vec![
                "inspect".into(),
                file("lambda = 0.3\nparameter = \"minimax\"\n"),
            ],
            "at most one of parameter, lambda and n",
        ),
        (
            vec!["inspect".into(), file("lambda = -1.0\n")],
            "shadow.lambda",
        ),
        (
            vec!["inspect".into(), file("focus = \"nowhere\"\n")],
            "shadow.focus",
        ),
        (
            vec![
                "inspect".into(),
                file("technique = \"optimal\"\noptimal_readback = \"70\"\n"),
            ],
            "shadow.optimal_readback",
        ),
        (
            vec![
                "inspect".into(),
                file("technique = \"optimal\"\noptimal_border = 0.7\n"),
            ],
            "shadow.optimal_border",
        ),
        (
            vec!["inspect".into(), file("optimal_initial = 0\n")],
            "shadow.optimal_initial",
        ),
        (
            vec![
                "analyze".into(),
                "outdoor".into(),
                "--lambda".into(),
                "0".into(),
                "--resolutions".into(),
                "64".into(),
            ],
            "--lambda",
        ),
    ];
    for (args, expected) in cases {
        assert_refused(&args, expected);
    }
}
