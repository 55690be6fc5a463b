//! The documented limits on user-supplied numbers, in one place, and the
//! shared validated parsers for them (docs/language.md#syntax: no input may panic).
//!
//! | what | limit | where checked |
//! |---|---|---|
//! | coordinates `x`, `y`, `space.x`, `space.y` | `|v| ≤` [`MAX_SCENE_COORD`] (10^15) | [`crate::scene::Scene::validate`] |
//! | sizes `width`, `height`, `grid` | `1 ≤ v ≤` [`MAX_SCENE_COORD`] | [`crate::scene::Scene::validate`] |
//! | time limits (`--time-limit`, studio `time_limit`) | finite, `0 ≤ t ≤` [`MAX_TIME_LIMIT_SECS`] | [`time_limit`] |
//! | null-model samples (`--samples`, studio `samples`) | `1 ≤ n ≤` [`MAX_SAMPLES`] | [`check_samples`] |
//! | statements weighed by one learning run | at most [`MAX_STATEMENTS`] | `infer::learn` |
//! | `.rcc` rule text | at most [`MAX_RULES_BYTES`] (16 MiB) | `rules::parse_rules` |
//! | values echoed in error messages | cut past [`MAX_ECHO`] characters | [`cut`] |
//! | synthesis coordinates | `|v| ≤ 2^28` (the engine works in `i32`) | `synth::synthesize` ([`crate::synth::MAX_SYNTH_COORD`]) |
//! | synthesis grid positions per object and axis | `≤ 2^18` | `synth::synthesize` ([`crate::synth::MAX_POSITIONS`]) |
//! | synthesis: pairs of objects the rules relate | at most 120 000 | `synth::synthesize` (`synth::model::MAX_PAIR_LITERALS`) |
//!
//! With every coordinate and size within ±10^15, every edge `x + width` is
//! within ±2·10^15 and every difference of two edges within ±4·10^15 <
//! 2^53: exact in `i64` (far from overflow) and in `f64`.

use std::time::Duration;

/// Largest absolute value of a coordinate, and largest size or grid step,
/// in a scene (10^15).
pub const MAX_SCENE_COORD: i64 = 1_000_000_000_000_000;

/// Largest time limit accepted anywhere, in seconds (10^6 s, about 11.6
/// days).
pub const MAX_TIME_LIMIT_SECS: f64 = 1_000_000.0;

/// Most objects in one scene (each demonstration counts on its own). Every
/// relation is computed per pair of objects, so a scene past this would
/// not fail but take hours; it is refused instead.
pub const MAX_OBJECTS: usize = 10_000;

/// Most random scenes the null model may draw (`--samples`).
pub const MAX_SAMPLES: usize = 1_000_000;

/// Most statements one learning run weighs (generated from the templates
/// or given with `--statements`). Each is evaluated on every object of
/// every random scene: past this, learning would take minutes and
/// gigabytes (200 classes generate about a million) and is refused.
pub const MAX_STATEMENTS: usize = 50_000;

/// Largest `.rcc` rule text, in bytes (16 MiB): about 300,000 rules of
/// the learner's length. A larger file is refused before parsing (a 50 MB
/// file took 2.8 GB of memory to check).
pub const MAX_RULES_BYTES: usize = 16 << 20;

/// Largest scene JSON file (a problem, a scene or a demonstrations
/// array), in bytes (256 MiB): far past any real task. A larger file, or
/// an endless device such as `/dev/zero`, is refused while reading.
pub const MAX_SCENE_BYTES: usize = 256 << 20;

/// Largest priors file (`--priors`), in bytes (16 MiB), checked while
/// reading.
pub const MAX_PRIORS_BYTES: usize = 16 << 20;

/// Largest `@LIST` file of `rccpack priors`, in bytes (16 MiB), checked
/// while reading.
pub const MAX_LIST_BYTES: usize = 16 << 20;

/// Longest value echoed whole in an error message, in characters; a longer
/// one is cut to its first [`CUT_TO`] characters and `…`.
pub const MAX_ECHO: usize = 80;
/// What is kept of a value longer than [`MAX_ECHO`].
pub const CUT_TO: usize = 60;

/// A user-supplied value as echoed in an error message: whole up to
/// [`MAX_ECHO`] characters, else its first [`CUT_TO`] and `…` (a 10 MB id
/// must not become a 10 MB message).
pub fn cut(value: &str) -> String {
    if value.chars().count() > MAX_ECHO {
        value.chars().take(CUT_TO).collect::<String>() + "…"
    } else {
        value.to_string()
    }
}

/// A user-supplied number as echoed in an error message: as `{}` writes it
/// when that is short, else in exponent form (`-1e-320`, not 330 digits).
pub fn number(v: f64) -> String {
    let s = v.to_string();
    if s.chars().count() > 24 {
        format!("{v:e}")
    } else {
        s
    }
}

/// A number outside its documented limit.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LimitError {
    /// A time limit that is not a finite number of seconds in range.
    #[error("time limit {value} is out of range; expected a number of seconds from 0 to {MAX_TIME_LIMIT_SECS}")]
    TimeLimit {
        /// The value as given.
        value: String,
    },
    /// A sample count out of range.
    #[error("samples {value} is out of range; expected a whole number from 1 to {MAX_SAMPLES}")]
    Samples {
        /// The value as given.
        value: String,
    },
}

/// A validated time limit: finite, `0 ≤ seconds ≤ MAX_TIME_LIMIT_SECS`.
/// Never panics (unlike `Duration::from_secs_f64` on unchecked input).
pub fn time_limit(seconds: f64) -> Result<Duration, LimitError> {
    if seconds.is_finite() && (0.0..=MAX_TIME_LIMIT_SECS).contains(&seconds) {
        Ok(Duration::from_secs_f64(seconds))
    } else {
        Err(LimitError::TimeLimit {
            value: number(seconds),
        })
    }
}

/// Parse a time limit written as text (a command-line value).
pub fn parse_time_limit(text: &str) -> Result<Duration, LimitError> {
    match text.trim().parse::<f64>() {
        Ok(v) => time_limit(v),
        Err(_) => Err(LimitError::TimeLimit {
            value: format!("`{}`", cut(text)),
        }),
    }
}

/// Check a null-model sample count: `1 ≤ n ≤ MAX_SAMPLES`.
pub fn check_samples(n: usize) -> Result<usize, LimitError> {
    if (1..=MAX_SAMPLES).contains(&n) {
        Ok(n)
    } else {
        Err(LimitError::Samples {
            value: n.to_string(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_limits_at_and_past_the_cap() {
        assert_eq!(time_limit(0.0), Ok(Duration::ZERO));
        assert_eq!(
            time_limit(MAX_TIME_LIMIT_SECS),
            Ok(Duration::from_secs(1_000_000))
        );
        for bad in [
            -1.0,
            -0.0001,
            1e20,
            MAX_TIME_LIMIT_SECS + 1.0,
            f64::NAN,
            f64::INFINITY,
        ] {
            let e = time_limit(bad).unwrap_err().to_string();
            assert!(
                e.contains("expected a number of seconds from 0 to 1000000"),
                "{e}"
            );
        }
        assert!(parse_time_limit("1e20").is_err());
        assert!(parse_time_limit("inf").is_err());
        assert!(parse_time_limit("ten")
            .unwrap_err()
            .to_string()
            .contains("`ten`"));
        assert_eq!(parse_time_limit("2.5"), Ok(Duration::from_millis(2500)));
    }

    #[test]
    fn long_numbers_are_echoed_short() {
        assert_eq!(number(2.5), "2.5");
        assert_eq!(number(-1e-320), "-1e-320");
        let e = time_limit(-1e-320).unwrap_err().to_string();
        assert!(e.len() < 120, "{e}");
    }

    #[test]
    fn samples_at_and_past_the_cap() {
        assert_eq!(check_samples(1), Ok(1));
        assert_eq!(check_samples(MAX_SAMPLES), Ok(MAX_SAMPLES));
        assert!(check_samples(0).is_err());
        let e = check_samples(MAX_SAMPLES + 1).unwrap_err().to_string();
        assert!(
            e.contains("1000001") && e.contains("from 1 to 1000000"),
            "{e}"
        );
    }
}
