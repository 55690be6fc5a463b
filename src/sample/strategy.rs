//! Strategies for property tests (`--features proptest`).
//!
//! * [`demo_scenes`] — (a) scenes from the demonstrations' distribution:
//!   the learner's null model (docs/guide.md#learning) re-places the movable objects of
//!   a demonstration at random; optionally only the objects that keep given
//!   rules stay.
//! * [`layouts`] — (b) layouts of one problem that keep given rules, drawn
//!   by [`crate::sample::sample()`].
//! * [`ruleset_strategy`], [`formula_strategy`] and their parts — (c) rule
//!   sets and formulas of the `.rcc` language (the strategies the
//!   project's own parser tests use).
//!
//! # Shrinking
//!
//! Every shrunk value is as valid as the first one (a test checks every
//! step of the shrinking):
//!
//! * a demonstration-like scene shrinks by dropping movable objects (each
//!   kept with probability 9/10 at first; shrinking drops them), towards
//!   the first demonstration and towards seed 0. Dropping objects keeps a
//!   scene valid; with rules to keep, objects that break a rule are dropped
//!   again after every step (and scenes whose scene-level hard rules fail
//!   are rejected), so every value keeps them;
//! * a layout of a problem must place every object of the problem, so it
//!   cannot lose objects: it shrinks towards **simpler layouts of the same
//!   pool** — the pool of `n` distinct sampled layouts is sorted by the sum
//!   of the objects' grid coordinates (smallest first: objects towards the
//!   space's origin), and the strategy picks an index that shrinks towards
//!   0. Every candidate is a sampled, verified layout;
//! * rule sets shrink to fewer rules and smaller formulas (proptest's
//!   collection and recursion shrinking).

use crate::eval::evaluate;
use crate::infer::NullModel;
use crate::relations::{Contact, Quant, Relation};
use crate::rules::{Atom, Formula, Rule, RuleSet, Scope, Strength, Target};
use crate::sample::{sample, SampleError, SampleOptions};
use crate::scene::Scene;
use proptest::prelude::*;

// ---- (a) scenes like the demonstrations ----------------------------------

/// Scenes from the demonstrations' distribution (the null model of
/// docs/guide.md#learning; see the module documentation for shrinking). With `keep`, only
/// objects that keep those rules (evaluated with that contact mode) stay,
/// and scenes whose scene-level hard rules fail are rejected.
///
/// `demos` must be non-empty complete scenes whose movable objects fit the
/// space (as for learning); otherwise the strategy rejects every value.
pub fn demo_scenes(
    demos: Vec<Scene>,
    keep: Option<(RuleSet, Contact)>,
) -> impl Strategy<Value = Scene> {
    let d = demos.len().max(1);
    let most = demos.iter().map(|s| s.objects.len()).max().unwrap_or(0);
    (
        any::<u64>(),
        0..d,
        proptest::collection::vec(proptest::bool::weighted(0.9), most),
    )
        .prop_filter_map("no scene", move |(seed, index, mask)| {
            let null = NullModel::new(&demos, seed).ok()?;
            let mut scene = null.scene(index).ok()?;
            let mut i = 0;
            scene.objects.retain(|o| {
                let k = o.fixed || mask.get(i).copied().unwrap_or(true);
                i += 1;
                k
            });
            if let Some((rules, contact)) = &keep {
                keep_rules(&mut scene, rules, *contact)?;
            }
            Some(scene)
        })
}

/// Drop movable objects that break a rule until none does; `None` when a
/// scene-level hard rule fails or a fixed object breaks a rule.
fn keep_rules(scene: &mut Scene, rules: &RuleSet, contact: Contact) -> Option<()> {
    loop {
        let e = evaluate(scene, rules, contact);
        let bad: std::collections::BTreeSet<&str> = e
            .rules
            .iter()
            .flat_map(|r| r.violators.iter().map(String::as_str))
            .collect();
        let scene_fails = e.rules.iter().zip(&rules.rules).any(|(r, rule)| {
            rule.scope != Scope::Each && r.satisfied < r.subjects && r.violators.is_empty()
        });
        if bad.is_empty() && !scene_fails {
            return Some(());
        }
        if scene_fails
            || scene
                .objects
                .iter()
                .any(|o| o.fixed && bad.contains(o.id.as_str()))
        {
            return None;
        }
        let bad: Vec<String> = bad.into_iter().map(String::from).collect();
        scene.objects.retain(|o| !bad.contains(&o.id));
    }
}

// ---- (b) layouts that keep the rules ---------------------------------------

/// Layouts of `problem` that keep `rules` at the quality of `opts`: a pool
/// of up to `pool` distinct layouts is drawn by [`sample`] when the
/// strategy is made (fewer when fewer exist), sorted simplest first, and
/// the strategy picks one (shrinking towards the simplest; see the module
/// documentation). Errors: those of [`sample`], or no layout at all.
pub fn layouts(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SampleOptions,
    pool: usize,
) -> Result<impl Strategy<Value = Scene>, SampleError> {
    let mut found: Vec<Scene> = sample(problem, rules, opts)?
        .take(pool.max(1))
        .collect::<Result<_, _>>()?;
    if found.is_empty() {
        return Err(SampleError::LimitReached { found: 0 });
    }
    let g = problem.grid.max(1);
    let weight = |s: &Scene| -> i64 {
        s.objects
            .iter()
            .zip(&problem.objects)
            .filter(|(_, p)| !p.is_placed())
            .map(|(o, _)| {
                (o.x.unwrap_or(0) - problem.space.x) / g + (o.y.unwrap_or(0) - problem.space.y) / g
            })
            .sum()
    };
    found.sort_by_cached_key(|s| weight(s));
    let n = found.len();
    Ok((0..n).prop_map(move |i| found[i].clone()))
}

// ---- (c) rule sets ----------------------------------------------------------

/// Classes, including the quantifier words, which are not reserved (docs/language.md#syntax).
pub const CLASSES: [&str; 10] = [
    "B", "R", "G", "W", "no", "some", "every", "at", "least", "most",
];

/// Landmark ids, including quantifier words.
pub const LANDMARKS: [&str; 5] = ["w_west", "w1", "_x", "no", "at"];

/// Every quantifier, with the boundary counts 0 and 65 535.
pub fn quant_strategy() -> impl Strategy<Value = Quant> {
    prop_oneof![
        Just(Quant::Every),
        Just(Quant::Some),
        Just(Quant::No),
        prop_oneof![Just(0u32), Just(65_535u32), 0u32..=65_535].prop_map(Quant::AtLeast),
        prop_oneof![Just(0u32), Just(65_535u32), 0u32..=65_535].prop_map(Quant::AtMost),
    ]
}

/// Every scope: the ordinary rule or a scene-level one (never
/// `Scene(Every)`, which is `Each`).
pub fn scope_strategy() -> impl Strategy<Value = Scope> {
    prop_oneof![Just(Scope::Each), quant_strategy().prop_map(Scope::of)]
}

/// One atom over `subject`: any relation, an optional quantifier, a class,
/// `*` or a landmark target.
pub fn atom_strategy(subject: &'static str) -> impl Strategy<Value = Formula> {
    let target = prop_oneof![
        3 => prop::sample::select(CLASSES.to_vec()).prop_map(|c| Target::Class(c.to_string())),
        1 => Just(Target::Any),
        1 => prop::sample::select(LANDMARKS.to_vec()).prop_map(|l| Target::Landmark(l.to_string())),
    ];
    (
        prop::sample::select(Relation::ALL.to_vec()),
        prop::option::of(quant_strategy()),
        target,
    )
        .prop_map(move |(r, q, target)| {
            Formula::Atom(match (q, &target) {
                // A landmark takes no quantifier.
                (Some(q), Target::Class(_) | Target::Any) => {
                    Atom::quantified(r, subject, q, target)
                }
                _ => Atom::new(r, subject, target),
            })
        })
}

/// Flatten nested same-operator chains the way the parser does.
fn normalize(f: Formula) -> Formula {
    match f {
        Formula::Atom(_) | Formula::Shape(_) | Formula::Turned(_) => f,
        Formula::Not(g) => Formula::not(normalize(*g)),
        Formula::And(v) => {
            let mut out = Vec::new();
            for g in v {
                match normalize(g) {
                    Formula::And(w) => out.extend(w),
                    g => out.push(g),
                }
            }
            Formula::And(out)
        }
        Formula::Or(v) => {
            let mut out = Vec::new();
            for g in v {
                match normalize(g) {
                    Formula::Or(w) => out.extend(w),
                    g => out.push(g),
                }
            }
            Formula::Or(out)
        }
    }
}

/// Random formulas over one subject class, in the parser's normal form.
pub fn formula_strategy_for(subject: &'static str) -> impl Strategy<Value = Formula> {
    atom_strategy(subject)
        .prop_recursive(5, 40, 4, |inner| {
            prop_oneof![
                inner.clone().prop_map(Formula::not),
                prop::collection::vec(inner.clone(), 2..4).prop_map(Formula::And),
                prop::collection::vec(inner, 2..4).prop_map(Formula::Or),
            ]
        })
        .prop_map(normalize)
}

/// Random formulas over a random subject class, in the parser's normal form.
pub fn formula_strategy() -> impl Strategy<Value = Formula> {
    prop::sample::select(CLASSES.to_vec()).prop_flat_map(formula_strategy_for)
}

/// Rule strengths: weights (tiny to huge), posteriors, `hard`.
pub fn strength_strategy() -> impl Strategy<Value = Strength> {
    prop_oneof![
        Just(Strength::Weight(1.0)),
        (1e-300f64..1e300).prop_map(Strength::Weight),
        (0.0f64..1e6)
            .prop_filter("positive", |w| *w > 0.0)
            .prop_map(Strength::Weight),
        (0.0f64..1.0)
            .prop_filter("in (0,1)", |p| *p > 0.0)
            .prop_map(Strength::P),
        (-700.0f64..-1e-3).prop_map(|l| Strength::P(l.exp())),
        Just(Strength::Hard),
    ]
}

/// Random rule sets: unique names, random subjects, strengths, scopes and
/// formulas.
pub fn ruleset_strategy() -> impl Strategy<Value = RuleSet> {
    let rule = (0..CLASSES.len())
        .prop_flat_map(|s| {
            (
                formula_strategy_for(CLASSES[s]),
                strength_strategy(),
                scope_strategy(),
            )
        })
        .prop_map(|(f, s, q)| Rule::new("x", f).with_strength(s).with_scope(q));
    // Group statements: `column(R)`, `not block(G)`, ….
    let group = (
        prop::sample::select(crate::shapes::ShapeKind::ALL.to_vec()),
        prop::sample::select(CLASSES.to_vec()),
        any::<bool>(),
        strength_strategy(),
    )
        .prop_map(|(kind, class, negated, s)| {
            Rule::group("x", crate::rules::Shape::new(kind, class), negated).with_strength(s)
        });
    let rule = prop_oneof![5 => rule, 1 => group];
    (
        prop::collection::vec(rule, 0..6),
        prop::collection::vec("[a-z ]{0,20}", 0..6),
    )
        .prop_map(|(mut rules, comments)| {
            for (i, r) in rules.iter_mut().enumerate() {
                r.name = format!("rule_{i}");
                if let Some(c) = comments.get(i) {
                    r.comments = vec![c.clone()];
                }
            }
            RuleSet::new(rules)
        })
}
