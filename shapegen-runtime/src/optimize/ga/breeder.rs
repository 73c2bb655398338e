//! What a GA breeds with ([`Breeder`]): its operators, its population and their scores,
//! the next generation bred beside it, and the breeding's scratch; the GA, the hybrid,
//! the multi-objective GA and the island model each hold one beside their [`Core`](
//! crate::optimize::Core).

use rayon::prelude::*;

use super::breed::{Generation, Parents};
use super::settings::GaSettings;
use crate::derive::Grammar;
use crate::evaluate::{Bred, EvaluateError, Evaluator};
use crate::genome::{Genome, Limits};
use crate::ops::Operators;
use crate::optimize::error::OptimizeError;
use crate::optimize::error::check_sizes;
use crate::optimize::fitness::Roulette;
use crate::optimize::run::{Progress, derived_seed, stream};

/// A GA's operators and populations: one population, or the islands of an island model
/// one after the other, each of the settings' size, with their scores (the same number
/// per genome: one fitness, or an objective vector), and the next generation bred
/// beside them.
pub(crate) struct Breeder<G> {
    /// The operators, keeping to the limits.
    pub(crate) ops: Operators<G>,
    /// The current population.
    pub(crate) population: Vec<Genome<G>>,
    /// Its scores.
    pub(crate) scores: Vec<f64>,
    /// The next generation, as it is bred.
    pub(crate) next: Vec<Genome<G>>,
    /// Its scores.
    pub(crate) next_scores: Vec<f64>,
    /// The parent each child was bred from, by index into `population`.
    pub(crate) from: Vec<u32>,
    /// Scratch: a population's ranks.
    pub(crate) order: Vec<u32>,
    /// Scratch: the roulette wheel.
    pub(crate) roulette: Roulette,
}

impl<G: Grammar> Breeder<G> {
    /// Buffers for `islands` populations of `settings`, with `k` scores per genome (0
    /// while the number is not known), breeding with the settings' operators within
    /// `limits`; fails if the settings do not fit the limits.
    pub(crate) fn new(
        settings: &GaSettings,
        limits: Limits,
        islands: usize,
        k: usize,
    ) -> Result<Self, OptimizeError> {
        let n = settings.population as usize;
        let empty = |count| {
            (0..count)
                .map(|_| Genome::from_parts(Vec::new(), 0))
                .collect()
        };
        Ok(Breeder {
            ops: settings.build_operators(limits)?,
            population: empty(islands * n),
            scores: vec![f64::NAN; islands * n * k],
            next: empty(islands * n),
            next_scores: vec![f64::NAN; islands * n * k],
            from: vec![0; islands * settings.children() as usize],
            order: Vec::with_capacity(n),
            roulette: Roulette::default(),
        })
    }

    /// Grows every island's initial population in parallel: island `i` from the seed
    /// derived for `first + i` (the run's own for island 0), its genome `j` from stream
    /// (that seed, 0, `j`), to a length around the settings' initial length (exactly
    /// that length with the original's operators).
    pub(crate) fn grow(&mut self, settings: &GaSettings, seed: u64, first: usize) {
        let len = settings.initial_length;
        let n = settings.population as usize;
        for (i, island) in self.population.chunks_mut(n).enumerate() {
            let seed = derived_seed(seed, (first + i) as u64);
            island.par_iter_mut().enumerate().for_each_init(
                || self.ops.clone(),
                |ops, (j, g)| ops.random_into(len, g, &mut stream(seed, 0, j as u64)),
            );
        }
    }

    /// Grows every island's initial population (see [`grow`](Self::grow)) and evaluates
    /// them on one fitness.
    pub(crate) fn start(
        &mut self,
        settings: &GaSettings,
        seed: u64,
        first: usize,
        evaluator: &mut (dyn Evaluator<G> + '_),
    ) -> Result<(), OptimizeError> {
        self.grow(settings, seed, first);
        evaluator.evaluate(&self.population, &mut self.scores)?;
        Ok(())
    }

    /// Breeds and evaluates the next generation of a run on one fitness, counting its
    /// evaluations in `progress`.
    pub(crate) fn generation<R>(
        &mut self,
        settings: &GaSettings,
        progress: &mut Progress<R>,
        evaluator: &mut (dyn Evaluator<G> + '_),
    ) -> Result<(), OptimizeError> {
        let (seed, generation) = (progress.seed, progress.generation + 1);
        self.step(settings, seed, generation, None, |bred, out| {
            evaluator.evaluate_bred(bred, out)
        })?;
        progress.evaluations += settings.children();
        Ok(())
    }

    /// Breeds the next generation of the one population and scores its children with
    /// `evaluate` (called as [`Evaluator::evaluate_bred`](crate::optimize::Evaluator::
    /// evaluate_bred) is), then makes it the current one: the `elitism` best, ranked by
    /// `selection` (one value per genome; the scores themselves when `None`), keep their
    /// scores; the children of generation `generation` draw from the streams of `seed`.
    pub(crate) fn step(
        &mut self,
        settings: &GaSettings,
        seed: u64,
        generation: u64,
        selection: Option<&[f64]>,
        evaluate: impl FnOnce(Bred<'_, G>, &mut [f64]) -> Result<(), EvaluateError>,
    ) -> Result<(), OptimizeError> {
        let elite = settings.elitism as usize;
        let k = self.scores.len() / self.population.len();
        self.next_scores.resize(self.scores.len(), f64::NAN);
        let (elites, children) = self.next.split_at_mut(elite);
        Generation {
            settings,
            ops: &self.ops,
            seed,
            generation,
        }
        .breed(
            Parents {
                population: &self.population,
                fitness: selection.unwrap_or(&self.scores),
                scores: &self.scores,
            },
            &mut self.order,
            &mut self.roulette,
            (elites, &mut self.next_scores[..elite * k]),
            (children, &mut self.from),
        )?;
        let bred = Bred {
            children: &self.next[elite..],
            parents: &self.population,
            from: &self.from,
        };
        evaluate(bred, &mut self.next_scores[elite * k..])?;
        self.advance();
        Ok(())
    }

    /// `core` beside the population and its scores, as
    /// [`Optimizer::parts`](crate::optimize::driver::Optimizer::parts) returns them.
    pub(crate) fn parts<'a, C>(
        &'a self,
        core: &'a mut C,
    ) -> (&'a mut C, &'a [Genome<G>], &'a [f64]) {
        (core, &self.population, &self.scores)
    }

    /// Copies of the population and its scores, as a checkpoint saves them.
    pub(crate) fn save(&self) -> (Vec<Genome<G>>, Vec<f64>) {
        (self.population.clone(), self.scores.clone())
    }

    /// Puts back a population and its scores that [`save`](Self::save) gave.
    pub(crate) fn restore(&mut self, (population, scores): (Vec<Genome<G>>, Vec<f64>)) {
        self.population = population;
        self.scores = scores;
    }

    /// Makes the next generation the current one.
    pub(crate) fn advance(&mut self) {
        std::mem::swap(&mut self.population, &mut self.next);
        std::mem::swap(&mut self.scores, &mut self.next_scores);
    }
}

/// Checks a checkpoint's population and fitness (of island `island`, if given) against
/// a population of `settings`.
pub(crate) fn check_population<G>(
    settings: &GaSettings,
    population: &[Genome<G>],
    fitness: &[f64],
    island: Option<usize>,
) -> Result<(), OptimizeError> {
    let n = settings.population as usize;
    let island = island.map(|k| format!("island {k}, ")).unwrap_or_default();
    check_sizes(
        &[
            (population.len(), n, "genomes"),
            (fitness.len(), n, "fitness values"),
        ],
        format_args!("{island}a population of {n}"),
    )
}
