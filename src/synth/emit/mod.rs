//! The solver-free `Model` written out for other solvers: plain JSON
//! (`rccpack-model/1`) and a MiniZinc model, so OR-Tools CP-SAT, Gecode or
//! any other engine can solve exactly the problem the Pumpkin engine solves
//! (`rccpack synth --emit FILE`, `benches/peers/`, the bench crate's `peers`).
//!
//! # What is written
//!
//! [`emitted`] runs the checks of [`super::synthesize`] (`check_problem`,
//! the weight check) and builds the same `Model` (same `BuildOptions`:
//! contact mode, rules, symmetry breaking and redundant cumulatives as in
//! the [`SynthOptions`]) and the same integer objective coefficients
//! (`super::weights::integer_weights`). It must stay in step with
//! `synthesize`.
//!
//! - **Only the first objective** (the score numerator, scaled to
//!   integers) is written. The second objective of `--like`
//!   ([`SynthOptions::like`], docs/guide.md#layouts-like-the-demonstrations) is *not*: a peer maximises the score
//!   and nothing else.
//! - The objective is `constant + Σ coef_i·[lit_i]` over the soft terms
//!   whose literal is a model Boolean; soft terms whose literal is the
//!   constant `true` add their coefficient to `constant` (the engine leaves
//!   them out of its objective variable, so its objective value is the
//!   peers' minus `constant`), constant-`false` terms add nothing.
//! - **Objects that cannot lie inside the space at all**
//!   (`Model::too_large`): `Model::build` then stops before posting any
//!   constraint and `synthesize` answers `infeasible` at once. The emitted
//!   model is made *trivially infeasible* instead: the JSON form gets one
//!   empty clause (`[]`, false), the MiniZinc form `constraint false;` (with
//!   a comment saying why), and both list the objects in `too_large`.
//!
//! - **Group statements** (`column(R)`, …) need no new operator: the
//!   model's circuit for them (layered reachability over contact literals,
//!   the block's box as `diff_ge` literals) is made of `and` Booleans,
//!   negations and clauses, and is written like every other definition;
//!   a group rule contributes one literal, as a scene-level rule does.
//!   That circuit grows with the cube of the group's objects; for MiniZinc
//!   (`--emit F.mzn`, [`emitted_for_minizinc`]) connectivity is written as
//!   one reachability array per group instead, which grows with the
//!   contact edges (8 MB instead of about 170 MB for 120 objects).
//!
//! # The JSON form ([`to_json`])
//!
//! One JSON object (compact, one line, then a newline):
//!
//! | field | meaning |
//! |---|---|
//! | `format` | `"rccpack-model/1"` |
//! | `contact` | `"point"` or `"edge"` (informative: already compiled in) |
//! | `origin` | `[space.x, space.y]` |
//! | `grid` | the grid step |
//! | `objects` | per object of the problem, in order: `{id, class, width, height, x, y, x_var, y_var}` and, for an object that may turn, `turn_var`; `x`/`y` are the fixed coordinates (or `null`), `x_var`/`y_var` the grid variables (or `null`): the object's coordinate is `origin + grid·value`; `width`/`height` its footprint unturned |
//! | `vars` | per grid variable `i`: `{object, object_id, axis ("x"/"y"/"turn"), lb (always 0), ub}`, domain `lb..=ub`; a `"turn"` variable (domain `0..=1`, after every coordinate variable) is an object's orientation: 1 when it lies turned, its footprint then `height × width` |
//! | `bools` | per Boolean `j` (children before parents), its exact definition `b_j ⇔ …`: `{"op": "ge", var, k}` is `vars[var] ≥ k`; `{"op": "diff_ge", a, b, k}` is `vars[a] − vars[b] ≥ k`; `{"op": "and", lits}` the conjunction; `{"op": "at_least", lits, k}` at least `k` of `lits` true, repeated literals counted with their multiplicity. Group statements' connectivity is written as `and` nodes (a layered reachability circuit), so these four ops are all a reader needs; `{"op": "connected", nodes, edges: [[a, b, lit], …]}` (the graph is connected over the edges whose literal holds) appears only in an [`Emitted`] built by hand from an engine model, never in what [`emitted`] returns |
//! | literal | `{"var": j, "neg": bool}` (Boolean `j`, negated when `neg`) or `{"const": true/false}` |
//! | `clauses` | lists of literals, each clause a disjunction that must hold (non-overlap, symmetry fallback, `[]` for a too-large object) |
//! | `hard` | per hard rule: `{rule (index in the rule file), name, lits}`; every literal must hold (one per subject object, or one for a scene-level or group rule) |
//! | `soft` | per objective term: `{rule, name, object (index or null for a scene-level rule), object_id, lit, coef (integer), weight (the real weight)}` |
//! | `objective` | `{"sense": "maximize", "constant": c}`: maximise `Σ coef·[lit]` over `soft` (constant literals included: the constant-`true` ones sum to `c`) |
//! | `symmetry` | linear `{terms: [[coef, var], …], rhs}`: `Σ coef·vars[var] ≤ rhs` must hold |
//! | `cumulative` | redundant, implied by non-overlap: `{axis, shift, capacity, tasks}`; per task `{object, start, duration, demand}` with `start` either `{"var": v, "scale": s, "offset": o}` (`s·vars[v] + o`, with `s = grid`, `o = origin + shift` on the axis) or `{"const": c}` (the fixed coordinate plus `shift`) exactly as the engine posts it (`Model::cumulative_shift` makes every start ≥ 0); at every point `t`, the demands of the tasks with `start ≤ t < start + duration` sum to at most `capacity` |
//! | `too_large` | ids of objects that cannot lie inside the space (the model is then infeasible) |
//!
//! A solution is one value per variable (`vars` order, orientation
//! variables included); the layout is `model.scene(problem, &values)`
//! (`Model::scene`: an orientation variable at 1 sets `turned`).
//!
//! - **Objects that turn** need no new Boolean kind: an object that may
//!   turn has an orientation variable (`turn_var`, domain `0..=1`), and
//!   every comparison naming its far edge is already a disjunction over
//!   its two orientations of `ge`/`diff_ge`/`and` literals (`Model::pair`),
//!   as are the bounds of each orientation inside the space (clauses). So
//!   a reader of format 1 that creates every variable of `vars` solves the
//!   model unchanged, and its values give the orientations back.
//!
//! # The MiniZinc form ([`to_minizinc`])
//!
//! `var 0..ub: v{i}` per grid variable, `var bool: b{j}` per Boolean with
//! its definition as an equivalence (`b <-> (v >= k)`,
//! `b <-> (va - vb >= k)`, `b <-> (l1 /\ l2 …)`,
//! `b <-> (m1*bool2int(l1) + … >= k)`), clauses as disjunctions, hard
//! literals as constraints, symmetry as linear `<=`, the cumulatives through
//! the standard library's `cumulative.mzn` (not `globals.mzn`, which
//! Debian's MiniZinc 2.6.4 with Gecode 6.2.0 cannot type-check), `var int: obj = constant + Σ coef*bool2int(lit)`,
//! `solve maximize obj;` and an output item printing two lines:
//! `values = [v0, v1, …]` and `objective = N` (the objective includes
//! the constant).

use super::model::{Axis, Coord, Cumulative, IntVar, Lit, Model};
use super::{SynthError, SynthOptions};
use crate::relations::Contact;
use crate::rules::RuleSet;
use crate::scene::Scene;

mod json;
mod minizinc;

pub use json::to_json;
pub use minizinc::to_minizinc;

/// The value of the JSON `format` field.
pub const FORMAT: &str = "rccpack-model/1";

/// A model ready to be written: the model `synthesize` would solve, its
/// integer objective coefficients and the names that make it readable.
#[derive(Debug, Clone)]
pub struct Emitted {
    /// The solver-free model (as [`super::synthesize`] builds it).
    pub model: Model,
    /// Integer coefficient per soft term (`model.soft` order).
    pub coefs: Vec<i64>,
    /// Sum of the coefficients of the soft terms whose literal is the
    /// constant `true`.
    pub constant: i64,
    /// Object ids, in problem order.
    pub object_ids: Vec<String>,
    /// Object classes, in problem order.
    pub object_classes: Vec<String>,
    /// Rule names, in rule-file order.
    pub rule_names: Vec<String>,
    /// The contact mode compiled into the model.
    pub contact: Contact,
}

impl Emitted {
    /// The objective value (constant included) of grid values `vals`, one
    /// per model variable; `None` when `vals` has the wrong length.
    pub fn objective_of(&self, vals: &[i64]) -> Option<i64> {
        if vals.len() != self.model.vars.len() {
            return None;
        }
        Some(self.model.objective_value(&self.coefs, vals) + self.constant)
    }

    /// Whether the model is trivially infeasible (an object too large for
    /// the space).
    pub fn trivially_infeasible(&self) -> bool {
        !self.model.too_large.is_empty()
    }
}

/// Build the model and objective that [`super::synthesize`] would solve
/// for `problem` under `rules` and `opts` (the same checks and errors).
/// `opts.like` is ignored: only the score objective is emitted; the limits,
/// seed and strategy do not change the model.
pub fn emitted(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SynthOptions,
) -> Result<Emitted, SynthError> {
    // Group statements as circuits: a peer has no connectivity propagator.
    emitted_encoded(problem, rules, opts, super::model::Connectivity::Circuit)
}

/// [`emitted`] for [`to_minizinc`]: a group statement's connectivity as a
/// `connected` definition, which MiniZinc gets as one reachability array
/// (its text grows with the contact edges), where [`emitted`]'s circuit of
/// `and` nodes grows with the cube of the objects (165 MB for 120 objects
/// in one group). [`to_json`]'s readers know the four ops of [`emitted`]
/// only; use [`emitted`] for it.
pub fn emitted_for_minizinc(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SynthOptions,
) -> Result<Emitted, SynthError> {
    emitted_encoded(problem, rules, opts, super::model::Connectivity::Propagator)
}

fn emitted_encoded(
    problem: &Scene,
    rules: &RuleSet,
    opts: &SynthOptions,
    connectivity: super::model::Connectivity,
) -> Result<Emitted, SynthError> {
    problem.validate()?;
    let encoding = super::model::Encoding {
        connectivity,
        ..super::model::Encoding::of(&opts.tuning)
    };
    let (mut model, coefs, _) =
        super::objective_model_encoded(problem, rules, opts, &|| false, encoding)?
            .expect("never stopped");
    // The engine keeps non-overlap in one propagator; a peer gets it as
    // one clause per pair.
    model.add_pairwise_no_overlap(opts.contact);
    let constant = model
        .soft
        .iter()
        .zip(&coefs)
        .filter(|(s, _)| s.lit == Lit::TRUE)
        .map(|(_, &c)| c)
        .sum();
    Ok(Emitted {
        model,
        coefs,
        constant,
        object_ids: problem.objects.iter().map(|o| o.id.clone()).collect(),
        object_classes: problem.objects.iter().map(|o| o.class.clone()).collect(),
        rule_names: rules.rules.iter().map(|r| r.name.clone()).collect(),
        contact: opts.contact,
    })
}

pub(super) fn axis_name(a: Axis) -> &'static str {
    match a {
        Axis::X => "x",
        Axis::Y => "y",
    }
}

/// A variable's `axis` field: its coordinate, or `"turn"`.
pub(super) fn var_axis_name(v: &IntVar) -> &'static str {
    if v.turn {
        "turn"
    } else {
        axis_name(v.axis)
    }
}

pub(super) fn name_of(names: &[String], i: usize) -> &str {
    names.get(i).map(String::as_str).unwrap_or("?")
}

/// One cumulative task's start as the engine posts it.
pub(super) enum Start {
    /// `scale·vars[var] + offset`.
    Var { var: usize, scale: i64, offset: i64 },
    /// A constant.
    Const(i64),
}

/// The starts of cumulative `c`, exactly as `engine/mod.rs` posts them: a
/// variable object `grid·v + (origin + shift)`, a constant one `c + shift`
/// (saturating like the engine; the engine then refuses what does not fit
/// `i32`, which [`Model::cumulative_fits_i32`] already rules out).
pub(super) fn starts(m: &Model, c: &Cumulative) -> Vec<Start> {
    let shift = m.cumulative_shift(c);
    c.tasks
        .iter()
        .map(|&(o, _, _)| {
            let (cx, cy) = m.coords[o];
            let (coord, origin) = match c.axis {
                Axis::X => (cx, m.origin.0),
                Axis::Y => (cy, m.origin.1),
            };
            match coord {
                Coord::Const(v) => Start::Const(v.saturating_add(shift)),
                Coord::Var(v) => Start::Var {
                    var: v,
                    scale: m.grid,
                    offset: origin.saturating_add(shift),
                },
            }
        })
        .collect()
}
