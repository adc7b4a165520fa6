//! CAD Fig. 7: the generalised LiSPSM parameter n'(γ) of eq. 16 for each fall-back curve r(γ)
//! (eq. 17, the reconstructed eq. 18, sin²), over the raw equal-error branches n'_1 and n'_2 of
//! eq. 13 and the model's true minimax (formulas.md §5.8).

use shadowlab_params::cad::{self, Falloff};
use shadowlab_params::{ModelCase, gmnpr};
use shadowlab_plot::{Axis, Figure, LegendPosition, LineStyle, Marker, Panel, Series, Table};

use crate::sampling::{angle, angles_degrees};
use crate::{CurveConfig, CurvesError};

pub(crate) fn compute(config: &CurveConfig) -> Result<(Figure, Table), CurvesError> {
    let m = config.model();
    let mut columns = vec!["gamma_deg".to_owned(), "n1_raw".into(), "n2_raw".into()];
    columns.extend(Falloff::ALL.map(|f| format!("n_{}", f.key())));
    columns.push("n_minimax".into());
    let mut table = Table::new(columns);
    for degrees in angles_degrees() {
        let gamma = angle(degrees)?;
        let narrow = m.case(gamma) == ModelCase::Narrow;
        let mut row = vec![
            degrees,
            cad::n1(m, gamma),
            if narrow { cad::n2(m, gamma) } else { f64::NAN },
        ];
        row.extend(Falloff::ALL.map(|f| cad::n_prime(m, gamma, f)));
        row.push(gmnpr::lambda_minimax(m, gamma).near_distance(m.warp_depth(gamma)));
        table.push(row)?;
    }
    let column =
        |i: usize| -> Vec<(f64, f64)> { table.rows().iter().map(|row| (row[0], row[i])).collect() };
    let mut series = vec![
        Series::new("raw n'₁ (eq. 13)", column(1), 6, LineStyle::Dotted),
        Series::new("raw n'₂ (eq. 13)", column(2), 5, LineStyle::Dotted),
    ];
    for (i, falloff) in Falloff::ALL.into_iter().enumerate() {
        let label = format!("n' eq. 16, {}", falloff.formula());
        series.push(Series::new(label, column(3 + i), i, LineStyle::Solid));
    }
    series.push(Series::new(
        "minimax of the model (§5.8)",
        column(6),
        6,
        LineStyle::Dashed,
    ));

    let b = m.far_half_height();
    let top = b.max(4.0 * cad::n1(m, shadowlab_params::LightAngle::PERPENDICULAR));
    let panel = Panel {
        title: String::new(),
        x: Axis::linear("γ (degrees between light and view)", 0.0, 90.0),
        y: Axis::linear("n' (warp near distance)", -1.05 * b, 1.05 * top),
        series,
        markers: vec![
            Marker {
                x: cad::gamma0(m).degrees(),
                label: "γ₀".into(),
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
        legend: LegendPosition::LowerRight,
    };
    let title = format!(
        "CAD Fig. 7: generalised LiSPSM parameter n'(γ), eq. 16 ({})",
        config.describe()
    );
    Ok((Figure::single(title, panel), table))
}
