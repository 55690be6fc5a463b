//! Benchmarks and studies: the thesis runtime study (`rccpack bench
//! thesis`), its tables and its chart.
//!
//! * [`pool`] — the pilot rules and SPEC §8 templates, built through the AST;
//! * [`thesis`] — the seeded study generator and runner (solver injected, so
//!   tests can run it on any engine);
//! * [`chart`] — the PNG chart (plotters, embedded font);
//! * [`peers`] — other solvers (OR-Tools CP-SAT, MiniZinc/Gecode) run on
//!   the emitted model, for side-by-side measurement.

pub mod chart;
pub mod peers;
pub mod pool;
pub mod thesis;
