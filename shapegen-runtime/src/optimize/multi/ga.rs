//! The multi-objective GA: the GA's breeding, selecting on a multi-objective selection
//! fitness, with an archive of the non-dominated models found.

use std::time::Duration;

use serde::{Deserialize, Serialize};

use super::rank::{Fronts, RankScratch, crowding, first_of_equals, selection_fitness};
use super::settings::MultiGaSettings;
use crate::derive::Grammar;
use crate::genome::{Genome, Limits};
use crate::ops::Operators;
use crate::optimize::error::check_sizes;
use crate::optimize::fitness::{Roulette, bits_vec, rank};
use crate::optimize::ga::{Breed, random_population};
use crate::optimize::run::grammar_struct_traits;
use crate::optimize::{
    Control, EvaluateError, Held, MultiEvaluator, OptimizeError, Optimizer, Progress, Record,
    Sense, Settings, Silent, StopReason,
};

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
/// Results never depend on the thread count; budgets are those of [`Budget`](crate::optimize::Budget).
///
/// ```
/// use shapegen_runtime::optimize::multi::{MultiEvaluator, MultiGa, MultiGaSettings};
/// use shapegen_runtime::optimize::{Budget, EvaluateError, GaSettings, Optimizer, Sense, Silent};
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
    progress: Progress<Front<G>>,
    population: Vec<Genome<G>>,
    values: Vec<f64>,
    next: Vec<Genome<G>>,
    next_values: Vec<f64>,
    /// The parent each child of `next` was bred from, by index into `population`.
    from: Vec<u32>,
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
            .field("generation", &self.progress.generation)
            .field("evaluations", &self.progress.evaluations)
            .field("archive", &self.progress.record.archive.len())
            .finish_non_exhaustive()
    }
}

impl<G: Grammar> MultiGa<G> {
    /// The archive: the non-dominated models found so far.
    pub fn front(&self) -> &[Member<G>] {
        &self.progress.record.archive
    }

    /// Takes the population's individuals from `from` on (the newly evaluated) into the
    /// best values and the archive.
    fn update(&mut self, from: usize) {
        let record = &mut self.progress.record;
        let k = record.senses.len();
        let fresh = &self.values[from * k..];
        for row in fresh.chunks_exact(k) {
            for ((b, &v), s) in record.best.iter_mut().zip(row).zip(&record.senses) {
                if b.is_nan() || s.better(v, *b) {
                    *b = v;
                }
            }
        }
        let s = &mut self.archive_scratch;
        s.values.clear();
        for m in &record.archive {
            s.values.extend_from_slice(&m.values);
        }
        s.values.extend_from_slice(fresh);
        let old = record.archive.len();
        s.fronts.sort(&s.values, k, &record.senses);
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
                &record.senses,
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
        let mut previous = std::mem::take(&mut record.archive);
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
            record.archive.push(member);
        }
    }
}

impl<G: Grammar> Optimizer<G> for MultiGa<G> {
    type Settings = MultiGaSettings;
    type State = MultiGaState<G>;
    type Record = Front<G>;

    /// The GA's population, next generation and checkpoint copy, and the archive with
    /// its checkpoint copy.
    fn genomes_held(settings: &MultiGaSettings) -> Vec<Held> {
        vec![
            settings.ga.held(1),
            Held {
                genomes: 2 * u64::from(settings.archive),
                saved: settings.archive.into(),
                setting: "optimizer.archive",
                value: settings.archive.into(),
            },
        ]
    }

    /// A multi-objective GA with these settings, keeping genomes within `limits`, seeded
    /// with `seed`.
    fn new(settings: MultiGaSettings, limits: Limits, seed: u64) -> Result<Self, OptimizeError> {
        settings.validate()?;
        let n = settings.ga.population as usize;
        let empty = || Genome::from_parts(Vec::new(), 0);
        Ok(MultiGa {
            ops: settings.ga.build_operators(limits)?,
            progress: Progress::new(seed),
            population: (0..n).map(|_| empty()).collect(),
            values: Vec::new(),
            next: (0..n).map(|_| empty()).collect(),
            next_values: Vec::new(),
            from: vec![0; n - settings.ga.elitism as usize],
            fitness: vec![f64::NAN; n],
            order: Vec::with_capacity(n),
            roulette: Roulette::default(),
            rank_scratch: RankScratch::default(),
            archive_scratch: ArchiveScratch::default(),
            settings,
        })
    }

    fn resume(state: MultiGaState<G>) -> Result<Self, OptimizeError> {
        // The population is counted before the GA is made, so that settings disagreeing
        // with the checkpoint cannot make it allocate more than that holds.
        if !state.history.is_empty() {
            let n = state.settings.ga.population as usize;
            check_sizes(
                &[(state.population.len(), n, "genomes")],
                format_args!("a population of {n}"),
            )?;
        }
        let mut ga = MultiGa::new(state.settings, state.limits, state.seed)?;
        let record = Front {
            senses: state.senses,
            archive: state.archive,
            best: state.best,
            history: state.history,
        };
        if record.started() {
            let (n, k) = (ga.population.len(), record.senses.len());
            let odd = record.archive.iter().filter(|m| m.values.len() != k);
            check_sizes(
                &[
                    (k.min(1), 1, "objectives (at least)"),
                    (state.population.len(), n, "genomes"),
                    (state.values.len(), n * k, "values"),
                    (record.best.len(), k, "best values"),
                    (odd.count(), 0, "archive members of another size"),
                ],
                format_args!("a population of {n} on {k} objectives"),
            )?;
            ga.population = state.population;
            ga.values = state.values;
        }
        ga.progress = Progress {
            seed: state.seed,
            generation: state.generation,
            evaluations: state.evaluations,
            elapsed_s: state.elapsed_s,
            record,
        };
        Ok(ga)
    }

    fn checkpoint(&self) -> MultiGaState<G> {
        let (p, r) = (&self.progress, &self.progress.record);
        MultiGaState {
            settings: self.settings.clone(),
            limits: *self.ops.limits(),
            seed: p.seed,
            generation: p.generation,
            evaluations: p.evaluations,
            elapsed_s: p.elapsed_s,
            senses: r.senses.clone(),
            population: self.population.clone(),
            values: self.values.clone(),
            archive: r.archive.clone(),
            best: r.best.clone(),
            history: r.history.clone(),
        }
    }

    fn settings(&self) -> &MultiGaSettings {
        &self.settings
    }

    fn state_settings(state: &MultiGaState<G>) -> &MultiGaSettings {
        &state.settings
    }

    fn state_limits(state: &MultiGaState<G>) -> &Limits {
        &state.limits
    }

    fn progress(&self) -> &Progress<Front<G>> {
        &self.progress
    }

    fn parts(&mut self) -> (&mut Progress<Front<G>>, &[Genome<G>], &[f64]) {
        (&mut self.progress, &self.population, &self.values)
    }

    fn step_cost(&self) -> u64 {
        u64::from(self.settings.ga.population - self.settings.ga.elitism)
    }

    /// Fails if the evaluator has no objectives, if its senses differ from those of
    /// earlier runs, or if a weighted sum's weights are not one per objective.
    fn check(&self, evaluator: &mut (dyn MultiEvaluator<G> + '_)) -> Result<(), OptimizeError> {
        let senses = evaluator.senses();
        if senses.is_empty() {
            return Err(EvaluateError("the evaluator has no objectives".into()).into());
        }
        let record = &self.progress.record;
        if record.started() && record.senses != senses {
            return Err(OptimizeError::Checkpoint(format!(
                "objectives {:?} for a run on {:?}",
                senses, record.senses
            )));
        }
        self.settings.selection.check_objectives(senses.len())?;
        Ok(())
    }

    /// Grows and evaluates the initial population.
    fn start(&mut self, evaluator: &mut (dyn MultiEvaluator<G> + '_)) -> Result<(), OptimizeError> {
        let senses = evaluator.senses().to_vec();
        let (n, k) = (self.population.len(), senses.len());
        let seed = self.progress.seed;
        random_population(&self.ops, &self.settings.ga, seed, &mut self.population);
        self.values.clear();
        self.values.resize(n * k, f64::NAN);
        evaluator.evaluate(&self.population, &mut self.values)?;
        self.progress.evaluations += n as u64;
        self.progress.record.senses = senses;
        self.progress.record.best = vec![f64::NAN; k];
        self.update(0);
        Ok(())
    }

    /// One generation: selection fitness, elites, breeding, evaluation of the children.
    fn step(&mut self, evaluator: &mut (dyn MultiEvaluator<G> + '_)) -> Result<(), OptimizeError> {
        let senses = &self.progress.record.senses;
        let k = senses.len();
        let elite = self.settings.ga.elitism as usize;
        selection_fitness(
            &self.settings.selection,
            &self.values,
            k,
            senses,
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
        let (seed, generation) = (self.progress.seed, self.progress.generation + 1);
        let children = &mut self.next[elite..];
        breed.children(&self.ops, seed, generation, children, &mut self.from)?;
        evaluator.evaluate_bred(
            &self.next[elite..],
            &self.population,
            &self.from,
            &mut self.next_values[elite * k..],
        )?;
        self.progress.evaluations += self.step_cost();
        std::mem::swap(&mut self.population, &mut self.next);
        std::mem::swap(&mut self.values, &mut self.next_values);
        self.update(elite);
        Ok(())
    }
}
