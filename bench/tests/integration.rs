//! The bench crate's integration tests, linked as one binary; they share
//! the root package's `tests/support/`.

#[path = "../../tests/support/mod.rs"]
mod support;

mod bench_cli;
mod bench_tasks;
mod bench_thesis;
mod priors_bench;
