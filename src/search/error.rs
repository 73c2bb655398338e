//! Why a search, a comparison or a front's search failed.

use std::path::PathBuf;

use shapegen_runtime::optimize::{OptimizeError, SessionError};

use crate::scene::{Method, SceneError};

/// Why a [`Search`](super::Search), a [`Compare`](super::Compare) or a
/// [`FrontSearch`](super::FrontSearch) failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SearchError {
    /// The scene's scorers or backend could not be made.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The method could not start or go on.
    #[error(transparent)]
    Session(#[from] SessionError),
    /// The state to resume from is not a checkpoint of the scene's method.
    #[error("the checkpoint is not one of a {method} run: {source}")]
    Checkpoint {
        /// The scene's method.
        method: &'static str,
        /// What the reader said.
        source: serde_json::Error,
    },
}

impl From<OptimizeError> for SearchError {
    fn from(error: OptimizeError) -> Self {
        SearchError::Session(error.into())
    }
}

/// Why a [`Compare`](super::Compare) cannot be planned.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CompareError {
    /// No method to compare.
    #[error("no methods to compare: give one or more of {}", Method::names())]
    NoMethods,
    /// A method listed twice.
    #[error("`{}` is listed twice among the methods", .0.name())]
    Twice(Method),
    /// No run of each method.
    #[error("give at least 1 run per method")]
    NoRuns,
    /// A wall-time budget that is not a number of seconds above 0.
    #[error("seconds = {0}: give a wall-time budget of more than 0 seconds")]
    Seconds(f64),
    /// Runs of a method that nothing would stop.
    #[error(
        "the runs of {} would never end: give a wall-time budget (seconds) or an evaluation \
         budget (evaluations, or the scene's optimizer.evaluations)",
        .0.name()
    )]
    Unbounded(Method),
    /// Seeds past the largest.
    #[error("seed {base}: with {runs} runs the seeds would pass {}", u64::MAX)]
    Seeds {
        /// The base seed.
        base: u64,
        /// Runs of each method.
        runs: u64,
    },
    /// A scene with objectives, which has no single fitness to compare.
    #[error(
        "`{}` has [[objective]] tables: compare measures single-objective methods by one \
         fitness, and a multi-objective scene is searched by the multi-objective GA",
        .0.display()
    )]
    MultiObjective(PathBuf),
    /// A method's goal could not be read from the scene.
    #[error(transparent)]
    Scene(#[from] SceneError),
}
