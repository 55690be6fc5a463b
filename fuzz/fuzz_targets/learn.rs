//! `cargo +nightly fuzz run learn`: see `rccpack::fuzzing::learn`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rccpack::fuzzing::learn(data));
