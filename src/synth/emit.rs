//! The solver-free `Model` written out for other solvers: plain JSON
//! (`rccpack-model/1`) and a MiniZinc model, so OR-Tools CP-SAT, Gecode or
//! any other engine can solve exactly the problem the Pumpkin engine solves
//! (`rccpack synth --emit FILE`, `benches/peers/`, [`crate::bench::peers`]).
//!
//! # What is written
//!
//! [`emitted`] runs the checks of [`super::synthesize`] ([`super::check_problem`],
//! the weight check) and builds the same `Model` (same `BuildOptions`:
//! contact mode, rules, symmetry breaking and redundant cumulatives as in
//! the [`SynthOptions`]) and the same integer objective coefficients
//! (`super::weights::integer_weights`). It must stay in step with
//! `synthesize`.
//!
//! - **Only the first objective** (the §6 score numerator, scaled to
//!   integers) is written. The second objective of `--like`
//!   ([`SynthOptions::like`], SPEC §12) is *not*: a peer maximises the score
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
//! | `objects` | per object of the problem, in order: `{id, class, width, height, x, y, x_var, y_var}`; `x`/`y` are the fixed coordinates (or `null`), `x_var`/`y_var` the grid variables (or `null`): the object's coordinate is `origin + grid·value` |
//! | `vars` | per grid variable `i`: `{object, object_id, axis ("x"/"y"), lb (always 0), ub}`, domain `lb..=ub` |
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
//! A solution is one value per grid variable (`vars` order); the layout is
//! `model.scene(problem, &values)` (`Model::scene`).
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

use super::model::{Axis, BoolDef, Coord, Cumulative, Lit, Model};
use super::{SynthError, SynthOptions};
use crate::relations::Contact;
use crate::rules::RuleSet;
use crate::scene::Scene;
use serde::Serialize;
use std::fmt::Write as _;

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
    let encoding = super::model::Encoding {
        connectivity: super::model::Connectivity::Circuit,
        ..super::model::Encoding::from_env()
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

// ---- JSON ------------------------------------------------------------------

#[derive(Serialize)]
#[serde(untagged)]
enum JLit {
    Var { var: u32, neg: bool },
    Const { r#const: bool },
}

fn jlit(l: Lit) -> JLit {
    match l {
        Lit::Const(b) => JLit::Const { r#const: b },
        Lit::Var { id, neg } => JLit::Var { var: id, neg },
    }
}

fn jlits(ls: &[Lit]) -> Vec<JLit> {
    ls.iter().map(|&l| jlit(l)).collect()
}

#[derive(Serialize)]
struct JObject<'a> {
    id: &'a str,
    class: &'a str,
    width: i64,
    height: i64,
    x: Option<i64>,
    y: Option<i64>,
    x_var: Option<usize>,
    y_var: Option<usize>,
}

#[derive(Serialize)]
struct JVar<'a> {
    object: usize,
    object_id: &'a str,
    axis: &'static str,
    lb: i64,
    ub: i64,
}

#[derive(Serialize)]
#[serde(tag = "op", rename_all = "snake_case")]
enum JBool {
    Ge {
        var: usize,
        k: i64,
    },
    DiffGe {
        a: usize,
        b: usize,
        k: i64,
    },
    And {
        lits: Vec<JLit>,
    },
    AtLeast {
        lits: Vec<JLit>,
        k: u32,
    },
    Connected {
        nodes: u32,
        edges: Vec<(u32, u32, JLit)>,
    },
}

#[derive(Serialize)]
struct JHard<'a> {
    rule: usize,
    name: &'a str,
    lits: Vec<JLit>,
}

#[derive(Serialize)]
struct JSoft<'a> {
    rule: usize,
    name: &'a str,
    object: Option<usize>,
    object_id: Option<&'a str>,
    lit: JLit,
    coef: i64,
    weight: f64,
}

#[derive(Serialize)]
struct JObjective {
    sense: &'static str,
    constant: i64,
}

#[derive(Serialize)]
struct JLin {
    terms: Vec<(i64, usize)>,
    rhs: i64,
}

#[derive(Serialize)]
#[serde(untagged)]
enum JStart {
    Var { var: usize, scale: i64, offset: i64 },
    Const { r#const: i64 },
}

#[derive(Serialize)]
struct JTask {
    object: usize,
    start: JStart,
    duration: i64,
    demand: i64,
}

#[derive(Serialize)]
struct JCumulative {
    axis: &'static str,
    shift: i64,
    capacity: i64,
    tasks: Vec<JTask>,
}

#[derive(Serialize)]
struct JModel<'a> {
    format: &'static str,
    contact: String,
    origin: (i64, i64),
    grid: i64,
    objects: Vec<JObject<'a>>,
    vars: Vec<JVar<'a>>,
    bools: Vec<JBool>,
    clauses: Vec<Vec<JLit>>,
    hard: Vec<JHard<'a>>,
    soft: Vec<JSoft<'a>>,
    objective: JObjective,
    symmetry: Vec<JLin>,
    cumulative: Vec<JCumulative>,
    too_large: Vec<&'a str>,
}

fn axis_name(a: Axis) -> &'static str {
    match a {
        Axis::X => "x",
        Axis::Y => "y",
    }
}

fn name_of(names: &[String], i: usize) -> &str {
    names.get(i).map(String::as_str).unwrap_or("?")
}

/// One cumulative task's start as the engine posts it.
enum Start {
    /// `scale·vars[var] + offset`.
    Var { var: usize, scale: i64, offset: i64 },
    /// A constant.
    Const(i64),
}

/// The starts of cumulative `c`, exactly as `engine/mod.rs` posts them: a
/// variable object `grid·v + (origin + shift)`, a constant one `c + shift`
/// (saturating like the engine; the engine then refuses what does not fit
/// `i32`, which [`Model::cumulative_fits_i32`] already rules out).
fn starts(m: &Model, c: &Cumulative) -> Vec<Start> {
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

/// The model as `rccpack-model/1` JSON (see the module doc for every field).
pub fn to_json(e: &Emitted) -> String {
    let m = &e.model;
    let objects = m
        .coords
        .iter()
        .zip(&m.sizes)
        .enumerate()
        .map(|(i, (&(cx, cy), &(w, h)))| {
            let (x, x_var) = match cx {
                Coord::Const(v) => (Some(v), None),
                Coord::Var(v) => (None, Some(v)),
            };
            let (y, y_var) = match cy {
                Coord::Const(v) => (Some(v), None),
                Coord::Var(v) => (None, Some(v)),
            };
            JObject {
                id: name_of(&e.object_ids, i),
                class: name_of(&e.object_classes, i),
                width: w,
                height: h,
                x,
                y,
                x_var,
                y_var,
            }
        })
        .collect();
    let vars = m
        .vars
        .iter()
        .map(|v| JVar {
            object: v.object,
            object_id: name_of(&e.object_ids, v.object),
            axis: axis_name(v.axis),
            lb: 0,
            ub: v.ub,
        })
        .collect();
    let bools = m
        .bools
        .iter()
        .map(|b| match b {
            BoolDef::Ge { var, k } => JBool::Ge { var: *var, k: *k },
            BoolDef::DiffGe { a, b, k } => JBool::DiffGe {
                a: *a,
                b: *b,
                k: *k,
            },
            BoolDef::And(ls) => JBool::And { lits: jlits(ls) },
            BoolDef::AtLeast { lits, k } => JBool::AtLeast {
                lits: jlits(lits),
                k: *k,
            },
            BoolDef::Connected { nodes, edges } => JBool::Connected {
                nodes: *nodes,
                edges: edges.iter().map(|&(a, b, l)| (a, b, jlit(l))).collect(),
            },
        })
        .collect();
    let mut clauses: Vec<Vec<JLit>> = m.clauses.iter().map(|c| jlits(c)).collect();
    if !m.too_large.is_empty() {
        // Trivially infeasible: an object cannot lie inside the space.
        clauses.push(Vec::new());
    }
    let hard = m
        .hard
        .iter()
        .map(|h| JHard {
            rule: h.rule,
            name: name_of(&e.rule_names, h.rule),
            lits: jlits(&h.lits),
        })
        .collect();
    let soft = m
        .soft
        .iter()
        .zip(&e.coefs)
        .map(|(s, &coef)| JSoft {
            rule: s.rule,
            name: name_of(&e.rule_names, s.rule),
            object: s.object,
            object_id: s.object.map(|o| name_of(&e.object_ids, o)),
            lit: jlit(s.lit),
            coef,
            weight: s.weight,
        })
        .collect();
    let symmetry = m
        .symmetry
        .iter()
        .map(|l| JLin {
            terms: l.terms.clone(),
            rhs: l.rhs,
        })
        .collect();
    let cumulative = m
        .cumulative
        .iter()
        .map(|c| JCumulative {
            axis: axis_name(c.axis),
            shift: m.cumulative_shift(c),
            capacity: c.capacity,
            tasks: c
                .tasks
                .iter()
                .zip(starts(m, c))
                .map(|(&(object, duration, demand), s)| JTask {
                    object,
                    start: match s {
                        Start::Var { var, scale, offset } => JStart::Var { var, scale, offset },
                        Start::Const(v) => JStart::Const { r#const: v },
                    },
                    duration,
                    demand,
                })
                .collect(),
        })
        .collect();
    let j = JModel {
        format: FORMAT,
        contact: e.contact.to_string(),
        origin: m.origin,
        grid: m.grid,
        objects,
        vars,
        bools,
        clauses,
        hard,
        soft,
        objective: JObjective {
            sense: "maximize",
            constant: e.constant,
        },
        symmetry,
        cumulative,
        too_large: m
            .too_large
            .iter()
            .map(|&o| name_of(&e.object_ids, o))
            .collect(),
    };
    // Plain data (strings, integers, finite weights): serialisation cannot
    // fail; a weight that is not finite was refused by `emitted`.
    let mut s = serde_json::to_string(&j).unwrap_or_else(|e| format!("{{\"error\":\"{e}\"}}"));
    s.push('\n');
    s
}

// ---- MiniZinc --------------------------------------------------------------

/// A MiniZinc comment's text: one line, printable.
fn comment(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .collect()
}

/// A [`BoolDef::Connected`] as a MiniZinc `let` with a layered
/// reachability array from node 0 (only for an [`Emitted`] built by hand:
/// [`emitted`] writes group statements as circuits).
fn mzn_connected(nodes: u32, edges: &[(u32, u32, Lit)]) -> String {
    let n = nodes.max(1) - 1;
    let mut s = format!(
        "let {{ array[0..{n}, 0..{n}] of var bool: r; constraint forall(i in 0..{n})(r[0, i] = (i = 0));"
    );
    for i in 0..nodes {
        let mut ways = vec![format!("r[t - 1, {i}]")];
        for &(a, b, l) in edges {
            let other = if a == i {
                b
            } else if b == i {
                a
            } else {
                continue;
            };
            ways.push(format!("(r[t - 1, {other}] /\\ {})", mzn_lit(l)));
        }
        let _ = write!(
            s,
            " constraint forall(t in 1..{n})(r[t, {i}] = ({}));",
            ways.join(" \\/ ")
        );
    }
    let _ = write!(s, " }} in forall(i in 0..{n})(r[{n}, i])");
    s
}

fn mzn_lit(l: Lit) -> String {
    match l {
        Lit::Const(true) => "true".into(),
        Lit::Const(false) => "false".into(),
        Lit::Var { id, neg: false } => format!("b{id}"),
        Lit::Var { id, neg: true } => format!("(not b{id})"),
    }
}

/// `c1*x1 + c2*x2 …` with signs folded (`- 3*v2`), or `0` when empty.
fn mzn_sum(terms: &[(i64, String)]) -> String {
    let mut s = String::new();
    for (i, (c, x)) in terms.iter().enumerate() {
        let (sign, mag) = if *c < 0 {
            ("-", c.unsigned_abs())
        } else {
            ("+", c.unsigned_abs())
        };
        match (i, sign) {
            (0, "-") => s.push('-'),
            (0, _) => {}
            _ => {
                s.push(' ');
                s.push_str(sign);
                s.push(' ');
            }
        }
        if mag == 1 {
            s.push_str(x);
        } else {
            let _ = write!(s, "{mag}*{x}");
        }
    }
    if s.is_empty() {
        s.push('0');
    }
    s
}

/// `a + b` with the sign of `b` folded.
fn plus_const(expr: &str, c: i64) -> String {
    match c {
        0 => expr.to_string(),
        c if c < 0 => format!("{expr} - {}", c.unsigned_abs()),
        c => format!("{expr} + {c}"),
    }
}

/// The model as MiniZinc (see the module doc). Solve it with e.g.
/// `minizinc --solver gecode model.mzn`; the last `values = […]` line is
/// the best layout's grid values.
pub fn to_minizinc(e: &Emitted) -> String {
    let m = &e.model;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "% {FORMAT} as MiniZinc, written by rccpack {}.",
        env!("CARGO_PKG_VERSION")
    );
    let _ = writeln!(
        s,
        "% Grid variable v_i: the object's coordinate is origin + grid * v_i, origin = ({}, {}), grid = {}.",
        m.origin.0, m.origin.1, m.grid
    );
    let _ = writeln!(
        s,
        "% Contact mode `{}`. Only the score objective is written (not the resemblance objective of SPEC §12).",
        e.contact
    );
    if !m.cumulative.is_empty() {
        // `cumulative.mzn` rather than `globals.mzn`: Debian's MiniZinc 2.6.4
        // with its Gecode 6.2.0 library fails to type-check `globals.mzn`
        // (`inverse`), and the standard file is all the model needs.
        s.push_str("include \"cumulative.mzn\";\n");
    }
    s.push('\n');
    for (i, v) in m.vars.iter().enumerate() {
        let _ = writeln!(
            s,
            "var 0..{}: v{i}; % objects[{}] `{}` {}",
            v.ub,
            v.object,
            comment(name_of(&e.object_ids, v.object)),
            axis_name(v.axis)
        );
    }
    if !m.bools.is_empty() {
        s.push('\n');
    }
    for (j, b) in m.bools.iter().enumerate() {
        let _ = writeln!(s, "var bool: b{j};");
        let def = match b {
            BoolDef::Ge { var, k } => format!("v{var} >= {k}"),
            BoolDef::DiffGe { a, b, k } => format!("v{a} - v{b} >= {k}"),
            BoolDef::And(ls) => {
                if ls.is_empty() {
                    "true".into()
                } else {
                    ls.iter()
                        .map(|&l| mzn_lit(l))
                        .collect::<Vec<_>>()
                        .join(" /\\ ")
                }
            }
            BoolDef::AtLeast { lits, k } => {
                let terms: Vec<(i64, String)> = lits
                    .chunk_by(|a, b| a == b)
                    .map(|g| (g.len() as i64, format!("bool2int({})", mzn_lit(g[0]))))
                    .collect();
                format!("{} >= {k}", mzn_sum(&terms))
            }
            BoolDef::Connected { nodes, edges } => mzn_connected(*nodes, edges),
        };
        let _ = writeln!(s, "constraint b{j} <-> ({def});");
    }
    if !m.clauses.is_empty() {
        s.push_str("\n% clauses (non-overlap, symmetry)\n");
    }
    for c in &m.clauses {
        let body = if c.is_empty() {
            "false".into()
        } else {
            c.iter()
                .map(|&l| mzn_lit(l))
                .collect::<Vec<_>>()
                .join(" \\/ ")
        };
        let _ = writeln!(s, "constraint {body};");
    }
    if !m.too_large.is_empty() {
        let ids: Vec<String> = m
            .too_large
            .iter()
            .map(|&o| format!("`{}`", comment(name_of(&e.object_ids, o))))
            .collect();
        let _ = writeln!(
            s,
            "\n% Trivially infeasible: {} cannot lie inside the space at all.\nconstraint false;",
            ids.join(", ")
        );
    }
    for h in &m.hard {
        let _ = writeln!(
            s,
            "\n% hard rule `{}`",
            comment(name_of(&e.rule_names, h.rule))
        );
        for &l in &h.lits {
            let _ = writeln!(s, "constraint {};", mzn_lit(l));
        }
    }
    if !m.symmetry.is_empty() {
        s.push_str("\n% symmetry breaking\n");
    }
    for l in &m.symmetry {
        let terms: Vec<(i64, String)> =
            l.terms.iter().map(|&(c, v)| (c, format!("v{v}"))).collect();
        let _ = writeln!(s, "constraint {} <= {};", mzn_sum(&terms), l.rhs);
    }
    for c in &m.cumulative {
        let st: Vec<String> = starts(m, c)
            .into_iter()
            .map(|st| match st {
                Start::Var { var, scale, offset } => {
                    plus_const(&mzn_sum(&[(scale, format!("v{var}"))]), offset)
                }
                Start::Const(v) => v.to_string(),
            })
            .collect();
        let list = |f: &dyn Fn(&(usize, i64, i64)) -> i64| {
            c.tasks
                .iter()
                .map(|t| f(t).to_string())
                .collect::<Vec<_>>()
                .join(", ")
        };
        let _ = writeln!(
            s,
            "\n% redundant cumulative along {} (starts shifted by {})\nconstraint cumulative([{}], [{}], [{}], {});",
            axis_name(c.axis),
            m.cumulative_shift(c),
            st.join(", "),
            list(&|t| t.1),
            list(&|t| t.2),
            c.capacity
        );
    }
    let terms: Vec<(i64, String)> = m
        .soft
        .iter()
        .zip(&e.coefs)
        .filter(|(t, _)| matches!(t.lit, Lit::Var { .. }))
        .map(|(t, &c)| (c, format!("bool2int({})", mzn_lit(t.lit))))
        .collect();
    let obj = if terms.is_empty() {
        e.constant.to_string()
    } else {
        plus_const(&mzn_sum(&terms), e.constant)
    };
    let _ = writeln!(
        s,
        "\n% the score numerator, weights scaled to integers\nvar int: obj = {obj};\nsolve maximize obj;\n"
    );
    let values = if m.vars.is_empty() {
        "\"values = []\\n\"".to_string()
    } else {
        let vs: Vec<String> = (0..m.vars.len()).map(|i| format!("v{i}")).collect();
        format!("\"values = \", show([{}]), \"\\n\"", vs.join(", "))
    };
    let _ = writeln!(
        s,
        "output [{values}, \"objective = \", show(obj), \"\\n\"];"
    );
    s
}
