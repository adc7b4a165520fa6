//! `shadowlab curves`: compute the closed-form figures and write each as CSV, SVG and PNG.

use shadowlab_curves::{CurveConfig, CurvesError, FigureName};

use crate::args::CurvesArgs;
use crate::error::CliError;
use crate::output::{OutputDir, TEXT_BOUND, print_line};

pub(crate) fn run(args: &CurvesArgs) -> Result<(), CliError> {
    let config =
        CurveConfig::new(args.near, args.far, args.fov).map_err(|e| CliError::from_param(&e))?;
    let names: Vec<FigureName> = if args.figures.is_empty() {
        FigureName::ALL.to_vec()
    } else {
        args.figures.clone()
    };
    // A figure's PNG is a few hundred kilobytes.
    let estimate = TEXT_BOUND * names.len() as u64;
    let out = OutputDir::check(args.out.clone(), "--out", estimate)?;
    // Everything is computed and rendered before the first file is written.
    let mut files = Vec::new();
    for name in names {
        let curves = shadowlab_curves::compute(name, &config).map_err(|e| match e {
            CurvesError::Param(p) => CliError::from_param(&p),
            other => CliError::Failure(anyhow::anyhow!("figure {name}: {other}")),
        })?;
        let failure =
            |e: shadowlab_plot::PlotError| CliError::Failure(anyhow::anyhow!("figure {name}: {e}"));
        let svg = shadowlab_plot::render_svg(&curves.figure).map_err(failure)?;
        let png = shadowlab_plot::render_png(&svg).map_err(failure)?;
        let csv = curves.table.to_csv().map_err(failure)?;
        files.push((format!("{name}.csv"), csv.into_bytes()));
        files.push((format!("{name}.svg"), svg.into_bytes()));
        files.push((format!("{name}.png"), png));
    }
    out.write("curves", &files)?;
    for (file, _) in &files {
        print_line(&out.path().join(file).display().to_string())?;
    }
    Ok(())
}
