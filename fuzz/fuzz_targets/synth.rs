//! `cargo +nightly fuzz run synth`: see `rccpack::fuzzing::synth`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rccpack::fuzzing::synth(data));
