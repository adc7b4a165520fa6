//! The merged sweep: one table of every cell and one report of each technique across the sweep —
//! the distributions of misclassified pixels and of the texel footprint against γ, resolution and
//! scene, with plots. Everything but the timings is a function of the cells' results alone, so a
//! sweep run as one shard or as many merges to the same bytes; the timings sit in the report's
//! last section (`## Time`) and in the table's `*_ms` columns.

use std::collections::BTreeSet;
use std::fmt::Write as _;

use shadowlab_plot::{Axis, Figure, LegendPosition, LineStyle, Panel, Series};

use crate::error::SweepError;
use crate::record::CellRecord;
use crate::table;

/// The heading of the report's timing section, its last: everything from it on may differ
/// between two runs of the same sweep.
pub const TIME_HEADING: &str = "## Time";

/// Width of the γ bins of the report's table, degrees.
pub const GAMMA_BIN_DEGREES: f64 = 15.0;

/// Points per degree at which the γ figure groups cells.
const GAMMA_PLOT_RESOLUTION: f64 = 1000.0;

/// The smallest value a log axis shows (0 % misclassified is drawn here).
const LOG_FLOOR: f64 = 1e-4;

/// The merged files of `records` (every cell of one sweep, in cell order): `results.csv`,
/// `results.parquet`, `report.md`, and its figures `distribution`, `gamma` and `resolution`
/// (each `.svg` and `.png`).
///
/// # Errors
/// [`SweepError::Output`] if a table or figure cannot be written.
pub fn merged_files(records: &[CellRecord]) -> Result<Vec<(String, Vec<u8>)>, SweepError> {
    let output = |e: String| SweepError::Output(e);
    let mut files = vec![
        ("results.csv".to_string(), table::csv(records).into_bytes()),
        (
            "results.parquet".to_string(),
            table::parquet(records).map_err(|e| output(e.to_string()))?,
        ),
        ("report.md".to_string(), report(records).into_bytes()),
    ];
    for (name, figure) in [
        ("distribution", distribution(records)),
        ("gamma", against(records, Versus::Gamma)),
        ("resolution", against(records, Versus::Resolution)),
    ] {
        let svg = shadowlab_plot::render_svg(&figure).map_err(|e| output(e.to_string()))?;
        let png = shadowlab_plot::render_png(&svg).map_err(|e| output(e.to_string()))?;
        files.push((format!("{name}.svg"), svg.into_bytes()));
        files.push((format!("{name}.png"), png));
    }
    Ok(files)
}

/// Distinct values in first-seen order.
fn distinct<T: PartialEq + Clone>(values: impl Iterator<Item = T>) -> Vec<T> {
    let mut out: Vec<T> = Vec::new();
    for v in values {
        if !out.contains(&v) {
            out.push(v);
        }
    }
    out
}

/// The `q`-quantile of `values` by nearest rank (`q` in `[0, 1]`); `None` if empty.
#[must_use]
pub fn quantile(values: &[f64], q: f64) -> Option<f64> {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        clippy::cast_precision_loss,
        reason = "a rank within the slice"
    )]
    let rank = ((q * sorted.len() as f64).ceil() as usize).clamp(1, sorted.len().max(1)) - 1;
    sorted.get(rank).copied()
}

fn percent(record: &CellRecord) -> Option<f64> {
    record.misclassified_fraction().map(|f| 100.0 * f)
}

fn cell(value: Option<f64>, digits: usize) -> String {
    value.map_or_else(|| "—".into(), |v| format!("{v:.digits$}"))
}

/// The misclassified percentages of `records` matching `keep`, and the median.
fn median_percent<'a>(
    records: impl Iterator<Item = &'a CellRecord>,
    keep: impl Fn(&CellRecord) -> bool,
) -> Option<f64> {
    let values: Vec<f64> = records.filter(|r| keep(r)).filter_map(percent).collect();
    quantile(&values, 0.5)
}

/// The γ bin of a record: `[k·15°, (k+1)·15°)`, 90° in the last.
fn gamma_bin(gamma: f64) -> usize {
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "γ in [0, 90]"
    )]
    let bin = (gamma / GAMMA_BIN_DEGREES).floor().max(0.0) as usize;
    bin.min(bins() - 1)
}

fn bins() -> usize {
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "a small constant"
    )]
    let n = (90.0 / GAMMA_BIN_DEGREES).ceil() as usize;
    n
}

/// The report: the sweep's extent, then per technique the misclassified pixels and footprints
/// across the sweep, against γ, resolution and scene, the undefined cells, and last the timings.
#[must_use]
pub fn report(records: &[CellRecord]) -> String {
    let techniques = distinct(records.iter().map(|r| r.technique.clone()));
    let scenes = distinct(records.iter().map(|r| r.scene.clone()));
    let resolutions: BTreeSet<u32> = records.iter().map(|r| r.resolution).collect();
    let frames: BTreeSet<(String, u32, u32)> = records
        .iter()
        .map(|r| (r.scene.clone(), r.camera, r.light))
        .collect();
    let defined = records.iter().filter(|r| r.defined).count();
    let mut md = String::new();
    let w = &mut md;
    let _ = writeln!(w, "# Sweep: {} cells\n", records.len());
    let _ = writeln!(
        w,
        "{} frames (scene × camera pose × light direction) over {} scene(s) ({}), {} technique(s), map sides {}; {defined} cells defined. Misclassified pixels are a percentage of the frame's visible pixels against the exact truth; the texel footprint is in pixels per texel (its 99th percentile over the frame's visible pixels, first light). Medians and 90th percentiles are over the cells of each row, nearest rank.\n",
        frames.len(),
        scenes.len(),
        scenes.join(", "),
        techniques.len(),
        resolutions
            .iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(w, "## Per technique\n");
    let _ = writeln!(
        w,
        "| technique | cells | defined | misclassified %: median | p90 | max | footprint p99: median | max |\n|---|---:|---:|---:|---:|---:|---:|---:|"
    );
    for t in &techniques {
        let of: Vec<&CellRecord> = records.iter().filter(|r| &r.technique == t).collect();
        let errors: Vec<f64> = of.iter().copied().filter_map(percent).collect();
        let footprints: Vec<f64> = of.iter().filter_map(|r| r.footprint_p99).collect();
        let _ = writeln!(
            w,
            "| {t} | {} | {} | {} | {} | {} | {} | {} |",
            of.len(),
            of.iter().filter(|r| r.defined).count(),
            cell(quantile(&errors, 0.5), 3),
            cell(quantile(&errors, 0.9), 3),
            cell(quantile(&errors, 1.0), 3),
            cell(quantile(&footprints, 0.5), 2),
            cell(quantile(&footprints, 1.0), 2),
        );
    }
    let _ = writeln!(
        w,
        "\n![The distributions of misclassified pixels and footprints](distribution.png)\n"
    );
    let _ = writeln!(
        w,
        "## Against γ\n\nMedian misclassified % per γ bin of {GAMMA_BIN_DEGREES}° (γ, the angle between the view and light directions, in degrees; — where the sweep has no defined cell).\n"
    );
    let present: Vec<usize> = (0..bins())
        .filter(|b| records.iter().any(|r| gamma_bin(r.gamma_deg) == *b))
        .collect();
    let header: Vec<String> = present
        .iter()
        .map(|b| {
            #[expect(clippy::cast_precision_loss, reason = "a small bin index")]
            let lo = *b as f64 * GAMMA_BIN_DEGREES;
            if *b + 1 == bins() {
                format!("{lo:.0}–90°")
            } else {
                format!("{lo:.0}–{:.0}°", lo + GAMMA_BIN_DEGREES)
            }
        })
        .collect();
    table_by(w, &techniques, &header, records, |r, k| {
        gamma_bin(r.gamma_deg) == present[k]
    });
    let _ = writeln!(w, "\n![Against γ](gamma.png)\n");
    let _ = writeln!(
        w,
        "## Against resolution\n\nMedian misclassified % per shadow-map side.\n"
    );
    let sides: Vec<u32> = resolutions.iter().copied().collect();
    let header: Vec<String> = sides.iter().map(|s| format!("{s}²")).collect();
    table_by(w, &techniques, &header, records, |r, k| {
        r.resolution == sides[k]
    });
    let _ = writeln!(w, "\n![Against resolution](resolution.png)\n");
    let _ = writeln!(w, "## Per scene\n\nMedian misclassified % per scene.\n");
    table_by(w, &techniques, &scenes, records, |r, k| {
        r.scene == scenes[k]
    });
    let undefined: Vec<&CellRecord> = records.iter().filter(|r| !r.defined).collect();
    if !undefined.is_empty() {
        let _ = writeln!(
            w,
            "\n## Undefined cells\n\n| technique | cells | why |\n|---|---:|---|"
        );
        for t in &techniques {
            let of: Vec<&&CellRecord> = undefined.iter().filter(|r| &r.technique == t).collect();
            if of.is_empty() {
                continue;
            }
            let reasons = distinct(of.iter().filter_map(|r| r.undefined_reason.clone()));
            let _ = writeln!(w, "| {t} | {} | {} |", of.len(), reasons.join("; "));
        }
    }
    let _ = writeln!(
        w,
        "\n{TIME_HEADING}\n\nPer cell, milliseconds (median over the technique's defined cells): its planning, shadow pass and lookups (the technique's own cost), and the cell's whole measurement (with footprints and error attribution, every timing run; the frames' truths not included). Timings depend on the machine and the run; nothing above this section does.\n\n| technique | planning | shadow pass | lookup | whole cell | sum of whole cells, s |\n|---|---:|---:|---:|---:|---:|"
    );
    for t in &techniques {
        let of: Vec<&CellRecord> = records.iter().filter(|r| &r.technique == t).collect();
        let median = |f: fn(&CellRecord) -> Option<f64>| {
            quantile(&of.iter().filter_map(|r| f(r)).collect::<Vec<_>>(), 0.5)
        };
        let _ = writeln!(
            w,
            "| {t} | {} | {} | {} | {} | {:.2} |",
            cell(median(|r| r.planning_ms), 2),
            cell(median(|r| r.shadow_pass_ms), 2),
            cell(median(|r| r.lookup_ms), 2),
            cell(median(|r| Some(r.cell_ms)), 1),
            of.iter().map(|r| r.cell_ms).sum::<f64>() / 1e3
        );
    }
    md
}

/// A table of techniques × `header` columns, each entry the median misclassified % of the records
/// of that technique for which `in_column(record, column)`.
fn table_by(
    w: &mut String,
    techniques: &[String],
    header: &[String],
    records: &[CellRecord],
    in_column: impl Fn(&CellRecord, usize) -> bool,
) {
    let _ = writeln!(
        w,
        "| technique | {} |\n|---|{}",
        header.join(" | "),
        "---:|".repeat(header.len())
    );
    for t in techniques {
        let entries: Vec<String> = (0..header.len())
            .map(|k| {
                cell(
                    median_percent(records.iter(), |r| &r.technique == t && in_column(r, k)),
                    3,
                )
            })
            .collect();
        let _ = writeln!(w, "| {t} | {} |", entries.join(" | "));
    }
}

/// One line per technique, in the palette's order (dashed after the seventh), its points made by
/// `points(technique)`.
fn technique_series(
    techniques: &[String],
    points: impl Fn(&str) -> Vec<(f64, f64)>,
) -> Vec<Series> {
    techniques
        .iter()
        .enumerate()
        .map(|(k, t)| {
            let line = if k < 7 {
                LineStyle::Solid
            } else {
                LineStyle::Dashed
            };
            Series::new(t.clone(), points(t), k, line)
        })
        .collect()
}

/// A log axis's range over the finite `values`, widened by `margin` each way (at least a decade,
/// never below [`LOG_FLOOR`]).
fn log_range(values: impl Iterator<Item = f64>, margin: f64) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, 0.0f64), |(l, h), v| (l.min(v), h.max(v)));
    if lo.is_finite() {
        ((lo / margin).max(LOG_FLOOR), (hi * margin).max(lo * 10.0))
    } else {
        (LOG_FLOOR, 1.0)
    }
}

/// The two panels every sweep figure has — misclassified pixels (left) and the 99th-percentile
/// footprint (right) — as lines `errors` and `footprints` on axes made by `axes(left)` (x, y).
fn error_and_footprint(
    title: String,
    (errors, footprints): (Vec<Series>, Vec<Series>),
    axes: impl Fn(bool, &[Series]) -> (Axis, Axis),
    legend: LegendPosition,
) -> Figure {
    let panel = |caption: &str, left: bool, series: Vec<Series>| {
        let (x, y) = axes(left, &series);
        Panel {
            title: caption.into(),
            x,
            y,
            series,
            markers: Vec::new(),
            legend,
        }
    };
    Figure {
        title,
        panels: vec![
            panel("misclassified pixels, % of visible", true, errors),
            panel("texel footprint, 99th percentile", false, footprints),
        ],
        columns: 2,
        panel_width: 720,
        panel_height: 520,
    }
}

/// The axis label of a panel's measure.
fn measure_label(left: bool) -> &'static str {
    if left {
        "misclassified %"
    } else {
        "pixels per texel"
    }
}

/// The empirical distribution over the sweep's defined cells of each technique: the fraction of
/// its cells with at most x misclassified % (left) and at most x pixels per texel at the 99th
/// percentile (right), as staircases.
fn distribution(records: &[CellRecord]) -> Figure {
    let techniques = distinct(records.iter().map(|r| r.technique.clone()));
    let series = |value: fn(&CellRecord) -> Option<f64>| {
        technique_series(&techniques, |t| {
            let mut values: Vec<f64> = records
                .iter()
                .filter(|r| r.technique == t)
                .filter_map(value)
                .map(|v| v.max(LOG_FLOOR))
                .collect();
            values.sort_by(f64::total_cmp);
            #[expect(clippy::cast_precision_loss, reason = "cell counts")]
            let n = values.len() as f64;
            values
                .iter()
                .enumerate()
                .flat_map(|(j, v)| {
                    #[expect(clippy::cast_precision_loss, reason = "cell counts")]
                    let (below, at) = (j as f64 / n, (j + 1) as f64 / n);
                    [(*v, below), (*v, at)]
                })
                .collect()
        })
    };
    error_and_footprint(
        "The sweep's distributions: the fraction of each technique's defined cells at or below x"
            .into(),
        (series(percent), series(|r| r.footprint_p99)),
        |left, series| {
            let (lo, hi) = log_range(
                series.iter().flat_map(|s| s.points.iter().map(|p| p.0)),
                1.25,
            );
            (
                Axis::log(measure_label(left), lo, hi),
                Axis::linear("fraction of the technique's cells", 0.0, 1.0),
            )
        },
        LegendPosition::LowerRight,
    )
}

/// What a figure's x axis is.
#[derive(Clone, Copy)]
enum Versus {
    Gamma,
    Resolution,
}

/// Two panels against γ or resolution: each technique's median misclassified % and median
/// 99th-percentile footprint at each distinct x of the sweep.
fn against(records: &[CellRecord], versus: Versus) -> Figure {
    let techniques = distinct(records.iter().map(|r| r.technique.clone()));
    let x_of = |r: &CellRecord| match versus {
        // γ to a thousandth of a degree: the same placement in two scenes differs in its last bits.
        Versus::Gamma => (r.gamma_deg * GAMMA_PLOT_RESOLUTION).round() / GAMMA_PLOT_RESOLUTION,
        Versus::Resolution => f64::from(r.resolution),
    };
    let mut xs: Vec<f64> = records.iter().map(x_of).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let series = |value: fn(&CellRecord) -> Option<f64>| {
        technique_series(&techniques, |t| {
            xs.iter()
                .map(|x| {
                    let values: Vec<f64> = records
                        .iter()
                        .filter(|r| r.technique == t && x_of(r).to_bits() == x.to_bits())
                        .filter_map(value)
                        .collect();
                    let median = quantile(&values, 0.5);
                    (*x, median.map_or(f64::NAN, |v| v.max(LOG_FLOOR)))
                })
                .collect()
        })
    };
    let (x_axis, title) = match versus {
        Versus::Gamma => (
            Axis::linear("γ, angle between light and view (degrees)", 0.0, 90.0),
            "against γ",
        ),
        Versus::Resolution => {
            let lo = xs.first().copied().unwrap_or(1.0);
            let hi = xs.last().copied().unwrap_or(2.0);
            (
                Axis::log("shadow-map side (texels)", lo / 1.25, hi * 1.25),
                "against the shadow-map side",
            )
        }
    };
    error_and_footprint(
        format!("The sweep {title}: medians over cameras, lights, scenes and the other settings"),
        (series(percent), series(|r| r.footprint_p99)),
        |left, series| {
            let (lo, hi) = log_range(
                series.iter().flat_map(|s| s.points.iter().map(|p| p.1)),
                2.0,
            );
            (x_axis.clone(), Axis::log(measure_label(left), lo, hi))
        },
        LegendPosition::UpperRight,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_are_nearest_rank() {
        let v = [5.0, 1.0, 4.0, 2.0, 3.0];
        assert_eq!(quantile(&v, 0.5), Some(3.0));
        assert_eq!(quantile(&v, 0.9), Some(5.0));
        assert_eq!(quantile(&v, 0.0), Some(1.0));
        assert_eq!(quantile(&[], 0.5), None);
    }

    #[test]
    fn gamma_bins_cover_zero_to_ninety() {
        assert_eq!(gamma_bin(0.0), 0);
        assert_eq!(gamma_bin(14.999), 0);
        assert_eq!(gamma_bin(15.0), 1);
        assert_eq!(gamma_bin(90.0), bins() - 1);
    }
}
