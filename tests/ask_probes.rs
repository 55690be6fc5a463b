//! Probes (docs/guide.md#questions) against exhaustive enumeration on random tiny problems.
//!
//! A case (seeded: case `i` is `ChaCha8Rng::seed_from_u64(BASE)` on stream
//! `i`) is a space of at most 40×40 on grid 10 with 2–4 unplaced blocks of
//! classes A/B/C (2–3 classes), maybe one or two fixed objects (`f`, `g`,
//! class F or W), and a "held" set of 2–5 rules drawn like the second-edition
//! generator of `tests/synth_differential.rs` (per-object and scene-level
//! rules, quantified atoms, landmarks, `*` targets), in a random contact mode.
//!
//! Every complete grid layout of the case is enumerated here (the test's own
//! loop, independent of the engine and of `ask::negation`) and the evaluator
//! says which rules each layout breaks. Then for every rule `k`:
//!
//! - `Probe(p)`: `p.scene` is a complete valid layout of the problem, breaks
//!   rule `k`, keeps every other rule, `p.broken` is the evaluator's list of
//!   violators, and (per-object rule) it breaks `k` for as many subjects as
//!   any such layout does (the probe's soft objective, solved exactly);
//! - `Implied { by }`: no enumerated layout breaks `k` and keeps the rest;
//!   when `by` is given (explained runs) no layout breaks `k` and keeps the
//!   rules of `by` alone;
//! - `Unknown` never happens (no limit on tiny problems).

use crate::support::cases::{rule_text, Case};
use crate::support::overlaps_any;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rccpack::ask::probe_rules;
use rccpack::ask::{find_probe, negation, ProbeOptions, ProbeOutcome};
use rccpack::eval::{evaluate, Evaluator};
use rccpack::relations::{Contact, Dir, Kind, Quant, Relation, MAX_COUNT};
use rccpack::resemblance::ResemblanceTarget;
use rccpack::rules::{Atom, Formula, Rule, RuleSet, Scope, Target};
use rccpack::scene::{Object, Rect, Scene};
use rccpack::synth::brute_force::grid_positions;
use rccpack::synth::verify_solution;
use rccpack_bench::pool::{among, atom, corner, touches};

use crate::support::formulas::{pick, q_atom, random_target, random_tree, Vocabulary};

/// Classes A, B, C (twice as likely), F, W; `@a0` is never a fixed object.
const VOC: Vocabulary = Vocabulary {
    classes: ["A", "B", "C", "F", "W", "C"],
    absent: "a0",
};

const BASE_SEED: u64 = 0xA5C0_9B0E;
/// Cases whose product of domain sizes exceeds this are made smaller.
const MAX_LAYOUTS: u64 = 2500;

// ---- the generator (after tests/synth_differential.rs, with a class C) ----

fn class_target(rng: &mut ChaCha8Rng) -> Target {
    Target::Class(pick(rng, &["A", "B", "C", "F", "W"]).into())
}

fn random_formula(rng: &mut ChaCha8Rng, subject: &str) -> Formula {
    let own = Target::Class(subject.into());
    let target = random_target(rng, &VOC);
    let dir = pick(rng, &Dir::ALL);
    let some = |kind, d, t: &Target| q_atom(kind, d, subject, Quant::Some, t);
    match rng.random_range(0..16) {
        0..=3 => {
            let depth = rng.random_range(1..=3);
            random_tree(rng, &VOC, subject, depth)
        }
        4 => {
            let (a, b) = pick(rng, &[(Dir::S, Dir::N), (Dir::W, Dir::E)]);
            Formula::And(vec![
                q_atom(Kind::AL, a, subject, Quant::Every, &own),
                q_atom(Kind::AL, b, subject, Quant::Every, &own),
            ])
        }
        5 => Formula::And(
            Dir::ALL
                .iter()
                .map(|&d| q_atom(Kind::EC, d, subject, Quant::No, &target))
                .collect(),
        ),
        6 => Formula::Or(vec![
            some(Kind::FL, Dir::E, &own),
            some(Kind::FL, Dir::W, &own),
        ]),
        7 => touches(subject, &Target::Landmark(pick(rng, &["f", "g"]).into())),
        8 => touches(subject, &own),
        9 => touches(subject, &Target::Any),
        10 => among(subject, &class_target(rng)),
        11 => corner(subject),
        12 => atom(pick(rng, &[Kind::DR, Kind::EC]), dir, subject, &target),
        13 => Formula::not(atom(Kind::DR, dir, subject, &target)),
        _ => {
            let rel = pick(rng, &Relation::ALL);
            let k = rng.random_range(1..=3u32);
            let q = if rng.random_range(0..2) == 0 {
                Quant::AtLeast(k)
            } else {
                Quant::AtMost(k)
            };
            let t = if rng.random_range(0..3) == 0 {
                own
            } else {
                Target::Any
            };
            Formula::Atom(Atom::quantified(rel, subject, q, t))
        }
    }
}

fn random_scope(rng: &mut ChaCha8Rng) -> Scope {
    if rng.random_range(0..10) < 6 {
        return Scope::Each;
    }
    let k = rng.random_range(0..=3u32);
    Scope::Scene(match rng.random_range(0..12) {
        0..=2 => Quant::Some,
        3..=4 => Quant::No,
        5..=7 => Quant::AtLeast(k),
        8..=10 => Quant::AtMost(k),
        _ => pick(
            rng,
            &[Quant::AtLeast(0), Quant::AtMost(MAX_COUNT), Quant::Every],
        ),
    })
}

/// Product of the domain sizes of the unplaced objects.
fn layouts(scene: &Scene) -> u64 {
    domains(scene)
        .iter()
        .fold(1u64, |a, (_, d)| a.saturating_mul(d.len() as u64))
}

fn random_case(index: u64) -> Case {
    let mut rng = ChaCha8Rng::seed_from_u64(BASE_SEED);
    rng.set_stream(index);
    let (w, h) = pick(
        &mut rng,
        &[(20, 20), (30, 20), (30, 30), (40, 30), (40, 40)],
    );
    let mut objects: Vec<Object> = Vec::new();
    let n_fixed = pick(&mut rng, &[0, 1, 1, 2]);
    for id in ["f", "g"].into_iter().take(n_fixed) {
        let (fw, fh) = pick(&mut rng, &[(10, 10), (20, 10), (10, 20), (10, 30)]);
        let (fw, fh) = (fw.min(w), fh.min(h));
        let class = pick(&mut rng, &["F", "W"]);
        let x = 10 * rng.random_range(0..=(w - fw) / 10);
        let y = 10 * rng.random_range(0..=(h - fh) / 10);
        let o = Object::fixed_at(id, class, x, y, fw, fh);
        if !overlaps_any(&objects, &o) {
            objects.push(o);
        }
    }
    let classes: &[&str] = if rng.random_range(0..3) == 0 {
        &["A", "B", "C"]
    } else {
        &["A", "B"]
    };
    let movable = rng.random_range(2..=4);
    for i in 0..movable {
        let class = pick(&mut rng, classes);
        let (bw, bh) = match rng.random_range(0..8) {
            0 => (20, 10),
            1 => (10, 20),
            _ => (10, 10),
        };
        objects.push(Object::movable(
            &format!("{}{}", class.to_lowercase(), i),
            class,
            bw,
            bh,
        ));
    }
    // Now and then an already-placed movable object.
    if rng.random_range(0..5) == 0 {
        let class = pick(&mut rng, classes);
        let o = Object::placed(
            "p0",
            class,
            10 * rng.random_range(0..w / 10),
            10 * rng.random_range(0..h / 10),
            10,
            10,
        );
        if !overlaps_any(&objects, &o) {
            objects.push(o);
        }
    }
    let mut scene = crate::support::table(w, h, objects);
    // Keep the enumeration small: drop unplaced blocks (never below two).
    while layouts(&scene) > MAX_LAYOUTS {
        let unplaced = scene.objects.iter().filter(|o| !o.is_placed()).count();
        if unplaced <= 2 {
            break;
        }
        let last = scene
            .objects
            .iter()
            .rposition(|o| !o.is_placed())
            .expect("an unplaced object");
        scene.objects.remove(last);
    }
    let n_rules = rng.random_range(2..=5);
    let contact = if rng.random_range(0..2) == 0 {
        Contact::Point
    } else {
        Contact::Edge
    };
    let mut case = Case {
        index,
        scene,
        rules: RuleSet::default(),
        contact,
    };
    // Two cases in three: "habits" of a random layout (rules drawn until
    // `n_rules` of them hold on it), so the set is satisfiable and most
    // rules have probes; else rules drawn freely (often jointly
    // infeasible: everything is implied).
    // A habit must also be broken by one of a few other random layouts
    // (not true of every layout).
    let habit_of = if index % 3 != 0 {
        random_layout(&case, &mut rng)
    } else {
        None
    };
    let others: Vec<Scene> = (0..4)
        .filter_map(|_| random_layout(&case, &mut rng))
        .collect();
    let mut rules = Vec::new();
    let mut tries = 0;
    while rules.len() < n_rules && tries < 200 {
        tries += 1;
        let subject = pick(&mut rng, classes);
        let scope = random_scope(&mut rng);
        let r = Rule::new(
            format!("r{}", rules.len()),
            random_formula(&mut rng, subject),
        )
        .with_scope(scope);
        if let Some(l) = &habit_of {
            let set = RuleSet::new(vec![r.clone()]);
            if !holds(&Evaluator::new(l, &set, contact), &r) {
                continue;
            }
            let broken_elsewhere = others
                .iter()
                .any(|o| !holds(&Evaluator::new(o, &set, contact), &r));
            if !broken_elsewhere && tries < 150 {
                continue;
            }
        }
        rules.push(r);
    }
    case.rules = RuleSet::new(rules);
    case
}

// ---- the enumeration --------------------------------------------------------

/// `(object index, its grid positions)` for every unplaced object.
fn domains(scene: &Scene) -> Vec<(usize, Vec<Rect>)> {
    let placed: Vec<Rect> = scene.objects.iter().filter_map(|o| o.rect()).collect();
    scene
        .objects
        .iter()
        .enumerate()
        .filter(|(_, o)| !o.is_placed())
        .map(|(i, o)| {
            let d = grid_positions(scene, o.width, o.height)
                .into_iter()
                .map(|(x, y)| Rect::new(x, y, o.width, o.height))
                .filter(|r| placed.iter().all(|p| !p.interiors_overlap(r)))
                .collect();
            (i, d)
        })
        .collect()
}

/// Whether `rule` holds on `scene` (every subject, or the scene-level count).
fn holds(ev: &Evaluator, rule: &Rule) -> bool {
    let r = ev.evaluate_rule(rule);
    r.satisfied == r.subjects
}

/// What the enumeration of every layout found, per rule.
struct Enumerated {
    layouts: u64,
    /// `breakable[k]`: some layout breaks rule `k` and keeps all the others.
    breakable: Vec<bool>,
    /// For a per-object rule: the most subjects breaking it in such a layout.
    most_broken: Vec<usize>,
    /// Distinct sets of broken rules (bit `k`: rule `k` broken).
    masks: std::collections::BTreeSet<u32>,
}

fn enumerate(case: &Case) -> Enumerated {
    let doms = domains(&case.scene);
    let n = case.rules.rules.len();
    let mut out = Enumerated {
        layouts: 0,
        breakable: vec![false; n],
        most_broken: vec![0; n],
        masks: Default::default(),
    };
    let mut scene = case.scene.clone();
    let mut chosen: Vec<Rect> = Vec::new();
    fn dfs(
        depth: usize,
        doms: &[(usize, Vec<Rect>)],
        scene: &mut Scene,
        chosen: &mut Vec<Rect>,
        case: &Case,
        out: &mut Enumerated,
    ) {
        if depth == doms.len() {
            out.layouts += 1;
            let ev = Evaluator::new(scene, &case.rules, case.contact);
            let mut mask = 0u32;
            let mut broken = vec![0usize; case.rules.rules.len()];
            for (k, r) in case.rules.rules.iter().enumerate() {
                let rep = ev.evaluate_rule(r);
                if rep.satisfied != rep.subjects {
                    mask |= 1 << k;
                    broken[k] = rep.subjects - rep.satisfied;
                }
            }
            out.masks.insert(mask);
            if mask.count_ones() == 1 {
                let k = mask.trailing_zeros() as usize;
                out.breakable[k] = true;
                out.most_broken[k] = out.most_broken[k].max(broken[k]);
            }
            return;
        }
        let (i, dom) = &doms[depth];
        for r in dom {
            if chosen.iter().any(|c| c.interiors_overlap(r)) {
                continue;
            }
            scene.objects[*i].x = Some(r.x);
            scene.objects[*i].y = Some(r.y);
            chosen.push(*r);
            dfs(depth + 1, doms, scene, chosen, case, out);
            chosen.pop();
        }
        scene.objects[*i].x = None;
        scene.objects[*i].y = None;
    }
    dfs(0, &doms, &mut scene, &mut chosen, case, &mut out);
    out
}

// ---- the differential check -------------------------------------------------

#[derive(Default, Debug)]
struct Tally {
    cases: usize,
    layouts: u64,
    probes: usize,
    probes_scene_level: usize,
    probes_like: usize,
    implied: usize,
    /// Implied although the rule alone can be broken on this problem: the
    /// other rules really imply it.
    implied_by_others: usize,
    /// Implied by the others while the whole set is satisfiable.
    implied_satisfiable: usize,
    implied_explained: usize,
    unbreakable_quantifier: usize,
    failures: Vec<String>,
}

fn check_case(case: &Case, t: &mut Tally) {
    let en = enumerate(case);
    t.cases += 1;
    t.layouts += en.layouts;
    // `explain` on every third case: `by` is then checked as well.
    let explain = case.index % 3 == 0;
    // A like-scene on every fourth case: a random complete layout.
    let like = (case.index % 4 == 1)
        .then(|| random_layout(case, &mut ChaCha8Rng::seed_from_u64(case.index ^ 0x11CE)))
        .flatten()
        .map(|s| ResemblanceTarget::new(&[s]));
    for k in 0..case.rules.rules.len() {
        let rule = &case.rules.rules[k];
        let opts = ProbeOptions {
            contact: case.contact,
            seed: case.index,
            solve_time: None,
            stop: rccpack::stop::Stop::never(),
            check_nodes: None,
            like: like.clone(),
            explain,
            warm_start: Vec::new(),
            tuning: Default::default(),
        };
        let fail = |t: &mut Tally, why: String| {
            t.failures
                .push(format!("rule r{k}: {why}\n{}", case.describe()));
        };
        let outcome = match find_probe(&case.scene, &case.rules, k, &opts) {
            Ok(o) => o,
            Err(e) => {
                fail(t, format!("find_probe error: {e}"));
                continue;
            }
        };
        match outcome {
            ProbeOutcome::Probe(p) => {
                t.probes += 1;
                t.probes_scene_level += usize::from(rule.scope != Scope::Each);
                t.probes_like += usize::from(like.is_some());
                if !en.breakable[k] {
                    fail(
                        t,
                        format!(
                            "a probe, but enumeration finds no layout breaking it and keeping the rest:\n{}",
                            p.scene.to_json()
                        ),
                    );
                    continue;
                }
                if let Err(e) =
                    verify_solution(&case.scene, &p.scene, &RuleSet::default(), case.contact)
                {
                    fail(t, format!("probe is not a layout of the problem: {e}"));
                    continue;
                }
                if p.rule != rule.name {
                    fail(t, format!("probe names rule `{}`", p.rule));
                }
                let ev = Evaluator::new(&p.scene, &case.rules, case.contact);
                if holds(&ev, rule) {
                    fail(
                        t,
                        format!("the probe keeps the rule:\n{}", p.scene.to_json()),
                    );
                }
                for (j, r) in case.rules.rules.iter().enumerate() {
                    if j != k && !holds(&ev, r) {
                        fail(
                            t,
                            format!("the probe breaks another rule r{j}:\n{}", p.scene.to_json()),
                        );
                    }
                }
                let rep = ev.evaluate_rule(rule);
                if p.broken != rep.violators {
                    fail(
                        t,
                        format!(
                            "broken {:?}, the evaluator's violators {:?}",
                            p.broken, rep.violators
                        ),
                    );
                }
                if rule.scope == Scope::Each {
                    if p.broken.is_empty() {
                        fail(t, "a per-object probe with no broken object".into());
                    }
                    if p.broken.len() != en.most_broken[k] {
                        fail(
                            t,
                            format!(
                                "the probe breaks the rule for {} subjects; a layout breaking it for {} exists",
                                p.broken.len(),
                                en.most_broken[k]
                            ),
                        );
                    }
                }
                if let Some(l) = &like {
                    // The resemblance cost is the evaluator-side one.
                    if p.cost != l.cost(&case.scene, &p.scene) {
                        fail(t, format!("cost {} ≠ ResemblanceTarget::cost", p.cost));
                    }
                } else if p.cost != 0 {
                    fail(t, format!("cost {} without like", p.cost));
                }
            }
            ProbeOutcome::Implied { by } => {
                t.implied += 1;
                if en.breakable[k] {
                    fail(
                        t,
                        "Implied, but the enumeration finds a layout breaking it and keeping the rest"
                            .into(),
                    );
                    continue;
                }
                if negation(rule).is_none() {
                    t.unbreakable_quantifier += 1;
                    continue;
                }
                // Can the rule be broken at all (ignoring the others)?
                if en.masks.iter().any(|m| m & (1 << k) != 0) {
                    t.implied_by_others += 1;
                    t.implied_satisfiable += usize::from(en.masks.contains(&0));
                }
                if explain {
                    t.implied_explained += 1;
                    let idx: Vec<usize> = match by
                        .iter()
                        .map(|n| case.rules.rules.iter().position(|r| &r.name == n))
                        .collect::<Option<Vec<_>>>()
                    {
                        Some(v) => v,
                        None => {
                            fail(t, format!("`by` {by:?} names unknown rules"));
                            continue;
                        }
                    };
                    if idx.contains(&k) {
                        fail(t, format!("`by` {by:?} names the rule itself"));
                    }
                    let keep: u32 = idx.iter().map(|&j| 1u32 << j).sum();
                    let escapes = en.masks.iter().any(|m| m & (1 << k) != 0 && m & keep == 0);
                    if escapes {
                        fail(
                            t,
                            format!("`by` {by:?}: some layout breaks the rule and keeps those"),
                        );
                    }
                }
            }
            ProbeOutcome::Unknown => fail(t, "Unknown without a limit".into()),
        }
    }
}

/// A random complete non-overlapping layout of the case (None if the random
/// tries all clash).
fn random_layout(case: &Case, rng: &mut ChaCha8Rng) -> Option<Scene> {
    let doms = domains(&case.scene);
    'outer: for _ in 0..50 {
        let mut s = case.scene.clone();
        let mut chosen: Vec<Rect> = Vec::new();
        for (i, d) in &doms {
            if d.is_empty() {
                return None;
            }
            let r = d[rng.random_range(0..d.len())];
            if chosen.iter().any(|c| c.interiors_overlap(&r)) {
                continue 'outer;
            }
            s.objects[*i].x = Some(r.x);
            s.objects[*i].y = Some(r.y);
            chosen.push(r);
        }
        return Some(s);
    }
    None
}

fn run(cases: std::ops::Range<u64>) -> Tally {
    let mut t = Tally::default();
    for i in cases {
        check_case(&random_case(i), &mut t);
    }
    eprintln!(
        "ask_probes: {} cases, {} layouts enumerated; {} probes ({} scene-level, {} with like), {} implied ({} by the other rules, {} of them in a satisfiable set, {} explained, {} unbreakable quantifiers); {} failures",
        t.cases,
        t.layouts,
        t.probes,
        t.probes_scene_level,
        t.probes_like,
        t.implied,
        t.implied_by_others,
        t.implied_satisfiable,
        t.implied_explained,
        t.unbreakable_quantifier,
        t.failures.len()
    );
    t
}

fn assert_clean(t: &Tally) {
    if !t.failures.is_empty() {
        let shown: Vec<&str> = t.failures.iter().take(5).map(String::as_str).collect();
        panic!(
            "{} failures; first ones:\n{}",
            t.failures.len(),
            shown.join("\n----\n")
        );
    }
}

#[test]
fn probes_agree_with_enumeration() {
    let t = run(0..1000);
    assert_clean(&t);
    // Both outcomes occur many times, and the implications are not all
    // trivial (a rule nothing can break).
    assert!(t.probes >= 600, "{t:?}");
    assert!(t.probes_scene_level >= 200, "{t:?}");
    assert!(t.probes_like >= 100, "{t:?}");
    assert!(t.implied >= 1000, "{t:?}");
    assert!(t.implied_by_others >= 500, "{t:?}");
    assert!(t.implied_satisfiable >= 300, "{t:?}");
    assert!(t.implied_explained >= 300, "{t:?}");
    assert!(t.unbreakable_quantifier >= 30, "{t:?}");
}

#[test]
#[ignore = "slow: cargo test --release --test integration ask_probes:: -- --ignored"]
fn probes_agree_with_enumeration_large() {
    let t = run(10_000..14_000);
    assert_clean(&t);
}

/// The probe problem holds the other rules hard, the negation hard, and for
/// a per-object rule the soft "break it" objective.
#[test]
fn probe_rules_shape() {
    for i in 0..100 {
        let case = random_case(i);
        for k in 0..case.rules.rules.len() {
            let r = &case.rules.rules[k];
            let Some(p) = probe_rules(&case.rules, k) else {
                assert!(negation(r).is_none());
                continue;
            };
            let hard = p.rules.iter().filter(|x| x.strength.is_hard()).count();
            let soft = p.rules.len() - hard;
            assert_eq!(hard, case.rules.rules.len());
            assert_eq!(soft, usize::from(r.scope == Scope::Each));
        }
    }
}

// ---- negation, algebraically ------------------------------------------------

/// Every subject scope the language has, with `K` around the object counts.
fn scopes() -> Vec<Scope> {
    let mut v = vec![
        Scope::Each,
        Scope::Scene(Quant::Every),
        Scope::Scene(Quant::Some),
        Scope::Scene(Quant::No),
        Scope::Scene(Quant::AtMost(MAX_COUNT)),
        Scope::Scene(Quant::AtMost(MAX_COUNT - 1)),
        Scope::Scene(Quant::AtLeast(MAX_COUNT)),
    ];
    for k in 0..=5 {
        v.push(Scope::Scene(Quant::AtLeast(k)));
        v.push(Scope::Scene(Quant::AtMost(k)));
    }
    v
}

#[test]
fn negation_holds_iff_the_rule_is_broken() {
    let mut checked = 0;
    let mut both = [0usize; 2];
    let mut none = 0;
    for i in 0..400 {
        let case = random_case(50_000 + i);
        let mut rng = ChaCha8Rng::seed_from_u64(i);
        let Some(scene) = random_layout(&case, &mut rng) else {
            continue;
        };
        for r in &case.rules.rules {
            for scope in scopes() {
                let r = Rule { scope, ..r.clone() };
                let set = RuleSet::new(vec![r.clone()]);
                let ev = evaluate(&scene, &set, case.contact);
                let held = ev.rules[0].satisfied == ev.rules[0].subjects;
                match negation(&r) {
                    None => {
                        none += 1;
                        assert!(
                            held,
                            "negation None but `{}` is broken\n{}",
                            rule_text(&r),
                            scene.to_json()
                        );
                        assert!(matches!(
                            scope,
                            Scope::Scene(Quant::AtLeast(0))
                                | Scope::Scene(Quant::AtMost(MAX_COUNT))
                        ));
                    }
                    Some(n) => {
                        assert!(n.strength.is_hard());
                        assert_eq!(n.subject(), r.subject());
                        let set = RuleSet::new(vec![n.clone()]);
                        let nev = evaluate(&scene, &set, case.contact);
                        let nheld = nev.rules[0].satisfied == nev.rules[0].subjects;
                        assert_eq!(
                            nheld,
                            !held,
                            "rule `{}` holds: {held}; negation `{}` holds: {nheld}\n{}",
                            rule_text(&r),
                            rule_text(&n),
                            scene.to_json()
                        );
                        both[usize::from(held)] += 1;
                        checked += 1;
                    }
                }
            }
        }
    }
    eprintln!(
        "negation: {checked} checked (broken {}, held {}), {none} unbreakable",
        both[0], both[1]
    );
    assert!(checked > 5000 && both[0] > 1000 && both[1] > 1000 && none > 500);
}

// ---- a whole session against enumeration -----------------------------------

/// Whether some complete layout of `scene`'s unplaced objects breaks
/// `held.rules[k]` and keeps every other held rule (enumerated).
fn breakable_by_enumeration(scene: &Scene, held: &RuleSet, k: usize, contact: Contact) -> bool {
    let doms = domains(scene);
    fn dfs(
        depth: usize,
        doms: &[(usize, Vec<Rect>)],
        scene: &mut Scene,
        chosen: &mut Vec<Rect>,
        held: &RuleSet,
        k: usize,
        contact: Contact,
    ) -> bool {
        if depth == doms.len() {
            let ev = Evaluator::new(scene, held, contact);
            return held.rules.iter().enumerate().all(|(j, r)| {
                let rep = ev.evaluate_rule(r);
                (rep.satisfied == rep.subjects) != (j == k)
            });
        }
        let (i, dom) = &doms[depth];
        for r in dom {
            if chosen.iter().any(|c| c.interiors_overlap(r)) {
                continue;
            }
            scene.objects[*i].x = Some(r.x);
            scene.objects[*i].y = Some(r.y);
            chosen.push(*r);
            let found = dfs(depth + 1, doms, scene, chosen, held, k, contact);
            chosen.pop();
            if found {
                return true;
            }
        }
        scene.objects[*i].x = None;
        scene.objects[*i].y = None;
        false
    }
    let mut s = scene.clone();
    dfs(0, &doms, &mut s, &mut Vec::new(), held, k, contact)
}

/// A session on tiny problems, every probe rejected (so the held rules stay
/// the same): every question's probe breaks its rule and keeps the others,
/// and every rule the session leaves unasked because the others imply it
/// cannot be broken, by enumeration, on the problem nor — when the session
/// says it searched them — on any demonstration with one or two movable
/// objects moved.
#[test]
fn a_session_agrees_with_enumeration() {
    use rccpack::ask::{AskOptions, Asker, QuestionBudget, Unasked};
    use rccpack::infer::LearnParams;
    let (mut sessions, mut implied, mut with_edits, mut questions) = (0, 0, 0, 0);
    for i in 0..300 {
        let case = random_case(i);
        let mut rng = ChaCha8Rng::seed_from_u64(i);
        let demos: Vec<Scene> = (0..200)
            .filter_map(|_| random_layout(&case, &mut rng))
            .filter(|s| {
                let ev = Evaluator::new(s, &case.rules, case.contact);
                case.rules.rules.iter().all(|r| holds(&ev, r))
            })
            .take(2)
            .collect();
        if demos.len() < 2 {
            continue;
        }
        let opts = AskOptions {
            learn: LearnParams {
                samples: 200,
                cutoff: 0.99,
                contact: case.contact,
                ..LearnParams::default()
            },
            probe: ProbeOptions {
                contact: case.contact,
                ..ProbeOptions::default()
            },
            budget: QuestionBudget {
                nodes: u64::MAX,
                wall: None,
            },
            ..AskOptions::default()
        };
        let Ok(mut asker) = Asker::new(
            case.scene.clone(),
            demos.clone(),
            Some(case.rules.clone()),
            Vec::new(),
            opts,
        ) else {
            continue;
        };
        sessions += 1;
        while let Some(q) = asker.next_question().unwrap() {
            questions += 1;
            let ev = evaluate(&q.probe.scene, asker.held(), case.contact);
            for r in &ev.rules {
                let broken = r.satisfied < r.subjects;
                assert_eq!(
                    broken,
                    r.name == q.rule || q.also_broken.contains(&r.name),
                    "question about {}: {} ({})",
                    q.rule,
                    r.name,
                    case.describe()
                );
            }
            asker.answer(&q, false).unwrap();
        }
        let held = asker.held().clone();
        for (name, why) in asker.unasked() {
            let k = held.rules.iter().position(|r| r.name == name).unwrap();
            let Unasked::Implied { edits_tried } = why else {
                continue;
            };
            implied += 1;
            assert!(
                !breakable_by_enumeration(&case.scene, &held, k, case.contact),
                "{name} is breakable on the problem\n{}",
                case.describe()
            );
            if !edits_tried {
                continue;
            }
            with_edits += 1;
            for d in asker.demos() {
                let movable: Vec<usize> = (0..d.objects.len())
                    .filter(|&j| !d.objects[j].fixed)
                    .collect();
                for (a, &x) in movable.iter().enumerate() {
                    for y in std::iter::once(None).chain(movable[a + 1..].iter().map(Some)) {
                        let mut s = d.clone();
                        for j in std::iter::once(x).chain(y.copied()) {
                            s.objects[j].x = None;
                            s.objects[j].y = None;
                        }
                        assert!(
                            !breakable_by_enumeration(&s, &held, k, case.contact),
                            "{name} is breakable in an edit of a demonstration\n{}",
                            case.describe()
                        );
                    }
                }
            }
        }
    }
    eprintln!("a_session_agrees_with_enumeration: {sessions} sessions, {questions} questions, {implied} unasked as implied ({with_edits} with edits tried)");
    assert!(
        sessions >= 100 && questions >= 100 && with_edits >= 50,
        "{sessions} {questions} {implied} {with_edits}"
    );
}

/// A session whose meant statement is about orientation ("every L lies
/// turned", "no L lies turned") asks about it with a probe that turns a
/// block over — a demonstration edit first — which the evaluator and the
/// checker confirm, and whose `turned` flags survive in the answer.
#[test]
fn a_session_breaks_an_orientation_rule_by_turning_a_block() {
    use rccpack::ask::{AnswersFile, AskOptions, Asker};
    use rccpack::rules::parse_rules;
    use rccpack::scene::Space;
    let space = Space {
        x: 0,
        y: 0,
        width: 80,
        height: 40,
    };
    for (text, on_end) in [
        ("rule L_on_end: turned(L)\nrule S_east: DR_E(S, L)\n", true),
        ("rule L_flat: !turned(L)\nrule S_east: DR_E(S, L)\n", false),
    ] {
        let held = parse_rules(text).unwrap();
        let l = |id: &str, x, y| {
            let o = Object::placed(id, "L", x, y, 20, 10).with_turnable();
            if on_end {
                o.with_turned()
            } else {
                o
            }
        };
        // Two L blocks (on end or flat) west of an S, in five places.
        let demos: Vec<Scene> = (0..5)
            .map(|d| {
                let objects = vec![
                    l("l1", 10 * d, 0),
                    l("l2", 10 * d + 10, 20),
                    Object::placed("s", "S", 70, 0, 10, 10),
                ];
                Scene::new(space, 10, objects).unwrap()
            })
            .collect();
        let problem = Scene::new(
            space,
            10,
            vec![
                Object::movable("l1", "L", 20, 10).with_turnable(),
                Object::movable("l2", "L", 20, 10).with_turnable(),
                Object::movable("s", "S", 10, 10),
            ],
        )
        .unwrap();
        let mut asker = Asker::new(
            problem.clone(),
            demos,
            Some(held.clone()),
            Vec::new(),
            AskOptions::default(),
        )
        .unwrap();
        let name = &held.rules[0].name;
        let mut asked = false;
        while let Some(q) = asker.next_question().unwrap() {
            if &q.rule != name {
                asker.answer(&q, true).unwrap();
                continue;
            }
            asked = true;
            let s = &q.probe.scene;
            // It breaks the rule asked about and keeps every other held one.
            let ev = evaluate(s, asker.held(), Contact::Point);
            for r in &ev.rules {
                let broken = r.satisfied < r.subjects;
                let about = r.name == q.rule || q.also_broken.contains(&r.name);
                assert_eq!(broken, about, "{text}: {}", r.name);
            }
            // Some L lies the other way than the demonstrator's.
            assert!(
                s.objects
                    .iter()
                    .any(|o| o.class == "L" && o.turned != on_end),
                "{text}: {s:?}"
            );
            match &q.probe.edit {
                // A demonstration with a block turned over: the evaluator
                // agrees with the checker, nothing overlaps.
                Some(e) => {
                    s.validate().unwrap();
                    let m = e.moved.iter().find(|m| m.id.starts_with('l')).unwrap();
                    assert_eq!(m.turned, on_end, "{text}: where it was");
                }
                None => {
                    verify_solution(&problem, s, &RuleSet::new(Vec::new()), Contact::Point).unwrap()
                }
            }
            let a = asker.answer(&q, false).unwrap().clone();
            let file = AnswersFile {
                answers: vec![a.clone()],
            };
            let back = AnswersFile::from_json(&file.to_json()).unwrap();
            assert_eq!(back.answers[0].probe, a.probe, "{text}");
            assert_eq!(back.answers[0].edit, a.edit, "{text}");
        }
        assert!(
            asked,
            "{text}: never asked: held {:?}, unasked {:?}",
            asker
                .held()
                .rules
                .iter()
                .map(|r| &r.name)
                .collect::<Vec<_>>(),
            asker.unasked()
        );
    }
}
