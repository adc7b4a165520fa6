//! Which of a light's maps serves a visible point: the one rule every lookup, footprint and
//! attribution reads ([`served`]), applying a light's [`Selection`].

use glam::DVec3;

use crate::input::Eye;
use crate::partition::Partition;
use crate::selection::{Beyond, Selection, SelectionRule};

/// What serves one visible point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Served {
    /// The serving partition.
    pub index: usize,
    /// Within a blend band: the next partition and its weight in `(0, 1)`.
    pub blend: Option<(usize, f64)>,
    /// The fade toward lit, in `[0, 1]` (0: none).
    pub fade: f64,
}

impl Served {
    /// The lit fraction from the serving map's (`lit(index)`) and, within a blend band, the next
    /// map's, faded: `s = (1 − w)·s_i + w·s_{i+1}`, then `s + (1 − s)·fade`.
    pub fn combine(&self, mut lit: impl FnMut(usize) -> f64) -> f64 {
        let mut s = lit(self.index);
        if let Some((next, weight)) = self.blend {
            s = (1.0 - weight) * s + weight * lit(next);
        }
        s + (1.0 - s) * self.fade
    }
}

/// Which of `partitions` (nearest first, as planned; each reached through `partition`) serves the
/// visible point `world` seen by `eye`, as `selection` says; `None` if the point lies beyond the
/// shadowed range ([`Beyond::Lit`]) and is lit. A blend band applies by eye depth after either
/// rule: a point in the overlap of its partition and the next is blended from both.
#[must_use]
pub fn served<T>(
    partitions: &[T],
    partition: impl Fn(&T) -> &Partition,
    selection: &Selection,
    eye: &Eye,
    world: DVec3,
) -> Option<Served> {
    if partitions.is_empty() {
        return None;
    }
    let offset = world - eye.pose.eye();
    let depth = offset.dot(eye.pose.forward());
    let first = match selection.rule {
        SelectionRule::Depth => partitions.iter().position(|p| partition(p).far > depth),
        SelectionRule::Containing => partitions.iter().position(|p| partition(p).contains(world)),
    };
    let first = match (first, selection.beyond) {
        (Some(k), _) => k,
        (None, Beyond::Last) => partitions.len() - 1,
        (None, Beyond::Lit) => return None,
    };
    let index = match selection.rule {
        SelectionRule::Depth => face_serving(partitions, &partition, first, world),
        SelectionRule::Containing => first,
    };
    let blend = if selection.blend {
        blend_with_next(partitions, &partition, index, depth, world)
    } else {
        None
    };
    let fade = selection
        .fade
        .map_or(0.0, |fade| fade.amount(depth, offset.length()));
    Some(Served { index, blend, fade })
}

/// Among the partitions that share the depths of `partitions[first]` (the faces of one
/// z-partition), the one whose face holds `world` most deeply (the first of equals); `first` itself
/// if it has no face.
fn face_serving<T>(
    partitions: &[T],
    partition: &impl Fn(&T) -> &Partition,
    first: usize,
    world: DVec3,
) -> usize {
    let head = partition(&partitions[first]);
    // Back up to the group's first face: the depth rule finds the first whose far lies beyond,
    // which is the group's first already, but a Beyond::Last pick is the last partition.
    let near = head.near;
    let start = partitions[..first]
        .iter()
        .rposition(|p| partition(p).near != near)
        .map_or(0, |k| k + 1);
    if head.face.is_none() && start == first {
        return first;
    }
    let mut best = (first, f64::NEG_INFINITY);
    for (k, p) in partitions.iter().enumerate().skip(start) {
        let p = partition(p);
        if p.near != near {
            break;
        }
        let inside = p
            .face
            .as_ref()
            .map_or(f64::INFINITY, |face| face.inside(world));
        if inside > best.1 {
            best = (k, inside);
        }
    }
    best.0
}

/// The next partition and its weight where `depth` lies in the overlap of `partitions[index]` and
/// the next z-partition.
fn blend_with_next<T>(
    partitions: &[T],
    partition: &impl Fn(&T) -> &Partition,
    index: usize,
    depth: f64,
    world: DVec3,
) -> Option<(usize, f64)> {
    let this = partition(&partitions[index]);
    let next = partitions
        .iter()
        .skip(index + 1)
        .position(|p| partition(p).near != this.near)?
        + index
        + 1;
    let band_start = partition(&partitions[next]).near;
    if depth < band_start || depth >= this.far {
        return None;
    }
    let weight = (depth - band_start) / (this.far - band_start);
    (weight > 0.0).then(|| (face_serving(partitions, partition, next, world), weight))
}
