//! Real rule weights → integer objective coefficients, and the set of values
//! the integer objective can take.
//!
//! # Precision
//!
//! When every weight is an integer (the default weight 1, `weight 2`, …) the
//! integers are used exactly (divided by their gcd). Otherwise each weight is
//! rounded to `round(w · 10^p)` with the largest `p ≤ 6` for which the total
//! stays below 2^30 (the solver works in `i32`), then divided by the gcd.
//! Equal real weights always get equal coefficients. Two layouts whose real
//! numerators differ by less than the rounding error (at most `n/2 · 10^-p`
//! for `n` objective terms) may therefore be ordered differently than by the
//! exact score; the reported score is always recomputed exactly by the
//! evaluator.

/// Largest total of the integer coefficients.
const MAX_TOTAL: i64 = 1 << 30;

/// Integer coefficients for `weights` (all > 0), or `None` when even
/// `p = 0` overflows.
pub(super) fn integer_weights(weights: &[f64]) -> Option<Vec<i64>> {
    if weights.is_empty() {
        return Some(Vec::new());
    }
    // Divided by their gcd *before* the total is checked: `weight
    // 1000000000` and `weight 2000000000` are 1 and 2.
    let reduced = |mut v: Vec<i64>| {
        let g = v.iter().fold(0, |g, &x| gcd(g, x));
        if g > 1 {
            for x in &mut v {
                *x /= g;
            }
        }
        // Summed in i128: many terms of up to 1e12 must not overflow.
        let total: i128 = v.iter().map(|&x| i128::from(x)).sum();
        (total <= i128::from(MAX_TOTAL)).then_some(v)
    };
    let all_int = weights.iter().all(|w| w.fract() == 0.0 && *w < 1e12);
    if all_int {
        if let Some(v) = reduced(weights.iter().map(|&w| w as i64).collect()) {
            return Some(v);
        }
    }
    (0..=6).rev().find_map(|p| {
        let k = 10f64.powi(p);
        reduced(
            weights
                .iter()
                .map(|&w| ((w * k).round() as i64).max(1))
                .collect(),
        )
    })
}

fn gcd(a: i64, b: i64) -> i64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// Largest total for which [`SubsetSums`] is computed.
const MAX_DP: i64 = 1 << 24;

/// Which totals `Σ_{i∈S} c_i` are reachable, for stepping an upper bound
/// down to the next achievable objective value.
#[derive(Debug, Clone)]
pub(super) struct SubsetSums {
    /// `None`: every integer counts as reachable (total too large for the
    /// table).
    bits: Option<Vec<u64>>,
}

impl SubsetSums {
    /// Every non-negative integer treated as reachable.
    pub(super) fn all() -> SubsetSums {
        SubsetSums { bits: None }
    }

    /// The reachable sums of `coefs`, or `None` when the total is too large.
    pub(super) fn new(coefs: &[i64]) -> Option<SubsetSums> {
        let total: i64 = coefs.iter().sum();
        if total > MAX_DP {
            return None;
        }
        let words = (total as usize) / 64 + 1;
        let mut bits = vec![0u64; words];
        bits[0] = 1;
        // Group equal coefficients; binary splitting of multiplicities.
        let mut sorted = coefs.to_vec();
        sorted.sort_unstable();
        let mut i = 0;
        while i < sorted.len() {
            let c = sorted[i];
            let mut j = i;
            while j < sorted.len() && sorted[j] == c {
                j += 1;
            }
            let mut count = (j - i) as i64;
            let mut chunk = 1;
            while count > 0 {
                let take = chunk.min(count);
                shift_or(&mut bits, (c * take) as usize);
                count -= take;
                chunk *= 2;
            }
            i = j;
        }
        Some(SubsetSums { bits: Some(bits) })
    }

    /// Whether `v` is reachable.
    pub(super) fn contains(&self, v: i64) -> bool {
        let Some(bits) = &self.bits else {
            return v >= 0;
        };
        v >= 0 && {
            let v = v as usize;
            v / 64 < bits.len() && bits[v / 64] >> (v % 64) & 1 == 1
        }
    }

    /// The largest reachable sum `< v`, if any.
    pub(super) fn below(&self, v: i64) -> Option<i64> {
        let mut u = v - 1;
        if u < 0 {
            return None;
        }
        let Some(bits) = &self.bits else {
            return Some(u);
        };
        let max = (bits.len() * 64 - 1) as i64;
        u = u.min(max);
        while u >= 0 {
            let w = bits[u as usize / 64];
            let masked = if u % 64 == 63 {
                w
            } else {
                w & ((1u64 << (u % 64 + 1)) - 1)
            };
            if masked != 0 {
                return Some((u / 64) * 64 + 63 - masked.leading_zeros() as i64);
            }
            u = (u / 64) * 64 - 1;
        }
        None
    }
}

fn shift_or(bits: &mut [u64], s: usize) {
    let (ws, bs) = (s / 64, s % 64);
    for i in (0..bits.len()).rev() {
        if i < ws {
            break;
        }
        let lo = bits[i - ws] << bs;
        let hi = if bs > 0 && i > ws {
            bits[i - ws - 1] >> (64 - bs)
        } else {
            0
        };
        bits[i] |= lo | hi;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integer_weights_exact_and_reduced() {
        assert_eq!(integer_weights(&[1.0, 1.0, 2.0]), Some(vec![1, 1, 2]));
        assert_eq!(integer_weights(&[2.5, 1.0]), Some(vec![5, 2]));
        // Reduced before the size check.
        assert_eq!(integer_weights(&[1e9, 2e9, 1e9]), Some(vec![1, 2, 1]));
        let p = [-(1e-8f64).ln(), -(0.001f64).ln()];
        let v = integer_weights(&p).unwrap();
        assert!((v[0] as f64 / v[1] as f64 - p[0] / p[1]).abs() < 1e-5);
    }

    #[test]
    fn subset_sums() {
        let s = SubsetSums::new(&[3, 5, 5, 70]).unwrap();
        let reach: Vec<i64> = (0..=83).filter(|&v| s.contains(v)).collect();
        assert_eq!(reach, vec![0, 3, 5, 8, 10, 13, 70, 73, 75, 78, 80, 83]);
        assert_eq!(s.below(83), Some(80));
        assert_eq!(s.below(70), Some(13));
        assert_eq!(s.below(0), None);
        assert_eq!(s.below(1000), Some(83));
        let ones = SubsetSums::new(&vec![1; 200]).unwrap();
        assert_eq!(ones.below(200), Some(199));
        assert_eq!(ones.below(65), Some(64));
    }
}
