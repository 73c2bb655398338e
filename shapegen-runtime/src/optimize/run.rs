//! What every run shares: budgets, the observer hook, the progress bookkeeping (the
//! counters, and for one fitness the best so far and the history) and the
//! per-individual random streams.

use std::time::Duration;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::fitness::bits;
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
    pub fn stop(
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
///
/// ```
/// use shapegen_runtime::optimize::StopReason;
///
/// assert_eq!(StopReason::WallTime.name(), "time");
/// assert_eq!(StopReason::Observer.to_string(), "interrupted");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StopReason {
    /// The generation budget was reached.
    Generations,
    /// The next generation would have gone past the evaluation budget.
    Evaluations,
    /// The wall-time budget was reached.
    WallTime,
    /// The observer or the stop flag asked to stop: the run was interrupted.
    Observer,
}

impl StopReason {
    /// Every reason.
    pub const ALL: [StopReason; 4] = [
        StopReason::Generations,
        StopReason::Evaluations,
        StopReason::WallTime,
        StopReason::Observer,
    ];

    /// Its name in summaries: `"generations"`, `"evaluations"`, `"time"` or
    /// `"interrupted"`.
    pub const fn name(self) -> &'static str {
        match self {
            StopReason::Generations => "generations",
            StopReason::Evaluations => "evaluations",
            StopReason::WallTime => "time",
            StopReason::Observer => "interrupted",
        }
    }
}

impl std::fmt::Display for StopReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
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
/// Exported for [`checkpoint!`](crate::checkpoint)'s expansion; not a public API.
#[doc(hidden)]
#[macro_export]
macro_rules! grammar_struct_traits {
    ($name:ident { $($field:ident),* $(,)? }) => {
        impl<G: $crate::derive::Grammar> Clone for $name<G> {
            fn clone(&self) -> Self {
                $name { $($field: self.$field.clone()),* }
            }
        }
        impl<G: $crate::derive::Grammar> PartialEq for $name<G> {
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
pub(crate) use crate::grammar_struct_traits;

grammar_struct_traits!(RunResult {
    best,
    best_fitness,
    evaluations,
    generations,
    history,
    stopped
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

/// Bookkeeping common to every optimizer's checkpoint: the counters the driver keeps
/// (generations, evaluations, wall time) and the record of what the run found, `R`
/// ([`Best`](super::Best) for one fitness, [`multi::Front`](super::multi::Front) for objective
/// vectors), whose fields serialize inline beside the counters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Progress<R> {
    /// The run's seed: with the generation number it fixes every random stream.
    pub seed: u64,
    /// Generations done after the initial population.
    pub generation: u64,
    /// Fitness evaluations done.
    pub evaluations: u64,
    /// Wall time spent so far, in seconds.
    pub elapsed_s: f64,
    /// What the run found, and its per-generation history.
    #[serde(flatten)]
    pub record: R,
}

impl<R: Default> Progress<R> {
    /// Progress of a run not yet started.
    pub fn new(seed: u64) -> Self {
        Progress {
            seed,
            generation: 0,
            evaluations: 0,
            elapsed_s: 0.0,
            record: R::default(),
        }
    }
}

/// The random stream of individual `index` in generation `generation`: ChaCha8 seeded
/// with the run's seed, on stream `generation << 32 | index`. Independent of threads;
/// every optimizer draws from these, so that its results depend only on the seed.
///
/// ```
/// use rand::RngExt;
/// use shapegen_runtime::optimize::stream;
///
/// let a: u64 = stream(7, 3, 1).random();
/// assert_eq!(a, stream(7, 3, 1).random::<u64>());
/// assert_ne!(a, stream(7, 3, 2).random::<u64>());
/// ```
pub fn stream(seed: u64, generation: u64, index: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(generation << 32 | (index & 0xffff_ffff));
    rng
}

/// The seed of the `k`th family of streams derived from a run's `seed` (the seed itself
/// for `k = 0`): the island model's island `k`, the hybrid's epoch `k`.
pub(crate) fn derived_seed(seed: u64, k: u64) -> u64 {
    const GOLDEN: u64 = 0x9e37_79b9_7f4a_7c15;
    seed.wrapping_add(GOLDEN.wrapping_mul(k))
}
