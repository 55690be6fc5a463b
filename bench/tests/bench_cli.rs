//! The `rccpack-bench` command line: flags checked at once (exit 1,
//! naming the flag and the value), before anything is drawn or written.

use crate::support::{bench_command, stderr};
use std::process::Output;

/// Run `rccpack-bench` with `args` in the repository root.
fn bench(args: &[&str]) -> Output {
    bench_command()
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .output()
        .expect("run rccpack-bench")
}

/// Every bench command's time limit goes through the library's validated
/// parser (moved from `rccpack`'s `bad_time_limits_exit_1_everywhere`).
#[test]
fn bad_time_limits_exit_1() {
    let out = crate::support::scratch("bench-time-limits").join("out");
    let out = out.to_str().unwrap();
    for bad in ["1e20", "-1", "nan", "inf", "1000001", "soon"] {
        let args = ["thesis", "--out", out, "--time-limit", bad];
        let o = bench(&args);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {e}");
        assert!(!e.contains("panicked"), "{args:?}: {e}");
        assert!(
            e.contains("expected a number of seconds from 0 to 1000000"),
            "{args:?}: {e}"
        );
    }
}

/// `bench thesis` refuses out-of-range series, set counts and peers at
/// once (exit 1, naming the flag and the value), before drawing anything.
#[test]
fn bench_flags_out_of_range_are_refused() {
    let out = crate::support::scratch("robust-bench-refuse").join("out");
    for (args, names) in [
        (vec!["--scale-ns", "0"], "invalid value '0' for '--scale-ns"),
        (
            vec!["--scale-ns", "16,513"],
            "invalid value '513' for '--scale-ns",
        ),
        (vec!["--scale-ks", "6"], "invalid value '6' for '--scale-ks"),
        (
            vec!["--scale-ks", "3,0"],
            "invalid value '0' for '--scale-ks",
        ),
        (vec!["--sets", "0"], "invalid value '0' for '--sets"),
        (vec!["--sets", "1001"], "invalid value '1001' for '--sets"),
        (vec!["--peers", "cplex"], "unknown peer `cplex`"),
        (
            vec!["--time-limit", "nan"],
            "invalid value 'nan' for '--time-limit",
        ),
    ] {
        let mut all = vec!["thesis", "--out", out.to_str().unwrap()];
        all.extend(&args);
        let o = bench(&all);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
        let e = stderr(&o);
        assert!(e.contains(names), "{args:?}: message names {names}: {e}");
        assert!(
            !out.exists(),
            "{args:?}: refused before writing {}",
            out.display()
        );
    }
}

/// `rccpack-bench sample --time-limit` takes the shared parser.
#[test]
fn bench_sample_time_limits_are_checked() {
    for v in ["nan", "inf", "-1", "1e30"] {
        let o = bench(&["sample", "--time-limit", v]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{v}: {e}");
        assert!(
            e.contains("time limit") && e.contains("expected"),
            "{v}: {e}"
        );
    }
}

/// The engine tuning variables reach `thesis` and `tasks` (the library
/// never reads them): a value that is not a choice is refused at once,
/// naming the variable, before anything is drawn or written.
#[test]
fn a_tuning_variable_that_is_not_a_choice_is_refused() {
    let out = crate::support::scratch("bench-tuning").join("out");
    let out = out.to_str().unwrap();
    for command in ["thesis", "tasks"] {
        let o = bench_command()
            .args([command, "--quick", "--out", out])
            .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
            .env("RCCPACK_CONNECTIVITY", "circuits")
            .output()
            .expect("run rccpack-bench");
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{command}: {e}");
        assert!(
            e.contains("RCCPACK_CONNECTIVITY=\"circuits\"")
                && e.contains("expected circuit or propagator"),
            "{command}: {e}"
        );
        assert!(!std::path::Path::new(out).exists(), "{command} wrote {out}");
    }
}
