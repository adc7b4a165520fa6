//! The one font of every figure, embedded, so that no output depends on the fonts a machine has.
//! DejaVu Sans (Bitstream Vera licence, see data/fonts/DejaVuSans-LICENSE.txt).

use std::sync::{Arc, OnceLock};

use crate::error::PlotError;

/// The font file.
const DEJAVU_SANS: &[u8] = include_bytes!("../../../data/fonts/DejaVuSans.ttf");

/// The family name inside the font file.
pub(crate) const FAMILY: &str = "DejaVu Sans";

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

/// The advance width of `text` set in the embedded font at `size` (the em size, SVG's
/// `font-size`), with its kerning pairs: where text ends, for layout. Characters the font lacks
/// count as its missing-glyph box, as usvg draws them.
pub(crate) fn text_width(text: &str, size: f64) -> Result<f64, PlotError> {
    use ab_glyph::Font as _;
    static FONT: OnceLock<Option<ab_glyph::FontRef<'static>>> = OnceLock::new();
    let font = FONT
        .get_or_init(|| ab_glyph::FontRef::try_from_slice(DEJAVU_SANS).ok())
        .as_ref()
        .ok_or_else(|| PlotError::Render("the embedded font could not be parsed".into()))?;
    let units = font
        .units_per_em()
        .ok_or_else(|| PlotError::Render("the embedded font has no em size".into()))?;
    let mut advance = 0.0f32;
    let mut previous = None;
    for c in text.chars() {
        let glyph = font.glyph_id(c);
        advance += font.h_advance_unscaled(glyph);
        if let Some(p) = previous {
            advance += font.kern_unscaled(p, glyph);
        }
        previous = Some(glyph);
    }
    Ok(f64::from(advance / units) * size)
}
