//! `cargo +nightly fuzz run scene`: see `rccpack::fuzzing::scene`.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| rccpack::fuzzing::scene(data));
