//! What a multi-objective run records and reports: the archive's [`Member`]s and the
//! per-generation history in its [`Front`], the [`MultiSnapshot`] an observer sees after
//! each generation, and the [`MultiResult`].

use std::time::Duration;

use serde::{Deserialize, Serialize};

use crate::derive::Grammar;
use crate::evaluate::{MultiEvaluator, Sense};
use crate::genome::Genome;
use crate::optimize::driver::Record;
use crate::optimize::fitness::bits_vec;
use crate::optimize::run::grammar_struct_traits;
use crate::optimize::run::{Control, Progress, Silent, StopReason};

/// A model of the archive: its genome and its raw objective values.
#[derive(Serialize, Deserialize)]
#[serde(
    deny_unknown_fields,
    bound(serialize = "G: Grammar", deserialize = "G: Grammar")
)]
pub struct Member<G> {
    /// The genome.
    pub genome: Genome<G>,
    /// Its objective values, one per objective.
    #[serde(with = "bits_vec")]
    pub values: Vec<f64>,
}

grammar_struct_traits!(Member { genome, values });

/// One generation of a multi-objective run's history.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MultiHistoryEntry {
    /// Generation (0: the initial population).
    pub generation: u64,
    /// Wall time at its end, in seconds.
    pub elapsed_s: f64,
    /// Evaluations done by its end.
    pub evaluations: u64,
    /// Members of the archive at its end.
    pub front: u32,
    /// Per objective, the best raw value evaluated so far (by the objective's sense).
    #[serde(with = "bits_vec")]
    pub best: Vec<f64>,
}

/// The state of a multi-objective run after a generation, as shown to a
/// [`MultiObserver`].
pub struct MultiSnapshot<'a, G> {
    /// Generations done after the initial population (0: just initialized).
    pub generation: u64,
    /// Wall time spent, summed over resumed runs.
    pub elapsed: Duration,
    /// Evaluations done.
    pub evaluations: u64,
    /// Per objective, the best raw value evaluated so far.
    pub best: &'a [f64],
    /// The archive of non-dominated models.
    pub front: &'a [Member<G>],
}

impl<G: Grammar> std::fmt::Debug for MultiSnapshot<'_, G> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MultiSnapshot")
            .field("generation", &self.generation)
            .field("elapsed", &self.elapsed)
            .field("evaluations", &self.evaluations)
            .field("best", &self.best)
            .field("front", &self.front)
            .finish()
    }
}

/// Called after every generation of a [`MultiGa`](super::MultiGa) (the initial population's included).
pub trait MultiObserver<G: Grammar> {
    /// Sees a snapshot; returns whether to go on.
    fn observe(&mut self, snapshot: &MultiSnapshot<'_, G>) -> Control;
}

impl<G: Grammar, F: FnMut(&MultiSnapshot<'_, G>) -> Control> MultiObserver<G> for F {
    fn observe(&mut self, snapshot: &MultiSnapshot<'_, G>) -> Control {
        self(snapshot)
    }
}

impl<G: Grammar> MultiObserver<G> for Silent {
    fn observe(&mut self, _: &MultiSnapshot<'_, G>) -> Control {
        Control::Continue
    }
}

/// The outcome of a multi-objective run.
pub struct MultiResult<G> {
    /// The archive: the non-dominated models among all evaluated, no two with equal
    /// objective vectors.
    pub front: Vec<Member<G>>,
    /// Evaluations done in all.
    pub evaluations: u64,
    /// Generations done after the initial population.
    pub generations: u64,
    /// One entry per generation, the initial population's first.
    pub history: Vec<MultiHistoryEntry>,
    /// Why the run ended.
    pub stopped: StopReason,
}

grammar_struct_traits!(MultiResult {
    front,
    evaluations,
    generations,
    history,
    stopped
});

/// The record of a multi-objective run: the objectives' senses, the archive front, the
/// best value of each objective so far, and the history.
///
/// The optimizer keeps the archive and the best values up to date as it evaluates (only
/// it knows which individuals are new); recording a generation appends its history
/// entry.
#[derive(Serialize, Deserialize)]
#[serde(bound(serialize = "G: Grammar", deserialize = "G: Grammar"))]
pub struct Front<G> {
    /// The objectives' senses (empty before the first run).
    pub senses: Vec<Sense>,
    /// The non-dominated models found so far.
    pub archive: Vec<Member<G>>,
    /// Per objective, the best value so far.
    #[serde(with = "bits_vec")]
    pub best: Vec<f64>,
    /// Per-generation history.
    pub history: Vec<MultiHistoryEntry>,
}

grammar_struct_traits!(Front {
    senses,
    archive,
    best,
    history
});

impl<G> Default for Front<G> {
    fn default() -> Self {
        Front {
            senses: Vec::new(),
            archive: Vec::new(),
            best: Vec::new(),
            history: Vec::new(),
        }
    }
}

impl<G: Grammar> Record<G> for Front<G> {
    type Evaluator<'e> = dyn MultiEvaluator<G> + 'e;
    type Observer<'o> = dyn MultiObserver<G> + 'o;
    type Result = MultiResult<G>;

    fn started(&self) -> bool {
        !self.history.is_empty()
    }

    fn record(progress: &mut Progress<Self>, _: &[Genome<G>], _: &[f64]) {
        let r = &mut progress.record;
        r.history.push(MultiHistoryEntry {
            generation: progress.generation,
            elapsed_s: progress.elapsed_s,
            evaluations: progress.evaluations,
            front: r.archive.len() as u32,
            best: r.best.clone(),
        });
    }

    fn observe(progress: &Progress<Self>, observer: &mut Self::Observer<'_>) -> Control {
        observer.observe(&MultiSnapshot {
            generation: progress.generation,
            elapsed: Duration::from_secs_f64(progress.elapsed_s),
            evaluations: progress.evaluations,
            best: &progress.record.best,
            front: &progress.record.archive,
        })
    }

    fn result(progress: &Progress<Self>, stopped: StopReason) -> MultiResult<G> {
        MultiResult {
            front: progress.record.archive.clone(),
            evaluations: progress.evaluations,
            generations: progress.generation,
            history: progress.record.history.clone(),
            stopped,
        }
    }
}
