//! `rccpack-bench priors` on a tiny configuration: a library
//! of 5 tasks, 3 held-out tasks, a true library of 10, no question loop.
//! The population is what the module says (class names vary, demonstration
//! counts, truth rules are candidates), the report is the same on one and
//! two threads, and on this seed the conditions order as they should: the
//! true frequencies keep recall at least as high as the uniform prior, no
//! prior loses a rare truth rule the uniform prior keeps, and the shuffled
//! control learns more spurious rules and recalls less than the real
//! library.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rccpack::infer::candidate_flags;
use rccpack::relations::Contact;
use rccpack_bench::priors::{
    draw_population_habits, library_kept, population, run, Condition, PriorsBenchConfig,
    PriorsBenchReport, CLASS_POOL,
};
use rccpack_bench::tasks::{Habit, WallSide};
use std::collections::BTreeSet;

fn tiny() -> PriorsBenchConfig {
    PriorsBenchConfig {
        library_sizes: vec![5],
        held_out: 3,
        true_library: 10,
        ask: false,
        ..PriorsBenchConfig::full(0)
    }
}

fn on_threads(cfg: &PriorsBenchConfig, threads: usize) -> PriorsBenchReport {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    pool.install(|| run(cfg, &|_| {}))
        .expect("the benchmark runs")
}

#[test]
fn tiny_run_is_deterministic_and_orders_the_conditions() {
    let cfg = tiny();
    let a = on_threads(&cfg, 1);
    let b = on_threads(&cfg, 2);
    assert_eq!(a, b, "same seed, same report, on 1 and 2 threads");
    let md = rccpack_bench::priors::table_markdown(&a);
    assert_eq!(md, rccpack_bench::priors::table_markdown(&b));
    assert!(md.contains("| library | condition | recall |"), "{md}");

    let row = |c: Condition| {
        a.rows
            .iter()
            .find(|r| r.condition == c)
            .unwrap_or_else(|| panic!("a {c:?} row"))
            .total
    };
    let (u, l, s, t) = (
        row(Condition::Uniform),
        row(Condition::Learned),
        row(Condition::Shuffled),
        row(Condition::True),
    );
    // Every condition scores the same truth rules.
    assert!(u.truth > 0);
    assert!([l.truth, s.truth, t.truth].iter().all(|&n| n == u.truth));
    // The uniform prior leaves nothing out.
    assert_eq!((u.left_out, u.truth_ruled_out), (0, 0));
    assert!(t.recalled >= u.recalled, "true {t:?} uniform {u:?}");
    assert!(l.rare_recalled >= u.rare_recalled, "{l:?} {u:?}");
    assert!(t.rare_recalled >= u.rare_recalled, "{t:?} {u:?}");
    assert!(s.spurious > l.spurious, "shuffled {s:?} learned {l:?}");
    assert!(s.recalled <= l.recalled, "shuffled {s:?} learned {l:?}");
    assert_eq!(a.targets.len(), 4, "no question loop, no question target");
}

#[test]
fn population_has_varying_names_demo_counts_and_truth_candidates() {
    let cfg = PriorsBenchConfig {
        library_sizes: vec![8],
        ..tiny()
    };
    let (held, library) = population(&cfg, &|_| {}).expect("a population");
    assert_eq!((held.len(), library.len()), (3, 8));
    let mut name_sets = BTreeSet::new();
    for t in held.iter().chain(&library) {
        let names: Vec<&str> = t.classes.iter().map(|c| c.class.as_str()).collect();
        assert!((2..=4).contains(&names.len()));
        assert!(names.iter().all(|n| CLASS_POOL.contains(n)));
        assert_eq!(names.iter().collect::<BTreeSet<_>>().len(), names.len());
        name_sets.insert(names.join(","));
        // Every truth rule holds in every demonstration shown.
        let flags = candidate_flags(&t.demos, &t.truth, Contact::Point).expect("flags");
        assert!(flags.iter().all(|&c| c), "task {}", t.stream);
    }
    assert!(name_sets.len() > 5, "class names vary: {name_sets:?}");
    assert!(held.iter().all(|t| t.demos.len() == 4));
    assert!(library.iter().all(|t| (3..=5).contains(&t.demos.len())));
    assert!(library.iter().any(|t| t.demos.len() != 4));
    // A library task keeps its truth.
    let kept = library_kept(&library[0], &cfg).expect("kept rules");
    assert_eq!(kept.rules.len(), library[0].truth.rules.len());
}

#[test]
fn habits_are_far_from_uniform() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (mut common, mut rare, mut all) = (0usize, 0usize, 0usize);
    for _ in 0..500 {
        for h in draw_population_habits(3, &mut rng) {
            all += 1;
            match h {
                Habit::Cluster | Habit::Band { wall: WallSide::S } => common += 1,
                Habit::Corner { .. } | Habit::Stack => rare += 1,
                _ => {}
            }
        }
    }
    // Cluster and band on the floor: about 55 % of classes; corners and
    // stacks: about 15 %.
    assert!(common * 2 > all, "{common} of {all}");
    assert!(rare * 5 < all, "{rare} of {all}");
}
