//! The line-by-line check of OBJ text that runs before tobj parses it.
//!
//! tobj's errors carry no line number, and tobj accepts some input that this crate must not: NaN
//! and infinite coordinates, and (in debug builds) face indices that overflow its index arithmetic.
//! So every statement tobj reads is checked here first, the way tobj reads it, and the first
//! problem is reported with its line. Once this check passes, tobj does not fail (a failure would
//! be a bug, reported as [`super::ObjError::Internal`]).
//!
//! Where tobj's reading of a legal file would be wrong, the check is stricter than tobj and says so
//! in its error:
//! - face indices must refer to elements defined *above* the line (tobj also accepts forward
//!   references to positions, which the OBJ format does not define), and a `v/vt` or `v//vn` index
//!   must refer to an existing `vt` or `vn` even though tobj ignores it when the file has none;
//! - within a group (a run of faces between `g`/`o` statements), every face corner names a normal
//!   or none does: tobj's single index pairs normals with vertices by position in a list, which
//!   breaks when some corners have none;
//! - every `v` statement carries a colour (`v x y z r g b`) or none does (tobj rejects mixed files
//!   later, without a line);
//! - `vn` takes exactly three values, and its values must be finite, as must `v`'s;
//! - `v`'s coordinates (divided by w where a weight is given) lie within ±[`MAX_COORDINATE`].

use super::error::{ObjElement, ObjProblem};
use crate::mesh::MAX_COORDINATE;

/// What the check learnt about a file that passed it.
#[derive(Debug)]
pub(crate) struct ObjSummary {
    /// The number of `f` statements (each with at least three vertices).
    pub(crate) faces: usize,
    /// Whether the file has polyline (`l`) statements, which tobj would read as faces.
    pub(crate) has_polylines: bool,
}

/// A problem and the line (from 1) it is on.
pub(crate) type LineProblem = (usize, ObjProblem);

/// Counts of the elements defined so far, for resolving face indices.
#[derive(Default)]
struct Defined {
    positions: usize,
    tex_coords: usize,
    normals: usize,
}

impl Defined {
    fn count(&self, element: ObjElement) -> usize {
        match element {
            ObjElement::Position => self.positions,
            ObjElement::TexCoord => self.tex_coords,
            ObjElement::Normal => self.normals,
        }
    }
}

/// The check's state while it walks the lines.
#[derive(Default)]
struct Checker {
    defined: Defined,
    /// Whether the first `v` statement had a colour, and its line.
    colour_pattern: Option<(bool, usize)>,
    /// Whether the current group's first face named normals, and its line.
    normal_pattern: Option<(bool, usize)>,
    summary_faces: usize,
    has_polylines: bool,
}

/// Checks OBJ text line by line; see the module documentation for what is checked.
pub(crate) fn check(text: &str) -> Result<ObjSummary, LineProblem> {
    let mut checker = Checker::default();
    for (index, line) in text.lines().enumerate() {
        let number = index + 1;
        checker
            .line(line, number)
            .map_err(|problem| (number, problem))?;
    }
    Ok(ObjSummary {
        faces: checker.summary_faces,
        has_polylines: checker.has_polylines,
    })
}

/// Text that tobj reads as `text` without its polyline (`l`) statements: each becomes an empty
/// line, so line numbers stay the same.
pub(crate) fn without_polylines(text: &str) -> String {
    let mut kept = String::with_capacity(text.len());
    for line in text.lines() {
        if line.split_whitespace().next() != Some("l") {
            kept.push_str(line);
        }
        kept.push('\n');
    }
    kept
}

impl Checker {
    fn line(&mut self, line: &str, number: usize) -> Result<(), ObjProblem> {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => self.position(&words.collect::<Vec<_>>(), number),
            Some("vt") => {
                let values: Vec<&str> = words.collect();
                // tobj reads u and v and ignores anything after them.
                if values.len() < 2 {
                    return Err(ObjProblem::WrongValueCount {
                        keyword: "vt",
                        found: values.len(),
                        expected: "u v (optionally w)",
                    });
                }
                for token in &values[..2] {
                    parse_number("vt", token)?;
                }
                self.defined.tex_coords += 1;
                Ok(())
            }
            Some("vn") => {
                let values: Vec<&str> = words.collect();
                if values.len() != 3 {
                    return Err(ObjProblem::WrongValueCount {
                        keyword: "vn",
                        found: values.len(),
                        expected: "x y z",
                    });
                }
                for token in &values {
                    parse_finite("vn", token)?;
                }
                self.defined.normals += 1;
                Ok(())
            }
            Some("f") => self.face(words, number),
            Some("l") => {
                self.has_polylines = true;
                Ok(())
            }
            Some("g" | "o") => {
                self.normal_pattern = None;
                Ok(())
            }
            Some("usemtl") => {
                // Exactly tobj's reading of the name.
                if line.split_once(' ').unwrap_or_default().1.trim().is_empty() {
                    Err(ObjProblem::MissingMaterialName)
                } else {
                    Ok(())
                }
            }
            _ => Ok(()),
        }
    }

    /// `v x y z`, `v x y z w` (tobj divides by w) or `v x y z r g b`.
    fn position(&mut self, values: &[&str], number: usize) -> Result<(), ObjProblem> {
        if !matches!(values.len(), 3 | 4 | 6) {
            return Err(ObjProblem::WrongValueCount {
                keyword: "v",
                found: values.len(),
                expected: "x y z, x y z w or x y z r g b",
            });
        }
        let mut coordinates = [0.0; 3];
        for (coordinate, token) in coordinates.iter_mut().zip(values) {
            *coordinate = parse_finite("v", token)?;
        }
        if values.len() == 4 {
            let weight = parse_finite("v", values[3])?;
            if weight == 0.0 {
                return Err(ObjProblem::ZeroWeight);
            }
            for (coordinate, token) in coordinates.iter().zip(values) {
                let divided = coordinate / weight;
                let token = || format!("{token}/{}", values[3]);
                if !divided.is_finite() {
                    return Err(ObjProblem::NotFinite {
                        keyword: "v",
                        token: token(),
                    });
                }
                if divided.abs() > MAX_COORDINATE {
                    return Err(ObjProblem::CoordinateOutOfRange { token: token() });
                }
            }
        } else if let Some((_, token)) = coordinates
            .iter()
            .zip(values)
            .find(|(coordinate, _)| coordinate.abs() > MAX_COORDINATE)
        {
            return Err(ObjProblem::CoordinateOutOfRange {
                token: (*token).to_owned(),
            });
        }
        let has_colour = values.len() == 6;
        if has_colour {
            for token in &values[3..] {
                parse_number("v", token)?;
            }
        }
        match self.colour_pattern {
            None => self.colour_pattern = Some((has_colour, number)),
            Some((first, first_vertex_line)) if first != has_colour => {
                return Err(ObjProblem::MixedVertexColours { first_vertex_line });
            }
            Some(_) => {}
        }
        self.defined.positions += 1;
        Ok(())
    }

    /// `f v1 v2 v3 ...`, each vertex `v`, `v/vt`, `v//vn` or `v/vt/vn`.
    fn face<'a>(
        &mut self,
        corners: impl Iterator<Item = &'a str>,
        number: usize,
    ) -> Result<(), ObjProblem> {
        let mut count = 0;
        let mut with_normal = 0;
        for corner in corners {
            count += 1;
            if self.corner(corner)? {
                with_normal += 1;
            }
        }
        if count < 3 {
            return Err(ObjProblem::TooFewFaceVertices { found: count });
        }
        if with_normal != 0 && with_normal != count {
            return Err(ObjProblem::MixedNormalsInFace);
        }
        let names_normals = with_normal == count;
        match self.normal_pattern {
            None => self.normal_pattern = Some((names_normals, number)),
            Some((first, first_face_line)) if first != names_normals => {
                return Err(ObjProblem::MixedNormals {
                    names_normals,
                    first_face_line,
                });
            }
            Some(_) => {}
        }
        self.summary_faces += 1;
        Ok(())
    }

    /// Checks one face vertex; returns whether it names a normal.
    fn corner(&self, corner: &str) -> Result<bool, ObjProblem> {
        let malformed = || ObjProblem::MalformedFaceVertex {
            token: corner.to_owned(),
        };
        let parts: Vec<&str> = corner.split('/').collect();
        if parts.len() > 3 || parts[0].is_empty() {
            return Err(malformed());
        }
        let elements = [
            ObjElement::Position,
            ObjElement::TexCoord,
            ObjElement::Normal,
        ];
        for (part, element) in parts.iter().zip(elements) {
            if part.is_empty() {
                continue;
            }
            let index: isize = part.parse().map_err(|_| malformed())?;
            self.resolve(index, element)?;
        }
        Ok(parts.get(2).is_some_and(|part| !part.is_empty()))
    }

    /// Checks that an index (1-based, or negative counting back) refers to a defined element.
    fn resolve(&self, index: isize, element: ObjElement) -> Result<(), ObjProblem> {
        if index == 0 {
            return Err(ObjProblem::ZeroIndex { element });
        }
        // Index k > 0 is element k − 1; index −k is element `defined − k`: both need k ≤ defined.
        let defined = self.defined.count(element);
        if index.unsigned_abs() <= defined {
            Ok(())
        } else {
            Err(ObjProblem::IndexOutOfRange {
                element,
                index,
                defined,
            })
        }
    }
}

/// Parses a number the way tobj does (`f64::from_str`, which also accepts `nan` and `inf`).
fn parse_number(keyword: &'static str, token: &str) -> Result<f64, ObjProblem> {
    token.parse().map_err(|_| ObjProblem::NotANumber {
        keyword,
        token: token.to_owned(),
    })
}

/// Parses a number that must be finite.
fn parse_finite(keyword: &'static str, token: &str) -> Result<f64, ObjProblem> {
    let value = parse_number(keyword, token)?;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ObjProblem::NotFinite {
            keyword,
            token: token.to_owned(),
        })
    }
}
