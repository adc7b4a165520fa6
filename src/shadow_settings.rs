//! The scene argument, technique lists (`compare` and the study commands), and the shadow
//! settings of `render` and `inspect`: a flag wins over the scene's `[shadow]` table, which wins
//! over the defaults. A bad value is an input error naming the flag, or the scene file and field
//! it came from.

use std::path::Path;

use shadowlab_raster::DepthFormat;
use shadowlab_scene::{DEFAULT_SCENE, Scene, builtin_scene, load_scene};
use shadowlab_shadow::{Bias, Filter, Lookup, Splits, Technique};

use crate::args::ShadowArgs;
use crate::error::CliError;

/// The default shadow-map side.
const DEFAULT_RESOLUTION: u32 = 1024;

/// Everything `render` and `inspect` need, resolved.
pub(crate) struct Resolved {
    pub(crate) scene: Scene,
    pub(crate) technique: Technique,
    pub(crate) resolution: u32,
    pub(crate) partitions: usize,
    pub(crate) splits: Splits,
    pub(crate) lookup: Lookup,
    pub(crate) format: DepthFormat,
}

/// Loads the scene and resolves the settings.
pub(crate) fn resolve(args: &ShadowArgs) -> Result<Resolved, CliError> {
    let scene = load_scene_argument(args.scene.as_deref())?;
    let file = scene_label(args.scene.as_deref());
    let settings = scene.shadow.clone();
    // The value of a setting and where it came from, for the error message.
    let pick =
        |flag: &Option<String>, from_scene: &Option<String>, name: &str| match (flag, from_scene) {
            (Some(v), _) => Some((v.clone(), format!("invalid --{name}"))),
            (None, Some(v)) => Some((
                v.clone(),
                format!("{file}: shadow.{}", name.replace('-', "_")),
            )),
            (None, None) => None,
        };
    let technique_spec = pick(&args.technique, &settings.technique, "technique");
    let parameter_spec = pick(&args.parameter, &settings.parameter, "param");
    let technique = Technique::parse(
        technique_spec.as_ref().map_or("lispsm", |(v, _)| v),
        parameter_spec.as_ref().map(|(v, _)| v.as_str()),
    )
    .map_err(|e| {
        let origin = parameter_spec
            .as_ref()
            .filter(|_| e.contains("parameter"))
            .or(technique_spec.as_ref())
            .map_or("invalid --technique".to_string(), |(_, o)| o.clone());
        CliError::Input(format!("{origin}: {e}"))
    })?;
    let parsed = |spec: Option<(String, String)>,
                  default: &str,
                  parse: &dyn Fn(&str) -> Result<(), String>| {
        match spec {
            Some((value, origin)) => parse(&value)
                .map(|()| value)
                .map_err(|e| CliError::Input(format!("{origin}: {e}"))),
            None => Ok(default.to_string()),
        }
    };
    let splits_spec = parsed(
        pick(&args.split_scheme, &settings.split_scheme, "split-scheme"),
        "practical:0.5",
        &|s| Splits::parse(s).map(|_| ()),
    )?;
    let bias_spec = pick(&args.bias, &settings.bias, "bias");
    let bias = match &bias_spec {
        Some((value, origin)) => {
            Bias::parse(value).map_err(|e| CliError::Input(format!("{origin}: {e}")))?
        }
        None => Bias::DEFAULT,
    };
    let filter_spec = parsed(
        pick(&args.filter, &settings.filter, "filter"),
        "nearest",
        &|s| Filter::parse(s).map(|_| ()),
    )?;
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
    let resolution = args
        .resolution
        .or(settings.resolution)
        .unwrap_or(DEFAULT_RESOLUTION);
    if !(1..=16384).contains(&resolution) {
        return Err(CliError::Input(format!(
            "{file}: shadow.resolution ({resolution}) must lie in 1..=16384"
        )));
    }
    let partitions = args.splits.or(settings.splits).unwrap_or(1);
    if !(1..=16).contains(&partitions) {
        return Err(CliError::Input(format!(
            "{file}: shadow.splits ({partitions}) must lie in 1..=16"
        )));
    }
    Ok(Resolved {
        scene,
        technique,
        resolution,
        partitions: partitions as usize,
        splits: Splits::parse(&splits_spec).expect("checked above"),
        lookup: Lookup::new(bias, Filter::parse(&filter_spec).expect("checked above")),
        format,
    })
}

/// The scene named on the command line: a built-in name, or a path to a scene file.
pub(crate) fn load_scene_argument(name: Option<&str>) -> Result<Scene, CliError> {
    let name = name.unwrap_or(DEFAULT_SCENE);
    let path = Path::new(name);
    let result = if path.exists() || name.ends_with(".toml") {
        load_scene(path)
    } else {
        builtin_scene(name)
    };
    result.map_err(|e| CliError::Input(e.to_string()))
}

/// How errors name the scene's settings: the file, or the built-in scene.
fn scene_label(name: Option<&str>) -> String {
    match name {
        Some(n) if Path::new(n).exists() || n.ends_with(".toml") => n.to_string(),
        Some(n) => format!("built-in scene {n}"),
        None => format!("built-in scene {DEFAULT_SCENE}"),
    }
}

/// The techniques named on the command line (`TECHNIQUE` or `lispsm:PARAMETER`).
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
