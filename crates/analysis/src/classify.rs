//! Misclassified pixels: where a technique's shadow test disagrees with the truth.
//!
//! A technique's frame gives, per light and pixel, the lit fraction of the visible point
//! (`shadowlab_shadow::Frame::lit`: 1 lit, 0 shadowed, fractions from filters). It **counts as
//! lit when the fraction is at least [`LIT_THRESHOLD`] = ½**: a filtered lookup says "lit" when
//! most of its taps do, the nearest-texel lookup is 0 or 1 and is unaffected. Against a
//! [`Truth`] each judged (light, pixel) pair is then correct, *falsely lit* (a light leak: lit
//! where the point is in shadow) or *falsely shadowed* (acne, over-shadowing: shadowed where the
//! point is lit). A pair is judged where a surface is visible and, for a spot light, lies inside
//! its cone ([`Truth::outside_cone`]: outside it the cone darkens the point whatever the map says).
//! Counts are summed over lights.

use std::ops::AddAssign;

use rayon::prelude::*;
use shadowlab_raster::{EyeImage, NO_TRIANGLE};

use crate::tally::{self, TALLY_CHUNK};
use crate::truth::{LIT_THRESHOLD, Truth};

/// How many judged (light, pixel) pairs a technique got wrong, and how.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Misclassification {
    /// The (light, pixel) pairs judged: a surface visible and inside the light's cone.
    pub visible: u64,
    /// Lit by the technique, in shadow in truth.
    pub falsely_lit: u64,
    /// Shadowed by the technique, lit in truth.
    pub falsely_shadowed: u64,
}

impl Misclassification {
    /// Falsely lit plus falsely shadowed.
    #[must_use]
    pub fn total(&self) -> u64 {
        self.falsely_lit + self.falsely_shadowed
    }

    /// The misclassified share of the judged pairs, in percent; 0 when none was judged.
    #[must_use]
    pub fn percentage(&self) -> f64 {
        if self.visible == 0 {
            return 0.0;
        }
        #[expect(
            clippy::cast_precision_loss,
            reason = "pixel counts are far below 2^53"
        )]
        let share = self.total() as f64 / self.visible as f64;
        100.0 * share
    }
}

impl AddAssign for Misclassification {
    fn add_assign(&mut self, other: Self) {
        self.visible += other.visible;
        self.falsely_lit += other.falsely_lit;
        self.falsely_shadowed += other.falsely_shadowed;
    }
}

/// Counts one light's pairs: `truth` and `outside_cone` per pixel, `judged(pixel)` the compared
/// classification (`None`: not judged there); in parallel over chunks of pixels whose counts are
/// summed (`tally`).
pub(crate) fn compare(
    truth: &[Option<bool>],
    outside_cone: &[bool],
    judged: impl Fn(usize) -> Option<bool> + Sync,
) -> Misclassification {
    tally::total(
        truth
            .par_chunks(TALLY_CHUNK)
            .zip(outside_cone.par_chunks(TALLY_CHUNK))
            .enumerate()
            .map(|(chunk, (truth, outside_cone))| {
                let first = chunk * TALLY_CHUNK;
                let mut count = Misclassification::default();
                for (k, (truth, outside)) in truth.iter().zip(outside_cone).enumerate() {
                    let (Some(truly_lit), false) = (*truth, *outside) else {
                        continue;
                    };
                    let Some(lit) = judged(first + k) else {
                        continue;
                    };
                    count.visible += 1;
                    match (lit, truly_lit) {
                        (true, false) => count.falsely_lit += 1,
                        (false, true) => count.falsely_shadowed += 1,
                        _ => {}
                    }
                }
                count
            }),
    )
}

/// The misclassified pairs of a technique whose lit fractions are `lit` (per light, per pixel, as
/// `shadowlab_shadow::Frame::lit`), judged against `truth`; see the module docs.
///
/// # Panics
/// If `lit` and `truth` differ in their numbers of lights or pixels.
#[must_use]
pub fn misclassification(truth: &Truth, lit: &[Vec<f64>]) -> Misclassification {
    check_shapes(truth, lit);
    let mut total = Misclassification::default();
    for (light, fractions) in lit.iter().enumerate() {
        total += compare(&truth.lit[light], &truth.outside_cone[light], |pixel| {
            Some(fractions[pixel] >= LIT_THRESHOLD)
        });
    }
    total
}

/// A pixel falsely lit by some light (a light leak): Okabe and Ito's vermillion.
pub const FALSELY_LIT: [u8; 3] = [213, 94, 0];
/// A pixel falsely shadowed by some light, and falsely lit by none: Okabe and Ito's blue.
pub const FALSELY_SHADOWED: [u8; 3] = [0, 114, 178];
/// A pixel every light classifies correctly and at least one lights: light grey.
pub const CORRECT_LIT: [u8; 3] = [224, 224, 224];
/// A pixel every light classifies correctly and none lights: dark grey.
pub const CORRECT_SHADOW: [u8; 3] = [96, 96, 96];
/// A pixel that sees no surface: black.
pub const BACKGROUND: [u8; 3] = [0, 0, 0];

/// The misclassified pixels as a picture (8-bit sRGB, row-major, row 0 at the bottom like
/// `eye`): [`FALSELY_LIT`] where any light is falsely lit, else [`FALSELY_SHADOWED`] where any is
/// falsely shadowed, else [`CORRECT_LIT`] where at least one light lights the point, else
/// [`CORRECT_SHADOW`]; [`BACKGROUND`] where nothing is visible. The two error colours are from
/// Okabe and Ito's palette for colour-blind readers (*Color Universal Design*, 2008,
/// <https://jfly.uni-koeln.de/color/>); the greys keep the scene's shadows readable around them.
///
/// # Panics
/// If `lit`, `truth` and `eye` differ in their numbers of lights or pixels.
#[must_use]
pub fn difference_image(truth: &Truth, lit: &[Vec<f64>], eye: &EyeImage) -> Vec<[u8; 3]> {
    check_shapes(truth, lit);
    assert_eq!(
        eye.triangle.len(),
        eye.width as usize * eye.height as usize,
        "difference_image: the eye image's triangles do not fill width × height"
    );
    (0..eye.triangle.len())
        .into_par_iter()
        .map(|pixel| {
            if eye.triangle[pixel] == NO_TRIANGLE {
                return BACKGROUND;
            }
            let (mut falsely_lit, mut falsely_shadowed, mut lit_by_one) = (false, false, false);
            for (light, fractions) in lit.iter().enumerate() {
                let Some(truly_lit) = truth.lit[light][pixel] else {
                    continue;
                };
                if truth.outside_cone[light][pixel] {
                    continue;
                }
                let classified_lit = fractions[pixel] >= LIT_THRESHOLD;
                falsely_lit |= classified_lit && !truly_lit;
                falsely_shadowed |= !classified_lit && truly_lit;
                lit_by_one |= truly_lit;
            }
            if falsely_lit {
                FALSELY_LIT
            } else if falsely_shadowed {
                FALSELY_SHADOWED
            } else if lit_by_one {
                CORRECT_LIT
            } else {
                CORRECT_SHADOW
            }
        })
        .collect()
}

/// Panics unless `lit` has the lights and pixels of `truth`.
fn check_shapes(truth: &Truth, lit: &[Vec<f64>]) {
    assert_eq!(
        truth.lit.len(),
        lit.len(),
        "the lit fractions and the truth have different numbers of lights"
    );
    for (light, (t, l)) in truth.lit.iter().zip(lit).enumerate() {
        assert!(
            t.len() == l.len() && truth.outside_cone[light].len() == l.len(),
            "light {light}: {} lit fractions for {} truth values",
            l.len(),
            t.len()
        );
    }
}

/// How far truth `b` is from truth `a`, counted as [`misclassification`] counts a
/// technique against the truth: `falsely_lit` where `b` lights what `a` shadows,
/// `falsely_shadowed` the reverse, `visible` the (light, pixel) pairs where both see a surface
/// and neither marks the point outside the light's cone.
///
/// # Panics
/// If the two have different numbers of lights or pixels (they must describe the same eye image).
#[must_use]
pub fn disagreement(a: &Truth, b: &Truth) -> Misclassification {
    assert_eq!(
        a.lit.len(),
        b.lit.len(),
        "disagreement: the truths have different numbers of lights"
    );
    let mut total = Misclassification::default();
    for (light, (reference, other)) in a.lit.iter().zip(&b.lit).enumerate() {
        assert_eq!(
            reference.len(),
            other.len(),
            "disagreement: the truths of light {light} have different numbers of pixels"
        );
        let judged = |pixel: usize| match other[pixel] {
            Some(lit) if !b.outside_cone[light][pixel] => Some(lit),
            _ => None,
        };
        total += compare(reference, &a.outside_cone[light], judged);
    }
    total
}
