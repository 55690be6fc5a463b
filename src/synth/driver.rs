//! The optimisation driver: every synthesis procedure as a sequence of
//! calls to a [`Backend`], independent of the engine behind it.
//!
//! # Background
//!
//! The score numerator is an integer objective `obj = Σ cᵢ·[litᵢ]` with
//! positive coefficients (the scaled rule weights, see
//! [`weights`](super::weights)). Only the values that are subset sums of
//! the coefficients can occur, so every bound is snapped to the next
//! reachable sum below it ([`SubsetSums`]).
//!
//! - [`optimise`] — [`Strategy::UpperBoundFirst`] (the default, chosen by
//!   measurement) finds a first solution, then asks twice for `obj ≥ hi`
//!   with `hi` the largest reachable value below the proven bound (a
//!   refutation adds `obj ≤ hi − 1` for good and steps `hi` down); after
//!   that it bisects between the incumbent and the bound. Pure stepping was
//!   slow on real-valued weights with many reachable sums (max 800 ms on
//!   the study set); pure bisection was 10× slower on the near-satisfiable
//!   24-object problem. [`Strategy::ImproveFromFirst`] asks for
//!   `obj ≥ best + 1` after each solution until refuted.
//! - [`minimise_cost`] — the second objective (docs/guide.md#layouts-like-the-demonstrations): with the
//!   numerator held at least the first phase's, ask for one step below
//!   the incumbent's resemblance cost, each probe with a node budget; when
//!   a step runs out, ask for halfway between the proven lower bound and
//!   the incumbent; when that runs out too, double the budget.
//! - [`shrink_conflict`] — a minimal set of hard rules that conflict, by
//!   deletion, using the backend's cores when it gives them.
//!
//! # Practical
//!
//! A limit ends a procedure with the best it has (never a wrong claim of
//! optimality or minimality). The driver has no clock of its own: every
//! limit is the backend's to obey, so under a node limit the whole run is
//! deterministic.
//!
//! # How to extend
//!
//! A new procedure is a new function here over `&mut dyn Backend`; its
//! tests go in the `tests` module below, against its `MockBackend`, which states
//! the answers a backend may give.

use super::backend::{Assumption, Backend, Core, Fact, Stop, Verdict};
use super::weights::SubsetSums;

/// How many times [`Strategy::UpperBoundFirst`] asks for the proven upper
/// bound itself before it bisects between incumbent and bound.
const UPPER_BOUND_PROBES: u32 = 2;

/// The first node budget of a probe of [`minimise_cost`]: on the realistic
/// 1.5× and 2× tasks of `bench tasks`, a first budget of as many nodes as
/// the first phase took (at least this) measured no better.
const COST_PROBE_NODES: u64 = 2_000;

#[cfg(test)]
thread_local! {
    /// The first probe budget of [`minimise_cost`] on this thread (tests
    /// set it tiny so that the engine's probes run out).
    pub(crate) static COST_PROBE_NODES_HERE: std::cell::Cell<u64> =
        const { std::cell::Cell::new(COST_PROBE_NODES) };
}

fn first_probe_budget() -> u64 {
    #[cfg(test)]
    return COST_PROBE_NODES_HERE.with(|n| n.get());
    #[cfg(not(test))]
    COST_PROBE_NODES
}

/// How to optimise.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Strategy {
    /// First solution, then `obj ≥ hi` stepping down from the upper bound.
    #[default]
    UpperBoundFirst,
    /// First solution, then `obj ≥ best + 1` until refuted.
    ImproveFromFirst,
}

/// How an optimisation ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum OptOutcome {
    /// Proved optimal.
    Optimal(Vec<i64>),
    /// Best found before a limit.
    Feasible(Vec<i64>),
    /// No solution exists.
    Infeasible,
    /// A limit stopped the search before any solution.
    Unknown,
}

/// How the second phase ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct CostOutcome {
    /// The layout to return: the numerator is at least the first phase's.
    pub values: Vec<i64>,
    /// Its resemblance cost.
    pub cost: u64,
    /// Whether the cost is proven minimal among layouts with at least its
    /// numerator.
    pub proven: bool,
    /// A proven lower bound on the cost of every layout with at least its
    /// numerator (`cost` itself when `proven`).
    pub bound: u64,
}

/// The first objective as the driver sees it.
pub(super) struct Objective<'a> {
    /// The positive integer coefficients (for the reachable sums).
    pub coefs: &'a [i64],
    /// The objective value of a solution.
    pub value: &'a dyn Fn(&[i64]) -> i64,
}

/// Maximise the objective (none: any solution is optimal). `on_incumbent`
/// is called with every improving solution. (The solve runs its two halves
/// separately; this is their composition, for the driver's tests.)
#[cfg(test)]
pub(super) fn optimise(
    backend: &mut dyn Backend,
    objective: Option<&Objective<'_>>,
    limits: &Stop,
    strategy: Strategy,
    on_incumbent: &mut dyn FnMut(&[i64]),
) -> OptOutcome {
    let best = match first_solution(backend, limits) {
        Ok(v) => v,
        Err(o) => return o,
    };
    on_incumbent(&best);
    optimise_from(backend, objective, best, limits, strategy, on_incumbent)
}

/// The first solution of `backend` (then told [`Backend::found_first`]),
/// or the outcome when there is none.
pub(super) fn first_solution(
    backend: &mut dyn Backend,
    limits: &Stop,
) -> Result<Vec<i64>, OptOutcome> {
    match backend.solve(&[], limits) {
        Verdict::Solution(v) => {
            backend.found_first();
            Ok(v)
        }
        Verdict::Infeasible(_) => Err(OptOutcome::Infeasible),
        Verdict::Unknown => Err(OptOutcome::Unknown),
    }
}

/// [`optimise`] from a known solution `best` (the backend's own first
/// solution, or one found elsewhere, e.g. by [`super::lns`]: it need not
/// come from this backend, only satisfy its model).
pub(super) fn optimise_from(
    backend: &mut dyn Backend,
    objective: Option<&Objective<'_>>,
    best: Vec<i64>,
    limits: &Stop,
    strategy: Strategy,
    on_incumbent: &mut dyn FnMut(&[i64]),
) -> OptOutcome {
    let mut best = best;
    let Some(objective) = objective else {
        return OptOutcome::Optimal(best);
    };
    let Some(mut root_bound) = backend.objective_bound() else {
        return OptOutcome::Optimal(best);
    };
    let value = objective.value;
    let mut best_val = value(&best);
    if strategy == Strategy::ImproveFromFirst {
        loop {
            if best_val >= root_bound {
                return OptOutcome::Optimal(best);
            }
            match backend.solve(&[Assumption::ObjectiveAtLeast(best_val + 1)], limits) {
                Verdict::Solution(v) => {
                    best_val = value(&v);
                    best = v;
                    on_incumbent(&best);
                }
                Verdict::Infeasible(_) => return OptOutcome::Optimal(best),
                Verdict::Unknown => return OptOutcome::Feasible(best),
            }
            root_bound = backend.objective_bound().unwrap_or(root_bound);
        }
    }
    let sums = SubsetSums::new(objective.coefs).unwrap_or_else(SubsetSums::all);
    let total: i64 = objective.coefs.iter().sum();
    let snap = |v: i64| -> i64 {
        if v < 0 || sums.contains(v) {
            v
        } else {
            sums.below(v).unwrap_or(-1)
        }
    };
    let mut hi = snap(total.min(root_bound));
    let mut step = 0u32;
    loop {
        if let Some(b) = backend.objective_bound() {
            if b < hi {
                hi = snap(b);
            }
        }
        if best_val >= hi {
            return OptOutcome::Optimal(best);
        }
        // Upper bound first; then bisect between the incumbent and the bound.
        let target = if step < UPPER_BOUND_PROBES {
            hi
        } else {
            best_val + (hi - best_val + 1) / 2
        };
        step += 1;
        match backend.solve(&[Assumption::ObjectiveAtLeast(target)], limits) {
            Verdict::Solution(v) => {
                best_val = value(&v);
                best = v;
                on_incumbent(&best);
            }
            Verdict::Infeasible(_) => {
                backend.add(Fact::ObjectiveAtMost(target - 1));
                hi = snap(target - 1);
            }
            Verdict::Unknown => return OptOutcome::Feasible(best),
        }
    }
}

/// The second phase (docs/guide.md#layouts-like-the-demonstrations): keep the numerator at least that of `best`
/// (the first phase's layout) and minimise the resemblance `cost`. A layout
/// with a larger numerator, should one turn up (only when a limit stopped
/// the first phase), replaces the incumbent and raises the numerator floor:
/// the score is never traded for resemblance. `on_incumbent` is called with
/// every improving layout. Without a cost bound (no second objective in the
/// backend) `best` is returned as proven.
///
/// Each probe asks for `cost ≤ best − 1` (a refutation proves `best`
/// minimal) with a node budget, [`COST_PROBE_NODES`] at first. When a step
/// down runs out of it, one probe asks for halfway between the proven
/// lower bound and `best` with the same budget (its refutation raises the
/// bound a limit reports); when that runs out too, the budget doubles and
/// stepping down resumes. The backend keeps what it learned across probes;
/// every budget is in nodes, so a node limit keeps the run deterministic.
pub(super) fn minimise_cost(
    backend: &mut dyn Backend,
    objective: Option<&Objective<'_>>,
    cost: &dyn Fn(&[i64]) -> u64,
    best: Vec<i64>,
    limits: &Stop,
    on_incumbent: &mut dyn FnMut(&[i64]),
) -> CostOutcome {
    let best_cost = cost(&best);
    let lo = match open_cost_phase(backend, best_cost, limits) {
        Ok(lo) => lo,
        Err((proven, bound)) => {
            return CostOutcome {
                values: best,
                cost: best_cost,
                proven,
                bound,
            }
        }
    };
    let num = |v: &[i64]| objective.map_or(0, |o| (o.value)(v));
    let best_num = num(&best);
    if objective.is_some() {
        backend.add(Fact::ObjectiveAtLeast(best_num));
    }
    let mut search = CostSearch {
        best,
        best_cost,
        best_num,
        lo,
        // Measured on the ten 1.5× and 2× tasks of `bench tasks` (seed 0,
        // 30 s; docs/performance.md): stepping down first took a median of
        // 1.5 s at 1.5× where bisection first took 1.9 s; the budgets keep
        // one hard refutation from taking the whole limit.
        budget: first_probe_budget().max(1),
        // Step down from the incumbent first; bisect when a step down runs
        // out of its budget.
        step_down: true,
    };
    let out_of_limits =
        |b: &dyn Backend| limits.expired() || limits.nodes().is_some_and(|n| b.nodes() >= n);
    // A spent limit needs no check here: the backend answers `Unknown` at
    // once, and that arm ends the phase.
    while search.lo < search.best_cost {
        let mid = search.target();
        let (verdict, cap) = probe_cost(backend, &search, mid, limits, cost);
        match verdict {
            Verdict::Solution(v) => {
                let n = num(&v);
                search.improve(backend, v, n, cost, on_incumbent);
            }
            Verdict::Infeasible(_) => search.refute(backend, mid),
            Verdict::Unknown => {
                // Below the probe's cap, something other than its budget
                // stopped the engine: end as at a limit.
                if out_of_limits(&*backend) || backend.nodes() < cap {
                    return search.stopped(&*backend);
                }
                if search.try_halfway() {
                    continue;
                }
                search.double_budget();
            }
        }
        search.raise_floor(&*backend);
    }
    CostOutcome {
        values: search.best,
        cost: search.best_cost,
        proven: true,
        bound: search.best_cost,
    }
}

/// The start of the cost phase for an incumbent of cost `best_cost`: the
/// proven cost floor to search above, or `Err((proven, bound))` when the
/// phase ends before its first probe — no cost bound in the backend, the
/// root bound already reached, or the limit spent by the first phase.
fn open_cost_phase(
    backend: &mut dyn Backend,
    best_cost: u64,
    limits: &Stop,
) -> Result<u64, (bool, u64)> {
    let Some(lo) = backend.cost_bound() else {
        return Err((true, best_cost));
    };
    backend.found_first();
    if best_cost <= lo {
        // Already at the root bound (typically cost 0: every object on a
        // shown position): nothing to post or search.
        return Err((true, best_cost));
    }
    if limits.expired() {
        // The first phase used the whole limit: posting the second
        // objective (a second or so at 40 objects) would overrun it.
        return Err((false, lo));
    }
    backend.start_cost_phase();
    Ok(lo.max(backend.cost_bound().unwrap_or(lo)))
}

/// One probe of the cost phase: `cost ≤ mid` within the search's node
/// budget (and the run's limits). Returns the verdict and the node count
/// the budget capped the probe at.
fn probe_cost(
    backend: &mut dyn Backend,
    search: &CostSearch,
    mid: u64,
    limits: &Stop,
    cost: &dyn Fn(&[i64]) -> u64,
) -> (Verdict, u64) {
    let cap = backend.nodes().saturating_add(search.budget);
    let probe_limits = limits
        .clone()
        .nodes_at_most(Some(limits.nodes().map_or(cap, |n| cap.min(n))));
    let t0 = std::time::Instant::now();
    let verdict = backend.solve(&[Assumption::CostAtMost(mid)], &probe_limits);
    log::debug!(
        "cost ≤ {mid} (floor {}, best {}, budget {}): {} in {:.1} ms",
        search.lo,
        search.best_cost,
        search.budget,
        match &verdict {
            Verdict::Solution(v) => format!("cost {}", cost(v)),
            Verdict::Infeasible(_) => "none".to_string(),
            Verdict::Unknown => "unknown".to_string(),
        },
        t0.elapsed().as_secs_f64() * 1e3
    );
    (verdict, cap)
}

/// The state of the cost phase's search: the incumbent, its cost and
/// numerator, the proven cost floor, and how the next probe is chosen.
struct CostSearch {
    best: Vec<i64>,
    best_cost: u64,
    best_num: i64,
    lo: u64,
    budget: u64,
    step_down: bool,
}

impl CostSearch {
    /// Halfway between the proven floor and the incumbent's cost.
    fn halfway(&self) -> u64 {
        self.lo + (self.best_cost - self.lo - 1) / 2
    }

    /// The cost the next probe asks for at most.
    fn target(&self) -> u64 {
        if self.step_down {
            self.best_cost - 1
        } else {
            self.halfway()
        }
    }

    /// A probe found `values` with numerator `num`: the new incumbent.
    fn improve(
        &mut self,
        backend: &mut dyn Backend,
        values: Vec<i64>,
        num: i64,
        cost: &dyn Fn(&[i64]) -> u64,
        on_incumbent: &mut dyn FnMut(&[i64]),
    ) {
        self.best_cost = cost(&values);
        self.best = values;
        on_incumbent(&self.best);
        if num > self.best_num {
            self.best_num = num;
            // The cost floor was proven for a lower numerator floor;
            // it still holds (fewer layouts now).
            backend.add(Fact::ObjectiveAtLeast(self.best_num));
        }
        self.step_down = true;
    }

    /// A probe proved no layout costs `mid` or less.
    fn refute(&mut self, backend: &mut dyn Backend, mid: u64) {
        backend.add(Fact::CostAtLeast(mid + 1));
        self.lo = mid + 1;
        self.step_down = true;
    }

    /// After a step down ran out of its budget: try halfway with the same
    /// budget when that is a different probe. Returns whether it is.
    fn try_halfway(&mut self) -> bool {
        if self.step_down && self.halfway() + 1 < self.best_cost {
            self.step_down = false;
            return true;
        }
        false
    }

    /// Both probes ran out: twice the budget, stepping down again.
    fn double_budget(&mut self) {
        self.budget = self.budget.saturating_mul(2);
        self.step_down = true;
    }

    /// Take the backend's proven cost floor when it is higher.
    fn raise_floor(&mut self, backend: &dyn Backend) {
        self.lo = self.lo.max(backend.cost_bound().unwrap_or(self.lo));
    }

    /// The outcome when a limit stopped the search.
    fn stopped(self, backend: &dyn Backend) -> CostOutcome {
        let bound = self
            .lo
            .max(backend.cost_bound().unwrap_or(self.lo))
            .min(self.best_cost);
        CostOutcome {
            values: self.best,
            cost: self.best_cost,
            proven: bound >= self.best_cost,
            bound,
        }
    }
}

/// A subset of the hard rules `rules` (indices for [`Assumption::Rule`])
/// that still conflict, minimal unless a limit interrupted: deletion (drop
/// each rule in turn; keep it out when the rest still conflict), cut short
/// by the backend's cores where it gives them. The input is assumed to
/// conflict. Returns the set and whether it is proven minimal.
pub(super) fn shrink_conflict(
    backend: &mut dyn Backend,
    rules: &[usize],
    limits: &Stop,
) -> (Vec<usize>, bool) {
    let mut core: Vec<usize> = rules.to_vec();
    let mut minimal = true;
    let mut i = 0;
    while i < core.len() {
        let trial: Vec<Assumption> = core
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, &r)| Assumption::Rule(r))
            .collect();
        match backend.solve(&trial, limits) {
            // The rules before `i` were each needed in a superset, so they
            // are needed here too: `i` stays put.
            Verdict::Infeasible(Core::Unknown) => {
                core.remove(i);
            }
            Verdict::Infeasible(Core::Rules(c)) => {
                if c.is_empty() {
                    // Infeasible whatever is assumed: no rule is needed.
                    return (Vec::new(), true);
                }
                // Keep the rules before `i` (proven needed) and, of the
                // rest, those in the core.
                let keep: Vec<usize> = core
                    .iter()
                    .enumerate()
                    .filter(|&(j, r)| j != i && (j < i || c.contains(r)))
                    .map(|(_, &r)| r)
                    .collect();
                core = keep;
            }
            Verdict::Solution(_) => i += 1,
            Verdict::Unknown => {
                minimal = false;
                i += 1;
            }
        }
    }
    (core, minimal)
}

#[cfg(test)]
mod tests {
    //! The driver against a mock backend whose "models" are explicit lists
    //! of candidate solutions, each with an objective and a cost and the
    //! set of hard rules it satisfies. The mock obeys facts and
    //! assumptions exactly, counts calls, and can be told to run out of
    //! budget after a number of calls or to give cores.
    use super::*;

    #[derive(Debug, Clone)]
    struct Cand {
        obj: i64,
        cost: u64,
        /// Hard rules it satisfies.
        sat: Vec<usize>,
    }

    struct MockBackend {
        cands: Vec<Cand>,
        obj_max: i64,
        obj_min: i64,
        cost_min: u64,
        with_cost: bool,
        /// Calls left before every answer is `Unknown` (spent for good).
        budget: Option<u32>,
        calls: u32,
        give_cores: bool,
        /// Nodes a refutation of `cost ≤ k` takes (0: free); a call whose
        /// node limit leaves fewer ends `Unknown` at the limit.
        refute_cost_nodes: u64,
        /// Refutations of `cost ≤ k` with `k` below this are free.
        cheap_below: u64,
        /// Nodes spent by refutations.
        spent: u64,
        facts: Vec<Fact>,
        asked: Vec<Vec<Assumption>>,
    }

    impl MockBackend {
        fn new(cands: Vec<Cand>) -> Self {
            MockBackend {
                cands,
                obj_max: i64::MAX,
                obj_min: i64::MIN,
                cost_min: 0,
                with_cost: true,
                budget: None,
                calls: 0,
                give_cores: false,
                refute_cost_nodes: 0,
                cheap_below: 0,
                spent: 0,
                facts: Vec::new(),
                asked: Vec::new(),
            }
        }
        fn allowed(&self, c: &Cand, a: &[Assumption]) -> bool {
            c.obj <= self.obj_max
                && c.obj >= self.obj_min
                && c.cost >= self.cost_min
                && a.iter().all(|a| match *a {
                    Assumption::ObjectiveAtLeast(k) => c.obj >= k,
                    Assumption::CostAtMost(k) => c.cost <= k,
                    Assumption::Rule(r) => c.sat.contains(&r),
                })
        }
    }

    impl Backend for MockBackend {
        fn solve(&mut self, a: &[Assumption], limits: &Stop) -> Verdict {
            self.calls += 1;
            self.asked.push(a.to_vec());
            if self.budget.is_some_and(|b| self.calls > b) {
                return Verdict::Unknown;
            }
            let refutes_cost = a
                .iter()
                .any(|x| matches!(x, Assumption::CostAtMost(k) if *k >= self.cheap_below))
                && !self.cands.iter().any(|c| self.allowed(c, a));
            if refutes_cost && self.refute_cost_nodes > 0 {
                let cap = limits.nodes().unwrap_or(u64::MAX);
                if self.nodes() + self.refute_cost_nodes > cap {
                    self.spent += cap.saturating_sub(self.nodes());
                    return Verdict::Unknown;
                }
                self.spent += self.refute_cost_nodes;
            }
            // The first allowed candidate in list order: like a real
            // backend, not necessarily the best one.
            match self.cands.iter().find(|c| self.allowed(c, a)) {
                Some(c) => Verdict::Solution(vec![c.obj, c.cost as i64]),
                None if self.give_cores => {
                    // A core: the rule assumptions that, with the facts,
                    // no candidate satisfies together (greedy, not minimal).
                    let rules: Vec<usize> = a
                        .iter()
                        .filter_map(|x| match x {
                            Assumption::Rule(r) => Some(*r),
                            _ => None,
                        })
                        .collect();
                    let mut core = rules.clone();
                    for r in &rules {
                        let without: Vec<Assumption> = core
                            .iter()
                            .filter(|x| *x != r)
                            .map(|&x| Assumption::Rule(x))
                            .collect();
                        if !self.cands.iter().any(|c| self.allowed(c, &without)) {
                            core.retain(|x| x != r);
                        }
                    }
                    Verdict::Infeasible(Core::Rules(core))
                }
                None => Verdict::Infeasible(Core::Unknown),
            }
        }
        fn add(&mut self, f: Fact) {
            self.facts.push(f);
            match f {
                Fact::ObjectiveAtMost(k) => self.obj_max = self.obj_max.min(k),
                Fact::ObjectiveAtLeast(k) => self.obj_min = self.obj_min.max(k),
                Fact::CostAtLeast(k) => self.cost_min = self.cost_min.max(k),
            }
        }
        fn objective_bound(&self) -> Option<i64> {
            Some(self.obj_max.min(1_000))
        }
        fn cost_bound(&self) -> Option<u64> {
            self.with_cost.then_some(self.cost_min)
        }
        fn nodes(&self) -> u64 {
            u64::from(self.calls) + self.spent
        }
        // Sampling's operations: the driver never calls them.
        fn hint_in_order(&mut self, _hints: &[(usize, i64)]) {}
        fn exclude(&mut self, _values: &[i64]) {}
        fn random_search(&mut self) {}
    }

    fn cand(obj: i64, cost: u64) -> Cand {
        Cand {
            obj,
            cost,
            sat: Vec::new(),
        }
    }

    const COEFS: [i64; 4] = [1, 2, 4, 8];

    fn run(m: &mut MockBackend, s: Strategy) -> (OptOutcome, Vec<i64>) {
        let value = |v: &[i64]| v[0];
        let obj = Objective {
            coefs: &COEFS,
            value: &value,
        };
        let mut seen = Vec::new();
        let out = optimise(m, Some(&obj), &Stop::never(), s, &mut |v| seen.push(v[0]));
        (out, seen)
    }

    /// Every strategy finds the optimum, reports strictly improving
    /// incumbents, and never asks for a value above a refuted one.
    #[test]
    fn optimise_finds_the_optimum() {
        for s in [Strategy::UpperBoundFirst, Strategy::ImproveFromFirst] {
            for best in 0..=15 {
                // The first candidate the mock gives is the worst.
                let mut m = MockBackend::new((0..=best).map(|o| cand(o, 0)).collect());
                let (out, seen) = run(&mut m, s);
                assert_eq!(out, OptOutcome::Optimal(vec![best, 0]), "{s:?} best {best}");
                assert!(seen.windows(2).all(|w| w[0] < w[1]), "{seen:?}");
                assert_eq!(*seen.last().unwrap(), best);
                // Facts only exclude values above the optimum.
                for f in &m.facts {
                    if let Fact::ObjectiveAtMost(k) = f {
                        assert!(*k >= best, "{s:?}: excluded {k} > optimum {best}");
                    }
                }
            }
        }
    }

    /// Upper bound first on a satisfiable top: two calls (first solution,
    /// then `obj ≥ 15`), no bisection.
    #[test]
    fn upper_bound_first_asks_for_the_bound() {
        let mut m = MockBackend::new(vec![cand(3, 0), cand(15, 0)]);
        let (out, _) = run(&mut m, Strategy::UpperBoundFirst);
        assert_eq!(out, OptOutcome::Optimal(vec![15, 0]));
        assert_eq!(
            m.asked,
            vec![vec![], vec![Assumption::ObjectiveAtLeast(15)]]
        );
    }

    /// Bisection on `0..=15` with the optimum 9: after the two bound probes
    /// (15, 14 refuted) it halves the gap; the number of calls is
    /// logarithmic, not linear.
    #[test]
    fn bisection_is_logarithmic() {
        let mut m = MockBackend::new((0..=9).map(|o| cand(o, 0)).collect());
        let (out, _) = run(&mut m, Strategy::UpperBoundFirst);
        assert_eq!(out, OptOutcome::Optimal(vec![9, 0]));
        assert!(m.calls <= 1 + 2 + 4 + 1, "{} calls: {:?}", m.calls, m.asked);
        assert_eq!(m.asked[1], vec![Assumption::ObjectiveAtLeast(15)]);
        assert_eq!(m.asked[2], vec![Assumption::ObjectiveAtLeast(14)]);
    }

    /// The bound probes skip unreachable values: with coefficients {4, 8}
    /// only 0, 4, 8, 12 can occur, so after 12 is refuted the next probe is
    /// 8, not 11. (Bisection targets between two reachable values need no
    /// snapping: `obj ≥ 2` means `obj ≥ 4`.)
    #[test]
    fn bound_probes_are_reachable_sums() {
        let value = |v: &[i64]| v[0];
        let obj = Objective {
            coefs: &[4, 8],
            value: &value,
        };
        let mut m = MockBackend::new(vec![cand(0, 0), cand(4, 0)]);
        let out = optimise(
            &mut m,
            Some(&obj),
            &Stop::never(),
            Strategy::UpperBoundFirst,
            &mut |_| {},
        );
        assert_eq!(out, OptOutcome::Optimal(vec![4, 0]));
        assert_eq!(m.asked[1], vec![Assumption::ObjectiveAtLeast(12)]);
        assert_eq!(m.asked[2], vec![Assumption::ObjectiveAtLeast(8)]);
        assert!(m.facts.contains(&Fact::ObjectiveAtMost(7)));
    }

    /// A limit: the best so far, never claimed optimal; before any
    /// solution, `Unknown`; an infeasible model, `Infeasible`.
    #[test]
    fn limits_and_infeasibility() {
        for budget in 1..6 {
            let mut m = MockBackend::new((0..=9).map(|o| cand(o, 0)).collect());
            m.budget = Some(budget);
            let (out, seen) = run(&mut m, Strategy::UpperBoundFirst);
            match out {
                OptOutcome::Feasible(v) => assert_eq!(v[0], *seen.last().unwrap()),
                OptOutcome::Optimal(v) => {
                    assert_eq!(v[0], 9);
                    assert!(budget >= 5, "optimal after {budget} calls");
                }
                o => panic!("budget {budget}: {o:?}"),
            }
        }
        let mut m = MockBackend::new(vec![cand(1, 0)]);
        m.budget = Some(0);
        assert_eq!(
            run(&mut m, Strategy::UpperBoundFirst).0,
            OptOutcome::Unknown
        );
        let mut m = MockBackend::new(Vec::new());
        assert_eq!(
            run(&mut m, Strategy::UpperBoundFirst).0,
            OptOutcome::Infeasible
        );
    }

    /// [`minimise_cost`] from the layout `[5, 9]` (numerator 5, cost 9) of
    /// a mock whose values are `[numerator, cost]`.
    fn minimise_from_9(m: &mut MockBackend, limits: &Stop) -> CostOutcome {
        let value = |v: &[i64]| v[0];
        let cost = |v: &[i64]| v[1] as u64;
        let obj = Objective {
            coefs: &COEFS,
            value: &value,
        };
        minimise_cost(m, Some(&obj), &cost, vec![5, 9], limits, &mut |_| {})
    }

    /// The second phase: the cheapest layout among those keeping the
    /// numerator; the numerator floor is a fact; a better numerator found
    /// on the way raises it.
    #[test]
    fn minimise_cost_keeps_the_score() {
        let mut m = MockBackend::new(vec![cand(5, 9), cand(4, 0), cand(5, 3), cand(6, 7)]);
        let r = minimise_from_9(&mut m, &Stop::never());
        // cost 0 needs numerator 4 < 5: refused; cost 3 at numerator 5.
        assert_eq!(
            r,
            CostOutcome {
                values: vec![5, 3],
                cost: 3,
                proven: true,
                bound: 3,
            }
        );
        assert!(m.facts.contains(&Fact::ObjectiveAtLeast(5)));
        // Numerator 6 turns up under `cost ≤ 7`: the floor rises to 6.
        let mut m = MockBackend::new(vec![cand(6, 7), cand(5, 9)]);
        let r = minimise_from_9(&mut m, &Stop::never());
        assert_eq!(r.values, vec![6, 7]);
        assert!(r.proven);
        assert!(m.facts.contains(&Fact::ObjectiveAtLeast(6)));
        // A limit: not proven.
        let mut m = MockBackend::new(vec![cand(5, 3), cand(5, 9)]);
        m.budget = Some(0);
        let r = minimise_from_9(&mut m, &Stop::never());
        assert_eq!((r.cost, r.proven, r.bound), (9, false, 0));
        // A limit after a refutation: the refuted bound is the reported
        // one (candidates 5/9 and 5/6: `cost ≤ 8` finds 6; `cost ≤ 5` runs
        // out of its budget; halfway, `cost ≤ 2`, is refuted at once; then
        // the limit).
        let mut m = MockBackend::new(vec![cand(5, 9), cand(5, 6)]);
        m.refute_cost_nodes = 3 * COST_PROBE_NODES / 2;
        m.cheap_below = 3;
        m.budget = Some(3);
        let r = minimise_from_9(&mut m, &Stop::never());
        assert_eq!((r.cost, r.proven, r.bound), (6, false, 3));
        // No second objective: the input, proven.
        let mut m = MockBackend::new(vec![cand(5, 3)]);
        m.with_cost = false;
        let r = minimise_from_9(&mut m, &Stop::never());
        assert_eq!((r.cost, r.proven, m.calls), (9, true, 0));
    }

    /// A refutation too long for the probe budget: the driver steps down
    /// from the incumbent while that succeeds, tries halfway when a step
    /// runs out, then doubles the budget, and proves the minimum; under a
    /// node limit it ends unproven with the proven bound.
    #[test]
    fn minimise_cost_steps_down_when_a_probe_runs_out() {
        let cands = vec![cand(5, 8), cand(5, 7), cand(5, 6)];
        let mut m = MockBackend::new(cands.clone());
        m.refute_cost_nodes = 3 * COST_PROBE_NODES / 2;
        let r = minimise_from_9(&mut m, &Stop::never());
        assert_eq!((r.cost, r.proven, r.bound), (6, true, 6));
        let probes: Vec<u64> = m
            .asked
            .iter()
            .map(|a| match a[..] {
                [Assumption::CostAtMost(k)] => k,
                _ => panic!("unexpected assumptions {a:?}"),
            })
            .collect();
        // 8, 7, 6 step down; 5 runs out, and so does halfway (2); with
        // twice the budget 5 is refuted.
        assert_eq!(probes, vec![8, 7, 6, 5, 2, 5]);
        // Under a node limit that the first refutation exhausts.
        let mut m = MockBackend::new(cands);
        m.refute_cost_nodes = 3 * COST_PROBE_NODES / 2;
        let limits = Stop::never().nodes_at_most(Some(COST_PROBE_NODES + 5));
        let r = minimise_from_9(&mut m, &limits);
        assert!(!r.proven);
        assert!(r.cost <= 8 && r.bound == 0, "{r:?}");
        assert!(m.nodes() <= COST_PROBE_NODES + 5);
    }

    /// Conflicts: rules {0, 1, 2, 3}; candidates satisfy {0,1,3}, {0,2,3},
    /// {1,2,3}: the only conflict is {0, 1, 2} (3 is harmless). Deletion
    /// finds it with and without cores; cores take fewer calls; an empty
    /// core means no rule is needed; a limit keeps rules (not minimal).
    #[test]
    fn shrink_conflict_finds_a_minimal_set() {
        let cands = || {
            vec![
                Cand {
                    obj: 0,
                    cost: 0,
                    sat: vec![0, 1, 3],
                },
                Cand {
                    obj: 0,
                    cost: 0,
                    sat: vec![0, 2, 3],
                },
                Cand {
                    obj: 0,
                    cost: 0,
                    sat: vec![1, 2, 3],
                },
            ]
        };
        let all = [3, 0, 1, 2];
        let mut plain = MockBackend::new(cands());
        let (c, minimal) = shrink_conflict(&mut plain, &all, &Stop::never());
        assert_eq!((c, minimal), (vec![0, 1, 2], true));
        let mut cored = MockBackend::new(cands());
        cored.give_cores = true;
        let (c, minimal) = shrink_conflict(&mut cored, &all, &Stop::never());
        assert_eq!((c, minimal), (vec![0, 1, 2], true));
        assert!(cored.calls <= plain.calls);
        // Infeasible whatever is assumed.
        let mut none = MockBackend::new(Vec::new());
        none.give_cores = true;
        assert_eq!(
            shrink_conflict(&mut none, &all, &Stop::never()),
            (Vec::new(), true)
        );
        // Without cores the same model says "no core": every rule is
        // dropped one by one, each drop proven by a call.
        let mut none = MockBackend::new(Vec::new());
        let (c, _) = shrink_conflict(&mut none, &all, &Stop::never());
        assert!(c.is_empty());
        assert_eq!(none.calls, 4);
        // Out of budget at once: everything kept, not minimal.
        let mut spent = MockBackend::new(cands());
        spent.budget = Some(0);
        assert_eq!(
            shrink_conflict(&mut spent, &all, &Stop::never()),
            (all.to_vec(), false)
        );
    }
}
