//! The integration tests, linked as one binary (one link instead of one per
//! file); `tests/support/` holds what they share. Run one area with
//! `cargo test --test integration parser::`.

mod support;

mod architecture;
mod ask_budget;
mod ask_cli;
mod ask_groups;
mod ask_probes;
mod ask_tasks;
mod cli;
mod docs;
mod emit;
mod example;
mod first_edition;
mod fuzz_replay;
mod hardening;
mod hardening2;
mod hardening3;
mod learn;
mod learn_cli;
mod learn_props;
mod measured;
mod parser;
mod priors;
mod relations;
mod render;
mod resemblance;
mod robust;
mod sample;
mod sample_cli;
mod scene;
mod shapes;
mod shelf_example;
mod studio_api;
mod studio_browser;
mod synth;
mod synth_differential;
mod task;
mod turns;
mod worked_example;
