//! The [`synth`] harness: a tiny structured problem and rules, coordinates
//! also extreme; on success `verify` passes and the score equals brute
//! force's optimum, on refusal a typed error.

use super::{rule_set, CLASSES};
use crate::eval::evaluate;
use crate::relations::Contact;
use crate::rules::{print_rules, RuleSet};
use crate::scene::{Object, Scene, Space};
use arbitrary::{Result as AResult, Unstructured};

/// Coordinates: mostly small, sometimes at or past the documented bounds.
fn coord(u: &mut Unstructured, small: i64) -> AResult<i64> {
    use crate::limits::MAX_SCENE_COORD as SCENE_MAX;
    use crate::synth::MAX_SYNTH_COORD as SYNTH_MAX;
    Ok(if u.ratio(7, 8)? {
        u.int_in_range(0..=small)?
    } else {
        *u.choose(&[
            SYNTH_MAX,
            SYNTH_MAX - 30,
            -SYNTH_MAX,
            SYNTH_MAX + 1,
            SCENE_MAX,
            -SCENE_MAX,
            SCENE_MAX + 1,
            i64::MAX,
            i64::MIN,
            -1,
        ])?
    })
}

fn size(u: &mut Unstructured, small: i64) -> AResult<i64> {
    Ok(if u.ratio(15, 16)? {
        u.int_in_range(1..=small)?
    } else {
        *u.choose(&[
            crate::synth::MAX_SYNTH_COORD,
            crate::synth::MAX_SYNTH_COORD + 1,
            crate::limits::MAX_SCENE_COORD,
            i64::MAX,
            0,
            -5,
        ])?
    })
}

fn problem(u: &mut Unstructured) -> AResult<Scene> {
    let space = Space {
        x: coord(u, 20)?,
        y: coord(u, 20)?,
        width: size(u, 60)?,
        height: size(u, 60)?,
    };
    let grid = if u.ratio(15, 16)? {
        *u.choose(&[1i64, 5, 10, 15, 20, 7])?
    } else {
        size(u, 60)?
    };
    let mut objects = Vec::new();
    for i in 0..u.int_in_range(0..=4)? {
        let class = *u.choose(&CLASSES)?;
        let kind = u.int_in_range(0..=5)?;
        let (w, h) = if u.ratio(3, 4)? {
            *u.choose(&[(10i64, 10i64), (20, 10), (10, 20), (5, 5), (15, 10)])?
        } else {
            (size(u, 40)?, size(u, 40)?)
        };
        let pos = match kind {
            // Fixed or already placed: a position relative to the space.
            0 | 1 => Some((
                space.x.saturating_add(coord(u, 50)?),
                space.y.saturating_add(coord(u, 50)?),
            )),
            _ => None,
        };
        objects.push(Object {
            id: format!("o{i}"),
            class: class.into(),
            x: pos.map(|p| p.0),
            y: pos.map(|p| p.1),
            width: w,
            height: h,
            fixed: kind == 0,
            turnable: false,
            turned: false,
        });
    }
    Ok(Scene {
        space,
        grid,
        objects,
    })
}

/// Whether every number is within synthesis's documented bound.
fn within_synth_bound(p: &Scene) -> bool {
    let m = crate::synth::MAX_SYNTH_COORD;
    let ok = |v: i64| v.unsigned_abs() <= m.unsigned_abs();
    let sp = p.space;
    ok(sp.x)
        && ok(sp.y)
        && ok(sp.width)
        && ok(sp.height)
        && ok(p.grid)
        && ok(sp.x.saturating_add(sp.width))
        && ok(sp.y.saturating_add(sp.height))
        && p.objects
            .iter()
            .all(|o| ok(o.width) && ok(o.height) && o.x.is_none_or(ok) && o.y.is_none_or(ok))
        && p.objects.iter().filter(|o| !o.is_placed()).all(|o| {
            let n = |space: i64, size: i64| {
                if space < size {
                    0
                } else {
                    (i128::from(space) - i128::from(size)) / i128::from(p.grid.max(1)) + 1
                }
            };
            let max = i128::from(crate::synth::MAX_POSITIONS);
            n(sp.width, o.width) <= max && n(sp.height, o.height) <= max
        })
}

/// One synthesis on a drawn problem and rule set, checked against the
/// validator, the bound, the solution checker, the evaluator, brute force
/// (when the positions are few) and a probe.
fn synth_inner(u: &mut Unstructured) -> AResult<()> {
    use crate::synth::{synthesize, SynthError};
    let p = problem(u)?;
    let fixed_ids: Vec<String> = p
        .objects
        .iter()
        .filter(|o| o.fixed)
        .map(|o| o.id.clone())
        .collect();
    let rules = rule_set(u, &fixed_ids, 4)?;
    let contact = *u.choose(&Contact::ALL)?;
    let opts = synth_options(u, contact)?;
    if std::env::var_os("RCCPACK_FUZZ_DEBUG").is_some() {
        eprintln!("{}{}\n{opts:?}", p.to_json(), print_rules(&rules));
    }
    let valid = p.validate().is_ok();
    let r = match synthesize(&p, &rules, &opts) {
        Ok(r) => r,
        Err(e @ (SynthError::Scene(_) | SynthError::BadWeight { .. })) => {
            assert!(!valid, "a valid problem refused as bad: {e}");
            return Ok(());
        }
        Err(SynthError::TooLarge(m)) => {
            assert!(
                !valid || !within_synth_bound(&p),
                "refused as too large within the bound: {m}\n{}",
                p.to_json()
            );
            return Ok(());
        }
        // No resemblance target here; a failed independent check is a bug.
        Err(e) => panic!("unexpected refusal: {e}\n{}", p.to_json()),
    };
    assert!(valid, "an invalid problem was solved");
    let brute = brute_reference(&p, &rules, contact);
    check_result(&p, &rules, contact, &r, brute.as_ref());
    // A probe (docs/guide.md#questions) for one rule, the set as the held rules.
    if brute.is_some() && !rules.rules.is_empty() {
        probe_check(u, &p, &rules, contact)?;
    }
    Ok(())
}

/// The engine's options for one fuzzed solve: a node limit, seed,
/// symmetry breaking and redundant constraints drawn, and now and then
/// large-neighbourhood search forced onto the tiny problem (it runs only
/// from 16 objects by default).
fn synth_options(u: &mut Unstructured, contact: Contact) -> AResult<crate::synth::SynthOptions> {
    let mut opts = crate::synth::SynthOptions {
        contact,
        stop: crate::stop::Stop::never().with_nodes(u.int_in_range(50..=4000)?),
        seed: u.arbitrary()?,
        symmetry_breaking: u.arbitrary()?,
        redundant: u.arbitrary()?,
        ..crate::synth::SynthOptions::default()
    };
    if u.arbitrary::<bool>()? {
        opts.lns = Some(crate::synth::LnsOptions {
            min_objects: 0,
            window: 1,
            max_window: 2,
            patience: 2,
            round_nodes: 100,
            budget_nodes: 1_000,
            proof_nodes: 50,
        });
    }
    Ok(opts)
}

/// Brute force on `p`, only when it has few positions to enumerate.
fn brute_reference(
    p: &Scene,
    rules: &RuleSet,
    contact: Contact,
) -> Option<crate::synth::brute_force::BruteResult> {
    let positions: i128 = p
        .objects
        .iter()
        .filter(|o| !o.is_placed())
        .map(|o| {
            let g = i128::from(p.grid);
            let count = |room: i128| if room < 0 { 0 } else { room / g + 1 };
            count(i128::from(p.space.width) - i128::from(o.width))
                * count(i128::from(p.space.height) - i128::from(o.height))
        })
        .fold(1, |a: i128, n| a.saturating_mul(n.max(1)));
    if positions <= 4000 {
        crate::synth::brute_force::solve_with_limit(p, rules, contact, 4000).ok()
    } else {
        None
    }
}

/// A solve's result against the checker, the evaluator and brute force:
/// a layout passes the checker, scores what the evaluator says, never
/// beats brute force and matches it when proved optimal; "infeasible" only
/// when brute force finds nothing either.
fn check_result(
    p: &Scene,
    rules: &RuleSet,
    contact: Contact,
    r: &crate::synth::SynthResult,
    brute: Option<&crate::synth::brute_force::BruteResult>,
) {
    use crate::synth::brute_force::approx_eq;
    use crate::synth::{verify_solution, Status};
    let terms: f64 = r
        .evaluation
        .as_ref()
        .map_or(0.0, |e| e.total_weight.max(1.0));
    match r.status {
        Status::Optimal | Status::Feasible => {
            let s = r
                .scene
                .as_ref()
                .unwrap_or_else(|| unreachable!("a solution has a scene"));
            if let Err(e) = verify_solution(p, s, rules, contact) {
                panic!("solution fails verification: {e}\n{}", s.to_json());
            }
            let e = r
                .evaluation
                .as_ref()
                .unwrap_or_else(|| unreachable!("evaluated"));
            let again = evaluate(s, rules, contact);
            assert_eq!(again.satisfied_weight, e.satisfied_weight);
            if let Some(b) = brute {
                assert!(b.feasible, "brute force finds no layout, synthesis did");
                // Weights are scaled to integers (≤ 1e-6 relative error per
                // term), so allow that much.
                let tol = 1e-6 * terms;
                assert!(
                    e.satisfied_weight <= b.best_numerator + tol,
                    "synthesis beats brute force: {} > {}",
                    e.satisfied_weight,
                    b.best_numerator
                );
                if r.status == Status::Optimal {
                    assert!(
                        approx_eq(e.satisfied_weight, b.best_numerator)
                            || (e.satisfied_weight - b.best_numerator).abs() <= tol,
                        "optimal {} but brute force {}\n{}",
                        e.satisfied_weight,
                        b.best_numerator,
                        p.to_json()
                    );
                }
            }
        }
        Status::Infeasible => {
            if let Some(b) = brute {
                assert!(
                    !b.feasible,
                    "infeasible, but brute force found {}",
                    b.best.as_ref().map(|s| s.to_json()).unwrap_or_default()
                );
            }
        }
        Status::Unknown => {}
    }
}

/// The probe for one rule of `rules` breaks it and keeps the others (by the
/// evaluator); "no probe" only when brute force finds none either.
fn probe_check(u: &mut Unstructured, p: &Scene, rules: &RuleSet, contact: Contact) -> AResult<()> {
    use crate::ask::{find_probe, probe_rules, ProbeOptions, ProbeOutcome};
    use crate::synth::brute_force::solve_with_limit;
    let k = u.choose_index(rules.rules.len())?;
    let opts = ProbeOptions {
        contact,
        stop: crate::stop::Stop::never().with_nodes(4000),
        solve_time: None,
        ..ProbeOptions::default()
    };
    let Ok(outcome) = find_probe(p, rules, k, &opts) else {
        unreachable!("the problem was solved above, so it is usable for probes")
    };
    match outcome {
        ProbeOutcome::Probe(pr) => {
            let ev = evaluate(&pr.scene, rules, contact);
            for (j, r) in ev.rules.iter().enumerate() {
                if j == k {
                    assert!(r.satisfied < r.subjects, "the probe keeps rule {k}");
                    assert_eq!(pr.broken, r.violators);
                } else {
                    assert_eq!(r.satisfied, r.subjects, "the probe breaks rule {j}");
                }
            }
        }
        ProbeOutcome::Implied { .. } => {
            if let Some(set) = probe_rules(rules, k) {
                if let Ok(b) = solve_with_limit(p, &set, contact, 4000) {
                    assert!(
                        !b.feasible,
                        "no probe said, but brute force found {}",
                        b.best.map(|s| s.to_json()).unwrap_or_default()
                    );
                }
            }
        }
        ProbeOutcome::Unknown => {}
    }
    Ok(())
}

/// A structured tiny problem (space ≤ 60×60, ≤ 4 objects, random rules of
/// every form, hard and soft, both contact modes, coordinates and sizes
/// also extreme) → synthesize with a node limit → verified, and optimal
/// means brute force's optimum; a refusal is a typed error.
pub fn synth(data: &[u8]) {
    let _ = synth_inner(&mut Unstructured::new(data));
}
