//! Engine tuning: choices that change how a problem is encoded or
//! searched, never which layouts are valid nor the optimum's score.
//!
//! The library never reads the environment: [`Tuning::default`] is what
//! every solve uses unless its caller fills [`SynthOptions::tuning`]. The
//! command line (and the bench crate) fill it from `RCCPACK_*` variables
//! with [`Tuning::from_env`], to compare encodings on real problems; the
//! differential tests set the fields directly.
//!
//! [`SynthOptions::tuning`]: super::SynthOptions::tuning

/// How non-overlap between pairs of objects enters the model.
#[doc(hidden)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NoOverlap {
    /// One clause per pair for a small model, the engine's propagator past
    /// a number of pairs (the default).
    #[default]
    ByPairs,
    /// One clause per pair, whatever the size (`RCCPACK_NO_OVERLAP=clauses`).
    Clauses,
    /// The engine's propagator, whatever the size
    /// (`RCCPACK_NO_OVERLAP=propagator`).
    Propagator,
}

/// Engine tuning (see the module documentation). Doc-hidden: a switch for
/// measurements, not part of the supported interface.
#[doc(hidden)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tuning {
    /// Non-overlap's encoding (`RCCPACK_NO_OVERLAP`).
    pub no_overlap: NoOverlap,
    /// Group statements as layered circuits instead of the connectivity
    /// propagator (`RCCPACK_CONNECTIVITY=circuit`).
    pub circuit_connectivity: bool,
    /// Difference Booleans share one propagator per pair of variables; off,
    /// one reified linear constraint each (`RCCPACK_DIFFERENCE=off`).
    pub difference_propagator: bool,
    /// Resemblance terms of one class and size share one propagator; off,
    /// every term alone (`RCCPACK_LIKE_GROUPS=off`).
    pub like_groups: bool,
    /// The warm start grows the demonstrations' mosaic to place every
    /// object (`RCCPACK_WARM_GROW=off` turns it off).
    pub warm_grow: bool,
    /// Orientations enumerated, one solve per choice, instead of the
    /// model's orientation variables (`RCCPACK_TURNS=enumerate`).
    pub enumerate_turns: bool,
}

impl Default for Tuning {
    fn default() -> Self {
        Tuning {
            no_overlap: NoOverlap::ByPairs,
            circuit_connectivity: false,
            difference_propagator: true,
            like_groups: true,
            warm_grow: true,
            enumerate_turns: false,
        }
    }
}

/// An `RCCPACK_*` tuning variable with a value it does not take.
#[doc(hidden)]
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("environment variable {name}={value:?} is not a choice: expected {expected}")]
pub struct TuningError {
    /// The variable.
    pub name: &'static str,
    /// Its value (lossily decoded).
    pub value: String,
    /// The values it takes.
    pub expected: &'static str,
}

impl Tuning {
    /// The defaults, overridden by the `RCCPACK_*` variables that are set
    /// (an unset or empty variable keeps the default).
    pub fn from_env() -> Result<Tuning, TuningError> {
        Tuning::from_vars(|name| std::env::var_os(name).map(|v| v.to_string_lossy().into_owned()))
    }

    /// [`Tuning::from_env`] with the variables read by `var`.
    pub fn from_vars(var: impl Fn(&str) -> Option<String>) -> Result<Tuning, TuningError> {
        let pick = |name: &'static str, expected: &'static str, choices: &[&str]| match var(name)
            .filter(|v| !v.is_empty())
        {
            None => Ok(None),
            Some(v) => match choices.iter().position(|c| *c == v) {
                Some(i) => Ok(Some(i)),
                None => Err(TuningError {
                    name,
                    value: v,
                    expected,
                }),
            },
        };
        let mut t = Tuning::default();
        let on_off = "on or off";
        if let Some(i) = pick(
            "RCCPACK_NO_OVERLAP",
            "clauses, propagator or pairs",
            &["clauses", "propagator", "pairs"],
        )? {
            t.no_overlap = [
                NoOverlap::Clauses,
                NoOverlap::Propagator,
                NoOverlap::ByPairs,
            ][i];
        }
        if let Some(i) = pick(
            "RCCPACK_CONNECTIVITY",
            "circuit or propagator",
            &["circuit", "propagator"],
        )? {
            t.circuit_connectivity = i == 0;
        }
        if let Some(i) = pick("RCCPACK_DIFFERENCE", on_off, &["on", "off"])? {
            t.difference_propagator = i == 0;
        }
        if let Some(i) = pick("RCCPACK_LIKE_GROUPS", on_off, &["on", "off"])? {
            t.like_groups = i == 0;
        }
        if let Some(i) = pick("RCCPACK_WARM_GROW", on_off, &["on", "off"])? {
            t.warm_grow = i == 0;
        }
        if let Some(i) = pick(
            "RCCPACK_TURNS",
            "enumerate or model",
            &["enumerate", "model"],
        )? {
            t.enumerate_turns = i == 0;
        }
        Ok(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vars<'a>(set: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |name| {
            set.iter()
                .find(|(n, _)| *n == name)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn unset_variables_keep_the_defaults_and_set_ones_override_them() {
        assert_eq!(Tuning::from_vars(vars(&[])), Ok(Tuning::default()));
        assert_eq!(
            Tuning::from_vars(vars(&[("RCCPACK_TURNS", "")])),
            Ok(Tuning::default())
        );
        let t = Tuning::from_vars(vars(&[
            ("RCCPACK_NO_OVERLAP", "propagator"),
            ("RCCPACK_CONNECTIVITY", "circuit"),
            ("RCCPACK_DIFFERENCE", "off"),
            ("RCCPACK_LIKE_GROUPS", "off"),
            ("RCCPACK_WARM_GROW", "off"),
            ("RCCPACK_TURNS", "enumerate"),
        ]))
        .unwrap();
        assert_eq!(
            t,
            Tuning {
                no_overlap: NoOverlap::Propagator,
                circuit_connectivity: true,
                difference_propagator: false,
                like_groups: false,
                warm_grow: false,
                enumerate_turns: true,
            }
        );
    }

    #[test]
    fn a_value_that_is_not_a_choice_is_an_error_naming_it() {
        let e = Tuning::from_vars(vars(&[("RCCPACK_DIFFERENCE", "of")])).unwrap_err();
        assert_eq!(
            e.to_string(),
            "environment variable RCCPACK_DIFFERENCE=\"of\" is not a choice: expected on or off"
        );
    }
}
