//! GMNPR Fig. 6: the aliasing distribution F(z) at several light angles — LiSPSM's and GMNPR's
//! parameters (the paper's two rows) and the model's minimax (a third row), on a linear scale for
//! θ ≥ φ and a log10 scale for θ ≤ φ, as in the paper.

use shadowlab_params::{FrustumModel, LightAngle, WarpParameter, gmnpr};
use shadowlab_plot::{Axis, Figure, LegendPosition, LineStyle, Panel, Series, Table};

use crate::sampling::{decades, depths, round_up};
use crate::{CurveConfig, CurvesError};

/// Angles of the wide column, as fractions of the way from φ to 90° (90°, 75°, 60°, 45°, 30° for
/// φ = 30°).
const WIDE_FRACTIONS: [f64; 5] = [1.0, 0.75, 0.5, 0.25, 0.0];
/// Angles of the narrow column, as fractions of φ (30°, 20°, 10°, 5°, 1° for φ = 30°).
const NARROW_FRACTIONS: [f64; 5] = [1.0, 2.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0, 1.0 / 30.0];

/// A row of the figure: a parameter rule.
struct Row {
    key: &'static str,
    label: &'static str,
    warp: fn(&FrustumModel, LightAngle) -> WarpParameter,
}

const ROWS: [Row; 3] = [
    Row {
        key: "lispsm",
        label: "F_LiSPSM",
        warp: gmnpr::lambda_lispsm,
    },
    Row {
        key: "gmnpr",
        label: "F_GMNPR",
        warp: gmnpr::lambda_gmnpr,
    },
    Row {
        key: "minimax",
        label: "F_minimax (§5.8)",
        warp: gmnpr::lambda_minimax,
    },
];

pub(crate) fn compute(config: &CurveConfig) -> Result<(Figure, Table), CurvesError> {
    let m = config.model();
    let phi = m.half_fov().degrees();
    let wide: Vec<f64> = WIDE_FRACTIONS
        .iter()
        .map(|t| phi + t * (90.0 - phi))
        .collect();
    let narrow: Vec<f64> = NARROW_FRACTIONS.iter().map(|t| t * phi).collect();
    let z = depths(config.range(), true);

    // One column per (row, angle): the wide angles, then the narrow ones.
    let mut columns = vec!["z".to_owned()];
    let mut curves: Vec<Vec<f64>> = Vec::new();
    for row in &ROWS {
        for &degrees in wide.iter().chain(&narrow) {
            let theta = LightAngle::from_degrees(degrees)?;
            let warp = (row.warp)(m, theta);
            columns.push(format!("{}_theta{}", row.key, trim(degrees)));
            curves.push(
                z.iter()
                    .map(|&z| gmnpr::error(m, theta, warp, z))
                    .collect::<Result<_, _>>()?,
            );
        }
    }
    let mut table = Table::new(columns);
    for (i, &depth) in z.iter().enumerate() {
        let mut values = vec![depth];
        values.extend(curves.iter().map(|c| c[i]));
        table.push(values)?;
    }

    let per_row = wide.len() + narrow.len();
    let wide_top = round_up(
        curves
            .iter()
            .enumerate()
            .filter(|(i, _)| i % per_row < wide.len())
            .flat_map(|(_, c)| c.iter().copied())
            .fold(0.0, f64::max),
    );
    let narrow_range = decades(
        curves
            .iter()
            .enumerate()
            .filter(|(i, _)| i % per_row >= wide.len())
            .flat_map(|(_, c)| c.iter().copied()),
        -3.0,
    );
    let x = Axis::linear("z (eye depth)", config.range().near(), config.range().far());
    let mut panels = Vec::new();
    for (r, row) in ROWS.iter().enumerate() {
        for (narrow_column, angles) in [(false, &wide), (true, &narrow)] {
            let offset = r * per_row + if narrow_column { wide.len() } else { 0 };
            let series = angles
                .iter()
                .enumerate()
                .map(|(i, &degrees)| {
                    let points = z
                        .iter()
                        .copied()
                        .zip(curves[offset + i].iter().copied())
                        .collect();
                    Series::new(
                        format!("θ = {}°", trim(degrees)),
                        points,
                        i,
                        LineStyle::Solid,
                    )
                })
                .collect();
            let (title, y) = if narrow_column {
                (
                    format!("{}, 0 ≤ θ ≤ φ (log scale)", row.label),
                    Axis::log("F", narrow_range.0, narrow_range.1),
                )
            } else {
                (
                    format!("{}, φ ≤ θ ≤ 90°", row.label),
                    Axis::linear("F", 0.0, wide_top),
                )
            };
            panels.push(Panel {
                title,
                x: x.clone(),
                y,
                series,
                markers: Vec::new(),
                legend: LegendPosition::UpperRight,
            });
        }
    }
    let figure = Figure {
        title: format!(
            "GMNPR Fig. 6: aliasing distributions F(z) ({})",
            config.describe()
        ),
        panels,
        columns: 2,
        panel_width: 720,
        panel_height: 460,
    };
    Ok((figure, table))
}

/// An angle in degrees without trailing zeros: 30, 7.5, 0.333.
fn trim(degrees: f64) -> String {
    let text = format!("{degrees:.3}");
    text.trim_end_matches('0').trim_end_matches('.').to_owned()
}
