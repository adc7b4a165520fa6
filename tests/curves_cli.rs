use std::fs;
use std::path::Path;

use crate::support::{shadowlab, stderr, stdout};

const FIGURES: [&str; 6] = [
    "lispsm-fig6",
    "cad-fig7",
    "gmnpr-fig5",
    "gmnpr-fig6",
    "partitions",
    "max-error-vs-angle",
];

fn read(dir: &Path, file: &str) -> Vec<u8> {
    fs::read(dir.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"))
}

#[test]
fn every_figure_is_written_and_repeats_byte_for_byte() {
    let first = tempfile::tempdir().unwrap();
    let second = tempfile::tempdir().unwrap();
    for dir in [first.path(), second.path()] {
        let output = shadowlab(&["curves", "--out", dir.to_str().unwrap()], None);
        assert!(output.status.success(), "{}", stderr(&output));
        assert_eq!(stdout(&output).lines().count(), 3 * FIGURES.len());
    }
    for figure in FIGURES {
        for ext in ["csv", "svg", "png"] {
            let file = format!("{figure}.{ext}");
            let a = read(first.path(), &file);
            assert!(!a.is_empty(), "{file} is empty");
            assert!(
                a == read(second.path(), &file),
                "{file} differs between runs"
            );
        }
        let png = read(first.path(), &format!("{figure}.png"));
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{figure}.png is not a PNG");
        let svg = String::from_utf8(read(first.path(), &format!("{figure}.svg"))).unwrap();
        assert!(
            svg.starts_with("<svg"),
            "{figure}.svg is not an SVG document"
        );
        assert!(
            svg.contains("n = 1") || svg.contains("zn = 1"),
            "{figure}: the title states the configuration"
        );
    }
    let leftovers: Vec<_> = fs::read_dir(first.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(
        leftovers.len(),
        // Each figure's CSV, SVG and PNG, and the set's manifest.
        3 * FIGURES.len() + 1,
        "temporary files left: {leftovers:?}"
    );
}

#[test]
fn the_lispsm_table_holds_the_papers_values() {
    let dir = tempfile::tempdir().unwrap();
    let output = shadowlab(
        &[
            "curves",
            "--figure",
            "lispsm-fig6",
            "--out",
            dir.path().to_str().unwrap(),
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let csv = String::from_utf8(read(dir.path(), "lispsm-fig6.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("z,uniform,psm,lispsm_n_opt,logarithmic"));
    let first: Vec<f64> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    // z = zn: uniform (zf − zn)/zn = 99, PSM (zf − zn)/zf = 0.99, LiSPSM 9.9, log ln 100.
    assert_eq!(first[0], 1.0);
    assert_eq!(first[1], 99.0);
    assert!((first[2] - 0.99).abs() < 1e-15);
    assert!((first[3] - 9.9).abs() < 1e-12);
    assert!((first[4] - 100f64.ln()).abs() < 1e-14);
    assert_eq!(csv.lines().count(), 1 + 1001);
    // CSV, SVG, PNG and the manifest.
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 4);
}

#[test]
fn the_configuration_can_be_changed() {
    let dir = tempfile::tempdir().unwrap();
    let output = shadowlab(
        &[
            "curves",
            "--figure",
            "max-error-vs-angle",
            "--far",
            "800",
            "--out",
            dir.path().to_str().unwrap(),
        ],
        None,
    );
    assert!(output.status.success(), "{}", stderr(&output));
    let svg = String::from_utf8(read(dir.path(), "max-error-vs-angle.svg")).unwrap();
    assert!(svg.contains("f = 800"));
}

#[test]
fn bad_input_exits_2_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("figures");
    let out = out.to_str().unwrap();
    let output = shadowlab(&["curves", "--figure", "fig99", "--out", out], None);
    assert_eq!(output.status.code(), Some(2));
    assert!(
        stderr(&output).contains("lispsm-fig6"),
        "the message lists the figures"
    );
    let output = shadowlab(&["curves", "--far", "0.5", "--out", out], None);
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("--far"));
    assert!(
        !Path::new(out).exists(),
        "nothing may be written on bad input"
    );
    let file = dir.path().join("a-file");
    fs::write(&file, "x").unwrap();
    let output = shadowlab(
        &[
            "curves",
            "--figure",
            "partitions",
            "--out",
            file.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("--out"));
}
