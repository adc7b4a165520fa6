//! Integration tests of `shadowlab-analysis`, one binary (ripgrep's layout):
//! - `truth`: hand-built cases (under the box or beside it, surfaces facing away, a spot's cone and
//!   segment), exact against map truth (bounded disagreement at edges), thread counts, errors;
//! - `attribution`: scenes where each cause of a misclassified pixel occurs alone (acne,
//!   peter-panning, aliasing, seams in a blend band and at a boundary), the causes summing to the
//!   misclassified pixels on every built-in scene, thread counts;
//! - `classify`: an aligned uniform map misclassifies nothing; counting and the difference
//!   image as documented;
//! - `aliasing`: the footprint against closed forms (a tilted plane, an independent construction
//!   per pixel, `measure`'s view-axis error at 90° and at any γ), statistics, thread counts;
//! - `images`: the heat map's colours and scale, the difference image's classes counted;
//! - `pictures`: the annotated pictures hold the raw ones pixel for pixel, their titles and keys;
//! - `report_html`: `report.html` in headless Chromium (loads, sorts, switches, no errors);
//! - `setup_file`: the set-up format written and read back bit for bit, every convention
//!   converted, cameras from their matrices, every error naming the file and the field;
//! - `evaluate`: a written set-up measures what analyzing its technique measures; images
//!   shadowlab wrote measure what rendering does; a perturbed map as its rule predicts; shimmer as
//!   `temporal`'s;
//! - `sweep`: the logarithmic map's misclassified pixels continuous across γ = φ and at γ = 0;
//! - `point_lights`: the cube and paraboloid maps against the exact truth, converging with
//!   resolution; the range bounding truth and maps; a study refusing a technique that cannot
//!   serve a point light;
//! - `temporal`: the camera walk, and a frame where the optimizer keeps the initial map;
//! - `view_axis`: measured on the matrices against the closed form at 90°;
//! - `support`: scenes, hand-built eye images, the seeded configuration.

mod aliasing;
mod attribution;
mod classify;
mod evaluate;
mod images;
mod pictures;
mod point_lights;
mod report_html;
mod setup_file;
mod support;
mod sweep;
mod temporal;
mod truth;
mod view_axis;
