//! GMNPR Fig. 5: the warp parameter λ against the light angle θ — GMNPR's selection (eq. 8), the
//! raw equal-error λ1 and λ2 (eq. 4), LiSPSM's λ (eq. 9), GLPR, and the model's true minimax.

use shadowlab_params::{ModelCase, WarpParameter, gmnpr};
use shadowlab_plot::{Axis, Figure, LegendPosition, LineStyle, Marker, Panel, Series, Table};

use crate::sampling::{angle, angles_degrees};
use crate::{CurveConfig, CurvesError};

pub(crate) fn compute(config: &CurveConfig) -> Result<(Figure, Table), CurvesError> {
    let m = config.model();
    let names = [
        "theta_deg",
        "gmnpr",
        "lispsm",
        "glpr",
        "minimax",
        "lambda1_raw",
        "lambda2_raw",
    ];
    let mut table = Table::new(names.map(String::from).to_vec());
    for degrees in angles_degrees() {
        let theta = angle(degrees)?;
        let wide = m.case(theta) == ModelCase::Wide;
        table.push(vec![
            degrees,
            gmnpr::lambda_gmnpr(m, theta).lambda(),
            gmnpr::lambda_lispsm(m, theta).lambda(),
            gmnpr::lambda_glpr(m, theta).map_or(f64::NAN, WarpParameter::lambda),
            gmnpr::lambda_minimax(m, theta).lambda(),
            if wide {
                gmnpr::lambda1(m, theta)
            } else {
                f64::NAN
            },
            if wide {
                f64::NAN
            } else {
                gmnpr::lambda2(m, theta)
            },
        ])?;
    }
    let column =
        |i: usize| -> Vec<(f64, f64)> { table.rows().iter().map(|row| (row[0], row[i])).collect() };
    let series = vec![
        Series::new("λ_GMNPR (eq. 8)", column(1), 2, LineStyle::Solid),
        Series::new("λ_LiSPSM (eq. 9)", column(2), 0, LineStyle::Solid),
        Series::new("λ_GLPR (ϕ = 0)", column(3), 3, LineStyle::Solid),
        Series::new("λ minimax (§5.8)", column(4), 6, LineStyle::Dashed),
        Series::new("raw λ₁ (eq. 4)", column(5), 1, LineStyle::Dotted),
        Series::new("raw λ₂ (eq. 4)", column(6), 4, LineStyle::Dotted),
    ];
    let panel = Panel {
        title: String::new(),
        x: Axis::linear("θ (degrees between light and view)", 0.0, 90.0),
        y: Axis::log("λ = n'/(f' − n')", 1e-3, 1e3),
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
        ],
        legend: LegendPosition::UpperRight,
    };
    let title = format!(
        "GMNPR Fig. 5: warp parameter λ against θ ({})",
        config.describe()
    );
    Ok((Figure::single(title, panel), table))
}
