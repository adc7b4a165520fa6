//! Point lights from the command line: the built-in point-light scenes render with the cube map by
//! default and analyze with the omnidirectional techniques; a technique that cannot serve a light
//! is refused with exit code 2, naming the light and the technique, before anything is written.

use crate::support::{assert_refused, shadowlab, stdout};

/// Claim: `render room-point` makes six cube faces by default, one map and light view each.
#[test]
fn a_point_light_renders_with_the_cube_map_by_default() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("render");
    let output = shadowlab(
        &[
            "render",
            "room-point",
            "--resolution",
            "128",
            "--out",
            out.to_str().unwrap(),
        ],
        None,
    );
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(out.join("eye.png").is_file());
    let maps = std::fs::read_dir(&out)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .file_name()
                .to_string_lossy()
                .starts_with("shadowmap-light0-part")
        })
        .count();
    assert_eq!(maps, 6, "{}", stdout(&output));
}

/// Claim: `analyze chess-point` measures cube, dual-paraboloid and PSM by default, every one of
/// them defined there (the light lies outside PSM's body).
#[test]
fn a_point_light_scene_is_analyzed_with_the_omnidirectional_techniques() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("analyze");
    let output = shadowlab(
        &[
            "analyze",
            "chess-point",
            "--resolutions",
            "256",
            "--timing-runs",
            "1",
            "--out",
            out.to_str().unwrap(),
        ],
        None,
    );
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    let techniques: Vec<&str> = rows.iter().map(|r| r[1]).collect();
    assert_eq!(techniques, ["cube", "dual-paraboloid", "psm"]);
    assert!(rows.iter().all(|r| r[5] == "true"), "{csv}");
}

/// Claim: every command refuses a technique that cannot serve a scene's light, with exit code 2,
/// the light and the technique named and nothing written.
#[test]
fn a_technique_that_cannot_serve_a_light_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("never");
    let out = out.to_str().unwrap();
    let cases: [(&[&str], &str); 6] = [
        (
            &["render", "room-point", "--technique", "lispsm"],
            "--technique: light[0] of room-point: lispsm cannot serve a point light; techniques \
             for point lights: cube, dual-paraboloid, psm",
        ),
        (
            &["analyze", "chess-point", "--techniques", "cube,uniform"],
            "--techniques: light[0] of chess-point: uniform cannot serve a point light",
        ),
        (
            &["temporal", "room-point", "--techniques", "sdsm"],
            "sdsm cannot serve a point light",
        ),
        (
            &["sweep-angle", "room-point", "--techniques", "bevy"],
            "bevy cannot serve a point light",
        ),
        (
            &["compare", "chess-point", "--techniques", "logarithmic"],
            "logarithmic cannot serve a point light",
        ),
        (
            &["render", "outdoor", "--technique", "dual-paraboloid"],
            "light[0] of outdoor: dual-paraboloid cannot serve a directional light",
        ),
    ];
    for (args, expected) in cases {
        let mut args = args.to_vec();
        args.extend(["--out", out]);
        assert_refused(&args, expected);
        assert!(!std::path::Path::new(out).exists(), "{args:?} wrote {out}");
    }
}
