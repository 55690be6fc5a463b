//! The thesis runtime study (§4.1, Figure 4-1), reproduced with a seeded
//! generator.
//!
//! 1. **Viable sets.** Draw 5 rules per class (R, G, B) at random from
//!    [`pool_for`](super::pool::pool_for); keep the draw when 2 objects per class can reach score 1
//!    in the box (solved by the engine within the time limit). Repeat until
//!    `sets` viable sets are found (or `max_draws` draws were tried).
//! 2. **Pilot grid.** For every set, every `n` in `ns` (objects) and every `k`
//!    in `ks` (rules per class): the first `k` rules per class of the set, and
//!    `n` objects of uniformly random classes, in the 600×600 box scene.
//! 3. **Scale series.** The same with `n` in `scale_ns` and `k` in
//!    `scale_ks`, in a box enlarged to hold the objects ([`interior_side`]).
//!
//! Every rule is soft with weight 1. Each problem is solved once; the row
//! records status, wall time and search nodes, and the solution is checked
//! by the engine's solution checker.
//!
//! Determinism: the draws use `ChaCha8Rng::seed_from_u64(seed)` on stream 0;
//! the classes of problem `(series, set, n, k)` come from their own stream,
//! so a quick run's problems are the first problems of a full run with the
//! same seed (as long as the engine decides viability the same way).

mod problems;
mod report;
mod solve;

use super::peers::Peer;
pub use super::{SolveFn, Solver, VerifyFn};
use rccpack::relations::Contact;
use serde::Serialize;
use std::time::Duration;

pub use problems::{
    box_scene, draw_set, find_viable_sets, interior_side, problems, study_problems,
    unsatisfiable_with_two, with_blocks, DrawnSet, Problem,
};
pub use report::{
    median, peer_table_text, summarize, summarize_peers, table_text, PeerSummary, Summary,
};
pub use solve::{
    run_study, solve_peer, solve_problem, study_options, PeerRow, Row, SetReport, StudyEvent,
    StudyReport,
};

/// The movable classes of the box-packing task.
pub const CLASSES: [&str; 3] = ["R", "G", "B"];

/// Side of every movable block.
pub const BLOCK: i64 = 20;

/// Thickness of the walls.
pub const WALL: i64 = 10;

/// Free table between the walls and the edge of the space.
pub const MARGIN: i64 = 190;

/// Which part of the study a problem belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, PartialOrd, Ord, Hash)]
#[serde(rename_all = "lowercase")]
pub enum Series {
    /// n = 2..6, k = 1..5 in the 600×600 box (the thesis grid).
    Pilot,
    /// Larger n in an enlarged box.
    Scale,
}

impl Series {
    fn code(self) -> u64 {
        match self {
            Series::Pilot => 1,
            Series::Scale => 2,
        }
    }
}

/// Study parameters.
#[derive(Debug, Clone, Serialize)]
pub struct StudyConfig {
    /// Seed of every random choice.
    pub seed: u64,
    /// Per-problem time limit (also for the viability solves).
    #[serde(serialize_with = "ser_secs")]
    pub time_limit: Duration,
    /// Viable rule sets to collect.
    pub sets: usize,
    /// Rules drawn per class.
    pub rules_per_class: usize,
    /// Objects per class in the viability check.
    pub viability_objects_per_class: usize,
    /// Give up drawing after this many draws.
    pub max_draws: usize,
    /// Object counts of the pilot grid.
    pub ns: Vec<usize>,
    /// Rules per class of the pilot grid.
    pub ks: Vec<usize>,
    /// Object counts of the scale series (empty: no scale series).
    pub scale_ns: Vec<usize>,
    /// Rules per class of the scale series.
    pub scale_ks: Vec<usize>,
    /// Contact mode.
    #[serde(serialize_with = "ser_display")]
    pub contact: Contact,
    /// Large-neighbourhood search on large problems (`SynthOptions::lns`).
    pub lns: bool,
    /// Peer solvers run beside rccpack on every problem (same model, same
    /// time limit).
    #[serde(serialize_with = "ser_peers")]
    pub peers: Vec<Peer>,
    /// Engine tuning of every solve (never changes an answer; the
    /// command filled it from `RCCPACK_*` variables).
    #[serde(skip)]
    pub tuning: rccpack::synth::Tuning,
}

pub(crate) fn ser_peers<S: serde::Serializer>(p: &[Peer], s: S) -> Result<S::Ok, S::Error> {
    s.collect_seq(p.iter().map(|p| p.name()))
}

pub(crate) fn ser_secs<S: serde::Serializer>(d: &Duration, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(d.as_secs_f64())
}

fn ser_display<S: serde::Serializer>(c: &Contact, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&c.to_string())
}

impl StudyConfig {
    /// The full study: 10 sets, n = 2..6 × k = 1..5, and the scale series
    /// n ∈ {8, 12, 16, 24, 32, 48, 64, 96} × k ∈ {3, 5}.
    pub fn full(seed: u64, time_limit: Duration) -> Self {
        StudyConfig {
            seed,
            time_limit,
            sets: 10,
            rules_per_class: 5,
            viability_objects_per_class: 2,
            max_draws: 50_000,
            ns: (2..=6).collect(),
            ks: (1..=5).collect(),
            scale_ns: vec![8, 12, 16, 24, 32, 48, 64, 96],
            scale_ks: vec![3, 5],
            contact: Contact::Point,
            lns: true,
            peers: Vec::new(),
            tuning: rccpack::synth::Tuning::default(),
        }
    }

    /// A smoke run: 3 sets, the pilot grid only.
    pub fn quick(seed: u64, time_limit: Duration) -> Self {
        StudyConfig {
            sets: 3,
            scale_ns: Vec::new(),
            ..Self::full(seed, time_limit)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use rccpack::relations::Kind;
    use rccpack::rules::{Formula, Target};

    #[test]
    fn pilot_box_matches_the_thesis_scene() {
        let s = box_scene(200);
        assert_eq!((s.space.width, s.space.height), (600, 600));
        let r: Vec<_> = s.objects.iter().map(|o| o.rect().unwrap()).collect();
        use rccpack::scene::Rect;
        assert_eq!(r[0], Rect::new(190, 190, 220, 10));
        assert_eq!(r[1], Rect::new(190, 400, 220, 10));
        assert_eq!(r[2], Rect::new(190, 200, 10, 200));
        assert_eq!(r[3], Rect::new(400, 200, 10, 200));
        s.validate().unwrap();
        box_scene(interior_side(48)).validate().unwrap();
    }

    #[test]
    fn interior_grows_with_n() {
        assert_eq!(interior_side(2), 200);
        assert_eq!(interior_side(32), 200);
        assert_eq!(interior_side(48), 240);
        assert_eq!(interior_side(200), 440);
    }

    #[test]
    fn problems_are_deterministic_and_shaped() {
        let cfg = StudyConfig::quick(7, Duration::from_secs(1));
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let sets: Vec<DrawnSet> = (1..=2).map(|d| draw_set(&mut rng, 5, d)).collect();
        for s in &sets {
            for (c, rs) in CLASSES.iter().zip(&s.rules) {
                assert_eq!(rs.len(), 5);
                assert!(rs.iter().all(|r| r.subject() == *c));
                let mut names: Vec<_> = rs.iter().map(|r| &r.name).collect();
                names.dedup();
                assert_eq!(names.len(), 5);
            }
            assert_eq!(s.first(2).rules.len(), 6);
        }
        let a = problems(&cfg, &sets, Series::Pilot, &cfg.ns, &cfg.ks);
        let b = problems(&cfg, &sets, Series::Pilot, &cfg.ns, &cfg.ks);
        assert_eq!(a.len(), 2 * 5 * 5);
        for (p, q) in a.iter().zip(&b) {
            assert_eq!(p.scene, q.scene);
            assert_eq!(p.classes().len(), p.n);
            assert_eq!(p.rules.rules.len(), 3 * p.k);
            p.scene.validate().unwrap();
        }
        let classes: std::collections::HashSet<String> = a.iter().map(|p| p.classes()).collect();
        assert!(classes.len() > 10, "classes vary: {classes:?}");
    }

    #[test]
    fn self_referential_atoms_are_hopeless_for_two() {
        use crate::pool::{atom, touches};
        use rccpack::relations::Dir;
        let c = |s: &str| Target::Class(s.into());
        assert!(unsatisfiable_with_two(&atom(
            Kind::DR,
            Dir::N,
            "R",
            &c("R")
        )));
        assert!(unsatisfiable_with_two(&atom(
            Kind::EC,
            Dir::W,
            "R",
            &c("R")
        )));
        assert!(unsatisfiable_with_two(&atom(
            Kind::DR,
            Dir::E,
            "R",
            &Target::Any
        )));
        assert!(!unsatisfiable_with_two(&atom(
            Kind::EC,
            Dir::E,
            "R",
            &Target::Any
        )));
        assert!(!unsatisfiable_with_two(&atom(
            Kind::DR,
            Dir::N,
            "R",
            &c("G")
        )));
        assert!(!unsatisfiable_with_two(&touches("R", &c("R"))));
        assert!(!unsatisfiable_with_two(&Formula::not(atom(
            Kind::DR,
            Dir::N,
            "R",
            &c("R")
        ))));
    }

    #[test]
    fn median_and_summary() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
        assert!(median(&[]).is_nan());
    }
}
