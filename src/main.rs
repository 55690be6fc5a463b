//! The `rccpack` command line (SPEC §10).

mod cli;

use std::process::ExitCode;

fn main() -> ExitCode {
    cli::main()
}
