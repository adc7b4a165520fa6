//! `shadowlab sweep` and `shadowlab merge`: a study spec run whole or shard by shard, its Slurm
//! job array, and the merge of its cells.

use std::path::{Path, PathBuf};
use std::time::Instant;

use shadowlab_scene::Scene;
use shadowlab_sweep::merge::merged_files;
use shadowlab_sweep::run::run_shard;
use shadowlab_sweep::shard::{assign, loads};
use shadowlab_sweep::store::{MERGED_DIR, SLURM_DIR, SweepDir, collect, write_atomically};
use shadowlab_sweep::{EXAMPLE, Plan, Shard, Spec, SweepError, SweepIdentity};

use crate::args::{MergeArgs, SceneArg, SweepSpecArgs};
use crate::error::CliError;
use crate::output::{OutputDir, TEXT_BOUND, print_line, slug};
use crate::progress;
use crate::shadow_settings::load_scene_argument;

/// The merged output's size bound: the tables, the report and two figures.
const MERGED_BOUND: u64 = 16 * TEXT_BOUND;

fn sweep_error(e: SweepError) -> CliError {
    match e {
        SweepError::Spec(_) | SweepError::Scene(_) | SweepError::Shard(_) => {
            CliError::Input(e.to_string())
        }
        SweepError::Analysis(_) | SweepError::Output(_) => CliError::Failure(anyhow::anyhow!(e)),
    }
}

/// The spec file's text and its plan (scenes loaded, cells enumerated).
fn plan_of(path: &Path) -> Result<(String, Plan), CliError> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        CliError::Input(format!(
            "cannot read the sweep spec {}: {e}",
            path.display()
        ))
    })?;
    let base = path.parent().unwrap_or(Path::new("."));
    let spec = Spec::parse(&text, base)
        .map_err(|e| CliError::Input(format!("{}: {e}", path.display())))?;
    let scenes = spec
        .scenes
        .iter()
        .enumerate()
        .map(|(k, (label, source))| {
            let scene: Scene = load_scene_argument(&SceneArg {
                name: Some(source.argument()),
                gltf_scene: None,
            })
            .map_err(|e| match e {
                CliError::Input(m) => {
                    CliError::Input(format!("{}: scenes[{k}] ({label}): {m}", path.display()))
                }
                other => other,
            })?;
            Ok((label.clone(), scene))
        })
        .collect::<Result<Vec<_>, CliError>>()?;
    let plan = Plan::new(&spec, scenes)
        .map_err(|e| CliError::Input(format!("{}: {e}", path.display())))?;
    Ok((text, plan))
}

/// `--out`, or out/sweep/<the spec's file stem>.
fn sweep_dir_path(args: &SweepSpecArgs, spec: &Path) -> PathBuf {
    args.out.clone().unwrap_or_else(|| {
        let stem = spec
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        PathBuf::from("out")
            .join("sweep")
            .join(slug(&stem, "sweep"))
    })
}

pub(crate) fn sweep(args: &SweepSpecArgs) -> Result<(), CliError> {
    if args.example {
        return print_line(EXAMPLE.trim_end());
    }
    let spec_path = args
        .spec
        .as_ref()
        .expect("clap requires SPEC without --example");
    let (text, plan) = plan_of(spec_path)?;
    let identity = SweepIdentity {
        spec: text,
        cells: plan.cells.len(),
    };
    let root = sweep_dir_path(args, spec_path);
    if args.dry_run {
        // What a directory of this sweep already holds, if there is one (never created here).
        let done = SweepDir::open(&root)
            .ok()
            .filter(|dir| dir.identity() == &identity);
        return dry_run(
            &plan,
            args.shard.map(|s| s.count).or(args.shards),
            done.as_ref(),
        );
    }
    if args.slurm {
        for option in &args.sbatch_option {
            if !option.starts_with("--") || option.contains('\n') {
                return Err(CliError::Input(format!(
                    "invalid --sbatch-option: `{option}` is not one sbatch long option (--name=value)"
                )));
            }
        }
    }
    // A --slurm run makes the sweep directory too, so that its tasks find it theirs.
    let dir = SweepDir::create(&root, identity).map_err(|e| match e {
        SweepError::Shard(m) => CliError::Input(format!("invalid --out: {m}")),
        other => sweep_error(other),
    })?;
    if args.slurm {
        let shards = args.shards.expect("clap requires --shards with --slurm");
        return write_slurm(spec_path, &root, shards, &args.sbatch_option);
    }
    let shard = args.shard.unwrap_or(Shard::ALL);
    // Checked before the work, so a whole run does not fail at its end.
    let merged = if args.shard.is_none() {
        Some(OutputDir::check(
            root.join(MERGED_DIR),
            "--out",
            MERGED_BOUND,
        )?)
    } else {
        None
    };
    let bar = progress::bar("sweep");
    let start = Instant::now();
    let run = run_shard(&plan, shard, &dir, |done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    });
    bar.finish_and_clear();
    let run = run.map_err(sweep_error)?;
    print_line(&format!(
        "shard {shard}: {} cells ({} measured now, {} stored before) in {:.1} s; {}",
        run.records.len(),
        run.measured,
        run.records.len() - run.measured,
        start.elapsed().as_secs_f64(),
        root.join(shard.dir_name()).join("results.csv").display()
    ))?;
    if let Some(out) = merged {
        write_merged(&out, &run.records)?;
    }
    Ok(())
}

/// Prints the sweep's size and estimated work, per shard if `shards` is given, and how many
/// cells the sweep directory `done` holds already (in all and per shard).
fn dry_run(plan: &Plan, shards: Option<usize>, done: Option<&SweepDir>) -> Result<(), CliError> {
    let finished: Vec<bool> = plan
        .cells
        .iter()
        .map(|c| done.is_some_and(|d| d.load_cell(c.index).is_some()))
        .collect();
    let progress = |cells: &mut dyn Iterator<Item = usize>| -> String {
        match done {
            Some(_) => {
                let (n, finished) =
                    cells.fold((0, 0), |(n, f), c| (n + 1, f + usize::from(finished[c])));
                format!(", {finished} of {n} done")
            }
            None => String::new(),
        }
    };
    let seconds = |ns: f64| ns / 1e9;
    print_line(&format!(
        "{} cells in {} frames ({} scene(s)){}",
        plan.cells.len(),
        plan.frames.len(),
        plan.scenes.len(),
        progress(&mut (0..plan.cells.len()))
    ))?;
    print_line(&format!(
        "estimated work: {:.1} CPU-seconds (the cost model of docs/cluster.md; frames' truths {:.1} s of it)",
        seconds(plan.total_cost()),
        seconds(plan.frame_costs.iter().sum())
    ))?;
    if let Some(count) = shards {
        let assignment = assign(plan, count).map_err(sweep_error)?;
        let loads = loads(plan, &assignment, count);
        for (k, load) in loads.iter().enumerate() {
            let cells = assignment.iter().filter(|s| **s == k).count();
            let mine = &mut (0..plan.cells.len()).filter(|c| assignment[*c] == k);
            print_line(&format!(
                "shard {k}/{count}: {cells} cells, estimated {:.1} CPU-seconds{}",
                seconds(*load),
                progress(mine)
            ))?;
        }
    }
    Ok(())
}

/// Writes the merged table, report and figures of `records` as the output set `out`.
fn write_merged(out: &OutputDir, records: &[shadowlab_sweep::CellRecord]) -> Result<(), CliError> {
    let files = merged_files(records).map_err(sweep_error)?;
    let mut set = out.begin("sweep")?;
    for (name, bytes) in &files {
        set.add(name, bytes)?;
    }
    set.finish()?;
    print_line(&out.path().join("report.md").display().to_string())
}

pub(crate) fn merge(args: &MergeArgs) -> Result<(), CliError> {
    let out = OutputDir::check(args.out.clone(), "--out", MERGED_BOUND)?;
    let dirs = args
        .dirs
        .iter()
        .map(|d| SweepDir::open(d))
        .collect::<Result<Vec<_>, _>>()
        .map_err(sweep_error)?;
    let (_, records) = collect(&dirs).map_err(sweep_error)?;
    write_merged(&out, &records)
}

/// An absolute form of `path` (which need not exist yet), for scripts run elsewhere.
fn absolute(path: &Path, flag: &str) -> Result<PathBuf, CliError> {
    std::path::absolute(path)
        .map_err(|e| CliError::Input(format!("invalid {flag}: {}: {e}", path.display())))
}

/// Single-quotes `text` for a POSIX shell.
fn shell_quote(text: &str) -> String {
    format!("'{}'", text.replace('\'', "'\\''"))
}

/// `--slurm` (its `options` checked): DIR/slurm/array.sbatch (a job array, one task per shard), merge.sbatch (the merge)
/// and submit.sh (submits the array, then the merge with `--dependency=afterok` on it, and
/// prints both job ids).
fn write_slurm(
    spec: &Path,
    root: &Path,
    shards: usize,
    options: &[String],
) -> Result<(), CliError> {
    let exe = std::env::current_exe()
        .map_err(|e| CliError::Failure(anyhow::anyhow!("cannot find this program: {e}")))?;
    let spec = absolute(spec, "SPEC")?;
    let root = absolute(root, "--out")?;
    let slurm = root.join(SLURM_DIR);
    std::fs::create_dir_all(slurm.join("logs")).map_err(|e| {
        CliError::Input(format!(
            "invalid --out: cannot create {}: {e}",
            slurm.display()
        ))
    })?;
    let q = |p: &Path| shell_quote(&p.display().to_string());
    let extra: String = options.iter().map(|o| format!("#SBATCH {o}\n")).collect();
    let array = format!(
        "#!/bin/bash\n# A shadowlab sweep as a Slurm job array: task I runs shard I of {shards}.\n#SBATCH --job-name=shadowlab-sweep\n#SBATCH --array=0-{last}\n#SBATCH --ntasks=1\n#SBATCH --output={logs}/shard-%a.out\n{extra}set -euo pipefail\n# As many threads as CPUs the task was given (1 unless --cpus-per-task says more), whether or not\n# the cluster binds tasks to their CPUs.\nexport RAYON_NUM_THREADS=\"${{SLURM_CPUS_PER_TASK:-1}}\"\nexec {exe} sweep {spec} --out {root} --shard \"${{SLURM_ARRAY_TASK_ID}}/{shards}\"\n",
        last = shards - 1,
        logs = slurm.join("logs").display(),
        exe = q(&exe),
        spec = q(&spec),
        root = q(&root),
    );
    let merge = format!(
        "#!/bin/bash\n# Merges the sweep's shards once every task of the array has succeeded.\n#SBATCH --job-name=shadowlab-merge\n#SBATCH --ntasks=1\n#SBATCH --output={logs}/merge.out\nset -euo pipefail\nexec {exe} merge {root} --out {merged}\n",
        logs = slurm.join("logs").display(),
        exe = q(&exe),
        root = q(&root),
        merged = q(&root.join(MERGED_DIR)),
    );
    let submit = format!(
        "#!/bin/bash\n# Submits the sweep's job array, then its merge to run after every task succeeded;\n# prints the array's job id, then the merge's.\nset -euo pipefail\narray=$(sbatch --parsable {array})\narray=${{array%%;*}}\necho \"$array\"\nsbatch --parsable --dependency=afterok:\"$array\" {merge} | cut -d';' -f1\n",
        array = q(&slurm.join("array.sbatch")),
        merge = q(&slurm.join("merge.sbatch")),
    );
    for (name, text) in [
        ("array.sbatch", array),
        ("merge.sbatch", merge),
        ("submit.sh", submit),
    ] {
        write_atomically(&slurm.join(name), text.as_bytes()).map_err(sweep_error)?;
    }
    print_line(&format!(
        "submit with: bash {}",
        slurm.join("submit.sh").display()
    ))
}
