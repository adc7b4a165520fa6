//! `shadowlab`: the command-line tool. It parses arguments, calls the library crates and writes
//! files; every computation lives in a crate a library user can call directly. The binary
//! (`src/main.rs`) calls [`run`]; [`check_arguments`] is the same front end without the work, for
//! the argument fuzzer (`fuzz/`).
//!
//! Exit codes: 0 success; 1 an I/O or internal failure; 2 a usage or input error (the message names
//! the flag or file); 130 or 143 when interrupted by SIGINT or SIGTERM. Outputs are written whole
//! into a staging directory beside their destination and moved into place in one step (see
//! `output`), so a failed, interrupted or killed run leaves nothing half-written.

mod analyze_command;
mod args;
mod compare_command;
mod curves_command;
mod error;
mod evaluate_command;
mod exports;
mod inspect_command;
mod memory;
mod output;
mod params_command;
mod progress;
mod render_command;
mod render_mesh_command;
mod shadow_settings;
mod staging;
mod sweep_command;

use std::ffi::OsString;
use std::process::ExitCode;

use clap::Parser;

use crate::args::{Cli, Command};

/// Runs the tool on `arguments` (the program name first, as `std::env::args_os` gives them):
/// parses them, runs the subcommand, prints an error to standard error and returns the exit code.
pub fn run<I, T>(arguments: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = match Cli::try_parse_from(arguments) {
        Ok(cli) => cli,
        // clap prints help and version to stdout with code 0, and usage errors with code 2.
        Err(e) => e.exit(),
    };
    staging::install_interrupt_cleanup();
    let result = match cli.command {
        Command::Params(args) => params_command::run(&args),
        Command::Curves(args) => curves_command::run(&args),
        Command::RenderMesh(args) => render_mesh_command::run(&args),
        Command::Render(args) => render_command::run(&args),
        Command::Inspect(args) => inspect_command::run(&args),
        Command::Compare(args) => compare_command::run(&args),
        Command::Analyze(args) => analyze_command::analyze(&args),
        Command::SweepAngle(args) => analyze_command::sweep_angle(&args),
        Command::Evaluate(args) => evaluate_command::run(&args),
        Command::Temporal(args) => analyze_command::temporal(&args),
        Command::Sweep(args) => sweep_command::sweep(&args),
        Command::Merge(args) => sweep_command::merge(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("shadowlab: error: {error}");
            error.exit_code()
        }
    }
}

/// Parses `arguments` as [`run`] does, without running anything: `Err` carries the message a user
/// would see. Never panics, whatever the arguments.
pub fn check_arguments<I, T>(arguments: I) -> Result<(), String>
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    Cli::try_parse_from(arguments)
        .map(drop)
        .map_err(|e| e.to_string())
}
