//! The emitted model (`synth::emit`) means what the engine's model means.
//!
//! - **JSON** (always runs): on random tiny problems (space ≤ 60×60 with an
//!   offset origin now and then, grid 10, ≤ 4 objects of which some fixed or
//!   already placed, rules over all sixteen relations with every target
//!   quantifier, landmarks, `not`/`and`/`or`, scene-level rules, hard and
//!   soft, both contact modes, symmetry breaking and cumulatives on and off)
//!   the `to_json` text is read back with `serde_json` and evaluated by a
//!   little interpreter written here from the module doc alone, on rccpack's
//!   optimal layout: every clause, hard literal, symmetry order and
//!   cumulative holds, and the objective is the integer numerator implied
//!   by the evaluator's verdict. The interpreter's Booleans also equal
//!   `Model::eval_bools` on random assignments.
//! - **Gecode** through MiniZinc (`bench::peers`; needs `minizinc` and
//!   `python3`) and **CP-SAT** (needs `python3` with `ortools`), ignored
//!   tests that `.ci/run` runs after installing both: the peer's layout passes
//!   `verify_solution`, its evaluator score equals rccpack's proven optimum,
//!   its reported objective equals the emitted objective of its values, and
//!   infeasible problems are infeasible for both.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rccpack::eval::evaluate;
use rccpack::relations::{Contact, Dir, Kind, Quant, Relation};
use rccpack::rules::{Atom, Formula, Rule, RuleSet, Scope, Strength, Target};
use rccpack::scene::{Object, Scene, Space};
use rccpack::synth::emit::{emitted, to_json, to_minizinc, Emitted, FORMAT};
use rccpack::synth::model::{BoolDef, LinLe, Lit, SoftTerm};
use rccpack::synth::verify_solution;
use rccpack::synth::{synthesize, Status, SynthOptions};
use rccpack_bench::peers::{self, Peer, PeerStatus};
use serde_json::Value;

use crate::support::formulas::{pick, random_tree, Vocabulary};
use crate::support::require_peer;
use std::time::Duration;

const SEED: u64 = 0x0E41_7ED5;

struct Case {
    index: u64,
    scene: Scene,
    rules: RuleSet,
    opts: SynthOptions,
}

/// Classes A (weight 4) and B (2); `@a0` is never a fixed object.
const VOC: Vocabulary = Vocabulary {
    classes: ["A", "A", "A", "A", "B", "B"],
    absent: "a0",
};

/// Every side touched by something, flush: a shape like the templates' (docs/guide.md#learning), with many
/// shared literals.
fn flush_shape(subject: &str) -> Formula {
    Formula::And(
        Dir::ALL
            .iter()
            .map(|&d| {
                let q = |k| {
                    Formula::Atom(Atom::quantified(
                        Relation::new(k, d),
                        subject,
                        Quant::Some,
                        Target::Any,
                    ))
                };
                Formula::Or(vec![Formula::not(q(Kind::EC)), q(Kind::FL)])
            })
            .collect(),
    )
}

fn random_case(index: u64) -> Case {
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    rng.set_stream(index);
    let (w, h) = pick(
        &mut rng,
        &[(30, 30), (40, 30), (30, 40), (40, 40), (50, 30)],
    );
    let (ox, oy) = pick(&mut rng, &[(0, 0), (0, 0), (-10, 5), (7, -3)]);
    let sizes = [(10, 10), (10, 10), (20, 10), (10, 20), (15, 10)];
    let mut objects: Vec<Object> = Vec::new();
    if rng.random_range(0..2) == 0 {
        let (fw, fh) = pick(&mut rng, &sizes);
        let x = ox + 10 * rng.random_range(0..=(w - fw) / 10);
        let y = oy + 10 * rng.random_range(0..=(h - fh) / 10);
        objects.push(Object::fixed_at(
            "f",
            pick(&mut rng, &["F", "A"]),
            x,
            y,
            fw,
            fh,
        ));
    }
    if rng.random_range(0..4) == 0 {
        let o = Object::placed(
            "p0",
            pick(&mut rng, &["A", "B"]),
            ox + 10 * rng.random_range(0..w / 10 - 1),
            oy + 10 * rng.random_range(0..h / 10 - 1),
            10,
            10,
        );
        if !crate::support::overlaps_any(&objects, &o) {
            objects.push(o);
        }
    }
    // Often as many as fit: counts over three others make `at_least`s.
    let most = (4 - objects.len()).min(3);
    let movable = if rng.random_range(0..2) == 0 {
        most
    } else {
        rng.random_range(1..=most)
    };
    for i in 0..movable {
        let class = pick(&mut rng, &["A", "A", "B"]);
        let (bw, bh) = if rng.random_range(0..3) == 0 {
            pick(&mut rng, &sizes)
        } else {
            (10, 10)
        };
        objects.push(Object::movable(
            &format!("{}{i}", class.to_lowercase()),
            class,
            bw,
            bh,
        ));
    }
    let scene = Scene {
        space: Space {
            x: ox,
            y: oy,
            width: w,
            height: h,
        },
        grid: 10,
        objects,
    };
    let rules: Vec<Rule> = (0..rng.random_range(1..=4))
        .map(|i| {
            let subject = pick(&mut rng, &["A", "B"]);
            let f = match rng.random_range(0..8) {
                0 => flush_shape(subject),
                // A count over every other object (an `at_least` when there
                // are three of them).
                1 | 2 => {
                    let q = pick(&mut rng, &[Quant::AtLeast(2), Quant::AtMost(1)]);
                    let rel = pick(&mut rng, &Relation::ALL);
                    Formula::Atom(Atom::quantified(rel, subject, q, Target::Any))
                }
                _ => {
                    let depth = rng.random_range(0..=2);
                    random_tree(&mut rng, &VOC, subject, depth + 1)
                }
            };
            let strength = match rng.random_range(0..8) {
                0 | 1 => Strength::Hard,
                _ => Strength::Weight(pick(&mut rng, &[0.5, 1.0, 2.0, 2.5])),
            };
            let scope = if rng.random_range(0..4) == 0 {
                Scope::Scene(match rng.random_range(0..5) {
                    0 => Quant::Some,
                    1 => Quant::No,
                    2 => Quant::AtLeast(rng.random_range(0..=3)),
                    3 => Quant::AtMost(rng.random_range(0..=3)),
                    _ => Quant::AtLeast(2),
                })
            } else {
                Scope::Each
            };
            Rule::new(format!("r{i}"), f)
                .with_strength(strength)
                .with_scope(scope)
        })
        .collect();
    let opts = SynthOptions {
        contact: pick(&mut rng, &Contact::ALL),
        stop: rccpack::stop::Stop::after(Duration::from_secs(20)),
        symmetry_breaking: rng.random_range(0..4) != 0,
        redundant: rng.random_range(0..4) != 0,
        explain: false,
        ..SynthOptions::default()
    };
    let mut rules: Vec<Rule> = rules;
    // From GROUP_CASES on, one group statement more, drawn last (the cases
    // before it are those of earlier editions, unchanged).
    if index >= GROUP_CASES {
        let kind = pick(&mut rng, &rccpack::shapes::ShapeKind::ALL);
        let class = pick(&mut rng, &["A", "A", "B"]);
        let strength = match rng.random_range(0..3) {
            0 => Strength::Hard,
            _ => Strength::Weight(pick(&mut rng, &[0.5, 1.0, 2.5])),
        };
        let negated = rng.random_range(0..5) == 0;
        let shape = rccpack::rules::Shape::new(kind, class);
        rules.push(Rule::group("g", shape, negated).with_strength(strength));
    }
    Case {
        index,
        scene,
        rules: RuleSet::new(rules),
        opts,
    }
}

/// The first case index whose rules include a group statement.
const GROUP_CASES: u64 = 5000;

/// The first case index of the cases with objects that turn.
const TURN_CASES: u64 = 9000;

/// [`random_case`] with every movable block `turnable` and a soft
/// orientation rule (`turned(A)`): the orientation variables' model.
fn turning_case(index: u64) -> Case {
    let mut c = random_case(index);
    for o in c.scene.objects.iter_mut().filter(|o| !o.is_placed()) {
        o.turnable = true;
    }
    let mut rules = c.rules.rules.clone();
    rules.push(Rule::new("on_end", Formula::Turned("A".into())));
    c.rules = RuleSet::new(rules);
    c
}

/// `n` turning cases and the first `k` packings that fit only turned
/// (`tests/support/turn_packing.rs`), with the orientation rule.
fn turning_cases(n: u64, k: usize) -> Vec<Case> {
    let mut cases: Vec<Case> = (TURN_CASES..TURN_CASES + n).map(turning_case).collect();
    for (i, scene) in crate::support::turn_packing::packings(k)
        .into_iter()
        .enumerate()
    {
        cases.push(Case {
            index: 2_000_000 + i as u64,
            scene,
            rules: RuleSet::new(vec![Rule::new("on_end", Formula::Turned("B".into()))]),
            opts: SynthOptions::default(),
        });
    }
    cases
}

/// Problems every peer must find infeasible: an object larger than the
/// space (the trivially infeasible emitted model), and contradicting hard
/// rules.
fn infeasible_cases() -> Vec<Case> {
    let space = Space {
        x: 0,
        y: 0,
        width: 30,
        height: 30,
    };
    let block = |id: &str, class: &str, w, h| Object::movable(id, class, w, h);
    let dr = |d, s: &str, t: &str| {
        Formula::Atom(Atom::new(
            Relation::new(Kind::DR, d),
            s,
            Target::Class(t.into()),
        ))
    };
    let opts = SynthOptions {
        explain: false,
        ..SynthOptions::default()
    };
    vec![
        Case {
            index: 1_000_000,
            scene: Scene {
                space,
                grid: 10,
                objects: vec![block("a0", "A", 10, 10), block("big", "B", 40, 10)],
            },
            rules: RuleSet::new(vec![Rule::new("r0", dr(Dir::N, "A", "B"))]),
            opts: opts.clone(),
        },
        Case {
            index: 1_000_001,
            scene: Scene {
                space,
                grid: 10,
                objects: vec![block("a0", "A", 10, 10), block("b0", "B", 10, 10)],
            },
            rules: RuleSet::new(vec![
                Rule::new("north", dr(Dir::N, "A", "B")).with_strength(Strength::Hard),
                Rule::new("south", dr(Dir::S, "A", "B")).with_strength(Strength::Hard),
                Rule::new("soft", dr(Dir::E, "A", "B")),
            ]),
            opts,
        },
    ]
}

// ---- an independent interpreter of the JSON form ---------------------------

fn int(v: &Value) -> i64 {
    v.as_i64()
        .unwrap_or_else(|| panic!("expected an integer, got {v}"))
}

fn lit(l: &Value, bools: &[bool]) -> bool {
    if let Some(c) = l.get("const") {
        return c.as_bool().expect("const is a bool");
    }
    let b = bools[int(&l["var"]) as usize];
    b != l["neg"].as_bool().expect("neg is a bool")
}

fn arr(v: &Value) -> &Vec<Value> {
    v.as_array()
        .unwrap_or_else(|| panic!("expected an array, got {v}"))
}

fn json_bools(j: &Value, vals: &[i64]) -> Vec<bool> {
    let mut out: Vec<bool> = Vec::new();
    for d in arr(&j["bools"]) {
        let v = match d["op"].as_str().expect("op") {
            "ge" => vals[int(&d["var"]) as usize] >= int(&d["k"]),
            "diff_ge" => vals[int(&d["a"]) as usize] - vals[int(&d["b"]) as usize] >= int(&d["k"]),
            "and" => arr(&d["lits"]).iter().all(|l| lit(l, &out)),
            "at_least" => {
                arr(&d["lits"]).iter().filter(|l| lit(l, &out)).count() as i64 >= int(&d["k"])
            }
            op => panic!("unknown op {op}"),
        };
        out.push(v);
    }
    out
}

/// Every constraint of the JSON model holds under `vals`; returns the
/// objective.
fn json_check(j: &Value, vals: &[i64]) -> Result<i64, String> {
    for (i, v) in arr(&j["vars"]).iter().enumerate() {
        if !(int(&v["lb"])..=int(&v["ub"])).contains(&vals[i]) {
            return Err(format!("v{i} = {} outside its domain", vals[i]));
        }
    }
    let bools = json_bools(j, vals);
    for (i, c) in arr(&j["clauses"]).iter().enumerate() {
        if !arr(c).iter().any(|l| lit(l, &bools)) {
            return Err(format!("clause {i} {c} fails"));
        }
    }
    for h in arr(&j["hard"]) {
        if !arr(&h["lits"]).iter().all(|l| lit(l, &bools)) {
            return Err(format!("hard rule {} fails", h["name"]));
        }
    }
    for s in arr(&j["symmetry"]) {
        let lhs: i64 = arr(&s["terms"])
            .iter()
            .map(|t| int(&t[0]) * vals[int(&t[1]) as usize])
            .sum();
        if lhs > int(&s["rhs"]) {
            return Err(format!("symmetry {s} fails"));
        }
    }
    for c in arr(&j["cumulative"]) {
        let tasks: Vec<(i64, i64, i64)> = arr(&c["tasks"])
            .iter()
            .map(|t| {
                let s = &t["start"];
                let start = match s.get("const") {
                    Some(v) => int(v),
                    None => int(&s["scale"]) * vals[int(&s["var"]) as usize] + int(&s["offset"]),
                };
                (start, int(&t["duration"]), int(&t["demand"]))
            })
            .collect();
        for &(t, _, _) in &tasks {
            let load: i64 = tasks
                .iter()
                .filter(|&&(s, d, _)| s <= t && t < s + d)
                .map(|x| x.2)
                .sum();
            if load > int(&c["capacity"]) {
                return Err(format!("cumulative {} overloaded at {t}", c["axis"]));
            }
        }
    }
    let mut obj = 0;
    let mut constant = 0;
    for s in arr(&j["soft"]) {
        if lit(&s["lit"], &bools) {
            obj += int(&s["coef"]);
        }
        if s["lit"].get("const").and_then(Value::as_bool) == Some(true) {
            constant += int(&s["coef"]);
        }
    }
    assert_eq!(constant, int(&j["objective"]["constant"]));
    Ok(obj)
}

/// The grid values of `solution` per JSON variable.
fn grid_values(j: &Value, solution: &Scene) -> Vec<i64> {
    let (ox, oy) = (int(&j["origin"][0]), int(&j["origin"][1]));
    let g = int(&j["grid"]);
    arr(&j["vars"])
        .iter()
        .map(|v| {
            let o = &solution.objects[int(&v["object"]) as usize];
            assert_eq!(v["object_id"].as_str(), Some(o.id.as_str()));
            let (c, origin) = match v["axis"].as_str() {
                Some("x") => (o.x.expect("placed"), ox),
                Some("y") => (o.y.expect("placed"), oy),
                Some("turn") => {
                    assert_eq!(v["ub"], 1);
                    return i64::from(o.turned);
                }
                a => panic!("axis {a:?}"),
            };
            assert_eq!((c - origin) % g, 0, "off the grid");
            (c - origin) / g
        })
        .collect()
}

/// The integer numerator the evaluator's verdict on `solution` implies.
fn implied_objective(j: &Value, solution: &Scene, case: &Case) -> i64 {
    let ev = evaluate(solution, &case.rules, case.opts.contact);
    let mut obj = 0;
    for s in arr(&j["soft"]) {
        let rep = &ev.rules[int(&s["rule"]) as usize];
        assert_eq!(s["name"].as_str(), Some(rep.name.as_str()));
        let holds = match s["object_id"].as_str() {
            Some(id) => !rep.violators.iter().any(|v| v == id),
            None => rep.satisfied == 1,
        };
        if holds {
            obj += int(&s["coef"]);
        }
    }
    obj
}

#[test]
fn json_form_holds_on_rccpack_solutions() {
    let mut solved = 0;
    let mut infeasible = 0;
    // Cases whose model has: at_least, and, diff_ge, a symmetry order, a
    // cumulative, a scene-level soft term, a constant-true soft term.
    let mut seen = [0usize; 7];
    let mut cases: Vec<Case> = (0..120).map(random_case).collect();
    cases.extend((GROUP_CASES..GROUP_CASES + 60).map(random_case));
    cases.extend(infeasible_cases());
    cases.extend(turning_cases(40, 8));
    // Optimal layouts with a block turned, read back from the values.
    let mut turned = 0;
    for case in &cases {
        let e = emitted(&case.scene, &case.rules, &case.opts).expect("usable problem");
        let text = to_json(&e);
        let j: Value = serde_json::from_str(&text).expect("to_json is JSON");
        let has_op = |op: &str| arr(&j["bools"]).iter().any(|b| b["op"] == op);
        let flags = [
            has_op("at_least"),
            has_op("and"),
            has_op("diff_ge"),
            !arr(&j["symmetry"]).is_empty(),
            !arr(&j["cumulative"]).is_empty(),
            arr(&j["soft"]).iter().any(|s| s["object"].is_null()),
            int(&j["objective"]["constant"]) > 0,
        ];
        for (n, f) in seen.iter_mut().zip(flags) {
            *n += usize::from(f);
        }
        assert_eq!(j["format"], FORMAT);
        assert_eq!(arr(&j["vars"]).len(), e.model.vars.len());
        assert_eq!(arr(&j["objects"]).len(), case.scene.objects.len());
        // The interpreter's Booleans are the model's, on random assignments.
        let mut rng = ChaCha8Rng::seed_from_u64(case.index);
        for _ in 0..20 {
            let vals: Vec<i64> = e
                .model
                .vars
                .iter()
                .map(|v| rng.random_range(0..=v.ub))
                .collect();
            assert_eq!(json_bools(&j, &vals), e.model.eval_bools(&vals));
        }
        let r = synthesize(&case.scene, &case.rules, &armed(&case.opts)).expect("solves");
        match r.status {
            Status::Optimal => {
                solved += 1;
                let s = r.scene.as_ref().expect("scene");
                let vals = grid_values(&j, s);
                let obj = json_check(&j, &vals).unwrap_or_else(|m| {
                    panic!("case {}: {m}\n{}", case.index, case.scene.to_json())
                });
                assert_eq!(obj, implied_objective(&j, s, case), "case {}", case.index);
                assert_eq!(Some(obj), e.objective_of(&vals));
                // The values give the layout back, orientations included.
                assert_eq!(&e.model.scene(&case.scene, &vals), s, "case {}", case.index);
                if s.objects.iter().any(|o| o.turned) {
                    turned += 1;
                    let with_var = arr(&j["objects"])
                        .iter()
                        .filter(|o| !o["turn_var"].is_null());
                    assert!(with_var.count() > 0, "case {}", case.index);
                }
            }
            Status::Infeasible => {
                infeasible += 1;
                if !e.model.too_large.is_empty() {
                    assert!(arr(&j["clauses"]).iter().any(|c| arr(c).is_empty()));
                    assert_eq!(arr(&j["too_large"]).len(), e.model.too_large.len());
                }
            }
            st => panic!("case {}: {st:?} on a tiny problem", case.index),
        }
    }
    assert!(solved >= 50, "{solved} solved");
    assert!(infeasible >= 2, "{infeasible} infeasible");
    assert!(seen.iter().all(|&n| n >= 3), "coverage {seen:?}");
    assert!(turned >= 10, "{turned} layouts with a block turned");
    eprintln!(
        "json: {solved} optimal ({turned} turned), {infeasible} infeasible, coverage {seen:?}"
    );
}

/// The MiniZinc text names every variable and Boolean, has the objective
/// and output items, and is trivially infeasible for a too-large object.
#[test]
fn minizinc_form_is_complete() {
    for case in (0..10).map(random_case).chain(infeasible_cases()) {
        let e = emitted(&case.scene, &case.rules, &case.opts).expect("usable");
        let mzn = to_minizinc(&e);
        for i in 0..e.model.vars.len() {
            assert!(mzn.contains(&format!("var 0..{}: v{i};", e.model.vars[i].ub)));
        }
        for j in 0..e.model.bools.len() {
            assert!(mzn.contains(&format!("var bool: b{j};")));
            assert!(mzn.contains(&format!("constraint b{j} <-> (")));
        }
        assert!(mzn.contains("solve maximize obj;"));
        assert!(mzn.contains("\"values = "));
        assert_eq!(
            mzn.contains("% Trivially infeasible:"),
            !e.model.too_large.is_empty()
        );
        if !e.model.too_large.is_empty() {
            assert!(mzn.contains("cannot lie inside the space at all.\nconstraint false;"));
        }
    }
}

/// `opts` with its 20-s safety net counted from now: the cases are drawn
/// before any is solved, and a `Stop` holds a deadline, not a duration.
fn armed(opts: &SynthOptions) -> SynthOptions {
    SynthOptions {
        stop: rccpack::stop::Stop::after(Duration::from_secs(20)),
        ..opts.clone()
    }
}

/// Runs `peer` on the cases and compares with rccpack.
fn against_peer(peer: Peer, cases: &[Case], time_limit: Duration) {
    against_peer_with(peer, cases, time_limit, emitted);
}

type Emit = fn(&Scene, &RuleSet, &SynthOptions) -> Result<Emitted, rccpack::synth::SynthError>;

fn against_peer_with(peer: Peer, cases: &[Case], time_limit: Duration, emit: Emit) {
    require_peer(peer);
    let (mut optimal, mut infeasible) = (0, 0);
    for case in cases {
        let e: Emitted = emit(&case.scene, &case.rules, &case.opts).expect("usable");
        let r = synthesize(&case.scene, &case.rules, &armed(&case.opts)).expect("solves");
        let p = peers::solve(peer, &e, time_limit)
            .unwrap_or_else(|m| panic!("case {}: {m}", case.index));
        let ctx = || format!("{peer} case {}\n{}", case.index, case.scene.to_json());
        match r.status {
            Status::Infeasible => {
                assert_eq!(p.status, PeerStatus::Infeasible, "{}", ctx());
                infeasible += 1;
            }
            Status::Optimal => {
                assert_eq!(p.status, PeerStatus::Optimal, "{}", ctx());
                let vals = p.values.as_ref().expect("values");
                assert_eq!(p.objective, e.objective_of(vals), "{}", ctx());
                let s = e.model.scene(&case.scene, vals);
                if let Err(m) = verify_solution(&case.scene, &s, &case.rules, case.opts.contact) {
                    panic!("{}: {m}\n{}", ctx(), s.to_json());
                }
                let mine = r.evaluation.as_ref().expect("evaluated");
                let theirs = evaluate(&s, &case.rules, case.opts.contact);
                assert!(
                    (mine.score - theirs.score).abs() <= 1e-9
                        && (mine.satisfied_weight - theirs.satisfied_weight).abs() <= 1e-9,
                    "{}: rccpack {} ({}), {peer} {} ({})",
                    ctx(),
                    mine.score,
                    mine.satisfied_weight,
                    theirs.score,
                    theirs.satisfied_weight
                );
                optimal += 1;
            }
            st => panic!("case {}: rccpack {st:?} on a tiny problem", case.index),
        }
    }
    assert!(infeasible >= 2, "{peer}: {infeasible} infeasible cases");
    eprintln!("{peer}: {optimal} optimal, {infeasible} infeasible, all agree");
}

/// `e` reduced to its Boolean definitions, with every grid variable fixed
/// to `vals` (two symmetry rows each) and, as the objective, the number of
/// Booleans that take the value opposite to `Model::eval_bools`'s: the
/// optimum is 0, with those values, exactly when the peer's encoding of
/// every definition agrees with the model's at `vals` both ways (the
/// model's values are allowed, and no other value is).
fn definitions_only(e: &Emitted, vals: &[i64]) -> Emitted {
    let mut d = e.clone();
    let m = &mut d.model;
    let bools = m.eval_bools(vals);
    m.clauses.clear();
    m.cumulative.clear();
    m.too_large.clear();
    m.hard.clear();
    m.symmetry = vals
        .iter()
        .enumerate()
        .flat_map(|(i, &v)| {
            [
                LinLe {
                    terms: vec![(1, i)],
                    rhs: v,
                },
                LinLe {
                    terms: vec![(-1, i)],
                    rhs: -v,
                },
            ]
        })
        .collect();
    m.soft = (0..bools.len())
        .map(|j| {
            let l = Lit::pos(j as u32);
            SoftTerm {
                rule: 0,
                object: None,
                lit: if bools[j] { !l } else { l },
                weight: 1.0,
            }
        })
        .collect();
    d.coefs = vec![1; bools.len()];
    d.constant = 0;
    d
}

/// On `n` cases whose models have Booleans, `peer`'s encoding of every
/// definition agrees with the model's at rccpack's layout (when there is
/// one) and at a random assignment, preferring models with `at_least`.
fn definitions_agree(peer: Peer, from: u64, n: usize) {
    require_peer(peer);
    let mut with_at_least = 0;
    let mut done = 0;
    let mut index = from;
    while done < n {
        let case = random_case(index);
        index += 1;
        let e = emitted(&case.scene, &case.rules, &case.opts).expect("usable");
        let at_least = e
            .model
            .bools
            .iter()
            .any(|b| matches!(b, BoolDef::AtLeast { .. }));
        // Half of the runs on models with counts, while they last.
        if e.model.bools.is_empty() || (!at_least && done % 2 == 0 && index < from + 400) {
            continue;
        }
        with_at_least += usize::from(at_least);
        done += 1;
        let mut rng = ChaCha8Rng::seed_from_u64(index);
        let vals: Vec<i64> = match synthesize(&case.scene, &case.rules, &armed(&case.opts)) {
            Ok(r) if r.scene.is_some() && done % 2 == 1 => {
                let s = r.scene.expect("scene");
                let j: Value = serde_json::from_str(&to_json(&e)).expect("json");
                grid_values(&j, &s)
            }
            _ => e
                .model
                .vars
                .iter()
                .map(|v| rng.random_range(0..=v.ub))
                .collect(),
        };
        let d = definitions_only(&e, &vals);
        let p = peers::solve(peer, &d, Duration::from_secs(10))
            .unwrap_or_else(|m| panic!("case {}: {m}", case.index));
        assert_eq!(
            (p.status, p.objective),
            (PeerStatus::Optimal, Some(0)),
            "{peer} case {}: the definitions disagree at {vals:?}",
            case.index
        );
        assert_eq!(p.values.as_deref(), Some(&vals[..]));
    }
    assert!(with_at_least >= n / 4, "{with_at_least} with at_least");
    eprintln!("{peer}: definitions agree on {n} models ({with_at_least} with at_least)");
}

#[test]
#[ignore = "needs MiniZinc/Gecode and python3: run by .ci/run"]
fn gecode_agrees_with_rccpack() {
    let mut cases: Vec<Case> = (0..55).map(random_case).collect();
    cases.extend((GROUP_CASES..GROUP_CASES + 15).map(random_case));
    cases.extend(infeasible_cases());
    cases.extend(turning_cases(10, 4));
    against_peer(Peer::Gecode, &cases, Duration::from_secs(10));
    definitions_agree(Peer::Gecode, 1000, 30);
    // Group statements as MiniZinc reachability (`--emit F.mzn`).
    let mut groups: Vec<Case> = (GROUP_CASES..GROUP_CASES + 15).map(random_case).collect();
    groups.extend(infeasible_cases());
    against_peer_with(
        Peer::Gecode,
        &groups,
        Duration::from_secs(10),
        rccpack::synth::emit::emitted_for_minizinc,
    );
}

#[test]
#[ignore = "needs CP-SAT (python3 with ortools): run by .ci/run"]
fn cpsat_agrees_with_rccpack() {
    let mut cases: Vec<Case> = (200..222).map(random_case).collect();
    cases.extend((GROUP_CASES + 100..GROUP_CASES + 108).map(random_case));
    cases.extend(infeasible_cases());
    cases.extend(turning_cases(12, 6));
    against_peer(Peer::CpSat, &cases, Duration::from_secs(10));
    definitions_agree(Peer::CpSat, 2000, 12);
}

/// A peer's failure is an error naming it, never a panic.
#[test]
fn peer_errors_are_errors() {
    let case = random_case(0);
    let e = emitted(&case.scene, &case.rules, &case.opts).expect("usable");
    for peer in Peer::ALL {
        assert!(peer.script().is_file(), "{}", peer.script().display());
        assert_eq!(peer.name().parse::<Peer>(), Ok(peer));
        if peers::check_available(peer).is_err() {
            continue;
        }
        // A zero time limit: an answer, an error, but no panic.
        let _ = peers::solve(peer, &e, Duration::ZERO);
    }
    assert!("nope".parse::<Peer>().unwrap_err().contains("`nope`"));
}

/// `synth --emit`: the format follows the extension, the file is written
/// before the solve (which still runs), and a bad name or an unwritable
/// path is exit 1 with a message naming the file.
#[test]
fn cli_emit_writes_the_model() {
    let dir = crate::support::scratch("emit-cli");
    let ex = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/box-packing");
    let run = |emit: &std::path::Path| {
        crate::support::command()
            .args(["synth", &format!("{ex}/problem.json"), "--rules"])
            .arg(format!("{ex}/pilot.rcc"))
            .arg("--quiet")
            .arg("-o")
            .arg(dir.join("sol.json"))
            .arg("--emit")
            .arg(emit)
            .output()
            .expect("runs")
    };
    let json = dir.join("model.json");
    let o = run(&json);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: Value =
        serde_json::from_str(&std::fs::read_to_string(&json).expect("written")).expect("json");
    assert_eq!(j["format"], FORMAT);
    assert!(dir.join("sol.json").is_file(), "the solve still runs");
    let mzn = dir.join("model.MZN");
    assert!(run(&mzn).status.success());
    assert!(std::fs::read_to_string(&mzn)
        .expect("written")
        .contains("solve maximize obj;"));
    for bad in [
        dir.join("model.txt"),
        dir.join("no-such-dir").join("m.json"),
    ] {
        let o = run(&bad);
        assert_eq!(o.status.code(), Some(1));
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(&bad.display().to_string()), "{err}");
        assert!(err.starts_with("error: "), "{err}");
        assert!(!bad.exists());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Hardening, third pass: `--emit F.mzn` of a group statement grows with the
/// contact edges (about the square of the objects), not with their cube as
/// the circuit of `and` nodes does (165 MB of MiniZinc for 120 objects).
/// Sizes as ratios between 20 and 40 objects of one group.
#[test]
fn a_group_statement_emits_to_minizinc_in_quadratic_size() {
    let size = |n: usize, compact: bool| -> usize {
        let objects: Vec<Object> = (0..n)
            .map(|i| Object {
                id: format!("r{i}"),
                class: "R".into(),
                x: None,
                y: None,
                width: 10,
                height: 10,
                fixed: false,
                turnable: false,
                turned: false,
            })
            .collect();
        let scene = Scene {
            space: Space {
                x: 0,
                y: 0,
                width: 200,
                height: 200,
            },
            grid: 10,
            objects,
        };
        let rules = rccpack::rules::parse_rules("rule g: group(R)\n").unwrap();
        let opts = SynthOptions::default();
        let e = if compact {
            rccpack::synth::emit::emitted_for_minizinc(&scene, &rules, &opts)
        } else {
            emitted(&scene, &rules, &opts)
        }
        .expect("usable");
        to_minizinc(&e).len()
    };
    let (c20, c40) = (size(20, true), size(40, true));
    let (k20, k40) = (size(20, false), size(40, false));
    let growth = |a: usize, b: usize| b as f64 / a as f64;
    assert!(growth(c20, c40) < 5.0, "compact: {c20} -> {c40}");
    assert!(growth(k20, k40) > 6.0, "circuit: {k20} -> {k40}");
    assert!(c40 * 5 < k40, "compact {c40}, circuit {k40}");
}
