//! The `rccpack-bench` command line (docs/performance.md): the benchmark
//! suites of rccpack.

mod cli;

use std::process::ExitCode;

fn main() -> ExitCode {
    cli::main()
}
