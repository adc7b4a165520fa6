//! The one font of every figure, embedded, so that no output depends on the fonts a machine has.
//! DejaVu Sans (Bitstream Vera licence, see data/fonts/DejaVuSans-LICENSE.txt).

use std::sync::{Arc, OnceLock};

use crate::error::PlotError;

/// The font file.
const DEJAVU_SANS: &[u8] = include_bytes!("../../../data/fonts/DejaVuSans.ttf");

/// The family name inside the font file.
const FAMILY: &str = "DejaVu Sans";

/// The family the chart code asks for; it resolves to the embedded font both when the chart is laid
/// out (plotters measures text with it) and when the SVG is rasterised (usvg maps the generic
/// family to it).
pub(crate) const CHART_FAMILY: &str = "sans-serif";

/// Registers the embedded font with plotters for text layout, once per process.
pub(crate) fn register_for_layout() -> Result<(), PlotError> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            plotters::style::register_font(
                CHART_FAMILY,
                plotters::style::FontStyle::Normal,
                DEJAVU_SANS,
            )
            .map_err(|_| "the embedded font could not be parsed".to_owned())
        })
        .clone()
        .map_err(PlotError::Render)
}

/// A font database holding only the embedded font, with every generic family mapped to it.
pub(crate) fn database() -> Arc<resvg::usvg::fontdb::Database> {
    static DATABASE: OnceLock<Arc<resvg::usvg::fontdb::Database>> = OnceLock::new();
    DATABASE
        .get_or_init(|| {
            let mut db = resvg::usvg::fontdb::Database::new();
            db.load_font_data(DEJAVU_SANS.to_vec());
            db.set_sans_serif_family(FAMILY);
            db.set_serif_family(FAMILY);
            db.set_monospace_family(FAMILY);
            Arc::new(db)
        })
        .clone()
}
