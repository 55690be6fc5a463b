//! The `rccpack` command line (docs/cli.md).

mod cli;

use std::process::ExitCode;

fn main() -> ExitCode {
    cli::main()
}
