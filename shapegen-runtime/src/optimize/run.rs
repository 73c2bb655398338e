//! The run loop shared by every optimizer: budgets, the observer hook, progress
//! bookkeeping (best so far, history) and the per-individual random streams.

use std::time::{Duration, Instant};

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::fitness::{self, bits, compare};
use super::{Evaluator, OptimizeError};
use crate::derive::Grammar;
use crate::genome::Genome;

/// When a run stops: after a number of generations, of evaluations, or of wall time, any
/// combination; the first limit reached ends the run. With none set, only the
/// [`Observer`] can stop it.
///
/// Generations and evaluations count from the start of the optimization, across
/// checkpoints. Only these two are deterministic: a wall-time budget makes where the run
/// stops, and so its result, depend on the machine's speed.
///
/// The initial population is always evaluated; before each further generation the run
/// checks the budgets and stops if the generation could take the evaluation count past
/// [`evaluations`](Self::evaluations).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Budget {
    /// Most generations (steps, iterations) after the initial population.
    pub generations: Option<u64>,
    /// Most fitness evaluations, the initial population's included.
    pub evaluations: Option<u64>,
    /// Most wall time, summed over resumed runs.
    pub wall_time: Option<Duration>,
}

impl Budget {
    /// A budget of `n` generations.
    pub fn generations(n: u64) -> Self {
        Budget {
            generations: Some(n),
            ..Budget::default()
        }
    }

    /// A budget of `n` evaluations.
    pub fn evaluations(n: u64) -> Self {
        Budget {
            evaluations: Some(n),
            ..Budget::default()
        }
    }

    /// This budget with an evaluation limit as well.
    pub fn and_evaluations(self, n: u64) -> Self {
        Budget {
            evaluations: Some(n),
            ..self
        }
    }

    /// This budget with a wall-time limit as well.
    pub fn and_wall_time(self, t: Duration) -> Self {
        Budget {
            wall_time: Some(t),
            ..self
        }
    }
}

impl Budget {
    /// Why a run that has done `generations` generations and `evaluations` evaluations in
    /// `elapsed_s` seconds must stop before a generation costing up to `cost` evaluations;
    /// `None` if it may go on.
    pub(crate) fn stop(
        &self,
        generations: u64,
        evaluations: u64,
        cost: u64,
        elapsed_s: f64,
    ) -> Option<StopReason> {
        if self.generations.is_some_and(|n| generations >= n) {
            Some(StopReason::Generations)
        } else if self
            .evaluations
            .is_some_and(|n| evaluations.saturating_add(cost) > n)
        {
            Some(StopReason::Evaluations)
        } else if self.wall_time.is_some_and(|t| elapsed_s >= t.as_secs_f64()) {
            Some(StopReason::WallTime)
        } else {
            None
        }
    }
}

/// What an [`Observer`] wants after a generation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Control {
    /// Go on.
    Continue,
    /// Stop now (the run returns its result, and can be checkpointed and resumed).
    Stop,
}

/// The state of a run after a generation, as shown to an [`Observer`].
pub struct Snapshot<'a, G> {
    /// Generations done after the initial population (0: just initialized).
    pub generation: u64,
    /// Wall time spent, summed over resumed runs.
    pub elapsed: Duration,
    /// Fitness evaluations done.
    pub evaluations: u64,
    /// Best fitness found so far.
    pub best_fitness: f64,
    /// Mean of the current population's finite fitness values (NaN if none).
    pub mean: f64,
    /// Standard deviation of the same values.
    pub std: f64,
    /// The best genome found so far.
    pub best: &'a Genome<G>,
}

/// Called after every generation (the initial population's included).
pub trait Observer<G: Grammar> {
    /// Sees a snapshot; returns whether to go on.
    fn observe(&mut self, snapshot: &Snapshot<'_, G>) -> Control;
}

impl<G: Grammar, F: FnMut(&Snapshot<'_, G>) -> Control> Observer<G> for F {
    fn observe(&mut self, snapshot: &Snapshot<'_, G>) -> Control {
        self(snapshot)
    }
}

/// An [`Observer`] that never stops the run.
#[derive(Clone, Copy, Debug, Default)]
pub struct Silent;

impl<G: Grammar> Observer<G> for Silent {
    fn observe(&mut self, _: &Snapshot<'_, G>) -> Control {
        Control::Continue
    }
}

/// One generation of a run's history. Fitness values are stored as exact bits in
/// checkpoints.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct HistoryEntry {
    /// Generation (0: the initial population).
    pub generation: u64,
    /// Wall time at its end, in seconds.
    pub elapsed_s: f64,
    /// Evaluations done by its end.
    pub evaluations: u64,
    /// Best fitness so far.
    #[serde(with = "bits")]
    pub best: f64,
    /// Mean of the population's finite fitness values.
    #[serde(with = "bits")]
    pub mean: f64,
    /// Their standard deviation.
    #[serde(with = "bits")]
    pub std: f64,
}

/// Why a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopReason {
    /// The generation budget was reached.
    Generations,
    /// The next generation would have gone past the evaluation budget.
    Evaluations,
    /// The wall-time budget was reached.
    WallTime,
    /// The observer asked to stop.
    Observer,
}

/// The outcome of a run.
pub struct RunResult<G> {
    /// The best genome found.
    pub best: Genome<G>,
    /// Its fitness.
    pub best_fitness: f64,
    /// Fitness evaluations done in all.
    pub evaluations: u64,
    /// Generations done after the initial population.
    pub generations: u64,
    /// One entry per generation, the initial population's first.
    pub history: Vec<HistoryEntry>,
    /// Why the run ended.
    pub stopped: StopReason,
}

/// Implements `Clone`, `PartialEq` and `Debug` for a struct generic over a grammar `G`,
/// field by field, without asking `G` itself for them (grammars are bare marker types).
macro_rules! grammar_struct_traits {
    ($name:ident { $($field:ident),* $(,)? }) => {
        impl<G> Clone for $name<G> {
            fn clone(&self) -> Self {
                $name { $($field: self.$field.clone()),* }
            }
        }
        impl<G> PartialEq for $name<G> {
            fn eq(&self, other: &Self) -> bool {
                true $(&& self.$field == other.$field)*
            }
        }
        impl<G: $crate::derive::Grammar> std::fmt::Debug for $name<G> {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.debug_struct(stringify!($name))
                    $(.field(stringify!($field), &self.$field))*
                    .finish()
            }
        }
    };
}
pub(crate) use grammar_struct_traits;

grammar_struct_traits!(RunResult {
    best,
    best_fitness,
    evaluations,
    generations,
    history,
    stopped
});
grammar_struct_traits!(Progress {
    seed,
    generation,
    evaluations,
    elapsed_s,
    best,
    best_fitness,
    history
});

impl<G: Grammar> std::fmt::Debug for Snapshot<'_, G> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Snapshot")
            .field("generation", &self.generation)
            .field("elapsed", &self.elapsed)
            .field("evaluations", &self.evaluations)
            .field("best_fitness", &self.best_fitness)
            .field("mean", &self.mean)
            .field("std", &self.std)
            .field("best", self.best)
            .finish()
    }
}

/// Bookkeeping common to every optimizer's checkpoint.
#[derive(Serialize, Deserialize)]
#[serde(bound(serialize = "G: Grammar", deserialize = "G: Grammar"))]
pub struct Progress<G> {
    /// The run's seed: with the generation number it fixes every random stream.
    pub seed: u64,
    /// Generations done after the initial population.
    pub generation: u64,
    /// Fitness evaluations done.
    pub evaluations: u64,
    /// Wall time spent so far, in seconds.
    pub elapsed_s: f64,
    /// Best genome so far (`None` before the initial population is evaluated).
    pub best: Option<Genome<G>>,
    /// Its fitness.
    #[serde(with = "bits")]
    pub best_fitness: f64,
    /// Per-generation history.
    pub history: Vec<HistoryEntry>,
}

impl<G> Progress<G> {
    /// Progress of a run not yet started.
    pub(crate) fn new(seed: u64) -> Self {
        Progress {
            seed,
            generation: 0,
            evaluations: 0,
            elapsed_s: 0.0,
            best: None,
            best_fitness: f64::NAN,
            history: Vec::new(),
        }
    }
}

/// The random stream of individual `index` in generation `generation`: ChaCha8 seeded
/// with the run's seed, on stream `generation << 32 | index`. Independent of threads.
pub(crate) fn stream(seed: u64, generation: u64, index: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(generation << 32 | (index & 0xffff_ffff));
    rng
}

/// One optimization method, as the run loop drives it.
pub(crate) trait Method<G: Grammar> {
    /// Evaluations the next step may use at most.
    fn step_cost(&self) -> u64;
    /// Builds and evaluates the initial population, counting evaluations in progress.
    fn start<E: Evaluator<G>>(&mut self, evaluator: &mut E) -> Result<(), OptimizeError>;
    /// Runs one generation (the generation counter is advanced by the caller after).
    fn step<E: Evaluator<G>>(&mut self, evaluator: &mut E) -> Result<(), OptimizeError>;
    /// The progress and the current population with its fitness.
    fn parts(&mut self) -> (&mut Progress<G>, &[Genome<G>], &[f64]);
}

/// Runs `method` until the budget or the observer stops it.
pub(crate) fn drive<G: Grammar, M: Method<G>>(
    method: &mut M,
    evaluator: &mut impl Evaluator<G>,
    budget: &Budget,
    observer: &mut impl Observer<G>,
) -> Result<RunResult<G>, OptimizeError> {
    let t0 = Instant::now();
    let base = method.parts().0.elapsed_s;
    let elapsed = || base + t0.elapsed().as_secs_f64();
    if method.parts().0.history.is_empty() {
        method.start(evaluator)?;
        if record(method, elapsed(), observer) == Control::Stop {
            return Ok(finish(method, StopReason::Observer));
        }
    }
    loop {
        let cost = method.step_cost();
        let p = method.parts().0;
        if let Some(reason) = budget.stop(p.generation, p.evaluations, cost, elapsed()) {
            method.parts().0.elapsed_s = elapsed();
            return Ok(finish(method, reason));
        }
        method.step(evaluator)?;
        method.parts().0.generation += 1;
        if record(method, elapsed(), observer) == Control::Stop {
            return Ok(finish(method, StopReason::Observer));
        }
    }
}

/// Updates the best so far and the history after a generation, and asks the observer.
fn record<G: Grammar, M: Method<G>>(
    method: &mut M,
    elapsed_s: f64,
    observer: &mut impl Observer<G>,
) -> Control {
    let (p, genomes, fit) = method.parts();
    if let Some(i) = fitness::best_index(fit)
        && (p.best.is_none() || compare(fit[i], p.best_fitness).is_gt())
    {
        match &mut p.best {
            Some(b) => b.clone_from(&genomes[i]),
            None => p.best = Some(genomes[i].clone()),
        }
        p.best_fitness = fit[i];
    }
    let (mean, std) = fitness::mean_std(fit);
    p.elapsed_s = elapsed_s;
    p.history.push(HistoryEntry {
        generation: p.generation,
        elapsed_s,
        evaluations: p.evaluations,
        best: p.best_fitness,
        mean,
        std,
    });
    let best = p.best.as_ref().expect("a population is never empty");
    observer.observe(&Snapshot {
        generation: p.generation,
        elapsed: Duration::from_secs_f64(elapsed_s),
        evaluations: p.evaluations,
        best_fitness: p.best_fitness,
        mean,
        std,
        best,
    })
}

fn finish<G: Grammar, M: Method<G>>(method: &mut M, stopped: StopReason) -> RunResult<G> {
    let p = method.parts().0;
    RunResult {
        best: p.best.clone().expect("started runs have a best genome"),
        best_fitness: p.best_fitness,
        evaluations: p.evaluations,
        generations: p.generation,
        history: p.history.clone(),
        stopped,
    }
}
