//! The multi-objective GA: the GA's breeding, selecting on a multi-objective selection
//! fitness, with an archive of the non-dominated models found.

use super::rank::{Fronts, RankScratch, crowding, first_of_equals, selection_fitness};
use super::record::{Front, Member};
use super::settings::MultiGaSettings;
use super::state::MultiGaState;
use crate::derive::Grammar;
use crate::evaluate::{EvaluateError, MultiEvaluator};
use crate::genome::{Genome, Limits};
use crate::optimize::core::Core;
use crate::optimize::driver::{Held, Optimizer, Record};
use crate::optimize::error::OptimizeError;
use crate::optimize::error::{CheckpointError, check_sizes};
use crate::optimize::ga::Breeder;
use crate::optimize::settings::Settings;

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
    core: Core<MultiGaSettings, Front<G>>,
    /// The GA's breeding; the scores are the objective values, row-major.
    breeder: Breeder<G>,
    /// The selection fitness of the population.
    fitness: Vec<f64>,
    rank_scratch: RankScratch,
    archive_scratch: ArchiveScratch,
}

impl<G: Grammar> std::fmt::Debug for MultiGa<G> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let p = &self.core.progress;
        f.debug_struct("MultiGa")
            .field("settings", &self.core.settings)
            .field("generation", &p.generation)
            .field("evaluations", &p.evaluations)
            .field("archive", &p.record.archive.len())
            .finish_non_exhaustive()
    }
}

impl<G: Grammar> MultiGa<G> {
    /// The archive: the non-dominated models found so far.
    pub fn front(&self) -> &[Member<G>] {
        &self.core.progress.record.archive
    }

    /// Takes the population's individuals from `from` on (the newly evaluated) into the
    /// best values and the archive.
    fn update(&mut self, from: usize) {
        let record = &mut self.core.progress.record;
        let k = record.senses.len();
        let fresh = &self.breeder.scores[from * k..];
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
        let cap = self.core.settings.archive as usize;
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
                    genome: self.breeder.population[from + i - old].clone(),
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
            Held::per("optimizer.archive", settings.archive, 2, 1),
        ]
    }

    /// A multi-objective GA with these settings, keeping genomes within `limits`, seeded
    /// with `seed`.
    fn new(settings: MultiGaSettings, limits: Limits, seed: u64) -> Result<Self, OptimizeError> {
        settings.validate()?;
        Ok(MultiGa {
            // The number of objectives is known once the evaluator is.
            breeder: Breeder::new(&settings.ga, limits, 1, 0)?,
            fitness: vec![f64::NAN; settings.ga.population as usize],
            rank_scratch: RankScratch::default(),
            archive_scratch: ArchiveScratch::default(),
            core: Core::new(settings, limits, seed),
        })
    }

    fn core(&self) -> &Core<MultiGaSettings, Front<G>> {
        &self.core
    }

    fn parts(&mut self) -> (&mut Core<MultiGaSettings, Front<G>>, &[Genome<G>], &[f64]) {
        self.breeder.parts(&mut self.core)
    }

    fn save_body(&self) -> (Vec<Genome<G>>, Vec<f64>) {
        self.breeder.save()
    }

    /// Counts the population first, then checks the objective values, the best values
    /// and the archive against the objectives.
    fn check_body(state: &MultiGaState<G>) -> Result<(), OptimizeError> {
        let n = state.settings.ga.population as usize;
        let genomes = (state.population.len(), n, "genomes");
        check_sizes(&[genomes], format_args!("a population of {n}"))?;
        let record = &state.progress.record;
        let k = record.senses.len();
        let odd = record.archive.iter().filter(|m| m.values.len() != k);
        check_sizes(
            &[
                (k.min(1), 1, "objectives (at least)"),
                genomes,
                (state.values.len(), n * k, "values"),
                (record.best.len(), k, "best values"),
                (odd.count(), 0, "archive members of another size"),
            ],
            format_args!("a population of {n} on {k} objectives"),
        )
    }

    fn restore_body(&mut self, body: (Vec<Genome<G>>, Vec<f64>)) -> Result<(), OptimizeError> {
        self.breeder.restore(body);
        Ok(())
    }

    fn step_cost(&self) -> u64 {
        self.core.settings.ga.children()
    }

    /// Fails if the evaluator has no objectives, if its senses differ from those of
    /// earlier runs, or if a weighted sum's weights are not one per objective.
    fn check(&self, evaluator: &mut (dyn MultiEvaluator<G> + '_)) -> Result<(), OptimizeError> {
        let senses = evaluator.senses();
        if senses.is_empty() {
            return Err(EvaluateError("the evaluator has no objectives".into()).into());
        }
        let record = &self.core.progress.record;
        if record.started() && record.senses != senses {
            return Err(OptimizeError::Checkpoint(CheckpointError::Objectives {
                found: senses.to_vec(),
                saved: record.senses.clone(),
            }));
        }
        self.core
            .settings
            .selection
            .check_objectives(senses.len())?;
        Ok(())
    }

    /// Grows and evaluates the initial population.
    fn start(&mut self, evaluator: &mut (dyn MultiEvaluator<G> + '_)) -> Result<(), OptimizeError> {
        let senses = evaluator.senses().to_vec();
        let k = senses.len();
        let (b, progress) = (&mut self.breeder, &mut self.core.progress);
        let n = b.population.len();
        b.grow(&self.core.settings.ga, progress.seed, 0);
        b.scores.clear();
        b.scores.resize(n * k, f64::NAN);
        evaluator.evaluate(&b.population, &mut b.scores)?;
        progress.evaluations += n as u64;
        progress.record.senses = senses;
        progress.record.best = vec![f64::NAN; k];
        self.update(0);
        Ok(())
    }

    /// One generation: selection fitness, elites, breeding, evaluation of the children.
    fn step(&mut self, evaluator: &mut (dyn MultiEvaluator<G> + '_)) -> Result<(), OptimizeError> {
        let (settings, progress) = (&self.core.settings, &self.core.progress);
        let senses = &progress.record.senses;
        selection_fitness(
            &settings.selection,
            &self.breeder.scores,
            senses.len(),
            senses,
            &mut self.fitness,
            &mut self.rank_scratch,
        );
        self.breeder.step(
            &settings.ga,
            progress.seed,
            progress.generation + 1,
            Some(&self.fitness),
            |bred, out| evaluator.evaluate_bred(bred, out),
        )?;
        self.core.progress.evaluations += self.step_cost();
        self.update(self.core.settings.ga.elitism as usize);
        Ok(())
    }
}
