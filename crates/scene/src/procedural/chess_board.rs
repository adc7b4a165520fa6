//! A chess board: squares that a renderer can colour, with an optional frame.

use glam::DVec3;

use super::ShapeError;
use super::builder::MeshBuilder;
use super::parameters::{non_negative, positive};
use crate::mesh::Mesh;

/// The group id of the dark squares of [`chess_board`].
pub const CHESS_DARK: u32 = 0;
/// The group id of the light squares of [`chess_board`].
pub const CHESS_LIGHT: u32 = 1;
/// The group id of the frame of [`chess_board`], if it has one.
pub const CHESS_FRAME: u32 = 2;

/// A flat 8 × 8 chess board in the plane y = 0, centred on the origin and facing +y, with squares
/// of side `square_size` and, if `frame_width > 0`, a frame of that width around them.
///
/// Square (file i, rank j), i, j in 0..8, covers x ∈ [−4 + i, −3 + i]·square_size and
/// z ∈ [3 − j, 4 − j]·square_size: files run along +x and ranks along −z, so a camera on the +z
/// side looking down −z sees the board from white's side, with a1 (i = j = 0) at the near left. Its
/// group is [`CHESS_DARK`] when i + j is even (a1 is dark) and [`CHESS_LIGHT`] when odd; the
/// frame is [`CHESS_FRAME`]. Group names: `"dark"`, `"light"` and, with a frame, `"frame"`.
///
/// The board is one grid of vertices shared by all its quads (9 × 9 without a frame, 11 × 11 with
/// one), so neighbouring squares share their edges exactly and there are no T-junctions. 128
/// triangles, or 200 with the frame.
///
/// # Errors
/// [`ShapeError::InvalidParameter`] naming `square_size` (finite and > 0) or `frame_width` (finite
/// and ≥ 0).
pub fn chess_board(square_size: f64, frame_width: f64) -> Result<Mesh, ShapeError> {
    let square_size = positive("square_size", square_size)?;
    let frame_width = non_negative("frame_width", frame_width)?;
    let framed = frame_width > 0.0;
    let half = 4.0 * square_size;
    // Grid lines, shared by x (files, growing) and z (ranks, growing toward −z).
    let mut lines: Vec<f64> = (0..=8)
        .map(|k| -half + f64::from(k) * square_size)
        .collect();
    if framed {
        lines.insert(0, -half - frame_width);
        lines.push(half + frame_width);
    }
    let mut builder = MeshBuilder::default();
    let grid: Vec<Vec<u32>> = lines
        .iter()
        .map(|&x| {
            lines
                .iter()
                .rev()
                .map(|&z| builder.vertex(DVec3::new(x, 0.0, z), DVec3::Y))
                .collect()
        })
        .collect();
    // grid[p][q]: x = lines[p], z = the q-th line from +z toward −z.
    let cells = lines.len() - 1;
    let first_square = usize::from(framed);
    for p in 0..cells {
        for q in 0..cells {
            let in_board = |k: usize| (first_square..first_square + 8).contains(&k);
            let group = if in_board(p) && in_board(q) {
                if (p + q - 2 * first_square) % 2 == 0 {
                    CHESS_DARK
                } else {
                    CHESS_LIGHT
                }
            } else {
                CHESS_FRAME
            };
            // q grows toward −z: +x then −z is counter-clockwise seen from +y.
            builder.quad(
                [
                    grid[p][q],
                    grid[p + 1][q],
                    grid[p + 1][q + 1],
                    grid[p][q + 1],
                ],
                group,
            );
        }
    }
    if framed {
        builder.finish(&["dark", "light", "frame"])
    } else {
        builder.finish(&["dark", "light"])
    }
}
