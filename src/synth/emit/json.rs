//! The `rccpack-model/1` JSON form of an emitted model (every field is
//! described in the parent module's doc).

use super::{axis_name, name_of, starts, var_axis_name, Emitted, Start, FORMAT};
use crate::synth::model::{BoolDef, Coord, Lit};
use serde::Serialize;

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
    #[serde(skip_serializing_if = "Option::is_none")]
    turn_var: Option<usize>,
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

/// The `objects` field: per object, its fixed coordinates or its grid variables.
fn objects(e: &Emitted) -> Vec<JObject<'_>> {
    let m = &e.model;
    m.coords
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
                turn_var: m.turn_vars[i],
            }
        })
        .collect()
}

/// The `vars` field: per grid variable, its object, axis and domain.
fn vars(e: &Emitted) -> Vec<JVar<'_>> {
    let m = &e.model;
    m.vars
        .iter()
        .map(|v| JVar {
            object: v.object,
            object_id: name_of(&e.object_ids, v.object),
            axis: var_axis_name(v),
            lb: 0,
            ub: v.ub,
        })
        .collect()
}

/// The `bools` field: per Boolean, its exact definition.
fn bools(e: &Emitted) -> Vec<JBool> {
    let m = &e.model;
    m.bools
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
        .collect()
}

/// The `hard` field: per hard rule, the literals that must hold.
fn hard(e: &Emitted) -> Vec<JHard<'_>> {
    let m = &e.model;
    m.hard
        .iter()
        .map(|h| JHard {
            rule: h.rule,
            name: name_of(&e.rule_names, h.rule),
            lits: jlits(&h.lits),
        })
        .collect()
}

/// The `soft` field: per objective term, its literal, coefficient and weight.
fn soft(e: &Emitted) -> Vec<JSoft<'_>> {
    let m = &e.model;
    m.soft
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
        .collect()
}

/// The `cumulative` field: the redundant relaxations with their starts as the engine posts them.
fn cumulative(e: &Emitted) -> Vec<JCumulative> {
    let m = &e.model;
    m.cumulative
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
        .collect()
}

/// The model as `rccpack-model/1` JSON (see the module doc for every field).
pub fn to_json(e: &Emitted) -> String {
    let m = &e.model;
    let mut clauses: Vec<Vec<JLit>> = m.clauses.iter().map(|c| jlits(c)).collect();
    if !m.too_large.is_empty() {
        // Trivially infeasible: an object cannot lie inside the space.
        clauses.push(Vec::new());
    }
    let symmetry = m
        .symmetry
        .iter()
        .map(|l| JLin {
            terms: l.terms.clone(),
            rhs: l.rhs,
        })
        .collect();
    let j = JModel {
        format: FORMAT,
        contact: e.contact.to_string(),
        origin: m.origin,
        grid: m.grid,
        objects: objects(e),
        vars: vars(e),
        bools: bools(e),
        clauses,
        hard: hard(e),
        soft: soft(e),
        objective: JObjective {
            sense: "maximize",
            constant: e.constant,
        },
        symmetry,
        cumulative: cumulative(e),
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
