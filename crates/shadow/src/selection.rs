//! Which of a light's maps serves a visible point: the one rule every lookup, footprint and
//! attribution reads ([`served`]), with the cascade selections engines ship — by eye depth
//! (interval) or by the first map that contains the point, blending across the overlap of two
//! cascades, and fading the shadow out toward the last cascade's far end.

use glam::DVec3;

use crate::input::Eye;
use crate::partition::Partition;

/// How a light's partitions (cascades) share the view.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Selection {
    /// How the serving partition is found.
    pub rule: SelectionRule,
    /// Blend linearly across the overlap of two consecutive partitions (by eye depth): from the
    /// later partition's near to the earlier one's far, the lit fraction goes from the earlier
    /// map's to the later map's (Bevy's `fetch_directional_shadow`: `mix(s_i, s_{i+1}, (z −
    /// near_{i+1})/(far_i − near_{i+1}))`). Without it, the earlier map serves the overlap.
    pub blend: bool,
    /// What serves a point beyond the last partition's far end.
    pub beyond: Beyond,
    /// The shadow faded out toward the far end of the shadowed range, if any.
    pub fade: Option<Fade>,
}

impl Selection {
    /// shadowlab's partitions: by eye depth, no blending, the last partition serving everything
    /// beyond it (the camera's far plane ends it anyway), no fade.
    pub const DEFAULT: Self = Self {
        rule: SelectionRule::Depth,
        blend: false,
        beyond: Beyond::Last,
        fade: None,
    };
}

/// How the serving partition is found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SelectionRule {
    /// By eye depth: the first partition whose far end lies beyond the point's eye depth
    /// (Bevy's `get_cascade_index`, Filament's `getShadowCascade`, Godot's split offsets,
    /// Babylon's and three.js's intervals). Partitions that share their depths (faces of the
    /// logarithmic map, [`crate::faces`]) are told apart by the face whose projection holds the
    /// point most deeply.
    #[default]
    Depth,
    /// The first partition whose map contains the point: its culling sphere where it has one (Unity
    /// URP's `ComputeCascadeIndex`: the first sphere with `|p − c|² < r²`), else its map's window
    /// (`x, y ∈ [0, 1)`, depth in `[0, 1]`).
    Containing,
}

/// What serves a point beyond the last partition.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Beyond {
    /// The last partition (shadowlab's partitions, which end at the camera's far plane).
    #[default]
    Last,
    /// Nothing: the point is lit (engines' shadow distance: Bevy's "beyond the last cascade →
    /// unshadowed", Babylon's `shadowMaxZ`, Unity's and Godot's maximum distance).
    Lit,
}

/// The shadow faded to lit between two distances: the lit fraction `s` becomes `s + (1 − s)·f`
/// with `f` rising from 0 at `start` to 1 at `end`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fade {
    /// Where the fade starts.
    pub start: f64,
    /// Where the point is fully lit.
    pub end: f64,
    /// How `f` rises, and on which distance.
    pub curve: FadeCurve,
}

/// How a [`Fade`] rises.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FadeCurve {
    /// `smoothstep(start, end, eye depth)` (Godot 4, `fade_from`/`fade_to` in
    /// `scene_forward_clustered.glsl`).
    SmoothstepDepth,
    /// Linear in the squared distance from the camera, `saturate((d² − start²)/(end² − start²))`
    /// (Unity URP `GetMainLightShadowFade` with `GetScaleAndBiasForLinearDistanceFade`).
    LinearSquaredDistance,
}

impl Fade {
    /// `f` for a point at eye depth `depth` and distance `distance` from the camera.
    #[must_use]
    pub fn amount(&self, depth: f64, distance: f64) -> f64 {
        let (start, end) = (self.start, self.end);
        match self.curve {
            FadeCurve::SmoothstepDepth => {
                let t = ((depth - start) / (end - start)).clamp(0.0, 1.0);
                t * t * (3.0 - 2.0 * t)
            }
            FadeCurve::LinearSquaredDistance => ((distance * distance - start * start)
                / (end * end - start * start))
                .clamp(0.0, 1.0),
        }
    }
}

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
/// shadowed range ([`Beyond::Lit`]) and is lit.
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
    let (index, blend) = match selection.rule {
        SelectionRule::Depth => {
            let group = partitions.iter().position(|p| partition(p).far > depth);
            let first = match (group, selection.beyond) {
                (Some(k), _) => k,
                (None, Beyond::Last) => partitions.len() - 1,
                (None, Beyond::Lit) => return None,
            };
            let index = face_serving(partitions, &partition, first, world);
            let blend = if selection.blend {
                blend_with_next(partitions, &partition, index, depth, world)
            } else {
                None
            };
            (index, blend)
        }
        SelectionRule::Containing => {
            match (
                partitions.iter().position(|p| partition(p).contains(world)),
                selection.beyond,
            ) {
                (Some(k), _) => (k, None),
                (None, Beyond::Last) => (partitions.len() - 1, None),
                (None, Beyond::Lit) => return None,
            }
        }
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
    if depth < band_start || band_start >= this.far {
        return None;
    }
    let weight = (depth - band_start) / (this.far - band_start);
    (weight > 0.0).then(|| (face_serving(partitions, partition, next, world), weight))
}
