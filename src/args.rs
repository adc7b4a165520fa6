//! The command line, declared with clap. Every numeric flag takes negative numbers
//! (`allow_negative_numbers`) and every flag whose value is a spec or a size takes values that
//! start with `-`, so that a bad value reaches its check, which names the flag and the allowed
//! range, instead of clap reading it as an unknown flag.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};
use shadowlab_raster::{DepthFormat, MAX_TARGET_SIZE};
use shadowlab_shadow::optimal::{BORDER, INITIAL_MAP_RESOLUTION, ITERATIONS, READBACK_SIZE};
use shadowlab_shadow::{Bias, Filter, FocusPolicy, Splits, Technique};

use shadowlab_sweep::Shard;

use crate::memory::Bytes;

/// The most timing runs per combination `analyze` takes.
const MAX_TIMING_RUNS: u64 = 100;

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
    /// Render a scene with shadows by one technique: the shaded eye view, every shadow map, and
    /// the light's view with the eye frustum and the focus body outlined.
    Render(RenderArgs),
    /// Print what a technique decides for a scene: γ, the warp parameter, the focus body B, the
    /// light's view and projection matrices, the split distances.
    Inspect(InspectArgs),
    /// Render a scene with several techniques and put the same crop of each eye view side by side
    /// in one labelled picture.
    Compare(CompareArgs),
    /// Measure what each technique costs and buys on a scene: misclassified pixels against the
    /// exact truth, the texel footprint on screen, time; written as a report with tables, CSV,
    /// JSON, a Pareto plot, heatmaps and difference images.
    Analyze(AnalyzeArgs),
    /// Sweep the light from parallel to perpendicular to the view and plot each technique's
    /// misclassified pixels and largest texel footprint, to show continuity at γ = 0.
    SweepAngle(SweepArgs),
    /// Walk the camera and count the pixels whose shadow flips while the truth does not
    /// (shimmer), per technique, with and without texel snapping.
    Temporal(TemporalArgs),
    /// Measure an engine's own shadow set-up (a set-up file: per frame, light and partition its
    /// matrices, map size, format, bias, filter, optionally its depth images) against the exact
    /// truth, as analyze measures a technique; over several frames, its shimmer too.
    Evaluate(EvaluateArgs),
    /// Run a study spec (TOML: scenes × techniques × resolutions × partitions × filters × light
    /// directions × camera poses), whole or one shard of it, into a resumable sweep directory;
    /// or print its size (--dry-run), an example spec (--example), or a Slurm job array for it
    /// (--slurm). docs/cluster.md.
    Sweep(SweepSpecArgs),
    /// Merge the cells of one sweep from one or more sweep directories (its shards) into one
    /// table (CSV, Parquet) and one report: the same, timings aside, as the sweep run whole.
    Merge(MergeArgs),
}

/// Arguments of `shadowlab sweep`.
#[derive(Debug, Args)]
pub(crate) struct SweepSpecArgs {
    /// The sweep spec (TOML; `shadowlab sweep --example` prints one).
    #[arg(value_name = "SPEC", required_unless_present = "example")]
    pub(crate) spec: Option<PathBuf>,
    /// Print a small commented spec that runs as it is, and exit.
    #[arg(long, conflicts_with_all = ["spec", "dry_run", "shard", "slurm", "out"])]
    pub(crate) example: bool,
    /// Print the number of frames and cells and the estimated work (per shard with --shard or
    /// --shards) and, if the sweep directory holds this sweep, how many cells are done; run
    /// nothing.
    #[arg(long)]
    pub(crate) dry_run: bool,
    /// The sweep directory: cells/ (one result per cell), shard-I-of-N/ (each finished shard's
    /// table) and, for a whole run, merged/. Rerunning into it resumes. Default:
    /// out/sweep/SPEC-NAME.
    #[arg(long, value_name = "DIR")]
    pub(crate) out: Option<PathBuf>,
    /// Run only shard I of N (0-based): a deterministic, cost-balanced share of the cells.
    #[arg(long, value_name = "I/N", value_parser = shard_spec, conflicts_with = "slurm")]
    pub(crate) shard: Option<Shard>,
    /// Write a Slurm job array for the sweep (DIR/slurm/array.sbatch, one task per shard; the
    /// merge as a dependent job, merge.sbatch; submit.sh submits both) and run nothing.
    #[arg(long, requires = "shards")]
    pub(crate) slurm: bool,
    /// The number of shards of --slurm or --dry-run.
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = shard_count)]
    pub(crate) shards: Option<usize>,
    /// An extra `#SBATCH` option for the job array's script, e.g. `--partition=short` or
    /// `--time=01:00:00` (repeatable).
    #[arg(
        long,
        value_name = "OPTION",
        requires = "slurm",
        allow_hyphen_values = true
    )]
    pub(crate) sbatch_option: Vec<String>,
}

/// Arguments of `shadowlab merge`.
#[derive(Debug, Args)]
pub(crate) struct MergeArgs {
    /// Sweep directories holding the cells (one per shard, or one shared).
    #[arg(value_name = "DIR", required = true)]
    pub(crate) dirs: Vec<PathBuf>,
    /// Directory to write the merged table and report into (an output set).
    #[arg(long, value_name = "DIR")]
    pub(crate) out: PathBuf,
}

/// A shard, `I/N` ([`Shard::parse`]).
fn shard_spec(text: &str) -> Result<Shard, String> {
    Shard::parse(&value_not_flag(text)?)
}

/// A shard count in `1..=MAX_SHARDS`.
fn shard_count(text: &str) -> Result<usize, String> {
    text.parse::<usize>()
        .ok()
        .filter(|n| (1..=shadowlab_sweep::shard::MAX_SHARDS).contains(n))
        .ok_or_else(|| {
            format!(
                "`{text}` is not a shard count in 1..={}",
                shadowlab_sweep::shard::MAX_SHARDS
            )
        })
}

/// Arguments of `shadowlab evaluate`.
#[derive(Debug, Args)]
pub(crate) struct EvaluateArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArg,
    /// The set-up file (JSON, docs/setup-format.md), e.g. written by `inspect --setup-json`.
    #[arg(long, value_name = "FILE")]
    pub(crate) setup: PathBuf,
    /// Also write every per-pixel result under export/ (each frame's eye pass, exact truth,
    /// lookups, classes, footprints and maps; the scene as glTF and OBJ), docs/outputs.md.
    #[arg(long)]
    pub(crate) export: bool,
    #[command(flatten)]
    pub(crate) memory: MemoryArgs,
    /// Directory to write into. Default: out/evaluate/SCENE.
    #[arg(long)]
    pub(crate) out: Option<PathBuf>,
}

/// A value that may begin with `-` (flags that take one accept it, so that the flag's own check
/// refuses a bad value), but not a flag: `--technique --resolution 5` would otherwise take
/// `--resolution` as the technique.
fn value_not_flag(value: &str) -> Result<String, String> {
    if value.starts_with("--") {
        Err(format!(
            "`{value}` is a flag, not a value: give this flag a value before the next flag"
        ))
    } else {
        Ok(value.to_string())
    }
}

/// A technique spec, `TECHNIQUE` or `TECHNIQUE:PARAMETER` ([`Technique::parse_spec`]).
fn technique_spec(text: &str) -> Result<Technique, String> {
    Technique::parse_spec(&value_not_flag(text)?)
}

/// A bias ([`Bias::parse`]).
fn bias_spec(text: &str) -> Result<Bias, String> {
    Bias::parse(&value_not_flag(text)?)
}

/// A lookup filter ([`Filter::parse`]).
fn filter_spec(text: &str) -> Result<Filter, String> {
    Filter::parse(&value_not_flag(text)?)
}

/// A filter in a comma-separated list, its own numbers separated by `;` (`disk:16;1.5`).
fn filter_in_list(text: &str) -> Result<Filter, String> {
    Filter::parse(&value_not_flag(text)?.replace(';', ","))
}

/// A split scheme ([`Splits::parse`]).
fn split_scheme(text: &str) -> Result<Splits, String> {
    Splits::parse(&value_not_flag(text)?)
}

/// A depth format by its key ([`DepthFormat::parse`]).
fn depth_format(text: &str) -> Result<DepthFormat, String> {
    DepthFormat::parse(&value_not_flag(text)?)
}

/// The scene of every command that takes one.
#[derive(Debug, Args)]
pub(crate) struct SceneArg {
    /// A built-in scene (outdoor, dueling-frusta, cad-lattice, chess-spot, bunny, room-point,
    /// chess-point), a scene file
    /// (.toml) or a glTF 2.0 file (.gltf, .glb: its camera and lights, defaults otherwise).
    /// Default: outdoor.
    #[arg(value_name = "SCENE")]
    pub(crate) name: Option<String>,
    /// The scene of the glTF file to load, by index (default: the file's default scene).
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = clap::value_parser!(usize))]
    pub(crate) gltf_scene: Option<usize>,
}

pub(crate) use shadowlab_analysis::study::DEFAULT_TECHNIQUES as ALL_TECHNIQUES;

/// Arguments of `shadowlab analyze`.
#[derive(Debug, Args)]
pub(crate) struct AnalyzeArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArg,
    /// The techniques, comma-separated: each TECHNIQUE or TECHNIQUE:PARAMETER (lispsm:minimax,
    /// optimal:refit, sdsm:kmeans), or an engine's preset (bevy, filament, godot, babylon, threejs,
    /// unity, unreal), with choices of its own after a colon, +-joined: unsnapped, fit=diagonal|
    /// diagonal-ceil|box|sphere|sphere-border, blend=W (0 ≤ W < 1), select=depth|containing
    /// (godot:unsnapped+blend=0.1).
    /// Default: uniform, uniform_limited, psm, lispsm, lispsm:minimax, logarithmic, optimal, sdsm;
    /// for a scene of point lights: cube, dual-paraboloid, psm.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, value_parser = technique_spec)]
    pub(crate) techniques: Option<Vec<Technique>>,
    /// Shadow-map sides, comma-separated (Chong and Gortler's: 750 to 2000).
    #[arg(long, value_delimiter = ',', default_value = "750,1000,1250,1500,1750,2000", allow_negative_numbers = true, value_parser = whole::<1, MAX_TARGET_SIZE>)]
    pub(crate) resolutions: Vec<u32>,
    /// Partition counts (z-partitions, one map each), comma-separated (`--splits` is an alias).
    #[arg(long, visible_alias = "splits", value_delimiter = ',', default_value = "1", allow_negative_numbers = true, value_parser = whole::<1, MAX_PARTITIONS>)]
    pub(crate) partitions: Vec<u32>,
    /// How partitions split the depth range: uniform, logarithmic, practical or practical:WEIGHT,
    /// adaptive or adaptive:DELTA. Default: practical:0.5 (`Splits::DEFAULT`).
    #[arg(long, allow_hyphen_values = true, value_parser = split_scheme)]
    pub(crate) split_scheme: Option<Splits>,
    /// Filters, comma-separated: nearest, pcf:K, disk:TAPS;RADIUS (use ; between a filter's
    /// numbers here), vsm:K, and the filterable maps esm:K;C, evsm2:K;C, evsm4:K;C+;C-,
    /// msm:K;ALPHA. The filterable maps (vsm to msm) take knobs after @: the kernel @box (default)
    /// or @gauss, the moments' storage @exact (default), @f32 or @f16, e.g. evsm4:5;40;5@gauss@f16.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "nearest",
        allow_hyphen_values = true, value_parser = filter_in_list
    )]
    pub(crate) filters: Vec<Filter>,
    /// Bias of every lookup, terms joined by + (see `render --help`). Default: slope:2,1e-5
    /// (`Bias::DEFAULT`).
    #[arg(long, allow_hyphen_values = true, value_parser = bias_spec)]
    pub(crate) bias: Option<Bias>,
    /// Sweep the bias instead of measuring one: the study at each of these biases (space-separated
    /// specs, as --bias takes them; with no value, a ladder of every family), its errors split by
    /// cause, written as bias-sweep.md and bias-sweep.csv with the Pareto front of acne against
    /// peter-panning. Not for the engines' presets, which read their maps with their own bias.
    #[arg(long, num_args = 0.., allow_hyphen_values = true, value_parser = bias_spec, conflicts_with_all = ["bias", "export", "map_truth"])]
    pub(crate) biases: Option<Vec<Bias>>,
    /// Also compare the exact truth with a 4096² uniform map's, as Chong and Gortler's truth was.
    #[arg(long)]
    pub(crate) map_truth: bool,
    /// Stated warps measured beside the techniques.
    #[command(flatten)]
    pub(crate) stated: StatedWarps,
    /// The focus body B of every map.
    #[arg(long, value_parser = FocusPolicy::parse, default_value = "light", help = FOCUS_HELP)]
    pub(crate) focus: FocusPolicy,
    /// The scene-optimized map's settings.
    #[command(flatten)]
    pub(crate) optimizer: OptimizerArgs,
    /// How many times each combination's shadows are made to time it: its time is the median
    /// run's, ± half the range (the Pareto front counts a combination dominated only beyond that).
    #[arg(long, value_name = "N", default_value_t = shadowlab_analysis::study::DEFAULT_TIMING_RUNS, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=MAX_TIMING_RUNS))]
    pub(crate) timing_runs: usize,
    /// Also write every per-pixel result under export/: the eye pass, the exact truth, and per
    /// combination the lookups and their classes, the texel footprints and the maps' raw depths
    /// (NPY and EXR, listed in export/index.json and results.json).
    #[arg(long)]
    pub(crate) export: bool,
    #[command(flatten)]
    pub(crate) memory: MemoryArgs,
    /// Directory to write into. Default: out/analyze/SCENE.
    #[arg(long)]
    pub(crate) out: Option<PathBuf>,
}

/// The default shadow-map side of `render` and `inspect`.
pub(crate) const DEFAULT_RESOLUTION: u32 = 1024;

/// The most z-partitions.
pub(crate) const MAX_PARTITIONS: u32 = 16;

/// What `--focus` chooses.
const FOCUS_HELP: &str = "The focus body B each map is fitted to: light (B = conv(V ∪ l) ∩ S ∩ L, \
    every occluder of a visible point), view-scene (V ∩ S), view (V alone, the papers' 2-D model)";

/// LiSPSM maps at stated warps, added to a technique list (`compare`, `analyze`); the logarithmic
/// map's reference is stated in the list itself (`logarithmic:lambda=L`).
#[derive(Debug, Args)]
pub(crate) struct StatedWarps {
    /// Also LiSPSM at each of these λ = n/d (comma-separated; inf: the uniform map), as
    /// `lispsm:lambda=L` in the list would.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub(crate) lambda: Vec<f64>,
    /// Also LiSPSM at each of these warp near distances n (light-space units: world units for a
    /// directional light), as `lispsm:n=N` in the list would.
    #[arg(long = "n", value_delimiter = ',', allow_hyphen_values = true)]
    pub(crate) near_distance: Vec<f64>,
}

/// The memory a run may plan to use.
#[derive(Debug, Args)]
pub(crate) struct MemoryArgs {
    /// Refuse a run whose estimated memory exceeds SIZE: bytes, or a number with K, M, G or T
    /// (powers of 1024). Default: 75 % of the memory available to the process (its cgroup's limit
    /// or the system's).
    #[arg(long, value_name = "SIZE", value_parser = Bytes::parse, allow_hyphen_values = true)]
    pub(crate) memory_budget: Option<Bytes>,
}

/// The map size and eye image of `sweep-angle` and `temporal`.
#[derive(Debug, Args)]
pub(crate) struct StudyView {
    /// Shadow-map side.
    #[arg(long, default_value_t = 1024, allow_negative_numbers = true, value_parser = whole::<1, MAX_TARGET_SIZE>)]
    pub(crate) resolution: u32,
    /// Eye image size, WIDTHxHEIGHT (default: the scene's).
    #[arg(long, value_parser = parse_size, allow_hyphen_values = true)]
    pub(crate) eye_size: Option<(u32, u32)>,
    /// The lookup filter of every map (as render --filter): nearest, pcf:K, disk:TAPS,RADIUS[,SEED],
    /// vsm:K[,MIN_VARIANCE]; the filterable maps esm:K,C, evsm2:K,C[,MIN_VARIANCE],
    /// evsm4:K,C+,C-[,MIN_VARIANCE], msm:K,ALPHA. The filterable maps (vsm to msm) take knobs
    /// after @: the kernel @box (default) or @gauss, the moments' storage @exact (default), @f32 or
    /// @f16, e.g. evsm4:5,40,5@gauss@f16.
    #[arg(long, default_value = "nearest", value_parser = filter_spec, allow_hyphen_values = true)]
    pub(crate) filter: Filter,
}

/// Arguments of `shadowlab sweep-angle`.
#[derive(Debug, Args)]
pub(crate) struct SweepArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArg,
    /// The techniques (near-parallel policies), comma-separated.
    /// Default: uniform, psm, lispsm, lispsm:minimax, lispsm:filament, lispsm:ogre,
    /// lispsm:osg, lispsm:osg_vdsm, optimal; for a scene of point lights: cube, dual-paraboloid, psm.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true, value_parser = technique_spec
    )]
    pub(crate) techniques: Option<Vec<Technique>>,
    #[command(flatten)]
    pub(crate) view: StudyView,
    /// Let the light come from behind the viewer as γ → 0 (default: from in front, the dueling
    /// frusta).
    #[arg(long)]
    pub(crate) behind: bool,
    #[command(flatten)]
    pub(crate) memory: MemoryArgs,
    /// Directory to write into. Default: out/sweep/SCENE.
    #[arg(long)]
    pub(crate) out: Option<PathBuf>,
}

/// Arguments of `shadowlab temporal`.
#[derive(Debug, Args)]
pub(crate) struct TemporalArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArg,
    /// Number of frames of the walk.
    #[arg(long, default_value_t = 24, allow_negative_numbers = true, value_parser = whole::<2, MAX_FRAMES>)]
    pub(crate) frames: u32,
    /// The techniques, comma-separated. Default: uniform, uniform_limited, psm, lispsm, optimal;
    /// for a scene of point lights: cube, dual-paraboloid, psm.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true, value_parser = technique_spec
    )]
    pub(crate) techniques: Option<Vec<Technique>>,
    #[command(flatten)]
    pub(crate) view: StudyView,
    #[command(flatten)]
    pub(crate) memory: MemoryArgs,
    /// Directory to write into. Default: out/temporal/SCENE.
    #[arg(long)]
    pub(crate) out: Option<PathBuf>,
}

/// Arguments of `shadowlab compare`.
#[derive(Debug, Args)]
pub(crate) struct CompareArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArg,
    /// The techniques, comma-separated: each `TECHNIQUE` or `TECHNIQUE:PARAMETER`, or an engine's
    /// preset (`bevy`, `filament`, `godot`, `babylon`, `threejs`, `unity`, `unreal`) with its
    /// choices (as for analyze --techniques). Default: uniform, uniform_limited, psm, lispsm,
    /// logarithmic; for a scene of point lights: cube, dual-paraboloid, psm.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true, value_parser = technique_spec
    )]
    pub(crate) techniques: Option<Vec<Technique>>,
    /// Shadow-map side in texels.
    #[arg(long, default_value_t = 1024, allow_negative_numbers = true, value_parser = whole::<1, MAX_TARGET_SIZE>)]
    pub(crate) resolution: u32,
    /// The part of the eye image to show, `X,Y,WIDTH,HEIGHT` in pixels from the top left. Default:
    /// the whole image.
    #[arg(long, value_parser = parse_crop, allow_hyphen_values = true)]
    pub(crate) crop: Option<[u32; 4]>,
    /// Pictures per row.
    #[arg(long, default_value_t = 3, allow_negative_numbers = true, value_parser = whole::<1, MAX_COLUMNS>)]
    pub(crate) columns: u32,
    /// Stated warps shown beside the techniques.
    #[command(flatten)]
    pub(crate) stated: StatedWarps,
    /// The focus body B of every map.
    #[arg(long, value_parser = FocusPolicy::parse, default_value = "light", help = FOCUS_HELP)]
    pub(crate) focus: FocusPolicy,
    #[command(flatten)]
    pub(crate) memory: MemoryArgs,
    /// The PNG to write.
    #[arg(long, default_value = "out/compare.png")]
    pub(crate) out: PathBuf,
    /// The scene-optimized map's settings.
    #[command(flatten)]
    pub(crate) optimizer: OptimizerArgs,
}

fn parse_crop(text: &str) -> Result<[u32; 4], String> {
    let values: Vec<u32> = text
        .split(',')
        .map(|v| {
            v.trim()
                .parse::<u32>()
                .map_err(|_| format!("{v:?} is not a whole number"))
        })
        .collect::<Result<_, _>>()?;
    let [x, y, w, h] = values[..] else {
        return Err("expected X,Y,WIDTH,HEIGHT".into());
    };
    if w == 0 || h == 0 {
        return Err("the crop's width and height must be at least 1".into());
    }
    Ok([x, y, w, h])
}

/// What shadows to make and how to read them; unset values come from the scene's `[shadow]`
/// table, then from the defaults shown.
#[derive(Debug, Args)]
pub(crate) struct ShadowArgs {
    #[command(flatten)]
    pub(crate) scene: SceneArg,
    /// The technique: uniform, uniform_limited, psm, lispsm, logarithmic, optimal, sdsm, or
    /// TECHNIQUE:PARAMETER; or an engine's preset (bevy, filament, godot, babylon, threejs, unity,
    /// unreal) with its choices (bevy:fit=sphere+blend=0.1, as for analyze --techniques). Given
    /// here, it replaces the scene's technique and parameter. Default: lispsm.
    #[arg(long, allow_hyphen_values = true, value_parser = technique_spec)]
    pub(crate) technique: Option<Technique>,
    /// LiSPSM's parameter: lispsm (the paper's n = (z_n + √(z_n·z_f))/sin γ, default), lispsm_dz,
    /// cad, cad_eq17, cad_sin2, gmnpr, glpr, minimax, uniform, model (shadowlab's λ transfer); or
    /// an engine's: filament, ogre, osg, authors2006, osg_vdsm. For logarithmic, the reference
    /// point: eye (default) or faces (Lloyd et al.'s face partitioning). For optimal, the step:
    /// paper (default) or refit.
    #[arg(long = "param", conflicts_with_all = ["lambda", "near_distance"], allow_hyphen_values = true, value_parser = value_not_flag)]
    pub(crate) parameter: Option<String>,
    /// λ = n/d instead of --param: LiSPSM's warp, or where the logarithmic map's reference point
    /// lies (inf: the uniform map).
    #[arg(long, allow_hyphen_values = true, conflicts_with = "near_distance")]
    pub(crate) lambda: Option<f64>,
    /// The warp near distance n instead of --param (light-space units: world units for a
    /// directional light).
    #[arg(long = "n", allow_hyphen_values = true)]
    pub(crate) near_distance: Option<f64>,
    /// The focus body B each map is fitted to: light (B = conv(V ∪ l) ∩ S ∩ L, default),
    /// view-scene (V ∩ S), view (V alone, the papers' 2-D model).
    #[arg(long, value_parser = FocusPolicy::parse)]
    pub(crate) focus: Option<FocusPolicy>,
    /// Shadow-map side in texels.
    #[arg(long, allow_negative_numbers = true, value_parser = whole::<1, MAX_TARGET_SIZE>,
          help = format!("Shadow-map side in texels. Default: {DEFAULT_RESOLUTION}"))]
    pub(crate) resolution: Option<u32>,
    /// Number of z-partitions (one map each; `--splits` is an alias). Default: 1.
    #[arg(long, visible_alias = "splits", allow_negative_numbers = true, value_parser = whole::<1, MAX_PARTITIONS>)]
    pub(crate) partitions: Option<u32>,
    /// How partitions split the depth range: uniform, logarithmic, practical or practical:WEIGHT,
    /// adaptive or adaptive:DELTA. Default: practical:0.5.
    #[arg(long, allow_hyphen_values = true, value_parser = split_scheme)]
    pub(crate) split_scheme: Option<Splits>,
    /// Bias: terms joined by +, at most one of each kind. A depth comparison (window-depth units):
    /// none, constant:OFFSET, slope:FACTOR or slope:FACTOR,CONSTANT, second-depth, midpoint,
    /// dual-depth:MAX, receiver-plane or receiver-plane:CONSTANT (Isidoro 2006). A receiver offset
    /// along the normal, in texels of the map at the point: normal:K (Bevy), normal-sine:K
    /// (Filament; its normalBias 1 is normal-sine:0.5), normal-lateral:K (Godot),
    /// normal-versine:K (Unity's inset, on the receiver). light:D moves the
    /// receiver D world units toward the light. E.g. slope:2,1e-5+normal:1.8+light:0.02. Default:
    /// slope:2,1e-5.
    #[arg(long, allow_hyphen_values = true, value_parser = bias_spec)]
    pub(crate) bias: Option<Bias>,
    /// Filter: nearest, pcf:K, disk:TAPS,RADIUS or disk:TAPS,RADIUS,SEED, vsm:K or
    /// vsm:K,MIN_VARIANCE; the filterable maps esm:K,C, evsm2:K,C[,MIN_VARIANCE],
    /// evsm4:K,C+,C-[,MIN_VARIANCE], msm:K,ALPHA; the filterable maps (vsm to msm) take knobs
    /// after @: the kernel @box (default) or @gauss, the moments' storage @exact (default), @f32 or
    /// @f16, e.g. evsm4:5,40,5@gauss@f16. Default: nearest.
    #[arg(long, allow_hyphen_values = true, value_parser = filter_spec)]
    pub(crate) filter: Option<Filter>,
    /// Depth format of the maps: f32, reversed-f32, unorm24, unorm16. Default: f32.
    #[arg(long, allow_hyphen_values = true, value_parser = depth_format)]
    pub(crate) format: Option<DepthFormat>,
    /// The scene-optimized map's settings.
    #[command(flatten)]
    pub(crate) optimizer: OptimizerArgs,
}

/// Arguments of `shadowlab render`.
#[derive(Debug, Args)]
pub(crate) struct RenderArgs {
    /// The scene and its shadows.
    #[command(flatten)]
    pub(crate) shadow: ShadowArgs,
    /// Also write every per-pixel result under export/: the eye pass, the exact truth, the
    /// lookups and their classes, the texel footprints and the maps' raw depths (NPY and EXR,
    /// listed in export/index.json).
    #[arg(long)]
    pub(crate) export: bool,
    #[command(flatten)]
    pub(crate) memory: MemoryArgs,
    /// Directory to write into (created if missing). Default: out/render/SCENE-TECHNIQUE.
    #[arg(long)]
    pub(crate) out: Option<PathBuf>,
}

/// Arguments of `shadowlab inspect`.
#[derive(Debug, Args)]
pub(crate) struct InspectArgs {
    /// The scene and its shadows.
    #[command(flatten)]
    pub(crate) shadow: ShadowArgs,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub(crate) json: bool,
    /// Also write the set-up as a set-up file (docs/setup-format.md), which `evaluate --setup`
    /// reads: every technique that is a matrix per partition (not the logarithmic map).
    #[arg(long, value_name = "FILE")]
    pub(crate) setup_json: Option<PathBuf>,
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
    #[arg(long, default_value_t = 2048, allow_negative_numbers = true, value_parser = whole::<1, MAX_TARGET_SIZE>)]
    pub(crate) size: u32,
    /// Size of the eye pass's target, WIDTHxHEIGHT.
    #[arg(long, default_value = "1024x768", value_parser = parse_size, allow_hyphen_values = true)]
    pub(crate) eye_size: (u32, u32),
    /// Round positions and matrices to f32 first, as a GPU's vertex buffers and uniforms hold them
    /// (the rasterizer still works in f64 from there); for pixel comparisons with GL renderers.
    #[arg(long)]
    pub(crate) f32_inputs: bool,
    /// Also write each depth image as a NumPy .npy file (f32, row 0 at the bottom, as GL reads it
    /// back), for pixel comparisons with other renderers (e.g. the peer harness's --dump).
    #[arg(long)]
    pub(crate) npy: bool,
    #[command(flatten)]
    pub(crate) memory: MemoryArgs,
    /// Directory to write into (created if missing): MESH-light.{png,exr}, MESH-eye.{png,exr}.
    #[arg(long, default_value = "out/render-mesh")]
    pub(crate) out: PathBuf,
}

/// The most frames of a camera walk (`temporal --frames`).
pub(crate) const MAX_FRAMES: u32 = 10000;

/// The most pictures per row of `compare`.
pub(crate) const MAX_COLUMNS: u32 = 16;

/// A whole number in `MIN..=MAX`: the parser of every count and size flag, whose message states
/// the range for any text (clap's own says "invalid digit found in string" for `1e9`).
pub(crate) fn whole<const MIN: u32, const MAX: u32>(text: &str) -> Result<u32, String> {
    text.trim()
        .parse::<u32>()
        .ok()
        .filter(|value| (MIN..=MAX).contains(value))
        .ok_or_else(|| format!("{text:?} is not a whole number in {MIN}..={MAX}"))
}

/// `WIDTHxHEIGHT`, each side 1 to [`MAX_TARGET_SIZE`]: the one size parser of every flag.
pub(crate) fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("{text:?} is not WIDTHxHEIGHT, e.g. 1024x768"))?;
    let side = |s: &str| {
        s.trim()
            .parse::<u32>()
            .ok()
            .filter(|v| (1..=MAX_TARGET_SIZE).contains(v))
            .ok_or_else(|| format!("{s:?} is not a size between 1 and {MAX_TARGET_SIZE}"))
    };
    Ok((side(w)?, side(h)?))
}

/// Arguments of `shadowlab params`.
#[derive(Debug, Args)]
pub(crate) struct ParamsArgs {
    /// Eye near distance (> 0).
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) near: f64,
    /// Eye far distance (> near).
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) far: f64,
    /// Full field of view in degrees, in the plane of the light and view directions (0 < fov < 180).
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) fov: f64,
    /// Angle between light and view directions in degrees, 0 (parallel) to 90 (perpendicular).
    #[arg(long, allow_negative_numbers = true)]
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
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub(crate) near: f64,
    /// Eye far distance of every figure.
    #[arg(long, default_value_t = 100.0, allow_negative_numbers = true)]
    pub(crate) far: f64,
    /// Full field of view in degrees of every figure.
    #[arg(long, default_value_t = 60.0, allow_negative_numbers = true)]
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

/// The scene-optimized map's settings (technique `optimal`; CG06 Algorithm 1), for measuring what
/// each costs and buys. Unset: the scene's `[shadow]` table (render, inspect), then the paper's (or
/// shadowlab's documented) defaults.
#[derive(Debug, Args)]
pub(crate) struct OptimizerArgs {
    /// Size of the optimizer's low-resolution eye pass, WIDTHxHEIGHT.
    #[arg(long, value_name = "WxH", value_parser = parse_size, allow_hyphen_values = true, help = format!(
        "Size of the optimizer's low-resolution eye pass, WIDTHxHEIGHT. Default: {}x{} (CG06 §4)",
        READBACK_SIZE.0, READBACK_SIZE.1
    ))]
    pub(crate) optimal_readback: Option<(u32, u32)>,
    /// Side of the initial map.
    #[arg(long, value_name = "TEXELS", allow_negative_numbers = true, value_parser = whole::<1, MAX_TARGET_SIZE>, help = format!(
        "Side of the initial (uniform-limited) map the samples' shadow states are read from, \
         texels. Default: {INITIAL_MAP_RESOLUTION}"
    ))]
    pub(crate) optimal_initial: Option<u32>,
    /// The most iterations.
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = whole::<0, MAX_OPTIMAL_ITERATIONS>, help = format!(
        "The most iterations of the optimizer's descent (0: the initial fit only). Default: \
         {ITERATIONS} (CG06 §4)"
    ))]
    pub(crate) optimal_iterations: Option<u32>,
    /// The border.
    #[arg(long, value_name = "FRACTION", value_parser = parse_border, allow_negative_numbers = true, help = format!(
        "The border around the samples, a fraction of the map's side in [0, 0.5). Default: {BORDER}"
    ))]
    pub(crate) optimal_border: Option<f64>,
}

/// A fraction in [0, 0.5).
fn parse_border(value: &str) -> Result<f64, String> {
    let fraction = value
        .trim()
        .parse::<f64>()
        .map_err(|_| format!("{value:?} is not a number"))?;
    border_fraction(fraction)
}

/// A border fraction in `[0, 0.5)`.
pub(crate) fn border_fraction(value: f64) -> Result<f64, String> {
    if (0.0..0.5).contains(&value) {
        Ok(value)
    } else {
        Err(format!("{value} is not a fraction in [0, 0.5)"))
    }
}

/// The most descent iterations a user may ask of the optimizer.
pub(crate) const MAX_OPTIMAL_ITERATIONS: u32 = 1000;

/// The techniques `sweep-angle` measures by default for directional and spot lights.
pub(crate) const SWEEP_TECHNIQUES: &str = "uniform,psm,lispsm,lispsm:minimax,lispsm:filament,lispsm:ogre,lispsm:osg,lispsm:osg_vdsm,optimal";

/// The techniques `temporal` measures by default for directional and spot lights.
pub(crate) const TEMPORAL_TECHNIQUES: &str = "uniform,uniform_limited,psm,lispsm,optimal";

/// The techniques `compare` measures by default for directional and spot lights.
pub(crate) const COMPARE_TECHNIQUES: &str = "uniform,uniform_limited,psm,lispsm,logarithmic";
