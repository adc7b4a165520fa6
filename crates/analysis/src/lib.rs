//! # shadowlab-analysis: what a shadow-map technique costs and buys, measured
//!
//! `shadow` makes a technique's frame; this crate holds it against the truth and measures its
//! aliasing. It never re-implements a technique.
//!
//! | module | what | source |
//! |---|---|---|
//! | [`truth`] | whether each visible point is lit by each light: exactly, one shadow ray per pixel ([`truth::exact_truth`], `shadowlab-trace`), or from a very fine uniform map ([`truth::map_truth`]) | CG06 §5 (map truth) |
//! | [`classify`] | falsely lit and falsely shadowed pixels of a frame against a truth, and their picture | — |
//! | [`attribution`] | each misclassified pixel's cause — acne, peter-panning, a partition seam, aliasing — counted and pictured | — |
//! | [`aliasing`] | the texel's footprint on screen per pixel from the Jacobian of screen → shadow map on the visible surface, split into perspective and projection parts | CG06 eqs. 4–6, LiSPSM eq. 1; formulas.md §1, §6 |
//! | [`export`] | every per-pixel result as NumPy arrays and EXR channels with an index: eye pass, truth, lookups and their classes, footprints, raw map depths | — |
//! | [`images`] | heat maps of per-pixel values on a logarithmic viridis scale; the colour bar and the difference image's legend | — |
//! | [`pictures`] | a study's pictures as files: raw (pixel for pixel) and annotated (title, settings, colour bar or legend) | — |
//! | [`study`] | one scene, every combination of technique, resolution, partitions and filter, measured against one exact truth in one run | CG06 §5 (their table) |
//! | [`report`] | a study as `report.md`, `report.html` (self-contained, sortable tables, the pictures side by side), `results.csv`, `results.json` and a Pareto plot of time against misclassified pixels | — |
//! | [`sweep`] | the light swept from parallel to perpendicular to the view: errors and aliasing per angle | formulas.md §9 (near-parallel policies) |
//! | [`view_axis`] | the perspective error along the view axis, measured on each technique's matrices over the closed form of `shadowlab-params` | LiSPSM eq. 3, GMNPR eq. 2, CAD eq. 12 |
//! | [`setup_file`] | a shadow set-up as an engine dumps it (per frame, light and partition: matrices, depth range, map size, format, bias, filter, depth images), read in any convention and written for every technique that is a matrix per partition | docs/setup-format.md |
//! | [`evaluate`] | a set-up file's maps against the exact truth, frame by frame, as `analyze` measures a technique and `temporal` counts shimmer | — |
//! | [`temporal`] | a moving camera: pixels whose shadow flips while the truth does not ("shimmer"), with and without texel snapping | production-variants.md (snapping) |
//!
//! ```no_run
//! use shadowlab_analysis::{aliasing, classify, truth};
//! use shadowlab_shadow::{FrameOptions, render_frame};
//!
//! # fn run(options: &FrameOptions) -> Result<(), shadowlab_analysis::AnalysisError> {
//! let scene = shadowlab_scene::builtin_scene("outdoor").expect("a built-in scene");
//! let frame = render_frame(&scene, options)?;
//! let bvh = truth::scene_bvh(&scene)?;
//! let exact = truth::exact_truth(&scene, &frame.eye, &bvh)?;
//! let wrong = classify::misclassification(&exact, &frame.lit);
//! println!("{:.3} % misclassified", wrong.percentage());
//! let (partition, map) = &frame.lights[0].maps[0];
//! let footprints = aliasing::footprints(&partition.setup, map.resolution, &frame.eye, &scene.camera);
//! let [worst, ..] = footprints.stats();
//! println!("max {} pixels per texel, p99 {}", worst.max, worst.p99);
//! # Ok(())
//! # }
//! ```
//!
//! # Conventions
//! Per-pixel vectors are row-major with row 0 at the bottom, like the eye image (`shadowlab-raster`);
//! per-light vectors follow the scene's light order. Every result is the same on any thread count.

#![deny(missing_docs)]

pub mod aliasing;
pub mod attribution;
pub mod bias_sweep;
pub mod classify;
mod document;
mod error;
pub mod evaluate;
mod exact_sum;
pub mod export;
mod html;
mod hypot;
pub mod images;
mod labels;
pub mod leaks;
pub mod pictures;
pub mod report;
pub mod setup_file;
pub mod study;
pub mod sweep;
mod tally;
pub mod temporal;
pub mod truth;
pub mod view_axis;

pub use error::AnalysisError;
