//! `shadowlab analyze`, `sweep-angle` and `temporal`: every file written, results repeatable bit for
//! bit (all but the timings), the Chong–Gortler table, continuity at γ = 0, and bad input.

use std::fs;
use std::path::Path;

use crate::support::{shadowlab, stderr, stdout};

/// A small scene: a plane, a box and a pole under a sun, 160 × 120 pixels.
fn scene_file(dir: &Path) -> String {
    let path = dir.join("small.toml");
    fs::write(
        &path,
        "[camera]\nposition = [0.0, 3.0, 12.0]\ntarget = [0.0, 0.0, -10.0]\nimage = [160, 120]\n\
         far = 60.0\n\
         [[light]]\ndirection = [-0.6, -1.0, -0.2]\n\
         [[mesh]]\nshape = \"plane\"\nsize = [60.0, 60.0]\n\
         [[mesh]]\nshape = \"box\"\nsize = [2.0, 2.0, 2.0]\ntranslate = [0.0, 1.0, 0.0]\n\
         [[mesh]]\nshape = \"cylinder\"\nradius = 0.2\nheight = 4.0\ntranslate = [3.0, 2.0, -8.0]\n",
    )
    .unwrap();
    path.display().to_string()
}

/// The columns of `results.csv` that do not depend on the clock: everything before the timings,
/// which start at `planning_ms`.
fn untimed(csv: &str) -> Vec<String> {
    let header: Vec<&str> = csv.lines().next().unwrap_or_default().split(',').collect();
    let timings = header
        .iter()
        .position(|c| *c == "planning_ms")
        .expect("a planning_ms column");
    csv.lines()
        .map(|line| line.split(',').take(timings).collect::<Vec<_>>().join(","))
        .collect()
}

/// Every output but the timings is the same on any thread count: the untimed columns of
/// `results.csv` and every picture, byte for byte.
#[test]
fn analyze_is_identical_on_any_thread_count_but_for_timings() {
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path());
    let root = tempfile::tempdir().unwrap();
    let mut sets = Vec::new();
    for threads in ["1", "2", "5"] {
        let out = root.path().join(threads);
        let output = std::process::Command::new(env!("CARGO_BIN_EXE_shadowlab"))
            .args([
                "analyze",
                &scene,
                "--techniques",
                "uniform,lispsm,logarithmic",
                "--resolutions",
                "128,256",
                "--timing-runs",
                "2",
                "--out",
                out.to_str().unwrap(),
            ])
            .env("RAYON_NUM_THREADS", threads)
            .output()
            .unwrap();
        assert!(output.status.success(), "{}", stderr(&output));
        let manifest: serde_json::Value =
            serde_json::from_slice(&fs::read(out.join("manifest.json")).unwrap()).unwrap();
        let pictures: Vec<(String, String)> = manifest["files"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| {
                (
                    f["name"].as_str().unwrap().to_string(),
                    f["sha256"].as_str().unwrap().to_string(),
                )
            })
            .filter(|(name, _)| name.starts_with("images/") || name.starts_with("pictures/"))
            .collect();
        // Three techniques, each with four raw and four annotated pictures.
        assert_eq!(pictures.len(), 24, "{pictures:?}");
        sets.push((
            untimed(&fs::read_to_string(out.join("results.csv")).unwrap()),
            pictures,
        ));
    }
    assert_eq!(sets[0], sets[1], "1 and 2 threads differ");
    assert_eq!(sets[0], sets[2], "1 and 5 threads differ");
}

#[test]
fn analyze_writes_the_report_and_repeats_its_results_exactly() {
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path());
    let (first, second) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    for dir in [first.path(), second.path()] {
        let output = shadowlab(
            &[
                "analyze",
                &scene,
                "--techniques",
                "uniform_limited,optimal,psm",
                "--resolutions",
                "128,256",
                "--map-truth",
                "--out",
                dir.to_str().unwrap(),
            ],
            None,
        );
        assert!(output.status.success(), "{}", stderr(&output));
        assert!(
            stdout(&output).contains("misclassified"),
            "{}",
            stdout(&output)
        );
    }
    let read = |dir: &Path, name: &str| fs::read_to_string(dir.join(name)).unwrap();
    let csv = read(first.path(), "results.csv");
    assert_eq!(csv.lines().count(), 1 + 3 * 2, "{csv}");
    assert_eq!(untimed(&csv), untimed(&read(second.path(), "results.csv")));

    let report = read(first.path(), "report.md");
    for needle in [
        "## Misclassified pixels",
        "Against Chong and Gortler's Table 1",
        "disagrees with it at",
        "Pareto front",
        "## Along the view axis",
    ] {
        assert!(
            report.contains(needle),
            "report.md lacks {needle:?}:\n{report}"
        );
    }
    let json: serde_json::Value =
        serde_json::from_str(&read(first.path(), "results.json")).unwrap();
    assert_eq!(
        json["measurements"].as_array().map(Vec::len),
        Some(6),
        "{json}"
    );
    for file in [
        "pareto.png",
        "images/heatmap-optimal.png",
        "images/difference-psm.png",
    ] {
        let bytes = fs::read(first.path().join(file)).unwrap();
        assert!(bytes.starts_with(b"\x89PNG"), "{file} is not a PNG");
    }
    assert!(read(first.path(), "pareto.svg").starts_with("<svg"));
}

/// Claim: a study of techniques without a view-axis curve (the scene-optimized map alone, with
/// its settings from the command line) writes its report and leaves the view-axis figure out
/// instead of failing on an empty figure.
#[test]
fn analyze_without_view_axis_curves_leaves_that_figure_out() {
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path());
    let out = tempfile::tempdir().unwrap();
    let output = shadowlab(
        &[
            "analyze",
            &scene,
            "--techniques",
            "optimal",
            "--resolutions",
            "128",
            "--optimal-iterations",
            "1",
            "--out",
            out.path().to_str().unwrap(),
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    for file in ["report.md", "results.csv", "pareto.svg"] {
        assert!(out.path().join(file).is_file(), "{file} missing");
    }
    assert!(!out.path().join("view-axis.svg").exists());
    let report = fs::read_to_string(out.path().join("report.md")).unwrap();
    assert!(!report.contains("view-axis.png"), "{report}");
}

#[test]
fn sweep_angle_reaches_gamma_zero_continuously() {
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path());
    let out = tempfile::tempdir().unwrap();
    let output = shadowlab(
        &[
            "sweep-angle",
            &scene,
            "--techniques",
            "uniform,lispsm,lispsm:minimax,psm",
            "--resolution",
            "128",
            "--out",
            out.path().to_str().unwrap(),
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let csv = fs::read_to_string(out.path().join("sweep.csv")).unwrap();
    // technique → misclassified pixels at γ = 0, 1e-9 and 1e-6 rad.
    for technique in ["uniform", "lispsm", "lispsm/minimax", "psm"] {
        let near_zero: Vec<u64> = csv
            .lines()
            .skip(1)
            .map(|line| line.split(',').collect::<Vec<_>>())
            .filter(|f| f[1] == technique && f[2].parse::<f64>().unwrap() <= 1e-6)
            .map(|f| {
                assert_eq!(f[4], "true", "{technique} not defined at γ = {}", f[2]);
                f[5].parse().unwrap()
            })
            .collect();
        assert_eq!(near_zero.len(), 3, "{technique}: {csv}");
        let spread = near_zero.iter().max().unwrap() - near_zero.iter().min().unwrap();
        // 160 × 120 pixels: a jump of more than 1 % of them would be a discontinuity.
        assert!(spread <= 192, "{technique}: {near_zero:?} near γ = 0");
    }
    for file in ["sweep.md", "sweep.svg", "sweep.png"] {
        assert!(out.path().join(file).is_file(), "{file} missing");
    }
}

/// A long walk stays in the scene (a straight walk of ~600 frames left the outdoor scene and the
/// run failed at its end).
#[test]
fn a_long_temporal_walk_stays_in_the_scene() {
    let out = tempfile::tempdir().unwrap();
    let output = shadowlab(
        &[
            "temporal",
            "--frames",
            "640",
            "--techniques",
            "uniform",
            "--resolution",
            "32",
            "--eye-size",
            "32x24",
            "--out",
            out.path().to_str().unwrap(),
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let csv = fs::read_to_string(out.path().join("temporal.csv")).unwrap();
    // A row per frame pair, snapping off and on.
    assert_eq!(csv.lines().count(), 1 + 2 * 639);
}

#[test]
fn temporal_counts_shimmer_with_and_without_snapping() {
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path());
    let out = tempfile::tempdir().unwrap();
    let output = shadowlab(
        &[
            "temporal",
            &scene,
            "--frames",
            "3",
            "--techniques",
            "uniform,optimal",
            "--resolution",
            "256",
            "--out",
            out.path().to_str().unwrap(),
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let csv = fs::read_to_string(out.path().join("temporal.csv")).unwrap();
    // Two techniques × snapping off and on × two frame pairs.
    assert_eq!(csv.lines().count(), 1 + 2 * 2 * 2, "{csv}");
    let md = fs::read_to_string(out.path().join("temporal.md")).unwrap();
    assert!(md.contains("| uniform | 1 texel |"), "{md}");
}

#[test]
fn bad_input_exits_with_2_names_the_problem_and_writes_nothing() {
    let out = tempfile::tempdir().unwrap();
    let target = out.path().join("report");
    let target = target.to_str().unwrap();
    for (args, needle) in [
        (vec!["analyze", "--techniques", "bogus"], "--techniques"),
        (vec!["analyze", "--resolutions", "0"], "--resolutions"),
        (vec!["analyze", "--filters", "pcf:0"], "--filters"),
        (vec!["analyze", "--bias", "slope:x"], "--bias"),
        (vec!["analyze", "no-such-scene"], "no-such-scene"),
        (
            vec!["sweep-angle", "--techniques", "lispsm:nope"],
            "--techniques",
        ),
        (vec!["temporal", "--frames", "1"], "--frames"),
    ] {
        let mut all = args.clone();
        all.extend(["--out", target]);
        let output = shadowlab(&all, None);
        assert_eq!(
            output.status.code(),
            Some(2),
            "{args:?}: {}",
            stderr(&output)
        );
        assert!(
            stderr(&output).contains(needle),
            "{args:?}: {}",
            stderr(&output)
        );
        assert!(!Path::new(target).exists(), "{args:?} wrote {target}");
    }
}

/// `analyze` of the test scene with `techniques` at 256², one timing run, and the `extra`
/// arguments: its `results.json`'s measurements.
fn measured(techniques: &str, extra: &[&str]) -> Vec<serde_json::Value> {
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path());
    let out = tempfile::tempdir().unwrap();
    let mut args = vec![
        "analyze",
        &scene,
        "--techniques",
        techniques,
        "--resolutions",
        "256",
        "--timing-runs",
        "1",
        "--out",
        out.path().to_str().unwrap(),
    ];
    args.extend(extra);
    let output = shadowlab(&args, None);
    assert!(output.status.success(), "{}", stderr(&output));
    let json: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(out.path().join("results.json")).unwrap())
            .unwrap();
    json["measurements"].as_array().unwrap().clone()
}

/// Each measurement's technique label and number of maps.
fn labels_and_maps(measurements: &[serde_json::Value]) -> Vec<(String, u64)> {
    measurements
        .iter()
        .map(|m| {
            (
                m["setting"]["technique"].as_str().unwrap().to_string(),
                m["setting"]["maps"].as_u64().unwrap(),
            )
        })
        .collect()
}

/// Claim: the engines' presets and SDSM are techniques of `analyze`: a preset's combination has its
/// engine's cascade count as its maps whatever `--partitions` says, and every combination's errors
/// are given causes that sum to them.
#[test]
fn analyze_measures_engine_presets_and_sdsm_with_causes() {
    let measurements = measured(
        "bevy,godot:unsnapped,unity,sdsm:kmeans",
        &["--partitions", "2"],
    );
    assert_eq!(
        labels_and_maps(&measurements),
        [
            ("bevy".to_string(), 4),
            ("godot/unsnapped".to_string(), 4),
            ("unity".to_string(), 1),
            ("sdsm/kmeans".to_string(), 2)
        ]
    );
    for m in &measurements {
        let count = |k: &str| m[k].as_u64().unwrap();
        let causes: u64 = [
            "acne",
            "peter_panning",
            "seam_band",
            "seam_boundary",
            "aliasing",
        ]
        .map(count)
        .iter()
        .sum();
        assert_eq!(causes, count("misclassified"), "{m}");
        assert_eq!(
            count("seam"),
            count("seam_band") + count("seam_boundary"),
            "{m}"
        );
        // Every phase is timed, the analysis's own among them.
        for phase in [
            "planning",
            "shadow_pass",
            "lookup",
            "attribution",
            "footprints",
        ] {
            assert!(m["ms"][phase].as_f64().is_some_and(|t| t >= 0.0), "{m}");
        }
    }
}

/// Claim: a preset's choices are techniques of their own: `analyze` measures each, labelled as
/// written back (`babylon/fit=sphere+blend=0.2`), with the engine's cascade count; a choice that
/// does not apply is refused with exit 2, naming preset and choice, and nothing is written.
#[test]
fn analyze_measures_preset_choices_and_refuses_bad_ones() {
    let measurements = measured(
        "babylon,babylon:blend=0.2+fit=sphere,godot:select=containing+blend=0.1,filament:fit=sphere",
        &[],
    );
    assert_eq!(
        labels_and_maps(&measurements),
        [
            ("babylon".to_string(), 4),
            ("babylon/fit=sphere+blend=0.2".to_string(), 4),
            ("godot/blend=0.1+select=containing".to_string(), 4),
            ("filament/fit=sphere".to_string(), 1)
        ]
    );
    let misclassified = |k: usize| measurements[k]["misclassified"].as_u64().unwrap();
    // Another fit and band are other maps: Babylon's errors change.
    assert_ne!(misclassified(0), misclassified(1));

    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path());
    let refused = tempfile::tempdir().unwrap();
    let target = refused.path().join("out");
    let output = shadowlab(
        &[
            "analyze",
            &scene,
            "--techniques",
            "unity:blend=0.1",
            "--out",
            target.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("unity renders one cascade"),
        "{}",
        stderr(&output)
    );
    assert!(!target.exists());
}

/// Claim: `analyze --biases` sweeps the bias: a row per bias and combination, the Pareto front of
/// acne against peter-panning marked, the best bias named; no bias, the ladder; and a preset,
/// which reads its maps with its engine's bias, is refused with exit 2.
#[test]
fn analyze_sweeps_biases_and_refuses_presets() {
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path());
    let out = tempfile::tempdir().unwrap();
    let output = shadowlab(
        &[
            "analyze",
            &scene,
            "--techniques",
            "uniform",
            "--resolutions",
            "256",
            "--out",
            out.path().to_str().unwrap(),
            "--biases",
            "none",
            "constant:1e-3",
            "slope:2,1e-5+normal:1",
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let csv = fs::read_to_string(out.path().join("bias-sweep.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 3, "{csv}");
    let none = csv.lines().nth(1).unwrap();
    let acne: u64 = none.split(',').nth(8).unwrap().parse().unwrap();
    assert!(acne > 0, "no bias, no acne? {none}");
    assert!(csv.contains("\"slope:2.0,1e-5+normal:1.0\""), "{csv}");
    let md = fs::read_to_string(out.path().join("bias-sweep.md")).unwrap();
    assert!(md.contains('★') && md.contains("**`"), "{md}");
    assert!(!out.path().join("report.md").exists());

    let refused = tempfile::tempdir().unwrap();
    let output = shadowlab(
        &[
            "analyze",
            &scene,
            "--techniques",
            "bevy",
            "--out",
            refused.path().to_str().unwrap(),
            "--biases",
        ],
        None,
    );
    assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("bevy reads its maps"),
        "{}",
        stderr(&output)
    );
    assert!(fs::read_dir(refused.path()).unwrap().next().is_none());
}

/// The fields of one CSV record, double-quoted fields unquoted (RFC 4180).
fn csv_record(line: &str) -> Vec<String> {
    let (mut fields, mut field, mut quoted, mut chars) =
        (Vec::new(), String::new(), false, line.chars().peekable());
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(std::mem::take(&mut field)),
            _ => field.push(c),
        }
    }
    fields.push(field);
    fields
}

/// The filterable maps run through `analyze` from the command line (`;` between a filter's numbers
/// in the list), and `results.csv` quotes their labels, which hold commas, so that every record
/// has the header's columns and names its filter as `--filter` takes it; each filterable map's
/// errors against the nearest lookup of its map are filled in (leaks, over-darkening, their
/// extent, its bytes per texel), and left empty for the nearest filter; VSM at two prefilter sides
/// draws the figure of leaks against the side.
#[test]
fn analyze_reads_every_filterable_map_and_its_csv_keeps_their_labels_whole() {
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path());
    let out = tempfile::tempdir().unwrap();
    let output = shadowlab(
        &[
            "analyze",
            &scene,
            "--techniques",
            "lispsm",
            "--resolutions",
            "128",
            "--filters",
            "nearest,vsm:3,vsm:5,esm:3;80,evsm2:3;11.08,evsm4:3;11.08;11.08,msm:3;6e-5",
            "--timing-runs",
            "1",
            "--out",
            out.path().to_str().unwrap(),
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let csv = fs::read_to_string(out.path().join("results.csv")).unwrap();
    let mut lines = csv.lines();
    let header = csv_record(lines.next().unwrap());
    let filter = header.iter().position(|c| c == "filter").unwrap();
    let defined = header.iter().position(|c| c == "defined").unwrap();
    let column = |name: &str| header.iter().position(|c| c == name).unwrap();
    let (leaks, falsely_lit, bytes) = (
        column("filter_leaks"),
        column("falsely_lit"),
        column("bytes_per_texel"),
    );
    let filters: Vec<String> = lines
        .map(|line| {
            let record = csv_record(line);
            assert_eq!(record.len(), header.len(), "{line}");
            assert_eq!(record[defined], "true", "{line}");
            if record[filter] == "nearest" {
                assert!(
                    record[leaks].is_empty() && record[bytes].is_empty(),
                    "{line}"
                );
            } else {
                // A leak is a falsely lit pixel the nearest lookup gets right.
                let count: u64 = record[leaks].parse().unwrap();
                assert!(count <= record[falsely_lit].parse().unwrap(), "{line}");
                assert!(["4", "8", "16"].contains(&record[bytes].as_str()), "{line}");
            }
            record[filter].clone()
        })
        .collect();
    assert_eq!(
        filters,
        [
            "nearest",
            "vsm:3,0.000001",
            "vsm:5,0.000001",
            "esm:3,80",
            "evsm2:3,11.08,0.000001",
            "evsm4:3,11.08,11.08,0.000001",
            "msm:3,0.00006"
        ]
    );
    assert!(out.path().join("leaks.svg").is_file() && out.path().join("leaks.png").is_file());
    let report = fs::read_to_string(out.path().join("report.md")).unwrap();
    assert!(
        report.contains("light leaks against the prefilter's side") && report.contains("leaks.png"),
        "{report}"
    );
}
