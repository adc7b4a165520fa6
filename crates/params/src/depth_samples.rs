//! Depth samples under a filter kernel, validated once for every filterable map's moments
//! ([`crate::esm`], [`crate::evsm`], [`crate::msm`]): depths in `[0, 1]`, with weights.

use crate::error::ParamError;

/// `Ok(value)` if `value` is a depth in `[0, 1]`, else an error naming `name`.
pub(crate) fn unit_depth(name: &'static str, value: f64) -> Result<f64, ParamError> {
    ParamError::finite(name, value)?;
    ParamError::require(name, value, (0.0..=1.0).contains(&value), || {
        "in [0, 1]".into()
    })
}

/// Validated depth samples: every depth in `[0, 1]`, one finite weight `≥ 0` per depth (all 1 when
/// `weights` is `None`), and a finite positive total weight.
pub(crate) struct Samples<'a> {
    depths: &'a [f64],
    weights: Option<&'a [f64]>,
    total: f64,
}

impl<'a> Samples<'a> {
    /// `Err` names `depths` (empty, or a value not in `[0, 1]`) or `weights` (a length different from
    /// that of `depths`, a value that is negative or not finite, or a total that is 0 or overflows).
    pub(crate) fn new(depths: &'a [f64], weights: Option<&'a [f64]>) -> Result<Self, ParamError> {
        if depths.is_empty() {
            return Err(ParamError::OutOfDomain {
                name: "depths",
                value: 0.0,
                requirement: "non-empty".into(),
            });
        }
        for &d in depths {
            unit_depth("depths", d)?;
        }
        let total = match weights {
            None => depths.len() as f64,
            Some(w) => {
                if w.len() != depths.len() {
                    return Err(ParamError::OutOfDomain {
                        name: "weights",
                        value: w.len() as f64,
                        requirement: format!("one per depth ({})", depths.len()),
                    });
                }
                let mut total = 0.0;
                for &x in w {
                    ParamError::finite("weights", x)?;
                    ParamError::require("weights", x, x >= 0.0, || "at least 0".into())?;
                    total += x;
                }
                ParamError::finite("weights", total)?;
                ParamError::require("weights", total, total > 0.0, || "of positive sum".into())?
            }
        };
        Ok(Self {
            depths,
            weights,
            total,
        })
    }

    /// The sum of the weights, `W = Σ wᵢ` (finite, > 0).
    pub(crate) fn total(&self) -> f64 {
        self.total
    }

    /// The pairs `(dᵢ, wᵢ)` in the order given.
    pub(crate) fn iter(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.depths
            .iter()
            .enumerate()
            .map(|(i, &d)| (d, self.weights.map_or(1.0, |w| w[i])))
    }

    /// `Σ wᵢ f(dᵢ) / W`, summed in order, then clamped to the range of `f` over the samples of
    /// positive weight (where a mean lies; the clamp removes only rounding, and makes the mean of
    /// equal values exactly that value). The weights are divided by `W` first, so a term is never
    /// larger than the largest `|f(dᵢ)|` (no overflow from large weights).
    pub(crate) fn mean(&self, f: impl Fn(f64) -> f64) -> f64 {
        let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut sum = 0.0;
        for (d, w) in self.iter() {
            let value = f(d);
            if w > 0.0 {
                low = low.min(value);
                high = high.max(value);
            }
            sum += (w / self.total) * value;
        }
        sum.clamp(low, high)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_name_the_bad_input() {
        let bad = |depths: &[f64], weights: Option<&[f64]>| {
            Samples::new(depths, weights).err().map(|e| e.parameter())
        };
        assert_eq!(bad(&[], None), Some("depths"));
        assert_eq!(bad(&[0.5, 1.5], None), Some("depths"));
        assert_eq!(bad(&[0.5, f64::NAN], None), Some("depths"));
        assert_eq!(bad(&[0.5], Some(&[1.0, 2.0])), Some("weights"));
        assert_eq!(bad(&[0.5], Some(&[-1.0])), Some("weights"));
        assert_eq!(bad(&[0.5, 0.6], Some(&[0.0, 0.0])), Some("weights"));
        assert_eq!(
            bad(&[0.5, 0.6], Some(&[f64::MAX, f64::MAX])),
            Some("weights")
        );
        assert_eq!(bad(&[0.0, 1.0], Some(&[0.0, 2.0])), None);
        let s = Samples::new(&[0.25, 0.75], Some(&[1.0, 3.0])).unwrap();
        assert_eq!(s.mean(|d| d), 0.625);
        // Equal values have exactly that mean, whatever the rounding of the weights.
        let depths = [0.1 + 0.2; 7];
        let weights = [0.3, 0.1, 0.7, 0.1, 0.9, 0.3, 0.11];
        let s = Samples::new(&depths, Some(&weights)).unwrap();
        assert_eq!(s.mean(|d| d), depths[0]);
    }
}
