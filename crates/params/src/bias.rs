//! The depth-bias family of the CAD survey's Table 1 (CAD eq. 1; formulas.md §4.1):
//! `z_map = z1 + z_bias(z1, z2)`, with `z1` and `z2` the depths of the first and second surfaces
//! seen from the light. A receiver at depth `z` is lit when `z ≤ z_map`.

use crate::error::ParamError;

/// How the stored shadow-map depth is offset from the nearest surface's depth `z1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DepthBias {
    /// (a) Williams: `z_bias = z_offset`, a constant in depth units.
    Constant {
        /// The offset added to `z1`; finite.
        offset: f64,
    },
    /// (b) Wang & Molnar's second-depth: `z_bias = z2 − z1`, i.e. `z_map = z2`. Needs closed, thick
    /// solids.
    SecondDepth,
    /// (c) Woo's midpoint: `z_bias = (z2 − z1)/2`.
    Midpoint,
    /// (d) Dual depth: `z_bias = min((z2 − z1)/2, z_max)`, the midpoint capped by a user bound so
    /// that thick objects do not unshadow themselves.
    DualDepth {
        /// `z_max ≥ 0`, the cap on the bias, in depth units.
        max_bias: f64,
    },
}

impl DepthBias {
    /// A short stable name: `constant`, `second-depth`, `midpoint`, `dual-depth`.
    #[must_use]
    pub fn key(&self) -> &'static str {
        match self {
            Self::Constant { .. } => "constant",
            Self::SecondDepth => "second-depth",
            Self::Midpoint => "midpoint",
            Self::DualDepth { .. } => "dual-depth",
        }
    }

    /// `z_bias(z1, z2)`. `z2 = +∞` means there is no second surface behind the first (the map was
    /// cleared there): second-depth and midpoint then give `+∞` (always lit), dual-depth its cap.
    /// `Err` names `z1` (not finite), `z2` (NaN or less than `z1`), `offset` or `max_bias`.
    pub fn z_bias(&self, z1: f64, z2: f64) -> Result<f64, ParamError> {
        ParamError::finite("z1", z1)?;
        ParamError::require("z2", z2, z2 >= z1, || format!("at least z1 ({z1})"))?;
        match *self {
            Self::Constant { offset } => ParamError::finite("offset", offset),
            Self::SecondDepth => Ok(z2 - z1),
            Self::Midpoint => Ok((z2 - z1) / 2.0),
            Self::DualDepth { max_bias } => {
                ParamError::finite("max_bias", max_bias)?;
                ParamError::require("max_bias", max_bias, max_bias >= 0.0, || {
                    "at least 0".into()
                })?;
                Ok(((z2 - z1) / 2.0).min(max_bias))
            }
        }
    }

    /// `z_map = z1 + z_bias(z1, z2)` (CAD eq. 1). Same domain as [`Self::z_bias`].
    pub fn z_map(&self, z1: f64, z2: f64) -> Result<f64, ParamError> {
        Ok(z1 + self.z_bias(z1, z2)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_1_of_the_cad_survey() {
        let (z1, z2) = (0.25, 0.75);
        assert_eq!(
            DepthBias::Constant { offset: 0.01 }.z_map(z1, z2).unwrap(),
            0.26
        );
        assert_eq!(DepthBias::SecondDepth.z_map(z1, z2).unwrap(), z2);
        assert_eq!(DepthBias::Midpoint.z_map(z1, z2).unwrap(), 0.5);
        assert_eq!(
            DepthBias::DualDepth { max_bias: 0.125 }
                .z_map(z1, z2)
                .unwrap(),
            0.375
        );
        assert_eq!(
            DepthBias::DualDepth { max_bias: 1.0 }
                .z_map(z1, z2)
                .unwrap(),
            0.5
        );
    }

    #[test]
    fn no_second_surface() {
        let inf = f64::INFINITY;
        assert_eq!(DepthBias::SecondDepth.z_map(0.5, inf).unwrap(), inf);
        assert_eq!(DepthBias::Midpoint.z_map(0.5, inf).unwrap(), inf);
        assert_eq!(
            DepthBias::DualDepth { max_bias: 0.25 }
                .z_map(0.5, inf)
                .unwrap(),
            0.75
        );
    }

    #[test]
    fn bad_inputs_are_named() {
        let m = DepthBias::Midpoint;
        assert_eq!(m.z_map(f64::NAN, 1.0).unwrap_err().parameter(), "z1");
        assert_eq!(m.z_map(0.5, 0.25).unwrap_err().parameter(), "z2");
        assert_eq!(m.z_map(0.5, f64::NAN).unwrap_err().parameter(), "z2");
        let d = DepthBias::DualDepth { max_bias: -1.0 };
        assert_eq!(d.z_map(0.5, 0.6).unwrap_err().parameter(), "max_bias");
        let c = DepthBias::Constant { offset: f64::NAN };
        assert_eq!(c.z_map(0.5, 0.6).unwrap_err().parameter(), "offset");
    }
}
