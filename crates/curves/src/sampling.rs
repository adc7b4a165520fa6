//! The fixed grids every figure samples on, and axis ranges fitted to the data.

use shadowlab_params::{DepthRange, LightAngle, ParamError};

/// Steps of the light-angle grid over `[0°, 90°]` (0.05° apart).
const ANGLE_STEPS: u32 = 1800;
/// Steps of the depth grid over `[n, f]`.
const DEPTH_STEPS: u32 = 1000;

/// The light angles of every angle sweep, in degrees: `0, 0.05, …, 90`, exact at both ends.
pub(crate) fn angles_degrees() -> Vec<f64> {
    (0..=ANGLE_STEPS)
        .map(|i| 90.0 * f64::from(i) / f64::from(ANGLE_STEPS))
        .collect()
}

/// The angle of `degrees` from the grid.
pub(crate) fn angle(degrees: f64) -> Result<LightAngle, ParamError> {
    LightAngle::from_degrees(degrees)
}

/// Depths over the range, evenly spaced (`linear`) or geometrically, exact at both ends.
pub(crate) fn depths(range: DepthRange, linear: bool) -> Vec<f64> {
    (0..=DEPTH_STEPS)
        .map(|i| {
            let t = f64::from(i) / f64::from(DEPTH_STEPS);
            if linear {
                range.lerp(t)
            } else {
                range.geometric_lerp(t)
            }
        })
        .collect()
}

/// The smallest span of whole decades `[10^a, 10^b]` containing the finite positive values, with
/// `a` no lower than `10^floor` (so that values tending to 0 do not flatten the rest).
pub(crate) fn decades(values: impl IntoIterator<Item = f64>, floor: f64) -> (f64, f64) {
    let (mut low, mut high) = (f64::INFINITY, 0.0f64);
    for v in values.into_iter().filter(|v| v.is_finite() && *v > 0.0) {
        low = low.min(v);
        high = high.max(v);
    }
    if high == 0.0 {
        return (1.0, 10.0);
    }
    let a = low.log10().floor().max(floor);
    let b = high.log10().ceil().max(a + 1.0);
    (10f64.powf(a), 10f64.powf(b))
}

/// A round upper end for a linear axis from 0 showing values up to `max`: 1, 2 or 5 times a power
/// of ten, at least `max`.
pub(crate) fn round_up(max: f64) -> f64 {
    if !(max.is_finite() && max > 0.0) {
        return 1.0;
    }
    let decade = 10f64.powf(max.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&v| v >= max)
        .unwrap_or(10.0 * decade)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grids_are_exact_at_their_ends() {
        let a = angles_degrees();
        assert_eq!((a[0], a[a.len() - 1]), (0.0, 90.0));
        let r = DepthRange::new(1.0, 100.0).unwrap();
        for linear in [true, false] {
            let z = depths(r, linear);
            assert_eq!((z[0], z[z.len() - 1]), (1.0, 100.0));
        }
    }

    #[test]
    fn ranges_are_round() {
        assert_eq!(
            decades([0.05, 3.0, f64::NAN, -1.0, 12.0], -3.0),
            (0.01, 100.0)
        );
        assert_eq!(decades([1e-9, 5.0], -3.0), (0.001, 10.0));
        assert_eq!(round_up(99.0), 100.0);
        assert_eq!(round_up(101.0), 200.0);
        assert_eq!(round_up(0.3), 0.5);
    }
}
