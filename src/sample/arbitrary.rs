//! `Arbitrary` scenes and rule sets for cargo-fuzz users (`--features
//! arbitrary`): every value is a valid input, so a fuzzer spends
//! its time past the input checks.
//!
//! * [`Scene`]: a space of 1 to 16 grid steps a side (grid 1 to 20), up to
//!   8 objects of classes `A`, `B`, `C`, `W` (`W` fixed), sizes from 1 to 4
//!   grid steps; objects placed or not, on the grid, inside the space and
//!   never overlapping (an object that would overlap is left unplaced; a
//!   fixed one that would is dropped). Ids `o0`, `o1`, … are unique.
//! * [`RuleSet`]: up to 6 rules named `r0`, `r1`, … over the classes `A`,
//!   `B`, `C`, `W` and `*`, with formulas up to depth 3, every quantifier,
//!   scene-level scopes, weights, posteriors and `hard`: it prints as a
//!   `.rcc` file that parses back to the same rules.
//! * [`Task`]: a problem scene and rules about the classes it has (no
//!   error for a class the scene lacks), e.g. for fuzzing synthesis.

use crate::relations::{Quant, Relation};
use crate::rules::{Atom, Formula, Rule, RuleSet, Scope, Strength, Target};
use crate::scene::{Object, Scene, Space};
use arbitrary::{Arbitrary, Result, Unstructured};

const CLASSES: [&str; 4] = ["A", "B", "C", "W"];

impl<'a> Arbitrary<'a> for Scene {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        let grid: i64 = u.int_in_range(1..=20)?;
        let nx: i64 = u.int_in_range(1..=16)?;
        let ny: i64 = u.int_in_range(1..=16)?;
        let space = Space {
            x: u.int_in_range(-3..=3)? * grid,
            y: u.int_in_range(-3..=3)? * grid,
            width: nx * grid,
            height: ny * grid,
        };
        let n: usize = u.int_in_range(0..=8)?;
        let mut objects: Vec<Object> = Vec::with_capacity(n);
        for i in 0..n {
            let class = *u.choose(&CLASSES)?;
            let fixed = class == "W";
            let w = u.int_in_range(1..=4.min(nx))? * grid;
            let h = u.int_in_range(1..=4.min(ny))? * grid;
            let mut o = Object {
                id: format!("o{i}"),
                class: class.to_string(),
                x: None,
                y: None,
                width: w,
                height: h,
                fixed,
                turnable: false,
                turned: false,
            };
            if fixed || u.arbitrary::<bool>()? {
                let gx = u.int_in_range(0..=(nx - w / grid))?;
                let gy = u.int_in_range(0..=(ny - h / grid))?;
                let r = crate::scene::Rect::new(space.x + gx * grid, space.y + gy * grid, w, h);
                let free = objects
                    .iter()
                    .filter_map(Object::rect)
                    .all(|p| !p.interiors_overlap(&r));
                if free {
                    o.x = Some(r.x);
                    o.y = Some(r.y);
                } else if fixed {
                    continue;
                }
            }
            objects.push(o);
        }
        Ok(Scene {
            space,
            grid,
            objects,
        })
    }
}

fn quant(u: &mut Unstructured<'_>) -> Result<Quant> {
    Ok(match u.int_in_range(0..=4)? {
        0 => Quant::Every,
        1 => Quant::Some,
        2 => Quant::No,
        3 => Quant::AtLeast(u.int_in_range(0..=3)?),
        _ => Quant::AtMost(u.int_in_range(0..=3)?),
    })
}

fn formula(
    u: &mut Unstructured<'_>,
    subject: &str,
    classes: &[&str],
    depth: u32,
) -> Result<Formula> {
    let leaf = depth == 0 || u.ratio(1, 2)?;
    if leaf {
        let rel = *u.choose(&Relation::ALL)?;
        let target = if u.ratio(1, 4)? {
            Target::Any
        } else {
            Target::Class(u.choose(classes)?.to_string())
        };
        return Ok(Formula::Atom(if u.arbitrary::<bool>()? {
            Atom::quantified(rel, subject, quant(u)?, target)
        } else {
            Atom::new(rel, subject, target)
        }));
    }
    Ok(match u.int_in_range(0..=2)? {
        0 => Formula::not(formula(u, subject, classes, depth - 1)?),
        k => {
            let n = u.int_in_range(2..=3)?;
            let parts = (0..n)
                .map(|_| formula(u, subject, classes, depth - 1))
                .collect::<Result<Vec<_>>>()?;
            // Flattened as the parser does, so printing round-trips.
            let flat = |parts: Vec<Formula>, and: bool| -> Vec<Formula> {
                parts
                    .into_iter()
                    .flat_map(|f| match (f, and) {
                        (Formula::And(v), true) | (Formula::Or(v), false) => v,
                        (f, _) => vec![f],
                    })
                    .collect()
            };
            if k == 1 {
                Formula::And(flat(parts, true))
            } else {
                Formula::Or(flat(parts, false))
            }
        }
    })
}

/// Up to 6 rules whose classes are drawn from `classes` (non-empty).
fn rules(u: &mut Unstructured<'_>, classes: &[&str]) -> Result<RuleSet> {
    let n = u.int_in_range(0..=6)?;
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let subject = *u.choose(classes)?;
        let f = formula(u, subject, classes, 3)?;
        let strength = match u.int_in_range(0..=3)? {
            0 => Strength::Weight(1.0),
            1 => Strength::Weight(f64::from(u.int_in_range(1u32..=1000)?) / 10.0),
            2 => Strength::P(f64::from(u.int_in_range(1u32..=999)?) / 1000.0),
            _ => Strength::Hard,
        };
        let scope = if u.ratio(1, 4)? {
            Scope::of(quant(u)?)
        } else {
            Scope::Each
        };
        out.push(
            Rule::new(format!("r{i}"), f)
                .with_strength(strength)
                .with_scope(scope),
        );
    }
    Ok(RuleSet::new(out))
}

impl<'a> Arbitrary<'a> for RuleSet {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        rules(u, &CLASSES)
    }
}

/// A problem and rules about the classes it has.
#[derive(Debug, Clone)]
pub struct Task {
    /// A valid scene (some objects may be unplaced).
    pub problem: Scene,
    /// Rules whose classes all occur in `problem` (none when it has no
    /// object).
    pub rules: RuleSet,
}

impl<'a> Arbitrary<'a> for Task {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        let problem = Scene::arbitrary(u)?;
        let mut classes: Vec<&str> = CLASSES
            .iter()
            .copied()
            .filter(|c| problem.objects.iter().any(|o| o.class == *c))
            .collect();
        classes.dedup();
        let rules = if classes.is_empty() {
            RuleSet::default()
        } else {
            rules(u, &classes)?
        };
        Ok(Task { problem, rules })
    }
}
