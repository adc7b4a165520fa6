//! How a light's maps share the view, as data: the cascade selections engines ship — by eye depth
//! (interval) or by the first map that contains the point, blending across the overlap of two
//! cascades, and fading the shadow out toward the last cascade's far end. The rule that applies
//! them to a point is [`crate::serving`].

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

impl SelectionRule {
    /// Both rules.
    pub const ALL: [Self; 2] = [Self::Depth, Self::Containing];

    /// Its key in a preset's parameters: `depth` or `containing`.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Depth => "depth",
            Self::Containing => "containing",
        }
    }

    /// The rule named `key`.
    ///
    /// # Errors
    /// An unknown key, with the known ones.
    pub fn parse(key: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|r| r.key() == key)
            .ok_or_else(|| format!("unknown selection {key:?}; known: depth, containing"))
    }
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
