//! The scene argument, technique lists (`compare` and the study commands), and the shadow
//! settings of `render` and `inspect`: a flag wins over the scene's `[shadow]` table, which wins
//! over the defaults. A bad value is an input error naming the flag, or the scene file and field
//! it came from.

use std::path::Path;

use shadowlab_raster::{DepthFormat, MAX_TARGET_SIZE};
use shadowlab_scene::scene_file::MAX_IMAGE_SIDE;
use shadowlab_scene::{DEFAULT_SCENE, Scene, ShadowSettings, builtin_scene, load_scene};
use shadowlab_shadow::optimal::OptimalOptions;
use shadowlab_shadow::{Bias, Filter, FocusPolicy, Lookup, PlanOptions, Splits, Technique};

use crate::args::{
    DEFAULT_RESOLUTION, MAX_OPTIMAL_ITERATIONS, MAX_PARTITIONS, OptimizerArgs, ShadowArgs,
    StatedWarps, border_fraction, parse_size,
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

/// A setting's value with where it came from, for the error message: the flag, or the scene's
/// file and field.
struct Given<T> {
    value: T,
    origin: String,
}

/// Where settings come from: the flags, then the scene's `[shadow]` table.
struct Sources<'a> {
    file: String,
    scene: &'a ShadowSettings,
}

impl Sources<'_> {
    /// The flag's value if given, else the scene's field's.
    fn pick<T: Clone>(&self, flag: Option<&T>, field: Option<&T>, name: &str) -> Option<Given<T>> {
        match (flag, field) {
            (Some(v), _) => Some(Given {
                value: v.clone(),
                origin: format!("invalid --{name}"),
            }),
            (None, Some(v)) => Some(Given {
                value: v.clone(),
                origin: format!("{}: shadow.{}", self.file, name.replace('-', "_")),
            }),
            (None, None) => None,
        }
    }
}

impl<T> Given<T> {
    /// The value parsed by `parse`, its error prefixed with where the value came from.
    fn parse<U>(self, parse: impl FnOnce(T) -> Result<U, String>) -> Result<U, CliError> {
        parse(self.value).map_err(|e| CliError::Input(format!("{}: {e}", self.origin)))
    }
}

/// Loads the scene and resolves the settings: each value parsed once, where it was given.
pub(crate) fn resolve(args: &ShadowArgs) -> Result<Resolved, CliError> {
    let scene = load_scene_argument(args.scene.as_deref())?;
    let settings = scene.shadow.clone();
    let sources = Sources {
        file: scene_label(args.scene.as_deref()),
        scene: &settings,
    };
    let technique = technique(args, &sources)?;
    let splits = sources
        .pick(
            args.split_scheme.as_ref(),
            settings.split_scheme.as_ref(),
            "split-scheme",
        )
        .map(|g| g.parse(|s| Splits::parse(&s)))
        .transpose()?
        .unwrap_or(Splits::Practical { weight: 0.5 });
    let bias = sources
        .pick(args.bias.as_ref(), settings.bias.as_ref(), "bias")
        .map(|g| g.parse(|s| Bias::parse(&s)))
        .transpose()?
        .unwrap_or(Bias::DEFAULT);
    let filter = sources
        .pick(args.filter.as_ref(), settings.filter.as_ref(), "filter")
        .map(|g| g.parse(|s| Filter::parse(&s)))
        .transpose()?
        .unwrap_or(Filter::Nearest);
    let focus = match (args.focus, &settings.focus) {
        (Some(focus), _) => focus,
        (None, Some(key)) => FocusPolicy::parse(key)
            .map_err(|e| CliError::Input(format!("{}: shadow.focus: {e}", sources.file)))?,
        (None, None) => FocusPolicy::default(),
    };
    let format = match &args.format {
        Some(key) => DepthFormat::ALL
            .into_iter()
            .find(|f| f.key_name() == key)
            .ok_or_else(|| {
                CliError::Input(format!(
                    "invalid --format: unknown depth format {key:?}; known: f32, reversed-f32, unorm24, unorm16"
                ))
            })?,
        None => DepthFormat::F32,
    };
    let resolution = sources
        .pick(
            args.resolution.as_ref(),
            settings.resolution.as_ref(),
            "resolution",
        )
        .map_or(Ok(DEFAULT_RESOLUTION), |g| {
            g.parse(|r| in_range(r, 1, MAX_TARGET_SIZE))
        })?;
    let partitions = sources
        .pick(args.splits.as_ref(), settings.splits.as_ref(), "splits")
        .map_or(Ok(1), |g| g.parse(|k| in_range(k, 1, MAX_PARTITIONS)))?;
    let optimal = optimizer(&args.optimizer, &sources)?;
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

/// The technique and its parameter: `--param`, `--lambda` or `--n` (at most one, which clap
/// checks), else the scene's `parameter`, `lambda` or `n` (at most one).
fn technique(args: &ShadowArgs, sources: &Sources<'_>) -> Result<Technique, CliError> {
    let settings = sources.scene;
    let key = sources.pick(
        args.technique.as_ref(),
        settings.technique.as_ref(),
        "technique",
    );
    let from_flags = [
        args.parameter.clone().map(|p| ("param", p)),
        args.lambda.map(|l| ("lambda", format!("lambda={l}"))),
        args.near_distance.map(|n| ("n", format!("n={n}"))),
    ];
    let from_scene = [
        settings.parameter.clone().map(|p| ("parameter", p)),
        settings.lambda.map(|l| ("lambda", format!("lambda={l}"))),
        settings.n.map(|n| ("n", format!("n={n}"))),
    ];
    let given: Vec<_> = from_flags.into_iter().flatten().collect();
    let parameter = match &given[..] {
        [(flag, spec)] => Some(Given {
            value: spec.clone(),
            origin: format!("invalid --{flag}"),
        }),
        _ => {
            let fields: Vec<_> = from_scene.into_iter().flatten().collect();
            match &fields[..] {
                [] => None,
                [(field, spec)] => Some(Given {
                    value: spec.clone(),
                    origin: format!("{}: shadow.{field}", sources.file),
                }),
                _ => {
                    return Err(CliError::Input(format!(
                        "{}: shadow: give at most one of parameter, lambda and n",
                        sources.file
                    )));
                }
            }
        }
    };
    let key_name = key.as_ref().map_or("lispsm", |g| g.value.as_str());
    match Technique::parse(key_name, parameter.as_ref().map(|g| g.value.as_str())) {
        Ok(technique) => Ok(technique),
        // The key is checked alone first, so an error with a valid key is the parameter's.
        Err(e) => {
            let origin = match (&key, Technique::parse(key_name, None)) {
                (Some(k), Err(_)) => &k.origin,
                (None, Err(_)) => "invalid --technique",
                (_, Ok(_)) => parameter.as_ref().map_or("invalid --param", |g| &g.origin),
            };
            Err(CliError::Input(format!("{origin}: {e}")))
        }
    }
}

/// The scene-optimized map's settings: each flag, else the scene's field, else the default.
fn optimizer(args: &OptimizerArgs, sources: &Sources<'_>) -> Result<OptimalOptions, CliError> {
    let settings = sources.scene;
    let defaults = OptimalOptions::default();
    let readback = match (args.optimal_readback, &settings.optimal_readback) {
        (Some(size), _) => size,
        (None, Some(text)) => parse_size(text).map_err(|e| {
            CliError::Input(format!("{}: shadow.optimal_readback: {e}", sources.file))
        })?,
        (None, None) => defaults.readback,
    };
    let initial_resolution = sources
        .pick(
            args.optimal_initial.as_ref(),
            settings.optimal_initial.as_ref(),
            "optimal-initial",
        )
        .map_or(Ok(defaults.initial_resolution), |g| {
            g.parse(|r| in_range(r, 1, MAX_TARGET_SIZE))
        })?;
    let iterations = sources
        .pick(
            args.optimal_iterations.as_ref(),
            settings.optimal_iterations.as_ref(),
            "optimal-iterations",
        )
        .map_or(Ok(defaults.iterations), |g| {
            g.parse(|n| in_range(n, 0, MAX_OPTIMAL_ITERATIONS).map(|n| n as usize))
        })?;
    let border = sources
        .pick(
            args.optimal_border.as_ref(),
            settings.optimal_border.as_ref(),
            "optimal-border",
        )
        .map_or(Ok(defaults.border), |g| g.parse(border_fraction))?;
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
    optimizer(
        args,
        &Sources {
            file: String::new(),
            scene: &ShadowSettings::default(),
        },
    )
}

/// The scene named on the command line: a built-in name, or a path to a scene file.
pub(crate) fn load_scene_argument(name: Option<&str>) -> Result<Scene, CliError> {
    let name = name.unwrap_or(DEFAULT_SCENE);
    let path = Path::new(name);
    if path.exists() || name.ends_with(".toml") {
        load_scene(path).map_err(|e| CliError::from_input_file(&e))
    } else {
        builtin_scene(name).map_err(|e| CliError::Input(e.to_string()))
    }
}

/// How errors name the scene's settings: the file, or the built-in scene.
fn scene_label(name: Option<&str>) -> String {
    match name {
        Some(n) if Path::new(n).exists() || n.ends_with(".toml") => n.to_string(),
        Some(n) => format!("built-in scene {n}"),
        None => format!("built-in scene {DEFAULT_SCENE}"),
    }
}

/// The techniques of a list (`--techniques`), then LiSPSM at each stated λ and n (`--lambda`,
/// `--n`).
pub(crate) fn technique_list(
    specs: &[String],
    stated: &StatedWarps,
) -> Result<Vec<Technique>, CliError> {
    let mut techniques = parse_techniques(specs, "--techniques")?;
    for (flag, values) in [("--lambda", &stated.lambda), ("--n", &stated.near_distance)] {
        let key = if flag == "--lambda" { "lambda" } else { "n" };
        for value in values {
            techniques.push(
                Technique::parse("lispsm", Some(&format!("{key}={value}")))
                    .map_err(|e| CliError::Input(format!("invalid {flag}: {e}")))?,
            );
        }
    }
    Ok(techniques)
}

/// The techniques named on the command line (`TECHNIQUE` or `TECHNIQUE:PARAMETER`).
pub(crate) fn parse_techniques(specs: &[String], flag: &str) -> Result<Vec<Technique>, CliError> {
    specs
        .iter()
        .map(|spec| {
            let (key, parameter) = spec
                .split_once(':')
                .map_or((spec.as_str(), None), |(k, p)| (k, Some(p)));
            Technique::parse(key, parameter)
                .map_err(|e| CliError::Input(format!("invalid {flag}: {e}")))
        })
        .collect()
}
