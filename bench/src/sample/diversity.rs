//! Diversity of the layouts one run draws (distinct layouts, pairwise
//! distances, positions covered per class), and the same for CP-SAT with
//! randomised search as a baseline.

use super::Key;
use rccpack::relations::Contact;
use rccpack::rules::RuleSet;
use rccpack::sample::{canonical_key, sample, SampleOptions};
use rccpack::scene::Scene;
use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;

/// How spread out a set of layouts of one problem is.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Spread {
    /// Layouts.
    pub layouts: usize,
    /// Distinct layouts among them ([`canonical_key`]).
    pub distinct: usize,
    /// Mean distance between two layouts: the sum over movable objects
    /// (matched by id) of `(|dx| + |dy|) / grid`.
    pub mean_distance: f64,
    /// The smallest such distance (0 when a layout repeats).
    pub min_distance: f64,
    /// Per class of movable objects: distinct positions taken, over all
    /// layouts.
    pub positions_per_class: BTreeMap<String, usize>,
}

/// Pairwise distances and positions covered among `layouts` (complete
/// scenes of `problem`).
pub fn spread(problem: &Scene, layouts: &[Scene]) -> Spread {
    let g = problem.grid.max(1) as f64;
    let movable: Vec<usize> = (0..problem.objects.len())
        .filter(|&i| !problem.objects[i].is_placed())
        .collect();
    let dist = |a: &Scene, b: &Scene| -> f64 {
        movable
            .iter()
            .map(|&i| {
                let (p, q) = (&a.objects[i], &b.objects[i]);
                let dx = (p.x.unwrap_or(0) - q.x.unwrap_or(0)).abs();
                let dy = (p.y.unwrap_or(0) - q.y.unwrap_or(0)).abs();
                (dx + dy) as f64 / g
            })
            .sum()
    };
    let (mut sum, mut pairs, mut min) = (0.0, 0usize, f64::INFINITY);
    for i in 0..layouts.len() {
        for j in i + 1..layouts.len() {
            let d = dist(&layouts[i], &layouts[j]);
            sum += d;
            pairs += 1;
            min = min.min(d);
        }
    }
    let mut per_class: BTreeMap<String, BTreeSet<(i64, i64)>> = BTreeMap::new();
    for s in layouts {
        for &i in &movable {
            let o = &s.objects[i];
            per_class
                .entry(o.class.clone())
                .or_default()
                .insert((o.x.unwrap_or(0), o.y.unwrap_or(0)));
        }
    }
    let distinct: BTreeSet<Key> = layouts.iter().map(|s| canonical_key(problem, s)).collect();
    Spread {
        layouts: layouts.len(),
        distinct: distinct.len(),
        mean_distance: if pairs > 0 { sum / pairs as f64 } else { 0.0 },
        min_distance: if pairs > 0 { min } else { 0.0 },
        positions_per_class: per_class.into_iter().map(|(c, s)| (c, s.len())).collect(),
    }
}

/// One sampler run: its layouts' spread and its time.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Diversity {
    /// Spread of the layouts.
    #[serde(flatten)]
    pub spread: Spread,
    /// Wall time of the whole run (the optimum included), in ms.
    pub total_ms: f64,
    /// `total_ms / layouts`.
    pub ms_per_layout: f64,
    /// The time limit stopped the run before `n` layouts.
    pub limit_struck: bool,
}

/// Draw up to `n` layouts with `opts` and measure how spread out they are;
/// also returns the layouts. A limit (`opts.stop`) ends the run with
/// what was found ([`Diversity::limit_struck`]).
pub fn diversity(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SampleOptions,
    n: usize,
) -> Result<(Diversity, Vec<Scene>), rccpack::sample::SampleError> {
    let start = Instant::now();
    let mut layouts = Vec::with_capacity(n);
    let mut limit_struck = false;
    for item in sample(problem, rules, opts)?.take(n) {
        match item {
            Ok(s) => layouts.push(s),
            Err(rccpack::sample::SampleError::LimitReached { found }) if found > 0 => {
                limit_struck = true;
                break;
            }
            Err(e) => return Err(e),
        }
    }
    let total_ms = start.elapsed().as_secs_f64() * 1000.0;
    let d = Diversity {
        spread: spread(problem, &layouts),
        total_ms,
        ms_per_layout: total_ms / layouts.len().max(1) as f64,
        limit_struck,
    };
    Ok((d, layouts))
}

/// The baseline's run: CP-SAT with randomised search, one solve per seed
/// (`benches/peers/cpsat_sample.py`).
#[derive(Debug, Clone, serde::Serialize)]
pub struct Baseline {
    /// Spread of the layouts (repeats included).
    #[serde(flatten)]
    pub spread: Spread,
    /// CP-SAT's summed solve time, in ms (model building and the Python
    /// start excluded).
    pub solve_ms: f64,
    /// Wall time of the whole process, in ms.
    pub process_ms: f64,
    /// Layouts that failed the verifier or the quality (should be 0).
    pub invalid: usize,
}

/// Run the CP-SAT baseline for `n` layouts whose integer objective is at
/// least that of `like_this` (a layout of the quality wanted), seeds
/// `seed..seed + n`. `Err` says why it could not run (no `python3`, no
/// `ortools`, a script error).
pub fn cpsat_baseline(
    problem: &Scene,
    rules: &RuleSet,
    contact: Contact,
    like_this: &Scene,
    n: usize,
    seed: u64,
) -> Result<Baseline, String> {
    let opts = rccpack::synth::SynthOptions {
        contact,
        ..rccpack::synth::SynthOptions::default()
    };
    let e = rccpack::synth::emit::emitted(problem, rules, &opts).map_err(|e| e.to_string())?;
    let vals_of = |s: &Scene| rccpack::sample::grid_values(&e.model, s);
    let target = e
        .objective_of(&vals_of(like_this))
        .ok_or("the layout does not fit the model")?;
    let path = std::env::temp_dir().join(format!(
        "rccpack-sample-baseline-{}-{seed}.json",
        std::process::id()
    ));
    rccpack::fsutil::atomic_write(&path, rccpack::synth::emit::to_json(&e))
        .map_err(|e| e.to_string())?;
    let script = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../benches/peers/cpsat_sample.py"
    );
    let start = Instant::now();
    let out = std::process::Command::new("python3")
        .arg(script)
        .arg(&path)
        .args(["--min-objective", &target.to_string()])
        .args(["--n", &n.to_string(), "--seed", &seed.to_string()])
        .output();
    let _ = std::fs::remove_file(&path);
    let out = out.map_err(|e| format!("cannot run python3: {e}"))?;
    let process_ms = start.elapsed().as_secs_f64() * 1000.0;
    if !out.status.success() {
        return Err(String::from_utf8_lossy(&out.stderr).trim().to_string());
    }
    #[derive(serde::Deserialize)]
    struct Line {
        layouts: Vec<Vec<i64>>,
        time_s: f64,
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let line: Line = serde_json::from_str(text.lines().last().unwrap_or(""))
        .map_err(|e| format!("cannot read the script's answer: {e}"))?;
    let mut invalid = 0;
    let mut layouts = Vec::new();
    for v in &line.layouts {
        if v.len() != e.model.vars.len() {
            invalid += 1;
            continue;
        }
        let s = e.model.scene(problem, v);
        let ok = rccpack::synth::verify_solution(problem, &s, rules, contact).is_ok()
            && e.objective_of(v).is_some_and(|o| o >= target);
        if ok {
            layouts.push(s);
        } else {
            invalid += 1;
        }
    }
    Ok(Baseline {
        spread: spread(problem, &layouts),
        solve_ms: line.time_s * 1000.0,
        process_ms,
        invalid,
    })
}
