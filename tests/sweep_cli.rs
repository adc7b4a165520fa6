//! `shadowlab sweep` and `merge`: a spec run whole and as shards (concurrently, into one directory
//! or several, on one thread or two) merges to the same table, report and figures, timings aside;
//! reruns resume; a merge with cells missing, a bad spec and a foreign directory are refused;
//! `--slurm` writes a job array and a dependent merge. The real Slurm run is tests/slurm/run.sh.

use std::path::Path;
use std::process::{Command, Output, Stdio};

use crate::support::{assert_refused, shadowlab, stderr, stdout};

/// A sweep small enough for a test: 2 scenes × 2 lights × 2 techniques × 2 sides = 16 cells.
const SPEC: &str = r#"
scenes = ["outdoor", "dueling-frusta"]
techniques = ["uniform", "lispsm"]
resolutions = [128, 256]
[lights]
kind = "gamma"
degrees = [20.0, 70.0]
"#;

fn write_spec(dir: &Path) -> String {
    let path = dir.join("spec.toml");
    std::fs::write(&path, SPEC).unwrap();
    path.to_str().unwrap().to_string()
}

fn run_with_threads(args: &[&str], threads: &str) -> Output {
    Command::new(env!("CARGO_BIN_EXE_shadowlab"))
        .args(args)
        .env("RAYON_NUM_THREADS", threads)
        .output()
        .unwrap()
}

fn ok(output: &Output) {
    assert!(output.status.success(), "{}", stderr(output));
}

/// The merged results with their timings removed: the CSV without its `*_ms` columns, the report
/// up to its time section, and every figure's bytes.
fn timeless(merged: &Path) -> Vec<(String, Vec<u8>)> {
    let csv = std::fs::read_to_string(merged.join("results.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let keep: Vec<usize> = (0..header.len())
        .filter(|k| !header[*k].ends_with("_ms"))
        .collect();
    assert!(keep.len() < header.len(), "the table has timing columns");
    // No field of this sweep's table holds a comma, so splitting on commas is exact here.
    let table: String = std::iter::once(header.join(","))
        .chain(lines.map(|line| {
            let fields: Vec<&str> = line.split(',').collect();
            keep.iter()
                .map(|k| fields[*k])
                .collect::<Vec<_>>()
                .join(",")
        }))
        .collect::<Vec<_>>()
        .join("\n");
    let report = std::fs::read_to_string(merged.join("report.md")).unwrap();
    let (before_time, _) = report.split_once("\n## Time").expect("a time section");
    let mut out = vec![
        ("results.csv".into(), table.into_bytes()),
        ("report.md".into(), before_time.as_bytes().to_vec()),
    ];
    for figure in [
        "distribution.svg",
        "distribution.png",
        "gamma.svg",
        "gamma.png",
        "resolution.svg",
        "resolution.png",
    ] {
        out.push((figure.into(), std::fs::read(merged.join(figure)).unwrap()));
    }
    out
}

/// Claim: the sweep run whole on two threads and as three shards — concurrently, one thread each,
/// two sharing a directory and one in its own — merges to the same table, report and figures,
/// timings aside; a shard's own table lists exactly its cells.
#[test]
fn shards_merge_to_the_whole_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path());
    let whole = dir.path().join("whole");
    ok(&run_with_threads(
        &["sweep", &spec, "--out", whole.to_str().unwrap()],
        "2",
    ));
    let (a, b) = (dir.path().join("a"), dir.path().join("b"));
    let shards: Vec<_> = [(&a, "0/3"), (&a, "1/3"), (&b, "2/3")]
        .into_iter()
        .map(|(d, shard)| {
            Command::new(env!("CARGO_BIN_EXE_shadowlab"))
                .args([
                    "sweep",
                    &spec,
                    "--out",
                    d.to_str().unwrap(),
                    "--shard",
                    shard,
                ])
                .env("RAYON_NUM_THREADS", "1")
                .stdout(Stdio::null())
                .spawn()
                .unwrap()
        })
        .collect();
    for mut shard in shards {
        assert!(shard.wait().unwrap().success());
    }
    let merged = dir.path().join("merged");
    ok(&shadowlab(
        &[
            "merge",
            a.to_str().unwrap(),
            b.to_str().unwrap(),
            "--out",
            merged.to_str().unwrap(),
        ],
        None,
    ));
    assert_eq!(timeless(&whole.join("merged")), timeless(&merged));
    let rows = |p: &Path| std::fs::read_to_string(p).unwrap().lines().count() - 1;
    let shard_rows: usize = [
        a.join("shard-0-of-3/results.csv"),
        a.join("shard-1-of-3/results.csv"),
        b.join("shard-2-of-3/results.csv"),
    ]
    .iter()
    .map(|p| rows(p))
    .sum();
    assert_eq!(shard_rows, 16);
    assert_eq!(rows(&merged.join("results.csv")), 16);
    assert!(
        std::fs::read(merged.join("results.parquet"))
            .unwrap()
            .starts_with(b"PAR1")
    );
}

/// Claim: a rerun measures only the cells whose results are missing or unreadable, and the
/// results are the same as before.
#[test]
fn a_rerun_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path());
    let out = dir.path().join("sweep");
    let args = ["sweep", spec.as_str(), "--out", out.to_str().unwrap()];
    ok(&shadowlab(&args, None));
    let before = timeless(&out.join("merged"));
    std::fs::remove_file(out.join("cells/00000003.json")).unwrap();
    std::fs::write(out.join("cells/00000011.json"), "{\"cell\": 11, \"sce").unwrap();
    let again = shadowlab(&args, None);
    ok(&again);
    assert!(
        stdout(&again).contains("16 cells (2 measured now, 14 stored before)"),
        "{}",
        stdout(&again)
    );
    assert_eq!(before, timeless(&out.join("merged")));
}

/// Claim: a merge with cells missing is refused (exit 2), saying how many and what to do; so is
/// merging two different sweeps, and a sweep into a directory that holds something else.
#[test]
fn incomplete_or_foreign_results_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path());
    let half = dir.path().join("half");
    ok(&shadowlab(
        &[
            "sweep",
            &spec,
            "--out",
            half.to_str().unwrap(),
            "--shard",
            "0/2",
        ],
        None,
    ));
    let merged = dir.path().join("merged");
    assert_refused(
        &[
            "merge",
            half.to_str().unwrap(),
            "--out",
            merged.to_str().unwrap(),
        ],
        "cells have no result yet",
    );
    assert!(!merged.exists(), "nothing written");
    let other = dir.path().join("other.toml");
    std::fs::write(&other, "resolutions = [64]\n").unwrap();
    assert_refused(
        &[
            "sweep",
            other.to_str().unwrap(),
            "--out",
            half.to_str().unwrap(),
        ],
        "another sweep",
    );
    let foreign = dir.path().join("foreign");
    std::fs::create_dir(&foreign).unwrap();
    std::fs::write(foreign.join("notes.txt"), "mine").unwrap();
    assert_refused(
        &["sweep", &spec, "--out", foreign.to_str().unwrap()],
        "not a sweep's",
    );
    assert_refused(
        &[
            "merge",
            foreign.to_str().unwrap(),
            "--out",
            merged.to_str().unwrap(),
        ],
        "not a sweep directory",
    );
}

/// Claim: a bad spec is refused with exit 2 naming the field, before anything is written; a bad
/// shard names the form.
#[test]
fn bad_specs_name_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    for (text, field) in [
        ("techniques = [\"uniform\", \"bogus\"]", "techniques[1]"),
        ("scenes = [\"nowhere.toml\"]", "scenes[0]"),
        ("resolutions = [0]", "resolutions[0]"),
        ("[cameras]\nkind = \"random\"\ncount = 2", "seed"),
        ("techniques = [\"cube\"]", "does not serve"),
    ] {
        let spec = dir.path().join("bad.toml");
        std::fs::write(&spec, text).unwrap();
        assert_refused(
            &[
                "sweep",
                spec.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ],
            field,
        );
        assert!(!out.exists(), "{text}: nothing written");
    }
    let spec = write_spec(dir.path());
    assert_refused(&["sweep", &spec, "--shard", "3/3"], "I/N");
}

/// Claim: `--example` prints a spec that parses, and `--dry-run` counts its cells and frames and
/// splits them over shards, running nothing.
#[test]
fn the_example_and_the_dry_run() {
    let dir = tempfile::tempdir().unwrap();
    let example = shadowlab(&["sweep", "--example"], None);
    ok(&example);
    let spec = dir.path().join("example.toml");
    std::fs::write(&spec, stdout(&example)).unwrap();
    let dry = shadowlab(
        &[
            "sweep",
            spec.to_str().unwrap(),
            "--dry-run",
            "--shards",
            "4",
        ],
        Some(dir.path()),
    );
    ok(&dry);
    let text = stdout(&dry);
    assert!(
        text.starts_with("48 cells in 6 frames (2 scene(s))"),
        "{text}"
    );
    let per_shard: usize = text
        .lines()
        .filter(|l| l.starts_with("shard "))
        .map(|l| {
            l.split(": ")
                .nth(1)
                .unwrap()
                .split(' ')
                .next()
                .unwrap()
                .parse::<usize>()
                .unwrap()
        })
        .sum();
    assert_eq!(per_shard, 48);
    assert!(!dir.path().join("out").exists(), "a dry run writes nothing");
}

/// Claim: `--slurm --shards 4` writes a job array of 4 tasks (the task id as the shard), a merge
/// that runs after every task succeeded, and scripts bash accepts; it runs nothing.
#[test]
fn slurm_scripts_are_a_job_array_and_a_dependent_merge() {
    let dir = tempfile::tempdir().unwrap();
    let spec = write_spec(dir.path());
    let out = dir.path().join("sweep");
    let written = shadowlab(
        &[
            "sweep",
            &spec,
            "--out",
            out.to_str().unwrap(),
            "--slurm",
            "--shards",
            "4",
            "--sbatch-option",
            "--time=00:10:00",
        ],
        None,
    );
    ok(&written);
    let slurm = out.join("slurm");
    let array = std::fs::read_to_string(slurm.join("array.sbatch")).unwrap();
    assert!(array.contains("#SBATCH --array=0-3\n"), "{array}");
    assert!(array.contains("#SBATCH --time=00:10:00\n"), "{array}");
    assert!(
        array.contains("--shard \"${SLURM_ARRAY_TASK_ID}/4\""),
        "{array}"
    );
    let merge = std::fs::read_to_string(slurm.join("merge.sbatch")).unwrap();
    assert!(
        merge.contains(" merge ") && merge.contains("merged"),
        "{merge}"
    );
    let submit = std::fs::read_to_string(slurm.join("submit.sh")).unwrap();
    assert!(submit.contains("--dependency=afterok:"), "{submit}");
    for script in ["array.sbatch", "merge.sbatch", "submit.sh"] {
        let syntax = Command::new("bash")
            .arg("-n")
            .arg(slurm.join(script))
            .status()
            .unwrap();
        assert!(syntax.success(), "{script}");
    }
    let cells = std::fs::read_dir(out.join("cells")).unwrap().count();
    assert_eq!(cells, 0, "--slurm runs nothing");
    assert_refused(
        &[
            "sweep",
            &spec,
            "--slurm",
            "--shards",
            "2",
            "--sbatch-option",
            "time=5",
        ],
        "--sbatch-option",
    );
}

/// Claim: every light and camera generator yields the documented number of frames (a dry run
/// counts them), and random poses run: a sweep of them measures every cell.
#[test]
fn generators_make_the_documented_frames() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("gen.toml");
    for (text, frames) in [
        (
            "[lights]\nkind = \"sphere\"\nelevations = [30.0, 90.0]\nazimuths = 5",
            6,
        ),
        (
            "[lights]\nkind = \"gamma\"\nrange = { from = 0.0, to = 90.0, steps = 4 }",
            4,
        ),
        ("[cameras]\nkind = \"walk\"\nframes = 3\nevery = 10", 3),
        (
            "[cameras]\nkind = \"path\"\nposes = [{ eye = [0, 5, 20], target = [0, 0, 0] }, { eye = [5, 5, 20], target = [0, 0, 0] }]",
            2,
        ),
        ("[cameras]\nkind = \"random\"\ncount = 2\nseed = 11", 2),
    ] {
        std::fs::write(
            &spec,
            format!("techniques = [\"uniform\"]\nresolutions = [64]\n{text}"),
        )
        .unwrap();
        let dry = shadowlab(&["sweep", spec.to_str().unwrap(), "--dry-run"], None);
        ok(&dry);
        assert!(
            stdout(&dry).starts_with(&format!("{frames} cells in {frames} frames")),
            "{text}: {}",
            stdout(&dry)
        );
    }
    let out = dir.path().join("random");
    let run = shadowlab(
        &[
            "sweep",
            spec.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        None,
    );
    ok(&run);
    assert!(
        stdout(&run).contains("2 cells (2 measured now"),
        "{}",
        stdout(&run)
    );
}

/// Claim: a generated frame that admits no map for a technique (a camera looking at the sky:
/// SDSM has no visible sample to fit) is recorded as that cell's outcome, with the reason, and
/// the sweep goes on; the table quotes the reason's commas.
#[test]
fn frames_without_a_map_are_recorded_not_fatal() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("sky.toml");
    std::fs::write(
        &spec,
        "scenes = [\"outdoor\"]\ntechniques = [\"uniform\", \"sdsm\"]\nresolutions = [64]\n[cameras]\nkind = \"path\"\nposes = [{ eye = [0, 5, 0], target = [0, 50, 1] }, { eye = [0, 5, 20], target = [0, 0, 0] }]\n",
    )
    .unwrap();
    let out = dir.path().join("sky");
    ok(&shadowlab(
        &[
            "sweep",
            spec.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        None,
    ));
    let csv = std::fs::read_to_string(out.join("merged/results.csv")).unwrap();
    let undefined: Vec<&str> = csv.lines().filter(|l| l.contains(",false,")).collect();
    assert_eq!(undefined.len(), 1, "{csv}");
    assert!(
        undefined[0].contains(",sdsm,") && undefined[0].contains("\"no visible sample"),
        "{csv}"
    );
    let report = std::fs::read_to_string(out.join("merged/report.md")).unwrap();
    assert!(report.contains("## Undefined cells"), "{report}");
}
