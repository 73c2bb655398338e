//! The record of a run on one fitness ([`Best`]): the best genome so far and the
//! per-generation history, as the driver keeps it.

use std::time::Duration;

use serde::{Deserialize, Serialize};

use super::driver::Record;
use super::fitness::{self, bits, compare};
use super::run::{
    Control, HistoryEntry, Observer, Progress, RunResult, Snapshot, StopReason,
    grammar_struct_traits,
};
use crate::derive::Grammar;
use crate::evaluate::Evaluator;
use crate::genome::Genome;

/// The record of a run on one fitness: the best genome so far and the history.
///
/// The best is the best genome the run has scored, whatever it is: every genome a
/// method scores keeps to the limits that method keeps
/// ([`Settings::kept_limits`](super::Settings::kept_limits)), so the record has nothing
/// to refuse, and a generation's recorded best is never below its mean.
#[derive(Serialize, Deserialize)]
#[serde(bound(serialize = "G: Grammar", deserialize = "G: Grammar"))]
pub struct Best<G> {
    /// Best genome so far (`None` before the initial population is evaluated).
    pub best: Option<Genome<G>>,
    /// Its fitness.
    #[serde(with = "bits")]
    pub best_fitness: f64,
    /// Per-generation history.
    pub history: Vec<HistoryEntry>,
}

grammar_struct_traits!(Best {
    best,
    best_fitness,
    history
});

impl<G> Default for Best<G> {
    fn default() -> Self {
        Best {
            best: None,
            best_fitness: f64::NAN,
            history: Vec::new(),
        }
    }
}

impl<G: Grammar> Best<G> {
    /// Records a generation whose fitness values are `fitness` and whose best individual
    /// (the first of equals) is `best`, and appends the generation's best, mean and
    /// standard deviation to the history. Takes `best` if it beats the best so far.
    pub(crate) fn record_generation(
        progress: &mut Progress<Self>,
        best: Option<(&Genome<G>, f64)>,
        fitness: &[f64],
    ) {
        let r = &mut progress.record;
        if let Some((genome, f)) = best
            && (r.best.is_none() || compare(f, r.best_fitness).is_gt())
        {
            match &mut r.best {
                Some(b) => b.clone_from(genome),
                None => r.best = Some(genome.clone()),
            }
            r.best_fitness = f;
        }
        let (mean, std) = fitness::mean_std(fitness);
        r.history.push(HistoryEntry {
            generation: progress.generation,
            elapsed_s: progress.elapsed_s,
            evaluations: progress.evaluations,
            best: r.best_fitness,
            mean,
            std,
        });
    }
}

impl<G: Grammar> Record<G> for Best<G> {
    type Evaluator<'e> = dyn Evaluator<G> + 'e;
    type Observer<'o> = dyn Observer<G> + 'o;
    type Result = RunResult<G>;

    fn started(&self) -> bool {
        !self.history.is_empty()
    }

    /// Takes the best of `genomes` (the first of equals) if it beats the best so far,
    /// and appends the generation's best, mean and standard deviation to the history.
    fn record(progress: &mut Progress<Self>, genomes: &[Genome<G>], fitness: &[f64]) {
        let best = fitness::best_index(fitness).map(|i| (&genomes[i], fitness[i]));
        Best::record_generation(progress, best, fitness);
    }

    fn observe(progress: &Progress<Self>, observer: &mut Self::Observer<'_>) -> Control {
        let r = &progress.record;
        let last = r.history.last().expect("observed after a generation");
        observer.observe(&Snapshot {
            generation: progress.generation,
            elapsed: Duration::from_secs_f64(progress.elapsed_s),
            evaluations: progress.evaluations,
            best_fitness: r.best_fitness,
            mean: last.mean,
            std: last.std,
            best: r.best.as_ref().expect("a population is never empty"),
        })
    }

    fn result(progress: &Progress<Self>, stopped: StopReason) -> RunResult<G> {
        let r = &progress.record;
        RunResult {
            best: r.best.clone().expect("started runs have a best genome"),
            best_fitness: r.best_fitness,
            evaluations: progress.evaluations,
            generations: progress.generation,
            history: r.history.clone(),
            stopped,
        }
    }
}
