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
///
/// One map serving everything (the only one, the last serving beyond it, no fade) is answered
/// without reading the point: the rule's answer for every point.
#[must_use]
pub fn served<T>(
    partitions: &[T],
    partition: impl Fn(&T) -> &Partition,
    selection: &Selection,
    eye: &Eye,
    world: DVec3,
) -> Option<Served> {
    if serves_everything(partitions, selection) {
        return Some(SOLE_MAP);
    }
    served_by_rule(partitions, partition, selection, eye, world)
}

/// What [`served`] gives every point when one map serves everything.
const SOLE_MAP: Served = Served {
    index: 0,
    blend: None,
    fade: 0.0,
};

/// What [`served`] gives every point, if one map serves everything (see [`served`]): decided once
/// for many points, so that they need not be read.
pub(crate) fn sole_map<T>(partitions: &[T], selection: &Selection) -> Option<Served> {
    serves_everything(partitions, selection).then_some(SOLE_MAP)
}

/// Whether one partition serves every point, unblended and unfaded: the only partition, the last
/// serving beyond it ([`Beyond::Last`]), no fade. Then both rules pick it (the depth rule by
/// `Beyond::Last` where the point lies beyond its far end; a face group of one member is that
/// member, however deep its face holds the point), no next partition blends, and the fade is 0.
fn serves_everything<T>(partitions: &[T], selection: &Selection) -> bool {
    partitions.len() == 1 && selection.beyond == Beyond::Last && selection.fade.is_none()
}

/// [`served`] by the selection's rule, for any partitions.
fn served_by_rule<T>(
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

#[cfg(test)]
mod tests {
    use glam::{DMat4, DVec3};
    use shadowlab_hull::{Perspective, ViewPose};
    use shadowlab_test_random::SplitMix;

    use super::{SOLE_MAP, served_by_rule, serves_everything};
    use crate::input::Eye;
    use crate::omni::LightFace;
    use crate::partition::{CullingSphere, Partition, Region};
    use crate::selection::{Beyond, Fade, FadeCurve, Selection, SelectionRule};
    use crate::setup::{LightSetup, ProjectiveMapping, ShadowMapping};
    use crate::technique::Technique;

    /// Where one map serves everything, the rule gives every point — in front of the eye, behind
    /// it, beyond the partition's far end, outside its face — what `served` gives without looking:
    /// by depth and by containment (a culling sphere or the map's volume), blended or not, with and
    /// without a face. Where it does not
    /// (beyond lit, faded), `served` is the rule.
    #[test]
    fn a_sole_map_serves_every_point_as_the_rule_would() {
        let setup = LightSetup {
            technique: Technique::Uniform,
            mapping: ShadowMapping::Projective(ProjectiveMapping::new(
                DMat4::IDENTITY,
                DMat4::IDENTITY,
            )),
            gamma: 0.0,
            half_fov: 0.0,
            warp: None,
            psm: None,
            focus_body: Vec::new(),
        };
        let eye = Eye {
            pose: ViewPose::look_to(DVec3::ZERO, DVec3::NEG_Z, DVec3::Y).expect("a pose"),
            projection: Perspective::new(1.0, 1.0, 0.1, 100.0).expect("a projection"),
        };
        let mut random = SplitMix(0x5eed_0000_0000_5e1e);
        let (mut sole, mut ruled) = (0, 0);
        for round in 0..4000_usize {
            let near = random.range(0.1, 5.0);
            let face = (round % 3 == 0).then(|| {
                Region::LightFace(LightFace {
                    name: "front",
                    light: random.vector(5.0),
                    axis: random.vector(1.0).normalize_or(DVec3::Z),
                    across: None,
                })
            });
            let partition = Partition {
                near,
                far: near + random.range(0.1, 50.0),
                face,
                sphere: (round % 6 == 1).then(|| CullingSphere {
                    centre: random.vector(10.0),
                    radius: random.range(1.0, 30.0),
                }),
                setup: setup.clone(),
            };
            let selection = Selection {
                rule: if round % 2 == 0 {
                    SelectionRule::Depth
                } else {
                    SelectionRule::Containing
                },
                blend: round % 4 < 2,
                beyond: if round % 5 == 0 {
                    Beyond::Lit
                } else {
                    Beyond::Last
                },
                fade: (round % 7 == 0).then_some(Fade {
                    start: 10.0,
                    end: 20.0,
                    curve: FadeCurve::SmoothstepDepth,
                }),
            };
            let world = random.vector(80.0);
            let parts = [partition];
            let rule = served_by_rule(&parts, |p| p, &selection, &eye, world);
            let answer = super::served(&parts, |p| p, &selection, &eye, world);
            assert_eq!(answer, rule, "round {round}");
            if serves_everything(&parts, &selection) {
                assert_eq!(answer, Some(SOLE_MAP), "round {round}");
                sole += 1;
            } else {
                ruled += 1;
            }
        }
        assert!(sole > 1000 && ruled > 1000, "{sole} {ruled}");
    }
}
