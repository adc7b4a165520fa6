//! Hostile input through the real binary: malformed OBJ and scene files, special files, absurd
//! flags. Each case runs in a fresh directory holding its files and asserts the exit code (2 for a
//! usage or input error, 1 for an I/O failure), a message naming the cause (the flag, or the file
//! and the field or line, and the allowed range), no panic, and nothing written in the output
//! directory `out` that every command writing files is pointed at.
//!
//! To add a case, add a [`Case`] to a table: its arguments (`{dir}` stands for the case's
//! directory), the files to write there first, the exit code and the message's fragments.

use std::path::Path;

use crate::support::{shadowlab, stderr};

/// One hostile invocation and what it must produce.
struct Case {
    /// The arguments; `{dir}` is replaced by the case's directory.
    args: &'static [&'static str],
    /// Files written into the case's directory first: (name, contents).
    files: &'static [(&'static str, &'static [u8])],
    /// The exit code: 2 for usage and input errors, 1 for I/O failures.
    code: i32,
    /// Fragments the message on standard error must all contain.
    expected: &'static [&'static str],
}

/// Shorthand for a refused case (exit code 2).
const fn refused(
    args: &'static [&'static str],
    files: &'static [(&'static str, &'static [u8])],
    expected: &'static [&'static str],
) -> Case {
    Case {
        args,
        files,
        code: 2,
        expected,
    }
}

/// The output directory every writing command is given, relative to the case's directory.
const OUT: &str = "out";

/// Runs every case; collects all failures so one run reports them together.
fn run(cases: &[Case]) {
    let failures: Vec<String> = cases.iter().filter_map(check).collect();
    assert!(
        failures.is_empty(),
        "{} of {} cases failed:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

/// One case; `Some(why)` if it failed.
fn check(case: &Case) -> Option<String> {
    let dir = tempfile::tempdir().expect("a temporary directory");
    for (name, contents) in case.files {
        std::fs::write(dir.path().join(name), contents).expect("write a case's file");
    }
    let root = dir.path().display().to_string();
    let args: Vec<String> = case
        .args
        .iter()
        .map(|a| a.replace("{dir}", &root))
        .collect();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let output = shadowlab(&args, Some(dir.path()));
    let message = stderr(&output);
    let mut problems = Vec::new();
    if output.status.code() != Some(case.code) {
        problems.push(format!(
            "exit code {:?}, expected {}",
            output.status.code(),
            case.code
        ));
    }
    for fragment in case.expected {
        if !message.contains(fragment) {
            problems.push(format!("message lacks {fragment:?}"));
        }
    }
    if message.contains("panicked") {
        problems.push("it panicked".to_owned());
    }
    if wrote_something(&dir.path().join(OUT)) {
        problems.push(format!("it wrote into {OUT}/"));
    }
    (!problems.is_empty()).then(|| {
        format!(
            "{:?}: {}\n  stderr: {message}",
            case.args,
            problems.join("; ")
        )
    })
}

/// Whether `out` exists with anything in it (an empty directory created early is not output).
fn wrote_something(out: &Path) -> bool {
    std::fs::read_dir(out).is_ok_and(|mut entries| entries.next().is_some())
}

/// `render-mesh` on `bad.obj` at a tiny size.
macro_rules! mesh_case {
    ($text:expr, $($expected:expr),+) => {
        refused(
            &["render-mesh", "bad.obj", "--size", "8", "--eye-size", "8x8", "--out", OUT],
            &[("bad.obj", $text)],
            &[$($expected),+],
        )
    };
}

#[test]
fn malformed_obj_files_name_the_file_the_line_and_the_rule() {
    run(&[
        mesh_case!(
            b"v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
            "bad.obj:1:",
            "`nan` is not finite"
        ),
        mesh_case!(
            b"v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n",
            "bad.obj:2:",
            "not finite"
        ),
        mesh_case!(
            b"v 0 0 0\nv 1e308 0 0\nv 0 1 0\nf 1 2 3\n",
            "bad.obj:2:",
            "beyond ±1e40 (MAX_COORDINATE)"
        ),
        mesh_case!(
            b"v 0 0 0\nv 1 0 0\nv 0 1e30 0 1e-20\nf 1 2 3\n",
            "bad.obj:3:",
            "`1e30/1e-20` is beyond ±1e40 (MAX_COORDINATE)"
        ),
        mesh_case!(
            b"v 0 0 0\nv 1e-310 0 0\nv 0 1e-310 1e-310\nf 1 2 3\n",
            "bad.obj:",
            "span 1e-310",
            "at least 1e-40 (MIN_EXTENT)"
        ),
        mesh_case!(
            b"v 5 5 5\nv 5 5 5\nv 5 5 5\nf 1 2 3\n",
            "bad.obj:",
            "(MIN_EXTENT)"
        ),
        mesh_case!(
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
            "bad.obj:4:",
            "index 0"
        ),
        mesh_case!(
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
            "bad.obj:4:",
            "index 9 is out of range"
        ),
        mesh_case!(
            b"v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\n",
            "bad.obj:2:",
            "out of range"
        ),
        mesh_case!(
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -99999999999999999999 1 2\n",
            "bad.obj:4:",
            "face vertex `-99999999999999999999`"
        ),
        mesh_case!(
            b"v 0 0 0\nv 1 0 0\nf 1 2\n",
            "bad.obj:3:",
            "at least 3 vertices, found 2"
        ),
        mesh_case!(b"v 0 0\n", "bad.obj:1:", "`v` takes x y z"),
        mesh_case!(b"vn 0 1\n", "bad.obj:1:", "`vn` takes x y z"),
        mesh_case!(b"v a b c\n", "bad.obj:1:", "`a` is not a number"),
        mesh_case!(
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n",
            "bad.obj:4:",
            "face vertex `1/1/1/1`"
        ),
        mesh_case!(
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2 3\n",
            "bad.obj:5:",
            "some corners of this face name a normal"
        ),
        mesh_case!(b"v 1 2 3 0\n", "bad.obj:1:", "the weight w is 0"),
        mesh_case!(b"v 0 0 0\n# caf\xe9\n", "bad.obj:2:", "not valid UTF-8"),
        mesh_case!(b"", "bad.obj: no faces"),
        mesh_case!(b"# only a comment\nv 0 0 0\n", "bad.obj: no faces"),
        mesh_case!(b"usemtl\n", "bad.obj:1:", "`usemtl` needs a material name"),
        mesh_case!(
            b"v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
            "bad.obj:2:",
            "with and without a colour"
        ),
    ]);
}

#[test]
fn obj_paths_that_are_not_regular_files_are_refused_without_reading() {
    let mut cases = vec![
        refused(
            &["render-mesh", "/dev/zero", "--size", "8", "--out", OUT],
            &[],
            &["/dev/zero: is a character device, not a regular file"],
        ),
        refused(
            &["render-mesh", "{dir}", "--size", "8", "--out", OUT],
            &[],
            &["is a directory, not a regular file"],
        ),
        refused(
            &["render-mesh", "absent.obj", "--size", "8", "--out", OUT],
            &[],
            &["absent.obj: No such file"],
        ),
    ];
    if cfg!(target_os = "linux") {
        // A regular file that the kernel fails to read (EIO): an I/O failure, exit code 1.
        cases.push(Case {
            args: &["render-mesh", "/proc/self/mem", "--size", "8", "--out", OUT],
            files: &[],
            code: 1,
            expected: &["/proc/self/mem: Input/output error"],
        });
    }
    run(&cases);
}

/// `render` of `bad.toml` with a tiny map.
macro_rules! scene_case {
    ($text:expr, $($expected:expr),+) => {
        refused(
            &["render", "bad.toml", "--resolution", "8", "--out", OUT],
            const {
                &[
                    ("bad.toml", $text),
                    ("bad.obj", b"v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
                    ("tiny.obj", b"v 0 0 0\nv 1e-310 0 0\nv 0 1e-310 0\nf 1 2 3\n"),
                ]
            },
            &[$($expected),+],
        )
    };
}

/// A valid mesh entry.
macro_rules! with_box {
    ($text:expr) => {
        concat!("[[mesh]]\nshape = \"box\"\n", $text).as_bytes()
    };
}

#[test]
fn malformed_scene_files_name_the_file_the_field_and_the_range() {
    run(&[
        scene_case!(b"[camera\n", "bad.toml:1:"),
        scene_case!(
            with_box!("[camera]\nfovy = 60\n"),
            "bad.toml:",
            "camera.fovy",
            "unknown field `fovy`"
        ),
        scene_case!(
            with_box!("[camera]\nimage = [20000, 100]\n"),
            "bad.toml: camera.image[0] (20000) must be in 1..=16384 pixels (MAX_IMAGE_SIDE)"
        ),
        scene_case!(
            with_box!("[camera]\nimage = [64, 0]\n"),
            "bad.toml: camera.image[1] (0)",
            "1..=16384"
        ),
        scene_case!(
            with_box!("[camera]\nimage = [-1, 64]\n"),
            "bad.toml:",
            "camera.image[0]"
        ),
        scene_case!(
            with_box!("[camera]\nfov = 1e-9\n"),
            "bad.toml: camera.fov (1e-9) must be in [0.001, 180) degrees (MIN_ANGLE_DEGREES)"
        ),
        scene_case!(
            with_box!("[camera]\nfov = 180\n"),
            "bad.toml: camera.fov (180)",
            "[0.001, 180)"
        ),
        scene_case!(
            with_box!("[camera]\nfov = nan\n"),
            "bad.toml: camera.fov (NaN) must be finite"
        ),
        scene_case!(
            with_box!("[camera]\nnear = 1e-300\nfar = 10\n"),
            "bad.toml: camera.near (1e-300) must be at least camera.far / 1000000 (MAX_DEPTH_RATIO) = 1e-5"
        ),
        scene_case!(
            with_box!("[camera]\nnear = 1e-300\nfar = 1e-301\n"),
            "bad.toml: camera.near (1e-300) must be below camera.far (1e-301)"
        ),
        scene_case!(
            with_box!("[camera]\nnear = -1\n"),
            "bad.toml: camera.near (-1) must be > 0"
        ),
        scene_case!(
            with_box!("[camera]\ndirection = [0, -1, 0]\nup = [0, 1, 0]\n"),
            "bad.toml: camera.up [0, 1, 0] is parallel to the view direction"
        ),
        scene_case!(
            with_box!("[camera]\nposition = [1, 2, 3]\ntarget = [1, 2, 3]\n"),
            "bad.toml: camera.target [1, 2, 3] coincides with camera.position"
        ),
        scene_case!(
            with_box!("[camera]\ndirection = [0, 0, 0]\n"),
            "bad.toml: camera.direction [0, 0, 0] has no direction"
        ),
        scene_case!(
            with_box!("[camera]\nposition = [1e308, 0, 0]\ntarget = [-1e308, 0, 0]\n"),
            "bad.toml: camera:"
        ),
        scene_case!(
            with_box!("[[light]]\ndirection = [0, 0, 0]\n"),
            "bad.toml: light[0].direction [0, 0, 0] has no direction"
        ),
        scene_case!(
            with_box!("[[light]]\nkind = \"spot\"\ncone = 0\n"),
            "bad.toml: light[0].cone (0) must be in [0.001, 180)"
        ),
        scene_case!(
            with_box!("[[light]]\nkind = \"spot\"\ncone = 200\n"),
            "bad.toml: light[0].cone (200)"
        ),
        scene_case!(
            with_box!("[[light]]\nkind = \"spot\"\nnear = 3\nfar = 2\n"),
            "bad.toml: light[0].near (3) must be below light[0].far (2)"
        ),
        scene_case!(
            with_box!("[[light]]\nkind = \"laser\"\n"),
            "bad.toml:",
            "light[0].kind",
            "laser"
        ),
        scene_case!(
            with_box!("[[light]]\ncone = 30\n"),
            "bad.toml: light[0].cone does not apply to a directional light"
        ),
        scene_case!(
            b"name = \"empty\"\n",
            "bad.toml: mesh needs at least one `[[mesh]]` entry"
        ),
        scene_case!(
            b"[[mesh]]\nobj = \"a.obj\"\nshape = \"box\"\n",
            "bad.toml: mesh[0].obj and mesh[0].shape exclude each other"
        ),
        scene_case!(
            b"[[mesh]]\nobj = \"gone.obj\"\n",
            "bad.toml: mesh[0].obj:",
            "gone.obj: No such file"
        ),
        scene_case!(
            b"[[mesh]]\nobj = \"bad.obj\"\n",
            "bad.toml: mesh[0].obj:",
            "bad.obj:1: `v`: `nan` is not finite"
        ),
        scene_case!(
            b"[[mesh]]\nobj = \"tiny.obj\"\n",
            "bad.toml: mesh[0].obj:",
            "tiny.obj:",
            "(MIN_EXTENT)"
        ),
        scene_case!(
            b"[[mesh]]\nobj = \"/dev/zero\"\n",
            "bad.toml: mesh[0].obj: /dev/zero: is a character device"
        ),
        scene_case!(
            b"[[mesh]]\nshape = \"torus\"\n",
            "bad.toml:",
            "mesh[0].shape",
            "torus"
        ),
        scene_case!(
            b"[[mesh]]\nshape = \"sphere\"\nsegments = 2\n",
            "bad.toml: mesh[0].segments (2) must be at least 3"
        ),
        scene_case!(
            b"[[mesh]]\nshape = \"box\"\nsize = [1, -1, 1]\n",
            "bad.toml: mesh[0].size[1] (-1) must be > 0"
        ),
        scene_case!(
            b"[[mesh]]\nshape = \"box\"\nscale = 0\n",
            "bad.toml: mesh[0].scale (0) must be non-zero"
        ),
        scene_case!(
            b"[[mesh]]\nshape = \"box\"\nscale = 1e60\n",
            "bad.toml: mesh[0]:",
            "beyond ±1e40 (MAX_COORDINATE)"
        ),
        scene_case!(
            b"[[mesh]]\nshape = \"box\"\nscale = 1e-50\n",
            "bad.toml: mesh (the merged meshes) span 1e-50",
            "(MIN_EXTENT)"
        ),
        scene_case!(
            b"[[mesh]]\nshape = \"box\"\ncopies = 4294967295\nstep = [1, 0, 0]\n",
            "bad.toml: mesh[0].copies:",
            "(MAX_TRIANGLES)"
        ),
        scene_case!(
            b"[[mesh]]\nshape = \"box\"\ncopies = 2\n",
            "bad.toml: mesh[0].copies needs a `step`"
        ),
        scene_case!(
            b"[[mesh]]\nshape = \"lattice\"\nspacing = 1\nthickness = 2\n",
            "bad.toml: mesh[0]: `thickness` must be less than `spacing`, got 2"
        ),
        scene_case!(b"\nname = \"caf\xe9\"\n", "bad.toml:2: not valid UTF-8"),
        scene_case!(
            with_box!("[shadow]\ntechnique = \"bogus\"\n"),
            "bad.toml: shadow.technique",
            "bogus"
        ),
        refused(
            &["inspect", "bad.toml"],
            const { &[("bad.toml", with_box!("[shadow]\nresolution = 0\n"))] },
            &["bad.toml: shadow.resolution", "0 must lie in 1..=16384"],
        ),
        scene_case!(
            with_box!("[shadow]\nlambda = nan\n"),
            "bad.toml: shadow.lambda (NaN) must be finite"
        ),
        scene_case!(
            with_box!("[shadow]\nfilter = \"pcf:100000\"\n"),
            "bad.toml: shadow.filter",
            "1 to 64"
        ),
    ]);
}

#[test]
fn scene_paths_that_are_not_regular_files_or_too_large_are_refused() {
    let large = vec![b'#'; usize::try_from(shadowlab_scene::MAX_SCENE_FILE_BYTES).unwrap() + 1];
    let large: &'static [u8] = Box::leak(large.into_boxed_slice());
    let large_files: &'static [(&'static str, &'static [u8])] =
        Box::leak(vec![("large.toml", large)].into_boxed_slice());
    run(&[
        refused(
            &["render", "/dev/zero", "--resolution", "8", "--out", OUT],
            &[],
            &["/dev/zero: is a character device, not a regular file"],
        ),
        refused(
            &["inspect", "/dev/null"],
            &[],
            &["/dev/null: is a character device"],
        ),
        refused(
            &["render", "large.toml", "--resolution", "8", "--out", OUT],
            large_files,
            &["large.toml: larger than 4 MiB (MAX_SCENE_FILE_BYTES)"],
        ),
        refused(
            &["render", "absent.toml", "--out", OUT],
            &[],
            &["absent.toml: No such file"],
        ),
        refused(
            &["render", "indoor", "--out", OUT],
            &[],
            &["there is no built-in scene `indoor`", "outdoor"],
        ),
    ]);
}

#[test]
fn absurd_flags_name_the_flag_and_the_range() {
    run(&[
        refused(
            &["render", "--resolution", "-5", "--out", OUT],
            &[],
            &[
                "'--resolution <RESOLUTION>'",
                "\"-5\" is not a whole number in 1..=16384",
            ],
        ),
        refused(
            &["render", "--resolution", "0", "--out", OUT],
            &[],
            &["'--resolution <RESOLUTION>'", "1..=16384"],
        ),
        refused(
            &["render", "--resolution", "1e9", "--out", OUT],
            &[],
            &["'--resolution <RESOLUTION>'", "1..=16384"],
        ),
        refused(
            &["render", "--resolution", "", "--out", OUT],
            &[],
            &["'--resolution <RESOLUTION>'", "1..=16384"],
        ),
        refused(
            &["render", "--resolution", "16385", "--out", OUT],
            &[],
            &["'--resolution <RESOLUTION>'", "1..=16384"],
        ),
        refused(
            &["render", "--splits", "0", "--out", OUT],
            &[],
            &["'--partitions <PARTITIONS>'", "1..=16"],
        ),
        refused(
            &["render", "--splits", "17", "--out", OUT],
            &[],
            &["'--partitions <PARTITIONS>'", "1..=16"],
        ),
        refused(
            &["render", "--technique", "bogus", "--out", OUT],
            &[],
            &[
                "'--technique <TECHNIQUE>': unknown technique \"bogus\"",
                "known: uniform",
            ],
        ),
        refused(
            &[
                "render",
                "--technique",
                "lispsm:cad",
                "--param",
                "ogre",
                "--out",
                OUT,
            ],
            &[],
            &[
                "invalid --param",
                "already names its parameter (lispsm:cad); give one or the other",
            ],
        ),
        refused(
            &["render", "--technique", "psm:cad", "--out", OUT],
            &[],
            &[
                "'--technique <TECHNIQUE>'",
                "applies to lispsm, logarithmic, optimal, sdsm and the engines' presets only",
            ],
        ),
        refused(
            &["render", "--param", "bogus", "--out", OUT],
            &[],
            &["invalid --param: unknown parameter \"bogus\""],
        ),
        refused(
            &["render", "--lambda", "-5", "--out", OUT],
            &[],
            &["invalid --lambda", "greater than 0", "-5"],
        ),
        refused(
            &["render", "--lambda", "0", "--out", OUT],
            &[],
            &["invalid --lambda", "greater than 0"],
        ),
        refused(
            &["render", "--lambda", "nan", "--out", OUT],
            &[],
            &["invalid --lambda", "a number > 0, or inf"],
        ),
        refused(
            &["render", "--n", "-1", "--out", OUT],
            &[],
            &["invalid --n", "must be greater than 0"],
        ),
        refused(
            &["render", "--lambda", "1", "--n", "1", "--out", OUT],
            &[],
            &["--lambda", "--n"],
        ),
        refused(
            &["render", "--filter", "pcf:100000", "--out", OUT],
            &[],
            &["'--filter <FILTER>'", "from 1 to 64"],
        ),
        refused(
            &["render", "--filter", "pcf:0", "--out", OUT],
            &[],
            &["'--filter <FILTER>'", "from 1 to 64"],
        ),
        refused(
            &["render", "--filter", "-3", "--out", OUT],
            &[],
            &["'--filter <FILTER>': unknown filter \"-3\""],
        ),
        refused(
            &["render", "--filter", "disk:0,1", "--out", OUT],
            &[],
            &["'--filter <FILTER>'"],
        ),
        refused(
            &["render", "--bias", "constant:nan", "--out", OUT],
            &[],
            &["'--bias <BIAS>'", "not a finite number"],
        ),
        refused(
            &["render", "--bias", "slope:x", "--out", OUT],
            &[],
            &["'--bias <BIAS>'"],
        ),
        refused(
            &["render", "--split-scheme", "practical:2", "--out", OUT],
            &[],
            &["'--split-scheme <SPLIT_SCHEME>'", "[0, 1]"],
        ),
        refused(
            &["render", "--split-scheme", "adaptive:1", "--out", OUT],
            &[],
            &["'--split-scheme <SPLIT_SCHEME>'", "greater than 1"],
        ),
        refused(
            &["render", "--format", "f16", "--out", OUT],
            &[],
            &["'--format <FORMAT>': unknown depth format \"f16\""],
        ),
        refused(
            &["render", "--optimal-border", "-1", "--out", OUT],
            &[],
            &["'--optimal-border <FRACTION>'", "[0, 0.5)"],
        ),
        refused(
            &["render", "--optimal-border", "0.5", "--out", OUT],
            &[],
            &["'--optimal-border <FRACTION>'", "[0, 0.5)"],
        ),
        refused(
            &["render", "--optimal-iterations", "1001", "--out", OUT],
            &[],
            &["'--optimal-iterations <N>'", "0..=1000"],
        ),
        refused(
            &["render", "--optimal-readback", "0x5", "--out", OUT],
            &[],
            &["'--optimal-readback <WxH>'", "between 1 and 16384"],
        ),
        refused(
            &["analyze", "--resolutions", "0", "--out", OUT],
            &[],
            &["'--resolutions <RESOLUTIONS>'", "1..=16384"],
        ),
        refused(
            &["analyze", "--resolutions", "1e9", "--out", OUT],
            &[],
            &["'--resolutions <RESOLUTIONS>'", "1..=16384"],
        ),
        refused(
            &["analyze", "--techniques", "lispsm:n=-1", "--out", OUT],
            &[],
            &[
                "'--techniques <TECHNIQUES>'",
                "n = -1 must be greater than 0",
            ],
        ),
        refused(
            &["analyze", "--techniques", "", "--out", OUT],
            &[],
            &["'--techniques <TECHNIQUES>'"],
        ),
        refused(
            &["analyze", "--filters", "pcf:0", "--out", OUT],
            &[],
            &["'--filters <FILTERS>'", "from 1 to 64"],
        ),
        refused(
            &["temporal", "--frames", "1", "--out", OUT],
            &[],
            &["'--frames <FRAMES>'", "2..=10000"],
        ),
        refused(
            &["temporal", "--frames", "-3", "--out", OUT],
            &[],
            &["'--frames <FRAMES>'", "2..=10000"],
        ),
        refused(
            &["sweep-angle", "--eye-size", "0x5", "--out", OUT],
            &[],
            &["'--eye-size <EYE_SIZE>'", "between 1 and 16384"],
        ),
        refused(
            &["compare", "--columns", "0", "--out", "out/compare.png"],
            &[],
            &["'--columns <COLUMNS>'", "1..=16"],
        ),
        refused(
            &["compare", "--crop", "0,0,0,0", "--out", "out/compare.png"],
            &[],
            &["'--crop <CROP>'", "at least 1"],
        ),
        refused(
            &["compare", "--crop", "-1,0,5,5", "--out", "out/compare.png"],
            &[],
            &["'--crop <CROP>'", "not a whole number"],
        ),
        refused(
            &["render-mesh", "bad.obj", "--size", "-1", "--out", OUT],
            &[],
            &["'--size <SIZE>'", "1..=16384"],
        ),
        refused(
            &[
                "params", "--near", "-1", "--far", "10", "--fov", "60", "--gamma", "30",
            ],
            &[],
            &["invalid --near"],
        ),
        refused(
            &[
                "params", "--near", "nan", "--far", "10", "--fov", "60", "--gamma", "30",
            ],
            &[],
            &["invalid --near", "finite"],
        ),
        refused(
            &[
                "params", "--near", "1", "--far", "10", "--fov", "0", "--gamma", "30",
            ],
            &[],
            &["invalid --fov", "between 0 and 180"],
        ),
        refused(
            &[
                "params", "--near", "1", "--far", "10", "--fov", "60", "--gamma", "91",
            ],
            &[],
            &["invalid --gamma", "between 0 and 90"],
        ),
        refused(
            &[
                "params", "--near", "1", "--far", "10", "--fov", "60", "--gamma", "inf",
            ],
            &[],
            &["invalid --gamma"],
        ),
        refused(
            &["curves", "--figure", "bogus", "--out", OUT],
            &[],
            &["'--figure <NAME>'", "lispsm-fig6"],
        ),
        refused(&["curves", "--near", "-1", "--out", OUT], &[], &["--near"]),
        refused(
            &["render", "--bogus-flag"],
            &[],
            &["unexpected argument '--bogus-flag'"],
        ),
    ]);
}

/// Destinations shadowlab may not replace, runs beyond the memory budget, and flags that would
/// swallow the next flag: all refused before any work, naming the flag and what is wrong.
#[test]
fn outputs_memory_and_values_are_refused_before_work() {
    const BIG_IMAGE: &[u8] = b"[camera]\nposition = [0.0, 3.0, 12.0]\ntarget = [0.0, 0.0, 0.0]\n\
image = [16384, 16384]\n[[light]]\ndirection = [-0.6, -1.0, -0.2]\n[[mesh]]\nshape = \"plane\"\n\
size = [60.0, 60.0]\n";
    run(&[
        refused(
            &[
                "render",
                "--resolution",
                "16384",
                "--partitions",
                "16",
                "--out",
                OUT,
            ],
            &[],
            &[
                "16 map(s) of 16384²",
                "--resolution, --partitions",
                "--memory-budget",
            ],
        ),
        refused(
            &["analyze", "--memory-budget", "1M", "--out", OUT],
            &[],
            &[
                "above the budget of 1.0 MiB (--memory-budget)",
                "camera.image",
            ],
        ),
        refused(
            &[
                "analyze",
                "big.toml",
                "--techniques",
                "uniform",
                "--out",
                OUT,
            ],
            &[("big.toml", BIG_IMAGE)],
            &["16384x16384 eye image", "camera.image", "--memory-budget"],
        ),
        refused(
            &["compare", "big.toml", "--out", "out/c.png"],
            &[("big.toml", BIG_IMAGE)],
            &["16384x16384 eye image", "camera.image"],
        ),
        refused(
            &["render", "--memory-budget", "1Q", "--out", OUT],
            &[],
            &["'--memory-budget <SIZE>'", "K, M, G or T"],
        ),
        refused(
            &["analyze", "--memory-budget", "-5", "--out", OUT],
            &[],
            &["'--memory-budget <SIZE>'", "not a size"],
        ),
        refused(
            &["temporal", "--memory-budget", "0", "--out", OUT],
            &[],
            &["'--memory-budget <SIZE>'", "out of range"],
        ),
        refused(
            &["analyze", "--timing-runs", "0", "--out", OUT],
            &[],
            &["'--timing-runs <N>'", "1..=100"],
        ),
        refused(
            &["analyze", "--timing-runs", "101", "--out", OUT],
            &[],
            &["'--timing-runs <N>'", "1..=100"],
        ),
        refused(
            &["render", "--technique", "--resolution", "5", "--out", OUT],
            &[],
            &[
                "'--technique <TECHNIQUE>'",
                "`--resolution` is a flag, not a value",
            ],
        ),
        refused(
            &["analyze", "--filters", "--out", OUT],
            &[],
            &["'--filters <FILTERS>'", "is a flag, not a value"],
        ),
        refused(
            &["analyze", "--out", "/dev/null"],
            &[],
            &["invalid --out", "/dev/null is a character device"],
        ),
        refused(
            &["analyze", "--out", "/dev/full"],
            &[],
            &["invalid --out", "a character device"],
        ),
        refused(
            &["compare", "--out", "/dev/null"],
            &[],
            &["invalid --out", "shadowlab replaces only regular files"],
        ),
        refused(
            &["compare", "--out", "{dir}"],
            &[],
            &[
                "invalid --out",
                "is a directory; give a file name inside it",
            ],
        ),
        refused(
            &["analyze", "--out", "{dir}/notes.txt"],
            &[("notes.txt", b"mine")],
            &["invalid --out", "notes.txt is a regular file"],
        ),
        refused(
            &["curves", "--out", "{dir}/notes.txt/figures"],
            &[("notes.txt", b"mine")],
            &[
                "invalid --out",
                "notes.txt is a regular file, not a directory",
            ],
        ),
        refused(
            &["render-mesh", "m.obj", "--out", "{dir}"],
            &[("m.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")],
            &[
                "invalid --out",
                "not a shadowlab output set",
                "manifest.json",
            ],
        ),
        refused(
            &["analyze", "--out", "/"],
            &[],
            &["invalid --out", "does not end in a name"],
        ),
        refused(
            &["sweep-angle", "--out", "{dir}/.."],
            &[],
            &["invalid --out", "does not end in a name"],
        ),
    ]);
}
