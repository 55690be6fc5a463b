//! Benchmarks and studies: the thesis runtime study (`rccpack bench
//! thesis`), its tables and its chart; realistic tasks (`rccpack bench
//! tasks`).
//!
//! * [`pool`] — the pilot rules and SPEC §8 templates, built through the AST;
//! * [`thesis`] — the seeded study generator and runner (solver injected, so
//!   tests can run it on any engine);
//! * [`chart`] — the PNG chart (plotters, embedded font);
//! * [`peers`] — other solvers (OR-Tools CP-SAT, MiniZinc/Gecode) run on
//!   the emitted model, for side-by-side measurement;
//! * [`tasks`] — realistic tasks: demonstrations that follow a hidden
//!   style, rules learned from them, problems larger than the
//!   demonstrations, and the bundled example scaled.

pub mod chart;
pub mod peers;
pub mod pool;
pub mod sample;
pub mod tasks;
pub mod thesis;
