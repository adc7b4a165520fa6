//! `shadowlab render-mesh`: the benchmark's light and eye passes of a mesh, as depth images.

use std::time::Instant;

use glam::DMat4;
use shadowlab_raster::{DepthFormat, DepthTarget, RasterOptions, Rasterizer, Triangles, image_out};
use shadowlab_scene::benchmark::BenchmarkView;

use crate::args::RenderMeshArgs;
use crate::error::CliError;
use crate::output::{ensure_directory, print_line, write_atomic};

pub(crate) fn run(args: &RenderMeshArgs) -> Result<(), CliError> {
    let mesh = shadowlab_scene::load_obj(&args.mesh).map_err(|e| CliError::from_input_file(&e))?;
    let (eye_width, eye_height) = args.eye_size;
    let view = BenchmarkView::new(&mesh.bounds(), eye_width, eye_height);
    let mut positions = mesh.positions().to_vec();
    let (mut light, mut eye) = (view.light, view.eye);
    if args.f32_inputs {
        for p in &mut positions {
            *p = p.as_vec3().as_dvec3();
        }
        light = light.as_mat4().as_dmat4();
        eye = eye.as_mat4().as_dmat4();
    }
    let triangles = Triangles::new(&positions, mesh.triangles());
    let stem = args
        .mesh
        .file_stem()
        .map_or_else(|| "mesh".into(), |s| s.to_string_lossy().into_owned());
    let mut passes: Vec<(&str, u32, u32, DMat4)> = Vec::new();
    if !args.eye {
        passes.push(("light", args.size, args.size, light));
    }
    if !args.light {
        passes.push(("eye", eye_width, eye_height, eye));
    }
    let mut files = Vec::new();
    let mut raster = Rasterizer::new(RasterOptions::default());
    for (name, width, height, m) in passes {
        let mut target = DepthTarget::new(width, height, DepthFormat::F32)
            .map_err(|e| CliError::Input(e.to_string()))?;
        let start = Instant::now();
        let stats = raster
            .draw_depth(&mut target, triangles, &m)
            .map_err(|e| CliError::Input(format!("{}: {e}", args.mesh.display())))?;
        let elapsed = start.elapsed();
        let depths = target.depths();
        let failure = |e: shadowlab_raster::RasterError| {
            CliError::Failure(anyhow::anyhow!("{name} pass: {e}"))
        };
        files.push((
            format!("{stem}-{name}.exr"),
            image_out::depth_exr(&depths, width, height).map_err(failure)?,
        ));
        files.push((
            format!("{stem}-{name}.png"),
            image_out::depth_png16(&depths, width, height).map_err(failure)?,
        ));
        if args.npy {
            files.push((
                format!("{stem}-{name}.npy"),
                image_out::depth_npy(&depths, width, height).map_err(failure)?,
            ));
        }
        print_line(&format!(
            "{name}: {width}x{height}, {} triangles ({} drawn, {} clipped, {} empty, {} degenerate), {} fragments, {:.2} ms",
            stats.triangles,
            stats.drawn,
            stats.clipped,
            stats.empty,
            stats.degenerate,
            stats.fragments,
            elapsed.as_secs_f64() * 1e3
        ))?;
    }
    ensure_directory(&args.out, "--out")?;
    for (file, bytes) in &files {
        let path = args.out.join(file);
        write_atomic(&path, bytes)?;
        print_line(&path.display().to_string())?;
    }
    Ok(())
}
