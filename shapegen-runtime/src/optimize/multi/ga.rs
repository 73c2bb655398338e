//! The multi-objective GA: the GA's breeding, selecting on a multi-objective selection
//! fitness, with an archive of the non-dominated models found.

use std::time::{Duration, Instant};

use serde::{Deserialize, Serialize};

use super::rank::{Fronts, RankScratch, crowding, first_of_equals, selection_fitness};
use super::settings::MultiGaSettings;
use crate::derive::Grammar;
use crate::genome::{Genome, Limits};
use crate::ops::Operators;
use crate::optimize::fitness::{Roulette, bits_vec, rank};
use crate::optimize::ga::{Breed, random_population};
use crate::optimize::run::grammar_struct_traits;
use crate::optimize::{Budget, Control, EvaluateError, OptimizeError, Sense, Silent, StopReason};

/// Scores a whole population on `k` objectives at once.
pub trait MultiEvaluator<G: Grammar> {
    /// The `k` objectives' senses (at least one).
    fn senses(&self) -> &[Sense];

    /// Writes the `k` raw objective values of `genomes[i]` to `out[i * k..(i + 1) * k]`.
    /// `out` holds `genomes.len() * k` values.
    fn evaluate(&mut self, genomes: &[Genome<G>], out: &mut [f64]) -> Result<(), EvaluateError>;
}

impl<G: Grammar, E: MultiEvaluator<G> + ?Sized> MultiEvaluator<G> for &mut E {
    fn senses(&self) -> &[Sense] {
        (**self).senses()
    }

    fn evaluate(&mut self, genomes: &[Genome<G>], out: &mut [f64]) -> Result<(), EvaluateError> {
        (**self).evaluate(genomes, out)
    }
}

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

/// Called after every generation of a [`MultiGa`] (the initial population's included).
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

/// A checkpoint of a [`MultiGa`]: serialize it (e.g. with `serde_json`) and give it to
/// [`MultiGa::resume`] to go on exactly as an uninterrupted run would.
#[derive(Serialize, Deserialize)]
#[serde(
    deny_unknown_fields,
    bound(serialize = "G: Grammar", deserialize = "G: Grammar")
)]
pub struct MultiGaState<G> {
    /// The settings.
    pub settings: MultiGaSettings,
    /// The genome limits.
    pub limits: Limits,
    /// The seed.
    pub seed: u64,
    /// Generations done after the initial population.
    pub generation: u64,
    /// Evaluations done.
    pub evaluations: u64,
    /// Wall time spent, in seconds.
    pub elapsed_s: f64,
    /// The objectives' senses (empty before the first run).
    pub senses: Vec<Sense>,
    /// The current population.
    pub population: Vec<Genome<G>>,
    /// Its objective values, row-major.
    #[serde(with = "bits_vec")]
    pub values: Vec<f64>,
    /// The archive.
    pub archive: Vec<Member<G>>,
    /// Per objective, the best value so far.
    #[serde(with = "bits_vec")]
    pub best: Vec<f64>,
    /// Per-generation history.
    pub history: Vec<MultiHistoryEntry>,
}

grammar_struct_traits!(MultiGaState {
    settings,
    limits,
    seed,
    generation,
    evaluations,
    elapsed_s,
    senses,
    population,
    values,
    archive,
    best,
    history
});

/// Buffers of the archive update.
#[derive(Clone, Debug, Default)]
struct ArchiveScratch {
    values: Vec<f64>,
    fronts: Fronts,
    keep: Vec<u32>,
    first: Vec<bool>,
    order: Vec<u32>,
    crowd: Vec<f64>,
}

/// The multi-objective genetic algorithm: the [`Ga`](crate::optimize::Ga)'s loop and
/// breeding (elites, tournament and roulette parents, mutation or crossover, per-pair
/// random streams, rayon), selecting on the
/// [`selection_fitness`](super::selection_fitness) of the whole current population,
/// recomputed every generation from the objective vectors. Elites keep their cached
/// vectors; only the children are evaluated, all in one call.
///
/// The archive holds the non-dominated set of every model evaluated so far, leaving out
/// vectors with a NaN and keeping the first model of each group of equal vectors. When it
/// grows past [`archive`](MultiGaSettings::archive) members it keeps those of largest
/// [`crowding`](super::crowding) distance (the extremes of each objective first; ties
/// keep the earlier member, archive before population).
///
/// Results never depend on the thread count; budgets are those of [`Budget`].
///
/// ```
/// use shapegen_runtime::optimize::multi::{MultiEvaluator, MultiGa, MultiGaSettings};
/// use shapegen_runtime::optimize::{Budget, EvaluateError, GaSettings, Sense, Silent};
/// use shapegen_runtime::prelude::*;
///
/// generator! {
///     /// A chain of blocks.
///     pub Chain {
///         axiom Seg;
///         node Seg {
///             children { next: Seg = 0.5 }
///             derive(s) {
///                 s.emit(CUBE);
///                 if let Some(next) = next { s.translate(vec3(0.0, 1.0, 0.0)).derive(next); }
///             }
///         }
///     }
/// }
///
/// /// Two objectives: the chain's length, to be near 10, and to be short.
/// struct Length;
/// impl MultiEvaluator<Chain> for Length {
///     fn senses(&self) -> &[Sense] { &[Sense::Minimize, Sense::Minimize] }
///     fn evaluate(&mut self, genomes: &[Genome<Chain>], out: &mut [f64]) -> Result<(), EvaluateError> {
///         for (g, o) in genomes.iter().zip(out.chunks_exact_mut(2)) {
///             o.copy_from_slice(&[(g.len() as f64 - 10.0).abs(), g.len() as f64]);
///         }
///         Ok(())
///     }
/// }
///
/// let ga = GaSettings { population: 20, elitism: 2, initial_length: 4, ..GaSettings::default() };
/// let settings = MultiGaSettings { ga, ..MultiGaSettings::thesis() };
/// let mut mga = MultiGa::<Chain>::new(settings, Limits::new(1, 30, 30)?, 7)?;
/// let result = mga.run(&mut Length, &Budget::generations(20), &mut Silent)?;
/// // The front: every length from 1 to 10, each trading closeness to 10 for shortness.
/// let mut lengths: Vec<usize> = result.front.iter().map(|m| m.genome.len()).collect();
/// lengths.sort();
/// assert_eq!(lengths, (1..=10).collect::<Vec<_>>());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct MultiGa<G> {
    settings: MultiGaSettings,
    ops: Operators<G>,
    seed: u64,
    generation: u64,
    evaluations: u64,
    elapsed_s: f64,
    senses: Vec<Sense>,
    population: Vec<Genome<G>>,
    values: Vec<f64>,
    next: Vec<Genome<G>>,
    next_values: Vec<f64>,
    archive: Vec<Member<G>>,
    best: Vec<f64>,
    history: Vec<MultiHistoryEntry>,
    fitness: Vec<f64>,
    order: Vec<u32>,
    roulette: Roulette,
    rank_scratch: RankScratch,
    archive_scratch: ArchiveScratch,
}

impl<G: Grammar> std::fmt::Debug for MultiGa<G> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MultiGa")
            .field("settings", &self.settings)
            .field("generation", &self.generation)
            .field("evaluations", &self.evaluations)
            .field("archive", &self.archive.len())
            .finish_non_exhaustive()
    }
}

impl<G: Grammar> MultiGa<G> {
    /// A multi-objective GA with these settings, keeping genomes within `limits`, seeded
    /// with `seed`.
    pub fn new(
        settings: MultiGaSettings,
        limits: Limits,
        seed: u64,
    ) -> Result<Self, OptimizeError> {
        settings.validate()?;
        let n = settings.ga.population as usize;
        let empty = || Genome::from_parts(Vec::new(), 0);
        Ok(MultiGa {
            ops: settings.ga.build_operators(limits)?,
            seed,
            generation: 0,
            evaluations: 0,
            elapsed_s: 0.0,
            senses: Vec::new(),
            population: (0..n).map(|_| empty()).collect(),
            values: Vec::new(),
            next: (0..n).map(|_| empty()).collect(),
            next_values: Vec::new(),
            archive: Vec::new(),
            best: Vec::new(),
            history: Vec::new(),
            fitness: vec![f64::NAN; n],
            order: Vec::with_capacity(n),
            roulette: Roulette::default(),
            rank_scratch: RankScratch::default(),
            archive_scratch: ArchiveScratch::default(),
            settings,
        })
    }

    /// Resumes from a checkpoint; fails if it does not fit its own settings.
    pub fn resume(state: MultiGaState<G>) -> Result<Self, OptimizeError> {
        let mut ga = MultiGa::new(state.settings, state.limits, state.seed)?;
        let n = ga.population.len();
        let k = state.senses.len();
        if !state.history.is_empty() {
            let fits = k > 0
                && state.population.len() == n
                && state.values.len() == n * k
                && state.best.len() == k
                && state.archive.iter().all(|m| m.values.len() == k);
            if !fits {
                return Err(OptimizeError::Checkpoint(format!(
                    "{} genomes, {} values, {} best values for a population of {n} on {k} \
                     objectives",
                    state.population.len(),
                    state.values.len(),
                    state.best.len()
                )));
            }
            ga.population = state.population;
            ga.values = state.values;
            ga.senses = state.senses;
            ga.archive = state.archive;
            ga.best = state.best;
        }
        ga.generation = state.generation;
        ga.evaluations = state.evaluations;
        ga.elapsed_s = state.elapsed_s;
        ga.history = state.history;
        Ok(ga)
    }

    /// The state to resume from.
    pub fn checkpoint(&self) -> MultiGaState<G> {
        MultiGaState {
            settings: self.settings.clone(),
            limits: *self.ops.limits(),
            seed: self.seed,
            generation: self.generation,
            evaluations: self.evaluations,
            elapsed_s: self.elapsed_s,
            senses: self.senses.clone(),
            population: self.population.clone(),
            values: self.values.clone(),
            archive: self.archive.clone(),
            best: self.best.clone(),
            history: self.history.clone(),
        }
    }

    /// The settings.
    pub fn settings(&self) -> &MultiGaSettings {
        &self.settings
    }

    /// The archive: the non-dominated models found so far.
    pub fn front(&self) -> &[Member<G>] {
        &self.archive
    }

    /// Runs until `budget` or `observer` stops it; a later call goes on from there.
    ///
    /// Fails if the evaluator has no objectives, if its senses differ from those of
    /// earlier runs, or if a weighted sum's weights are not one per objective.
    pub fn run(
        &mut self,
        evaluator: &mut impl MultiEvaluator<G>,
        budget: &Budget,
        observer: &mut impl MultiObserver<G>,
    ) -> Result<MultiResult<G>, OptimizeError> {
        let senses = evaluator.senses();
        if senses.is_empty() {
            return Err(EvaluateError("the evaluator has no objectives".into()).into());
        }
        if !self.history.is_empty() && self.senses != senses {
            return Err(OptimizeError::Checkpoint(format!(
                "objectives {:?} for a run on {:?}",
                senses, self.senses
            )));
        }
        self.settings.selection.check_objectives(senses.len())?;
        let t0 = Instant::now();
        let base = self.elapsed_s;
        let elapsed = || base + t0.elapsed().as_secs_f64();
        if self.history.is_empty() {
            self.start(evaluator)?;
            if self.record(elapsed(), observer) == Control::Stop {
                return Ok(self.finish(StopReason::Observer));
            }
        }
        let cost = u64::from(self.settings.ga.population - self.settings.ga.elitism);
        loop {
            if let Some(reason) = budget.stop(self.generation, self.evaluations, cost, elapsed()) {
                self.elapsed_s = elapsed();
                return Ok(self.finish(reason));
            }
            self.step(evaluator)?;
            self.generation += 1;
            if self.record(elapsed(), observer) == Control::Stop {
                return Ok(self.finish(StopReason::Observer));
            }
        }
    }

    /// Grows and evaluates the initial population.
    fn start(&mut self, evaluator: &mut impl MultiEvaluator<G>) -> Result<(), OptimizeError> {
        self.senses = evaluator.senses().to_vec();
        let (n, k) = (self.population.len(), self.senses.len());
        random_population(
            &self.ops,
            &self.settings.ga,
            self.seed,
            &mut self.population,
        );
        self.values.clear();
        self.values.resize(n * k, f64::NAN);
        evaluator.evaluate(&self.population, &mut self.values)?;
        self.evaluations += n as u64;
        self.best = vec![f64::NAN; k];
        self.update(0);
        Ok(())
    }

    /// One generation: selection fitness, elites, breeding, evaluation of the children.
    fn step(&mut self, evaluator: &mut impl MultiEvaluator<G>) -> Result<(), OptimizeError> {
        let k = self.senses.len();
        let elite = self.settings.ga.elitism as usize;
        selection_fitness(
            &self.settings.selection,
            &self.values,
            k,
            &self.senses,
            &mut self.fitness,
            &mut self.rank_scratch,
        );
        rank(&self.fitness, &mut self.order);
        self.roulette.build(&self.fitness);
        self.next_values.clear();
        self.next_values.resize(self.values.len(), f64::NAN);
        for (e, &i) in self.order[..elite].iter().enumerate() {
            let i = i as usize;
            self.next[e].clone_from(&self.population[i]);
            self.next_values[e * k..(e + 1) * k].copy_from_slice(&self.values[i * k..(i + 1) * k]);
        }
        let breed = Breed {
            settings: &self.settings.ga,
            population: &self.population,
            fitness: &self.fitness,
            roulette: &self.roulette,
            worst: *self.order.last().expect("a population of at least 2"),
        };
        breed.children(
            &self.ops,
            self.seed,
            self.generation + 1,
            &mut self.next[elite..],
        )?;
        evaluator.evaluate(&self.next[elite..], &mut self.next_values[elite * k..])?;
        self.evaluations += (self.population.len() - elite) as u64;
        std::mem::swap(&mut self.population, &mut self.next);
        std::mem::swap(&mut self.values, &mut self.next_values);
        self.update(elite);
        Ok(())
    }

    /// Takes the population's individuals from `from` on (the newly evaluated) into the
    /// best values and the archive.
    fn update(&mut self, from: usize) {
        let k = self.senses.len();
        let fresh = &self.values[from * k..];
        for row in fresh.chunks_exact(k) {
            for ((b, &v), s) in self.best.iter_mut().zip(row).zip(&self.senses) {
                if b.is_nan() || s.better(v, *b) {
                    *b = v;
                }
            }
        }
        let s = &mut self.archive_scratch;
        s.values.clear();
        for m in &self.archive {
            s.values.extend_from_slice(&m.values);
        }
        s.values.extend_from_slice(fresh);
        let old = self.archive.len();
        s.fronts.sort(&s.values, k, &self.senses);
        s.first.clear();
        s.first.resize(s.values.len() / k, true);
        first_of_equals(&s.values, k, &mut s.order, &mut s.first);
        s.keep.clear();
        if !s.fronts.is_empty() {
            let values = &s.values;
            let first = &s.first;
            s.keep
                .extend(s.fronts.front(0).iter().copied().filter(|&i| {
                    let i = i as usize;
                    first[i] && !values[i * k..(i + 1) * k].iter().any(|v| v.is_nan())
                }));
        }
        let cap = self.settings.archive as usize;
        if s.keep.len() > cap {
            s.crowd.clear();
            s.crowd.resize(s.keep.len(), 0.0);
            crowding(
                &s.values,
                k,
                &self.senses,
                &s.keep,
                &mut s.order,
                &mut s.crowd,
            );
            s.order.clear();
            s.order.extend(0..s.keep.len() as u32);
            let crowd = &s.crowd;
            s.order.sort_unstable_by(|&a, &b| {
                crowd[b as usize]
                    .total_cmp(&crowd[a as usize])
                    .then(a.cmp(&b))
            });
            s.order.truncate(cap);
            s.order.sort_unstable();
            for (slot, &j) in s.order.iter().enumerate() {
                s.keep[slot] = s.keep[j as usize];
            }
            s.keep.truncate(cap);
        }
        let mut previous = std::mem::take(&mut self.archive);
        for &i in &s.keep {
            let i = i as usize;
            let member = if i < old {
                Member {
                    genome: std::mem::replace(
                        &mut previous[i].genome,
                        Genome::from_parts(Vec::new(), 0),
                    ),
                    values: std::mem::take(&mut previous[i].values),
                }
            } else {
                Member {
                    genome: self.population[from + i - old].clone(),
                    values: s.values[i * k..(i + 1) * k].to_vec(),
                }
            };
            self.archive.push(member);
        }
    }

    /// Appends the history entry of the generation just done and asks the observer.
    fn record(&mut self, elapsed_s: f64, observer: &mut impl MultiObserver<G>) -> Control {
        self.elapsed_s = elapsed_s;
        self.history.push(MultiHistoryEntry {
            generation: self.generation,
            elapsed_s,
            evaluations: self.evaluations,
            front: self.archive.len() as u32,
            best: self.best.clone(),
        });
        observer.observe(&MultiSnapshot {
            generation: self.generation,
            elapsed: Duration::from_secs_f64(elapsed_s),
            evaluations: self.evaluations,
            best: &self.best,
            front: &self.archive,
        })
    }

    fn finish(&self, stopped: StopReason) -> MultiResult<G> {
        MultiResult {
            front: self.archive.clone(),
            evaluations: self.evaluations,
            generations: self.generation,
            history: self.history.clone(),
            stopped,
        }
    }
}
