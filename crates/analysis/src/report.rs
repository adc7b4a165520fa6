//! A study written out: `report.md` (tables in the manner of Chong and Gortler's), `report.html`
//! (the same document as a self-contained page, with the pictures side by side),
//! `results.csv`, `results.json`, the Pareto plot of time against misclassified pixels, and the
//! pictures ([`crate::pictures`]). [`Report::files`] lists every file with its path.
//!
//! Every number but the times is deterministic; the times are wall-clock measurements of the same
//! run and vary from run to run.

use std::fmt::Write as _;

use rayon::prelude::*;
use serde_json::{Value, json};
use shadowlab_plot::{Axis, Figure, LegendPosition, LineStyle, Panel, Series};
use shadowlab_shadow::{Filter, StepDirection, Technique};

use crate::aliasing::AliasingStats;
use crate::document::{self, Align, Block, Table, code, paragraph, text};
use crate::error::AnalysisError;
use crate::study::{Measurement, Outcome, Study};

/// The files of a report.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// `report.md`.
    pub markdown: String,
    /// `results.csv`.
    pub csv: String,
    /// `results.json`.
    pub json: String,
    /// `pareto.svg`.
    pub pareto_svg: String,
    /// `pareto.png`.
    pub pareto_png: Vec<u8>,
    /// `view-axis.svg` and `view-axis.png`: the error along the view axis, measured over the
    /// closed form; `None` when no technique of the study has a view-axis curve (the
    /// scene-optimized map and frustum limiting alone), so there is nothing to draw.
    pub view_axis: Option<(String, Vec<u8>)>,
    /// `leaks.svg` and `leaks.png`: each filterable map's light leaks against its prefilter's
    /// side; `None` unless some method was measured at two sides or more.
    pub leaks: Option<(String, Vec<u8>)>,
    /// `report.html`: the same document as one self-contained page (inline style, script and
    /// plots; the pictures by relative path), with sortable tables and the pictures side by side.
    pub html: String,
    /// The pictures, raw and annotated, each with its path ([`crate::pictures::files`]).
    pub pictures: Vec<(String, Vec<u8>)>,
}

impl Report {
    /// Every file of the report, each with its path in the output set (`/`-separated, relative):
    /// `report.md`, `results.csv`, `results.json`, `pareto.svg`, `pareto.png`, `view-axis.svg`
    /// and `view-axis.png` (if drawn), `leaks.svg` and `leaks.png` (if drawn), `report.html`,
    /// then the pictures.
    #[must_use]
    pub fn files(self) -> Vec<(String, Vec<u8>)> {
        let mut files = vec![
            ("report.md".to_owned(), self.markdown.into_bytes()),
            ("results.csv".to_owned(), self.csv.into_bytes()),
            ("results.json".to_owned(), self.json.into_bytes()),
            ("pareto.svg".to_owned(), self.pareto_svg.into_bytes()),
            ("pareto.png".to_owned(), self.pareto_png),
        ];
        if let Some((svg, png)) = self.view_axis {
            files.push(("view-axis.svg".to_owned(), svg.into_bytes()));
            files.push(("view-axis.png".to_owned(), png));
        }
        if let Some((svg, png)) = self.leaks {
            files.push(("leaks.svg".to_owned(), svg.into_bytes()));
            files.push(("leaks.png".to_owned(), png));
        }
        files.push(("report.html".to_owned(), self.html.into_bytes()));
        files.extend(self.pictures);
        files
    }
}

pub use crate::labels::{filter_label, technique_label};

fn ms(d: std::time::Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Writes the report of `study`.
///
/// # Errors
/// [`AnalysisError::Plot`] if a figure or picture cannot be drawn, [`AnalysisError::Raster`] if a
/// picture cannot be encoded.
pub fn report(study: &Study) -> Result<Report, AnalysisError> {
    // The figures and the pictures are drawn and encoded side by side: each is its own file.
    let drawn = |figure: Option<Figure>| -> Result<_, AnalysisError> {
        figure
            .map(|figure| {
                let svg = shadowlab_plot::render_svg(&figure)?;
                let png = shadowlab_plot::render_png(&svg)?;
                Ok((svg, png))
            })
            .transpose()
    };
    let figures = [
        Some(pareto(study)),
        (!study.view_axis.is_empty()).then(|| view_axis_figure(study)),
        leaks_figure(study),
    ];
    let (drawings, pictures) = rayon::join(
        || figures.into_par_iter().map(drawn).collect::<Vec<_>>(),
        || crate::pictures::files(study),
    );
    let mut drawings = drawings.into_iter();
    let mut next = || drawings.next().expect("one drawing per figure");
    let (pareto, view_axis, leaks, pictures) = (next()?, next()?, next()?, pictures?);
    let (pareto_svg, pareto_png) = pareto.expect("the Pareto figure is always drawn");
    let blocks = document(study, leaks.is_some());
    let html = crate::html::page(
        study,
        &blocks,
        &pareto_svg,
        view_axis.as_ref().map(|v| v.0.as_str()),
        leaks.as_ref().map(|v| v.0.as_str()),
    );
    Ok(Report {
        markdown: document::markdown(&blocks),
        html,
        pictures,
        csv: csv(study)?,
        json: serde_json::to_string_pretty(&results_json(study)).expect("plain data"),
        pareto_svg,
        pareto_png,
        view_axis,
        leaks,
    })
}

/// The groups of a study that share partitions and filter, in order of first appearance.
fn groups(study: &Study) -> Vec<(usize, String)> {
    let mut out: Vec<(usize, String)> = Vec::new();
    for m in &study.measurements {
        let key = (m.setting.partitions, filter_label(&m.setting.filter));
        if !out.contains(&key) {
            out.push(key);
        }
    }
    out
}

fn distinct<T: PartialEq + Copy>(values: impl Iterator<Item = T>) -> Vec<T> {
    let mut out = Vec::new();
    for v in values {
        if !out.contains(&v) {
            out.push(v);
        }
    }
    out
}

/// A table whose first column is the resolution and whose others are the techniques, all
/// numbers (right-aligned).
fn resolution_table(header: &[String], rows: Vec<Vec<String>>) -> Table {
    Table {
        header: std::iter::once("resolution".to_string())
            .chain(header.iter().cloned())
            .collect(),
        align: vec![Align::Right; header.len() + 1],
        rows,
    }
}

/// The report as a document: what `report.md` and `report.html` both say.
fn document(study: &Study, leaks_drawn: bool) -> Vec<Block> {
    let mut doc = Vec::new();
    let visible = study.visible.max(1);
    #[expect(clippy::cast_precision_loss, reason = "pixel counts")]
    let percent = |n: u64| 100.0 * n as f64 / visible as f64;
    doc.push(Block::Heading(
        1,
        vec![text("Shadow quality and cost: "), code(&study.scene)],
    ));
    let mut intro = vec![vec![text(format!(
        "{}×{} eye image, {} visible pixels. Misclassified pixels are counted against the exact truth \
         (one ray per visible pixel toward each light), computed in {:.1} ms.",
        study.width,
        study.height,
        study.visible,
        ms(study.truth_time)
    ))]];
    if let Some(d) = &study.map_truth {
        intro.push(vec![text(format!(
            "A {0}² uniform shadow map, Chong and Gortler's truth, disagrees with it at {1} pixels ({2:.3} %): \
             {3} falsely lit, {4} falsely shadowed.",
            crate::study::MAP_TRUTH_RESOLUTION,
            d.total(),
            percent(d.total()),
            d.falsely_lit,
            d.falsely_shadowed
        ))]);
    }
    intro.push(vec![text(
        "Each misclassified pixel is given one cause, the first that holds: acne (falsely \
         shadowed by its own surface's depth in the texel under it), peter-panning (falsely lit, \
         and shadowed by the same lookup without bias), seam in a blend band (served by two \
         partitions' maps blended), seam at a boundary (next to a pixel another partition serves) \
         and aliasing (the rest).",
    )]);
    doc.push(Block::Paragraph(intro));
    let techniques = distinct(study.measurements.iter().map(|m| m.setting.technique));
    let resolutions = distinct(study.measurements.iter().map(|m| m.setting.resolution));
    for (partitions, filter) in groups(study) {
        let find = |t: Technique, r: u32| {
            study.measurements.iter().find(|m| {
                m.setting.technique == t
                    && m.setting.resolution == r
                    && m.setting.partitions == partitions
                    && filter_label(&m.setting.filter) == filter
            })
        };
        doc.push(Block::Heading(
            2,
            vec![text(format!(
                "Misclassified pixels — {partitions} map(s) per light, filter {filter}"
            ))],
        ));
        let header: Vec<String> = techniques.iter().map(|t| technique_label(*t)).collect();
        let mut rows = Vec::new();
        let mut excess = Vec::new();
        for r in &resolutions {
            let counts: Vec<Option<u64>> = techniques
                .iter()
                .map(|t| {
                    find(*t, *r)
                        .and_then(|m| m.outcome.as_ref().ok())
                        .map(|o| o.errors.total())
                })
                .collect();
            let cells = counts
                .iter()
                .map(|c| c.map_or("—".into(), |c| format!("{c} ({:.2} %)", percent(c))));
            rows.push(std::iter::once(r.to_string()).chain(cells).collect());
            let best = counts.iter().flatten().min().copied();
            excess.push((r, counts, best));
        }
        doc.push(Block::Table(resolution_table(&header, rows)));
        doc.push(paragraph(vec![text(
            "Percentage more misclassified pixels than the best technique at that resolution:",
        )]));
        let rows = excess
            .into_iter()
            .map(|(r, counts, best)| {
                let cells = counts.iter().map(|c| match (c, best) {
                    (Some(c), Some(b)) if b > 0 => {
                        #[expect(clippy::cast_precision_loss, reason = "pixel counts")]
                        let more = 100.0 * (*c as f64 - b as f64) / b as f64;
                        format!("{more:.1} %")
                    }
                    (Some(_), _) => "0 %".into(),
                    (None, _) => "—".into(),
                });
                std::iter::once(r.to_string()).chain(cells).collect()
            })
            .collect();
        doc.push(Block::Table(resolution_table(&header, rows)));
        chong_gortler(&mut doc, &resolutions, &find);
        // Aliasing and time at every resolution, one table each.
        let table = |doc: &mut Vec<Block>, title: &str, cell: &dyn Fn(&Outcome) -> String| {
            doc.push(Block::Heading(3, vec![text(title)]));
            let rows = resolutions
                .iter()
                .map(|r| {
                    let cells = techniques.iter().map(|t| {
                        find(*t, *r)
                            .and_then(|m| m.outcome.as_ref().ok())
                            .map_or("—".into(), cell)
                    });
                    std::iter::once(r.to_string()).chain(cells).collect()
                })
                .collect();
            doc.push(Block::Table(resolution_table(&header, rows)));
        };
        table(&mut doc, "Falsely lit / falsely shadowed pixels", &|o| {
            format!("{} / {}", o.errors.falsely_lit, o.errors.falsely_shadowed)
        });
        table(
            &mut doc,
            "Misclassified pixels by cause: acne / peter-panning / seam in a band / seam at a \
             boundary / aliasing",
            &|o| o.causes.joined(" / "),
        );
        let leaks = study
            .measurements
            .iter()
            .filter(|m| {
                m.setting.partitions == partitions && filter_label(&m.setting.filter) == filter
            })
            .find_map(|m| m.outcome.as_ref().ok().and_then(|o| o.leaks));
        if let Some(leaks) = leaks {
            table(
                &mut doc,
                &format!(
                    "The filter's own errors, against the nearest lookup of the same map: light \
                     leaks / over-darkening; the leaks' distance to the true shadow's edge, \
                     pixels: 99th percentile / max ({}, {} bytes per texel at {}-bit moments)",
                    leaks.method.key(),
                    leaks.bytes_per_texel,
                    8 * leaks.storage.bytes_per_moment()
                ),
                &|o| {
                    o.leaks.map_or("—".into(), |l| {
                        format!(
                            "{} / {}; {:.1} / {:.1}",
                            l.leaks, l.over_darkening, l.extent.p99, l.extent.max
                        )
                    })
                },
            );
        }
        table(
            &mut doc,
            "Texel footprint on screen (pixels per texel): max / 99th percentile / mean",
            &|o| {
                let s = &o.footprint[0];
                format!("{:.2} / {:.2} / {:.2}", s.max, s.p99, s.mean)
            },
        );
        table(
            &mut doc,
            "Its factors, 99th percentiles: perspective (dp/ds) / projection (cos α / cos β)",
            &|o| format!("{:.2} / {:.2}", o.footprint[1].p99, o.footprint[2].p99),
        );
        table(
            &mut doc,
            "Time per frame, ms: total (planning + shadow pass + lookup); then the analysis's own \
             time, not in the total: measuring the footprints, attributing the errors",
            &|o| {
                format!(
                    "{:.1} ({:.1} + {:.1} + {:.1}); {:.1}, {:.1}",
                    ms(o.time()),
                    ms(o.planning),
                    ms(o.shadow_pass),
                    ms(o.lookup),
                    ms(o.footprints),
                    ms(o.attribution)
                )
            },
        );
    }
    let undefined: Vec<&Measurement> = study
        .measurements
        .iter()
        .filter(|m| m.outcome.is_err())
        .collect();
    if !undefined.is_empty() {
        doc.push(Block::Heading(2, vec![text("Not defined for this scene")]));
        let mut seen = Vec::new();
        let mut items = Vec::new();
        for m in undefined {
            let label = technique_label(m.setting.technique);
            if !seen.contains(&label) {
                items.push(vec![text(format!(
                    "{label}: {}",
                    m.outcome.as_ref().err().map_or("", String::as_str)
                ))]);
                seen.push(label);
            }
        }
        doc.push(Block::List(items));
    }
    view_axis_section(&mut doc, study);
    if leaks_drawn {
        doc.push(Block::Heading(
            2,
            vec![text(
                "Filterable maps: light leaks against the prefilter's side",
            )],
        ));
        doc.push(Block::Figure {
            alt: "Light leaks against the prefilter's side".into(),
            src: "leaks.png".into(),
        });
        doc.push(paragraph(vec![text(
            "Per technique, method and maps per light, at the study's highest resolution: the \
             falsely lit pixels of each filterable map that the nearest lookup of the same map \
             gets right, against the side of its box prefilter.",
        )]));
    }
    doc.push(Block::Heading(2, vec![text("The trade")]));
    doc.push(Block::Figure {
        alt: "Time against misclassified pixels".into(),
        src: "pareto.png".into(),
    });
    doc.push(paragraph(vec![text(format!(
        "Combinations no other beats in misclassified pixels while being faster by more than the \
         measured spread (the Pareto front). Times are the median of {} run(s) of each \
         combination's shadows, ± half their range:",
        study.timing_runs
    ))]));
    let rows = pareto_front(study)
        .into_iter()
        .map(|m| {
            let o = m.outcome.as_ref().expect("defined");
            vec![
                technique_label(m.setting.technique),
                m.setting.resolution.to_string(),
                m.setting.partitions.to_string(),
                filter_label(&m.setting.filter),
                o.errors.total().to_string(),
                format!("{:.1}", ms(o.time())),
                format!("{:.1}", ms(o.time_spread)),
            ]
        })
        .collect();
    doc.push(Block::Table(Table {
        header: [
            "technique",
            "resolution",
            "maps",
            "filter",
            "misclassified",
            "time (ms)",
            "± (ms)",
        ]
        .map(String::from)
        .to_vec(),
        align: vec![
            Align::Left,
            Align::Right,
            Align::Right,
            Align::Left,
            Align::Right,
            Align::Right,
            Align::Right,
        ],
        rows,
    }));
    doc
}

/// CG06's Table 1 reported 33–41 % more misclassified pixels for "normal" shadow maps (uniform
/// with frustum limiting) than for their optimized ones, at 750² to 2000².
const CG06_NORMAL_EXCESS: (f64, f64) = (33.0, 41.0);

/// The structure of CG06's Table 1 — normal (uniform with frustum limiting) against optimal per
/// resolution, and how many more pixels normal misclassifies — with the paper's range beside it.
/// Written only if the study has both techniques.
fn chong_gortler<'a>(
    doc: &mut Vec<Block>,
    resolutions: &[u32],
    find: &impl Fn(Technique, u32) -> Option<&'a Measurement>,
) {
    let errors = |t: Technique, r: u32| {
        find(t, r)
            .and_then(|m| m.outcome.as_ref().ok())
            .map(|o| o.errors.total())
    };
    let rows: Vec<(u32, u64, u64)> = resolutions
        .iter()
        .filter_map(|r| {
            Some((
                *r,
                errors(Technique::UniformLimited, *r)?,
                errors(Technique::Optimal(StepDirection::Paper), *r)?,
            ))
        })
        .collect();
    if rows.is_empty() {
        return;
    }
    doc.push(paragraph(vec![
        text("Against Chong and Gortler's Table 1 (normal = "),
        code("uniform_limited"),
        text("):"),
    ]));
    let mut excess = Vec::new();
    let mut cells = Vec::new();
    for (r, normal, optimal) in rows {
        #[expect(clippy::cast_precision_loss, reason = "pixel counts")]
        let more = 100.0 * (normal as f64 - optimal as f64) / (optimal.max(1) as f64);
        excess.push(more);
        cells.push(vec![
            r.to_string(),
            normal.to_string(),
            optimal.to_string(),
            format!("{more:.1} %"),
        ]);
    }
    doc.push(Block::Table(Table {
        header: [
            "resolution",
            "normal",
            "optimal",
            "normal misclassifies more",
        ]
        .map(String::from)
        .to_vec(),
        align: vec![Align::Right; 4],
        rows: cells,
    }));
    let low = excess.iter().copied().fold(f64::INFINITY, f64::min);
    let high = excess.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let (paper_low, paper_high) = CG06_NORMAL_EXCESS;
    let verdict = if high < paper_low {
        "less than the paper found"
    } else if low > paper_high {
        "more than the paper found"
    } else {
        "overlapping the paper's range"
    };
    doc.push(paragraph(vec![text(format!(
        "Here normal misclassifies {low:.1} % to {high:.1} % more than optimal; Chong and Gortler \
         reported {paper_low:.0} % to {paper_high:.0} % on their scenes (their truth: a 3700² uniform \
         map; ours: exact rays) — {verdict}."
    ))]));
}

/// Whether `p` dominates `o`: no more misclassified pixels, and faster by more than the two
/// times' spreads together (their ± intervals do not overlap) — a difference in time within the
/// measured noise never makes a combination dominated.
pub(crate) fn dominates(p: &Outcome, o: &Outcome) -> bool {
    p.errors.total() <= o.errors.total() && o.time() > p.time() + p.time_spread + o.time_spread
}

/// The measurements no other defined one dominates (as good in misclassified
/// pixels and faster beyond the measured spread), by time.
#[must_use]
pub fn pareto_front(study: &Study) -> Vec<&Measurement> {
    let defined: Vec<(&Measurement, &Outcome)> = study
        .measurements
        .iter()
        .filter_map(|m| m.outcome.as_ref().ok().map(|o| (m, o)))
        .collect();
    let mut front: Vec<(&Measurement, &Outcome)> = defined
        .iter()
        .filter(|(_, o)| !defined.iter().any(|(_, p)| dominates(p, o)))
        .copied()
        .collect();
    front.sort_by_key(|(_, o)| o.time());
    front.into_iter().map(|(m, _)| m).collect()
}

/// `text` as one CSV field (RFC 4180): quoted, with quotes doubled, when it holds a comma, a quote
/// or a line break — a scene's name comes from its file and may hold any of them.
#[must_use]
pub fn csv_field(text: &str) -> std::borrow::Cow<'_, str> {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\"")).into()
    } else {
        text.into()
    }
}

fn stats_columns(s: &AliasingStats) -> [f64; 3] {
    [s.max, s.p99, s.mean]
}

fn csv(study: &Study) -> Result<String, AnalysisError> {
    // Numbers in Rust's shortest round-trip form (`{:?}`), as the plot crate's tables write them.
    let mut out = String::from(
        "scene,technique,resolution,maps,filter,defined,visible,misclassified,falsely_lit,falsely_shadowed,\
         acne,peter_panning,seam_band,seam_boundary,aliasing,seam,\
         footprint_max,footprint_p99,footprint_mean,perspective_max,perspective_p99,perspective_mean,\
         projection_max,projection_p99,projection_mean,planning_ms,shadow_pass_ms,lookup_ms,time_ms,\
         time_spread_ms,attribution_ms,footprints_ms,filter_leaks,filter_over_darkening,\
         leak_extent_max,leak_extent_p99,leak_extent_mean,bytes_per_texel\n",
    );
    // The columns after `visible`, empty where the technique is not defined.
    let measured_columns = out.split(',').skip_while(|c| *c != "visible").count() - 1;
    for m in &study.measurements {
        let s = &m.setting;
        let prefix = format!(
            "{},{},{},{},{}",
            csv_field(&study.scene),
            technique_label(s.technique),
            s.resolution,
            s.partitions,
            csv_field(&filter_label(&s.filter))
        );
        match &m.outcome {
            Ok(o) => {
                let mut fields = vec![format!("{prefix},true,{}", study.visible)];
                fields.push(format!(
                    "{},{},{}",
                    o.errors.total(),
                    o.errors.falsely_lit,
                    o.errors.falsely_shadowed
                ));
                fields.push(o.causes.joined(","));
                fields.push(o.causes.seam().to_string());
                for part in &o.footprint {
                    fields.extend(stats_columns(part).iter().map(|v| format!("{v:?}")));
                }
                for d in [o.planning, o.shadow_pass, o.lookup, o.time(), o.time_spread] {
                    fields.push(format!("{:?}", ms(d)));
                }
                fields.push(format!("{:?}", ms(o.attribution)));
                fields.push(format!("{:?}", ms(o.footprints)));
                // Empty for the filters that are not filterable maps.
                let leaks = o.leaks.map(|l| {
                    [
                        l.leaks.to_string(),
                        l.over_darkening.to_string(),
                        format!("{:?}", l.extent.max),
                        format!("{:?}", l.extent.p99),
                        format!("{:?}", l.extent.mean),
                        l.bytes_per_texel.to_string(),
                    ]
                });
                fields.extend(leaks.unwrap_or_default());
                writeln!(out, "{}", fields.join(",")).unwrap();
            }
            Err(_) => writeln!(
                out,
                "{prefix},false,{}{}",
                study.visible,
                ",".repeat(measured_columns)
            )
            .unwrap(),
        }
    }
    Ok(out)
}

/// `results.json` of `study`: the scene, the eye image, the timing runs and every measurement (what
/// `analyze` writes, and what the Python package returns).
#[must_use]
pub fn results_json(study: &Study) -> Value {
    json!({
        "scene": study.scene,
        "timing_runs": study.timing_runs,
        "width": study.width,
        "height": study.height,
        "visible": study.visible,
        "truth_ms": ms(study.truth_time),
        "map_truth_disagreement": study.map_truth.as_ref().map(|d| json!({
            "falsely_lit": d.falsely_lit, "falsely_shadowed": d.falsely_shadowed, "total": d.total()
        })),
        "measurements": study.measurements.iter().map(|m| {
            let s = &m.setting;
            let base = json!({
                "technique": technique_label(s.technique),
                "resolution": s.resolution,
                "maps": s.partitions,
                "filter": filter_label(&s.filter),
            });
            match &m.outcome {
                Ok(o) => {
                    let stats = |a: &AliasingStats| json!({"max": a.max, "p99": a.p99, "mean": a.mean});
                    json!({
                        "setting": base,
                        "misclassified": o.errors.total(),
                        "falsely_lit": o.errors.falsely_lit,
                        "falsely_shadowed": o.errors.falsely_shadowed,
                        "acne": o.causes.acne,
                        "peter_panning": o.causes.peter_panning,
                        "seam": o.causes.seam(),
                        "seam_band": o.causes.seam_band,
                        "seam_boundary": o.causes.seam_boundary,
                        "aliasing": o.causes.aliasing,
                        "texels": o.texels,
                        "footprint": {"total": stats(&o.footprint[0]), "perspective": stats(&o.footprint[1]), "projection": stats(&o.footprint[2])},
                        "ms": {"planning": ms(o.planning), "shadow_pass": ms(o.shadow_pass), "lookup": ms(o.lookup), "total": ms(o.time()), "spread": ms(o.time_spread), "attribution": ms(o.attribution), "footprints": ms(o.footprints)},
                        "filter_leaks": o.leaks.map(|l| json!({
                            "method": l.method.key(), "leaks": l.leaks, "over_darkening": l.over_darkening,
                            "extent": stats(&l.extent), "bytes_per_texel": l.bytes_per_texel,
                        })),
                    })
                }
                Err(reason) => json!({"setting": base, "not_defined": reason}),
            }
        }).collect::<Vec<_>>(),
    })
}

/// Light leaks against the prefilter's side: one line per technique, filterable method, its
/// parameters and maps per light, through the sides measured at the study's highest resolution
/// (leaks of 0 drawn at ½ on the log axis); `None` unless some line has two sides or more.
fn leaks_figure(study: &Study) -> Option<Figure> {
    let top = study
        .measurements
        .iter()
        .filter(|m| m.outcome.as_ref().is_ok_and(|o| o.leaks.is_some()))
        .map(|m| m.setting.resolution)
        .max()?;
    let mut lines: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for m in &study.measurements {
        let (Ok(o), true) = (&m.outcome, m.setting.resolution == top) else {
            continue;
        };
        let (Some(leaks), Filter::Vsm { size, .. } | Filter::Moments { size, .. }) =
            (o.leaks, m.setting.filter)
        else {
            continue;
        };
        // The filter's label without its side: the method and its parameters.
        let label = filter_label(&m.setting.filter);
        let parameters = label.split_once(',').map_or("", |(_, rest)| rest);
        let line = format!(
            "{} {}{}{}",
            technique_label(m.setting.technique),
            leaks.method.key(),
            if parameters.is_empty() {
                String::new()
            } else {
                format!(" {parameters}")
            },
            if m.setting.partitions > 1 {
                format!(" ×{}", m.setting.partitions)
            } else {
                String::new()
            }
        );
        #[expect(clippy::cast_precision_loss, reason = "pixel counts")]
        let point = (f64::from(size), (leaks.leaks as f64).max(0.5));
        match lines.iter_mut().find(|(l, _)| *l == line) {
            Some((_, points)) => points.push(point),
            None => lines.push((line, vec![point])),
        }
    }
    if lines.iter().all(|(_, points)| points.len() < 2) {
        return None;
    }
    let (mut x_max, mut y_max) = (1.0f64, 1.0f64);
    let series = lines
        .into_iter()
        .enumerate()
        .map(|(index, (label, mut points))| {
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            for p in &points {
                x_max = x_max.max(p.0);
                y_max = y_max.max(p.1);
            }
            let style = if index < 7 {
                LineStyle::Solid
            } else {
                LineStyle::Dashed
            };
            Series::new(label, points, index, style)
        })
        .collect();
    Some(Figure::single(
        format!(
            "{}: light leaks of the filterable maps against their prefilter ({top}² maps)",
            study.scene
        ),
        Panel {
            title: String::new(),
            x: Axis::linear("prefilter side K (texels; a K × K box)", 0.0, x_max + 1.0),
            y: Axis::log(
                "light leaks (pixels the nearest lookup gets right)",
                0.5,
                y_max * 2.0,
            ),
            series,
            markers: Vec::new(),
            // Leaks grow with the prefilter: the lower right is where lines are least.
            legend: LegendPosition::LowerRight,
        },
    ))
}

/// Time against misclassified pixels, one line per technique (and maps/filter) through its
/// resolutions.
fn pareto(study: &Study) -> Figure {
    let mut series = Vec::new();
    let mut lines: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for m in &study.measurements {
        let Ok(o) = &m.outcome else { continue };
        let label = format!(
            "{}{}{}",
            technique_label(m.setting.technique),
            if m.setting.partitions > 1 {
                format!(" ×{}", m.setting.partitions)
            } else {
                String::new()
            },
            if m.setting.filter == Filter::Nearest {
                String::new()
            } else {
                format!(" {}", filter_label(&m.setting.filter))
            }
        );
        #[expect(clippy::cast_precision_loss, reason = "pixel counts")]
        let point = (ms(o.time()), (o.errors.total() as f64).max(0.5));
        match lines.iter_mut().find(|(l, _)| *l == label) {
            Some((_, points)) => points.push(point),
            None => lines.push((label, vec![point])),
        }
    }
    let (mut x_min, mut x_max) = (f64::INFINITY, 1e-3f64);
    let (mut y_min, mut y_max) = (f64::INFINITY, 1.0f64);
    // Each line runs through its resolutions in the order given (time is measured, so it need
    // not grow with resolution: the line shows that too).
    for (index, (label, points)) in lines.into_iter().enumerate() {
        for p in &points {
            x_min = x_min.min(p.0);
            x_max = x_max.max(p.0);
            y_min = y_min.min(p.1);
            y_max = y_max.max(p.1);
        }
        series.push(Series::new(
            label,
            points,
            index,
            if index < 7 {
                LineStyle::Solid
            } else {
                LineStyle::Dashed
            },
        ));
    }
    let y_min = if y_min.is_finite() {
        (y_min * 0.5).max(0.5)
    } else {
        0.5
    };
    Figure::single(
        format!(
            "{}: time per frame against misclassified pixels",
            study.scene
        ),
        Panel {
            title: String::new(),
            x: Axis::log(
                "time per frame (ms): planning + shadow pass + lookup",
                // From a power of ten, so that the axis has a labelled decade.
                if x_min.is_finite() {
                    10f64.powf(x_min.log10().floor())
                } else {
                    1e-3
                },
                x_max * 1.25,
            ),
            y: Axis::log("misclassified pixels", y_min, y_max * 2.0),
            series,
            markers: Vec::new(),
            legend: LegendPosition::UpperRight,
        },
    )
}

/// The view-axis section: how far the measurement on the V-fitted map lies from the closed form,
/// and what fitting to the scene changes, at the near plane, √(nf) and the far plane.
fn view_axis_section(doc: &mut Vec<Block>, study: &Study) {
    if study.view_axis.is_empty() {
        return;
    }
    doc.push(Block::Heading(2, vec![text("Along the view axis")]));
    doc.push(Block::Figure {
        alt: "The perspective error along the view axis".into(),
        src: "view-axis.png".into(),
    });
    doc.push(paragraph(vec![
        code("dp/ds = (1/z)·dz/ds"),
        text(
            " along the view axis for the first light (LiSPSM eq. 1's perspective \
             factor; resolution-independent): the closed form of ",
        ),
        code("shadowlab-params"),
        text(
            " for the map fitted \
             to the view frustum (LiSPSM eq. 3, GMNPR eq. 2, CAD eq. 12), measured on the matrices \
             fitted to it, and measured on the matrices fitted to the scene's focus body, which render.",
        ),
    ]));
    if let Some((fitted, model)) = study.view_axis.iter().find_map(|c| c.warp_depths) {
        doc.push(paragraph(vec![
            text(format!(
                "The closed forms model the frustum's cut by the light–view plane; the map is fitted to \
                 the 3-D frustum, whose corners reach further along the warp axis: d = {fitted:.4} \
                 against the model's {model:.4} ({:+.2} %). The closed form and the measurement differ \
                 by about that much; where the two depths agree (issue 5's proof, ",
                100.0 * (fitted / model - 1.0)
            )),
            code("crates/shadow/tests/shadow/closed_forms.rs"),
            text(") they agree to 1e-6."),
        ]));
    }
    let rows = study
        .view_axis
        .iter()
        .map(|curve| {
            let at = |k: usize| {
                let cell = |v: Option<f64>| v.map_or("—".into(), |v| format!("{v:.4}"));
                format!(
                    "{} / {} / {}",
                    cell(curve.closed_form[k]),
                    cell(curve.fitted_to_view[k]),
                    cell(curve.fitted_to_scene[k])
                )
            };
            let last = curve.depths.len() - 1;
            vec![
                technique_label(curve.technique),
                curve
                    .closed_form_deviation()
                    .map_or("no closed form".into(), |d| format!("{d:.1e}")),
                at(0),
                at(last / 2),
                at(last),
            ]
        })
        .collect();
    doc.push(Block::Table(Table {
        header: [
            "technique",
            "closed form vs measured (B = V), largest relative difference",
            "near: closed / B = V / scene",
            "√(nf)",
            "far",
        ]
        .map(String::from)
        .to_vec(),
        align: vec![
            Align::Left,
            Align::Right,
            Align::Right,
            Align::Right,
            Align::Right,
        ],
        rows,
    }));
}

/// One panel per technique: the closed form (dashed), the V-fitted measurement and the
/// scene-fitted one, against eye depth on log axes.
fn view_axis_figure(study: &Study) -> Figure {
    let points = |curve: &crate::view_axis::AxisCurve, values: &[Option<f64>]| -> Vec<(f64, f64)> {
        curve
            .depths
            .iter()
            .zip(values)
            .map(|(z, v)| (*z, v.unwrap_or(f64::NAN)))
            .collect()
    };
    let panels = study
        .view_axis
        .iter()
        .map(|curve| {
            let series = vec![
                Series::new(
                    "closed form (B = V)",
                    points(curve, &curve.closed_form),
                    0,
                    LineStyle::Dashed,
                ),
                Series::new(
                    "measured, B = V",
                    points(curve, &curve.fitted_to_view),
                    1,
                    LineStyle::Dotted,
                ),
                Series::new(
                    "measured, fitted to the scene",
                    points(curve, &curve.fitted_to_scene),
                    2,
                    LineStyle::Solid,
                ),
            ];
            let values = series
                .iter()
                .flat_map(|s| s.points.iter().map(|p| p.1))
                .filter(|v| v.is_finite() && *v > 0.0);
            let (low, high) =
                values.fold((f64::INFINITY, 0.0f64), |(l, h), v| (l.min(v), h.max(v)));
            // At least a factor 16, so that a labelled decade always falls inside (a constant
            // curve, the logarithmic map's, would otherwise get no tick labels).
            let (low, high) = if !low.is_finite() {
                (0.1, 10.0)
            } else if high / low < 16.0 / 2.25 {
                let centre = (low * high).sqrt();
                (centre / 4.0, centre * 4.0)
            } else {
                (low / 1.5, high * 1.5)
            };
            let (near, far) = (curve.depths[0], curve.depths[curve.depths.len() - 1]);
            Panel {
                title: technique_label(curve.technique),
                x: Axis::log("eye depth z", near, far),
                y: Axis::log("dp/ds", low, high),
                series,
                markers: Vec::new(),
                legend: LegendPosition::UpperRight,
            }
        })
        .collect();
    Figure {
        title: format!(
            "{}: perspective error along the view axis, first light",
            study.scene
        ),
        panels,
        columns: 3,
        panel_width: 520,
        panel_height: 380,
    }
}

#[cfg(test)]
mod csv_tests {
    use super::csv_field;

    #[test]
    fn names_with_separators_are_quoted() {
        assert_eq!(csv_field("outdoor"), "outdoor");
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        assert_eq!(csv_field("say \"hi\"\n"), "\"say \"\"hi\"\"\n\"");
    }
}
