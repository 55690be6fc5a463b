//! `cargo +nightly fuzz run studio`: see `rccpack::fuzzing::studio`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rccpack::fuzzing::studio(data));
