//! `--export`: every per-pixel result out, and each agrees with what the report counts — the
//! classes sum to the misclassified pixels, the truth to the visible pixels, the footprints to
//! their statistics — and `render` and `analyze` export the same eye pass and the same maps.

use std::fs;
use std::path::Path;

use crate::support::{shadowlab, stderr};

/// A small scene: a plane and a box under a sun and a spot, 96 × 64 pixels.
fn scene_file(dir: &Path) -> String {
    let path = dir.join("small.toml");
    fs::write(
        &path,
        "[camera]\nposition = [0.0, 3.0, 12.0]\ntarget = [0.0, 0.0, -10.0]\nimage = [96, 64]\n\
         far = 60.0\n\
         [[light]]\ndirection = [-0.6, -1.0, -0.2]\n\
         [[light]]\nkind = \"spot\"\nposition = [4.0, 8.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\n\
         cone = 50.0\n\
         [[mesh]]\nshape = \"plane\"\nsize = [60.0, 60.0]\n\
         [[mesh]]\nshape = \"box\"\nsize = [2.0, 2.0, 2.0]\ntranslate = [0.0, 1.0, 0.0]\n",
    )
    .unwrap();
    path.display().to_string()
}

/// A NumPy array as written by shadowlab: its type descriptor, shape and raw little-endian data.
struct Npy {
    descr: String,
    shape: Vec<usize>,
    data: Vec<u8>,
}

fn read_npy(path: &Path) -> Npy {
    let bytes = fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00", "{}", path.display());
    let header_len = usize::from(u16::from_le_bytes([bytes[8], bytes[9]]));
    let header = std::str::from_utf8(&bytes[10..10 + header_len]).unwrap();
    let field = |key: &str| {
        let start = header.find(key).unwrap() + key.len();
        header[start..].trim_start_matches([' ', ':']).to_string()
    };
    let descr = field("'descr'")[1..5].trim_end_matches('\'').to_string();
    let shape_text = field("'shape'");
    let shape = shape_text[1..shape_text.find(')').unwrap()]
        .split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|s| s.trim().parse().unwrap())
        .collect();
    Npy {
        descr,
        shape,
        data: bytes[10 + header_len..].to_vec(),
    }
}

impl Npy {
    fn f32s(&self) -> Vec<f32> {
        assert_eq!(self.descr, "<f4");
        self.data
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
            .collect()
    }
}

#[test]
fn exports_agree_with_the_report_and_across_commands() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_file(dir.path());
    let analyzed = dir.path().join("analyze");
    let output = shadowlab(
        &[
            "analyze",
            &scene,
            "--techniques",
            "uniform,lispsm",
            "--resolutions",
            "128",
            "--partitions",
            "1,2",
            "--timing-runs",
            "1",
            "--export",
            "--out",
            analyzed.to_str().unwrap(),
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let results: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(analyzed.join("results.json")).unwrap()).unwrap();
    let export = analyzed.join("export");
    // Every file the index lists is there, and results.json lists the same files.
    let index: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(export.join("index.json")).unwrap()).unwrap();
    assert_eq!(index["files"], results["exports"]);
    for entry in index["files"].as_array().unwrap() {
        let file = entry["file"].as_str().unwrap();
        assert!(analyzed.join(file).is_file(), "{file} listed, not written");
    }
    // The truth: judged or outside the cone exactly where a surface is visible.
    let visible = results["visible"].as_u64().unwrap();
    for light in 0..2 {
        let truth = read_npy(&export.join(format!("truth-light{light}.npy")));
        assert_eq!(
            (truth.descr.as_str(), &truth.shape[..]),
            ("|u1", &[64, 96][..])
        );
        let seen = truth.data.iter().filter(|&&c| c != 255).count() as u64;
        assert_eq!(seen, visible, "light {light}");
    }
    let triangles = read_npy(&export.join("eye-triangle.npy"));
    let hits = triangles
        .data
        .chunks_exact(4)
        .filter(|c| u32::from_le_bytes((*c).try_into().unwrap()) != u32::MAX)
        .count() as u64;
    assert_eq!(hits, visible);
    let positions = read_npy(&export.join("eye-position.npy"));
    assert_eq!(
        (positions.descr.as_str(), &positions.shape[..]),
        ("<f8", &[64, 96, 3][..])
    );
    // Per combination: the classes count what the report counts, summed over the lights.
    let measurements = results["measurements"].as_array().unwrap();
    assert_eq!(measurements.len(), 4);
    for m in measurements {
        let setting = &m["setting"];
        let combination = format!(
            "{}-128-{}p-nearest",
            setting["technique"].as_str().unwrap(),
            setting["maps"]
        );
        let base = export.join(&combination);
        let (mut falsely_lit, mut falsely_shadowed) = (0, 0);
        for light in 0..2 {
            let classes = read_npy(&base.join(format!("class-light{light}.npy")));
            falsely_lit += classes.data.iter().filter(|&&c| c == 1).count() as u64;
            falsely_shadowed += classes.data.iter().filter(|&&c| c == 2).count() as u64;
        }
        assert_eq!(
            falsely_lit,
            m["falsely_lit"].as_u64().unwrap(),
            "{combination}"
        );
        assert_eq!(
            falsely_shadowed,
            m["falsely_shadowed"].as_u64().unwrap(),
            "{combination}"
        );
        // The footprints' largest value is the report's, to f32 precision.
        let footprint = read_npy(&base.join("footprint.npy")).f32s();
        let largest = footprint
            .chunks_exact(3)
            .map(|f| f64::from(f[0]))
            .filter(|f| !f.is_nan())
            .fold(0.0, f64::max);
        let reported = m["footprint"]["total"]["max"].as_f64().unwrap();
        assert!(
            (largest - reported).abs() <= reported * 1e-6,
            "{largest} vs {reported}"
        );
        let maps = setting["maps"].as_u64().unwrap();
        for part in 0..maps {
            let map = read_npy(&base.join(format!("map-light0-part{part}.npy")));
            assert_eq!(map.shape, [128, 128]);
            assert!(map.f32s().iter().all(|z| (0.0..=1.0).contains(z)));
        }
    }
    // `render --export` of one combination writes the same eye pass, truth and maps, bit for bit.
    let rendered = dir.path().join("render");
    let output = shadowlab(
        &[
            "render",
            &scene,
            "--technique",
            "lispsm",
            "--resolution",
            "128",
            "--partitions",
            "2",
            "--export",
            "--out",
            rendered.to_str().unwrap(),
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let same = |relative: &str| {
        assert_eq!(
            fs::read(rendered.join("export").join(relative)).unwrap(),
            fs::read(export.join(relative)).unwrap(),
            "{relative}"
        );
    };
    for file in [
        "eye.exr",
        "eye-depth.npy",
        "eye-normal.npy",
        "truth-light0.npy",
        "truth-light1.npy",
        "lispsm-128-2p-nearest/map-light0-part1.npy",
        "lispsm-128-2p-nearest/class-light1.npy",
        "lispsm-128-2p-nearest/footprint.exr",
    ] {
        same(file);
    }
}

#[test]
fn without_export_nothing_is_exported() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_file(dir.path());
    let out = dir.path().join("render");
    let output = shadowlab(
        &[
            "render",
            &scene,
            "--resolution",
            "64",
            "--out",
            out.to_str().unwrap(),
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(!out.join("export").exists());
}

/// `inspect --setup-json` writes a set-up that `evaluate` measures exactly as `analyze` measures
/// the technique: the same misclassified pixels and footprints (timings aside); and
/// `--export` writes the same set-up beside the per-pixel results, with the scene as glTF and OBJ.
#[test]
fn evaluate_of_a_written_set_up_is_analyze() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_file(dir.path());
    let setup = dir.path().join("setup.json");
    for technique in ["lispsm", "psm"] {
        let output = shadowlab(
            &[
                "inspect",
                &scene,
                "--technique",
                technique,
                "--resolution",
                "128",
                "--partitions",
                "2",
                "--setup-json",
                setup.to_str().unwrap(),
            ],
            None,
        );
        assert!(output.status.success(), "{}", stderr(&output));
        let evaluated = dir.path().join(format!("evaluate-{technique}"));
        let output = shadowlab(
            &[
                "evaluate",
                &scene,
                "--setup",
                setup.to_str().unwrap(),
                "--out",
                evaluated.to_str().unwrap(),
            ],
            None,
        );
        assert!(output.status.success(), "{}", stderr(&output));
        let analyzed = dir.path().join(format!("analyze-{technique}"));
        let output = shadowlab(
            &[
                "analyze",
                &scene,
                "--techniques",
                technique,
                "--resolutions",
                "128",
                "--partitions",
                "2",
                "--timing-runs",
                "1",
                "--export",
                "--out",
                analyzed.to_str().unwrap(),
            ],
            None,
        );
        assert!(output.status.success(), "{}", stderr(&output));
        let results = |dir: &Path| -> serde_json::Value {
            serde_json::from_str(&fs::read_to_string(dir.join("results.json")).unwrap()).unwrap()
        };
        let (e, a) = (results(&evaluated), results(&analyzed));
        let (e, a) = (&e["measurements"][0], &a["measurements"][0]);
        for key in [
            "misclassified",
            "falsely_lit",
            "falsely_shadowed",
            "footprint",
        ] {
            assert_eq!(e[key], a[key], "{technique}: {key}");
        }
        // The export holds the same set-up and the scene.
        let export = analyzed.join("export");
        assert_eq!(
            fs::read_to_string(export.join(format!("{technique}-128-2p-nearest/setup.json")))
                .unwrap(),
            fs::read_to_string(&setup).unwrap()
        );
        assert!(
            fs::read(export.join("scene.glb"))
                .unwrap()
                .starts_with(b"glTF")
        );
        assert!(
            fs::read_to_string(export.join("scene.obj"))
                .unwrap()
                .contains("\nv ")
        );
    }
    // The logarithmic map is not a matrix per partition: refused, naming the flag.
    let output = shadowlab(
        &[
            "inspect",
            &scene,
            "--technique",
            "logarithmic",
            "--setup-json",
            setup.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("--setup-json"),
        "{}",
        stderr(&output)
    );
}
