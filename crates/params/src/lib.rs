//! The mathematics of perspective shadow-map reparameterisation: every warp parameter and
//! closed-form aliasing error of five papers, in f64, with their domains in the types.
//!
//! | module | paper |
//! |---|---|
//! | [`lispsm`], [`logarithmic`] | LiSPSM Wimmer, Scherzer, Purgathofer, *Light Space Perspective Shadow Maps*, EGSR 2004, doi 10.2312/EGWR/EGSR04/143-151; the logarithmic ideal after Lloyd et al., ACM TOG 27(4), 2008 |
//! | [`cad`], [`splits`], [`bias`], [`vsm`] | CAD Barroso & Celes, *Improved Real-Time Shadow Mapping for CAD Models*, SIBGRAPI 2007, doi 10.1109/SIBGRAPI.2007.36 |
//! | [`gmnpr`] | GMNPR *Theory to Practice: Generalized Minimum-Norm Perspective Shadow Maps*, ICEC 2007, LNCS 4740, 66–78 |
//! | [`esm`] | ESM Annen, Mertens, Seidel, Flerackers & Kautz, *Exponential Shadow Maps*, Graphics Interface 2008 |
//! | [`evsm`] | EVSM Lauritzen & McCool, *Layered Variance Shadow Maps*, Graphics Interface 2008 (the exponential warps), with VSM's bound |
//! | [`msm`] | MSM Peters & Klein, *Moment Shadow Mapping*, I3D 2015, doi 10.1145/2699276.2699277 (Hamburger 4MSM, depths in `[0, 1]`) |
//! | [`filterable`] | the filterable maps side by side (VSM, ESM, EVSM2, EVSM4, MSM): memory per texel, shared depth samples |
//! | [`storage`] | their moments in 32- and 16-bit float textures: IEEE rounding, the blur pass in f32, overflow |
//! | [`model`] | the 2-D view-frustum model shared by CAD eqs. 10–12 and GMNPR eq. 2 |
//! | [`rule`] | all parameter choices side by side, and the true minimax of the model |
//!
//! PSM (Stamminger & Drettakis, SIGGRAPH 2002) and CG06 (Chong & Gortler, Harvard TR-11-06)
//! enter through the limits `n = zn` of [`lispsm`] and through later crates.
//!
//! The reference for every formula is the project's `formulas.md` (in `shared/docs/`): it
//! reconstructs the formulas from the OCR'd papers, corrects 19 OCR errors and gives the stable
//! forms used here. Each function's documentation cites paper, equation and the section of that file.
//!
//! # Example
//! The best warp for a light at 45° to a 60° view of depths 1 to 100, and what each paper's choice
//! costs against it:
//! ```
//! use shadowlab_params::{DepthRange, FrustumModel, HalfFov, LightAngle, ParameterRule};
//!
//! let model = FrustumModel::new(DepthRange::new(1.0, 100.0)?, HalfFov::from_full_fov_degrees(60.0)?);
//! let gamma = LightAngle::from_degrees(45.0)?;
//! let best = ParameterRule::Minimax.evaluate(&model, gamma).expect("defined at every angle");
//! assert!((best.warp.lambda() - 0.0662544798897).abs() < 1e-12); // formulas.md §8.4
//! for rule in ParameterRule::ALL {
//!     if let Some(e) = rule.evaluate(&model, gamma) {
//!         assert!(e.max_error >= best.max_error * (1.0 - 1e-12), "{}", rule.key());
//!     }
//! }
//! # Ok::<(), shadowlab_params::ParamError>(())
//! ```
//!
//! # Conventions
//! * γ (LiSPSM, CAD) = θ (GMNPR) is the smallest angle between light and view directions,
//!   `0 ≤ γ ≤ π/2`; π/2 is the ideal case. φ is half the field of view in the light–view plane.
//! * Distances are in one world unit; only ratios matter.
//! * The warp is described by λ = n'/(f' − n') ([`WarpParameter`]): λ = ∞ is the uniform map.
//!   Functions in a paper's own variables (`n` of LiSPSM, `n'` of CAD) accept `f64::INFINITY`
//!   for "uniform" where the paper does.
//! * Error normalisations: LiSPSM's `dp/ds = (1/z)·dz/ds` (screen `[0, 1]`); GMNPR's
//!   `F = dp/ds / tan φ` (screen `[−1, 1]`); CAD's `m_z = (res_c/res_l)·F/2`.
//!
//! # Domains
//! A bad input is an `Err(ParamError)` naming the parameter, never a NaN. Near the singular points
//! the stable forms of formulas.md §9 are used: γ = 0 exactly gives `f64::INFINITY` for parameters
//! (meaning "uniform") and for errors (the view axis collapses onto one shadow-map row: unbounded);
//! θ at and around φ, θ_0 and θ1 are evaluated without `tan θ`; `f/n` from `1 + 1e-9` to `1e12`
//! without cancellation in `f − n`, `√(f/n) − 1` or `ln(f/n)`.

pub mod bias;
pub mod cad;
mod depth_samples;
mod domain;
mod error;
pub mod esm;
pub mod evsm;
pub mod filterable;
pub mod gmnpr;
pub mod lispsm;
pub mod logarithmic;
pub mod model;
pub mod msm;
pub mod rule;
pub mod splits;
pub mod storage;
pub mod vsm;

pub use domain::{DepthRange, HalfFov, LightAngle, WarpParameter};
pub use error::ParamError;
pub use filterable::FilterableMethod;
pub use model::{FrustumModel, ModelCase};
pub use rule::{ParameterRule, RuleEvaluation};
