//! The statement pool of the runtime study: the 12 pilot-study rules of the
//! thesis (§4.2) plus the template statements (docs/guide.md#learning), built with the
//! builders of [`rccpack::infer::templates`].
//!
//! The pool keeps its own names and order (`dr_n_b_r`, `ec_n_b_r`,
//! `not_dr_n_b_r` per direction, …), which the seeded draws of the study
//! depend on; only the formulas come from the templates module.

use rccpack::relations::{Dir, Kind};
use rccpack::rules::{Formula, Rule, Target};

pub use rccpack::infer::templates::{atom, corner, inside as among, touches};

fn target(t: &str) -> Target {
    if t == "*" {
        Target::Any
    } else {
        Target::Class(t.to_string())
    }
}

fn tname(t: &Target) -> String {
    match t {
        Target::Any => "any".into(),
        Target::Class(c) => c.to_lowercase(),
        Target::Landmark(id) => id.to_lowercase(),
    }
}

/// The twelve ground-truth rules of the thesis's pilot study (weight 1):
/// `DR_N(B,R)`, `DR_E(G,R)`, `DR_E(G,B)`; each of B, R, G touches its own
/// class; each sits in a corner; each is inside the walls `W`.
pub fn pilot_rules() -> Vec<Rule> {
    let c = |s: &str| Target::Class(s.to_string());
    let mut out = vec![
        Rule::new("b_north_of_r", atom(Kind::DR, Dir::N, "B", &c("R"))),
        Rule::new("g_east_of_r", atom(Kind::DR, Dir::E, "G", &c("R"))),
        Rule::new("g_east_of_b", atom(Kind::DR, Dir::E, "G", &c("B"))),
    ];
    for x in ["B", "R", "G"] {
        out.push(Rule::new(
            format!("{}_touches_{}", x.to_lowercase(), x.to_lowercase()),
            touches(x, &c(x)),
        ));
    }
    for x in ["B", "R", "G"] {
        out.push(Rule::new(format!("{}_corner", x.to_lowercase()), corner(x)));
    }
    for x in ["B", "R", "G"] {
        out.push(Rule::new(
            format!("{}_inside_w", x.to_lowercase()),
            among(x, &c("W")),
        ));
    }
    out
}

/// The template statements (docs/guide.md#learning) for one subject class over `targets`
/// (class names or `*`), named `dr_n_b_r`, `ec_n_b_r`, `not_dr_n_b_r`,
/// `b_touches_r`, `b_among_r`, `b_corner`.
pub fn templates(subject: &str, targets: &[&str]) -> Vec<Rule> {
    let s = subject.to_lowercase();
    let mut out = Vec::new();
    for t in targets {
        let t = target(t);
        let tn = tname(&t);
        for d in Dir::ALL {
            let dl = d.letter().to_ascii_lowercase();
            out.push(Rule::new(
                format!("dr_{dl}_{s}_{tn}"),
                atom(Kind::DR, d, subject, &t),
            ));
            out.push(Rule::new(
                format!("ec_{dl}_{s}_{tn}"),
                atom(Kind::EC, d, subject, &t),
            ));
            out.push(Rule::new(
                format!("not_dr_{dl}_{s}_{tn}"),
                Formula::not(atom(Kind::DR, d, subject, &t)),
            ));
        }
        out.push(Rule::new(format!("{s}_touches_{tn}"), touches(subject, &t)));
        out.push(Rule::new(format!("{s}_among_{tn}"), among(subject, &t)));
    }
    out.push(Rule::new(format!("{s}_corner"), corner(subject)));
    out
}

/// The study's pool for one subject class: the pilot rules about it, then
/// every template statement over `R, G, B, W, *` that is not already there
/// (compared by formula). Names are unique across all subjects.
pub fn pool_for(subject: &str) -> Vec<Rule> {
    let mut out: Vec<Rule> = pilot_rules()
        .into_iter()
        .filter(|r| r.subject() == subject)
        .collect();
    for r in templates(subject, &["R", "G", "B", "W", "*"]) {
        if !out.iter().any(|o| o.formula == r.formula) {
            out.push(r);
        }
    }
    out
}

/// A formula as `.rcc` text (fully parenthesised where precedence needs it).
pub fn formula_text(f: &Formula) -> String {
    fn go(f: &Formula, prec: u8, out: &mut String) {
        match f {
            Formula::Atom(a) => out.push_str(&a.to_string()),
            Formula::Shape(s) => out.push_str(&s.to_string()),
            Formula::Turned(c) => out.push_str(&format!("turned({c})")),
            Formula::Not(g) => {
                out.push('!');
                go(g, 3, out);
            }
            Formula::And(v) | Formula::Or(v) => {
                let (p, op) = if matches!(f, Formula::And(_)) {
                    (2, " & ")
                } else {
                    (1, " | ")
                };
                if p < prec {
                    out.push('(');
                }
                for (i, g) in v.iter().enumerate() {
                    if i > 0 {
                        out.push_str(op);
                    }
                    go(g, p + 1, out);
                }
                if p < prec {
                    out.push(')');
                }
            }
        }
    }
    let mut s = String::new();
    go(f, 0, &mut s);
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pilot_rules_are_twelve_and_in_the_pool() {
        let p = pilot_rules();
        assert_eq!(p.len(), 12);
        for s in ["R", "G", "B"] {
            let pool = pool_for(s);
            // 14 shapes × 5 targets + corner; the pilot rules are templates.
            assert_eq!(pool.len(), 71, "{s}");
            let mut names: Vec<&str> = pool.iter().map(|r| r.name.as_str()).collect();
            names.sort();
            names.dedup();
            assert_eq!(names.len(), 71);
            assert!(pool.iter().all(|r| r.subject() == s));
        }
        assert_eq!(
            formula_text(&p[9].formula),
            "!DR_N(B, W) & !DR_S(B, W) & !DR_E(B, W) & !DR_W(B, W)"
        );
        assert_eq!(
            formula_text(&p[6].formula),
            "EC_N(B, *) & EC_W(B, *) | EC_W(B, *) & EC_S(B, *) | EC_S(B, *) & EC_E(B, *) | EC_E(B, *) & EC_N(B, *)"
        );
    }
}
