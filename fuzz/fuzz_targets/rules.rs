//! `cargo +nightly fuzz run rules`: see `rccpack::fuzzing::rules`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rccpack::fuzzing::rules(data));
