//! Uniformity on tiny problems: every optimum layout by brute force, the
//! first layout of each of many seeds counted per layout, and a chi-square
//! test against uniform.

use super::repair;
use super::Key;
use rccpack::eval::evaluate;
use rccpack::relations::Contact;
use rccpack::rules::RuleSet;
use rccpack::sample::{canonical_key, sample, Quality, SampleOptions};
use rccpack::scene::Scene;
use rccpack::synth::brute_force::grid_positions;
use std::collections::{BTreeMap, BTreeSet};

/// Every layout of `problem` that keeps the hard rules, with its docs/language.md#the-score
/// numerator, one per canonical layout; `None` when more than `limit`
/// assignments would have to be tried.
pub fn enumerate(
    problem: &Scene,
    rules: &RuleSet,
    contact: Contact,
    limit: u128,
) -> Option<Vec<(Key, f64)>> {
    let free: Vec<usize> = (0..problem.objects.len())
        .filter(|&i| !problem.objects[i].is_placed())
        .collect();
    let domains: Vec<Vec<(i64, i64)>> = free
        .iter()
        .map(|&i| {
            // An object given turned (an orientation choice) covers its
            // footprint.
            let (w, h) = problem.objects[i].footprint();
            grid_positions(problem, w, h)
        })
        .collect();
    let size = domains
        .iter()
        .fold(1u128, |a, d| a.saturating_mul(d.len() as u128));
    if size > limit {
        return None;
    }
    let mut out: BTreeMap<Key, f64> = BTreeMap::new();
    let mut idx = vec![0usize; free.len()];
    let mut scene = problem.clone();
    if domains.iter().any(|d| d.is_empty()) {
        return Some(Vec::new());
    }
    loop {
        for (k, &i) in free.iter().enumerate() {
            let (x, y) = domains[k][idx[k]];
            scene.objects[i].x = Some(x);
            scene.objects[i].y = Some(y);
        }
        if scene.validate().is_ok() {
            let e = evaluate(&scene, rules, contact);
            if e.hard_ok() {
                out.entry(canonical_key(problem, &scene))
                    .or_insert(e.satisfied_weight);
            }
        }
        // Next assignment (odometer).
        let mut k = 0;
        loop {
            if k == idx.len() {
                return Some(out.into_iter().collect());
            }
            idx[k] += 1;
            if idx[k] < domains[k].len() {
                break;
            }
            idx[k] = 0;
            k += 1;
        }
    }
}

/// The chance that a chi-square variable with `dof` degrees of freedom is
/// at least `x` (the upper regularised incomplete gamma `Q(dof/2, x/2)`).
pub fn chi_square_p(x: f64, dof: f64) -> f64 {
    if dof <= 0.0 {
        return 1.0;
    }
    gamma_q(dof / 2.0, x / 2.0)
}

fn ln_gamma(x: f64) -> f64 {
    // Lanczos (g = 7, n = 9).
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        let pi = std::f64::consts::PI;
        return (pi / (pi * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + 7.5;
    for (i, &c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Upper regularised incomplete gamma `Q(a, x)` (series below `a + 1`,
/// continued fraction above).
fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let lg = ln_gamma(a);
    if x < a + 1.0 {
        let (mut sum, mut term, mut n) = (1.0 / a, 1.0 / a, a);
        for _ in 0..1000 {
            n += 1.0;
            term *= x / n;
            sum += term;
            if term.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        1.0 - sum * (-x + a * x.ln() - lg).exp()
    } else {
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..1000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-15 {
                break;
            }
        }
        (-x + a * x.ln() - lg).exp() * h
    }
}

/// [`uniformity`]'s result.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Uniformity {
    /// Layouts of the quality asked for (brute force).
    pub layouts: usize,
    /// Draws: the first layout of each of this many seeds.
    pub draws: usize,
    /// Distinct layouts among the draws.
    pub reached: usize,
    /// What a uniform sampler reaches in as many draws, on average:
    /// `layouts·(1 − (1 − 1/layouts)^draws)`.
    pub uniform_reached: f64,
    /// Pearson's chi-square statistic against uniform.
    pub chi_square: f64,
    /// Its p-value (`layouts − 1` degrees of freedom).
    pub p_value: f64,
    /// The largest and smallest count of one layout.
    pub max_count: usize,
    /// (0 when some layout was never drawn.)
    pub min_count: usize,
    /// Whether a full run (draw until exhausted) returned exactly the
    /// brute-force layouts.
    pub exhaustive_ok: bool,
}

/// Draw the first layout of `draws_per_layout × layouts` seeds (0, 1, …)
/// and compare the frequencies with uniform over every layout of the optimum score found by
/// brute force (`random`: [`Repair::Random`](rccpack::sample::Repair::Random), else [`Repair::Activity`](rccpack::sample::Repair::Activity));
/// also run the sampler to the end once and check that it
/// returns exactly those layouts. `None` when the problem is too large for
/// brute force or has no layout.
pub fn uniformity(
    problem: &Scene,
    rules: &RuleSet,
    quality: Quality,
    random: bool,
    draws_per_layout: usize,
) -> Option<Uniformity> {
    let contact = Contact::Point;
    let all = enumerate(problem, rules, contact, 2_000_000)?;
    let best = all
        .iter()
        .map(|(_, n)| *n)
        .fold(f64::NEG_INFINITY, f64::max);
    let total = evaluate(&problem_filled(problem, &all)?, rules, contact).total_weight;
    let keep = |n: f64| match quality {
        Quality::Optimum => rccpack::synth::brute_force::approx_eq(n, best),
        Quality::AllRules => rccpack::synth::brute_force::approx_eq(n, total),
        Quality::MinScore(x) => total <= 0.0 || n / total >= x - 1e-9,
    };
    let target: BTreeSet<Key> = all
        .into_iter()
        .filter(|(_, n)| keep(*n))
        .map(|(k, _)| k)
        .collect();
    if target.is_empty() {
        return None;
    }
    let opts = |seed| SampleOptions {
        quality,
        seed,
        contact,
        repair: repair(random),
        ..SampleOptions::default()
    };
    let full: BTreeSet<Key> = sample(problem, rules, &opts(0))
        .ok()?
        .map_while(Result::ok)
        .map(|s| canonical_key(problem, &s))
        .collect();
    let exhaustive_ok = full == target;
    let draws = draws_per_layout * target.len();
    let mut counts: BTreeMap<&Key, usize> = target.iter().map(|k| (k, 0)).collect();
    for seed in 0..draws as u64 {
        let first = sample(problem, rules, &opts(seed)).ok()?.next()?.ok()?;
        *counts.get_mut(&canonical_key(problem, &first))? += 1;
    }
    let m = target.len();
    let e = draws as f64 / m as f64;
    let chi_square: f64 = counts.values().map(|&c| (c as f64 - e).powi(2) / e).sum();
    Some(Uniformity {
        layouts: m,
        draws,
        reached: counts.values().filter(|&&c| c > 0).count(),
        uniform_reached: m as f64 * (1.0 - (1.0 - 1.0 / m as f64).powi(draws as i32)),
        chi_square,
        p_value: chi_square_p(chi_square, (m - 1) as f64),
        max_count: counts.values().copied().max().unwrap_or(0),
        min_count: counts.values().copied().min().unwrap_or(0),
        exhaustive_ok,
    })
}

/// Some complete scene of `problem` (for the denominator, which does
/// not depend on the positions).
fn problem_filled(problem: &Scene, all: &[(Key, f64)]) -> Option<Scene> {
    let (key, _) = all.first()?;
    let mut s = problem.clone();
    let mut pos: BTreeMap<(String, i64, i64), Vec<(i64, i64)>> = key
        .iter()
        .map(|(c, w, h, v)| ((c.clone(), *w, *h), v.clone()))
        .collect();
    for o in s.objects.iter_mut().filter(|o| !o.is_placed()) {
        let (x, y) = pos.get_mut(&(o.class.clone(), o.width, o.height))?.pop()?;
        o.x = Some(x);
        o.y = Some(y);
    }
    Some(s)
}
