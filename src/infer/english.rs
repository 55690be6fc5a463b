//! One-line English readings of statements, for comments in learned files
//! and the studio, and the implication marks between learned rules.
//!
//! # Readings
//!
//! A reading is a determiner for the subject ("every B", "no B", "at least
//! one B", "at least 2 Bs") and a predicate about one object. The predicate
//! recognises the template shapes (docs/guide.md#learning) by their form, whatever their
//! names (a statement file may use any name): one atom, a negated atom,
//! "touches some B" (flush or not), "touches no B", "inside the Bs", "lies
//! flush wherever it touches a B", one row, one column, flush neighbours,
//! a corner. Anything else gets a generic reading with words for the
//! connectives. Relation verbs come from [`crate::relations::TABLE`].
//! First-edition statements read exactly as they always did.
//!
//! # Implication
//!
//! [`rule_implies`] proves that one statement implies another by a truth
//! table over their atoms, restricted to the combinations allowed by the
//! implications between atoms: the relation implications of
//! [`crate::relations::implies`] (`FL_d ⇒ EC_d ⇒ DR_d`), read through the
//! quantifiers (`some`/`at least` grow with more target objects and with
//! weaker relations, `every` shrinks, `no`/`at most` go the other way) and
//! target inclusion (a class or a landmark is part of `*`).

use crate::relations::{implies as rel_implies, Contact, Dir, Kind, Quant};
use crate::rules::{Atom, Formula, Scope, Target};

/// Whether a count quantifier names more than one object.
fn plural_count(q: Quant) -> bool {
    matches!(q, Quant::AtLeast(k) | Quant::AtMost(k) if k != 1)
}

fn target_phrase(subject: &str, t: &Target, quant: &str) -> String {
    match t {
        Target::Any => format!("{quant} other object"),
        Target::Class(c) if c == subject => format!("{quant} other {c}"),
        Target::Class(c) => format!("{quant} {c}"),
        Target::Landmark(id) => id.clone(),
    }
}

/// The target as a quantified atom reads it: "some G", "no other B",
/// "at least 2 other objects".
fn quantified_target(subject: &str, t: &Target, q: Quant) -> String {
    let p = target_phrase(subject, t, &q.to_string());
    if plural_count(q) && !matches!(t, Target::Landmark(_)) {
        p + "s"
    } else {
        p
    }
}

fn atom_phrase(a: &Atom) -> String {
    format!(
        "{} {}",
        a.rel.def().verb_phrase(),
        quantified_target(&a.subject, &a.target, a.quant)
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

/// The four operands are atoms of `kind` and quantifier `quant` (`None`:
/// the relation's default) with one target, one per direction.
fn four_sides<'f>(
    v: &'f [Formula],
    pick: impl Fn(&'f Formula) -> Option<&'f Atom>,
    kind: Kind,
    quant: Option<Quant>,
) -> Option<&'f Target> {
    if v.len() != 4 {
        return None;
    }
    let atoms: Vec<&Atom> = v.iter().map(&pick).collect::<Option<_>>()?;
    let t = &atoms[0].target;
    let mut dirs: Vec<Dir> = Vec::new();
    for a in &atoms {
        let quant_ok = match quant {
            None => a.has_default_quant(),
            Some(q) => a.quant == q,
        };
        if a.rel.kind != kind || &a.target != t || !quant_ok || dirs.contains(&a.rel.dir) {
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
        let ec_any =
            |x: &Atom| x.rel.kind == Kind::EC && x.target == Target::Any && x.has_default_quant();
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

/// `(!EC_d(A,T) | FL_d(A,T))` for the four directions, one target.
fn contacts_flush(v: &[Formula]) -> Option<&Target> {
    if v.len() != 4 {
        return None;
    }
    let mut dirs: Vec<Dir> = Vec::new();
    let mut target: Option<&Target> = None;
    for f in v {
        let Formula::Or(w) = f else { return None };
        let [ec, fl] = w.as_slice() else { return None };
        let (ec, fl) = (negated_atom(ec)?, atom_of(fl)?);
        let ok = ec.rel.kind == Kind::EC
            && fl.rel.kind == Kind::FL
            && ec.rel.dir == fl.rel.dir
            && ec.target == fl.target
            && ec.has_default_quant()
            && fl.has_default_quant()
            && target.is_none_or(|t| *t == ec.target)
            && !dirs.contains(&ec.rel.dir);
        if !ok {
            return None;
        }
        target = Some(&ec.target);
        dirs.push(ec.rel.dir);
    }
    target
}

/// Two atoms of `kind` and quantifier `quant` (`None`: default), one
/// target, directions `{a, b}` in any order.
fn pair_of(v: &[Formula], kind: Kind, quant: Option<Quant>, a: Dir, b: Dir) -> Option<&Target> {
    let [x, y] = v else { return None };
    let (x, y) = (atom_of(x)?, atom_of(y)?);
    let quant_ok = |t: &Atom| match quant {
        None => t.has_default_quant(),
        Some(q) => t.quant == q,
    };
    let dirs_ok = (x.rel.dir, y.rel.dir) == (a, b) || (x.rel.dir, y.rel.dir) == (b, a);
    (x.rel.kind == kind
        && y.rel.kind == kind
        && x.target == y.target
        && quant_ok(x)
        && quant_ok(y)
        && dirs_ok)
        .then_some(&x.target)
}

/// "the other Bs", "every G", "every other object", "w_box".
fn aligned_with(subject: &str, t: &Target) -> String {
    match t {
        Target::Class(c) if c == subject => format!("the other {c}s"),
        Target::Class(c) => format!("every {c}"),
        Target::Any => "every other object".into(),
        Target::Landmark(id) => id.clone(),
    }
}

/// "another B", "a G", "another object", "w_box".
fn a_target(subject: &str, t: &Target) -> String {
    match t {
        Target::Class(c) if c == subject => format!("another {c}"),
        Target::Class(c) => format!("a {c}"),
        Target::Any => "another object".into(),
        Target::Landmark(id) => id.clone(),
    }
}

/// What a statement says about one object.
enum Pred {
    /// Read as "every A …" / "at least one A …".
    Pos(String),
    /// A negated atom: "no A {no}" for a per-object statement, "{det} A
    /// {not}" under a scene quantifier.
    Neg { no: String, not: String },
}

fn predicate(f: &Formula) -> Pred {
    let pos = Pred::Pos;
    match f {
        Formula::Atom(a) => pos(atom_phrase(a)),
        Formula::Shape(sh) => pos(format!("{} (with the others)", sh.kind.verb())),
        Formula::Turned(_) => pos("lies turned".to_string()),
        Formula::Not(g) => negated_predicate(f, g),
        Formula::Or(v) => pos(disjunction_phrase(f, v)),
        Formula::And(v) => pos(conjunction_phrase(f, v)),
    }
}

/// `f = !g`: a negated atom or `turned` read as "no A …", else the generic
/// reading.
fn negated_predicate(f: &Formula, g: &Formula) -> Pred {
    let s = f.subject();
    match atom_of(g) {
        Some(a) if a.has_default_quant() => {
            let d = a.rel.dir.word();
            match a.rel.kind {
                Kind::DR => {
                    let t = target_phrase(s, &a.target, "every");
                    Pred::Neg {
                        no: format!("is {d} of {t}"),
                        not: format!("is not {d} of {t}"),
                    }
                }
                Kind::EC => {
                    let t = target_phrase(s, &a.target, "any");
                    Pred::Neg {
                        no: format!("touches the {d} side of {t}"),
                        not: format!("does not touch the {d} side of {t}"),
                    }
                }
                Kind::FL | Kind::AL => {
                    let t = target_phrase(s, &a.target, "any");
                    let verb = a.rel.def().verb_phrase();
                    Pred::Neg {
                        no: format!("{verb} {t}"),
                        not: format!("does not satisfy: {verb} {t}"),
                    }
                }
            }
        }
        _ if matches!(g, Formula::Turned(_)) => Pred::Neg {
            no: "lies turned".into(),
            not: "does not lie turned".into(),
        },
        _ => generic(f),
    }
}

/// `f = v[0] | v[1] | …`: the patterns with a name (touching some side, a
/// corner, flush on two opposite sides), else the generic reading.
fn disjunction_phrase(f: &Formula, v: &[Formula]) -> String {
    let s = f.subject();
    if let Some(t) = four_sides(v, atom_of, Kind::EC, None) {
        format!("touches {}", target_phrase(s, t, "some"))
    } else if let Some(t) = four_sides(v, atom_of, Kind::FL, None) {
        format!("touches {} flush", target_phrase(s, t, "some"))
    } else if is_corner(v) {
        "touches something on two adjacent sides (a corner)".into()
    } else if let Some(t) = pair_of(v, Kind::FL, None, Dir::E, Dir::W) {
        format!(
            "lies flush on the east or west side of {}",
            target_phrase(s, t, "some")
        )
    } else if let Some(t) = pair_of(v, Kind::FL, None, Dir::N, Dir::S) {
        format!(
            "lies flush on the north or south side of {}",
            target_phrase(s, t, "some")
        )
    } else {
        generic_phrase(f)
    }
}

/// `f = v[0] & v[1] & …`: the patterns with a name (surrounded, touching
/// nothing, flush wherever it touches, one row or column), else the
/// generic reading.
fn conjunction_phrase(f: &Formula, v: &[Formula]) -> String {
    let s = f.subject();
    if let Some(t) = four_sides(v, negated_atom, Kind::DR, None) {
        match t {
            Target::Any => "is surrounded by other objects".into(),
            Target::Class(c) if c == s => format!("is among the other {c}s"),
            Target::Class(c) => format!("is inside the {c}s"),
            Target::Landmark(id) => format!("is inside {id}"),
        }
    } else if let Some(t) = four_sides(v, atom_of, Kind::EC, Some(Quant::No)) {
        format!("touches {}", target_phrase(s, t, "no"))
    } else if let Some(t) = contacts_flush(v) {
        format!("lies flush wherever it touches {}", a_target(s, t))
    } else if let Some(t) = pair_of(v, Kind::AL, Some(Quant::Every), Dir::S, Dir::N) {
        format!("is in one row with {}", aligned_with(s, t))
    } else if let Some(t) = pair_of(v, Kind::AL, Some(Quant::Every), Dir::W, Dir::E) {
        format!("is in one column with {}", aligned_with(s, t))
    } else {
        generic_phrase(f)
    }
}

fn generic_inner(f: &Formula, top: bool) -> String {
    let wrap = |t: String| if top { t } else { format!("({t})") };
    match f {
        Formula::Atom(a) => atom_phrase(a),
        Formula::Shape(sh) => sh.to_string(),
        Formula::Turned(_) => "lies turned".to_string(),
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

fn generic(f: &Formula) -> Pred {
    Pred::Pos(generic_phrase(f))
}

/// The generic reading of `f`: "satisfies: …" and the formula in words.
fn generic_phrase(f: &Formula) -> String {
    format!("satisfies: {}", generic_inner(f, true))
}

/// The plural of a predicate: its first word (the verb) and "its".
fn plural(pred: &str) -> String {
    let (verb, rest) = pred.split_once(' ').unwrap_or((pred, ""));
    let verb = match verb {
        "is" => "are",
        "has" => "have",
        "does" => "do",
        "touches" => "touch",
        "lies" => "lie",
        "satisfies" => "satisfy",
        v => v,
    };
    let rest = rest.replace(" its ", " their ");
    let rest = rest
        .strip_prefix("its ")
        .map_or(rest.clone(), |r| format!("their {r}"));
    if rest.is_empty() {
        verb.to_string()
    } else {
        format!("{verb} {rest}")
    }
}

/// A one-line English reading of a per-object statement, e.g.
/// "every B is north of every R".
pub fn reading(f: &Formula) -> String {
    statement_reading(Scope::Each, f)
}

/// A one-line English reading of a statement with its scope, e.g.
/// "every B is north of every R", "at least one R touches w_west",
/// "no R touches w_west", "at least 2 Gs lie flush on the north side of
/// some other G".
pub fn statement_reading(scope: Scope, f: &Formula) -> String {
    let s = f.subject();
    if let Some((sh, neg)) = f.shape() {
        let not = if neg { "do not " } else { "" };
        return format!("the {}s {not}{}", sh.class, sh.kind.verb());
    }
    let pred = predicate(f);
    match scope {
        Scope::Each | Scope::Group | Scope::Scene(Quant::Every) => match pred {
            Pred::Pos(p) => format!("every {s} {p}"),
            Pred::Neg { no, .. } => format!("no {s} {no}"),
        },
        Scope::Scene(q) => {
            let p = match pred {
                Pred::Pos(p) => p,
                Pred::Neg { not, .. } => not,
            };
            let det = match q {
                Quant::Some => format!("at least one {s}"),
                Quant::No => format!("no {s}"),
                Quant::AtLeast(k) | Quant::AtMost(k) if k != 1 => format!("{q} {s}s"),
                _ => format!("{q} {s}"),
            };
            if plural_count(q) {
                format!("{det} {}", plural(&p))
            } else {
                format!("{det} {p}")
            }
        }
    }
}

// ---- implication ------------------------------------------------------------

/// Whether the target set of `x` is part of that of `y` for every object
/// of every scene.
fn target_within(x: &Target, y: &Target) -> bool {
    x == y || *y == Target::Any
}

/// `Some(k)` for the quantifiers that grow with the count (`some` = at
/// least 1), `None` otherwise.
fn at_least(q: Quant) -> Option<u32> {
    match q {
        Quant::Some => Some(1),
        Quant::AtLeast(k) => Some(k),
        _ => None,
    }
}

/// `Some(k)` for the quantifiers that shrink with the count (`no` = at most
/// 0), `None` otherwise.
fn at_most(q: Quant) -> Option<u32> {
    match q {
        Quant::No => Some(0),
        Quant::AtMost(k) => Some(k),
        _ => None,
    }
}

/// Whether atom `a` implies atom `b` (same subject) for every object of
/// every scene: `c` counts the target objects in the relation, `m` all of
/// them, and a stronger relation or a smaller target set never has a larger
/// `c` (nor, for `every`, a larger `m`).
fn atom_implies(a: &Atom, b: &Atom, contact: Contact) -> bool {
    if a.subject != b.subject {
        return false;
    }
    if at_least(b.quant) == Some(0) {
        return true; // `at least 0` always holds
    }
    if let (Some(ka), Some(kb)) = (at_least(a.quant), at_least(b.quant)) {
        return ka >= kb
            && target_within(&a.target, &b.target)
            && rel_implies(a.rel, b.rel, contact);
    }
    if let (Some(ka), Some(kb)) = (at_most(a.quant), at_most(b.quant)) {
        return kb >= ka
            && target_within(&b.target, &a.target)
            && rel_implies(b.rel, a.rel, contact);
    }
    if a.quant == Quant::Every && b.quant == Quant::Every {
        return target_within(&b.target, &a.target) && rel_implies(a.rel, b.rel, contact);
    }
    false
}

/// Whether `f` implies `g` (same subject) for every object of every scene,
/// proved by a truth table over their atoms restricted to the combinations
/// the implications between atoms allow (see the module documentation).
/// Sound but not complete: `false` may hide an implication. Gives `false`
/// beyond 16 distinct atoms.
pub(crate) fn implies(f: &Formula, g: &Formula, contact: Contact) -> bool {
    if f.subject() != g.subject() {
        return false;
    }
    // The truth table is over relation atoms; an orientation statement is
    // not one, so only a formula implies itself there.
    if f.mentions_turns() || g.mentions_turns() {
        return f == g;
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
            if i != j && atom_implies(a, b, contact) {
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

/// Whether statement `f` (with its scope) implies statement `g` in every
/// scene: per-object statements by `implies`; scene-level ones when the
/// formulas imply each other in the direction of their quantifiers
/// (`some`/`at least k` ⇒ `at least j ≤ k` when `f ⇒ g`; `no`/`at most k`
/// ⇒ `at most j ≥ k` when `g ⇒ f`). A per-object and a scene-level
/// statement are never compared.
pub fn rule_implies(f: (Scope, &Formula), g: (Scope, &Formula), contact: Contact) -> bool {
    match (f.0, g.0) {
        (Scope::Each, Scope::Each) => implies(f.1, g.1, contact),
        (Scope::Scene(qf), Scope::Scene(qg)) => {
            if let (Some(kf), Some(kg)) = (at_least(qf), at_least(qg)) {
                kf >= kg && implies(f.1, g.1, contact)
            } else if let (Some(kf), Some(kg)) = (at_most(qf), at_most(qg)) {
                kg >= kf && implies(g.1, f.1, contact)
            } else {
                false
            }
        }
        (Scope::Group, Scope::Group) => match (f.1.shape(), g.1.shape()) {
            (Some((a, false)), Some((b, false))) => {
                use crate::shapes::ShapeKind as K;
                a.class == b.class && (a.kind == b.kind || b.kind == K::Group)
            }
            (Some((a, true)), Some((b, true))) => {
                use crate::shapes::ShapeKind as K;
                a.class == b.class && (a.kind == b.kind || a.kind == K::Group)
            }
            _ => false,
        },
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::infer::templates as t;
    use crate::relations::Relation;
    use crate::rules::parse_rules;

    fn f(src: &str) -> Formula {
        parse_rules(&format!("rule x: {src}\n")).unwrap().rules[0]
            .formula
            .clone()
    }

    fn q(kind: Kind, dir: Dir, s: &str, quant: Quant, target: Target) -> Formula {
        Formula::Atom(Atom::quantified(Relation::new(kind, dir), s, quant, target))
    }

    fn class(c: &str) -> Target {
        Target::Class(c.into())
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
            ("FL_N(B, B)", "every B lies flush on the north side of some other B"),
            ("AL_S(B, G)", "every B has its south edge in line with some G"),
            ("!FL_W(B, *)", "no B lies flush on the west side of any other object"),
            ("FL_N(B, G) | FL_S(B, G) | FL_E(B, G) | FL_W(B, G)", "every B touches some G flush"),
        ];
        for (src, want) in cases {
            assert_eq!(reading(&f(src)), want, "{src}");
        }
    }

    #[test]
    fn readings_of_the_second_edition_shapes() {
        let w = Target::Landmark("w_west".into());
        let cases: Vec<(Scope, Formula, &str)> = vec![
            (
                Scope::Each,
                t::apart("R", &class("G")),
                "every R touches no G",
            ),
            (
                Scope::Each,
                t::apart("R", &Target::Any),
                "every R touches no other object",
            ),
            (
                Scope::Each,
                t::contacts_flush("B", &class("B")),
                "every B lies flush wherever it touches another B",
            ),
            (
                Scope::Each,
                t::row("B"),
                "every B is in one row with the other Bs",
            ),
            (
                Scope::Each,
                t::column("B"),
                "every B is in one column with the other Bs",
            ),
            (
                Scope::Each,
                t::flush_neighbour_ew("B"),
                "every B lies flush on the east or west side of some other B",
            ),
            (
                Scope::Each,
                t::flush_neighbour_ns("B"),
                "every B lies flush on the north or south side of some other B",
            ),
            (
                Scope::Scene(Quant::Some),
                t::touches("R", &w),
                "at least one R touches w_west",
            ),
            (
                Scope::Scene(Quant::No),
                t::touches("R", &w),
                "no R touches w_west",
            ),
            (
                Scope::Scene(Quant::AtLeast(2)),
                t::atom(Kind::FL, Dir::N, "G", &class("G")),
                "at least 2 Gs lie flush on the north side of some other G",
            ),
            (
                Scope::Scene(Quant::AtMost(1)),
                t::atom(Kind::AL, Dir::N, "G", &class("G")),
                "at most 1 G has its north edge in line with some other G",
            ),
            (
                Scope::Scene(Quant::AtLeast(3)),
                t::atom(Kind::AL, Dir::N, "G", &class("G")),
                "at least 3 Gs have their north edge in line with some other G",
            ),
            (
                Scope::Scene(Quant::Some),
                Formula::not(t::atom(Kind::DR, Dir::E, "B", &Target::Any)),
                "at least one B is not east of every other object",
            ),
            (
                Scope::Each,
                q(Kind::EC, Dir::N, "R", Quant::No, class("G")),
                "every R touches the north side of no G",
            ),
            (
                Scope::Each,
                q(Kind::EC, Dir::N, "B", Quant::AtLeast(2), class("B")),
                "every B touches the north side of at least 2 other Bs",
            ),
            (
                Scope::Each,
                t::atom(Kind::EC, Dir::E, "B", &w),
                "every B touches the east side of w_west",
            ),
            (
                Scope::Each,
                q(Kind::AL, Dir::S, "B", Quant::Every, class("B")),
                "every B has its south edge in line with every other B",
            ),
        ];
        for (scope, formula, want) in cases {
            assert_eq!(statement_reading(scope, &formula), want, "{formula:?}");
        }
    }

    #[test]
    fn implication_is_sound_on_known_cases() {
        let c = Contact::Point;
        let inside = f("!DR_N(B, W) & !DR_S(B, W) & !DR_E(B, W) & !DR_W(B, W)");
        assert!(implies(&inside, &f("!DR_N(B, W)"), c));
        assert!(!implies(&f("!DR_N(B, W)"), &inside, c));
        let touches_b = f("EC_N(B, B) | EC_S(B, B) | EC_E(B, B) | EC_W(B, B)");
        assert!(implies(
            &touches_b,
            &f("EC_N(B, *) | EC_S(B, *) | EC_E(B, *) | EC_W(B, *)"),
            c
        ));
        assert!(implies(&f("DR_N(B, *)"), &f("DR_N(B, R)"), c));
        assert!(!implies(&f("DR_N(B, R)"), &f("DR_N(B, *)"), c));
        assert!(!implies(&f("DR_N(B, R)"), &f("DR_N(G, R)"), c));
    }

    #[test]
    fn implication_reads_the_relation_table() {
        let c = Contact::Point;
        let b = class("B");
        // FL ⇒ EC, for "some": touches some B flush ⇒ touches some B.
        assert!(implies(&t::touches_flush("B", &b), &t::touches("B", &b), c));
        assert!(!implies(
            &t::touches("B", &b),
            &t::touches_flush("B", &b),
            c
        ));
        assert!(implies(
            &t::atom(Kind::FL, Dir::N, "B", &b),
            &t::atom(Kind::EC, Dir::N, "B", &Target::Any),
            Contact::Edge
        ));
        // "no" goes the other way: touches no * ⇒ touches no B; no EC ⇒ no FL.
        assert!(implies(&t::apart("B", &Target::Any), &t::apart("B", &b), c));
        assert!(!implies(
            &t::apart("B", &b),
            &t::apart("B", &Target::Any),
            c
        ));
        let no_ec = q(Kind::EC, Dir::N, "B", Quant::No, b.clone());
        let no_fl = q(Kind::FL, Dir::N, "B", Quant::No, b.clone());
        assert!(implies(&no_ec, &no_fl, c));
        assert!(!implies(&no_fl, &no_ec, c));
        // at least 2 ⇒ some; some ⇏ at least 2.
        let two = q(Kind::EC, Dir::N, "B", Quant::AtLeast(2), b.clone());
        let some = t::atom(Kind::EC, Dir::N, "B", &b);
        assert!(implies(&two, &some, c));
        assert!(!implies(&some, &two, c));
        // every: EC_N every ⇒ DR_N every (EC ⇒ DR); a landmark is part of *.
        let ec_every = q(Kind::EC, Dir::N, "B", Quant::Every, Target::Any);
        let dr_lm = t::atom(Kind::DR, Dir::N, "B", &Target::Landmark("w".into()));
        assert!(implies(&ec_every, &dr_lm, c));
        // Scene-level statements.
        let w = Target::Landmark("w".into());
        let some_touch = (Scope::Scene(Quant::Some), &t::touches("B", &w));
        let fl = t::touches_flush("B", &w);
        let some_flush = (Scope::Scene(Quant::Some), &fl);
        assert!(rule_implies(some_flush, some_touch, c));
        assert!(!rule_implies(some_touch, some_flush, c));
        let no_touch = (Scope::Scene(Quant::No), some_touch.1);
        let no_flush = (Scope::Scene(Quant::No), &fl);
        assert!(rule_implies(no_touch, no_flush, c));
        assert!(!rule_implies(no_flush, no_touch, c));
        assert!(!rule_implies((Scope::Each, some_touch.1), some_touch, c));
    }
}
