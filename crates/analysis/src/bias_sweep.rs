//! A bias sweep: the same study at each of several biases, its errors split by cause, so that
//! acne can be weighed against peter-panning ([`crate::attribution`]). Per combination (technique,
//! resolution, maps, filter) the report lists each bias's acne, peter-panning and total, marks the
//! biases on the Pareto front of (acne, peter-panning) — none has both fewer acne pixels and fewer
//! peter-panning pixels, one of them strictly — and names the bias with the fewest misclassified
//! pixels in all.

use std::fmt::Write as _;

use shadowlab_scene::Scene;
use shadowlab_shadow::{Bias, Technique};

use crate::attribution::Causes;
use crate::classify::Misclassification;
use crate::error::AnalysisError;
use crate::report::{csv_field, filter_label, technique_label};
use crate::study::{self, Setting, StudyOptions};

/// The biases a sweep tries when none are named: each family of `--bias` at a few strengths
/// (window-depth offsets from 10⁻⁵ to 10⁻³, slopes 1 to 4, normal offsets of half a texel to two),
/// receiver-plane, and Bevy's and Godot's combinations.
pub const DEFAULT_BIASES: [&str; 14] = [
    "none",
    "constant:1e-5",
    "constant:1e-4",
    "constant:1e-3",
    "slope:1,1e-5",
    "slope:2,1e-5",
    "slope:4,1e-5",
    "receiver-plane:1e-5",
    "normal:0.5",
    "normal:1",
    "normal:2",
    "normal-sine:1",
    "normal:1.8+light:0.02",
    "normal-lateral:2+light:0.04",
];

/// One combination at one bias.
#[derive(Clone, Debug, PartialEq)]
pub struct BiasPoint {
    /// The bias.
    pub bias: Bias,
    /// The combination.
    pub setting: Setting,
    /// Its errors and their causes, or why the technique is not defined for the scene.
    pub outcome: Result<(Misclassification, Causes), String>,
}

/// The default biases, parsed.
///
/// # Panics
/// Never: [`DEFAULT_BIASES`] are tested to parse.
#[must_use]
pub fn default_biases() -> Vec<Bias> {
    DEFAULT_BIASES
        .iter()
        .map(|spec| Bias::parse(spec).expect("a default bias parses"))
        .collect()
}

/// Runs `options`' study once per bias in `biases` (its own bias ignored; one timing run, no
/// pictures, no map truth) and collects every combination's errors and causes, bias by bias.
///
/// # Errors
/// [`AnalysisError::NotSwept`] if a technique is an engine's preset (it reads its maps with its
/// engine's bias); the study's errors.
pub fn bias_sweep(
    scene: &Scene,
    options: &StudyOptions,
    biases: &[Bias],
    mut progress: impl FnMut(usize, usize),
) -> Result<Vec<BiasPoint>, AnalysisError> {
    if let Some(technique) = options
        .techniques
        .iter()
        .find(|t| matches!(t, Technique::Engine(..)))
    {
        return Err(AnalysisError::NotSwept {
            technique: technique.spec(),
        });
    }
    let mut points = Vec::new();
    for (k, bias) in biases.iter().enumerate() {
        progress(k, biases.len());
        let one = StudyOptions {
            bias: *bias,
            timing_runs: 1,
            pictures_at: None,
            map_truth: false,
            ..options.clone()
        };
        let study = study::run(scene, &one, |_, _, _| {})?;
        points.extend(study.measurements.into_iter().map(|m| BiasPoint {
            bias: *bias,
            setting: m.setting,
            outcome: m.outcome.map(|o| (o.errors, o.causes)),
        }));
    }
    progress(biases.len(), biases.len());
    Ok(points)
}

/// Which of `points` lie on the Pareto front of (acne, peter-panning) among those of the same
/// combination: no other point of it has at most as much of both and less of one.
#[must_use]
pub fn on_front(points: &[BiasPoint]) -> Vec<bool> {
    let causes = |p: &BiasPoint| {
        p.outcome
            .as_ref()
            .ok()
            .map(|(_, c)| (c.acne, c.peter_panning))
    };
    points
        .iter()
        .map(|p| {
            let Some((acne, peter)) = causes(p) else {
                return false;
            };
            !points.iter().any(|q| {
                q.setting == p.setting
                    && causes(q)
                        .is_some_and(|(a, b)| a <= acne && b <= peter && (a < acne || b < peter))
            })
        })
        .collect()
}

/// The sweep written out: `bias-sweep.csv` (every point, with `pareto` true on the front) and
/// `bias-sweep.md` (per combination: a row per bias, the front marked, the best bias named).
#[must_use]
pub fn write(scene: &str, points: &[BiasPoint]) -> Vec<(String, Vec<u8>)> {
    let front = on_front(points);
    let scene_field = csv_field(scene);
    let mut csv = String::from(
        "scene,technique,resolution,maps,filter,bias,defined,misclassified,acne,peter_panning,seam_band,seam_boundary,aliasing,seam,pareto\n",
    );
    let mut md = format!(
        "# Bias sweep: `{scene}`\n\nEach bias's misclassified pixels and their causes (acne: falsely shadowed by the receiver's own surface; peter-panning: falsely lit where the unbiased lookup shadows; seams in a blend band and at a partition boundary; aliasing: the rest). ★ marks the Pareto front of acne against peter-panning; **bold**, the bias with the fewest misclassified pixels.\n"
    );
    let mut settings: Vec<&Setting> = Vec::new();
    for p in points {
        if !settings.contains(&&p.setting) {
            settings.push(&p.setting);
        }
    }
    for (p, on) in points.iter().zip(&front) {
        let s = &p.setting;
        let head = format!(
            "{scene_field},{},{},{},{},{}",
            technique_label(s.technique),
            s.resolution,
            s.partitions,
            csv_field(&filter_label(&s.filter)),
            csv_field(&p.bias.to_string())
        );
        match &p.outcome {
            Ok((e, c)) => writeln!(
                csv,
                "{head},true,{},{},{},{on}",
                e.total(),
                c.joined(","),
                c.seam()
            ),
            Err(_) => writeln!(csv, "{head},false,,,,,,,,false"),
        }
        .expect("writing to a string");
    }
    for setting in settings {
        writeln!(
            md,
            "\n## {} at {}², {} map(s), {}\n\n| bias | misclassified | acne | peter-panning | seam in a band | seam at a boundary | aliasing | front |\n|---|---:|---:|---:|---:|---:|---:|:-:|",
            technique_label(setting.technique),
            setting.resolution,
            setting.partitions,
            filter_label(&setting.filter)
        )
        .expect("writing to a string");
        let rows: Vec<(&BiasPoint, bool)> = points
            .iter()
            .zip(front.iter().copied())
            .filter(|(p, _)| &p.setting == setting)
            .collect();
        let best = rows
            .iter()
            .filter_map(|(p, _)| p.outcome.as_ref().ok().map(|(e, _)| e.total()))
            .min();
        for (p, on) in rows {
            let bias = format!("`{}`", p.bias);
            match &p.outcome {
                Ok((e, c)) => {
                    let bias = if Some(e.total()) == best {
                        format!("**{bias}**")
                    } else {
                        bias
                    };
                    writeln!(
                        md,
                        "| {bias} | {} | {} | {} |",
                        e.total(),
                        c.joined(" | "),
                        if on { "★" } else { "" }
                    )
                }
                Err(reason) => writeln!(md, "| {bias} | not defined: {reason} | | | | | | |"),
            }
            .expect("writing to a string");
        }
    }
    vec![
        ("bias-sweep.csv".into(), csv.into_bytes()),
        ("bias-sweep.md".into(), md.into_bytes()),
    ]
}
