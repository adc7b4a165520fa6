//! Split positions against the light angle: the CAD survey's adaptive scheme (eq. 19), which blends
//! the logarithmic split (eq. 5, its value at γ = 90°) towards a fixed-ratio limit as the light turns
//! towards the view, beside the practical split (Zhang et al.) and the logarithmic split, which do not
//! depend on γ.

use shadowlab_params::splits::SplitScheme;
use shadowlab_plot::{Axis, Figure, LegendPosition, LineStyle, Panel, Series, Table};

use crate::sampling::{angle, angles_degrees};
use crate::{CurveConfig, CurvesError};

pub(crate) fn compute(config: &CurveConfig) -> Result<(Figure, Table), CurvesError> {
    let range = config.range();
    let k = config.partitions();
    let delta = config.adaptive_delta();
    let weight = config.practical_weight();
    let practical = SplitScheme::Practical { weight }.boundaries(range, k)?;
    let logarithmic = SplitScheme::Logarithmic.boundaries(range, k)?;
    let interior = 1..k;
    let mut columns = vec!["gamma_deg".to_owned()];
    for scheme in ["adaptive", "practical", "logarithmic"] {
        columns.extend(interior.clone().map(|i| format!("{scheme}_b{i}")));
    }
    let mut table = Table::new(columns);
    let mut effective_delta = delta;
    for degrees in angles_degrees() {
        let scheme = SplitScheme::Adaptive {
            delta,
            gamma: angle(degrees)?,
        };
        effective_delta = scheme.effective_delta(range, k).unwrap_or(delta);
        let adaptive = scheme.boundaries(range, k)?;
        let mut row = vec![degrees];
        for b in [&adaptive, &practical, &logarithmic] {
            row.extend(&b[interior.clone()]);
        }
        table.push(row)?;
    }
    let mut series = Vec::new();
    for (s, (name, line)) in [
        ("eq. 19 adaptive", LineStyle::Solid),
        ("practical", LineStyle::Dashed),
        ("eq. 5 logarithmic", LineStyle::Dotted),
    ]
    .into_iter()
    .enumerate()
    {
        for (j, i) in interior.clone().enumerate() {
            let column = 1 + s * (k - 1) + j;
            let points = table
                .rows()
                .iter()
                .map(|row| (row[0], row[column]))
                .collect();
            series.push(Series::new(format!("{name} b{i}"), points, j, line));
        }
    }
    let clamp = if effective_delta < delta {
        format!(", δ clamped to {effective_delta:.4}")
    } else {
        String::new()
    };
    let panel = Panel {
        title: String::new(),
        x: Axis::linear("γ (degrees between light and view)", 0.0, 90.0),
        // A decade above f leaves the legend room clear of the lines.
        y: Axis::log("split depth", range.near(), 10.0 * range.far()),
        series,
        markers: Vec::new(),
        legend: LegendPosition::UpperLeft,
    };
    let title = format!(
        "Split positions vs γ: CAD eq. 19 (δ = {delta}{clamp}), practical (λ = {weight}), eq. 5; k = {k}, n = {}, f = {}",
        range.near(),
        range.far()
    );
    Ok((Figure::single(title, panel), table))
}
