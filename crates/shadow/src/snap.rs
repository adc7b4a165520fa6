//! Texel snapping, the stabilisation engines ship against shimmer (production-variants.md): the
//! map's window moved by less than `texels` texels so that a fixed world point — the world origin —
//! falls on a corner of the `texels`-texel grid. As the camera moves, the window then moves in whole
//! steps of that grid, and a shadow that does not move stays on the same texels — as long as the
//! window's size and orientation stay the same, which the focusing fits here do not guarantee
//! (engines also round the window's size, or fit a bounding sphere; we measure snapping alone).
//! Bevy, three.js and OGRE snap to 1 texel, Filament and Godot to 2.

use glam::{DMat4, DVec3, DVec4};

use crate::setup::{LightSetup, ProjectiveMapping, ShadowMapping};
use crate::technique::Technique;

/// `setup` with its window snapped to the `texels`-texel grid of a `resolution`-texel map. The
/// maps that are not projective (logarithmic, paraboloid) are returned unchanged, and so is a cube
/// face: its grid is fixed to the light and the world's axes already, and a shifted face would no
/// longer meet its neighbours edge to edge.
#[must_use]
pub fn snap_to_texels(setup: &LightSetup, resolution: u32, texels: u32) -> LightSetup {
    let ShadowMapping::Projective(mapping) = setup.mapping else {
        return setup.clone();
    };
    if setup.technique == Technique::Cube {
        return setup.clone();
    }
    let clip = mapping.clip_from_world() * DVec3::ZERO.extend(1.0);
    if clip.w <= 0.0 || texels == 0 {
        return setup.clone();
    }
    let grid = 2.0 * f64::from(texels) / f64::from(resolution);
    let ndc = clip.truncate() / clip.w;
    let snapped = |v: f64| (v / grid).round() * grid - v;
    let (dx, dy) = (snapped(ndc.x), snapped(ndc.y));
    // An NDC translation: S·(x, y, z, w) = (x + dx·w, y + dy·w, z, w).
    let shift = DMat4::from_cols(DVec4::X, DVec4::Y, DVec4::Z, DVec4::new(dx, dy, 0.0, 1.0));
    let mut snapped_setup = setup.clone();
    snapped_setup.mapping = ShadowMapping::Projective(ProjectiveMapping::new(
        mapping.view(),
        shift * mapping.projection(),
    ));
    snapped_setup
}
