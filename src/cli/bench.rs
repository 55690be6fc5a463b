//! `rccpack bench ARGS…`: a thin delegate to the `rccpack-bench` binary
//! (the benchmarks are the `bench/` package of the repository, not part of
//! the library), found beside this executable.

use super::Reported;
use anyhow::Result;
use clap::Args;
use std::ffi::OsString;
use std::process::ExitCode;

/// `rccpack bench thesis|tasks|sample|priors|noisy …`
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// The command and flags of `rccpack-bench` (`rccpack-bench --help`).
    #[arg(
        trailing_var_arg = true,
        allow_hyphen_values = true,
        value_name = "ARGS"
    )]
    args: Vec<OsString>,
}

/// Run `rccpack-bench` from this executable's folder with the arguments
/// given; its exit code is this command's (1 when it has none: killed by a
/// signal).
pub fn run(a: BenchArgs) -> Result<ExitCode> {
    let exe = std::env::current_exe().map_err(|e| {
        Reported(format!(
            "error: rccpack bench: cannot locate this executable: {e}"
        ))
    })?;
    let bench = exe.with_file_name(format!("rccpack-bench{}", std::env::consts::EXE_SUFFIX));
    if !bench.is_file() {
        return Err(Reported(format!(
            "error: rccpack bench: {} not found: the benchmarks are the rccpack-bench \
             binary, which `cargo build --release` builds beside rccpack",
            bench.display()
        ))
        .into());
    }
    let status = std::process::Command::new(&bench)
        .args(&a.args)
        .status()
        .map_err(|e| {
            Reported(format!(
                "error: rccpack bench: cannot run {}: {e}",
                bench.display()
            ))
        })?;
    let code = status
        .code()
        .and_then(|c| u8::try_from(c).ok())
        .unwrap_or(1);
    Ok(ExitCode::from(code))
}
