//! What `shapegen run` writes of a run, by what its method records: one fitness
//! ([`Best`], `cli/single.rs`: the best model and the fitness curves) or objective
//! vectors ([`Front`], `cli/front.rs`: the non-dominated front). The run's one path
//! (`commands/run.rs`) writes what every run has, `run.json`, the checkpoint and
//! `summary.json`, and asks the record's [`Written`] for the rest; the evaluator it scores
//! with is a [`Scoring`].

use std::path::Path;

use shapegen::Grammar;
use shapegen::optimize::multi::Front;
use shapegen::optimize::{Best, Evaluator, MultiEvaluator, Record};
use shapegen::scene::{ObjectiveEvaluator, SceneEvaluator};

use super::backend::Incremental;
use super::files::Files;

/// The numbers of a run's outcome that `run.json` shows.
pub struct Counts {
    /// Generations done after the initial population.
    pub generations: u64,
    /// Evaluations done.
    pub evaluations: u64,
    /// Seconds the run has searched.
    pub elapsed_s: f64,
    /// The best fitness so far (a single-objective run).
    pub best_fitness: Option<f64>,
    /// The models on the front (a multi-objective run).
    pub front: Option<usize>,
}

/// What a finished run leaves beside its files: `summary.json`'s bytes and the line that
/// says what was written.
pub struct Ended {
    /// `summary.json`.
    pub summary: Vec<u8>,
    /// The last line printed.
    pub message: String,
}

/// The files of a run of record `R` beyond those every run writes, and how its progress
/// is shown.
pub trait Written<G: Grammar, R: Record<G>> {
    /// The progress line shown after each generation.
    type Progress;
    /// What is said after the incremental scoring's line.
    const INCREMENTAL_NOTE: &'static str;

    /// The progress line as the run's observer.
    fn observer<'s>(progress: &'s mut Self::Progress) -> &'s mut R::Observer<'s>
    where
        Self::Progress: 's;

    /// Ends the progress line.
    fn finish(progress: &Self::Progress);

    /// The numbers of `result` that `run.json` shows.
    fn counts(result: &R::Result) -> Counts;

    /// The record's files of a save, into the batch that lands with `run.json` and the
    /// checkpoint.
    fn save(&self, files: &mut Files, dir: &Path, result: &R::Result) -> anyhow::Result<()>;

    /// After a save has landed.
    fn saved(&mut self, dir: &Path, result: &R::Result) -> anyhow::Result<()>;

    /// The record's files of the finished run, its summary and last line; `incremental`
    /// says how bred children were counted.
    fn end(
        &self,
        dir: &Path,
        result: &R::Result,
        incremental: Option<Incremental>,
    ) -> anyhow::Result<Ended>;
}

/// The evaluator a run of record `R` scores with.
pub trait Scoring<G: Grammar, R: Record<G>> {
    /// The evaluator, as the run takes it.
    fn evaluator(&mut self) -> &mut R::Evaluator<'_>;
    /// How its bred children were counted; `None` when every model was counted from
    /// nothing.
    fn incremental(&self) -> Option<Incremental>;
}

impl<G: Grammar> Scoring<G, Best<G>> for SceneEvaluator<'_> {
    fn evaluator(&mut self) -> &mut (dyn Evaluator<G> + '_) {
        self
    }

    fn incremental(&self) -> Option<Incremental> {
        self.retention().map(Incremental::from)
    }
}

impl<G: Grammar> Scoring<G, Front<G>> for ObjectiveEvaluator<'_> {
    fn evaluator(&mut self) -> &mut (dyn MultiEvaluator<G> + '_) {
        self
    }

    fn incremental(&self) -> Option<Incremental> {
        self.retention().map(Incremental::from)
    }
}
