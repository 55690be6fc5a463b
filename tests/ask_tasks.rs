//! The question loop (docs/guide.md#questions) on generated tasks with a known ground truth.
//!
//! Each task is a box of four fixed walls (class W, ids `w_south`,
//! `w_north`, `w_west`, `w_east`, interior 60×60) in a 100×100 space on grid
//! 10, with 10×10 blocks of two or three classes and a ground-truth rule set
//! of 4–7 rules. Eight demonstrations are synthesised: the ground truth
//! hard, plus a random soft target (resemblance to a scene of random block
//! positions, `SynthOptions::like`), each on a random object mix. The
//! problem is the walls with unplaced blocks.
//!
//! The question loop runs with the ground truth as the oracle (a probe is
//! acceptable iff every ground-truth rule holds for every object), at most
//! [`MAX_QUESTIONS`] questions. Then, per task:
//!
//! - (a) every rule still held is implied by the ground truth: ground truth
//!   hard + the rule's negation hard is infeasible, on the problem and on a
//!   few random object mixes;
//! - (b) every ground-truth rule is implied by the held rules on the
//!   problem: held rules hard + the ground-truth rule's negation hard is
//!   infeasible;
//! - (c) synthesis with the held rules (soft, as learned) and the
//!   demonstrations as like-scenes gives a layout keeping the ground truth.
//!
//! `cargo test --test integration ask_tasks:: -- --nocapture` prints one table row per
//! task.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rccpack::ask::{negation, AskOptions, Asker, ProbeOptions, QuestionBudget};
use rccpack::eval::evaluate;
use rccpack::infer::LearnParams;
use rccpack::relations::Contact;
use rccpack::resemblance::ResemblanceTarget;
use rccpack::rules::{parse_rules, Rule, RuleSet, Strength};
use rccpack::scene::{Object, Scene, Space};
use rccpack::synth::{synthesize, Status, SynthOptions};
use std::time::{Duration, Instant};

const MAX_QUESTIONS: usize = 60;
const CONTACT: Contact = Contact::Point;
const SOLVE_LIMIT: Duration = Duration::from_secs(10);

/// One generated task.
#[derive(Clone, Copy)]
struct Task {
    name: &'static str,
    /// Block classes with the range of counts per demonstration.
    classes: &'static [(&'static str, u32, u32)],
    /// Blocks per class in the problem.
    problem_counts: &'static [u32],
    seed: u64,
}

const INSIDE_R: &str = "rule red_inside: !DR_N(R, W) & !DR_S(R, W) & !DR_E(R, W) & !DR_W(R, W)\n";
const INSIDE_B: &str = "rule blue_inside: !DR_N(B, W) & !DR_S(B, W) & !DR_E(B, W) & !DR_W(B, W)\n";
const INSIDE_G: &str = "rule green_inside: !DR_N(G, W) & !DR_S(G, W) & !DR_E(G, W) & !DR_W(G, W)\n";

/// Every task with its ground truth (`.rcc`).
fn tasks() -> Vec<(Task, String)> {
    let t = |name, extra: &str, inside: &[&str], classes, problem_counts, seed| {
        let truth = format!("{}{extra}", inside.concat());
        (
            Task {
                name,
                classes,
                problem_counts,
                seed,
            },
            truth,
        )
    };
    vec![
        t(
            "stack",
            "rule blue_north_of_red: DR_N(B, R)\n\
             rule red_touches_red: EC_N(R, R) | EC_S(R, R) | EC_E(R, R) | EC_W(R, R)\n\
             rule some_red_on_floor: some R: EC_N(R, @w_south)\n",
            &[INSIDE_R, INSIDE_B],
            &[("R", 2, 3), ("B", 1, 3)],
            &[3, 2],
            1,
        ),
        t(
            "row",
            "rule green_east_of_red: DR_E(G, R)\n\
             rule red_row: AL_S(R, every R) & AL_N(R, every R)\n\
             rule red_on_floor: EC_N(R, @w_south)\n\
             rule green_touches_green: EC_N(G, G) | EC_S(G, G) | EC_E(G, G) | EC_W(G, G)\n",
            &[INSIDE_R, INSIDE_G],
            &[("R", 1, 3), ("G", 2, 3)],
            &[3, 2],
            2,
        ),
        t(
            "apart",
            "rule red_apart_from_blue: EC_N(R, no B) & EC_S(R, no B) & EC_E(R, no B) & EC_W(R, no B)\n\
             rule blue_by_west_wall: some B: EC_E(B, @w_west)\n\
             rule red_touches_red: EC_N(R, R) | EC_S(R, R) | EC_E(R, R) | EC_W(R, R)\n",
            &[INSIDE_R, INSIDE_B],
            &[("R", 2, 3), ("B", 1, 3)],
            &[2, 3],
            3,
        ),
        t(
            "three",
            "rule blue_north_of_red: DR_N(B, R)\n\
             rule green_east_of_red: DR_E(G, R)\n\
             rule green_on_east_wall: EC_W(G, @w_east)\n",
            &[INSIDE_R, INSIDE_G, INSIDE_B],
            &[("R", 1, 2), ("G", 1, 2), ("B", 1, 2)],
            &[2, 2, 2],
            4,
        ),
    ]
}

fn walls() -> Vec<Object> {
    [
        ("w_south", 10, 10, 80, 10),
        ("w_north", 10, 80, 80, 10),
        ("w_west", 10, 20, 10, 60),
        ("w_east", 80, 20, 10, 60),
    ]
    .into_iter()
    .map(|(id, x, y, w, h)| Object::fixed_at(id, "W", x, y, w, h))
    .collect()
}

/// The walls and unplaced blocks, `counts[i]` of class `classes[i]`.
fn mix(classes: &[(&str, u32, u32)], counts: &[u32]) -> Scene {
    let mut objects = walls();
    for (&(class, _, _), &n) in classes.iter().zip(counts) {
        for i in 0..n {
            objects.push(Object::movable(
                &format!("{}{}", class.to_lowercase(), i + 1),
                class,
                10,
                10,
            ));
        }
    }
    Scene {
        space: Space {
            x: 0,
            y: 0,
            width: 100,
            height: 100,
        },
        grid: 10,
        objects,
    }
}

fn random_mix(task: &Task, rng: &mut ChaCha8Rng) -> Scene {
    let counts: Vec<u32> = task
        .classes
        .iter()
        .map(|&(_, lo, hi)| rng.random_range(lo..=hi))
        .collect();
    mix(task.classes, &counts)
}

/// The scene with every block at a random grid position (overlaps allowed:
/// only its positions are used, as a soft target).
fn random_positions(scene: &Scene, rng: &mut ChaCha8Rng) -> Scene {
    let mut s = scene.clone();
    for o in s.objects.iter_mut().filter(|o| !o.fixed) {
        o.x = Some(10 * rng.random_range(0..10));
        o.y = Some(10 * rng.random_range(0..10));
    }
    s
}

fn hard(rules: &[Rule]) -> Vec<Rule> {
    rules
        .iter()
        .map(|r| Rule {
            strength: Strength::Hard,
            comments: Vec::new(),
            ..r.clone()
        })
        .collect()
}

fn all_hold(scene: &Scene, rules: &RuleSet) -> bool {
    evaluate(scene, rules, CONTACT)
        .rules
        .iter()
        .all(|r| r.satisfied == r.subjects)
}

fn solve(
    scene: &Scene,
    rules: &RuleSet,
    like: Option<ResemblanceTarget>,
    seed: u64,
) -> rccpack::synth::SynthResult {
    let opts = SynthOptions {
        contact: CONTACT,
        explain: false,
        stop: rccpack::stop::Stop::after(SOLVE_LIMIT),
        seed,
        like,
        ..SynthOptions::default()
    };
    synthesize(scene, rules, &opts).expect("a usable problem")
}

/// The blocks' positions, `id(x,y)`.
fn positions(s: &Scene) -> String {
    s.objects
        .iter()
        .filter(|o| !o.fixed)
        .map(|o| format!("{}({},{})", o.id, o.x.unwrap_or(-1), o.y.unwrap_or(-1)))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A layout of `scene` keeping `premises` and breaking `r`, if any.
fn counterexample(premises: &[Rule], r: &Rule, scene: &Scene) -> Option<Scene> {
    let mut rules = hard(premises);
    rules.push(negation(r)?);
    solve(scene, &RuleSet::new(rules), None, 0).scene
}

/// Whether `premises` (hard) with `negation(r)` (hard) is infeasible on
/// `scene`: `Ok(true)` implied, `Ok(false)` a counterexample, `Err` a limit.
fn implies(premises: &[Rule], r: &Rule, scene: &Scene) -> Result<bool, String> {
    let Some(neg) = negation(r) else {
        return Ok(true);
    };
    let mut rules = hard(premises);
    rules.push(neg);
    let res = solve(scene, &RuleSet::new(rules), None, 0);
    match res.status {
        Status::Infeasible => Ok(true),
        Status::Optimal | Status::Feasible => Ok(false),
        Status::Unknown => Err(format!("time-out ({SOLVE_LIMIT:?}) deciding `{}`", r.name)),
    }
}

/// What one task's run gave.
#[derive(Debug, Default)]
struct Outcome {
    questions: usize,
    dropped: usize,
    confirmed: usize,
    implied: usize,
    unknown: usize,
    held_before: usize,
    held_after: usize,
    secs: f64,
    /// (a): held rules not implied by the ground truth.
    a_fail: Vec<String>,
    /// (a) in detail: where the counterexample is, and whether the rule
    /// was confirmed (by a rejected probe).
    a_detail: Vec<String>,
    /// (a) failures of rules never confirmed (held because "implied").
    a_fail_unconfirmed: Vec<String>,
    /// (b): ground-truth rules not implied by the held rules.
    b_fail: Vec<String>,
    /// Implication checks stopped by the time limit (each a failure).
    timeouts: Vec<String>,
    /// Names of the ground-truth rules not learned at first.
    gt_not_learned_names: Vec<String>,
    /// (c): ground-truth rules broken by synthesis from the held rules.
    c_fail: Vec<String>,
    /// Ground-truth rules not learned at first (by name: the learner may
    /// learn an equivalent statement under another name).
    gt_not_learned_first: Vec<String>,
    /// One line per question.
    log: Vec<String>,
    /// The held rules at the end.
    held: RuleSet,
    /// The problem.
    problem: Option<Scene>,
}

/// The task's demonstrations (synthesised with the truth hard), its
/// problem and the loop's options.
fn setup(task: &Task, truth: &RuleSet, rng: &mut ChaCha8Rng) -> (Scene, Vec<Scene>, AskOptions) {
    let truth_hard = RuleSet::new(hard(&truth.rules));
    // Demonstrations.
    let mut demos = Vec::new();
    for d in 0..8 {
        let m = random_mix(task, rng);
        let like = ResemblanceTarget::new(&[random_positions(&m, rng)]);
        let r = solve(&m, &truth_hard, Some(like), d);
        let s = r
            .scene
            .unwrap_or_else(|| panic!("task {}: demonstration {d}: {:?}", task.name, r.status));
        assert!(
            all_hold(&s, truth),
            "task {}: demo {d} breaks the truth",
            task.name
        );
        demos.push(s);
    }
    let problem = mix(task.classes, task.problem_counts);
    let opts = AskOptions {
        learn: LearnParams {
            samples: 300,
            contact: CONTACT,
            ..LearnParams::default()
        },
        probe: ProbeOptions {
            contact: CONTACT,
            solve_time: Some(SOLVE_LIMIT),
            ..ProbeOptions::default()
        },
        resemble: true,
        ..AskOptions::default()
    };
    (problem, demos, opts)
}

fn run_task(task: &Task, truth_text: &str, mixes: usize) -> Outcome {
    let start = Instant::now();
    let truth = parse_rules(truth_text).expect("ground truth parses");
    let mut rng = ChaCha8Rng::seed_from_u64(task.seed);
    let (problem, demos, opts) = setup(task, &truth, &mut rng);
    let mut asker = Asker::new(problem.clone(), demos, None, Vec::new(), opts).expect("asker");
    let mut out = Outcome {
        held_before: asker.held().rules.len(),
        ..Outcome::default()
    };
    // Which truth rules were learned at first (identical formula and scope).
    for g in &truth.rules {
        let learned = asker
            .held()
            .rules
            .iter()
            .any(|h| h.scope == g.scope && h.formula == g.formula);
        if !learned {
            // Why: the template statement of the same form, if any.
            let why = match asker
                .learned()
                .statements
                .iter()
                .find(|s| s.scope == g.scope && s.formula == g.formula)
            {
                None => "no such template statement".to_string(),
                Some(s) => match (&s.broken_by, s.posterior) {
                    (Some(b), _) => format!("`{}` broken by demo {}", s.name, b.demo),
                    (None, Some(p)) => format!(
                        "`{}` q = {:.3}, log10 P = {:.2}, implied by {:?}",
                        s.name,
                        s.q.unwrap_or(0.0),
                        p.log10_posterior,
                        s.implied_by
                    ),
                    (None, None) => format!("`{}` not a candidate", s.name),
                },
            };
            out.gt_not_learned_first.push(format!("{} ({why})", g.name));
            out.gt_not_learned_names.push(g.name.clone());
        }
    }
    while let Some(q) = asker.next_question().expect("next question") {
        if asker.progress().asked >= MAX_QUESTIONS {
            break;
        }
        let ok = all_hold(&q.probe.scene, &truth);
        let broken: Vec<String> = evaluate(&q.probe.scene, &truth, CONTACT)
            .rules
            .iter()
            .filter(|r| r.satisfied != r.subjects)
            .map(|r| r.name.clone())
            .collect();
        // A truth rule the probe breaks is never implied by the held rules
        // the probe keeps: all but the probed one and the rules equivalent
        // to it on the problem, which it breaks too (`also_broken`; else
        // the probe could not exist).
        let others: Vec<Rule> = asker
            .held()
            .rules
            .iter()
            .filter(|r| r.name != q.rule && !q.also_broken.contains(&r.name))
            .cloned()
            .collect();
        let broken: Vec<String> = broken
            .into_iter()
            .map(|name| {
                let g = truth
                    .rules
                    .iter()
                    .find(|g| g.name == name)
                    .expect("a truth rule");
                let implied = implies(&others, g, &problem);
                assert_ne!(
                    implied,
                    Ok(true),
                    "the probe breaks `{name}`, implied by the held rules"
                );
                name
            })
            .collect();
        out.log.push(format!(
            "{} `{}`: {} (truth broken: {broken:?})",
            if ok { "accepted" } else { "rejected" },
            q.rule,
            q.statement
        ));
        asker.answer(&q, ok).expect("answer");
    }
    let p = asker.progress();
    out.questions = p.asked;
    out.dropped = p.dropped;
    out.confirmed = p.confirmed;
    out.implied = p.implied;
    out.unknown = p.unknown;
    out.held_after = p.held;
    let held = asker.held().clone();
    // (a)
    let mut scenes = vec![problem.clone()];
    for _ in 0..mixes {
        scenes.push(random_mix(task, &mut rng));
    }
    for r in &held.rules {
        for (i, s) in scenes.iter().enumerate() {
            let where_ = if i == 0 {
                "problem".to_string()
            } else {
                format!("mix {i}")
            };
            match implies(&truth.rules, r, s) {
                Ok(true) => {}
                Ok(false) => {
                    // Confirmed, or implied here by the confirmed rules
                    // (a group statement the person kept settles "every R
                    // touches another R" with it): settled by an answer.
                    let confirmed_rules: Vec<Rule> = held
                        .rules
                        .iter()
                        .filter(|h| h.name != r.name && asker.is_confirmed(&h.name))
                        .cloned()
                        .collect();
                    let confirmed = asker.is_confirmed(&r.name)
                        || (!confirmed_rules.is_empty()
                            && implies(&confirmed_rules, r, s) == Ok(true));
                    out.a_fail.push(r.name.clone());
                    let ce = counterexample(&truth.rules, r, s)
                        .map(|c| positions(&c))
                        .unwrap_or_default();
                    let how = if asker.is_confirmed(&r.name) {
                        "confirmed"
                    } else if confirmed {
                        "implied by confirmed rules"
                    } else {
                        "not confirmed"
                    };
                    out.a_detail.push(format!(
                        "{} ({where_}; {how}; the truth keeps and the rule breaks: {ce})",
                        r.name
                    ));
                    if !confirmed {
                        out.a_fail_unconfirmed.push(r.name.clone());
                    }
                    break;
                }
                Err(e) => {
                    out.timeouts.push(format!("(a) {} ({where_}): {e}", r.name));
                    break;
                }
            }
        }
    }
    // (b)
    for g in &truth.rules {
        match implies(&held.rules, g, &problem) {
            Ok(true) => {}
            Ok(false) => out.b_fail.push(g.name.clone()),
            Err(e) => out.timeouts.push(format!("(b) {}: {e}", g.name)),
        }
    }
    // (c)
    let like = ResemblanceTarget::new(asker.demos());
    let r = solve(&problem, &held, Some(like), 0);
    match r.scene {
        Some(s) => {
            let ev = evaluate(&s, &truth, CONTACT);
            for rr in &ev.rules {
                if rr.satisfied != rr.subjects {
                    out.c_fail.push(rr.name.clone());
                }
            }
        }
        None => out.c_fail.push(format!("no layout: {:?}", r.status)),
    }
    out.held = held.clone();
    out.problem = Some(problem.clone());
    out.secs = start.elapsed().as_secs_f64();
    eprintln!(
        "| {:<6} | {:>3} asked | {:>2} dropped | {:>2} confirmed | {:>2} implied | {:>2} unknown | held {:>2} → {:>2} | {:>5.1} s | (a) {:?} | (b) {:?} | (c) {:?} | truth not learned at first: {:?}",
        task.name,
        out.questions,
        out.dropped,
        out.confirmed,
        out.implied,
        out.unknown,
        out.held_before,
        out.held_after,
        out.secs,
        out.a_detail,
        out.b_fail,
        out.c_fail,
        out.gt_not_learned_first,
    );
    for l in &out.log {
        eprintln!("    {l}");
    }
    for r in &held.rules {
        eprintln!(
            "    {} {}: {}",
            if asker.is_confirmed(&r.name) {
                "C"
            } else {
                " "
            },
            r.name,
            rccpack::infer::statement_text(r.scope, &r.formula)
        );
    }
    out
}

fn run(name: &str, mixes: usize) -> Outcome {
    let (task, truth) = tasks()
        .into_iter()
        .find(|(t, _)| t.name == name)
        .expect("a task");
    run_task(&task, &truth, mixes)
}

/// What must hold on every task, known failures or not: (c) for every
/// truth rule the held rules imply (a rule that is neither learned nor
/// implied — a known failure of (b) — has no claim on synthesis: whether
/// the layout keeps it depends on which of the equally good layouts comes
/// back); no time-out; a held rule not implied by the truth (a) is one a
/// rejected probe confirmed; a truth rule not implied by the held rules
/// (b) is one the learner did not learn in the first place; the budget was
/// not exhausted.
fn check_generic(o: &Outcome) {
    for c in &o.c_fail {
        assert!(
            o.b_fail.contains(c) && o.gt_not_learned_names.contains(c),
            "(c) `{c}` {o:#?}"
        );
    }
    assert!(o.timeouts.is_empty(), "{o:#?}");
    assert!(o.a_fail_unconfirmed.is_empty(), "(a) {o:#?}");
    for b in &o.b_fail {
        assert!(o.gt_not_learned_names.contains(b), "(b) `{b}` {o:#?}");
    }
    assert!(o.questions < MAX_QUESTIONS, "{o:#?}");
    assert!(o.questions > 0, "{o:#?}");
}

fn names(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

/// Known failure of (a). The learner does not learn the truth's
/// `some R: EC_N(R, @w_south)` (no template says "some red sits on the
/// floor"), but it learns the habit `R_ec_n_any: EC_N(R, *)` (every red sits
/// on something). The probe for the habit lifts a red off everything and,
/// keeping only the held rules, leaves no red on the floor: it breaks the
/// truth's `some_red_on_floor`. The oracle rejects it, and the rejection
/// confirms the habit (docs/guide.md#questions: a rejected probe confirms the rule it
/// asks about), although the truth does not imply it: the truth allows a
/// red that rests on nothing and only touches another red beside it (the
/// run prints one: `r1(20,20) r2(30,30) r3(40,30) b1(20,40) b2(30,40)`, r3
/// floats). The question loop cannot
/// tell "rejected because of this rule" from "rejected because of another
/// intended rule the learner does not have".
///
/// Which probe the question shows decides it: with probes that are edits
/// of the demonstrations the one for `R_ec_n_any` keeps the truth, is
/// accepted and the habit is dropped, so (a) may also come out clean.
#[test]
fn task_stack() {
    let o = run("stack", 2);
    check_generic(&o);
    assert!(o.a_fail.iter().all(|n| n == "R_ec_n_any"), "{o:#?}");
    assert!(o.b_fail.is_empty(), "{o:#?}");
}

#[test]
fn task_row() {
    let o = run("row", 2);
    check_generic(&o);
    assert!(o.a_fail.is_empty() && o.b_fail.is_empty(), "{o:#?}");
}

/// Known failure of (b): the truth's `red_apart_from_blue` is the template
/// `R_apart_B`, but it is not learned from these eight demonstrations: in
/// the null model's random scenes a red seldom touches a blue anyway (q ≈
/// 0.90), so eight demonstrations are no evidence (log10 P ≈ −1, cutoff
/// 0.01). Questions only drop or confirm learned rules, so the loop cannot
/// bring it back. (c) for it is luck: with the resemblance clauses alone
/// the final layout kept it; with the bounds propagator beside them
/// another layout of the same score and resemblance cost 0
/// comes back — each object at a position some demonstration showed (the
/// resemblance cost does not match objects one to one) — and a blue
/// touches a red. Every other truth rule is kept. The same rule never
/// learned is the known cause of (a) here: a probe for the habit `B_row`
/// may put a blue against a red (nothing held forbids it), the oracle
/// rejects it for that, and the rejection confirms `B_row` (as in
/// `task_stack`, the loop cannot tell why a probe was rejected). With the
/// third-edition templates the same happens to the habit `R_one_group`
/// (the two reds touch flush in every demonstration; its probe may put a
/// red against a blue), and the rules it implies on the problem
/// (`R_touches_flush_R`, `R_touches_flush_any`) are settled with it.
#[test]
fn task_apart() {
    let o = run("apart", 2);
    check_generic(&o);
    let known = [
        "B_row",
        "R_one_group",
        "R_touches_flush_R",
        "R_touches_flush_any",
    ];
    assert!(
        o.a_fail.iter().all(|n| known.contains(&n.as_str())),
        "{o:#?}"
    );
    assert_eq!(o.b_fail, names(&["red_apart_from_blue"]), "{o:#?}");
    assert!(
        o.c_fail.iter().all(|c| c == "red_apart_from_blue"),
        "(c) {o:#?}"
    );
}

#[test]
fn task_three() {
    let o = run("three", 2);
    check_generic(&o);
    assert!(o.a_fail.is_empty() && o.b_fail.is_empty(), "{o:#?}");
}

/// Every task on more seeds (other demonstrations) and more object mixes
/// for (a): prints the table and a summary; asserts only that no check
/// timed out (the other properties fail now and then for the reasons the
/// known failures above document).
#[test]
#[ignore = "slower: cargo test --release --test integration ask_tasks:: -- --ignored --nocapture"]
fn tasks_on_many_seeds() {
    let mut total = [0usize; 4];
    let mut runs = 0;
    for (task, truth) in tasks() {
        for seed in 100..110 {
            let t = Task { seed, ..task };
            let o = run_task(&t, &truth, 6);
            assert!(o.timeouts.is_empty(), "{o:#?}");
            runs += 1;
            total[0] += usize::from(!o.a_fail.is_empty());
            total[1] += usize::from(!o.a_fail_unconfirmed.is_empty());
            total[2] += usize::from(!o.b_fail.is_empty());
            total[3] += usize::from(!o.c_fail.is_empty());
        }
    }
    eprintln!(
        "{runs} runs: (a) fails in {} ({} with an unconfirmed rule), (b) in {}, (c) in {}",
        total[0], total[1], total[2], total[3]
    );
}

/// Found by this test: held habits that imply one another on the problem
/// — `R_dr_s_G: DR_S(R, G)` and `G_dr_n_R: DR_N(G, R)` (the same statement
/// from either side; the syntactic `rule_implies` does not see it) — each
/// got `Implied` from the engine because the other was kept hard in its
/// probe, so neither was ever asked and both stayed held, though the truth
/// allows a green beside the reds on the floor. The question loop now asks
/// about rules equivalent on the problem as one (`Question::also_broken`).
/// (Seed 101 of the `row` task.)
#[test]
fn mutually_implied_habits_are_asked_as_one() {
    let (task, truth) = tasks()
        .into_iter()
        .find(|(t, _)| t.name == "row")
        .expect("a task");
    let o = run_task(&Task { seed: 101, ..task }, &truth, 0);
    for name in ["R_dr_s_G", "G_dr_n_R"] {
        assert!(!o.a_fail_unconfirmed.iter().any(|n| n == name), "{o:#?}");
        assert!(!o.held.rules.iter().any(|r| r.name == name), "{o:#?}");
    }
    assert!(o.c_fail.is_empty(), "{o:#?}");
}

/// Reusing what earlier checks found (`AskOptions::reuse`: the pool of
/// layouts, the proofs for fewer premises, the implications kept across
/// relearning) changes how fast the questions come, not which: on every
/// task the same questions, probes and answers, and the same rules held
/// at the end, as with every check a solve.
#[test]
fn reuse_asks_the_same_questions() {
    for (task, truth_text) in tasks() {
        let truth = parse_rules(&truth_text).expect("ground truth parses");
        let mut rng = ChaCha8Rng::seed_from_u64(task.seed);
        let (problem, demos, opts) = setup(&task, &truth, &mut rng);
        let transcript = |reuse: bool| {
            // Without a question budget: what reuse settles costs no
            // search, so under a budget it changes which checks the budget
            // reaches (the budget's own determinism is tested in
            // `tests/ask_budget.rs`).
            let opts = AskOptions {
                reuse,
                budget: QuestionBudget {
                    nodes: u64::MAX,
                    wall: None,
                },
                ..opts.clone()
            };
            let mut asker =
                Asker::new(problem.clone(), demos.clone(), None, Vec::new(), opts).expect("asker");
            let mut out = Vec::new();
            while let Some(q) = asker.next_question().expect("next question") {
                if asker.progress().asked >= MAX_QUESTIONS {
                    break;
                }
                let ok = all_hold(&q.probe.scene, &truth);
                asker.answer(&q, ok).expect("answer");
                out.push((q, ok));
            }
            (out, asker.learned_rcc(), asker.progress())
        };
        let (off, on) = (transcript(false), transcript(true));
        assert!(!off.0.is_empty(), "task {}: no question", task.name);
        assert_eq!(off.0.len(), on.0.len(), "task {}", task.name);
        for ((a, x), (b, y)) in off.0.iter().zip(&on.0) {
            assert_eq!(
                (&a.rule, &a.also_broken, &a.probe.scene, x),
                (&b.rule, &b.also_broken, &b.probe.scene, y),
                "task {}",
                task.name
            );
        }
        assert_eq!(off.1, on.1, "task {}", task.name);
        assert_eq!(off.2, on.2, "task {}", task.name);
    }
}
