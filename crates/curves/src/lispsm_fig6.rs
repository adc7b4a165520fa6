//! LiSPSM Fig. 6: the perspective aliasing error dp/ds along z for view ⟂ light — uniform
//! (hyperbolic), PSM (linear), LiSPSM at n_opt (their minimax, eq. 3) and the logarithmic ideal.

use shadowlab_params::{lispsm, logarithmic};
use shadowlab_plot::{Axis, Figure, LegendPosition, LineStyle, Marker, Panel, Series, Table};

use crate::sampling::{depths, round_up};
use crate::{CurveConfig, CurvesError};

pub(crate) fn compute(config: &CurveConfig) -> Result<(Figure, Table), CurvesError> {
    let range = config.range();
    let n_opt = lispsm::n_opt(range);
    let mut table = Table::new(
        ["z", "uniform", "psm", "lispsm_n_opt", "logarithmic"]
            .map(String::from)
            .to_vec(),
    );
    for z in depths(range, true) {
        table.push(vec![
            z,
            lispsm::uniform_dp_ds(range, z)?,
            lispsm::psm_dp_ds(range, z)?,
            lispsm::dp_ds(range, n_opt, z)?,
            logarithmic::dp_ds(range),
        ])?;
    }
    let labels = [
        "uniform".to_owned(),
        "PSM (n = zn)".to_owned(),
        format!(
            "LiSPSM, n_opt = zn + √(zn·zf) = {}",
            (n_opt * 1e4).round() / 1e4
        ),
        "logarithmic ln(zf/zn)".to_owned(),
    ];
    let series = labels
        .into_iter()
        .enumerate()
        .map(|(i, label)| {
            let points = table
                .rows()
                .iter()
                .map(|row| (row[0], row[i + 1]))
                .collect();
            Series::new(label, points, i, LineStyle::Solid)
        })
        .collect();
    let panel = Panel {
        title: String::new(),
        x: Axis::linear("z (eye depth)", range.near(), range.far()),
        y: Axis::linear("dp/ds", 0.0, round_up(range.length() / range.near())),
        series,
        markers: vec![Marker {
            x: range.geometric_mean(),
            label: "√(zn·zf)".into(),
        }],
        legend: LegendPosition::UpperRight,
    };
    let title = format!(
        "LiSPSM Fig. 6: perspective aliasing dp/ds along z, light ⊥ view (zn = {}, zf = {})",
        range.near(),
        range.far()
    );
    Ok((Figure::single(title, panel), table))
}
