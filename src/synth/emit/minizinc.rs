//! The MiniZinc form of an emitted model (described in the parent module's
//! doc).

use super::{axis_name, name_of, starts, var_axis_name, Emitted, Start, FORMAT};
use crate::synth::model::{BoolDef, Lit};
use std::fmt::Write as _;

/// A MiniZinc comment's text: one line, printable.
fn comment(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .collect()
}

/// A [`BoolDef::Connected`] (Boolean `j`): top-level declarations of its
/// layered reachability array from node 0, `r{j}[t, i]` (node `i` reached
/// in `t` steps over edges whose literal holds), each layer defined from
/// the one before; and the definition of `b{j}`: every node reached. The
/// text grows with the edges, not with the cube of the nodes (the array is
/// declared at the top level: MiniZinc refuses a `let` with free variables
/// under `<->`).
fn mzn_connected(j: usize, nodes: u32, edges: &[(u32, u32, Lit)]) -> (String, String) {
    let n = nodes.max(1) - 1;
    let mut decls = format!(
        "array[0..{n}, 0..{n}] of var bool: r{j};\nconstraint forall(i in 0..{n})(r{j}[0, i] = (i = 0));\n"
    );
    for i in 0..nodes {
        let mut ways = vec![format!("r{j}[t - 1, {i}]")];
        for &(a, b, l) in edges {
            let other = if a == i {
                b
            } else if b == i {
                a
            } else {
                continue;
            };
            ways.push(format!("(r{j}[t - 1, {other}] /\\ {})", mzn_lit(l)));
        }
        let _ = writeln!(
            decls,
            "constraint forall(t in 1..{n})(r{j}[t, {i}] = ({}));",
            ways.join(" \\/ ")
        );
    }
    (decls, format!("forall(i in 0..{n})(r{j}[{n}, i])"))
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
    let mut s = String::new();
    header(&mut s, e);
    variables(&mut s, e);
    booleans(&mut s, e);
    clauses(&mut s, e);
    hard_rules(&mut s, e);
    symmetry(&mut s, e);
    cumulatives(&mut s, e);
    objective(&mut s, e);
    s
}

/// The header comments and the includes the model needs.
fn header(s: &mut String, e: &Emitted) {
    let m = &e.model;
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
        "% Contact mode `{}`. Only the score objective is written (not the resemblance objective of docs/guide.md#layouts-like-the-demonstrations).",
        e.contact
    );
    if !m.cumulative.is_empty() {
        // `cumulative.mzn` rather than `globals.mzn`: Debian's MiniZinc 2.6.4
        // with its Gecode 6.2.0 library fails to type-check `globals.mzn`
        // (`inverse`), and the standard file is all the model needs.
        s.push_str("include \"cumulative.mzn\";\n");
    }
    s.push('\n');
}

/// One `var 0..ub` per grid variable, named after its object.
fn variables(s: &mut String, e: &Emitted) {
    let m = &e.model;
    for (i, v) in m.vars.iter().enumerate() {
        let _ = writeln!(
            s,
            "var 0..{}: v{i}; % objects[{}] `{}` {}",
            v.ub,
            v.object,
            comment(name_of(&e.object_ids, v.object)),
            var_axis_name(v)
        );
    }
}

/// One `var bool` per Boolean, with its definition as an equivalence.
fn booleans(s: &mut String, e: &Emitted) {
    let m = &e.model;
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
            BoolDef::Connected { nodes, edges } => {
                let (decls, def) = mzn_connected(j, *nodes, edges);
                s.push_str(&decls);
                def
            }
        };
        let _ = writeln!(s, "constraint b{j} <-> ({def});");
    }
}

/// The clauses, and `constraint false` for an object too large for the space.
fn clauses(s: &mut String, e: &Emitted) {
    let m = &e.model;
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
}

/// Every hard rule's literals as constraints.
fn hard_rules(s: &mut String, e: &Emitted) {
    let m = &e.model;
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
}

/// The symmetry-breaking orders as linear `<=`.
fn symmetry(s: &mut String, e: &Emitted) {
    let m = &e.model;
    if !m.symmetry.is_empty() {
        s.push_str("\n% symmetry breaking\n");
    }
    for l in &m.symmetry {
        let terms: Vec<(i64, String)> =
            l.terms.iter().map(|&(c, v)| (c, format!("v{v}"))).collect();
        let _ = writeln!(s, "constraint {} <= {};", mzn_sum(&terms), l.rhs);
    }
}

/// The redundant cumulatives, starts as the engine posts them.
fn cumulatives(s: &mut String, e: &Emitted) {
    let m = &e.model;
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
}

/// The objective `obj`, `solve maximize obj;` and the output item.
fn objective(s: &mut String, e: &Emitted) {
    let m = &e.model;
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
}
