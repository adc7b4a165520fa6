//! Output sets under faults: a rerun, two concurrent runs, SIGINT and SIGKILL at any moment, a
//! write that fails, a full file system, destinations that are not shadowlab's to replace, and
//! scene names that try to leave the output directory.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use sha2::{Digest, Sha256};

use crate::support::{shadowlab, stderr};

/// The prefix of staging entries (`src/staging.rs`).
const STAGING_PREFIX: &str = ".shadowlab-staging-";

/// A small scene that analyzes in about a second in the test profile.
fn scene_file(dir: &Path) -> String {
    let path = dir.join("small.toml");
    fs::write(
        &path,
        "name = \"../../escape\"\n\
         [camera]\nposition = [0.0, 3.0, 12.0]\ntarget = [0.0, 0.0, -10.0]\nimage = [96, 72]\n\
         far = 60.0\n\
         [[light]]\ndirection = [-0.6, -1.0, -0.2]\n\
         [[mesh]]\nshape = \"plane\"\nsize = [60.0, 60.0]\n\
         [[mesh]]\nshape = \"box\"\nsize = [2.0, 2.0, 2.0]\ntranslate = [0.0, 1.0, 0.0]\n",
    )
    .unwrap();
    path.display().to_string()
}

/// `analyze` of `scene` by `techniques` at 128² into `out`.
fn analyze_args<'a>(scene: &'a str, techniques: &'a str, out: &'a str) -> Vec<&'a str> {
    vec![
        "analyze",
        scene,
        "--techniques",
        techniques,
        "--resolutions",
        "128",
        "--out",
        out,
    ]
}

/// A scene file (in the first directory) and an output set's path `set` in an empty second one.
fn fixture() -> (tempfile::TempDir, String, tempfile::TempDir, PathBuf) {
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path());
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("set");
    (scenes, scene, root, out)
}

/// Runs [`analyze_args`] and asserts success.
fn analyze_ok(scene: &str, techniques: &str, out: &str) {
    let output = shadowlab(&analyze_args(scene, techniques, out), None);
    assert!(output.status.success(), "{}", stderr(&output));
}

fn spawn(args: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_shadowlab"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the shadowlab binary starts")
}

/// Every file under `dir` (relative, `/`-separated), the manifest left out.
fn files_under(dir: &Path) -> Vec<String> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<String>) {
        for entry in fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(root, &path, out);
            } else {
                let name = path.strip_prefix(root).unwrap().to_string_lossy();
                out.push(name.replace('\\', "/"));
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.retain(|n| n != "manifest.json");
    out.sort();
    out
}

/// Asserts that `dir` holds exactly the files its manifest lists, each of the listed size and
/// SHA-256, and returns their names.
fn assert_whole_set(dir: &Path) -> Vec<String> {
    let manifest: serde_json::Value =
        serde_json::from_slice(&fs::read(dir.join("manifest.json")).expect("a manifest")).unwrap();
    let mut listed = Vec::new();
    for file in manifest["files"].as_array().unwrap() {
        let name = file["name"].as_str().unwrap().to_string();
        let bytes =
            fs::read(dir.join(&name)).unwrap_or_else(|_| panic!("{name} is listed but missing"));
        assert_eq!(file["bytes"].as_u64(), Some(bytes.len() as u64), "{name}");
        let hash: String = Sha256::digest(&bytes)
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect();
        assert_eq!(file["sha256"].as_str(), Some(hash.as_str()), "{name}");
        listed.push(name);
    }
    assert_eq!(files_under(dir), listed, "files the manifest does not list");
    listed
}

/// Staging entries left in `dir`.
fn staging_left(dir: &Path) -> Vec<PathBuf> {
    fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with(STAGING_PREFIX))
        })
        .collect()
}

/// The techniques whose pictures a set holds.
fn pictured(files: &[String]) -> Vec<String> {
    files
        .iter()
        .filter_map(|f| f.strip_prefix("images/heatmap-"))
        .map(|f| f.trim_end_matches(".png").to_string())
        .collect()
}

#[test]
fn a_rerun_replaces_the_whole_set() {
    let (_scenes, scene, root, out) = fixture();
    let out_s = out.to_str().unwrap();
    analyze_ok(&scene, "uniform,psm", out_s);
    assert_eq!(pictured(&assert_whole_set(&out)), ["psm", "uniform"]);
    analyze_ok(&scene, "lispsm", out_s);
    let files = assert_whole_set(&out);
    assert_eq!(
        pictured(&files),
        ["lispsm"],
        "the earlier run's images stayed"
    );
    assert!(staging_left(root.path()).is_empty());
}

#[test]
fn two_concurrent_runs_leave_one_whole_set() {
    let (_scenes, scene, root, out) = fixture();
    let out_s = out.to_str().unwrap();
    for _ in 0..3 {
        let a = spawn(&analyze_args(&scene, "uniform,psm", out_s));
        let b = spawn(&analyze_args(&scene, "lispsm", out_s));
        for child in [a, b] {
            let output = child.wait_with_output().unwrap();
            assert!(output.status.success(), "{}", stderr(&output));
        }
        let techniques = pictured(&assert_whole_set(&out));
        assert!(
            techniques == ["psm", "uniform"] || techniques == ["lispsm"],
            "a mixed set: {techniques:?}"
        );
        assert!(staging_left(root.path()).is_empty());
    }
}

#[test]
fn sigint_and_sigterm_leave_the_previous_set_and_no_staging() {
    use rustix::process::{Pid, Signal, kill_process};
    let (_scenes, scene, root, out) = fixture();
    let out_s = out.to_str().unwrap();
    analyze_ok(&scene, "uniform", out_s);
    let before = assert_whole_set(&out);
    for (signal, code) in [(Signal::INT, 130), (Signal::TERM, 143)] {
        // The default resolutions take several seconds: the signal arrives mid-run.
        let child = spawn(&[
            "analyze",
            &scene,
            "--techniques",
            "uniform,psm,lispsm",
            "--out",
            out_s,
        ]);
        std::thread::sleep(Duration::from_millis(700));
        let pid = Pid::from_child(&child);
        kill_process(pid, signal).unwrap();
        let output = child.wait_with_output().unwrap();
        assert_eq!(output.status.code(), Some(code), "{}", stderr(&output));
        assert!(
            stderr(&output).contains("interrupted"),
            "{}",
            stderr(&output)
        );
        assert_eq!(assert_whole_set(&out), before, "the previous set changed");
        assert!(staging_left(root.path()).is_empty());
    }
}

#[test]
fn sigkill_at_any_moment_leaves_a_whole_set_and_the_next_run_clears_the_rest() {
    use rustix::process::{Pid, Signal, kill_process};
    let (_scenes, scene, root, out) = fixture();
    let out_s = out.to_str().unwrap();
    analyze_ok(&scene, "uniform", out_s);
    let args = analyze_args(&scene, "uniform,psm", out_s);
    let start = Instant::now();
    let timed = shadowlab(&args, None);
    assert!(timed.status.success(), "{}", stderr(&timed));
    let duration = start.elapsed();
    // Kills spread over the whole run, the write phase at its end included.
    for k in 1..=8 {
        let child = spawn(&args);
        std::thread::sleep(duration.mul_f64(f64::from(k) / 8.0));
        let _ = kill_process(Pid::from_child(&child), Signal::KILL);
        let _ = child.wait_with_output().unwrap();
        let techniques = pictured(&assert_whole_set(&out));
        assert!(
            techniques == ["uniform"] || techniques == ["psm", "uniform"],
            "kill at {k}/8: a mixed set {techniques:?}"
        );
    }
    analyze_ok(&scene, "lispsm", out_s);
    assert_eq!(pictured(&assert_whole_set(&out)), ["lispsm"]);
    assert!(
        staging_left(root.path()).is_empty(),
        "orphans of killed runs stayed: {:?}",
        staging_left(root.path())
    );
}

#[test]
fn a_write_that_fails_keeps_the_previous_set() {
    let (_scenes, scene, root, out) = fixture();
    let out_s = out.to_str().unwrap();
    analyze_ok(&scene, "uniform", out_s);
    let before = assert_whole_set(&out);
    // Files larger than 8 blocks fail to write (EFBIG) as on a full disk; the shell ignores
    // SIGXFSZ so that the write returns the error instead of killing the process.
    let output = Command::new("sh")
        .arg("-c")
        .arg("ulimit -f 8; trap '' XFSZ; exec \"$0\" \"$@\"")
        .arg(env!("CARGO_BIN_EXE_shadowlab"))
        .args(analyze_args(&scene, "uniform,psm", out_s))
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("cannot write"),
        "{}",
        stderr(&output)
    );
    assert_eq!(assert_whole_set(&out), before);
    assert!(staging_left(root.path()).is_empty());
}

/// Mounts a tmpfs of `options` at `dir`; `None` (with the reason printed) where this process may
/// not mount.
fn mount_tmpfs(dir: &Path, options: &str) -> Option<()> {
    let status = Command::new("mount")
        .args(["-t", "tmpfs", "-o", options, "tmpfs"])
        .arg(dir)
        .stderr(Stdio::null())
        .status();
    if status.is_ok_and(|s| s.success()) {
        Some(())
    } else {
        eprintln!("skipped: cannot mount a tmpfs here (needs root and mount(8))");
        None
    }
}

fn unmount(dir: &Path) {
    let _ = Command::new("umount").arg(dir).status();
}

#[test]
fn a_full_or_read_only_file_system_is_refused_before_the_work() {
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path());
    let root = tempfile::tempdir().unwrap();
    let small = root.path().join("small");
    let read_only = root.path().join("read-only");
    fs::create_dir(&small).unwrap();
    fs::create_dir(&read_only).unwrap();
    if mount_tmpfs(&small, "size=64k").is_none() {
        return;
    }
    let out = small.join("set");
    // All techniques at all default resolutions would take a minute; refused at once.
    let start = Instant::now();
    let output = shadowlab(&["analyze", &scene, "--out", out.to_str().unwrap()], None);
    let elapsed = start.elapsed();
    let listed = fs::read_dir(&small).unwrap().count();
    unmount(&small);
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("not enough space for --out"),
        "{}",
        stderr(&output)
    );
    assert_eq!(listed, 0, "something was written");
    assert!(
        elapsed < Duration::from_secs(20),
        "refused only after {elapsed:?}"
    );
    if mount_tmpfs(&read_only, "ro,size=1m").is_none() {
        return;
    }
    let output = shadowlab(
        &[
            "analyze",
            &scene,
            "--out",
            read_only.join("set").to_str().unwrap(),
        ],
        None,
    );
    unmount(&read_only);
    assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("--out") && stderr(&output).contains("not writable"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn only_what_shadowlab_wrote_is_replaced() {
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path());
    let root = tempfile::tempdir().unwrap();
    let foreign = root.path().join("foreign");
    fs::create_dir(&foreign).unwrap();
    fs::write(foreign.join("thesis.tex"), b"mine").unwrap();
    let fifo = root.path().join("fifo");
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let file = root.path().join("file.txt");
    fs::write(&file, b"mine").unwrap();
    let link = root.path().join("link");
    std::os::unix::fs::symlink(&foreign, &link).unwrap();
    let file_link = root.path().join("file-link.png");
    std::os::unix::fs::symlink(&file, &file_link).unwrap();
    let cases: [(&[&str], &Path, &str); 8] = [
        (
            &["analyze", &scene, "--out"],
            &foreign,
            "not a shadowlab output set",
        ),
        (&["analyze", &scene, "--out"], &fifo, "a FIFO"),
        (&["analyze", &scene, "--out"], &file, "a regular file"),
        (&["analyze", &scene, "--out"], &link, "a symbolic link"),
        (&["curves", "--out"], &file.join("below"), "not a directory"),
        (&["compare", &scene, "--out"], &fifo, "only regular files"),
        (&["compare", &scene, "--out"], &file_link, "a symbolic link"),
        (&["compare", &scene, "--out"], &foreign, "is a directory"),
    ];
    for (args, target, expected) in cases {
        let mut all = args.to_vec();
        all.push(target.to_str().unwrap());
        let start = Instant::now();
        let output = shadowlab(&all, None);
        let message = stderr(&output);
        assert_eq!(output.status.code(), Some(2), "{all:?}: {message}");
        assert!(
            message.contains("--out") && message.contains(expected),
            "{all:?}: {message}"
        );
        assert!(
            start.elapsed() < Duration::from_secs(10),
            "{all:?}: refused late"
        );
    }
    assert_eq!(fs::read(foreign.join("thesis.tex")).unwrap(), b"mine");
    assert_eq!(fs::read_dir(&foreign).unwrap().count(), 1);
    assert_eq!(fs::read(&file).unwrap(), b"mine");
    assert!(
        fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert!(
        fs::symlink_metadata(&file_link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    {
        use std::os::unix::fs::FileTypeExt;
        assert!(fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
    }
    assert!(staging_left(root.path()).is_empty());
}

#[test]
fn a_scene_name_never_leaves_the_output_directory() {
    let scenes = tempfile::tempdir().unwrap();
    let scene = scene_file(scenes.path());
    let root = tempfile::tempdir().unwrap();
    let cwd = root.path().join("a").join("b");
    fs::create_dir_all(&cwd).unwrap();
    let output = shadowlab(
        &[
            "analyze",
            &scene,
            "--techniques",
            "uniform",
            "--resolutions",
            "64",
        ],
        Some(&cwd),
    );
    assert!(output.status.success(), "{}", stderr(&output));
    // The name "../../escape" is the slug "escape", inside out/analyze.
    assert_whole_set(&cwd.join("out/analyze/escape"));
    assert!(!root.path().join("escape").exists());
    assert_eq!(
        fs::read_dir(root.path()).unwrap().count(),
        1,
        "written beside a/"
    );
}
