//! The `shadowlab` binary: everything is in the library (`src/lib.rs`).

fn main() -> std::process::ExitCode {
    shadowlab::run(std::env::args_os())
}
