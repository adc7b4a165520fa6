//! How a cascade's window is fitted to its slice and stabilised on the texel grid: the engines'
//! choices as data, which presets name and users override (`bevy:fit=sphere`); the fitting itself
//! is [`crate::cascades`].

use std::fmt;

/// How a cascade's window is fitted to its slice (the slice's eight corners in the light basis).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CascadeFit {
    /// A square of side `d` = the larger of the slice's body diagonal and far-face diagonal (Bevy:
    /// `max(|c₀ − c₆|, |c₄ − c₆|)` in its corner order), which no rotation of the camera changes — centred on the box of the
    /// corners, `d` rounded up to a whole world unit when `ceil` (Bevy `calculate_cascade`; three.js
    /// CSM `updateShadowBounds` without rounding).
    Diagonal {
        /// Round the side up to a whole unit (Bevy).
        ceil: bool,
    },
    /// The axis-aligned box of the corners in the light basis (Babylon's
    /// `_computeCascadeFrustum` with `stabilizeCascades` off); not square, and it turns with the
    /// camera.
    CornerBox,
    /// The bounding sphere of the corners about their centroid (radius the largest distance), its
    /// radius multiplied by `border` (Godot `_light_instance_setup_directional_shadow`:
    /// `size/(size − 2)`, a texel each side; Unity URP's culling sphere, fitted by closed native
    /// code — unverified, taken as this sphere with no border), the window the square around it.
    Sphere {
        /// Godot's one-texel border on each side.
        texel_border: bool,
    },
}

/// How a cascade's window is moved onto the texel grid, in the light basis (whose origin is the
/// world origin, so a grid fixed in the world).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Snap {
    /// None.
    Off,
    /// The window's centre floored to a multiple of `texels` texels (Bevy `calculate_cascade`,
    /// three.js CSM `update`: `floor(c/t)·t`).
    CentreFloor {
        /// The grid, in texels.
        texels: u32,
    },
    /// The window's centre rounded to a multiple of `texels` texels (Babylon `_computeMatrices`:
    /// the world origin's NDC rounded to whole texels; Unreal, unverified).
    CentreRound {
        /// The grid, in texels.
        texels: u32,
    },
    /// Each edge of the window rounded to a multiple of `texels` texels (Godot
    /// `Math::snapped(x, 4r/size)`: 2 texels).
    EdgesRound {
        /// The grid, in texels.
        texels: u32,
    },
}

impl CascadeFit {
    /// Every fit, in the order messages list them.
    pub const ALL: [Self; 5] = [
        Self::Diagonal { ceil: false },
        Self::Diagonal { ceil: true },
        Self::CornerBox,
        Self::Sphere {
            texel_border: false,
        },
        Self::Sphere { texel_border: true },
    ];

    /// Its key in a preset's parameters: `diagonal`, `diagonal-ceil`, `box`, `sphere`,
    /// `sphere-border`.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Self::Diagonal { ceil: false } => "diagonal",
            Self::Diagonal { ceil: true } => "diagonal-ceil",
            Self::CornerBox => "box",
            Self::Sphere {
                texel_border: false,
            } => "sphere",
            Self::Sphere { texel_border: true } => "sphere-border",
        }
    }

    /// The fit named `key`.
    ///
    /// # Errors
    /// An unknown key, with the known ones.
    pub fn parse(key: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|f| f.key() == key)
            .ok_or_else(|| {
                let known: Vec<&str> = Self::ALL.iter().map(|f| f.key()).collect();
                format!("unknown cascade fit {key:?}; known: {}", known.join(", "))
            })
    }
}

impl fmt::Display for CascadeFit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.key())
    }
}
