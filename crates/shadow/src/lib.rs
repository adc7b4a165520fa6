//! # shadowlab-shadow: the shadow-map techniques of the five papers
//!
//! A technique turns the eye, a light and the scene bounds into a light set-up: the view and
//! projection (or, for the logarithmic and paraboloid maps, the exact mapping) the shadow map is
//! rendered with.
//!
//! | technique | paper | module |
//! |---|---|---|
//! | uniform, focused on B | the standard shadow map; B of PSM §4.1 / LiSPSM §3.3 | `plan`, `warp` (LiSPSM with `n = ∞`) |
//! | uniform with frustum limiting | CG06 §6 | `plan` |
//! | PSM | Stamminger & Drettakis 2002 | [`psm`] |
//! | LiSPSM, any parameter rule or engine variant | Wimmer et al. 2004 §3; CAD; GMNPR; production-variants.md | `plan`, `warp`, `frame` |
//! | logarithmic | LiSPSM §4, Lloyd et al. 2008 | [`logarithmic`] |
//! | logarithmic, face-partitioned | Lloyd et al. EGSR 2006 §5.2, TOG 2008 | [`faces`] |
//! | scene-optimized (`optimal`) | CG06 Algorithm 1 (Chong & Gortler 2006) | [`optimal`] |
//! | engines' cascades (`bevy`, `filament`, `godot`, `babylon`, `threejs`, `unity`, `unreal`) | the engines' sources, `docs/engine-sources.md` | [`presets`], [`cascades`]; selection, blending and fading: `selection` |
//! | sample distribution (z-partitions from the eye pass's samples) | Lauritzen, Salvi & Lefohn, I3D 2011 | [`sdsm`] |
//! | cube map of a point light (`cube`) | Gerasimov, GPU Gems ch. 12, 2004; OpenGL 4.6 Table 8.19 | [`cube`], `omni` |
//! | dual-paraboloid map of a point light (`dual-paraboloid`) | Brabec, Annen & Seidel, CGI 2002 | [`paraboloid`], `omni` |
//!
//! Which kinds of light each technique serves: `Technique::check_light` (a point light: cube,
//! dual-paraboloid and PSM; the omnidirectional maps serve point lights only).
//!
//! Every light-space technique (uniform, LiSPSM, logarithmic) works in LiSPSM's light space
//! (`shadowlab_hull::LightSpace`: y toward the light, the viewer looking down −z), for spot lights
//! after the spot's perspective transform (LiSPSM §3.4). [`measure`] measures the aliasing of a
//! planned map, which the tests hold against the closed forms of `shadowlab-params`.
//!
//! # Conventions
//! The shadow map's window x runs across the light's view, window y along the warp axis (0 on the
//! viewer's side), depth away from the light; the depth test is `Less` for every technique. (The
//! scene-optimized map has no warp axis: its x and y follow the sides of the samples' rectangle.)
//! Matrices act on column vectors and produce GL clip space (NDC depth in `[−1, 1]`).

pub mod bias;
mod cascade_fit;
pub mod cascades;
pub mod cube;
mod error;
pub mod faces;
mod focus;
mod frame;
pub mod gather;
pub mod homogeneous;
mod input;
pub mod lanes;
pub mod logarithmic;
mod logarithmic_map;
mod lookup;
mod map;
pub mod measure;
mod omni;
pub mod optimal;
pub mod paraboloid;
mod paraboloid_map;
mod parameter;
mod partition;
mod plan;
pub mod presets;
pub mod psm;
mod render;
pub mod sdsm;
mod selection;
mod serving;
mod setup;
mod snap;
mod technique;
pub mod view;
mod warp;

pub use bias::{Bias, DepthComparison, LightTexel, NormalOffset};
pub use cascade_fit::{CascadeFit, Snap};
pub use error::ShadowError;
pub use faces::FaceRegion;
pub use input::{Eye, FocusPolicy, LightSource, PlanInput};
pub use lookup::{
    DEFAULT_DISK_SEED, DEFAULT_MIN_VARIANCE, Filter, GAUSSIAN_SIDE_PER_SIGMA, Kernel, Lookup,
    MomentMethod, Prefilter, Storage,
};
pub use map::{MapOptions, ShadowMap};
pub use omni::{LightFace, MIN_NEAR_FRACTION};
pub use partition::{CullingSphere, Partition, Region};
pub use plan::{Splits, plan, plan_partitions};
pub use render::{
    FLAT_SCENE_THICKNESS, FLAT_SCENE_ULPS, Frame, FrameOptions, GivenDepths, LightMaps,
    LightShadow, MapSource, PartitionMap, PlanOptions, Shadows, Timings, eye_image, eye_pass,
    lit_at, lit_with, plan_frame, plan_light, render_frame, render_shadows, scene_box, scene_eye,
    scene_input, selection_of, shadows_of,
};
pub use selection::{Beyond, Fade, FadeCurve, Selection, SelectionRule};
pub use serving::{Served, served};
pub use setup::{LaneMapping, LightSetup, ProjectiveMapping, PsmReport, ShadowMapping, WarpReport};
pub use snap::snap_to_texels;
pub use technique::{
    BlendWidth, Engine, LogarithmicChoice, NearDistance, PresetChoices, ProductionVariant,
    SdsmVariant, Stabilisation, StepDirection, Technique, WarpChoice,
};
