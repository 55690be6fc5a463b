//! Learning parameters and their ranges.

use super::{InferError, Templates};
use crate::relations::Contact;

/// Learning parameters (docs/guide.md#learning; the defaults are the spec's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LearnParams {
    /// Random scenes in the null model, ≥ 1 (default 1000).
    pub samples: usize,
    /// Learn candidates with posterior below this, in (0, 1) (default 0.01).
    pub cutoff: f64,
    /// Prior that a statement is not intended, in (0, 1) (default 0.5).
    pub prior: f64,
    /// Floor of the chance rate, in (0, 1); `None`: `0.5 / N_A` per subject
    /// class.
    pub epsilon: Option<f64>,
    /// Seed of the null model (default 0).
    pub seed: u64,
    /// Contact mode of `EC` (default point).
    pub contact: Contact,
    /// The template set used when no statements are given (default: the
    /// second edition, docs/guide.md#learning).
    pub templates: Templates,
    /// Slip rate `η` in [0, 0.5): the chance that a movable block of a
    /// demonstration is not where the demonstrator meant it, but put down
    /// at random (docs/guide.md#slips). A statement broken in one
    /// demonstration only (of at least three) is weighed as meant when a
    /// block likelier a slip than not repairs it; 0 is the thesis's model,
    /// exactly (default [`DEFAULT_SLIP_RATE`]).
    pub slip_rate: f64,
}

/// The default slip rate: 0, the thesis's model (docs/guide.md#slips says
/// why; `--slip-rate 0.01` is the setting for recorded demonstrations).
pub const DEFAULT_SLIP_RATE: f64 = 0.0;

/// The slip rate suggested for demonstrations recorded by a camera or a
/// hand (`bench noisy`'s default).
pub const SUGGESTED_SLIP_RATE: f64 = 0.01;

impl Default for LearnParams {
    fn default() -> Self {
        LearnParams {
            samples: 1000,
            cutoff: 0.01,
            prior: 0.5,
            epsilon: None,
            seed: 0,
            contact: Contact::Point,
            templates: Templates::Third,
            slip_rate: DEFAULT_SLIP_RATE,
        }
    }
}

impl LearnParams {
    /// Check every range; the error names the parameter.
    pub fn validate(&self) -> Result<(), InferError> {
        let open_unit = |param: &'static str, v: f64| {
            if v > 0.0 && v < 1.0 {
                Ok(())
            } else {
                Err(InferError::BadParameter {
                    param,
                    value: crate::limits::number(v),
                    expected: "a number strictly between 0 and 1",
                })
            }
        };
        if self.samples == 0 {
            return Err(InferError::BadParameter {
                param: "samples",
                value: "0".into(),
                expected: "a whole number of at least 1",
            });
        }
        if self.samples > crate::limits::MAX_SAMPLES {
            return Err(InferError::BadParameter {
                param: "samples",
                value: self.samples.to_string(),
                // `crate::limits::MAX_SAMPLES`, written out.
                expected: "a whole number of at most 1000000",
            });
        }
        open_unit("cutoff", self.cutoff)?;
        open_unit("prior", self.prior)?;
        if let Some(e) = self.epsilon {
            open_unit("epsilon", e)?;
        }
        if !(self.slip_rate >= 0.0 && self.slip_rate < 0.5) {
            return Err(InferError::BadParameter {
                param: "slip_rate",
                value: crate::limits::number(self.slip_rate),
                expected: "a number from 0 to below 0.5",
            });
        }
        Ok(())
    }
}
