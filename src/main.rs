//! `shadowlab`: the command-line tool. It parses arguments, calls the library crates and writes
//! files; every computation lives in a crate a library user can call directly.
//!
//! Exit codes: 0 success; 1 an I/O or internal failure; 2 a usage or input error (the message names
//! the flag or file). Outputs are written to a temporary file beside their destination and renamed
//! into place, so a failed run leaves nothing half-written.

mod analyze_command;
mod args;
mod compare_command;
mod curves_command;
mod error;
mod inspect_command;
mod output;
mod params_command;
mod render_command;
mod render_mesh_command;
mod shadow_settings;

use std::process::ExitCode;

use clap::Parser;

use crate::args::{Cli, Command};

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // clap prints help and version to stdout with code 0, and usage errors with code 2.
        Err(e) => e.exit(),
    };
    let result = match cli.command {
        Command::Params(args) => params_command::run(&args),
        Command::Curves(args) => curves_command::run(&args),
        Command::RenderMesh(args) => render_mesh_command::run(&args),
        Command::Render(args) => render_command::run(&args),
        Command::Inspect(args) => inspect_command::run(&args),
        Command::Compare(args) => compare_command::run(&args),
        Command::Analyze(args) => analyze_command::analyze(&args),
        Command::SweepAngle(args) => analyze_command::sweep_angle(&args),
        Command::Temporal(args) => analyze_command::temporal(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("shadowlab: error: {error}");
            error.exit_code()
        }
    }
}
