//! `report.html`: the report as one self-contained page, beside `report.md`.
//!
//! The page needs nothing from a network: its style and scripts are inline, the Pareto plot and
//! the view-axis plot are inline SVG (the very SVG of `pareto.svg` and `view-axis.svg`), and the
//! pictures are the raw ones of the output set, referenced by relative path (`images/…`), so the
//! page works from the output directory as it is (or a copy of it), over `file://`.
//!
//! It holds the same document as `report.md` ([`crate::document`]: every table, every sentence),
//! with two additions:
//! - **sortable tables**: clicking a column's header (or Enter on it) sorts the rows by it,
//!   numbers by value (a cell's leading number: `568 (5.79 %)` sorts as 568), others as text,
//!   empty cells (`—`) last; again to reverse.
//! - **the pictures**: for each technique pictured, the eye view, the difference image, its
//!   causes and the heat map side by side, with the legends of the difference image and of its
//!   causes (each class's colour and pixel count) and the heat map's colour bar (quantity, unit, log scale, range, and ▼ at the least
//!   and greatest value of the picture). A technique is chosen with its button; the crop — a zoom
//!   factor and a centre, set by clicking a picture (or the arrow keys on it) — stays when the
//!   technique changes, so the same part of the view is compared. Links open the annotated PNGs.
//!
//! Everything that comes from input (the scene's name, technique specs, reasons) is HTML-escaped;
//! the pictures' data is JSON inside a `<script type="application/json">` with `<`, `>` and `&`
//! escaped as `\u003c` …, so no name can close the element.
//!
//! # Self-check
//! A script in the head records every error on the page — a script error, an element that fails
//! to load — and the page loads every picture it names (raw and annotated) once: the results go
//! into attributes of `<html>` (`data-pictures-named`, `data-pictures-loaded`: those that
//! loaded with a width, `data-problems`: one line per problem, `data-ready` once all have
//! settled) and, if anything failed, into a visible notice at the top. The browser test reads
//! them (crates/analysis/tests/analysis/report_html.rs).

use std::fmt::Write as _;

use serde_json::json;

use crate::classify::{BACKGROUND, CORRECT_LIT, CORRECT_SHADOW, FALSELY_LIT, FALSELY_SHADOWED};
use crate::document::{self, Block, escape_html};
use crate::images::{CauseCounts, ClassCounts, HeatScale, NO_VALUE, NO_VALUE_MEANING, VIRIDIS};
use crate::labels::{filter_label, technique_label};
use crate::pictures::{self, PictureKind};
use crate::study::Study;

/// The page's style.
const STYLE: &str = r#"
:root { color-scheme: light; --ink: #1e1e1e; --muted: #5a5a5a; --rule: #d0d0d0; --accent: #0072b2; }
body { font-family: "DejaVu Sans", system-ui, sans-serif; color: var(--ink); margin: 0; line-height: 1.45; }
main { max-width: 1500px; margin: 0 auto; padding: 1em 1.5em 3em; }
h1 { font-size: 1.6em; } h2 { font-size: 1.3em; margin-top: 2em; border-bottom: 1px solid var(--rule); }
h3 { font-size: 1.05em; margin-top: 1.6em; }
code { font-family: "DejaVu Sans Mono", ui-monospace, monospace; font-size: 0.92em; background: #f3f3f3; padding: 0 0.2em; }
.table { overflow-x: auto; }
table { border-collapse: collapse; margin: 0.6em 0; font-size: 0.92em; }
th, td { border: 1px solid var(--rule); padding: 0.25em 0.6em; text-align: left; white-space: nowrap; }
th.num, td.num { text-align: right; }
thead th { background: #f1f4f8; cursor: pointer; user-select: none; }
thead th:hover, thead th:focus { background: #dde7f3; outline: none; }
thead th[aria-sort="ascending"]::after { content: " ▲"; color: var(--accent); }
thead th[aria-sort="descending"]::after { content: " ▼"; color: var(--accent); }
tbody tr:nth-child(even) { background: #fafafa; }
figure.plot { margin: 1em 0; } figure.plot svg { max-width: 100%; height: auto; display: block; }
#problems { border: 2px solid #d55e00; background: #fff3eb; padding: 0.5em 1em; }
.controls { display: flex; flex-wrap: wrap; gap: 0.6em 1.5em; align-items: center; margin: 0.8em 0; }
.techniques button { font: inherit; padding: 0.2em 0.7em; margin: 0.1em; border: 1px solid #888; background: #fff; border-radius: 3px; cursor: pointer; }
.techniques button[aria-pressed="true"] { background: var(--accent); color: #fff; border-color: var(--accent); }
.panels { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }
.panel { flex: 1 1 300px; margin: 0; min-width: 0; }
.panel figcaption { font-weight: bold; margin-bottom: 0.3em; }
.crop { position: relative; overflow: hidden; width: 100%; border: 1px solid #999; cursor: zoom-in; background: #000; }
.crop:focus { outline: 2px solid var(--accent); }
.crop img { position: absolute; left: 0; top: 0; width: 100%; height: auto; max-width: none; image-rendering: pixelated; }
.key { font-size: 0.88em; color: var(--muted); margin: 0.4em 0; }
.swatches { list-style: none; padding: 0; margin: 0.4em 0; font-size: 0.88em; }
.swatches li { margin: 0.15em 0; }
.swatch { display: inline-block; width: 0.95em; height: 0.95em; border: 1px solid #777; vertical-align: -0.12em; margin-right: 0.4em; }
svg.colourbar { display: block; max-width: 100%; height: auto; }
#settings { color: var(--muted); }
"#;

/// Recorded before anything loads: errors of scripts and of elements (images) that fail to load.
const HEAD_SCRIPT: &str = r#"
(function () {
  'use strict';
  var root = document.documentElement;
  var problems = [];
  window.reportProblem = function (problem) {
    problems.push(problem);
    root.setAttribute('data-problems', problems.join('\n'));
    var box = document.getElementById('problems');
    if (box) {
      box.hidden = false;
      var item = document.createElement('li');
      item.textContent = problem;
      box.querySelector('ul').appendChild(item);
    }
  };
  window.reportProblems = problems;
  root.setAttribute('data-problems', '');
  window.addEventListener('error', function (event) {
    var target = event.target;
    if (target && target !== window && target.getAttribute) {
      window.reportProblem('cannot load ' + (target.getAttribute('src') || target.tagName));
    } else {
      window.reportProblem('script error: ' + event.message);
    }
  }, true);
  window.addEventListener('unhandledrejection', function (event) {
    window.reportProblem('script error: ' + event.reason);
  });
})();
"#;

/// Sorting, the pictures' viewer and the self-check.
const BODY_SCRIPT: &str = r#"
(function () {
  'use strict';
  var root = document.documentElement;
  var box = document.getElementById('problems');
  window.reportProblems.forEach(function (problem) {
    box.hidden = false;
    var item = document.createElement('li');
    item.textContent = problem;
    box.querySelector('ul').appendChild(item);
  });

  // Sortable tables: numbers by value (the cell's leading number), text as text, empty last.
  function number(cell) {
    var value = parseFloat(cell.textContent);
    return isFinite(value) ? value : null;
  }
  Array.prototype.forEach.call(document.querySelectorAll('table.sortable'), function (table) {
    var heads = table.tHead.rows[0].cells;
    var body = table.tBodies[0];
    Array.prototype.forEach.call(body.rows, function (row, k) { row.setAttribute('data-order', k); });
    Array.prototype.forEach.call(heads, function (head, column) {
      function sort() {
        var ascending = head.getAttribute('aria-sort') !== 'ascending';
        Array.prototype.forEach.call(heads, function (h) { h.removeAttribute('aria-sort'); });
        head.setAttribute('aria-sort', ascending ? 'ascending' : 'descending');
        var rows = Array.prototype.slice.call(body.rows);
        rows.sort(function (a, b) {
          var x = number(a.cells[column]), y = number(b.cells[column]);
          var ta = a.cells[column].textContent, tb = b.cells[column].textContent;
          var emptyA = ta.trim() === '—', emptyB = tb.trim() === '—';
          if (emptyA !== emptyB) { return emptyA ? 1 : -1; }
          var d;
          if (x !== null && y !== null) { d = x - y; }
          else if (x !== null) { d = -1; }
          else if (y !== null) { d = 1; }
          else { d = ta < tb ? -1 : (ta > tb ? 1 : 0); }
          if (!ascending) { d = -d; }
          return d !== 0 ? d : a.getAttribute('data-order') - b.getAttribute('data-order');
        });
        rows.forEach(function (row) { body.appendChild(row); });
      }
      head.addEventListener('click', sort);
      head.addEventListener('keydown', function (event) {
        if (event.key === 'Enter' || event.key === ' ') { event.preventDefault(); sort(); }
      });
    });
  });

  // The pictures: one technique at a time, one crop for all.
  var dataElement = document.getElementById('picture-data');
  var data = dataElement ? JSON.parse(dataElement.textContent) : [];
  var kinds = ['eye', 'difference', 'difference-causes', 'heatmap'];
  var view = { technique: 0, zoom: 1, cx: 0.5, cy: 0.5 };
  function offset(centre) {
    return Math.min(Math.max(centre * view.zoom - 0.5, 0), view.zoom - 1);
  }
  function place() {
    var ox = offset(view.cx), oy = offset(view.cy);
    kinds.forEach(function (kind) {
      var image = document.getElementById('picture-' + kind);
      image.style.width = (100 * view.zoom) + '%';
      image.style.left = (-100 * ox) + '%';
      image.style.top = (-100 * oy) + '%';
    });
    var zoom = document.getElementById('zoom');
    zoom.value = String(view.zoom);
    var panels = document.getElementById('panels');
    panels.setAttribute('data-crop', [view.cx.toFixed(4), view.cy.toFixed(4), view.zoom].join(','));
  }
  function show(k) {
    view.technique = k;
    var entry = data[k];
    kinds.forEach(function (kind) {
      var image = document.getElementById('picture-' + kind);
      image.setAttribute('src', entry.raw[kind]);
      image.setAttribute('alt', entry.alt[kind]);
      document.getElementById('annotated-' + kind).setAttribute('href', entry.annotated[kind]);
    });
    document.getElementById('settings').textContent = entry.settings;
    Object.keys(entry.counts).forEach(function (name) {
      document.getElementById('count-' + name).textContent = entry.counts[name];
    });
    document.getElementById('range-text').textContent = entry.range_text;
    ['low', 'high'].forEach(function (end, i) {
      var marker = document.getElementById('range-' + end);
      if (entry.range_at) {
        marker.setAttribute('visibility', 'visible');
        marker.setAttribute('transform', 'translate(' + entry.range_at[i].toFixed(2) + ',0)');
      } else {
        marker.setAttribute('visibility', 'hidden');
      }
    });
    Array.prototype.forEach.call(document.querySelectorAll('.techniques button'), function (button) {
      button.setAttribute('aria-pressed', String(Number(button.getAttribute('data-technique')) === k));
    });
    document.getElementById('panels').setAttribute('data-technique', entry.label);
  }
  if (data.length > 0) {
    Array.prototype.forEach.call(document.querySelectorAll('.techniques button'), function (button) {
      button.addEventListener('click', function () { show(Number(button.getAttribute('data-technique'))); });
    });
    document.getElementById('zoom').addEventListener('change', function (event) {
      view.zoom = Number(event.target.value);
      place();
    });
    document.getElementById('whole').addEventListener('click', function () {
      view.zoom = 1; view.cx = 0.5; view.cy = 0.5;
      place();
    });
    Array.prototype.forEach.call(document.querySelectorAll('.crop'), function (crop) {
      crop.addEventListener('click', function (event) {
        var box = crop.getBoundingClientRect();
        var ox = offset(view.cx), oy = offset(view.cy);
        view.cx = Math.min(Math.max((ox + (event.clientX - box.left) / box.width) / view.zoom, 0), 1);
        view.cy = Math.min(Math.max((oy + (event.clientY - box.top) / box.height) / view.zoom, 0), 1);
        if (view.zoom === 1) { view.zoom = 4; }
        place();
      });
      crop.addEventListener('keydown', function (event) {
        var step = 0.1 / view.zoom;
        var moves = { ArrowLeft: [-step, 0], ArrowRight: [step, 0], ArrowUp: [0, -step], ArrowDown: [0, step] };
        var move = moves[event.key];
        if (!move) { return; }
        event.preventDefault();
        view.cx = Math.min(Math.max(view.cx + move[0], 0), 1);
        view.cy = Math.min(Math.max(view.cy + move[1], 0), 1);
        place();
      });
    });
    show(0);
    place();
  }

  // Self-check: every picture the page names loads, with a width.
  var named = [];
  data.forEach(function (entry) {
    kinds.forEach(function (kind) { named.push(entry.raw[kind], entry.annotated[kind]); });
  });
  var loaded = 0, settled = 0;
  root.setAttribute('data-pictures-named', String(named.length));
  root.setAttribute('data-pictures-loaded', '0');
  function settle() {
    settled += 1;
    if (settled === named.length) { root.setAttribute('data-ready', 'true'); }
  }
  if (named.length === 0) { root.setAttribute('data-ready', 'true'); }
  named.forEach(function (source) {
    var probe = new Image();
    probe.onload = function () {
      if (probe.naturalWidth > 0) {
        loaded += 1;
        root.setAttribute('data-pictures-loaded', String(loaded));
      } else {
        window.reportProblem('empty picture ' + source);
      }
      settle();
    };
    probe.onerror = function () { window.reportProblem('cannot load ' + source); settle(); };
    probe.src = source;
  });
})();
"#;

/// The colour bar's drawing width and left end in its SVG, in user units.
const BAR: (f64, f64) = (300.0, 10.0);

/// `text` as JSON that is safe inside a `<script>` element.
fn script_json(value: &serde_json::Value) -> String {
    value
        .to_string()
        .replace('<', "\\u003c")
        .replace('>', "\\u003e")
        .replace('&', "\\u0026")
}

fn css(colour: [u8; 3]) -> String {
    format!("rgb({},{},{})", colour[0], colour[1], colour[2])
}

/// An inline SVG figure.
fn inline_figure(svg: &str, alt: &str) -> String {
    format!(
        "<figure class=\"plot\" role=\"img\" aria-label=\"{}\">\n{}\n</figure>\n",
        escape_html(alt),
        svg.trim_end()
    )
}

/// The heat map's colour bar as inline SVG: the viridis gradient, the decades, and the two range
/// markers the script moves.
fn colour_bar_svg() -> String {
    let scale = HeatScale::PIXELS_PER_TEXEL;
    let (length, left) = BAR;
    let mut svg = format!(
        "<svg class=\"colourbar\" xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"46\" \
         viewBox=\"0 0 {w} 46\" role=\"img\" aria-label=\"colour bar: texel footprint on screen, \
         pixels per texel, log scale from {} to {}\">\n<defs><linearGradient id=\"viridis\" x1=\"0\" \
         y1=\"0\" x2=\"1\" y2=\"0\">",
        scale.low(),
        scale.high(),
        w = length + 2.0 * left
    );
    let last = VIRIDIS.len() - 1;
    for (k, colour) in VIRIDIS.iter().enumerate() {
        #[expect(clippy::cast_precision_loss, reason = "ten stops")]
        let offset = k as f64 / last as f64;
        write!(
            svg,
            "<stop offset=\"{offset}\" stop-color=\"{}\"/>",
            css(*colour)
        )
        .expect("writing to a string");
    }
    svg.push_str("</linearGradient></defs>\n");
    for end in ["low", "high"] {
        writeln!(
            svg,
            "<path id=\"range-{end}\" d=\"M -4 0 L 4 0 L 0 7 Z\" fill=\"#1e1e1e\" visibility=\"hidden\"/>"
        )
        .expect("writing to a string");
    }
    writeln!(
        svg,
        "<rect x=\"{left}\" y=\"8\" width=\"{length}\" height=\"14\" fill=\"url(#viridis)\" stroke=\"#999\"/>"
    )
    .expect("writing to a string");
    #[expect(
        clippy::cast_possible_truncation,
        reason = "decimal exponents of a finite, positive scale"
    )]
    let decades = (scale.low().log10().ceil() as i32)..=(scale.high().log10().floor() as i32);
    for exponent in decades {
        let decade = 10f64.powi(exponent);
        let x = left + scale.fraction(decade).unwrap_or(0.0) * length;
        writeln!(
            svg,
            "<line x1=\"{x:.2}\" y1=\"22\" x2=\"{x:.2}\" y2=\"27\" stroke=\"#1e1e1e\"/>\
             <text x=\"{x:.2}\" y=\"40\" font-size=\"11\" text-anchor=\"middle\" fill=\"#1e1e1e\">{decade}</text>"
        )
        .expect("writing to a string");
    }
    svg.push_str("</svg>");
    svg
}

/// The pictures' section: controls, the three panels and their keys, and the data the script
/// switches between.
fn pictures_section(study: &Study) -> String {
    let Some(first) = study.pictures.first() else {
        return String::new();
    };
    let scale = HeatScale::PIXELS_PER_TEXEL;
    let (length, left) = BAR;
    let entries: Vec<serde_json::Value> = study
        .pictures
        .iter()
        .map(|p| {
            let technique = p.setting.technique;
            let by_kind = |f: &dyn Fn(PictureKind) -> String| {
                serde_json::Value::Object(
                    PictureKind::ALL
                        .into_iter()
                        .map(|kind| (kind.key().to_owned(), f(kind).into()))
                        .collect(),
                )
            };
            let path = |f: fn(PictureKind, shadowlab_shadow::Technique) -> String| {
                by_kind(&|kind| f(kind, technique))
            };
            let counts = ClassCounts::of(&p.difference);
            let mut count_values = serde_json::Map::new();
            for (name, n) in [
                ("falsely-lit", counts.falsely_lit),
                ("falsely-shadowed", counts.falsely_shadowed),
                ("correct-lit", counts.correct_lit),
                ("correct-shadow", counts.correct_shadow),
                ("background", counts.background),
            ] {
                count_values.insert(name.to_owned(), n.into());
            }
            for (_, _, n, name) in CauseCounts::of(&p.causes).classes() {
                count_values.insert(name.to_owned(), n.into());
            }
            let at = |v: f64| left + scale.fraction(v).unwrap_or(0.0) * length;
            let range_text = p.footprint_range.map_or_else(
                || "no pixel has a footprint".to_owned(),
                |(low, high)| {
                    format!(
                        "{} to {} pixels per texel",
                        shadowlab_plot::format_value(low),
                        shadowlab_plot::format_value(high)
                    )
                },
            );
            let alt = |kind: PictureKind| pictures::title(study, &p.setting, kind);
            json!({
                "label": technique_label(technique),
                "settings": pictures::settings(study, &p.setting),
                "raw": path(PictureKind::raw_path),
                "annotated": path(PictureKind::annotated_path),
                "alt": by_kind(&alt),
                "counts": count_values,
                "range_text": range_text,
                "range_at": p.footprint_range.map(|(low, high)| [at(low), at(high)]),
            })
        })
        .collect();
    let mut html = String::from("<h2 id=\"pictures\">Pictures</h2>\n");
    writeln!(
        html,
        "<p>Each technique at {}² with {} map(s) per light and filter {}: the view with its \
         shadows, the pixels it misclassifies against the exact truth, the same pixels coloured by \
         cause, and its texel footprint on screen, side by side, one pixel per eye pixel. Click a picture to zoom in there, or choose \
         the zoom; the crop stays when you switch techniques. The annotated pictures (title, \
         settings, legend or colour bar) are in <code>pictures/</code>, the raw ones in \
         <code>images/</code>.</p>",
        first.setting.resolution,
        first.setting.partitions,
        escape_html(&filter_label(&first.setting.filter))
    )
    .expect("writing to a string");
    html.push_str("<div class=\"controls\">\n<div class=\"techniques\" role=\"group\" aria-label=\"technique\">Technique: ");
    for (k, p) in study.pictures.iter().enumerate() {
        write!(
            html,
            "<button type=\"button\" data-technique=\"{k}\" aria-pressed=\"{}\">{}</button>",
            k == 0,
            escape_html(&technique_label(p.setting.technique))
        )
        .expect("writing to a string");
    }
    html.push_str(
        "</div>\n<label>Zoom <select id=\"zoom\"><option value=\"1\">1×</option>\
         <option value=\"2\">2×</option><option value=\"4\">4×</option><option value=\"8\">8×</option>\
         <option value=\"16\">16×</option></select></label>\n\
         <button type=\"button\" id=\"whole\">Whole view</button>\n</div>\n",
    );
    writeln!(
        html,
        "<p id=\"settings\">{}</p>",
        escape_html(&pictures::settings(study, &first.setting))
    )
    .expect("writing to a string");
    let aspect = format!("{} / {}", study.width, study.height);
    writeln!(
        html,
        "<div class=\"panels\" id=\"panels\" data-technique=\"{}\">",
        escape_html(&technique_label(first.setting.technique))
    )
    .expect("writing to a string");
    let swatch = |colour: [u8; 3], meaning: &str, count: Option<(&str, u64)>| {
        let count = count.map_or(String::new(), |(id, n)| {
            format!(": <span id=\"count-{id}\">{n}</span> px")
        });
        format!(
            "<li><span class=\"swatch\" style=\"background:{}\"></span>{}{count}</li>\n",
            css(colour),
            escape_html(meaning)
        )
    };
    for kind in PictureKind::ALL {
        let mut key = String::new();
        match kind {
            PictureKind::Eye => key.push_str(
                "<p class=\"key\">Shaded by each group's colour; dark where this technique's \
                 lookup says the light is blocked. Sky where nothing is seen.</p>\n",
            ),
            PictureKind::Difference => {
                let counts = ClassCounts::of(&first.difference);
                key.push_str("<ul class=\"swatches\">\n");
                for ((colour, meaning, n), id) in counts.classes().into_iter().zip([
                    "falsely-lit",
                    "falsely-shadowed",
                    "correct-lit",
                    "correct-shadow",
                    "background",
                ]) {
                    key.push_str(&swatch(colour, meaning, Some((id, n))));
                }
                key.push_str("</ul>\n");
                debug_assert_eq!(
                    [
                        FALSELY_LIT,
                        FALSELY_SHADOWED,
                        CORRECT_LIT,
                        CORRECT_SHADOW,
                        BACKGROUND
                    ],
                    counts.classes().map(|c| c.0)
                );
            }
            PictureKind::Causes => {
                key.push_str("<ul class=\"swatches\">\n");
                for (colour, meaning, n, id) in CauseCounts::of(&first.causes).classes() {
                    key.push_str(&swatch(colour, meaning, Some((id, n))));
                }
                key.push_str("</ul>\n");
            }
            PictureKind::Heatmap => {
                key.push_str(&colour_bar_svg());
                writeln!(
                    key,
                    "\n<p class=\"key\">Texel footprint on screen, pixels per texel (σ_max of the \
                     screen → map Jacobian's inverse), log scale from {} to {}; beyond the ends the \
                     end colours. ▼ values in this picture: <span id=\"range-text\"></span>.</p>",
                    scale.low(),
                    scale.high()
                )
                .expect("writing to a string");
                key.push_str("<ul class=\"swatches\">\n");
                key.push_str(&swatch(NO_VALUE, NO_VALUE_MEANING, None));
                key.push_str("</ul>\n");
            }
        }
        writeln!(
            html,
            "<figure class=\"panel\">\n<figcaption>{}</figcaption>\n\
             <div class=\"crop\" tabindex=\"0\" style=\"aspect-ratio: {aspect}\" title=\"click to zoom in here\">\
             <img id=\"picture-{}\" src=\"{}\" alt=\"{}\" width=\"{}\" height=\"{}\"></div>\n\
             {key}<p class=\"key\"><a id=\"annotated-{}\" href=\"{}\">annotated picture</a></p>\n</figure>",
            escape_html(&capitalised(kind.caption())),
            kind.key(),
            escape_html(&kind.raw_path(first.setting.technique)),
            escape_html(&pictures::title(study, &first.setting, kind)),
            study.width,
            study.height,
            kind.key(),
            escape_html(&kind.annotated_path(first.setting.technique)),
        )
        .expect("writing to a string");
    }
    html.push_str("</div>\n");
    writeln!(
        html,
        "<script type=\"application/json\" id=\"picture-data\">{}</script>",
        script_json(&serde_json::Value::Array(entries))
    )
    .expect("writing to a string");
    html
}

fn capitalised(text: &str) -> String {
    let mut chars = text.chars();
    chars.next().map_or_else(String::new, |c| {
        c.to_uppercase().chain(chars).collect::<String>()
    })
}

/// The page of `study`: `blocks` (the document `report.md` is written from), with the figures
/// inlined from `pareto_svg`, `view_axis_svg` and `leaks_svg`, and the pictures' section.
pub(crate) fn page(
    study: &Study,
    blocks: &[Block],
    pareto_svg: &str,
    view_axis_svg: Option<&str>,
    leaks_svg: Option<&str>,
) -> String {
    let figure = |src: &str, alt: &str| match (src, view_axis_svg, leaks_svg) {
        ("pareto.png", _, _) => inline_figure(pareto_svg, alt),
        ("view-axis.png", Some(svg), _) | ("leaks.png", _, Some(svg)) => inline_figure(svg, alt),
        _ => format!(
            "<p><img src=\"{}\" alt=\"{}\"></p>\n",
            escape_html(src),
            escape_html(alt)
        ),
    };
    let body = document::html(blocks, &figure);
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>Shadow quality and cost: {}</title>\n<style>{STYLE}</style>\n\
         <script>{HEAD_SCRIPT}</script>\n</head>\n<body>\n<main>\n\
         <div id=\"problems\" role=\"alert\" hidden><strong>Parts of this report did not load:</strong><ul></ul></div>\n\
         {body}{}</main>\n<script>{BODY_SCRIPT}</script>\n</body>\n</html>\n",
        escape_html(&study.scene),
        pictures_section(study),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_cannot_close_its_script() {
        let value = json!({"name": "</script><script>alert(1)</script> & <!--"});
        let text = script_json(&value);
        assert!(
            !text.contains('<') && !text.contains('>') && !text.contains('&'),
            "{text}"
        );
        let back: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(back, value);
    }

    #[test]
    fn the_colour_bar_has_every_stop_and_decade() {
        let svg = colour_bar_svg();
        assert_eq!(svg.matches("<stop ").count(), VIRIDIS.len());
        for label in [">0.1<", ">1<", ">10<", ">100<"] {
            assert!(svg.contains(label), "{label} in {svg}");
        }
    }
}
