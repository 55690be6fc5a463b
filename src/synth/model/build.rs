//! Building a model: the grid variables of the unplaced objects, then
//! non-overlap, symmetry breaking, the redundant relaxations and the rules,
//! under an [`Encoding`] that never changes what the model means.

use super::bools::floor_div;
use super::{BuildOptions, Connectivity, Coord, HardRule, IntVar, Lit, Model};
use crate::relations::Axis;
use crate::rules::RuleSet;
use crate::scene::{Object, Scene};
use std::collections::HashMap;

/// Most pairs of objects (at least one movable) whose non-overlap the model
/// states as one clause each (four reified pair literals, about 16 KB in
/// the engine per pair); past it the engine's non-overlap propagator holds
/// them all in linear memory. 2 000 pairs is about 64 objects.
pub(crate) const PAIRWISE_NO_OVERLAP_PAIRS: usize = 2_000;

/// How a model is encoded, beyond [`BuildOptions`]: choices that change
/// the model's Booleans but never what it means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Encoding {
    /// Non-overlap: `Some(true)` pairwise clauses, `Some(false)` the
    /// engine's propagator, `None` by the number of pairs.
    pub(crate) pairwise: Option<bool>,
    /// Group statements' connectivity.
    pub(crate) connectivity: Connectivity,
}

impl Encoding {
    /// The encoding `tuning` asks for.
    pub(crate) fn of(tuning: &crate::synth::Tuning) -> Encoding {
        use crate::synth::NoOverlap;
        Encoding {
            pairwise: match tuning.no_overlap {
                NoOverlap::ByPairs => None,
                NoOverlap::Clauses => Some(true),
                NoOverlap::Propagator => Some(false),
            },
            connectivity: if tuning.circuit_connectivity {
                Connectivity::Circuit
            } else {
                Connectivity::Propagator
            },
        }
    }
}

/// Whether `o` gets an orientation variable: unplaced, `turnable`, oblong
/// and not already `turned` (an unplaced object with `turned` set lies
/// turned: its orientation is given).
pub(crate) fn has_turn_var(o: &Object) -> bool {
    !o.is_placed() && o.turnable && !o.turned && o.is_oblong()
}

impl Model {
    /// Build the model of `problem` with `rules`.
    ///
    /// The problem must be a valid scene (see [`Scene::validate`]).
    pub fn build(problem: &Scene, rules: &RuleSet, opts: BuildOptions) -> Model {
        Self::build_until(problem, rules, opts, &|| false).expect("never stopped")
    }

    /// [`Model::build_until`] with the encoding chosen by the caller (for
    /// non-overlap, `None` decides by the number of pairs, see
    /// [`PAIRWISE_NO_OVERLAP_PAIRS`]).
    pub(crate) fn build_encoded(
        problem: &Scene,
        rules: &RuleSet,
        opts: BuildOptions,
        stop: &dyn Fn() -> bool,
        encoding: Encoding,
    ) -> Option<Model> {
        let pairwise = encoding.pairwise;
        let movable = problem.objects.iter().filter(|o| !o.is_placed()).count();
        let n = problem.objects.len();
        // Pairs with at least one movable object.
        let pairs =
            n * (n.saturating_sub(1)) / 2 - (n - movable) * (n - movable).saturating_sub(1) / 2;
        // The engine's non-overlap propagator assumes constant sizes: a
        // model with an orientation variable states non-overlap pairwise.
        let pairwise = pairwise.unwrap_or(pairs <= PAIRWISE_NO_OVERLAP_PAIRS)
            || problem.objects.iter().any(has_turn_var);
        let mut m = Self::build_core(problem, rules, opts, stop, pairwise, encoding.connectivity)?;
        m.pairwise_no_overlap = pairwise || !m.too_large.is_empty();
        Some(m)
    }

    /// [`Model::build`], given up (`None`) as soon as `stop` says so
    /// (checked per rule and every 256 subject objects: a deadline or
    /// Ctrl-C while a large model is built).
    pub fn build_until(
        problem: &Scene,
        rules: &RuleSet,
        opts: BuildOptions,
        stop: &dyn Fn() -> bool,
    ) -> Option<Model> {
        Self::build_encoded(problem, rules, opts, stop, Encoding::of(&opts.tuning))
    }

    pub(super) fn build_core(
        problem: &Scene,
        rules: &RuleSet,
        opts: BuildOptions,
        stop: &dyn Fn() -> bool,
        pairwise: bool,
        connectivity: Connectivity,
    ) -> Option<Model> {
        let mut m = Model::empty(problem, connectivity);
        m.tuning = opts.tuning;
        m.post_coords(problem);
        if !m.too_large.is_empty() {
            return Some(m);
        }
        m.post_turn_vars(problem);
        // Non-overlap between every pair with at least one variable object:
        // one clause per pair for a small model (the pair literals also
        // guide the search), else implicit — the engine posts one
        // propagator for all pairs (linear memory) and
        // `add_pairwise_no_overlap` writes the clauses for the peers.
        if pairwise {
            m.add_pairwise_no_overlap(opts.contact);
        }
        if opts.symmetry_breaking {
            m.post_symmetry(problem);
        }
        if opts.redundant {
            m.post_cumulative(problem);
        }
        if opts.rules && !m.post_rules(problem, rules, opts.contact, stop) {
            return None;
        }
        Some(m)
    }

    /// A model of `problem`'s space and grid with nothing posted yet.
    fn empty(problem: &Scene, connectivity: Connectivity) -> Model {
        let sp = problem.space;
        Model {
            origin: (sp.x, sp.y),
            grid: problem.grid,
            vars: Vec::new(),
            coords: Vec::new(),
            sizes: Vec::new(),
            turn_vars: vec![None; problem.objects.len()],
            bools: Vec::new(),
            clauses: Vec::new(),
            hard: Vec::new(),
            soft: Vec::new(),
            symmetry: Vec::new(),
            cumulative: Vec::new(),
            too_large: Vec::new(),
            pairwise_no_overlap: false,
            connectivity,
            tuning: crate::synth::Tuning::default(),
            interned: HashMap::new(),
        }
    }

    /// Each object's footprint and coordinates: constants for a placed
    /// object, two grid variables (x then y) for one to place, whose upper
    /// bounds cover every orientation it may take. An object that fits in
    /// no orientation goes to `too_large`.
    fn post_coords(&mut self, problem: &Scene) {
        for (i, o) in problem.objects.iter().enumerate() {
            let (w, h) = o.footprint();
            self.sizes.push((w, h));
            if let (Some(x), Some(y)) = (o.x, o.y) {
                self.coords.push((Coord::Const(x), Coord::Const(y)));
                continue;
            }
            let (ux, uy) = grid_upper_bounds(problem, o);
            if ux < 0 || uy < 0 {
                self.too_large.push(i);
            }
            let vx = self.vars.len();
            self.vars.push(IntVar {
                object: i,
                axis: Axis::X,
                ub: ux.max(0),
                turn: false,
            });
            self.vars.push(IntVar {
                object: i,
                axis: Axis::Y,
                ub: uy.max(0),
                turn: false,
            });
            self.coords.push((Coord::Var(vx), Coord::Var(vx + 1)));
        }
    }

    /// One orientation variable per object that may turn (after every
    /// coordinate variable, in object order), and the bounds of each
    /// orientation: `turned → gx ≤ ⌊(W − h)/g⌋ ∧ gy ≤ ⌊(H − w)/g⌋`, and the
    /// flat bounds when not turned (an orientation that does not fit at
    /// all is ruled out by a unit clause).
    fn post_turn_vars(&mut self, problem: &Scene) {
        let (sp, g) = (problem.space, problem.grid);
        for (i, o) in problem.objects.iter().enumerate() {
            if !has_turn_var(o) {
                continue;
            }
            let t = self.vars.len();
            self.vars.push(IntVar {
                object: i,
                axis: Axis::X,
                ub: 1,
                turn: true,
            });
            self.turn_vars[i] = Some(t);
            let (Coord::Var(vx), Coord::Var(vy)) = self.coords[i] else {
                continue;
            };
            let turned = self.ge(t, 1);
            let (w, h) = (o.width, o.height);
            for (when, fw, fh) in [(!turned, w, h), (turned, h, w)] {
                let (ux, uy) = (floor_div(sp.width - fw, g), floor_div(sp.height - fh, g));
                if ux < 0 || uy < 0 {
                    self.clauses.push(vec![!when]);
                    continue;
                }
                for (v, u) in [(vx, ux), (vy, uy)] {
                    let within = !self.ge(v, u + 1);
                    if within != Lit::TRUE {
                        self.clauses.push(vec![!when, within]);
                    }
                }
            }
        }
    }

    /// A hard "rule" pinning unplaced object `object` at `(x, y)` (its
    /// index in [`Model::hard`]; `HardRule::rule` is that index too, past
    /// any rule set's). `None` when the position is not on the object's
    /// grid domain (or the object is a constant).
    pub(crate) fn pin(&mut self, object: usize, x: i64, y: i64) -> Option<usize> {
        let (Coord::Var(vx), Coord::Var(vy)) = self.coords[object] else {
            return None;
        };
        let mut lits = Vec::with_capacity(4);
        for (v, at, origin) in [(vx, x, self.origin.0), (vy, y, self.origin.1)] {
            let d = at - origin;
            if d % self.grid != 0 {
                return None;
            }
            let k = d / self.grid;
            if k < 0 || k > self.vars[v].ub {
                return None;
            }
            lits.push(self.ge(v, k));
            lits.push(!self.ge(v, k + 1));
        }
        let at = self.hard.len();
        self.hard.push(HardRule { rule: at, lits });
        Some(at)
    }
}

/// The largest grid coordinates (x, y) of object `o` inside `problem`'s
/// space, negative when it does not fit; for an object that may turn, the
/// union of both orientations (each orientation's own bounds are clauses,
/// see `post_turn_vars`).
fn grid_upper_bounds(problem: &Scene, o: &Object) -> (i64, i64) {
    let (sp, g) = (problem.space, problem.grid);
    let (w, h) = o.footprint();
    let mut ux = floor_div(sp.width - w, g);
    let mut uy = floor_div(sp.height - h, g);
    if has_turn_var(o) {
        let (tx, ty) = (floor_div(sp.width - h, g), floor_div(sp.height - w, g));
        if tx >= 0 && ty >= 0 {
            if ux < 0 || uy < 0 {
                (ux, uy) = (tx, ty);
            } else {
                (ux, uy) = (ux.max(tx), uy.max(ty));
            }
        }
    }
    (ux, uy)
}
