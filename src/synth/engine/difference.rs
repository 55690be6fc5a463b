//! One propagator per pair of grid variables for every Boolean
//! `l ⇔ a − b ≥ k` on that pair (the model's `DiffGe`).
//!
//! # Background
//!
//! Every pairwise relation (`DR_N`, the two sides of an `EC`, `AL`, `FL`)
//! reifies a difference of two coordinates against a constant: a 20-object
//! box has about 2 600 of them over 40 variables, about 7 per pair of
//! variables and 130 per variable. Posted as reified linear constraints,
//! each is its own propagator, so every bound change of a coordinate wakes
//! some 130 propagators, most of which can do nothing. Here the literals of
//! one pair share one propagator: a bound change wakes it once, and it
//! looks at a handful of thresholds.
//!
//! # Propagation
//!
//! With `[lo_a, hi_a]`, `[lo_b, hi_b]` the bounds and `l ⇔ a − b ≥ k`:
//!
//! - `lo_a − hi_b ≥ k` sets `l`, because `[a ≥ hi_b + k] ∧ [b ≤ hi_b]`;
//! - `hi_a − lo_b < k` clears `l`, because `[a ≤ hi_a] ∧ [b ≥ hi_a − k + 1]`;
//! - a set `l` gives `a ≥ lo_b + k` (with `[b ≥ lo_b]`) and
//!   `b ≤ hi_a − k` (with `[a ≤ hi_a]`);
//! - a cleared `l` gives `a ≤ hi_b + k − 1` (with `[b ≤ hi_b]`) and
//!   `b ≥ lo_a − k + 1` (with `[a ≥ lo_a]`).
//!
//! These are exactly the propagations (and lifted explanations) of the
//! reified linear `b − a ≤ −k`, so the search is the one the reified
//! constraints gave: the same nodes, fewer wake-ups. A literal of the
//! reversed pair, `b − a ≥ k`, is stored as the negation of `a − b ≥ 1 − k`.
//!
//! # How to extend
//!
//! The literals of a pair are monotone in `k` (`a − b ≥ k` implies every
//! smaller threshold); a sorted sweep could set them at once where now each
//! is set from the bounds it moved.

use pumpkin_core::declare_inference_label;
use pumpkin_core::predicate;
use pumpkin_core::predicates::{Predicate, PropositionalConjunction};
use pumpkin_core::proof::{ConstraintTag, InferenceCode};
use pumpkin_core::propagation::{
    DomainEvents, EventsToRegister, LocalId, Priority, PropagationContext, Propagator,
    PropagatorConstructor, PropagatorConstructorContext, PropagatorSpec, ReadDomains,
    RuntimeCheckers,
};
use pumpkin_core::state::PropagationStatusCP;
use pumpkin_core::variables::{DomainId, Literal};

use super::no_overlap::clamp;

declare_inference_label!(Difference);

/// Posts [`DifferencePropagator`]: `lits[i].1 ⇔ a − b ≥ lits[i].0`.
#[derive(Debug, Clone)]
pub(super) struct DifferenceArgs {
    pub(super) a: DomainId,
    pub(super) b: DomainId,
    pub(super) lits: Vec<(i32, Literal)>,
    pub(super) tag: ConstraintTag,
}

impl PropagatorConstructor for DifferenceArgs {
    type PropagatorImpl = DifferencePropagator;

    fn create(self, _: PropagatorConstructorContext) -> PropagatorSpec<Self::PropagatorImpl> {
        let mut registration = EventsToRegister::builder()
            .add(&self.a, DomainEvents::BOUNDS, LocalId::from(0))
            .add(&self.b, DomainEvents::BOUNDS, LocalId::from(1));
        for (i, (_, l)) in self.lits.iter().enumerate() {
            let id = u32::try_from(i + 2).unwrap_or(u32::MAX);
            registration = registration.add(l, DomainEvents::ASSIGN, LocalId::from(id));
        }
        PropagatorSpec {
            registration: registration.build(),
            checkers: RuntimeCheckers::empty(),
            propagator: DifferencePropagator {
                a: self.a,
                b: self.b,
                lits: self.lits,
                code: InferenceCode::new(self.tag, Difference),
            },
        }
    }
}

/// The reified differences of one pair; see the module documentation.
#[derive(Debug, Clone)]
pub(super) struct DifferencePropagator {
    a: DomainId,
    b: DomainId,
    lits: Vec<(i32, Literal)>,
    code: InferenceCode,
}

/// `[v ≥ x]`, or nothing when every value of a grid variable (all ≥ 0)
/// satisfies it.
fn at_least(out: &mut PropositionalConjunction, v: DomainId, x: i64) {
    if x > 0 {
        out.push(predicate![v >= clamp(x)]);
    }
}

fn reason(ps: impl IntoIterator<Item = Predicate>) -> PropositionalConjunction {
    let mut r = PropositionalConjunction::default();
    for p in ps {
        r.push(p);
    }
    r
}

impl Propagator for DifferencePropagator {
    fn name(&self) -> &str {
        "Difference"
    }

    fn priority(&self) -> Priority {
        Priority::High
    }

    fn propagate_from_scratch(&self, mut ctx: PropagationContext) -> PropagationStatusCP {
        let (a, b) = (self.a, self.b);
        for &(k, l) in &self.lits {
            let k = i64::from(k);
            let (lo_a, hi_a) = (
                i64::from(ctx.lower_bound(&a)),
                i64::from(ctx.upper_bound(&a)),
            );
            let (lo_b, hi_b) = (
                i64::from(ctx.lower_bound(&b)),
                i64::from(ctx.upper_bound(&b)),
            );
            match ctx.evaluate_literal(l) {
                None => {
                    if lo_a - hi_b >= k {
                        let mut r = reason([predicate![b <= clamp(hi_b)]]);
                        at_least(&mut r, a, hi_b + k);
                        ctx.post(l.get_true_predicate(), (r, &self.code))?;
                    } else if hi_a - lo_b < k {
                        let mut r = reason([predicate![a <= clamp(hi_a)]]);
                        at_least(&mut r, b, hi_a - k + 1);
                        ctx.post(l.get_false_predicate(), (r, &self.code))?;
                    }
                }
                Some(true) => {
                    if lo_b + k > lo_a {
                        let mut r = reason([l.get_true_predicate()]);
                        at_least(&mut r, b, lo_b);
                        ctx.post(predicate![a >= clamp(lo_b + k)], (r, &self.code))?;
                    }
                    if hi_a - k < hi_b {
                        let r = reason([l.get_true_predicate(), predicate![a <= clamp(hi_a)]]);
                        ctx.post(predicate![b <= clamp(hi_a - k)], (r, &self.code))?;
                    }
                }
                Some(false) => {
                    if hi_b + k - 1 < hi_a {
                        let r = reason([l.get_false_predicate(), predicate![b <= clamp(hi_b)]]);
                        ctx.post(predicate![a <= clamp(hi_b + k - 1)], (r, &self.code))?;
                    }
                    if lo_a - k + 1 > lo_b {
                        let mut r = reason([l.get_false_predicate()]);
                        at_least(&mut r, a, lo_a);
                        ctx.post(predicate![b >= clamp(lo_a - k + 1)], (r, &self.code))?;
                    }
                }
            }
        }
        Ok(())
    }
}
