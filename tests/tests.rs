//! Integration tests of the `shadowlab` binary, one binary for the whole tool (ripgrep's layout).
//!
//! * `params_cli` — `shadowlab params`: values against formulas.md §8, JSON shape, bad input.
//! * `curves_cli` — `shadowlab curves`: every file written, byte-identical across runs, bad input.
//! * `render_mesh_cli` — `shadowlab render-mesh`: both passes as PNG and EXR, repeatable, bad meshes.
//! * `analyze_cli` — `shadowlab analyze`, `sweep-angle`, `temporal`: the reports, repeatable results,
//!   continuity at γ = 0, bad input.
//! * `point_light_cli` — point lights: the cube map by default, the omnidirectional techniques
//!   analyzed, techniques that cannot serve a light refused with exit 2 before anything is written.
//! * `render_cli` — `shadowlab render` and `inspect`: the pictures, repeatable, partitions, JSON,
//!   bad scenes and settings.
//! * `export_cli` — `--export`: per-pixel results that agree with the report and across commands.
//! * `hostile_cli` — hostile input: malformed OBJ and scene files, special files, absurd flags;
//!   each refused with exit code 2 (1 for I/O failures), a message naming the cause, and nothing
//!   written.
//! * `output_cli` — output sets under faults: rerun, concurrent runs, SIGINT/SIGTERM/SIGKILL, a
//!   failing write, a full or read-only file system, destinations not shadowlab's, hostile names.
//! * `sweep_cli` — `shadowlab sweep` and `merge`: shards merge to the whole sweep (timings aside,
//!   any thread count), reruns resume, incomplete or foreign results and bad specs refused, the
//!   Slurm job array's scripts.
//! * `warp_cli` — what a user states: `--lambda`, `--n`, `--focus`, the `[shadow]` table and its
//!   optimizer settings, rules' inputs in `inspect`, defaults in help texts, refusals named.

mod analyze_cli;
mod curves_cli;
mod export_cli;
mod hostile_cli;
mod output_cli;
mod params_cli;
mod point_light_cli;
mod render_cli;
mod render_mesh_cli;
mod support;
mod sweep_cli;
mod warp_cli;
