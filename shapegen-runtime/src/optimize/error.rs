//! Errors of the optimizers.

use crate::genome::LimitsError;

use crate::evaluate::{EvaluateError, Sense};

/// A settings field outside its valid range.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{field} = {value} is invalid: it must be {valid}")]
pub struct SettingsError {
    /// The field's name, as in scene files.
    pub field: &'static str,
    /// The value given, printed.
    pub value: String,
    /// The valid range, in words.
    pub valid: &'static str,
}

impl SettingsError {
    /// A settings error for `field` holding `value`, which must be `valid`.
    pub(crate) fn new(field: &'static str, value: impl ToString, valid: &'static str) -> Self {
        SettingsError {
            field,
            value: value.to_string(),
            valid,
        }
    }
}

/// Checks that `value` is at least 1.
pub(crate) fn check_positive(
    field: &'static str,
    value: impl Into<u64>,
) -> Result<(), SettingsError> {
    match value.into() {
        0 => Err(SettingsError::new(field, 0, "at least 1")),
        _ => Ok(()),
    }
}

/// Checks that `value` lies in `[lo, hi]` (and is not NaN).
pub(crate) fn check_range(
    field: &'static str,
    value: f64,
    lo: f64,
    hi: f64,
    valid: &'static str,
) -> Result<(), SettingsError> {
    if value >= lo && value <= hi {
        Ok(())
    } else {
        Err(SettingsError::new(field, value, valid))
    }
}

/// Why an optimizer could not start, resume or go on.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum OptimizeError {
    /// A settings field is out of range.
    #[error(transparent)]
    Settings(#[from] SettingsError),
    /// The genome limits cannot be met.
    #[error("genome limits")]
    Limits(#[from] LimitsError),
    /// The evaluator failed.
    #[error(transparent)]
    Evaluate(#[from] EvaluateError),
    /// A checkpoint does not fit its settings (population size, fitness count, ...) or
    /// the evaluator it is resumed with.
    #[error("checkpoint: {0}")]
    Checkpoint(CheckpointError),
    /// The processes a run is spread over could not exchange what it needs.
    #[error(transparent)]
    Exchange(#[from] super::islands::exchange::ExchangeError),
}

/// Why a checkpoint does not fit the run it is resumed into.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CheckpointError {
    /// Its buffers do not have the sizes its settings make.
    #[error("{} for {run}", buffers.iter().map(ToString::to_string).collect::<Vec<_>>().join(", "))]
    Sizes {
        /// Every buffer checked, the wrong ones and the right ones.
        buffers: Vec<BufferSize>,
        /// The run the settings make, in words (`a population of 100`).
        run: String,
    },
    /// A polishing strategy does not fit the genome it polishes, or holds numbers no
    /// strategy reaches.
    #[error(
        "a polishing strategy of {dimensions} dimensions for a genome of {coordinates} \
         continuous parameters, or with a step size or variance that is not a positive number"
    )]
    Strategy {
        /// The strategy's dimensions.
        dimensions: usize,
        /// The genome's coordinates.
        coordinates: usize,
    },
    /// The evaluator scores other objectives than the run did before it was saved.
    #[error("objectives {found:?} for a run on {saved:?}")]
    Objectives {
        /// The evaluator's objectives' senses.
        found: Vec<Sense>,
        /// The saved run's.
        saved: Vec<Sense>,
    },
}

/// One buffer of a checkpoint: how many items it holds and how many the settings make.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{found} {what} (expected {expected})")]
pub struct BufferSize {
    /// What the buffer holds (`genomes`, `fitness values`, ...).
    pub what: &'static str,
    /// Items in the checkpoint.
    pub found: usize,
    /// Items the settings make.
    pub expected: usize,
}

/// Checks the buffers of a started checkpoint against the run it must fit: each
/// `(found, expected, what)`; the error lists every buffer, then `run`.
pub(crate) fn check_sizes(
    sizes: &[(usize, usize, &'static str)],
    run: impl std::fmt::Display,
) -> Result<(), OptimizeError> {
    if sizes.iter().all(|&(found, expected, _)| found == expected) {
        return Ok(());
    }
    let buffers = sizes
        .iter()
        .map(|&(found, expected, what)| BufferSize {
            what,
            found,
            expected,
        })
        .collect();
    Err(OptimizeError::Checkpoint(CheckpointError::Sizes {
        buffers,
        run: run.to_string(),
    }))
}
