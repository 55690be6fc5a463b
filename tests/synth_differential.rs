//! Differential tests: the synthesis engine against the exhaustive solver
//! (`synth::brute_force`) on random tiny problems.
//!
//! Each case is drawn from a seeded generator (case `i` of a run uses
//! `ChaCha8Rng::seed_from_u64(BASE)` on stream `i`, so any failure is
//! reproducible alone; [`random_case`] prints nothing, [`Case::describe`]
//! gives the whole problem as text).
//!
//! **First edition** ([`Language::First`], docs/language.md#relations, docs/guide.md#synthesis): a space of at most
//! 60×60, grid 10, 2–3 unplaced blocks (10×10 or 20×20) of classes A/B,
//! optionally one fixed block F, and 1–4 random docs/guide.md#learning-shaped rules over
//! random subject/target (`*` included), each soft (weight 0.5, 1, 2 or 2.5)
//! or hard, in a random contact mode.
//!
//! **Second edition** ([`Language::Second`], docs/language.md): the same, plus
//! rectangles (10×20, 20×10), up to two fixed objects `f`, `g` (classes F or
//! W, any of the four sizes), now and then one or two already-placed movable
//! objects,
//! and rules drawn from random formulas over all sixteen relations with
//! every target quantifier (`every`, `some`, `no`, `at least K`,
//! `at most K` with K in 0..=4, around the object count), landmark targets
//! (`@f`, `@g` — fixed; `@a1` — movable, and `@f` when there is no `f`:
//! empty targets) and the docs/language.md#scene-rules example shapes, about 30 % of them
//! scene-level (`some`, `no`, `at least K`, `at most K` with K in 0..=3),
//! soft or hard.
//!
//! For each case the engine must agree with brute force: `infeasible` iff no
//! layout keeps the hard rules, and then its conflict is right (objects that
//! cannot fit even without rules, or a set of hard rules that brute force
//! confirms is infeasible on its own and feasible after dropping any one of
//! them); otherwise `optimal`, a solution that passes `verify_solution`, and
//! an evaluator numerator equal to the brute-force optimum (tolerance
//! `1e-9·(1+|x|)`), with the reported evaluation equal to the evaluator's.
//!
//! Default run: 600 + 300 first-edition cases (symmetry breaking and
//! redundant constraints on, then both off) and 4000 + 1500 second-edition
//! cases. `cargo test --release --test integration synth_differential:: -- --ignored` runs
//! 5000 + 2000 first-edition and 10000 + 4000 second-edition cases in
//! spaces up to 60×60.

use crate::support::cases::Case;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rccpack::eval::evaluate;
use rccpack::relations::{Contact, Dir, Kind, Quant, Relation};
use rccpack::resemblance::ResemblanceTarget;
use rccpack::rules::{Atom, Formula, Rule, RuleSet, Scope, Strength, Target};
use rccpack::scene::{Object, Scene, Space};
use rccpack::synth::brute_force::{self, approx_eq, BruteResult};
use rccpack::synth::model::{BoolDef, BuildOptions, Model};
use rccpack::synth::verify_solution;
use rccpack::synth::LnsOptions;
use rccpack::synth::{synthesize, Status, SynthOptions};
use rccpack_bench::pool::{among, atom, corner, touches};
use std::time::Duration;

use crate::support::formulas::{pick, q_atom, random_target, random_tree, Vocabulary};

/// Classes A (weight 3), B (2), F (1); `@a1` is never a fixed object.
const VOC: Vocabulary = Vocabulary {
    classes: ["A", "A", "A", "B", "B", "F"],
    absent: "a1",
};

const BASE_SEED: u64 = 0x5EED_D1FF;

/// Which rule language a run draws from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Language {
    /// docs/language.md#relations, docs/guide.md#synthesis only (the generator of the first differential runs,
    /// unchanged: the same stream gives the same case).
    First,
    /// Everything of docs/language.md too.
    Second,
    /// The second edition's cases with 3–4 movable blocks, most of class A,
    /// and one or two group statements (`group`, `row`, `column`, `block`,
    /// negated now and then, hard or soft) added after the other rules.
    Third,
    /// The second edition's cases with more oblong blocks (10×20, 20×10),
    /// each movable block `turnable` (a square one never turns): the
    /// engine's orientation choices against brute force's.
    Turning,
    /// The third edition's cases (group statements) with the turning
    /// edition's blocks, every movable one `turnable`: shapes whose sizes
    /// and block cell depend on orientations.
    TurningShapes,
}

/// What a run draws.
#[derive(Clone, Copy)]
struct Sizes {
    spaces: &'static [(i64, i64)],
    language: Language,
}

const SMALL: Sizes = Sizes {
    spaces: &[(30, 30), (40, 30), (40, 40), (50, 30)],
    language: Language::First,
};
const LARGE: Sizes = Sizes {
    spaces: &[(30, 30), (40, 40), (50, 30), (60, 40), (60, 60)],
    language: Language::First,
};
const SMALL2: Sizes = Sizes {
    language: Language::Second,
    ..SMALL
};
const LARGE2: Sizes = Sizes {
    language: Language::Second,
    ..LARGE
};
const SMALL_TURNING: Sizes = Sizes {
    language: Language::Turning,
    ..SMALL
};
const SMALL3: Sizes = Sizes {
    spaces: &[(30, 30), (40, 30), (30, 40), (40, 40), (50, 30)],
    language: Language::Third,
};
const SMALL3_TURNING: Sizes = Sizes {
    language: Language::TurningShapes,
    ..SMALL3
};

fn random_formula(rng: &mut ChaCha8Rng, subject: &str) -> Formula {
    let target = match rng.random_range(0..4) {
        0 => Target::Class("A".into()),
        1 => Target::Class("B".into()),
        2 => Target::Class("F".into()),
        _ => Target::Any,
    };
    let dir = pick(rng, &Dir::ALL);
    match rng.random_range(0..6) {
        0 => atom(Kind::DR, dir, subject, &target),
        1 => atom(Kind::EC, dir, subject, &target),
        2 => Formula::not(atom(Kind::DR, dir, subject, &target)),
        3 => touches(subject, &target),
        4 => among(subject, &target),
        _ => corner(subject),
    }
}

/// Second edition: a random formula: a random tree, a docs/language.md#scene-rules/docs/guide.md#learning
/// shape, or a first-edition shape.
fn random_formula2(rng: &mut ChaCha8Rng, subject: &str) -> Formula {
    let own = Target::Class(subject.into());
    let target = random_target(rng, &VOC);
    let dir = pick(rng, &Dir::ALL);
    let some = |kind, d, t: &Target| q_atom(kind, d, subject, Quant::Some, t);
    match rng.random_range(0..16) {
        0..=4 => {
            let depth = rng.random_range(1..=3);
            random_tree(rng, &VOC, subject, depth)
        }
        // "in one row with the other As" / "in one column"
        5 => {
            let (a, b) = pick(rng, &[(Dir::S, Dir::N), (Dir::W, Dir::E)]);
            Formula::And(vec![
                q_atom(Kind::AL, a, subject, Quant::Every, &own),
                q_atom(Kind::AL, b, subject, Quant::Every, &own),
            ])
        }
        // blue_row
        6 => Formula::And(vec![
            q_atom(Kind::AL, Dir::S, subject, Quant::Every, &own),
            Formula::Or(vec![
                some(Kind::FL, Dir::E, &own),
                some(Kind::FL, Dir::W, &own),
            ]),
        ]),
        // "every contact with a B is flush"
        7 => Formula::And(
            Dir::ALL
                .iter()
                .map(|&d| {
                    Formula::Or(vec![
                        Formula::not(some(Kind::EC, d, &target)),
                        some(Kind::FL, d, &target),
                    ])
                })
                .collect(),
        ),
        // "touches no B" (red_apart_green)
        8 => Formula::And(
            Dir::ALL
                .iter()
                .map(|&d| q_atom(Kind::EC, d, subject, Quant::No, &target))
                .collect(),
        ),
        // "touches some B flush"
        9 => Formula::Or(
            Dir::ALL
                .iter()
                .map(|&d| some(Kind::FL, d, &target))
                .collect(),
        ),
        // "has a flush neighbour east or west" / "north or south"
        10 => {
            let (a, b) = pick(rng, &[(Dir::E, Dir::W), (Dir::N, Dir::S)]);
            Formula::Or(vec![some(Kind::FL, a, &own), some(Kind::FL, b, &own)])
        }
        // touches(f) of docs/guide.md#learning
        11 => touches(subject, &Target::Landmark(pick(rng, &["f", "g"]).into())),
        12 => q_atom(Kind::FL, dir, subject, Quant::Some, &target),
        // A count over many objects: `REL(A, at least K *)`,
        // `REL(A, at most K *)`, K in 1..=3.
        13 | 14 => {
            let rel = pick(rng, &Relation::ALL);
            let k = rng.random_range(1..=3u32);
            let q = if rng.random_range(0..2) == 0 {
                Quant::AtLeast(k)
            } else {
                Quant::AtMost(k)
            };
            let t = if rng.random_range(0..3) == 0 {
                Target::Class(subject.into())
            } else {
                Target::Any
            };
            Formula::Atom(Atom::quantified(rel, subject, q, t))
        }
        _ => random_formula(rng, subject),
    }
}

const SIDES2: [(i64, i64); 4] = [(10, 10), (20, 10), (10, 20), (20, 20)];

fn random_case(index: u64, sizes: Sizes) -> Case {
    let mut rng = ChaCha8Rng::seed_from_u64(BASE_SEED);
    rng.set_stream(index);
    let second = sizes.language != Language::First;
    let third = matches!(sizes.language, Language::Third | Language::TurningShapes);
    let turning = matches!(sizes.language, Language::Turning | Language::TurningShapes);
    let (w, h) = pick(&mut rng, sizes.spaces);
    let mut objects: Vec<Object> = Vec::new();
    let n_fixed = if second {
        pick(&mut rng, &[0, 1, 1, 2])
    } else {
        usize::from(rng.random_range(0..2) == 0)
    };
    for id in ["f", "g"].into_iter().take(n_fixed) {
        let (fw, fh) = if second {
            pick(&mut rng, &SIDES2)
        } else {
            let side = pick(&mut rng, &[10, 20]);
            (side, side)
        };
        let class = if second {
            pick(&mut rng, &["F", "W"])
        } else {
            "F"
        };
        let x = 10 * rng.random_range(0..=(w - fw) / 10);
        let y = 10 * rng.random_range(0..=(h - fh) / 10);
        let o = Object::fixed_at(id, class, x, y, fw, fh);
        // Keep the scene valid: a second fixed object that overlaps the
        // first is dropped.
        if !crate::support::overlaps_any(&objects, &o) {
            objects.push(o);
        }
    }
    let movable = if third {
        rng.random_range(3..=4)
    } else if second && w * h <= 1200 && rng.random_range(0..4) == 0 {
        // Four blocks only in the smallest spaces (brute force grows as
        // the product of the domains).
        4
    } else {
        rng.random_range(2..=3)
    };
    for i in 0..movable {
        let class = if third {
            pick(&mut rng, &["A", "A", "A", "B"])
        } else {
            pick(&mut rng, &["A", "B"])
        };
        // Large blocks only now and then: they shrink the domains a lot.
        let (bw, bh) = if turning {
            match rng.random_range(0..8) {
                0 => (20, 20),
                1..=3 => (20, 10),
                4 | 5 => (10, 20),
                _ => (10, 10),
            }
        } else if second {
            match rng.random_range(0..8) {
                0 => (20, 20),
                1 => (20, 10),
                2 => (10, 20),
                _ => (10, 10),
            }
        } else {
            let side = if rng.random_range(0..4) == 0 { 20 } else { 10 };
            (side, side)
        };
        let mut o = Object::movable(&format!("{}{}", class.to_lowercase(), i), class, bw, bh);
        o.turnable = turning;
        objects.push(o);
    }
    // Already-placed movable objects (subjects and targets that do not
    // move, but no landmarks), where they fit: they make the counts of
    // `at least K` / `at most K` and of scene-level rules larger without
    // growing the search.
    let n_placed = if second {
        pick(&mut rng, &[0, 0, 1, 2])
    } else {
        0
    };
    for i in 0..n_placed {
        let class = pick(&mut rng, &["A", "B"]);
        let x = 10 * rng.random_range(0..w / 10);
        let y = 10 * rng.random_range(0..h / 10);
        let o = Object::placed(&format!("p{i}"), class, x, y, 10, 10);
        if !crate::support::overlaps_any(&objects, &o) {
            objects.push(o);
        }
    }
    let scene = crate::support::table(w, h, objects);
    let n_rules = if third {
        rng.random_range(0..=2)
    } else {
        rng.random_range(1..=4)
    };
    let mut rules: Vec<Rule> = (0..n_rules)
        .map(|i| {
            let subject = pick(&mut rng, &["A", "B"]);
            let strength = match rng.random_range(0..8) {
                0 | 1 => Strength::Hard,
                _ => Strength::Weight(pick(&mut rng, &[0.5, 1.0, 2.0, 2.5])),
            };
            if !second {
                return Rule::new(format!("r{i}"), random_formula(&mut rng, subject))
                    .with_strength(strength);
            }
            let scope = match rng.random_range(0..10) {
                0..=6 => Scope::Each,
                s => {
                    let k = rng.random_range(0..=3u32);
                    Scope::Scene(match (s, rng.random_range(0..4)) {
                        (7, _) => Quant::Some,
                        (8, 0) => Quant::No,
                        (8, _) => Quant::AtLeast(k),
                        _ => Quant::AtMost(k),
                    })
                }
            };
            Rule::new(format!("r{i}"), random_formula2(&mut rng, subject))
                .with_strength(strength)
                .with_scope(scope)
        })
        .collect();
    if turning && rng.random_range(0..2) == 0 {
        // An orientation statement ("every A lies turned", "no B lies
        // turned", or inside a formula), hard or soft.
        let subject = pick(&mut rng, &["A", "B"]);
        let turned = Formula::Turned(subject.into());
        let formula = match rng.random_range(0..4) {
            0 => turned,
            1 => Formula::not(turned),
            2 => Formula::Or(vec![turned, random_formula2(&mut rng, subject)]),
            _ => Formula::And(vec![
                Formula::not(turned),
                random_formula2(&mut rng, subject),
            ]),
        };
        let strength = if rng.random_range(0..3) == 0 {
            Strength::Hard
        } else {
            Strength::Weight(pick(&mut rng, &[0.5, 1.0, 2.5]))
        };
        rules.push(Rule::new("turn", formula).with_strength(strength));
    }
    if third {
        for i in 0..rng.random_range(1..=2) {
            let kind = pick(&mut rng, &rccpack::shapes::ShapeKind::ALL);
            let class = pick(&mut rng, &["A", "A", "B"]);
            let negated = rng.random_range(0..5) == 0;
            let strength = match rng.random_range(0..3) {
                0 => Strength::Hard,
                _ => Strength::Weight(pick(&mut rng, &[0.5, 1.0, 2.5])),
            };
            rules.push(
                Rule::group(
                    format!("g{i}"),
                    rccpack::rules::Shape::new(kind, class),
                    negated,
                )
                .with_strength(strength),
            );
        }
    }
    let contact = if rng.random_range(0..2) == 0 {
        Contact::Point
    } else {
        Contact::Edge
    };
    Case {
        index,
        scene,
        rules: RuleSet::new(rules),
        contact,
    }
}

/// Only the hard rules of `rules` named in `names`.
fn hard_subset(rules: &RuleSet, names: &[&str]) -> RuleSet {
    RuleSet::new(
        rules
            .rules
            .iter()
            .filter(|r| r.strength.is_hard() && names.contains(&r.name.as_str()))
            .cloned()
            .collect(),
    )
}

/// An infeasible case's conflict, checked by brute force: objects that
/// cannot fit cannot fit without any rule; otherwise the named hard rules
/// are infeasible on their own and each is needed.
fn check_conflict(case: &Case, c: &rccpack::synth::Conflict) -> Result<(), String> {
    let feasible = |rules: &RuleSet| -> Result<bool, String> {
        brute_force::solve(&case.scene, rules, case.contact)
            .map(|b| b.feasible)
            .map_err(|e| format!("brute force: {e}"))
    };
    if c.objects_cannot_fit {
        if feasible(&RuleSet::default())? {
            return Err("conflict says the objects cannot fit, but they fit".into());
        }
        return Ok(());
    }
    let names: Vec<&str> = c.hard_rules.iter().map(String::as_str).collect();
    if names.is_empty() {
        return Err("infeasible with an empty conflict".into());
    }
    if feasible(&hard_subset(&case.rules, &names))? {
        return Err(format!(
            "conflict {names:?} is feasible on its own (not a conflict)"
        ));
    }
    // With objects that turn too: the orientations are the model's
    // variables, so the conflict is one solve's, minimal.
    for i in 0..names.len() {
        let rest: Vec<&str> = names
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, &n)| n)
            .collect();
        if !feasible(&hard_subset(&case.rules, &rest))? {
            return Err(format!(
                "conflict {names:?} is not minimal: it stays infeasible without `{}`",
                names[i]
            ));
        }
    }
    Ok(())
}

/// Run the engine on `case` and compare with brute force.
fn check(case: &Case, symmetry_breaking: bool, redundant: bool) -> Result<BruteResult, String> {
    check_search(
        case,
        symmetry_breaking,
        redundant,
        SynthOptions::default().lns,
        Vec::new(),
    )
}

/// [`check`] with large-neighbourhood search forced on every problem,
/// however small: windows of one or two objects, so that the rounds (each
/// a sub-problem with the other objects placed) do the improving and the
/// main engine only proves.
fn check_lns(case: &Case, symmetry_breaking: bool, redundant: bool) -> Result<BruteResult, String> {
    // Tiny proof attempts: the main engine is stopped by its budget and
    // solved again many times per problem (the engine must stay usable
    // after every limit), with LNS phases in between.
    check_search(
        case,
        symmetry_breaking,
        redundant,
        Some(tiny_lns(3)),
        Vec::new(),
    )
}

/// LNS on every problem however small: windows of one or two objects,
/// proof attempts of `proof_nodes` nodes.
fn tiny_lns(proof_nodes: u64) -> LnsOptions {
    LnsOptions {
        min_objects: 0,
        window: 1,
        max_window: 2,
        patience: 3,
        round_nodes: 200,
        budget_nodes: 5_000,
        proof_nodes,
    }
}

/// Warm-start hints that are mostly wrong: every movable object of the
/// problem at a scrambled position (off the grid, outside the space,
/// overlapping, breaking hard rules), plus, when it exists, the brute-force
/// optimum with its objects shifted by one grid step.
fn bad_hints(case: &Case) -> Vec<Scene> {
    let mut scrambled = case.scene.clone();
    let sp = case.scene.space;
    for (i, o) in scrambled.objects.iter_mut().enumerate() {
        if o.fixed || o.is_placed() {
            continue;
        }
        let k = (i as i64 + 1) * (case.index as i64 % 7 + 3);
        o.x = Some(sp.x + (k * 13) % (sp.width + 20) - 10);
        o.y = Some(sp.y + (k * 7) % (sp.height + 20) - 10);
    }
    let mut out = vec![scrambled];
    if let Ok(bf) = brute_force::solve(&case.scene, &case.rules, case.contact) {
        if let Some(mut best) = bf.best {
            for (o, p) in best.objects.iter_mut().zip(&case.scene.objects) {
                if !p.is_placed() {
                    o.x = o.x.map(|x| x + case.scene.grid);
                }
            }
            out.push(best);
        }
    }
    out
}

/// With warm-start hints (wrong ones and a near-optimal one) and LNS with
/// tiny proof attempts: the same optimum as brute force.
fn check_warm(
    case: &Case,
    symmetry_breaking: bool,
    redundant: bool,
) -> Result<BruteResult, String> {
    check_search(
        case,
        symmetry_breaking,
        redundant,
        Some(tiny_lns(5)),
        bad_hints(case),
    )
}

fn check_search(
    case: &Case,
    symmetry_breaking: bool,
    redundant: bool,
    lns: Option<LnsOptions>,
    warm_start: Vec<Scene>,
) -> Result<BruteResult, String> {
    let bf = brute_force::solve(&case.scene, &case.rules, case.contact)
        .map_err(|e| format!("brute force: {e}"))?;
    let opts = SynthOptions {
        contact: case.contact,
        stop: rccpack::stop::Stop::after(Duration::from_secs(20)),
        symmetry_breaking,
        redundant,
        lns,
        warm_start,
        ..SynthOptions::default()
    };
    let r =
        synthesize(&case.scene, &case.rules, &opts).map_err(|e| format!("engine error: {e}"))?;
    if !bf.feasible {
        if r.status != Status::Infeasible {
            return Err(format!(
                "brute force: infeasible ({} layouts checked); engine: {:?}",
                bf.layouts_checked, r.status
            ));
        }
        let c = r
            .conflict
            .as_ref()
            .ok_or("engine: infeasible without a conflict")?;
        check_conflict(case, c).map_err(|e| format!("conflict: {e}"))?;
        return Ok(bf);
    }
    if r.status != Status::Optimal {
        return Err(format!(
            "brute force: feasible, optimum {}; engine: {:?}",
            bf.best_numerator, r.status
        ));
    }
    let sol = r.scene.as_ref().ok_or("engine: optimal without a scene")?;
    verify_solution(&case.scene, sol, &case.rules, case.contact)
        .map_err(|e| format!("engine solution fails verify_solution: {e}"))?;
    let ev = evaluate(sol, &case.rules, case.contact);
    if !approx_eq(ev.satisfied_weight, bf.best_numerator) {
        return Err(format!(
            "numerator: engine {} (evaluator), brute force {}\nengine solution:\n{}brute-force optimum:\n{}",
            ev.satisfied_weight,
            bf.best_numerator,
            sol.to_json(),
            bf.best.as_ref().map(Scene::to_json).unwrap_or_default()
        ));
    }
    let rev = r
        .evaluation
        .as_ref()
        .ok_or("engine: optimal without an evaluation")?;
    if rev != &ev {
        return Err(format!(
            "reported evaluation {rev:?} differs from the evaluator's {ev:?}"
        ));
    }
    for (rule, rep) in case.rules.rules.iter().zip(&ev.rules) {
        if rule.is_group() {
            if rep.subjects != 1 || rep.group.is_none() || rep.scene.is_some() {
                return Err(format!("group rule `{}` reported as {rep:?}", rule.name));
            }
        } else if rule.scope.is_scene() && (rep.subjects != 1 || rep.scene.is_none()) {
            return Err(format!(
                "scene-level rule `{}` reported with {} subjects",
                rule.name, rep.subjects
            ));
        }
    }
    Ok(bf)
}

/// Random like-scenes for `case` (docs/guide.md#layouts-like-the-demonstrations): one to four scenes, each
/// holding one movable object of a class and size of the problem (or, now
/// and then, of a size it lacks) at any integer position inside the space,
/// on the grid or off it (so rounding up matters).
fn random_like(case: &Case) -> Vec<Scene> {
    let mut rng = ChaCha8Rng::seed_from_u64(BASE_SEED ^ 0x11ce);
    rng.set_stream(case.index);
    let movable: Vec<&Object> = case.scene.objects.iter().filter(|o| !o.fixed).collect();
    let sp = case.scene.space;
    let n = rng.random_range(1..=4);
    (0..n)
        .map(|_| {
            let o = pick(&mut rng, &movable);
            let (w, h) = if rng.random_range(0..6) == 0 {
                (o.width + 10, o.height)
            } else {
                (o.width, o.height)
            };
            let x = sp.x + rng.random_range(0..=(sp.width - w).max(0));
            let y = sp.y + rng.random_range(0..=(sp.height - h).max(0));
            Scene {
                space: sp,
                grid: case.scene.grid,
                objects: vec![Object::placed("l", &o.class, x, y, w, h)],
            }
        })
        .collect()
}

/// The lexicographic optimum (numerator, then resemblance cost) of the
/// engine equals brute force's; the score with `--like` equals the score
/// without; the reported cost is the resemblance function's.
fn check_like(
    case: &Case,
    symmetry_breaking: bool,
    redundant: bool,
) -> Result<BruteResult, String> {
    check_like_with(case, symmetry_breaking, redundant, false)
}

/// [`check_like`] with the like-scenes also as warm-start hints (what
/// `synth --like` does) and LNS forced on.
fn check_like_warm(
    case: &Case,
    symmetry_breaking: bool,
    redundant: bool,
) -> Result<BruteResult, String> {
    check_like_with(case, symmetry_breaking, redundant, true)
}

fn check_like_with(
    case: &Case,
    symmetry_breaking: bool,
    redundant: bool,
    warm: bool,
) -> Result<BruteResult, String> {
    let scenes = random_like(case);
    let like = ResemblanceTarget::new(&scenes);
    let bf = brute_force::solve_like(
        &case.scene,
        &case.rules,
        case.contact,
        &like,
        brute_force::MAX_LAYOUTS,
    )
    .map_err(|e| format!("brute force: {e}"))?;
    let opts = SynthOptions {
        contact: case.contact,
        stop: rccpack::stop::Stop::after(Duration::from_secs(20)),
        symmetry_breaking,
        redundant,
        warm_start: if warm { scenes } else { Vec::new() },
        lns: if warm {
            Some(tiny_lns(5))
        } else {
            SynthOptions::default().lns
        },
        ..SynthOptions::default()
    };
    let plain =
        synthesize(&case.scene, &case.rules, &opts).map_err(|e| format!("engine error: {e}"))?;
    let r = synthesize(
        &case.scene,
        &case.rules,
        &SynthOptions {
            like: Some(like.clone()),
            ..opts
        },
    )
    .map_err(|e| format!("engine error with like: {e}"))?;
    if !bf.feasible {
        return match (r.status, plain.status) {
            (Status::Infeasible, Status::Infeasible) => Ok(bf),
            s => Err(format!(
                "brute force: infeasible; engine (like, plain): {s:?}"
            )),
        };
    }
    if r.status != Status::Optimal || plain.status != Status::Optimal {
        return Err(format!(
            "engine (like, plain): {:?}, {:?}",
            r.status, plain.status
        ));
    }
    let sol = r.scene.as_ref().ok_or("engine: optimal without a scene")?;
    verify_solution(&case.scene, sol, &case.rules, case.contact)
        .map_err(|e| format!("engine solution fails verify_solution: {e}"))?;
    let num = evaluate(sol, &case.rules, case.contact).satisfied_weight;
    let num_plain = plain
        .evaluation
        .as_ref()
        .map(|e| e.satisfied_weight)
        .unwrap_or(f64::NAN);
    if !approx_eq(num, bf.best_numerator) || !approx_eq(num, num_plain) {
        return Err(format!(
            "numerator: engine with like {num}, without {num_plain}, brute force {}",
            bf.best_numerator
        ));
    }
    let res = r.resemblance.ok_or("engine: no resemblance with like")?;
    let cost = like.cost(&case.scene, sol);
    if res.cost != cost || cost != bf.best_cost || !res.proven || res.bound != cost {
        return Err(format!(
            "cost: engine reports {} (proven {}, bound {}), resemblance function {cost}, brute force {}\nengine:\n{}brute force:\n{}",
            res.cost,
            res.proven,
            res.bound,
            bf.best_cost,
            sol.to_json(),
            bf.best.as_ref().map(Scene::to_json).unwrap_or_default()
        ));
    }
    Ok(bf)
}

struct Tally {
    cases: usize,
    infeasible: usize,
    failures: Vec<String>,
}

fn run(
    range: std::ops::Range<u64>,
    sizes: Sizes,
    symmetry_breaking: bool,
    redundant: bool,
) -> Tally {
    run_with(range, sizes, symmetry_breaking, redundant, check)
}

type Checker = fn(&Case, bool, bool) -> Result<BruteResult, String>;

fn run_with(
    range: std::ops::Range<u64>,
    sizes: Sizes,
    symmetry_breaking: bool,
    redundant: bool,
    check: Checker,
) -> Tally {
    use rayon::prelude::*;
    let results: Vec<(u64, Result<BruteResult, String>)> = range
        .into_par_iter()
        .map(|i| {
            let case = random_case(i, sizes);
            let r = std::panic::catch_unwind(|| check(&case, symmetry_breaking, redundant))
                .unwrap_or_else(|p| {
                    let msg = p
                        .downcast_ref::<String>()
                        .cloned()
                        .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                        .unwrap_or_default();
                    Err(format!("panic: {msg}"))
                })
                .map_err(|e| {
                    let bf = brute_force::solve(&case.scene, &case.rules, case.contact)
                        .map(|b| b.feasible)
                        .ok();
                    format!(
                        "{e} [brute force feasible: {bf:?}; rule classes all in scene: {}]\n{}",
                        rccpack::rules::check_classes(&case.rules, &case.scene).is_ok(),
                        case.describe()
                    )
                });
            (i, r)
        })
        .collect();
    let mut t = Tally {
        cases: results.len(),
        infeasible: 0,
        failures: Vec::new(),
    };
    let mut kinds: std::collections::BTreeMap<String, usize> = Default::default();
    for (_, r) in results {
        match r {
            Ok(bf) => t.infeasible += usize::from(!bf.feasible),
            Err(e) => {
                let l = e.lines().next().unwrap_or("");
                let kind: String = match l.find(" [") {
                    Some(i) => format!("{}…{}", &l[..i.min(60)], &l[i..]),
                    None => l.chars().take(80).collect(),
                };
                *kinds.entry(kind).or_default() += 1;
                t.failures.push(e)
            }
        }
    }
    for (k, n) in &kinds {
        eprintln!("  {n:>5} × {k}");
    }
    eprintln!(
        "differential (symmetry_breaking={symmetry_breaking}, redundant={redundant}): {} cases, {} infeasible, {} passed, {} failed",
        t.cases,
        t.infeasible,
        t.cases - t.failures.len(),
        t.failures.len()
    );
    t
}

fn assert_clean(t: Tally) {
    if !t.failures.is_empty() {
        let shown: Vec<&String> = t.failures.iter().take(3).collect();
        panic!(
            "{} of {} cases disagree; first ones:\n{}",
            t.failures.len(),
            t.cases,
            shown
                .iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join("\n----\n")
        );
    }
}

#[test]
fn generator_is_deterministic_and_varied() {
    let a: Vec<Case> = (0..200).map(|i| random_case(i, SMALL)).collect();
    let b: Vec<Case> = (0..200).map(|i| random_case(i, SMALL)).collect();
    let mut hard = 0;
    let mut fixed = 0;
    let mut edge = 0;
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(x.scene, y.scene);
        assert!(x.rules.same_rules(&y.rules));
        x.scene.validate().unwrap();
        hard += x.rules.rules.iter().any(|r| r.strength.is_hard()) as usize;
        fixed += x.scene.objects.iter().any(|o| o.fixed) as usize;
        edge += (x.contact == Contact::Edge) as usize;
    }
    assert!(hard > 20 && hard < 180, "{hard}");
    assert!(fixed > 50 && fixed < 150, "{fixed}");
    assert!(edge > 50 && edge < 150, "{edge}");
}

/// Brute force on its own: the optimum it reports is achieved by the scene
/// it returns, and that scene is a valid solution.
#[test]
fn brute_force_best_is_consistent() {
    let mut feasible = 0;
    for i in 0..150 {
        let case = random_case(i, SMALL);
        let bf = brute_force::solve(&case.scene, &case.rules, case.contact).unwrap();
        assert!(bf.layouts_feasible <= bf.layouts_checked);
        if let Some(best) = &bf.best {
            feasible += 1;
            verify_solution(&case.scene, best, &case.rules, case.contact)
                .unwrap_or_else(|e| panic!("{e}\n{}", case.describe()));
            let ev = evaluate(best, &case.rules, case.contact);
            assert!(ev.hard_ok());
            assert!(approx_eq(ev.satisfied_weight, bf.best_numerator));
        } else {
            assert!(!bf.feasible);
        }
    }
    assert!(feasible > 50, "{feasible}");
}

/// The smallest disagreements found by the differential runs (engine at
/// synth c839964): problems that are infeasible at the root made the engine
/// panic inside Pumpkin ("Variables cannot be created in an inconsistent
/// state") instead of answering `infeasible`.
#[test]
fn infeasible_at_root_minimal_reproducers() {
    let block = |id: &str, class: &str, side: i64| Object::movable(id, class, side, side);
    let space = Space {
        x: 0,
        y: 0,
        width: 30,
        height: 30,
    };
    // Two 20×20 blocks cannot both fit in a 30×30 space; no rules.
    let no_fit = Scene {
        space,
        grid: 10,
        objects: vec![block("a", "A", 20), block("b", "A", 20)],
    };
    // One block; the hard rule asks it to touch the west side of another A.
    let lonely = Scene {
        space,
        grid: 10,
        objects: vec![block("a", "A", 10)],
    };
    let hard_ec_w = RuleSet::new(vec![Rule::new(
        "r1",
        atom(Kind::EC, Dir::W, "A", &Target::Class("A".into())),
    )
    .with_strength(Strength::Hard)]);
    for (scene, rules) in [(no_fit, RuleSet::default()), (lonely, hard_ec_w)] {
        let bf = brute_force::solve(&scene, &rules, Contact::Point).unwrap();
        assert!(!bf.feasible);
        let r = std::panic::catch_unwind(|| synthesize(&scene, &rules, &SynthOptions::default()));
        match r {
            Ok(Ok(res)) => assert_eq!(res.status, Status::Infeasible),
            Ok(Err(e)) => panic!("engine error: {e}"),
            Err(_) => panic!(
                "engine panicked on an infeasible problem:\n{}",
                scene.to_json()
            ),
        }
    }
}

/// What the second-edition generator covers, counted over the cases of the
/// default run: every relation, every atom quantifier (and `K` from 0 to 4),
/// landmark targets on fixed and on non-fixed/missing objects, scene-level
/// rules with every subject quantifier, soft and hard, both contact modes,
/// rectangles, two fixed objects, already-placed movable objects, and
/// models with reified counts.
#[test]
fn second_edition_generator_covers_the_language() {
    use std::collections::BTreeSet;
    let mut rels = BTreeSet::new();
    let mut quants = BTreeSet::new();
    let mut ks = BTreeSet::new();
    let mut scene_quants = BTreeSet::new();
    let (mut lm_fixed, mut lm_empty, mut scene_soft, mut scene_hard) = (0, 0, 0, 0);
    let (mut edge, mut hard, mut two_fixed, mut placed, mut rect) = (0, 0, 0, 0, 0);
    // Cases whose model has a reified count (`at least K` that does not
    // fold to AND/OR/constants): the engine's `AtLeast` encoding.
    let mut counted = 0;
    let n = 1500;
    for i in 0..n {
        let c = random_case(i, SMALL2);
        let c2 = random_case(i, SMALL2);
        assert_eq!(c.scene, c2.scene);
        assert!(c.rules.same_rules(&c2.rules));
        c.scene.validate().unwrap();
        edge += usize::from(c.contact == Contact::Edge);
        hard += usize::from(c.rules.rules.iter().any(|r| r.strength.is_hard()));
        two_fixed += usize::from(c.scene.objects.iter().filter(|o| o.fixed).count() == 2);
        placed += usize::from(c.scene.objects.iter().any(|o| !o.fixed && o.is_placed()));
        rect += usize::from(c.scene.objects.iter().any(|o| o.width != o.height));
        let m = Model::build(
            &c.scene,
            &c.rules,
            BuildOptions {
                contact: c.contact,
                rules: true,
                symmetry_breaking: true,
                redundant: true,
                tuning: Default::default(),
            },
        );
        counted += usize::from(m.bools.iter().any(|b| matches!(b, BoolDef::AtLeast { .. })));
        for r in &c.rules.rules {
            if let Scope::Scene(q) = r.scope {
                scene_quants.insert(q);
                if r.strength.is_hard() {
                    scene_hard += 1;
                } else {
                    scene_soft += 1;
                }
            }
            for a in r.formula.atoms() {
                rels.insert(a.rel);
                quants.insert(match a.quant {
                    Quant::AtLeast(_) => Quant::AtLeast(0),
                    Quant::AtMost(_) => Quant::AtMost(0),
                    q => q,
                });
                if let Quant::AtLeast(k) | Quant::AtMost(k) = a.quant {
                    ks.insert(k);
                }
                if let Target::Landmark(id) = &a.target {
                    let fixed = c.scene.objects.iter().any(|o| o.fixed && &o.id == id);
                    if fixed {
                        lm_fixed += 1;
                    } else {
                        lm_empty += 1;
                    }
                }
            }
        }
    }
    eprintln!("cases with a reified count: {counted} of {n}");
    assert!(
        counted >= 80,
        "only {counted} cases exercise the engine's AtLeast"
    );
    assert_eq!(rels.len(), 16, "{rels:?}");
    assert_eq!(quants.len(), 5);
    assert_eq!(ks, (0..=4).collect());
    assert!(scene_quants.contains(&Quant::Some) && scene_quants.contains(&Quant::No));
    for k in 0..=3 {
        assert!(scene_quants.contains(&Quant::AtLeast(k)), "at least {k}");
        assert!(scene_quants.contains(&Quant::AtMost(k)), "at most {k}");
    }
    assert!(lm_fixed > 300 && lm_empty > 100, "{lm_fixed} {lm_empty}");
    assert!(
        scene_soft > 300 && scene_hard > 100,
        "{scene_soft} {scene_hard}"
    );
    assert!(edge > 500 && edge < 1000, "{edge}");
    assert!(hard > 300 && hard < 1200, "{hard}");
    assert!(
        two_fixed > 200 && placed > 100 && rect > 300,
        "{two_fixed} {placed} {rect}"
    );
}

#[test]
fn engine_matches_brute_force() {
    assert_clean(run(0..600, SMALL, true, true));
}

/// Large-neighbourhood search on (forced onto tiny problems) and off: both
/// reach brute force's optimum, first- and second-edition rules.
#[test]
fn engine_matches_brute_force_with_lns_forced_on() {
    assert_clean(run_with(0..400, SMALL, true, true, check_lns));
    assert_clean(run_with(0..600, SMALL2, true, true, check_lns));
    assert_clean(run_with(0..200, SMALL2, false, false, check_lns));
}

#[test]
fn engine_matches_brute_force_without_symmetry_breaking_or_redundancy() {
    assert_clean(run(0..300, SMALL, false, false));
}

#[test]
#[ignore = "slow: run with `cargo test --release --test integration synth_differential:: -- --ignored`"]
fn engine_matches_brute_force_large() {
    assert_clean(run(100_000..105_000, LARGE, true, true));
}

#[test]
#[ignore = "slow: run with `cargo test --release --test integration synth_differential:: -- --ignored`"]
fn engine_matches_brute_force_large_plain() {
    assert_clean(run(200_000..202_000, LARGE, false, false));
}

#[test]
fn engine_matches_brute_force_with_warm_starts() {
    // Wrong and near-optimal hints never change the optimum or the
    // conflict; first- and second-edition rules, both symmetry settings.
    assert_clean(run_with(0..400, SMALL, true, true, check_warm));
    assert_clean(run_with(0..600, SMALL2, true, true, check_warm));
    assert_clean(run_with(0..200, SMALL2, false, false, check_warm));
}

#[test]
fn engine_matches_brute_force_with_like_scenes_as_warm_starts() {
    // What `synth --like` does: the like-scenes are also the warm start;
    // (numerator, cost) stay brute force's lexicographic optimum.
    let t = run_with(0..600, SMALL2, true, true, check_like_warm);
    assert!(t.infeasible > 50, "{}", t.infeasible);
    assert_clean(t);
}

#[test]
fn engine_matches_brute_force_lexicographically_with_like_scenes() {
    let t = run_with(0..600, SMALL2, true, true, check_like);
    assert!(t.infeasible > 50, "{}", t.infeasible);
    assert_clean(t);
}

#[test]
fn engine_matches_brute_force_with_like_scenes_without_symmetry_breaking_or_redundancy() {
    assert_clean(run_with(600..900, SMALL2, false, false, check_like));
}

#[test]
fn engine_matches_brute_force_with_like_scenes_first_edition_rules() {
    assert_clean(run_with(0..300, SMALL, true, true, check_like));
}

#[test]
#[ignore = "slow: run with `cargo test --release --test integration synth_differential:: -- --ignored`"]
fn engine_matches_brute_force_with_like_scenes_large() {
    assert_clean(run_with(500_000..503_000, LARGE2, true, true, check_like));
}

/// Group statements (third edition): the circuit of `synth::model::shapes`
/// against the evaluator's `shapes::check`, through brute force.
#[test]
fn engine_matches_brute_force_group_shapes() {
    let t = run(0..1500, SMALL3, true, true);
    assert!(t.infeasible > 30 && t.infeasible < 1000, "{}", t.infeasible);
    assert_clean(t);
}

#[test]
fn engine_matches_brute_force_group_shapes_without_symmetry_breaking_or_redundancy() {
    assert_clean(run(0..600, SMALL3, false, false));
}

#[test]
fn engine_matches_brute_force_group_shapes_with_lns_and_warm_starts() {
    assert_clean(run_with(700_000..700_400, SMALL3, true, true, check_warm));
}

#[test]
fn engine_matches_brute_force_with_objects_that_turn() {
    let t = run(900_000..900_600, SMALL_TURNING, true, true);
    // Infeasible problems (their conflicts checked) and feasible ones.
    assert!(t.infeasible > 30 && t.infeasible < 400, "{}", t.infeasible);
    assert_clean(t);
}

#[test]
fn engine_matches_brute_force_with_objects_that_turn_without_symmetry_breaking_or_redundancy() {
    assert_clean(run(900_000..900_200, SMALL_TURNING, false, false));
}

#[test]
fn engine_matches_brute_force_with_objects_that_turn_lns_and_warm_starts() {
    assert_clean(run_with(
        910_000..910_200,
        SMALL_TURNING,
        true,
        true,
        check_warm,
    ));
}

#[test]
fn engine_matches_brute_force_group_shapes_with_objects_that_turn() {
    assert_clean(run(940_000..940_300, SMALL3_TURNING, true, true));
}

#[test]
fn engine_matches_brute_force_with_objects_that_turn_and_lns_forced_on() {
    assert_clean(run_with(
        930_000..930_200,
        SMALL_TURNING,
        true,
        true,
        check_lns,
    ));
}

#[test]
fn engine_matches_brute_force_lexicographically_with_objects_that_turn_and_like_scenes() {
    assert_clean(run_with(
        920_000..920_200,
        SMALL_TURNING,
        true,
        true,
        check_like,
    ));
}

#[test]
fn engine_matches_brute_force_second_edition() {
    let t = run(0..4000, SMALL2, true, true);
    // The run must include infeasible problems (checked conflicts) and
    // feasible ones.
    assert!(
        t.infeasible > 400 && t.infeasible < 2500,
        "{}",
        t.infeasible
    );
    assert_clean(t);
}

#[test]
fn engine_matches_brute_force_second_edition_without_symmetry_breaking_or_redundancy() {
    assert_clean(run(0..1500, SMALL2, false, false));
}

#[test]
#[ignore = "slow: run with `cargo test --release --test integration synth_differential:: -- --ignored`"]
fn engine_matches_brute_force_second_edition_large() {
    assert_clean(run(300_000..310_000, LARGE2, true, true));
}

#[test]
#[ignore = "slow: run with `cargo test --release --test integration synth_differential:: -- --ignored`"]
fn engine_matches_brute_force_second_edition_large_plain() {
    assert_clean(run(400_000..404_000, LARGE2, false, false));
}
