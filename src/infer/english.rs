//! One-line English readings of rules, for comments in learned files.
//!
//! The readings recognise the shapes of the §8 templates whatever their
//! names (a statement file may use any name) and fall back to a generic
//! reading with words for the connectives.

use crate::relations::{Dir, Kind};
use crate::rules::{Atom, Formula, Target};

fn target_phrase(subject: &str, t: &Target, quant: &str) -> String {
    match t {
        Target::Any => format!("{quant} other object"),
        Target::Class(c) if c == subject => format!("{quant} other {c}"),
        Target::Class(c) => format!("{quant} {c}"),
        Target::Landmark(id) => id.clone(),
    }
}

fn atom_phrase(a: &Atom) -> String {
    format!(
        "{} {}",
        a.rel.def().verb_phrase(),
        target_phrase(&a.subject, &a.target, &a.quant.to_string())
    )
}

fn atom_of(f: &Formula) -> Option<&Atom> {
    match f {
        Formula::Atom(a) => Some(a),
        _ => None,
    }
}

fn negated_atom(f: &Formula) -> Option<&Atom> {
    match f {
        Formula::Not(g) => atom_of(g),
        _ => None,
    }
}

/// The four operands are atoms of `kind` with one target, one per direction.
fn four_sides<'f>(
    v: &'f [Formula],
    pick: impl Fn(&'f Formula) -> Option<&'f Atom>,
    kind: Kind,
) -> Option<&'f Target> {
    if v.len() != 4 {
        return None;
    }
    let atoms: Vec<&Atom> = v.iter().map(&pick).collect::<Option<_>>()?;
    let t = &atoms[0].target;
    let mut dirs: Vec<Dir> = Vec::new();
    for a in &atoms {
        if a.rel.kind != kind || &a.target != t || dirs.contains(&a.rel.dir) {
            return None;
        }
        dirs.push(a.rel.dir);
    }
    Some(t)
}

fn is_corner(v: &[Formula]) -> bool {
    if v.len() != 4 {
        return false;
    }
    let mut pairs: Vec<(Dir, Dir)> = Vec::new();
    for f in v {
        let Formula::And(w) = f else { return false };
        if w.len() != 2 {
            return false;
        }
        let (Some(a), Some(b)) = (atom_of(&w[0]), atom_of(&w[1])) else {
            return false;
        };
        let ec_any = |x: &Atom| x.rel.kind == Kind::EC && x.target == Target::Any;
        if !ec_any(a) || !ec_any(b) {
            return false;
        }
        let (x, y) = (a.rel.dir, b.rel.dir);
        // Adjacent sides: one vertical, one horizontal.
        let vertical = |d: Dir| matches!(d, Dir::N | Dir::S);
        if vertical(x) == vertical(y) {
            return false;
        }
        let key = if vertical(x) { (x, y) } else { (y, x) };
        if pairs.contains(&key) {
            return false;
        }
        pairs.push(key);
    }
    true
}

/// A one-line English reading of a rule's formula, e.g.
/// "every B is north of every R".
pub fn reading(f: &Formula) -> String {
    let s = f.subject();
    match f {
        Formula::Atom(a) => format!("every {s} {}", atom_phrase(a)),
        Formula::Not(g) => match atom_of(g) {
            Some(a) if a.rel.kind == Kind::DR => format!(
                "no {s} is {} of {}",
                a.rel.dir.word(),
                target_phrase(s, &a.target, "every")
            ),
            Some(a) => format!(
                "no {s} touches the {} side of {}",
                a.rel.dir.word(),
                target_phrase(s, &a.target, "any")
            ),
            None => generic(f),
        },
        Formula::Or(v) => {
            if let Some(t) = four_sides(v, atom_of, Kind::EC) {
                format!("every {s} touches {}", target_phrase(s, t, "some"))
            } else if is_corner(v) {
                format!("every {s} touches something on two adjacent sides (a corner)")
            } else {
                generic(f)
            }
        }
        Formula::And(v) => match four_sides(v, negated_atom, Kind::DR) {
            Some(Target::Any) => format!("every {s} is surrounded by other objects"),
            Some(Target::Class(c)) if c == s => format!("every {s} is among the other {c}s"),
            Some(Target::Class(c)) => format!("every {s} is inside the {c}s"),
            Some(Target::Landmark(id)) => format!("every {s} is inside {id}"),
            None => generic(f),
        },
    }
}

fn generic_inner(f: &Formula, top: bool) -> String {
    let wrap = |t: String| if top { t } else { format!("({t})") };
    match f {
        Formula::Atom(a) => atom_phrase(a),
        Formula::Not(g) => format!("not {}", generic_inner(g, false)),
        Formula::And(v) => wrap(
            v.iter()
                .map(|g| generic_inner(g, false))
                .collect::<Vec<_>>()
                .join(" and "),
        ),
        Formula::Or(v) => wrap(
            v.iter()
                .map(|g| generic_inner(g, false))
                .collect::<Vec<_>>()
                .join(" or "),
        ),
    }
}

fn generic(f: &Formula) -> String {
    format!(
        "every {} satisfies: {}",
        f.subject(),
        generic_inner(f, true)
    )
}

/// Whether `f` implies `g` (same subject) for every object of every scene,
/// proved by a truth table over their atoms restricted to combinations the
/// semantics allows (`DR_d(A,*)` implies `DR_d(A,B)`, `EC_d(A,B)` implies
/// `EC_d(A,*)`). Sound but not complete: `false` may hide an implication.
/// Gives `false` beyond 16 distinct atoms.
pub fn implies(f: &Formula, g: &Formula) -> bool {
    if f.subject() != g.subject() {
        return false;
    }
    let mut atoms: Vec<&Atom> = Vec::new();
    for a in f.atoms().into_iter().chain(g.atoms()) {
        if !atoms.contains(&a) {
            atoms.push(a);
        }
    }
    if atoms.len() > 16 {
        return false;
    }
    let mut edges: Vec<(usize, usize)> = Vec::new();
    for (i, a) in atoms.iter().enumerate() {
        for (j, b) in atoms.iter().enumerate() {
            let same = a.rel == b.rel && i != j;
            let dr_any = a.rel.kind == Kind::DR && a.target == Target::Any;
            let ec_to_any = a.rel.kind == Kind::EC && b.target == Target::Any;
            if same && (dr_any || ec_to_any) {
                edges.push((i, j));
            }
        }
    }
    let index = |a: &Atom| atoms.iter().position(|b| *b == a).unwrap_or(0);
    (0u32..1 << atoms.len())
        .filter(|m| {
            edges
                .iter()
                .all(|&(i, j)| m & (1 << i) == 0 || m & (1 << j) != 0)
        })
        .all(|m| {
            let mut val = |a: &Atom| m & (1 << index(a)) != 0;
            !f.eval(&mut val) || g.eval(&mut val)
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rules::parse_rules;

    fn f(src: &str) -> Formula {
        parse_rules(&format!("rule x: {src}\n")).unwrap().rules[0]
            .formula
            .clone()
    }

    #[test]
    fn readings_of_the_template_shapes() {
        let cases = [
            ("DR_N(B, R)", "every B is north of every R"),
            ("EC_E(B, *)", "every B touches the east side of some other object"),
            ("!DR_E(B, *)", "no B is east of every other object"),
            ("EC_N(B, B) | EC_S(B, B) | EC_E(B, B) | EC_W(B, B)", "every B touches some other B"),
            ("!DR_N(B, W) & !DR_S(B, W) & !DR_E(B, W) & !DR_W(B, W)", "every B is inside the Ws"),
            (
                "(EC_N(B, *) & EC_W(B, *)) | (EC_W(B, *) & EC_S(B, *)) | (EC_S(B, *) & EC_E(B, *)) | (EC_E(B, *) & EC_N(B, *))",
                "every B touches something on two adjacent sides (a corner)",
            ),
            ("DR_N(B, R) & !EC_W(B, G)", "every B satisfies: is north of every R and not touches the west side of some G"),
        ];
        for (src, want) in cases {
            assert_eq!(reading(&f(src)), want, "{src}");
        }
    }

    #[test]
    fn implication_is_sound_on_known_cases() {
        let inside = f("!DR_N(B, W) & !DR_S(B, W) & !DR_E(B, W) & !DR_W(B, W)");
        assert!(implies(&inside, &f("!DR_N(B, W)")));
        assert!(!implies(&f("!DR_N(B, W)"), &inside));
        let touches_b = f("EC_N(B, B) | EC_S(B, B) | EC_E(B, B) | EC_W(B, B)");
        assert!(implies(
            &touches_b,
            &f("EC_N(B, *) | EC_S(B, *) | EC_E(B, *) | EC_W(B, *)")
        ));
        assert!(implies(&f("DR_N(B, *)"), &f("DR_N(B, R)")));
        assert!(!implies(&f("DR_N(B, R)"), &f("DR_N(B, *)")));
        assert!(!implies(&f("DR_N(B, R)"), &f("DR_N(G, R)")));
    }
}
