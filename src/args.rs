//! The command line, declared with clap.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};

/// shadowlab: what a shadow-map technique costs and what it buys, with numbers.
#[derive(Debug, Parser)]
#[command(name = "shadowlab", version, about, long_about = None)]
pub(crate) struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub(crate) command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub(crate) enum Command {
    /// Every technique's warp parameter and maximum error for one configuration, in the 2-D
    /// view-frustum model of the papers (B = V).
    Params(ParamsArgs),
    /// Write the closed-form figures (CSV, SVG, PNG): the papers' plots and the ones they lack.
    Curves(CurvesArgs),
    /// Rasterize a mesh in the benchmark's light and eye views and write the depth images (PNG and
    /// EXR), for comparison with any other renderer.
    RenderMesh(RenderMeshArgs),
}

/// Arguments of `shadowlab render-mesh`.
#[derive(Debug, Args)]
pub(crate) struct RenderMeshArgs {
    /// The mesh, a Wavefront OBJ file.
    pub(crate) mesh: PathBuf,
    /// Only the light pass (orthographic, size × size).
    #[arg(long, conflicts_with = "eye")]
    pub(crate) light: bool,
    /// Only the eye pass (perspective, --eye-size).
    #[arg(long)]
    pub(crate) eye: bool,
    /// Side of the light pass's square target, in pixels.
    #[arg(long, default_value_t = 2048, value_parser = clap::value_parser!(u32).range(1..=16384))]
    pub(crate) size: u32,
    /// Size of the eye pass's target, WIDTHxHEIGHT.
    #[arg(long, default_value = "1024x768", value_parser = parse_size)]
    pub(crate) eye_size: (u32, u32),
    /// Round positions and matrices to f32 first, as a GPU's vertex buffers and uniforms hold them
    /// (the rasterizer still works in f64 from there); for pixel comparisons with GL renderers.
    #[arg(long)]
    pub(crate) f32_inputs: bool,
    /// Also write each depth image as a NumPy .npy file (f32, row 0 at the bottom, as GL reads it
    /// back), for pixel comparisons with other renderers (e.g. the peer harness's --dump).
    #[arg(long)]
    pub(crate) npy: bool,
    /// Directory to write into (created if missing): MESH-light.{png,exr}, MESH-eye.{png,exr}.
    #[arg(long, default_value = "out/render")]
    pub(crate) out: PathBuf,
}

fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once('x')
        .ok_or("expected WIDTHxHEIGHT, e.g. 1024x768")?;
    let side = |s: &str| {
        s.parse::<u32>()
            .ok()
            .filter(|v| (1..=16384).contains(v))
            .ok_or_else(|| format!("{s:?} is not a size between 1 and 16384"))
    };
    Ok((side(w)?, side(h)?))
}

/// Arguments of `shadowlab params`.
#[derive(Debug, Args)]
pub(crate) struct ParamsArgs {
    /// Eye near distance (> 0).
    #[arg(long)]
    pub(crate) near: f64,
    /// Eye far distance (> near).
    #[arg(long)]
    pub(crate) far: f64,
    /// Full field of view in degrees, in the plane of the light and view directions (0 < fov < 180).
    #[arg(long)]
    pub(crate) fov: f64,
    /// Angle between light and view directions in degrees, 0 (parallel) to 90 (perpendicular).
    #[arg(long)]
    pub(crate) gamma: f64,
    /// Which fall-back curve r(γ) the CAD survey's eq. 16 uses below γ_lim.
    #[arg(long, value_enum, default_value_t = CadFalloff::Eq18)]
    pub(crate) cad_r: CadFalloff,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub(crate) json: bool,
}

/// The fall-back curves of CAD eq. 16.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum CadFalloff {
    /// r = 1 + sin((γ/γlim − 1)·π/2), the reconstructed eq. 18 (the paper's choice).
    Eq18,
    /// r = sin(γ/γlim·π/2), eq. 17.
    Eq17,
    /// r = sin²(γ/γlim·π/2).
    Sin2,
}

/// Arguments of `shadowlab curves`.
#[derive(Debug, Args)]
pub(crate) struct CurvesArgs {
    /// A figure to write (repeatable); all of them when none is named.
    #[arg(long = "figure", value_name = "NAME", value_parser = figure_name)]
    pub(crate) figures: Vec<shadowlab_curves::FigureName>,
    /// Directory to write into (created if missing).
    #[arg(long, default_value = "out/curves")]
    pub(crate) out: PathBuf,
    /// Eye near distance of every figure.
    #[arg(long, default_value_t = 1.0)]
    pub(crate) near: f64,
    /// Eye far distance of every figure.
    #[arg(long, default_value_t = 100.0)]
    pub(crate) far: f64,
    /// Full field of view in degrees of every figure.
    #[arg(long, default_value_t = 60.0)]
    pub(crate) fov: f64,
}

fn figure_name(text: &str) -> Result<shadowlab_curves::FigureName, String> {
    shadowlab_curves::FigureName::from_key(text).ok_or_else(|| {
        let names: Vec<&str> = shadowlab_curves::FigureName::ALL
            .iter()
            .map(|f| f.key())
            .collect();
        format!("unknown figure; the figures are: {}", names.join(", "))
    })
}
