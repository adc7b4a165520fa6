//! Clipping lines to a panel's axes in the axes' own linear space (log10 on a log axis), so that a
//! curve leaving the chart (a parameter rising to infinity) ends exactly at the frame.

use crate::figure::Axis;

/// A point in the axes' linear space.
type Point = (f64, f64);

/// The visible parts of the polyline `points`, as runs of at least two points in data space. A point
/// with no place on an axis (non-finite, or non-positive on a log axis) breaks the line.
pub(crate) fn visible_runs(points: &[(f64, f64)], x: &Axis, y: &Axis) -> Vec<Vec<(f64, f64)>> {
    let bounds = (
        (x.position_of(x.min), x.position_of(x.max)),
        (y.position_of(y.min), y.position_of(y.max)),
    );
    let ((Some(x0), Some(x1)), (Some(y0), Some(y1))) = bounds else {
        return Vec::new();
    };
    let linear: Vec<Option<Point>> = points
        .iter()
        .map(|&(px, py)| Some((x.position_of(px)?, y.position_of(py)?)))
        .collect();
    let mut runs: Vec<Vec<Point>> = Vec::new();
    let mut open = false;
    for pair in linear.windows(2) {
        let (Some(a), Some(b)) = (pair[0], pair[1]) else {
            open = false;
            continue;
        };
        let Some((p, q)) = clip_segment(a, b, (x0, x1), (y0, y1)) else {
            open = false;
            continue;
        };
        match runs.last_mut() {
            Some(run) if open && run.last() == Some(&p) => run.push(q),
            _ => runs.push(vec![p, q]),
        }
        // The run continues only if the segment ended inside, at b itself.
        open = q == b;
    }
    runs.into_iter()
        .map(|run| {
            run.into_iter()
                .map(|(lx, ly)| (x.value_at(lx), y.value_at(ly)))
                .collect()
        })
        .collect()
}

/// Liang–Barsky: the part of segment `a`–`b` inside the box, if any. Ends inside the box are
/// returned unchanged, bit for bit.
fn clip_segment(
    a: Point,
    b: Point,
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Option<(Point, Point)> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - x0),
        (dx, x1 - a.0),
        (-dy, a.1 - y0),
        (dy, y1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| {
        if t == 0.0 {
            a
        } else if t == 1.0 {
            b
        } else {
            (a.0 + t * dx, a.1 + t * dy)
        }
    };
    Some((at(t0), at(t1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_through_the_box_is_cut_at_the_frame() {
        let x = Axis::linear("x", 0.0, 10.0);
        let y = Axis::linear("y", 0.0, 10.0);
        let runs = visible_runs(&[(-5.0, 5.0), (5.0, 5.0), (15.0, 5.0)], &x, &y);
        assert_eq!(runs, vec![vec![(0.0, 5.0), (5.0, 5.0), (10.0, 5.0)]]);
    }

    #[test]
    fn gaps_and_excursions_split_the_line() {
        let x = Axis::linear("x", 0.0, 10.0);
        let y = Axis::log("y", 1.0, 100.0);
        let points = [
            (1.0, 10.0),
            (2.0, 10.0),
            (3.0, f64::NAN),
            (4.0, 10.0),
            (5.0, 10.0),
            (6.0, 1e9),
            (7.0, 10.0),
        ];
        let runs = visible_runs(&points, &x, &y);
        assert_eq!(runs.len(), 3, "{runs:?}");
        assert_eq!(runs[0], vec![(1.0, 10.0), (2.0, 10.0)]);
        let last = runs[2].first().unwrap();
        assert!((last.1 - 100.0).abs() < 1e-9, "{runs:?}");
        assert!(visible_runs(&[(1.0, -1.0), (2.0, 0.0)], &x, &y).is_empty());
    }
}
