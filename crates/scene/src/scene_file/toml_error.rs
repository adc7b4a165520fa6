//! toml's errors as [`SceneFileError::Toml`]: the file, the line and column, and the field at the
//! error's position (`mesh[1].obk`), found by walking the spanned document that toml parses.

use std::ops::Range;
use std::path::Path;

use toml::de::{DeTable, DeValue};

use super::error::SceneFileError;

/// The [`SceneFileError::Toml`] for toml's error about `text`, the contents of `path`.
pub(super) fn scene_toml_error(path: &Path, text: &str, error: &toml::de::Error) -> SceneFileError {
    let span = error.span();
    let position = span.as_ref().map(|span| line_column(text, span.start));
    // Only deserialisation errors are inside a document that parses; a syntax error has no field.
    let field = span.and_then(|span| {
        let document = DeTable::parse(text).ok()?;
        field_at(document.get_ref(), span.start)
    });
    SceneFileError::Toml {
        path: path.to_owned(),
        position,
        field,
        message: error.message().to_owned(),
    }
}

/// The line and column (both from 1; the column counts characters, as toml's own messages do) of
/// byte `offset` in `text`. An offset past the end is the end.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text.as_bytes()[..offset.min(text.len())];
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let line = 1 + before.iter().filter(|&&b| b == b'\n').count();
    // Characters are counted by their first bytes (UTF-8 continuation bytes are 0b10xx_xxxx).
    let column = 1 + before[line_start..]
        .iter()
        .filter(|&&b| b & 0xc0 != 0x80)
        .count();
    (line, column)
}

/// The path of the innermost key or value whose span holds byte `offset`: `camera.fov`,
/// `mesh[1]`, `camera.image[0]`.
fn field_at(table: &DeTable<'_>, offset: usize) -> Option<String> {
    let mut best: Option<(usize, String)> = None;
    visit_table(table, "", offset, &mut best);
    best.map(|(_, path)| path)
}

/// Offers every key and value of `table` (whose path is `prefix`) to [`offer`], depth first.
fn visit_table(
    table: &DeTable<'_>,
    prefix: &str,
    offset: usize,
    best: &mut Option<(usize, String)>,
) {
    for (key, value) in table.iter() {
        let path = if prefix.is_empty() {
            key.get_ref().to_string()
        } else {
            format!("{prefix}.{}", key.get_ref())
        };
        offer(key.span(), &path, offset, best);
        visit_value(value.get_ref(), value.span(), &path, offset, best);
    }
}

/// Offers a value, and everything inside it, to [`offer`].
fn visit_value(
    value: &DeValue<'_>,
    span: Range<usize>,
    path: &str,
    offset: usize,
    best: &mut Option<(usize, String)>,
) {
    offer(span, path, offset, best);
    match value {
        DeValue::Table(table) => visit_table(table, path, offset, best),
        DeValue::Array(array) => {
            for (index, element) in array.iter().enumerate() {
                let element_path = format!("{path}[{index}]");
                visit_value(
                    element.get_ref(),
                    element.span(),
                    &element_path,
                    offset,
                    best,
                );
            }
        }
        _ => {}
    }
}

/// Keeps `path` if `span` holds `offset` and is no longer than the best span so far; on a tie the
/// later (deeper) one wins. Tables opened by a header span only their header, so the body's keys
/// are found by their own spans.
fn offer(span: Range<usize>, path: &str, offset: usize, best: &mut Option<(usize, String)>) {
    if span.contains(&offset)
        && best
            .as_ref()
            .is_none_or(|(length, _)| span.len() <= *length)
    {
        *best = Some((span.len(), path.to_owned()));
    }
}
