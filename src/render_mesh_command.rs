//! `shadowlab render-mesh`: the benchmark's light and eye passes of a mesh, as depth images.

use std::time::Instant;

use glam::DMat4;
use shadowlab_raster::{DepthFormat, DepthTarget, RasterOptions, Rasterizer, Triangles, image_out};
use shadowlab_scene::benchmark::BenchmarkView;

use crate::args::RenderMeshArgs;
use crate::error::CliError;
use crate::memory::{self, Workload};
use crate::output::{OutputDir, png_bound, print_line, slug};

pub(crate) fn run(args: &RenderMeshArgs) -> Result<(), CliError> {
    // Per pass: EXR and NPY depths (4 bytes a texel, uncompressed) and a 16-bit PNG.
    let (eye_width, eye_height) = args.eye_size;
    let estimate =
        png_bound(args.size, args.size, 4 + 4 + 2) + png_bound(eye_width, eye_height, 4 + 4 + 2);
    let out = OutputDir::check(args.out.clone(), "--out", estimate)?;
    let mesh = shadowlab_scene::load_obj(&args.mesh).map_err(|e| CliError::from_input_file(&e))?;
    memory::check(
        &Workload {
            triangles: mesh.triangles().len() as u64,
            eye: (eye_width, eye_height),
            study: false,
            resolution: args.size,
            maps: 1,
            eye_source: "--eye-size",
            map_source: "--size",
            export: false,
        },
        args.memory.memory_budget,
    )?;
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
    let stem = slug(
        &args
            .mesh
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned()),
        "mesh",
    );
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
    out.write("render-mesh", &files)?;
    for (file, _) in &files {
        print_line(&out.path().join(file).display().to_string())?;
    }
    Ok(())
}
