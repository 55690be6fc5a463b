//! The formula builders of the templates (and of the runtime study's pool,
//! the bench crate's `pool`): one function per statement shape, built through the AST.

use crate::relations::{Dir, Kind, Quant, Relation};
use crate::rules::{Atom, Formula, Shape, Target};
use crate::shapes::ShapeKind;

/// `REL(subject, target)` with the relation's default quantifier.
pub fn atom(kind: Kind, dir: Dir, subject: &str, target: &Target) -> Formula {
    Formula::Atom(Atom::new(Relation::new(kind, dir), subject, target.clone()))
}

/// `REL(subject, Q target)`.
pub fn quantified(kind: Kind, dir: Dir, subject: &str, quant: Quant, target: &Target) -> Formula {
    Formula::Atom(Atom::quantified(
        Relation::new(kind, dir),
        subject,
        quant,
        target.clone(),
    ))
}

/// `K_N(A,B) | K_S(A,B) | K_E(A,B) | K_W(A,B)`.
pub fn any_side(kind: Kind, subject: &str, target: &Target) -> Formula {
    Formula::Or(
        Dir::ALL
            .iter()
            .map(|&d| atom(kind, d, subject, target))
            .collect(),
    )
}

/// `EC_N(A,B) | EC_S(A,B) | EC_E(A,B) | EC_W(A,B)`: touches some `B`.
pub fn touches(subject: &str, target: &Target) -> Formula {
    any_side(Kind::EC, subject, target)
}

/// `FL_N(A,B) | FL_S(A,B) | FL_E(A,B) | FL_W(A,B)`: touches some `B` flush.
pub fn touches_flush(subject: &str, target: &Target) -> Formula {
    any_side(Kind::FL, subject, target)
}

/// `!DR_N(A,B) & !DR_S(A,B) & !DR_E(A,B) & !DR_W(A,B)`: among the `B`s
/// (e.g. inside a box).
pub fn inside(subject: &str, target: &Target) -> Formula {
    Formula::And(
        Dir::ALL
            .iter()
            .map(|&d| Formula::not(atom(Kind::DR, d, subject, target)))
            .collect(),
    )
}

/// `EC_N(A, no B) & EC_S(A, no B) & EC_E(A, no B) & EC_W(A, no B)`:
/// touches no `B`.
pub fn apart(subject: &str, target: &Target) -> Formula {
    Formula::And(
        Dir::ALL
            .iter()
            .map(|&d| quantified(Kind::EC, d, subject, Quant::No, target))
            .collect(),
    )
}

/// `(!EC_N(A,B) | FL_N(A,B)) & … & (!EC_W(A,B) | FL_W(A,B))`: every
/// contact with a `B` is flush.
pub fn contacts_flush(subject: &str, target: &Target) -> Formula {
    Formula::And(
        Dir::ALL
            .iter()
            .map(|&d| {
                Formula::Or(vec![
                    Formula::not(atom(Kind::EC, d, subject, target)),
                    atom(Kind::FL, d, subject, target),
                ])
            })
            .collect(),
    )
}

/// `AL_a(A, every A) & AL_b(A, every A)`.
fn aligned_with_all(subject: &str, a: Dir, b: Dir) -> Formula {
    let own = Target::Class(subject.to_string());
    Formula::And(vec![
        quantified(Kind::AL, a, subject, Quant::Every, &own),
        quantified(Kind::AL, b, subject, Quant::Every, &own),
    ])
}

/// `AL_S(A, every A) & AL_N(A, every A)`: in one row with the other `A`s.
pub fn row(subject: &str) -> Formula {
    aligned_with_all(subject, Dir::S, Dir::N)
}

/// `AL_W(A, every A) & AL_E(A, every A)`: in one column with the other `A`s.
pub fn column(subject: &str) -> Formula {
    aligned_with_all(subject, Dir::W, Dir::E)
}

/// `FL_a(A,A) | FL_b(A,A)`.
fn flush_neighbour(subject: &str, a: Dir, b: Dir) -> Formula {
    let own = Target::Class(subject.to_string());
    Formula::Or(vec![
        atom(Kind::FL, a, subject, &own),
        atom(Kind::FL, b, subject, &own),
    ])
}

/// `FL_E(A,A) | FL_W(A,A)`: a flush neighbour east or west.
pub fn flush_neighbour_ew(subject: &str) -> Formula {
    flush_neighbour(subject, Dir::E, Dir::W)
}

/// `FL_N(A,A) | FL_S(A,A)`: a flush neighbour north or south.
pub fn flush_neighbour_ns(subject: &str) -> Formula {
    flush_neighbour(subject, Dir::N, Dir::S)
}

/// Contact on two adjacent sides:
/// `(EC_N(A,*) & EC_W(A,*)) | (EC_W(A,*) & EC_S(A,*)) | (EC_S(A,*) & EC_E(A,*)) | (EC_E(A,*) & EC_N(A,*))`.
pub fn corner(subject: &str) -> Formula {
    let any = Target::Any;
    let pair = |a: Dir, b: Dir| {
        Formula::And(vec![
            atom(Kind::EC, a, subject, &any),
            atom(Kind::EC, b, subject, &any),
        ])
    };
    Formula::Or(vec![
        pair(Dir::N, Dir::W),
        pair(Dir::W, Dir::S),
        pair(Dir::S, Dir::E),
        pair(Dir::E, Dir::N),
    ])
}

/// `column(A)` and its kin: the statement that all `A`s form one shape.
pub fn group_shape(kind: ShapeKind, subject: &str) -> Formula {
    Formula::Shape(Shape::new(kind, subject))
}
