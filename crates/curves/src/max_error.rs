//! Every parameter rule's maximum perspective error over the view axis, max F over [n, f], against
//! the light angle γ — the comparison none of the papers draws. The minimax of formulas.md §5.8 is the
//! lower envelope of all of them by construction; the figure shows by how much each rule misses it.
//! γ = 0 is left out: there F is unbounded for every rule.

use shadowlab_params::cad::{self, Falloff};
use shadowlab_params::{ParameterRule, gmnpr};
use shadowlab_plot::{Axis, Figure, LegendPosition, LineStyle, Marker, Panel, Series, Table};

use crate::sampling::{angle, angles_degrees, decades};
use crate::{CurveConfig, CurvesError};

/// Colour and dash of each rule; the CAD fall-back curves share a colour.
fn style(rule: ParameterRule) -> (usize, LineStyle) {
    match rule {
        ParameterRule::Uniform => (6, LineStyle::Dotted),
        ParameterRule::Lispsm => (0, LineStyle::Solid),
        ParameterRule::LispsmDeltaZ => (5, LineStyle::Solid),
        ParameterRule::Cad(Falloff::Eq18) => (1, LineStyle::Solid),
        ParameterRule::Cad(Falloff::Eq17) => (1, LineStyle::Dashed),
        ParameterRule::Cad(Falloff::SinSquared) => (1, LineStyle::Dotted),
        ParameterRule::Gmnpr => (2, LineStyle::Solid),
        ParameterRule::Glpr => (3, LineStyle::Solid),
        ParameterRule::Minimax => (6, LineStyle::Dashed),
    }
}

pub(crate) fn compute(config: &CurveConfig) -> Result<(Figure, Table), CurvesError> {
    let m = config.model();
    let mut columns = vec!["gamma_deg".to_owned()];
    columns.extend(ParameterRule::ALL.map(|r| r.key().to_owned()));
    let mut table = Table::new(columns);
    for degrees in angles_degrees().into_iter().filter(|&d| d > 0.0) {
        let gamma = angle(degrees)?;
        let mut row = vec![degrees];
        row.extend(ParameterRule::ALL.map(|rule| {
            rule.warp(m, gamma)
                .map_or(f64::NAN, |warp| gmnpr::max_error(m, gamma, warp))
        }));
        table.push(row)?;
    }
    let series: Vec<Series> = ParameterRule::ALL
        .into_iter()
        .enumerate()
        .map(|(i, rule)| {
            let points = table
                .rows()
                .iter()
                .map(|row| (row[0], row[i + 1]))
                .collect();
            let (color, line) = style(rule);
            Series::new(rule.label(), points, color, line)
        })
        .collect();
    let (low, high) = decades(
        table.rows().iter().flat_map(|row| row[1..].iter().copied()),
        -3.0,
    );
    let panel = Panel {
        title: String::new(),
        x: Axis::linear("γ (degrees between light and view)", 0.0, 90.0),
        y: Axis::log("max F over [n, f]", low, high),
        series,
        markers: vec![
            Marker {
                x: gmnpr::theta0(m).degrees(),
                label: "θ₀".into(),
            },
            Marker {
                x: gmnpr::theta1(m).degrees(),
                label: "θ₁".into(),
            },
            Marker {
                x: m.half_fov().degrees(),
                label: "φ".into(),
            },
            Marker {
                x: cad::gamma_lim(m).degrees(),
                label: "γ_lim".into(),
            },
        ],
        legend: LegendPosition::UpperRight,
    };
    let title = format!(
        "Maximum perspective error of every parameter rule against γ ({})",
        config.describe()
    );
    Ok((Figure::single(title, panel), table))
}
