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

/// `log10 P` of a statement that a slip repairs (docs/guide.md#slips):
/// `P = s·P' + (1 − s)`, with `P'` the posterior as if the slipped object
/// were left out and `s` the chance that it is a slip, from the slip's
/// `log10` odds. Never below `P'`, never above 1, falling as the odds rise;
/// with odds 0 (`s = 0`, slip rate 0) it is 1: the thesis's verdict on a
/// broken statement.
pub(crate) fn log10_posterior_repaired(log10_p_corrected: f64, log10_odds: f64) -> f64 {
    let log10_s = -log10_sum(0.0, -log10_odds);
    let log10_not_slip = -log10_sum(0.0, log10_odds);
    log10_sum(log10_s + log10_p_corrected, log10_not_slip).min(0.0)
}

impl Posterior {
    /// A statement that a slip repairs (docs/guide.md#slips): the chance
    /// likelihood and posterior `P'` of `n` subjects all keeping it (the
    /// slip left out), mixed with "not meant" by the slip's `log10` odds.
    pub fn repaired(q: f64, epsilon: f64, n: u64, prior: f64, log10_odds: f64) -> Self {
        let corrected = Posterior::new(q, epsilon, n, prior);
        Posterior {
            log10_posterior: log10_posterior_repaired(corrected.log10_posterior, log10_odds),
            ..corrected
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

        /// Law: a repaired statement's posterior lies between the
        /// corrected posterior `P'` and 1 (normalised: a mixture of the two
        /// hypotheses).
        #[test]
        fn a_repaired_posterior_is_a_probability_between(corrected in -300.0..0.0f64, odds in -50.0..300.0f64) {
            let p = log10_posterior_repaired(corrected, odds);
            proptest::prop_assert!(p <= 0.0 && p >= corrected - 1e-12, "{p} vs {corrected}");
        }

        /// Law: the likelier the slip, the likelier the statements it
        /// repairs are meant (monotone in the odds); a slip that is sure
        /// gives the corrected posterior.
        #[test]
        fn likelier_slips_lower_the_posterior(corrected in -300.0..-0.01f64, a in -50.0..300.0f64, d in 0.0..100.0f64) {
            let lo = log10_posterior_repaired(corrected, a);
            let hi = log10_posterior_repaired(corrected, a + d);
            proptest::prop_assert!(hi <= lo + 1e-12, "{hi} > {lo}");
            let sure = log10_posterior_repaired(corrected, 400.0);
            proptest::prop_assert!((sure - corrected).abs() < 1e-9, "{sure} vs {corrected}");
        }
    }

    /// At slip rate 0 (odds `−∞`) a broken statement keeps the thesis's
    /// verdict: not meant.
    #[test]
    fn no_slip_leaves_a_broken_statement_not_meant() {
        assert_eq!(log10_posterior_repaired(-50.0, f64::NEG_INFINITY), 0.0);
    }

    #[test]
    fn log10_sum_is_stable() {
        assert_eq!(log10_sum(-1000.0, f64::NEG_INFINITY), -1000.0);
        assert!((log10_sum(0.0, 0.0) - 2f64.log10()).abs() < 1e-15);
        assert!((log10_sum(-400.0, -0.301) - -0.301).abs() < 1e-15);
    }
}
