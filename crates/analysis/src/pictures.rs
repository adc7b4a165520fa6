//! A study's pictures as files, each in two forms.
//!
//! | path | what |
//! |---|---|
//! | `images/eye-T.png`, `images/difference-T.png`, `images/difference-causes-T.png`, `images/heatmap-T.png` | **raw**: one pixel per eye pixel, the view's top row first, nothing drawn on them — for comparing pixel by pixel (tests, other tools, the thread-count check) and for `report.html`, which crops them all alike |
//! | `pictures/eye-T.png`, `pictures/difference-T.png`, `pictures/difference-causes-T.png`, `pictures/heatmap-T.png` | **annotated**: the same pixels under a title (scene, technique, what the picture shows) and a line of settings, with the heat map's colour bar (quantity, unit, log scale, the bar's range and the picture's values) and the legends of the difference image and of its causes (each class's colour and pixel count) — for reading on their own |
//!
//! `T` is the technique's label with `/` as `-` (`lispsm-minimax`). Both forms are deterministic:
//! the annotated ones are drawn by `shadowlab-plot` with its embedded font around the raw pixels.

use rayon::prelude::*;
use shadowlab_plot::{Image, Picture, render_picture};
use shadowlab_raster::image_out;
use shadowlab_shadow::Technique;

use crate::error::AnalysisError;
use crate::images::{
    CauseCounts, ClassCounts, causes_legend, difference_legend, footprint_colour_bar,
    footprint_legend,
};
use crate::labels::{filter_label, technique_label};
use crate::study::{Pictures, Setting, Study};

/// One of the four pictures of a combination.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PictureKind {
    /// The view shaded with the combination's shadows.
    Eye,
    /// Misclassified pixels against the exact truth.
    Difference,
    /// Misclassified pixels coloured by cause ([`crate::attribution::cause_image`]).
    Causes,
    /// The texel footprint on screen, as a heat map.
    Heatmap,
}

impl PictureKind {
    /// The four, in the order the report shows them.
    pub const ALL: [Self; 4] = [Self::Eye, Self::Difference, Self::Causes, Self::Heatmap];

    /// The name in file names: `eye`, `difference`, `difference-causes`, `heatmap`.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Eye => "eye",
            Self::Difference => "difference",
            Self::Causes => "difference-causes",
            Self::Heatmap => "heatmap",
        }
    }

    /// What the picture shows, in words.
    #[must_use]
    pub fn caption(self) -> &'static str {
        match self {
            Self::Eye => "the view with its shadows",
            Self::Difference => "misclassified pixels against the exact truth",
            Self::Causes => "misclassified pixels by cause",
            Self::Heatmap => "texel footprint on screen",
        }
    }

    /// The raw picture's path in the output set.
    #[must_use]
    pub fn raw_path(self, technique: Technique) -> String {
        format!("images/{}-{}.png", self.key(), stem(technique))
    }

    /// The annotated picture's path in the output set.
    #[must_use]
    pub fn annotated_path(self, technique: Technique) -> String {
        format!("pictures/{}-{}.png", self.key(), stem(technique))
    }
}

/// The technique's part of its pictures' file names: its label with `/` as `-`.
#[must_use]
pub fn stem(technique: Technique) -> String {
    technique_label(technique).replace('/', "-")
}

/// The settings a combination's pictures were made with, as one line.
#[must_use]
pub fn settings(study: &Study, setting: &Setting) -> String {
    let lights = study.truth.lit.len();
    format!(
        "{}² shadow map, {} map(s) per light, filter {}, bias {}, focus {}; {}×{} eye image{}",
        setting.resolution,
        setting.partitions,
        filter_label(&setting.filter),
        study.bias,
        study.focus.map_or("none (maps given)", |f| f.key()),
        study.width,
        study.height,
        if lights > 1 {
            format!(", {lights} lights (footprints: the first)")
        } else {
            String::new()
        }
    )
}

/// A picture's title: scene, technique and what it shows.
#[must_use]
pub fn title(study: &Study, setting: &Setting, kind: PictureKind) -> String {
    format!(
        "{} — {}: {}",
        study.scene,
        technique_label(setting.technique),
        kind.caption()
    )
}

/// The raw pixels of one picture (rows from the bottom, like the eye image).
fn pixels(pictures: &Pictures, kind: PictureKind) -> &[[u8; 3]] {
    match kind {
        PictureKind::Eye => &pictures.eye,
        PictureKind::Difference => &pictures.difference,
        PictureKind::Causes => &pictures.causes,
        PictureKind::Heatmap => &pictures.heatmap,
    }
}

/// One picture annotated: title, settings, and its colour bar or legend.
///
/// # Errors
/// [`AnalysisError::Plot`] if the pixels do not fill the study's eye image size.
pub fn annotated(
    study: &Study,
    pictures: &Pictures,
    kind: PictureKind,
) -> Result<Picture, AnalysisError> {
    let image = Image::bottom_up(study.width, study.height, pixels(pictures, kind))?;
    let (colour_bar, legend) = match kind {
        PictureKind::Eye => (None, Vec::new()),
        PictureKind::Difference => (
            None,
            difference_legend(&ClassCounts::of(&pictures.difference)),
        ),
        PictureKind::Causes => (None, causes_legend(&CauseCounts::of(&pictures.causes))),
        PictureKind::Heatmap => (
            Some(footprint_colour_bar(pictures.footprint_range)),
            footprint_legend(),
        ),
    };
    Ok(Picture {
        title: title(study, &pictures.setting, kind),
        subtitle: settings(study, &pictures.setting),
        image,
        colour_bar,
        legend,
    })
}

/// Every picture of the study, raw and annotated, each with its path in the output set (module
/// docs), in technique order.
///
/// # Errors
/// [`AnalysisError::Raster`] or [`AnalysisError::Plot`] if a picture cannot be encoded.
pub fn files(study: &Study) -> Result<Vec<(String, Vec<u8>)>, AnalysisError> {
    // Each technique's pictures drawn and encoded in parallel, gathered in technique order; the
    // first error in that order is the one returned.
    let per_technique: Vec<_> = study
        .pictures
        .par_iter()
        .map(|pictures| technique_files(study, pictures))
        .collect();
    let mut files = Vec::new();
    for technique in per_technique {
        files.extend(technique?);
    }
    Ok(files)
}

/// One technique's pictures, raw then annotated, each with its path.
fn technique_files(
    study: &Study,
    pictures: &Pictures,
) -> Result<Vec<(String, Vec<u8>)>, AnalysisError> {
    let technique = pictures.setting.technique;
    let mut files = Vec::with_capacity(2 * PictureKind::ALL.len());
    for kind in PictureKind::ALL {
        files.push((
            kind.raw_path(technique),
            image_out::rgb_png(pixels(pictures, kind), study.width, study.height)?,
        ));
    }
    for kind in PictureKind::ALL {
        files.push((
            kind.annotated_path(technique),
            render_picture(&annotated(study, pictures, kind)?)?,
        ));
    }
    Ok(files)
}
