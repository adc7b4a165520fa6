//! `report.html` in a real browser (headless Chromium): a small study's report loads from a
//! `file://` URL with no console message and no problem recorded by its self-check, every picture
//! it names loads, its tables sort, its pictures switch technique with the crop kept, names from
//! input are shown as text, and a screenshot is a real picture.
//!
//! Where Chromium is absent the test says so on standard error and passes, unless
//! `SHADOWLAB_REQUIRE_BROWSER=1` (set by `.ci/run`, which installs Debian's `chromium`): then it
//! fails. `SHADOWLAB_CHROMIUM` names the browser binary if it is not `chromium` on the `PATH`.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use shadowlab_analysis::report::{Report, report};
use shadowlab_analysis::study::{self, Study, StudyOptions};
use shadowlab_raster::DepthFormat;
use shadowlab_shadow::{Bias, Filter, FocusPolicy, Splits, Technique};

/// A scene name with every character HTML must escape.
const HOSTILE_NAME: &str = "outdoor <b>&amp;</b> \"quoted\" 'x' </script>";

/// How long one browser run may take before the test gives up on it.
const BROWSER_DEADLINE: Duration = Duration::from_secs(180);

/// The built-in outdoor scene at 240 × 180, two techniques at 128² and 256², pictures at 256².
fn small_study() -> Study {
    let mut scene = shadowlab_scene::builtin_scene("outdoor").expect("the built-in scene");
    scene.name = HOSTILE_NAME.into();
    (scene.camera.width, scene.camera.height) = (240, 180);
    let options = StudyOptions {
        techniques: vec![
            Technique::Uniform,
            Technique::parse("lispsm", None).unwrap(),
        ],
        resolutions: vec![128, 256],
        partitions: vec![1],
        splits: Splits::Uniform,
        filters: vec![Filter::Nearest],
        bias: Bias::DEFAULT,
        format: DepthFormat::F32,
        map_truth: false,
        pictures_at: Some(256),
        optimal: shadowlab_shadow::optimal::OptimalOptions::default(),
        focus: FocusPolicy::Light,
        timing_runs: 1,
    };
    study::run(&scene, &options, |_, _, _| {}).expect("the study")
}

/// Writes every file of `report` under `dir`.
fn write_set(dir: &Path, report: Report) {
    for (path, bytes) in report.files() {
        let file = dir.join(path);
        std::fs::create_dir_all(file.parent().unwrap()).unwrap();
        std::fs::write(file, bytes).unwrap();
    }
}

/// The browser, or `None` (said on standard error; a failure if the browser is required).
fn chromium() -> Option<PathBuf> {
    if let Some(path) = std::env::var_os("SHADOWLAB_CHROMIUM") {
        return Some(PathBuf::from(path));
    }
    let found = std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|dir| dir.join("chromium"))
            .find(|candidate| candidate.is_file())
    });
    if found.is_none() {
        let required = std::env::var("SHADOWLAB_REQUIRE_BROWSER").is_ok_and(|v| v == "1");
        assert!(
            !required,
            "SHADOWLAB_REQUIRE_BROWSER=1 but no `chromium` on the PATH (apt-get install chromium, \
             or set SHADOWLAB_CHROMIUM)"
        );
        // Straight to the process's standard error, past the test harness's capture.
        let _ = writeln!(
            std::io::stderr(),
            "\n*** SKIPPED report_html: no `chromium` on the PATH, so report.html was NOT tested in \
             a browser (apt-get install chromium; SHADOWLAB_REQUIRE_BROWSER=1 makes this a \
             failure) ***\n"
        );
    }
    found
}

/// Runs headless Chromium on `url` with `args`, a fresh profile and no network, and returns its
/// output; panics if it runs past [`BROWSER_DEADLINE`] or fails.
fn run_browser(browser: &Path, args: &[String], url: &str) -> Output {
    let profile = tempfile::tempdir().unwrap();
    let mut child = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--enable-logging=stderr",
            "--v=0",
            "--virtual-time-budget=10000",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .args(args)
        .arg(url)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("chromium starts");
    // Read both pipes while waiting, so a full pipe cannot stall the browser.
    let stdout = child.stdout.take().unwrap();
    let stderr = child.stderr.take().unwrap();
    let read = |mut pipe: Box<dyn std::io::Read + Send>| {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            pipe.read_to_end(&mut bytes).map(|_| bytes)
        })
    };
    let (out, err) = (read(Box::new(stdout)), read(Box::new(stderr)));
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > BROWSER_DEADLINE {
            child.kill().unwrap();
            child.wait().unwrap();
            panic!("chromium ran past {BROWSER_DEADLINE:?} on {url}");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let output = Output {
        status,
        stdout: out.join().unwrap().unwrap(),
        stderr: err.join().unwrap().unwrap(),
    };
    assert!(
        output.status.success(),
        "chromium failed on {url}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

/// The console messages in Chromium's log (`--enable-logging=stderr`): lines of its `CONSOLE`
/// source, whatever their level.
fn console_messages(stderr: &[u8]) -> Vec<String> {
    String::from_utf8_lossy(stderr)
        .lines()
        .filter(|line| line.contains(":CONSOLE"))
        .map(str::to_owned)
        .collect()
}

/// The value of attribute `name` on the dumped `<html>` element, unescaped.
fn root_attribute(dom: &str, name: &str) -> Option<String> {
    let start = dom.find("<html")?;
    let tag = &dom[start..start + dom[start..].find('>')?];
    let key = format!(" {name}=\"");
    let value_start = tag.find(&key)? + key.len();
    let value = &tag[value_start..value_start + tag[value_start..].find('"')?];
    Some(
        value
            .replace("&quot;", "\"")
            .replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&#39;", "'")
            .replace("&nbsp;", "\u{a0}")
            .replace("&amp;", "&"),
    )
}

/// Every picture path `html` names (in attributes and in its data).
fn named_pictures(html: &str) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for folder in ["images/", "pictures/"] {
        let mut rest = html;
        while let Some(at) = rest.find(folder) {
            let tail = &rest[at..];
            let end = tail.find(".png").map(|e| e + 4);
            if let Some(end) = end {
                let name = &tail[..end];
                if !name.contains(['"', '<', ' ']) && !names.iter().any(|n| n == name) {
                    names.push(name.to_owned());
                }
            }
            rest = &rest[at + folder.len()..];
        }
    }
    names
}

/// Clicks through the page (sorting, zoom, a click on a picture, the second technique) and
/// records what it saw in `data-test` on `<html>`; run after the page's own script.
const INTERACTIONS: &str = r#"<script>
(function () {
  var out = {};
  try {
    var table = document.querySelector('table.sortable');
    var column = function (k) {
      return Array.prototype.map.call(table.tBodies[0].rows, function (r) { return r.cells[k].textContent; });
    };
    var resolution = table.tHead.rows[0].cells[0];
    resolution.click();
    resolution.click();
    out.resolutionsDescending = column(0);
    table.tHead.rows[0].cells[1].click();
    out.firstTechniqueAscending = column(1);
    out.ariaSort = table.tHead.rows[0].cells[1].getAttribute('aria-sort');
    var zoom = document.getElementById('zoom');
    zoom.value = '4';
    zoom.dispatchEvent(new Event('change'));
    var crop = document.querySelector('.crop');
    var box = crop.getBoundingClientRect();
    crop.dispatchEvent(new MouseEvent('click', {
      bubbles: true, clientX: box.left + 0.25 * box.width, clientY: box.top + 0.75 * box.height
    }));
    var state = function () {
      return ['eye', 'difference', 'difference-causes', 'heatmap'].map(function (kind) {
        var image = document.getElementById('picture-' + kind);
        return [image.getAttribute('src'), image.style.width, image.style.left, image.style.top];
      });
    };
    var panels = document.getElementById('panels');
    out.before = state();
    out.cropBefore = panels.getAttribute('data-crop');
    document.querySelectorAll('.techniques button')[1].click();
    out.after = state();
    out.cropAfter = panels.getAttribute('data-crop');
    out.technique = panels.getAttribute('data-technique');
    out.heading = document.querySelector('h1').textContent;
    out.title = document.title;
    out.pressed = Array.prototype.map.call(document.querySelectorAll('.techniques button'), function (b) {
      return b.getAttribute('aria-pressed');
    });
  } catch (error) {
    out.error = String(error);
  }
  document.documentElement.setAttribute('data-test', JSON.stringify(out));
})();
</script>
"#;

/// Claim: the report of a small study works in a real browser — see the module docs.
#[test]
fn report_html_works_in_a_browser() {
    let Some(browser) = chromium() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    write_set(dir.path(), report(&small_study()).unwrap());
    let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();

    // Nothing from outside: no URL with a scheme, nothing in the page loads from elsewhere.
    for needle in ["http://", "https://", "//cdn", "@import", "url(http"] {
        let allowed = "http://www.w3.org/2000/svg";
        assert!(
            html.replace(allowed, "").find(needle).is_none(),
            "report.html refers to {needle}"
        );
    }
    // The name from input appears only escaped.
    assert!(
        !html.contains("<b>&amp;</b>"),
        "the scene name is not escaped"
    );
    assert!(
        !html.contains(HOSTILE_NAME),
        "the scene name is not escaped"
    );
    let named = named_pictures(&html);
    // Two techniques, four pictures each, raw and annotated.
    assert_eq!(named.len(), 2 * 8, "{named:?}");
    for name in &named {
        assert!(
            dir.path().join(name).is_file(),
            "{name} is named but missing"
        );
    }

    // The page's own checks and the interactions, in a copy beside it (same relative paths).
    let check = dir.path().join("check.html");
    std::fs::write(
        &check,
        html.replace("</body>", &format!("{INTERACTIONS}</body>")),
    )
    .unwrap();
    let url = format!("file://{}", check.display());
    let output = run_browser(&browser, &["--dump-dom".to_owned()], &url);
    let dom = String::from_utf8(output.stdout).unwrap();
    let messages = console_messages(&output.stderr);
    assert!(messages.is_empty(), "console messages: {messages:#?}");
    let attribute = |name: &str| {
        root_attribute(&dom, name).unwrap_or_else(|| panic!("no {name} on <html> in {dom}"))
    };
    assert_eq!(attribute("data-ready"), "true");
    assert_eq!(attribute("data-problems"), "");
    assert_eq!(attribute("data-pictures-named"), named.len().to_string());
    assert_eq!(attribute("data-pictures-loaded"), named.len().to_string());

    let test: serde_json::Value = serde_json::from_str(&attribute("data-test")).unwrap();
    assert!(test.get("error").is_none(), "{test:#}");
    assert_eq!(
        test["resolutionsDescending"],
        serde_json::json!(["256", "128"])
    );
    let counts: Vec<f64> = test["firstTechniqueAscending"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| {
            let text = c.as_str().unwrap();
            text.split(' ').next().unwrap().parse().unwrap()
        })
        .collect();
    assert!(counts.windows(2).all(|w| w[0] <= w[1]), "{counts:?}");
    assert_eq!(test["ariaSort"], "ascending");
    // Zoom 4, a click at (¼, ¾) of the centred crop: centre (0.4375, 0.5625), offsets 1.25 and
    // 1.75 crop widths (to within the event's whole-pixel coordinates).
    let crop: Vec<f64> = test["cropBefore"]
        .as_str()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    assert!(
        (crop[0] - 0.4375).abs() < 0.005 && (crop[1] - 0.5625).abs() < 0.005 && crop[2] == 4.0,
        "{crop:?}"
    );
    assert_eq!(
        test["cropAfter"], test["cropBefore"],
        "the crop changed with the technique"
    );
    let percent = |v: &serde_json::Value| -> f64 {
        v.as_str().unwrap().trim_end_matches('%').parse().unwrap()
    };
    let kinds = ["eye", "difference", "difference-causes", "heatmap"];
    for (k, kind) in kinds.iter().enumerate() {
        let before = &test["before"][k];
        let after = &test["after"][k];
        assert_eq!(before[0], format!("images/{kind}-uniform.png"));
        assert_eq!(after[0], format!("images/{kind}-lispsm.png"));
        assert_eq!(before[1], "400%");
        assert!((percent(&before[2]) + 125.0).abs() < 2.0, "{before}");
        assert!((percent(&before[3]) + 175.0).abs() < 2.0, "{before}");
        for part in 1..4 {
            assert_eq!(before[part], after[part], "{kind}: the crop changed");
        }
    }
    assert_eq!(test["technique"], "lispsm");
    assert_eq!(test["pressed"], serde_json::json!(["false", "true"]));
    assert!(
        test["heading"].as_str().unwrap().contains(HOSTILE_NAME),
        "{}",
        test["heading"]
    );
    assert!(test["title"].as_str().unwrap().contains(HOSTILE_NAME));

    // A screenshot of the report itself: a PNG of the window's size, with the pictures' colours.
    let shot = dir.path().join("screenshot.png");
    let url = format!("file://{}", dir.path().join("report.html").display());
    let output = run_browser(
        &browser,
        &[
            format!("--screenshot={}", shot.display()),
            "--window-size=1280,2400".to_owned(),
        ],
        &url,
    );
    let messages = console_messages(&output.stderr);
    assert!(messages.is_empty(), "console messages: {messages:#?}");
    let png = std::fs::read(&shot).expect("the screenshot");
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"), "not a PNG");
    let pixmap = tiny_skia::Pixmap::decode_png(&png).expect("a PNG that decodes");
    assert_eq!((pixmap.width(), pixmap.height()), (1280, 2400));
    let mut colours: Vec<u32> = pixmap
        .pixels()
        .iter()
        .map(|p| {
            let c = p.demultiply();
            u32::from_be_bytes([c.red(), c.green(), c.blue(), 0])
        })
        .collect();
    colours.sort_unstable();
    colours.dedup();
    assert!(
        colours.len() > 200,
        "the screenshot has {} colours: an empty page?",
        colours.len()
    );
}
