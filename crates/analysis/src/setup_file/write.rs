//! Writing the set-up shadowlab plans for a technique, in the format it reads back: evaluating
//! the file gives what analyzing the technique gives, bit for bit (timings aside).

use glam::DMat4;
use shadowlab_hull::NdcDepth;
use shadowlab_scene::{Camera, Scene};
use shadowlab_shadow::{
    FrameOptions, Partition, Region, ShadowMapping, Technique, eye_pass, plan_frame,
};

use super::error::SetupError;
use super::file::{
    CameraEntry, Conventions, FORMAT, FrameEntry, LightEntry, PartitionEntry, SetupFile, VERSION,
};
use crate::report::filter_label;

/// The set-up of `scene`'s frame as `options` plans it: every light's partitions as
/// [`shadowlab_shadow::render_shadows`] renders them (planned after the eye pass, whose nearest
/// visible depth is PSM's near plane; snapped if `options.snap_texels` says so), each with the
/// map size, depth format, bias and filter of `options`. One frame, without a camera (the scene's
/// own), in [`Conventions::LIBRARY`], so that reading it back changes no bit.
///
/// # Errors
/// [`SetupError::NotRepresentable`] for an engine's preset (its per-cascade bias and selection
/// are not in the format) and for the logarithmic map (`logarithmic`, `logarithmic:faces`):
/// it is not a matrix per partition (docs/setup-format.md); [`SetupError::Analysis`] if the
/// technique cannot be planned for the scene.
pub fn setup_for(scene: &Scene, options: &FrameOptions) -> Result<SetupFile, SetupError> {
    let technique = options.plan.technique;
    if let Technique::Engine(..) = technique {
        return Err(SetupError::NotRepresentable {
            technique,
            reason: format!(
                "an engine's preset reads its cascades with its engine's bias per cascade and \
                 chooses between them by its own rule (blend bands, culling spheres, a shadow \
                 distance, a fade), which version {VERSION} of the set-up format has no fields \
                 for; measure the preset with analyze"
            ),
        });
    }
    let (eye, nearest_visible) = eye_pass(scene)?;
    let lights = plan_frame(scene, options, nearest_visible, Some(&eye))?
        .iter()
        .map(|partitions| {
            Ok(LightEntry {
                partitions: partitions
                    .iter()
                    .map(|partition| entry(partition, technique, options))
                    .collect::<Result<_, SetupError>>()?,
            })
        })
        .collect::<Result<_, SetupError>>()?;
    Ok(SetupFile {
        format: FORMAT.into(),
        version: VERSION,
        source: Some(format!(
            "shadowlab-analysis {}: scene {:?}, technique {}, {}² {} maps",
            env!("CARGO_PKG_VERSION"),
            scene.name,
            technique.spec(),
            options.resolution,
            options.format.key_name()
        )),
        technique: Some(technique.spec()),
        conventions: Conventions::LIBRARY,
        frames: vec![FrameEntry {
            camera: None,
            lights,
        }],
    })
}

/// The entry of one planned partition.
fn entry(
    partition: &Partition,
    technique: Technique,
    options: &FrameOptions,
) -> Result<PartitionEntry, SetupError> {
    let refused = |reason: &str| SetupError::NotRepresentable {
        technique,
        reason: reason.into(),
    };
    let (view, projection) = match (&partition.face, &partition.setup.mapping) {
        (None, ShadowMapping::Projective(mapping)) => (mapping.view(), mapping.projection()),
        (face, ShadowMapping::Logarithmic(_)) => {
            return Err(refused(&format!(
                "the logarithmic map is not a matrix per partition: its warp \
                 ln(1 + κτ)/ln(1 + κ) is not projective, and shadowlab makes it by casting one \
                 ray per texel through its exact inverse; no engine renders it from a view and a \
                 projection matrix, so version {VERSION} of the set-up format has no fields for \
                 it{}",
                if face.is_some() {
                    " (and its face partitions are chosen per pixel by the face of the view \
                     frustum a point projects into, not by eye depth)"
                } else {
                    ""
                }
            )));
        }
        (_, ShadowMapping::Paraboloid(_)) => {
            return Err(refused(&format!(
                "a dual-paraboloid hemisphere is not a matrix: the paraboloid (x, y) = \
                 (d_x, d_y)/(1 + d_z) is not projective, so version {VERSION} of the set-up format \
                 has no fields for it"
            )));
        }
        (Some(Region::LightFace(_)), ShadowMapping::Projective(_)) => {
            return Err(refused(
                "its faces are chosen per pixel by the direction from the light (a cube map), \
                 and the format's partitions are chosen by eye depth alone",
            ));
        }
        (Some(Region::ViewFace(_)), ShadowMapping::Projective(_)) => {
            return Err(refused(
                "its partitions are chosen per pixel by the face of the view frustum a point \
                 projects into, and the format's partitions are chosen by eye depth alone",
            ));
        }
    };
    Ok(PartitionEntry {
        near: partition.near,
        far: partition.far,
        view: row_major(&view),
        projection: row_major(&projection),
        map_size: options.resolution,
        depth_format: options.format.key_name().into(),
        bias: options.lookup.bias.to_string(),
        filter: filter_label(&options.lookup.filter),
        depth_image: None,
        second_depth_image: None,
    })
}

/// A matrix's 16 numbers row by row.
fn row_major(m: &DMat4) -> [f64; 16] {
    m.transpose().to_cols_array()
}

impl CameraEntry {
    /// The entry of `camera` in [`Conventions::LIBRARY`]: its view matrix and GL projection, row by
    /// row, and its image size. Read back, the eye pass is drawn through exactly the product
    /// `camera.view_projection` draws it through.
    #[must_use]
    pub fn of(camera: &Camera) -> Self {
        Self {
            view: row_major(&camera.pose.view_matrix()),
            projection: row_major(&camera.projection.matrix(NdcDepth::NegativeOneToOne)),
            width: Some(camera.width),
            height: Some(camera.height),
        }
    }
}

impl SetupFile {
    /// The file's JSON text (pretty-printed, numbers in their shortest round-trip form, a final
    /// newline).
    #[must_use]
    pub fn to_json(&self) -> String {
        let mut text = serde_json::to_string_pretty(self).expect("a set-up file is plain data");
        text.push('\n');
        text
    }
}
