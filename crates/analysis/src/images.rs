//! Pictures of per-pixel measurements: a heat map on a logarithmic scale, and the keys that make
//! the study's pictures explain themselves — the heat map's colour bar and the legends of the
//! difference image and of its causes, as `shadowlab-plot` draws them ([`footprint_colour_bar`],
//! [`difference_legend`], [`causes_legend`]).
//!
//! # The colour map
//! viridis (Stéfan van der Walt and Nathaniel Smith, 2015; matplotlib's default, released CC0),
//! perceptually uniform, readable in greyscale and by colour-blind readers. It is given here by
//! ten control points, the colours at `k/9` for `k = 0, …, 9` as R's `viridisLite::viridis(10)`
//! lists them (`#440154` … `#FDE725`), and interpolated linearly in sRGB between them; dark
//! purple is the low end, yellow the high end, and the lightness rises monotonically.
//!
//! # The scale (stated here and on every annotated heat map's colour bar)
//! A value `v` sits at `f = (log v − log low)/(log high − log low)` along the map, clamped to
//! `[0, 1]`: below `low` it is the darkest colour, above `high` (and +∞) the brightest. For
//! footprints, [`HeatScale::PIXELS_PER_TEXEL`] spans 0.1 to 100 pixels per texel over three
//! decades, so each decade takes a third of the map: one pixel per texel (neither under- nor
//! oversampled) is at `f = 1/3`, the control point `#31688E` (blue); ten pixels per texel at
//! `2/3`, the control point `#35B779` (green). Pixels without a value (nothing visible, or the
//! value undefined or NaN) are [`NO_VALUE`].

use std::ops::AddAssign;

use rayon::prelude::*;
use shadowlab_plot::{Color, ColourBar, Scale, Swatch};

use crate::attribution::{Cause, Causes};
use crate::classify::{BACKGROUND, CORRECT_LIT, CORRECT_SHADOW, FALSELY_LIT, FALSELY_SHADOWED};
use crate::error::AnalysisError;
use crate::tally::{self, TALLY_CHUNK};

/// viridis at `k/9`, `k = 0, …, 9` (see the module docs for the source): the colour map's control
/// points, which a colour bar's gradient runs through.
pub const VIRIDIS: [[u8; 3]; 10] = [
    [0x44, 0x01, 0x54],
    [0x48, 0x28, 0x78],
    [0x3E, 0x4A, 0x89],
    [0x31, 0x68, 0x8E],
    [0x26, 0x82, 0x8E],
    [0x1F, 0x9E, 0x89],
    [0x35, 0xB7, 0x79],
    [0x6D, 0xCD, 0x59],
    [0xB4, 0xDE, 0x2C],
    [0xFD, 0xE7, 0x25],
];

/// The colour of pixels without a value: mid grey, which viridis never takes (its greys are
/// tinted), so holes stay visible.
pub const NO_VALUE: [u8; 3] = [128, 128, 128];

/// A logarithmic scale from `low` to `high`.
///
/// # Guarantees
/// `0 < low < high < ∞`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeatScale {
    low: f64,
    high: f64,
}

impl HeatScale {
    /// 0.1 to 100 pixels per texel: the range of footprints worth telling apart (module docs).
    pub const PIXELS_PER_TEXEL: Self = Self {
        low: 0.1,
        high: 100.0,
    };

    /// The logarithmic scale from `low` to `high`.
    ///
    /// # Errors
    /// [`AnalysisError::HeatScale`] unless `0 < low < high < ∞`.
    pub fn log(low: f64, high: f64) -> Result<Self, AnalysisError> {
        if low > 0.0 && low < high && high.is_finite() {
            Ok(Self { low, high })
        } else {
            Err(AnalysisError::HeatScale { low, high })
        }
    }

    /// The value at the darkest colour.
    #[must_use]
    pub fn low(&self) -> f64 {
        self.low
    }

    /// The value at the brightest colour.
    #[must_use]
    pub fn high(&self) -> f64 {
        self.high
    }

    /// Where `value` sits along the map, in `[0, 1]` (module docs); `None` for NaN.
    #[must_use]
    pub fn fraction(&self, value: f64) -> Option<f64> {
        if value.is_nan() {
            return None;
        }
        if value <= self.low {
            return Some(0.0);
        }
        let f = (value / self.low).ln() / (self.high / self.low).ln();
        Some(f.min(1.0))
    }
}

/// The colour map at `fraction ∈ [0, 1]` (clamped): viridis, linear in sRGB between its control
/// points.
#[must_use]
pub fn colour(fraction: f64) -> [u8; 3] {
    let last = VIRIDIS.len() - 1;
    #[expect(clippy::cast_precision_loss, reason = "ten control points")]
    let position = fraction.clamp(0.0, 1.0) * last as f64;
    #[expect(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        reason = "floor of a value in [0, 9]"
    )]
    let k = (position.floor() as usize).min(last - 1);
    #[expect(clippy::cast_precision_loss, reason = "ten control points")]
    let t = position - k as f64;
    let (a, b) = (VIRIDIS[k], VIRIDIS[k + 1]);
    std::array::from_fn(|c| {
        let value = f64::from(a[c]) + t * (f64::from(b[c]) - f64::from(a[c]));
        #[expect(
            clippy::cast_possible_truncation,
            clippy::cast_sign_loss,
            reason = "between two u8 values"
        )]
        let byte = value.round() as u8;
        byte
    })
}

/// `values` (row-major, `width × height`, row 0 at the bottom) as colours on `scale`: 8-bit sRGB in
/// the same layout, [`NO_VALUE`] where a value is `None` or NaN.
///
/// # Panics
/// If `values` does not hold `width × height` values.
#[must_use]
pub fn heatmap(values: &[Option<f64>], width: u32, height: u32, scale: HeatScale) -> Vec<[u8; 3]> {
    assert_eq!(
        values.len(),
        width as usize * height as usize,
        "heatmap: {} values for a {width} × {height} image",
        values.len()
    );
    values
        .par_iter()
        .map(|v| v.and_then(|v| scale.fraction(v)).map_or(NO_VALUE, colour))
        .collect()
}

/// The least and greatest finite value of `values` (`None` if there is none): the range a heat
/// map of them shows.
#[must_use]
pub fn value_range(values: &[Option<f64>]) -> Option<(f64, f64)> {
    values
        .iter()
        .flatten()
        .filter(|v| v.is_finite())
        .fold(None, |range, &v| match range {
            None => Some((v, v)),
            Some((low, high)) => Some((v.min(low), v.max(high))),
        })
}

/// The colour bar of a heat map on `scale`: `label` names the quantity and its unit, `range` the
/// least and greatest value the picture holds. Its gradient runs through [`VIRIDIS`] linearly in
/// sRGB, as [`colour`] does, so the bar is the map.
#[must_use]
pub fn colour_bar(label: &str, scale: HeatScale, range: Option<(f64, f64)>) -> ColourBar {
    ColourBar {
        label: label.to_owned(),
        scale: Scale::Log,
        low: scale.low,
        high: scale.high,
        stops: VIRIDIS.iter().map(|&[r, g, b]| Color(r, g, b)).collect(),
        range,
    }
}

/// The colour bar of the footprint heat map ([`HeatScale::PIXELS_PER_TEXEL`]).
#[must_use]
pub fn footprint_colour_bar(range: Option<(f64, f64)>) -> ColourBar {
    colour_bar(
        "texel footprint on screen (pixels per texel)",
        HeatScale::PIXELS_PER_TEXEL,
        range,
    )
}

/// What the footprint heat map's grey means.
pub const NO_VALUE_MEANING: &str =
    "no footprint: nothing visible, or a surface edge-on to the light";

/// The heat map's legend: its one colour off the map, [`NO_VALUE`].
#[must_use]
pub fn footprint_legend() -> Vec<Swatch> {
    let [r, g, b] = NO_VALUE;
    vec![Swatch {
        color: Color(r, g, b),
        label: NO_VALUE_MEANING.to_owned(),
    }]
}

/// How many pixels of a difference image ([`crate::classify::difference_image`]) have each of
/// its colours.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ClassCounts {
    /// [`FALSELY_LIT`]: falsely lit by some light.
    pub falsely_lit: u64,
    /// [`FALSELY_SHADOWED`]: falsely shadowed by some light, falsely lit by none.
    pub falsely_shadowed: u64,
    /// [`CORRECT_LIT`]: correct, lit by at least one light.
    pub correct_lit: u64,
    /// [`CORRECT_SHADOW`]: correct, lit by none.
    pub correct_shadow: u64,
    /// [`BACKGROUND`]: nothing visible.
    pub background: u64,
}

impl ClassCounts {
    /// Counts the classes of `difference`; a pixel of any other colour counts nowhere.
    #[must_use]
    pub fn of(difference: &[[u8; 3]]) -> Self {
        let mut counts = Self::default();
        for pixel in difference {
            match *pixel {
                FALSELY_LIT => counts.falsely_lit += 1,
                FALSELY_SHADOWED => counts.falsely_shadowed += 1,
                CORRECT_LIT => counts.correct_lit += 1,
                CORRECT_SHADOW => counts.correct_shadow += 1,
                BACKGROUND => counts.background += 1,
                _ => {}
            }
        }
        counts
    }

    /// The classes in the legend's order: colour, what it means, how many pixels.
    #[must_use]
    pub fn classes(&self) -> [([u8; 3], &'static str, u64); 5] {
        [
            (FALSELY_LIT, "falsely lit (light leak)", self.falsely_lit),
            (FALSELY_SHADOWED, "falsely shadowed", self.falsely_shadowed),
            (CORRECT_LIT, "correct, lit", self.correct_lit),
            (CORRECT_SHADOW, "correct, in shadow", self.correct_shadow),
            (BACKGROUND, "nothing visible", self.background),
        ]
    }
}

/// The difference image's legend: each class's colour, meaning and pixel count.
#[must_use]
pub fn difference_legend(counts: &ClassCounts) -> Vec<Swatch> {
    counts
        .classes()
        .iter()
        .map(|&([r, g, b], meaning, n)| Swatch {
            color: Color(r, g, b),
            label: format!("{meaning}: {n} px"),
        })
        .collect()
}

/// How many pixels of a causes picture ([`crate::attribution::cause_image`]) have each of its
/// colours.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CauseCounts {
    /// Per cause, the pixels it colours: those where it is the first cause of some light's error.
    pub first: Causes,
    /// [`CORRECT_LIT`]: correct, lit by at least one light.
    pub correct_lit: u64,
    /// [`CORRECT_SHADOW`]: correct, lit by none.
    pub correct_shadow: u64,
    /// [`BACKGROUND`]: nothing visible.
    pub background: u64,
}

impl CauseCounts {
    /// Counts the classes of `causes`; a pixel of any other colour counts nowhere. In parallel
    /// over chunks of pixels whose counts are summed (`tally`): the same on any thread count.
    #[must_use]
    pub fn of(causes: &[[u8; 3]]) -> Self {
        tally::total(causes.par_chunks(TALLY_CHUNK).map(|chunk| {
            let mut counts = Self::default();
            for &pixel in chunk {
                if let Some(cause) = Cause::ALL.into_iter().find(|c| c.colour() == pixel) {
                    counts.first.count(cause);
                    continue;
                }
                match pixel {
                    CORRECT_LIT => counts.correct_lit += 1,
                    CORRECT_SHADOW => counts.correct_shadow += 1,
                    BACKGROUND => counts.background += 1,
                    _ => {}
                }
            }
            counts
        }))
    }

    /// The classes in the legend's order — the causes in precedence order, then correct lit,
    /// correct in shadow and nothing visible: colour, what it means, how many pixels, and the
    /// class's name in `report.html` (`count-NAME`).
    #[must_use]
    pub fn classes(&self) -> Vec<([u8; 3], &'static str, u64, &'static str)> {
        Cause::ALL
            .into_iter()
            .map(|c| (c.colour(), c.meaning(), self.first.of(c), c.label()))
            .chain([
                (
                    CORRECT_LIT,
                    "correct, lit",
                    self.correct_lit,
                    "causes-correct-lit",
                ),
                (
                    CORRECT_SHADOW,
                    "correct, in shadow",
                    self.correct_shadow,
                    "causes-correct-shadow",
                ),
                (
                    BACKGROUND,
                    "nothing visible",
                    self.background,
                    "causes-background",
                ),
            ])
            .collect()
    }
}

impl AddAssign for CauseCounts {
    fn add_assign(&mut self, other: Self) {
        self.first += other.first;
        self.correct_lit += other.correct_lit;
        self.correct_shadow += other.correct_shadow;
        self.background += other.background;
    }
}

/// The causes picture's legend: each class's colour, meaning and pixel count.
#[must_use]
pub fn causes_legend(counts: &CauseCounts) -> Vec<Swatch> {
    counts
        .classes()
        .iter()
        .map(|&([r, g, b], meaning, n, _)| Swatch {
            color: Color(r, g, b),
            label: format!("{meaning}: {n} px"),
        })
        .collect()
}
