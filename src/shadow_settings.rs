//! The scene argument, technique lists (`compare` and the study commands), and the shadow
//! settings of `render` and `inspect`: a flag wins over the scene's `[shadow]` table, which wins
//! over the defaults. A bad value is an input error naming the flag, or the scene file and field
//! it came from.

use std::path::Path;

use shadowlab_analysis::study::default_techniques;
use shadowlab_raster::{DepthFormat, MAX_TARGET_SIZE};
use shadowlab_scene::scene_file::MAX_IMAGE_SIDE;
use shadowlab_scene::{
    DEFAULT_SCENE, Scene, ShadowSettings, builtin_scene, is_gltf_path, load_gltf_scene,
    load_scene_with_warnings,
};
use shadowlab_shadow::optimal::OptimalOptions;
use shadowlab_shadow::{
    Bias, Filter, FocusPolicy, FrameOptions, LightSource, Lookup, PlanOptions, Splits, Technique,
    WarpChoice,
};

use crate::args::{
    DEFAULT_RESOLUTION, MAX_OPTIMAL_ITERATIONS, MAX_PARTITIONS, OptimizerArgs, SceneArg,
    ShadowArgs, StatedWarps, border_fraction, parse_size,
};
use crate::error::CliError;

// A scene file's camera image must fit a raster target, so that every scene has an eye pass.
const _: () = assert!(MAX_IMAGE_SIDE == MAX_TARGET_SIZE);

/// Everything `render` and `inspect` need, resolved.
pub(crate) struct Resolved {
    pub(crate) scene: Scene,
    pub(crate) plan: PlanOptions,
    pub(crate) resolution: u32,
    pub(crate) lookup: Lookup,
    pub(crate) format: DepthFormat,
}

impl Resolved {
    /// How one frame is made and read with these settings, measured as planned (no texel
    /// snapping).
    pub(crate) fn frame_options(&self) -> FrameOptions {
        FrameOptions {
            plan: self.plan.clone(),
            resolution: self.resolution,
            format: self.format,
            lookup: self.lookup.clone(),
            snap_texels: 0,
        }
    }
}

/// The scene's `[shadow]` table, read where no flag is given: each field parsed once, its error
/// naming the file and the field.
struct SceneTable<'a> {
    file: String,
    settings: &'a ShadowSettings,
}

impl SceneTable<'_> {
    /// The flag's value (already parsed by clap), else the scene field's, parsed by `parse`.
    fn or_field<F: ?Sized, T>(
        &self,
        flag: Option<T>,
        field: Option<&F>,
        name: &str,
        parse: impl FnOnce(&F) -> Result<T, String>,
    ) -> Result<Option<T>, CliError> {
        match (flag, field) {
            (Some(value), _) => Ok(Some(value)),
            (None, Some(field)) => parse(field).map(Some).map_err(|e| self.error(name, &e)),
            (None, None) => Ok(None),
        }
    }

    /// An input error naming the file and the field `shadow.NAME`.
    fn error(&self, name: &str, message: &str) -> CliError {
        CliError::Input(format!("{}: shadow.{name}: {message}", self.file))
    }
}

/// Loads the scene and resolves the settings: flags are typed by clap, the scene's fields parsed
/// here, each once.
pub(crate) fn resolve(args: &ShadowArgs) -> Result<Resolved, CliError> {
    let scene = load_scene_argument(&args.scene)?;
    let settings = scene.shadow.clone();
    let table = SceneTable {
        file: scene_label(&args.scene),
        settings: &settings,
    };
    let technique = technique(args, &table, &scene)?;
    let flag = if args.technique.is_some() {
        "--technique".to_owned()
    } else {
        format!("{}: shadow.technique", table.file)
    };
    check_techniques(&scene, &[technique], &flag)?;
    let splits = table
        .or_field(
            args.split_scheme,
            settings.split_scheme.as_deref(),
            "split_scheme",
            Splits::parse,
        )?
        .unwrap_or(Splits::DEFAULT);
    let bias = table
        .or_field(args.bias, settings.bias.as_deref(), "bias", Bias::parse)?
        .unwrap_or(Bias::DEFAULT);
    let filter = table
        .or_field(
            args.filter,
            settings.filter.as_deref(),
            "filter",
            Filter::parse,
        )?
        .unwrap_or(Filter::Nearest);
    let focus = table
        .or_field(
            args.focus,
            settings.focus.as_deref(),
            "focus",
            FocusPolicy::parse,
        )?
        .unwrap_or_default();
    let format = args.format.unwrap_or(DepthFormat::F32);
    let resolution = table
        .or_field(
            args.resolution,
            settings.resolution.as_ref(),
            "resolution",
            |&r| in_range(r, 1, MAX_TARGET_SIZE),
        )?
        .unwrap_or(DEFAULT_RESOLUTION);
    let partitions = table
        .or_field(
            args.partitions,
            settings.partitions.as_ref(),
            "partitions",
            |&k| in_range(k, 1, MAX_PARTITIONS),
        )?
        .unwrap_or(1);
    let optimal = optimizer(&args.optimizer, Some(&table))?;
    Ok(Resolved {
        plan: PlanOptions {
            technique,
            partitions: partitions as usize,
            splits,
            focus,
            optimal,
        },
        scene,
        resolution,
        lookup: Lookup::new(bias, filter),
        format,
    })
}

/// `value` if it lies in `lo..=hi`.
fn in_range(value: u32, lo: u32, hi: u32) -> Result<u32, String> {
    if (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(format!("{value} must lie in {lo}..={hi}"))
    }
}

/// The technique and its parameter. `--technique` (a spec, `TECHNIQUE[:PARAMETER]`) replaces the
/// scene's technique and its parameter; the parameter is then `--param`, `--lambda` or `--n` (at
/// most one, which clap checks), else, for the scene's own technique, the scene's `parameter`,
/// `lambda` or `n` (at most one).
/// Without either, the default of the scene's lights ([`default_technique`]).
fn technique(
    args: &ShadowArgs,
    table: &SceneTable<'_>,
    scene: &Scene,
) -> Result<Technique, CliError> {
    let settings = table.settings;
    let from_flags = [
        args.parameter.clone().map(|p| ("--param", p)),
        args.lambda.map(|l| ("--lambda", format!("lambda={l}"))),
        args.near_distance.map(|n| ("--n", format!("n={n}"))),
    ]
    .into_iter()
    .flatten()
    .next();
    let (base, parameter) = match args.technique {
        Some(technique) => (
            technique,
            from_flags.map(|(flag, p)| (format!("invalid {flag}"), p)),
        ),
        None => {
            let base = table
                .or_field(None, settings.technique.as_deref(), "technique", |key| {
                    Technique::parse_spec(key)
                })?
                .unwrap_or_else(|| default_technique(scene));
            let from_scene: Vec<_> = [
                settings.parameter.clone().map(|p| ("parameter", p)),
                settings.lambda.map(|l| ("lambda", format!("lambda={l}"))),
                settings.n.map(|n| ("n", format!("n={n}"))),
            ]
            .into_iter()
            .flatten()
            .collect();
            let parameter = match (from_flags, &from_scene[..]) {
                (Some((flag, p)), _) => Some((format!("invalid {flag}"), p)),
                (None, []) => None,
                (None, [(field, p)]) => {
                    Some((format!("{}: shadow.{field}", table.file), p.clone()))
                }
                (None, _) => {
                    return Err(CliError::Input(format!(
                        "{}: shadow: give at most one of parameter, lambda and n",
                        table.file
                    )));
                }
            };
            (base, parameter)
        }
    };
    let Some((origin, parameter)) = parameter else {
        return Ok(base);
    };
    if let Some(named) = base.parameter() {
        return Err(CliError::Input(format!(
            "{origin}: the technique already names its parameter ({}:{named}); give one or the other",
            base.key()
        )));
    }
    Technique::parse(base.key(), Some(&parameter))
        .map_err(|e| CliError::Input(format!("{origin}: {e}")))
}

/// The scene-optimized map's settings: each flag, else the scene's field (where there is a scene
/// table), else the default.
fn optimizer(
    args: &OptimizerArgs,
    table: Option<&SceneTable<'_>>,
) -> Result<OptimalOptions, CliError> {
    let defaults = OptimalOptions::default();
    let empty = ShadowSettings::default();
    let no_table = SceneTable {
        file: String::new(),
        settings: &empty,
    };
    let table = table.unwrap_or(&no_table);
    let settings = table.settings;
    let readback = table
        .or_field(
            args.optimal_readback,
            settings.optimal_readback.as_deref(),
            "optimal_readback",
            parse_size,
        )?
        .unwrap_or(defaults.readback);
    let initial_resolution = table
        .or_field(
            args.optimal_initial,
            settings.optimal_initial.as_ref(),
            "optimal_initial",
            |&r| in_range(r, 1, MAX_TARGET_SIZE),
        )?
        .unwrap_or(defaults.initial_resolution);
    let iterations = table
        .or_field(
            args.optimal_iterations,
            settings.optimal_iterations.as_ref(),
            "optimal_iterations",
            |&n| in_range(n, 0, MAX_OPTIMAL_ITERATIONS),
        )?
        .map_or(defaults.iterations, |n| n as usize);
    let border = table
        .or_field(
            args.optimal_border,
            settings.optimal_border.as_ref(),
            "optimal_border",
            |&b| border_fraction(b),
        )?
        .unwrap_or(defaults.border);
    Ok(OptimalOptions {
        readback,
        initial_resolution,
        iterations,
        border,
        direction: defaults.direction,
    })
}

/// The optimizer's settings of a command without a scene table (`compare`, `analyze`).
pub(crate) fn optimizer_flags(args: &OptimizerArgs) -> Result<OptimalOptions, CliError> {
    optimizer(args, None)
}

/// The scene named on the command line: a built-in name, or a path to a scene file or a glTF
/// file (`--gltf-scene` picks the latter's scene). The scene's warnings (what a glTF file holds
/// that shadowlab cannot represent, and skipped) are printed to standard error before any work.
pub(crate) fn load_scene_argument(arg: &SceneArg) -> Result<Scene, CliError> {
    let name = arg.name.as_deref().unwrap_or(DEFAULT_SCENE);
    let path = Path::new(name);
    let gltf = is_gltf_path(path);
    if arg.gltf_scene.is_some() && !gltf {
        return Err(CliError::Input(format!(
            "invalid --gltf-scene: it picks a scene of a glTF file (.gltf, .glb), and {} is not one",
            scene_label(arg)
        )));
    }
    if !is_scene_file(name) {
        return builtin_scene(name).map_err(|e| CliError::Input(e.to_string()));
    }
    let loaded = if gltf {
        load_gltf_scene(path, arg.gltf_scene)
    } else {
        load_scene_with_warnings(path)
    }
    .map_err(|e| CliError::from_input_file(&e))?;
    for warning in &loaded.warnings {
        eprintln!("shadowlab: warning: {warning}");
    }
    Ok(loaded.scene)
}

/// Whether the scene argument names a file rather than a built-in scene.
fn is_scene_file(name: &str) -> bool {
    let path = Path::new(name);
    path.exists() || name.ends_with(".toml") || is_gltf_path(path)
}

/// How errors name the scene's settings: the file, or the built-in scene.
fn scene_label(arg: &SceneArg) -> String {
    match arg.name.as_deref() {
        Some(n) if is_scene_file(n) => n.to_string(),
        Some(n) => format!("built-in scene {n}"),
        None => format!("built-in scene {DEFAULT_SCENE}"),
    }
}

/// The technique of a scene that names none: the first of the study commands' defaults for its
/// lights ([`default_techniques`] with LiSPSM for directional and spot lights) — LiSPSM (the paper's
/// parameter), the cube map where every light is a point light (what engines ship for them), PSM
/// where point lights mix with others (the one technique that serves both).
fn default_technique(scene: &Scene) -> Technique {
    default_techniques(scene, "lispsm")
        .first()
        .copied()
        .unwrap_or(Technique::Lispsm(WarpChoice::PAPER))
}

/// The techniques a study command measures: those given (`--techniques`), else its default for
/// the scene's lights ([`default_techniques`]: `directed` for directional and spot lights).
///
/// # Errors
/// As [`check_techniques`], for `--techniques`.
pub(crate) fn study_techniques(
    scene: &Scene,
    given: Option<&[Technique]>,
    directed: &str,
) -> Result<Vec<Technique>, CliError> {
    let techniques = default_or_given(scene, given, directed);
    check_techniques(scene, &techniques, "--techniques")?;
    Ok(techniques)
}

/// The techniques given, or the default of [`default_techniques`].
fn default_or_given(scene: &Scene, given: Option<&[Technique]>, directed: &str) -> Vec<Technique> {
    given.map_or_else(
        || default_techniques(scene, directed),
        <[Technique]>::to_vec,
    )
}

/// Checks that every technique serves every light of `scene`: an input error naming the flag or
/// field that chose the technique, the light (`light[K]`, its kind) and the techniques that serve
/// it.
pub(crate) fn check_techniques(
    scene: &Scene,
    techniques: &[Technique],
    flag: &str,
) -> Result<(), CliError> {
    for (index, light) in scene.lights.iter().enumerate() {
        let source = LightSource::from_scene(light);
        for technique in techniques {
            technique.check_light(&source).map_err(|error| {
                CliError::Input(format!("{flag}: light[{index}] of {}: {error}", scene.name))
            })?;
        }
    }
    Ok(())
}

/// The techniques of a list (`--techniques`, or the default for the scene's lights:
/// [`study_techniques`]), then LiSPSM at each stated λ and n (`--lambda`, `--n`), checked against
/// the scene's lights ([`check_techniques`]).
pub(crate) fn technique_list(
    scene: &Scene,
    given: Option<&[Technique]>,
    directed: &str,
    stated: &StatedWarps,
) -> Result<Vec<Technique>, CliError> {
    let mut techniques = default_or_given(scene, given, directed);
    for (flag, values) in [("--lambda", &stated.lambda), ("--n", &stated.near_distance)] {
        let key = if flag == "--lambda" { "lambda" } else { "n" };
        for value in values {
            techniques.push(
                Technique::parse("lispsm", Some(&format!("{key}={value}")))
                    .map_err(|e| CliError::Input(format!("invalid {flag}: {e}")))?,
            );
        }
    }
    check_techniques(scene, &techniques, "--techniques")?;
    Ok(techniques)
}
