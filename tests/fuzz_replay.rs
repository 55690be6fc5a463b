//! Replays every committed fuzz corpus file (`fuzz/corpus/<target>/`) and
//! every crash regression (`fuzz/regressions/<target>/`) through the
//! library's harnesses (`rccpack::fuzzing`), on stable Rust, as part of
//! plain `cargo test`. A harness panics on a bug, so a failing file names
//! itself in the panic message.

use std::path::{Path, PathBuf};

type Harness = fn(&[u8]);

const TARGETS: [(&str, Harness); 5] = [
    ("scene", rccpack::fuzzing::scene),
    ("rules", rccpack::fuzzing::rules),
    ("learn", rccpack::fuzzing::learn),
    ("synth", rccpack::fuzzing::synth),
    ("studio", rccpack::fuzzing::studio),
];

fn files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = match std::fs::read_dir(dir) {
        Ok(rd) => rd
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.is_file())
            .collect(),
        Err(_) => Vec::new(),
    };
    v.sort();
    v
}

fn replay(kind: &str, target: &str, harness: Harness) -> usize {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz")
        .join(kind)
        .join(target);
    let all = files(&dir);
    for f in &all {
        let data = std::fs::read(f).unwrap();
        let r = std::panic::catch_unwind(|| harness(&data));
        assert!(r.is_ok(), "{kind} file {} fails its harness", f.display());
    }
    all.len()
}

fn replay_target(target: &str) {
    let (_, harness) = TARGETS.iter().find(|t| t.0 == target).unwrap();
    let corpus = replay("corpus", target, *harness);
    let regressions = replay("regressions", target, *harness);
    eprintln!("{target}: {corpus} corpus files, {regressions} regressions replayed");
    assert!(corpus > 0, "fuzz/corpus/{target} is empty");
}

#[test]
fn scene_corpus() {
    replay_target("scene");
}

#[test]
fn rules_corpus() {
    replay_target("rules");
}

#[test]
fn learn_corpus() {
    replay_target("learn");
}

#[test]
fn synth_corpus() {
    replay_target("synth");
}

#[test]
fn studio_corpus() {
    replay_target("studio");
}

/// The bundled example and a few fixed inputs run through every harness
/// (the corpora grow from these seeds).
#[test]
fn harnesses_accept_known_good_inputs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let problem = std::fs::read(root.join("examples/box-packing/problem.json")).unwrap();
    rccpack::fuzzing::scene(&problem);
    let demos = std::fs::read(root.join("examples/box-packing/demos.json")).unwrap();
    rccpack::fuzzing::scene(&demos);
    let pilot = std::fs::read(root.join("examples/box-packing/pilot.rcc")).unwrap();
    rccpack::fuzzing::rules(&pilot);
    rccpack::fuzzing::rules(b"rule x: DR_N(B, R) &\n");
    rccpack::fuzzing::learn(&[7; 64]);
    rccpack::fuzzing::synth(&[3; 64]);
    rccpack::fuzzing::studio(&[1; 64]);
}
