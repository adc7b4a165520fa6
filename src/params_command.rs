//! `shadowlab params`: every technique's warp parameter and maximum error for one configuration.

use serde::Serialize;
use shadowlab_params::cad::{self, Falloff};
use shadowlab_params::{
    DepthRange, FrustumModel, HalfFov, LightAngle, ModelCase, ParameterRule, RuleEvaluation, gmnpr,
};

use crate::args::{CadFalloff, ParamsArgs};
use crate::error::CliError;
use crate::output::print_line;

/// The JSON document: the input, the special angles, and one entry per technique.
#[derive(Serialize)]
struct Report {
    input: Input,
    /// γ_lim of CAD eq. 15, in degrees.
    gamma_lim: f64,
    /// θ_0, below which no parameter equalises the errors, in degrees.
    theta0: f64,
    /// θ1, below which equal error is not the minimax, in degrees.
    theta1: f64,
    /// The model's warp depth d = f' − n' at this angle.
    warp_depth: f64,
    /// "wide" (γ ≥ φ) or "narrow".
    case: &'static str,
    techniques: Techniques,
    /// Techniques with no valid parameter at this angle.
    not_defined: Vec<&'static str>,
}

#[derive(Serialize)]
struct Input {
    near: f64,
    far: f64,
    fov: f64,
    gamma: f64,
}

/// The techniques, in this order; an undefined one is left out (and listed in `not_defined`).
#[derive(Serialize)]
struct Techniques {
    #[serde(skip_serializing_if = "Option::is_none")]
    uniform: Option<Technique>,
    #[serde(skip_serializing_if = "Option::is_none")]
    lispsm: Option<Technique>,
    #[serde(skip_serializing_if = "Option::is_none")]
    lispsm_dz: Option<Technique>,
    #[serde(skip_serializing_if = "Option::is_none")]
    cad: Option<Technique>,
    #[serde(skip_serializing_if = "Option::is_none")]
    gmnpr: Option<Technique>,
    #[serde(skip_serializing_if = "Option::is_none")]
    glpr: Option<Technique>,
    #[serde(skip_serializing_if = "Option::is_none")]
    minimax: Option<Technique>,
}

/// One technique's numbers. `null` for `n` and `lambda` means the uniform map (λ = ∞); `null` for
/// `max_error` means unbounded (γ = 0).
#[derive(Serialize)]
struct Technique {
    n: Option<f64>,
    lambda: Option<f64>,
    max_error: Option<f64>,
    /// For `cad`: which fall-back curve r(γ) was used.
    #[serde(skip_serializing_if = "Option::is_none")]
    r: Option<&'static str>,
}

impl Technique {
    fn new(evaluation: RuleEvaluation, r: Option<&'static str>) -> Self {
        let finite = |x: f64| x.is_finite().then_some(x);
        Self {
            n: finite(evaluation.near_distance),
            lambda: finite(evaluation.warp.lambda()),
            max_error: finite(evaluation.max_error),
            r,
        }
    }
}

pub(crate) fn run(args: &ParamsArgs) -> Result<(), CliError> {
    let model = FrustumModel::new(
        DepthRange::new(args.near, args.far).map_err(|e| CliError::from_param(&e))?,
        HalfFov::from_full_fov_degrees(args.fov).map_err(|e| CliError::from_param(&e))?,
    );
    let gamma = LightAngle::from_degrees(args.gamma).map_err(|e| CliError::from_param(&e))?;
    let falloff = match args.cad_r {
        CadFalloff::Eq18 => Falloff::Eq18,
        CadFalloff::Eq17 => Falloff::Eq17,
        CadFalloff::Sin2 => Falloff::SinSquared,
    };
    let rules = [
        ParameterRule::Uniform,
        ParameterRule::Lispsm,
        ParameterRule::LispsmDeltaZ,
        ParameterRule::Cad(falloff),
        ParameterRule::Gmnpr,
        ParameterRule::Glpr,
        ParameterRule::Minimax,
    ];
    let evaluations = rules.map(|rule| rule.evaluate(&model, gamma));
    let report = report(args, &model, gamma, falloff, &evaluations);
    if args.json {
        let text = serde_json::to_string_pretty(&report)
            .map_err(|e| CliError::Failure(anyhow::Error::new(e)))?;
        print_line(&text)
    } else {
        print_table(&report, &rules, &evaluations, falloff)
    }
}

fn report(
    args: &ParamsArgs,
    model: &FrustumModel,
    gamma: LightAngle,
    falloff: Falloff,
    evaluations: &[Option<RuleEvaluation>; 7],
) -> Report {
    let entry = |i: usize, r: Option<&'static str>| evaluations[i].map(|e| Technique::new(e, r));
    let keys = [
        "uniform",
        "lispsm",
        "lispsm_dz",
        "cad",
        "gmnpr",
        "glpr",
        "minimax",
    ];
    Report {
        input: Input {
            near: args.near,
            far: args.far,
            fov: args.fov,
            gamma: args.gamma,
        },
        gamma_lim: cad::gamma_lim(model).degrees(),
        theta0: gmnpr::theta0(model).degrees(),
        theta1: gmnpr::theta1(model).degrees(),
        warp_depth: model.warp_depth(gamma),
        case: match model.case(gamma) {
            ModelCase::Wide => "wide",
            ModelCase::Narrow => "narrow",
        },
        techniques: Techniques {
            uniform: entry(0, None),
            lispsm: entry(1, None),
            lispsm_dz: entry(2, None),
            cad: entry(3, Some(falloff.key())),
            gmnpr: entry(4, None),
            glpr: entry(5, None),
            minimax: entry(6, None),
        },
        not_defined: keys
            .iter()
            .zip(evaluations)
            .filter(|(_, e)| e.is_none())
            .map(|(k, _)| *k)
            .collect(),
    }
}

fn print_table(
    report: &Report,
    rules: &[ParameterRule; 7],
    evaluations: &[Option<RuleEvaluation>; 7],
    falloff: Falloff,
) -> Result<(), CliError> {
    let i = &report.input;
    print_line(&format!(
        "near = {}, far = {}, fov = {}°, gamma = {}° ({} case)",
        i.near, i.far, i.fov, i.gamma, report.case
    ))?;
    print_line(&format!(
        "gamma_lim = {}°, theta0 = {}°, theta1 = {}°, warp depth d = {}",
        significant(report.gamma_lim),
        significant(report.theta0),
        significant(report.theta1),
        significant(report.warp_depth)
    ))?;
    print_line("")?;
    print_line(&format!(
        "{:<10} {:>16} {:>16} {:>16}  rule",
        "technique", "n'", "lambda", "max error F"
    ))?;
    let keys = [
        "uniform",
        "lispsm",
        "lispsm_dz",
        "cad",
        "gmnpr",
        "glpr",
        "minimax",
    ];
    for ((key, rule), evaluation) in keys.iter().zip(rules).zip(evaluations) {
        let Some(e) = evaluation else { continue };
        let label = if matches!(rule, ParameterRule::Cad(_)) {
            format!("CAD eq. 16, {}", falloff.formula())
        } else {
            rule.label().to_owned()
        };
        print_line(&format!(
            "{:<10} {:>16} {:>16} {:>16}  {label}",
            key,
            significant(e.near_distance),
            significant(e.warp.lambda()),
            significant(e.max_error),
        ))?;
    }
    if !report.not_defined.is_empty() {
        print_line("")?;
        print_line(&format!(
            "not defined at this angle: {} (GLPR needs gamma > fov/2)",
            report.not_defined.join(", ")
        ))?;
    }
    if evaluations
        .iter()
        .flatten()
        .any(|e| e.max_error.is_infinite())
    {
        print_line(
            "max error inf: the light is parallel to the view, every map is unbounded along it",
        )?;
    }
    Ok(())
}

/// A number with 12 significant digits and no trailing zeros; "inf" for infinity.
fn significant(x: f64) -> String {
    if x.is_infinite() {
        return "inf".into();
    }
    let text = format!("{x:.11e}");
    let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
    let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
    let exponent: i32 = exponent.parse().unwrap_or(0);
    if (-4..12).contains(&exponent) {
        let value = format!("{x:.*}", usize::try_from(11 - exponent).unwrap_or(0));
        if value.contains('.') {
            value.trim_end_matches('0').trim_end_matches('.').to_owned()
        } else {
            value
        }
    } else {
        format!("{mantissa}e{exponent}")
    }
}

#[cfg(test)]
mod tests {
    use super::significant;

    #[test]
    fn numbers_keep_twelve_digits() {
        assert_eq!(significant(11.0), "11");
        assert_eq!(significant(0.1111111111111111), "0.111111111111");
        assert_eq!(significant(9.9), "9.9");
        assert_eq!(significant(1e-7), "1e-7");
        assert_eq!(significant(123456789012345.0), "1.23456789012e14");
        assert_eq!(significant(f64::INFINITY), "inf");
    }
}
