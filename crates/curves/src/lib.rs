//! The closed-form aliasing figures: the papers' own plots recomputed from `shadowlab-params`, and
//! the comparison none of them has (every technique's maximum error against the light angle). Each
//! figure is returned as a [`shadowlab_plot::Figure`] to draw and a [`shadowlab_plot::Table`] with
//! the same numbers at full precision.
//!
//! | figure | what it shows |
//! |---|---|
//! | `lispsm-fig6` | LiSPSM Fig. 6: dp/ds against z for uniform, PSM, LiSPSM at n_opt and the logarithmic ideal (γ = 90°) |
//! | `cad-fig7` | CAD Fig. 7: n'(γ) of eq. 16 for each fall-back curve r, with the raw n'_1, n'_2 and the model's minimax |
//! | `gmnpr-fig5` | GMNPR Fig. 5: λ against θ for GMNPR, LiSPSM, GLPR and the minimax, with the raw λ1, λ2 |
//! | `gmnpr-fig6` | GMNPR Fig. 6: F(z) at several θ for LiSPSM and GMNPR (and the minimax), linear above φ, log below |
//! | `partitions` | split positions against γ: CAD eq. 19 (δ = 2) and the practical split (λ = 0.5) |
//! | `max-error-vs-angle` | every parameter rule's maximum F against γ |
//!
//! All figures use one configuration ([`CurveConfig`], by default the papers' n = 1, f = 100,
//! 60° field of view) and fixed sampling grids, so their bytes repeat exactly.

mod cad_fig7;
mod config;
mod gmnpr_fig5;
mod gmnpr_fig6;
mod lispsm_fig6;
mod max_error;
mod partitions;
mod sampling;

use std::fmt;

pub use config::CurveConfig;
use shadowlab_params::ParamError;
use shadowlab_plot::{Figure, PlotError, Table};

/// The figures this crate draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FigureName {
    /// LiSPSM Fig. 6.
    LispsmFig6,
    /// CAD Fig. 7.
    CadFig7,
    /// GMNPR Fig. 5.
    GmnprFig5,
    /// GMNPR Fig. 6.
    GmnprFig6,
    /// Split positions against the light angle.
    Partitions,
    /// Every rule's maximum error against the light angle.
    MaxErrorVsAngle,
}

impl FigureName {
    /// Every figure, in the order they are written.
    pub const ALL: [Self; 6] = [
        Self::LispsmFig6,
        Self::CadFig7,
        Self::GmnprFig5,
        Self::GmnprFig6,
        Self::Partitions,
        Self::MaxErrorVsAngle,
    ];

    /// The figure's name, which is also its file stem.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::LispsmFig6 => "lispsm-fig6",
            Self::CadFig7 => "cad-fig7",
            Self::GmnprFig5 => "gmnpr-fig5",
            Self::GmnprFig6 => "gmnpr-fig6",
            Self::Partitions => "partitions",
            Self::MaxErrorVsAngle => "max-error-vs-angle",
        }
    }

    /// The figure named `key`.
    #[must_use]
    pub fn from_key(key: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|name| name.key() == key)
    }
}

impl fmt::Display for FigureName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.key())
    }
}

/// A computed figure: the chart and the table of its numbers.
#[derive(Clone, Debug)]
pub struct Curves {
    /// Which figure this is.
    pub name: FigureName,
    /// The chart to draw.
    pub figure: Figure,
    /// The same numbers at full precision, one column per curve.
    pub table: Table,
}

/// Why a figure could not be computed.
#[derive(Debug)]
#[non_exhaustive]
pub enum CurvesError {
    /// The configuration is outside the formulas' domain.
    Param(ParamError),
    /// The chart or table could not be assembled.
    Plot(PlotError),
}

impl fmt::Display for CurvesError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Param(e) => e.fmt(f),
            Self::Plot(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for CurvesError {}

impl From<ParamError> for CurvesError {
    fn from(e: ParamError) -> Self {
        Self::Param(e)
    }
}

impl From<PlotError> for CurvesError {
    fn from(e: PlotError) -> Self {
        Self::Plot(e)
    }
}

/// Computes the figure `name` for the configuration.
pub fn compute(name: FigureName, config: &CurveConfig) -> Result<Curves, CurvesError> {
    let (figure, table) = match name {
        FigureName::LispsmFig6 => lispsm_fig6::compute(config)?,
        FigureName::CadFig7 => cad_fig7::compute(config)?,
        FigureName::GmnprFig5 => gmnpr_fig5::compute(config)?,
        FigureName::GmnprFig6 => gmnpr_fig6::compute(config)?,
        FigureName::Partitions => partitions::compute(config)?,
        FigureName::MaxErrorVsAngle => max_error::compute(config)?,
    };
    Ok(Curves {
        name,
        figure,
        table,
    })
}
