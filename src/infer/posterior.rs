//! Chance rates, likelihoods and posteriors (docs/guide.md), in log space.
//!
//! # Background
//!
//! A candidate `φ` with subject class `A` has chance rate `q` (the fraction
//! of class-`A` objects of the random scenes that satisfy it) and
//! `p = max(ε, q)`. The likelihood that the `n` class-`A` objects of the
//! demonstrations satisfied it by chance is `L = pⁿ`, and the posterior that
//! it is *not* one of the demonstrator's rules is
//! `P = π·L / (π·L + 1 − π)`.
//!
//! # Practical
//!
//! `L` underflows a double quickly (`0.01^200`), so everything is computed as
//! `log10`: `log10 L = n·log10 p` and
//! `log10 P = log10 π + log10 L − log10(π·L + 1 − π)`, the last term by a
//! stable log-sum-exp. Only when a value is *written* is it turned back into
//! a number, floored at [`P_FLOOR`] since a `.rcc` file requires `0 < P`.

/// The smallest posterior written to a `.rcc` file (docs/guide.md#learning).
pub(crate) const P_FLOOR: f64 = 1e-300;

/// `p = max(ε, q)`.
pub(crate) fn chance_p(q: f64, epsilon: f64) -> f64 {
    q.max(epsilon)
}

/// `log10 L = n·log10 p` for `0 < p ≤ 1`.
pub(crate) fn log10_likelihood(p: f64, n: u64) -> f64 {
    if n == 0 {
        return 0.0;
    }
    n as f64 * p.log10()
}

/// `log10(10^a + 10^b)`, stable for any magnitudes.
fn log10_sum(a: f64, b: f64) -> f64 {
    let (hi, lo) = if a >= b { (a, b) } else { (b, a) };
    if lo == f64::NEG_INFINITY {
        return hi;
    }
    hi + (10f64.powf(lo - hi)).ln_1p() / std::f64::consts::LN_10
}

/// `log10 P` with `P = π·L / (π·L + 1 − π)`, from `log10 L` and the prior
/// `π ∈ (0, 1)`.
pub(crate) fn log10_posterior(log10_l: f64, prior: f64) -> f64 {
    let a = prior.log10() + log10_l;
    let b = (1.0 - prior).log10();
    a - log10_sum(a, b)
}

/// The posterior as written: `10^log10_p`, at least [`P_FLOOR`].
pub(crate) fn written_posterior(log10_p: f64) -> f64 {
    let p = 10f64.powf(log10_p);
    if p.is_finite() && p >= P_FLOOR {
        p
    } else {
        P_FLOOR
    }
}

/// All numbers for one candidate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Posterior {
    /// `p = max(ε, q)`.
    pub p: f64,
    /// `log10 L = n·log10 p`.
    pub log10_likelihood: f64,
    /// `log10 P`.
    pub log10_posterior: f64,
}

/// `log10` of the posterior that a statement is not meant when `f` of its
/// `n` subjects break it, with slip rate `η` (docs/guide.md#slips): by
/// chance each subject keeps it with `p` and breaks it with `1 − p`; meant,
/// each keeps it with `1 − η + η·p` and breaks it with `η·(1 − p)` (a slip
/// lands at random). `η = 0, f = 0` is the thesis's `log10 P`; with `η = 0`
/// a statement some subject breaks is never meant (the caller does not ask).
pub(crate) fn log10_posterior_with_slips(p: f64, n: u64, f: u64, eta: f64, prior: f64) -> f64 {
    let kept = n.saturating_sub(f) as f64;
    let f = f as f64;
    let l0 = kept * p.log10() + if f > 0.0 { f * (1.0 - p).log10() } else { 0.0 };
    let keep1 = 1.0 - eta + eta * p;
    let l1 = kept * keep1.log10()
        + if f > 0.0 {
            f * (eta * (1.0 - p)).log10()
        } else {
            0.0
        };
    let a = prior.log10() + l0;
    let b = (1.0 - prior).log10() + l1;
    a - log10_sum(a, b)
}

impl Posterior {
    /// With slips (docs/guide.md#slips): `f` of the `n`
    /// subjects break the statement, slip rate `eta`; `log10_likelihood`
    /// is the chance likelihood of what was seen. A statement nothing
    /// breaks (`f = 0`) is weighed exactly as [`Posterior::new`] weighs it,
    /// whatever `eta`: what every demonstration keeps is learned as before,
    /// and slips only enter for statements with exceptions.
    pub fn with_slips(q: f64, epsilon: f64, n: u64, f: u64, eta: f64, prior: f64) -> Self {
        if f == 0 {
            return Posterior::new(q, epsilon, n, prior);
        }
        let p = chance_p(q, epsilon).min(1.0 - 1e-12);
        let kept = n.saturating_sub(f);
        let log10_likelihood = log10_likelihood(p, kept) + f as f64 * (1.0 - p).log10();
        Posterior {
            p,
            log10_likelihood,
            log10_posterior: log10_posterior_with_slips(p, n, f, eta, prior),
        }
    }

    /// Compute from the chance rate `q`, the floor `ε`, the object count `n`
    /// and the prior `π`.
    pub fn new(q: f64, epsilon: f64, n: u64, prior: f64) -> Self {
        let p = chance_p(q, epsilon);
        let log10_likelihood = log10_likelihood(p, n);
        Posterior {
            p,
            log10_likelihood,
            log10_posterior: log10_posterior(log10_likelihood, prior),
        }
    }
    /// The posterior as written (floored at 1e-300, the smallest a `.rcc`
    /// file holds).
    pub fn written(&self) -> f64 {
        written_posterior(self.log10_posterior)
    }
    /// Whether the candidate is learned at `cutoff`: `P < cutoff`, decided in
    /// log space.
    pub fn learned(&self, cutoff: f64) -> bool {
        self.log10_posterior < cutoff.log10()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/guide.md#learning worked check.
    #[test]
    fn worked_check() {
        let cases = [
            (0.4, 4, 0.0256, 0.0256 / 1.0256),
            (0.01, 4, 1e-8, 1e-8 / (1.0 + 1e-8)),
            (0.3, 3, 0.027, 0.027 / 1.027),
        ];
        let mut learned = Vec::new();
        for (q, n, l, post) in cases {
            let p = Posterior::new(q, 1e-6, n, 0.5);
            assert!((10f64.powf(p.log10_likelihood) - l).abs() <= 1e-12 * l);
            assert!((p.written() - post).abs() <= 1e-12 * post);
            learned.push(p.learned(0.01));
        }
        assert_eq!(learned, [false, true, false]);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig { cases: 256, ..Default::default() })]

        /// Law: for `L ≪ 1` at prior 0.5 the posterior agrees with the
        /// unnormalised product `L`: `P = L/(L+1)`, so
        /// `0 ≤ L − P = L²/(1+L) ≤ L²` — checked up to the rounding of the
        /// `log10 → value` conversion, a relative `ln 10 · |log10 L| · ε_mach`
        /// (times a small factor).
        #[test]
        fn small_likelihood_posterior_is_the_product(log10_l in -300.0..-3.0f64) {
            let l = 10f64.powf(log10_l);
            let p = 10f64.powf(log10_posterior(log10_l, 0.5));
            let rounding = 4.0 * std::f64::consts::LN_10 * (1.0 - log10_l) * f64::EPSILON * l;
            proptest::prop_assert!((l - p).abs() <= l * l + rounding, "L {l}, P {p}");
        }

        /// Law: a higher prior gives a higher posterior for the same L.
        #[test]
        fn higher_prior_gives_higher_posterior(log10_l in -400.0..0.0f64, a in 1e-6..0.999f64, f in 1.001..2.0f64) {
            let b = (a * f).min(1.0 - 1e-9);
            proptest::prop_assume!(b > a);
            proptest::prop_assert!(log10_posterior(log10_l, a) < log10_posterior(log10_l, b));
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig { cases: 256, ..Default::default() })]

        /// Law: at slip rate 0 with nothing broken, the thesis's posterior
        /// exactly.
        #[test]
        fn slips_at_rate_zero_are_the_thesis(q in 1e-6..1.0f64, n in 1u64..500, prior in 0.01..0.99f64) {
            let a = Posterior::new(q, 1e-6, n, prior);
            let b = Posterior::with_slips(q, 1e-6, n, 0, 0.0, prior);
            proptest::prop_assert_eq!(a, b);
        }

        /// Law: every further exception makes "not meant" more likely
        /// (monotone in the number of exceptions).
        #[test]
        fn more_exceptions_raise_the_posterior(p in 0.01..0.99f64, n in 4u64..300, eta in 0.001..0.4f64, prior in 0.05..0.95f64) {
            let mut last = f64::NEG_INFINITY;
            for f in 0..4u64.min(n) {
                let now = log10_posterior_with_slips(p, n, f, eta, prior);
                proptest::prop_assert!(now >= last - 1e-12, "f {f}: {now} < {last}");
                last = now;
            }
        }

        /// Law: the per-subject probabilities of each hypothesis sum to 1
        /// (the likelihoods are normalised), and the posterior is a
        /// probability.
        #[test]
        fn slip_likelihoods_are_normalised(p in 0.0..1.0f64, eta in 0.0..0.5f64, n in 1u64..100, f in 0u64..3, prior in 0.01..0.99f64) {
            let meant = (1.0 - eta + eta * p) + eta * (1.0 - p);
            let chance = p + (1.0 - p);
            proptest::prop_assert!((meant - 1.0).abs() < 1e-12 && (chance - 1.0).abs() < 1e-12);
            let f = f.min(n);
            proptest::prop_assume!(p > 0.0 && p < 1.0 && (eta > 0.0 || f == 0));
            let post = log10_posterior_with_slips(p, n, f, eta, prior);
            proptest::prop_assert!(post <= 1e-12, "{post}");
        }
    }

    #[test]
    fn log10_sum_is_stable() {
        assert_eq!(log10_sum(-1000.0, f64::NEG_INFINITY), -1000.0);
        assert!((log10_sum(0.0, 0.0) - 2f64.log10()).abs() < 1e-15);
        assert!((log10_sum(-400.0, -0.301) - -0.301).abs() < 1e-15);
    }
}
