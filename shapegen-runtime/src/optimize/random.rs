//! Plain random search, the baseline every other method should beat: each generation
//! draws fresh models from the generator's own distribution and scores them, and the run
//! keeps the best it has seen.

use crate::optimize::settings::generations_field;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::best::Best;
use super::core::Core;
use super::driver::{Held, Optimizer};
use super::error::{OptimizeError, SettingsError, check_positive};
use super::run::stream;
use super::settings::Settings;
use crate::derive::Grammar;
use crate::evaluate::Evaluator;
use crate::genome::{Genome, Limits};
use crate::ops::Operators;

/// Settings of [`RandomSearch`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RandomSearchSettings {
    /// Models drawn and scored each generation (at least 1).
    pub samples: u32,
    /// Generations after the first draw.
    pub generations: u64,
}

impl Default for RandomSearchSettings {
    /// 100 models a generation for 100 generations.
    fn default() -> Self {
        RandomSearchSettings {
            samples: 100,
            generations: 100,
        }
    }
}

impl Settings for RandomSearchSettings {
    generations_field!("generations", generations);

    /// The given limits but `min_len`: the generator's own distribution, cut at
    /// `max_len` and `max_depth`, draws models of any length from the root alone up.
    fn kept_limits(&self, limits: Limits) -> Limits {
        limits.without_min_len()
    }

    fn validate(&self) -> Result<(), SettingsError> {
        check_positive("samples", self.samples)
    }
}

crate::checkpoint! {
    /// A checkpoint of a [`RandomSearch`]: its settings, limits and progress (the best
    /// model so far among them); the next draw depends on nothing else.
    pub struct RandomSearchState<G>: RandomSearchSettings, Best<G> {}
}

/// Plain random search: every generation draws
/// [`samples`](RandomSearchSettings::samples) models as the generator derives them on its
/// own ([`Operators::sample`]: each child slot taken with its probability, within the
/// limits' maximum length and depth) and scores them; the run's record keeps the best of
/// all. Nothing is bred, so the only thing it learns is which model was best.
///
/// Model `i` of generation `g` is drawn from the stream (seed, `g`, `i`), so results never
/// depend on the thread count, and a resumed run draws what an uninterrupted one would.
/// A generation costs `samples` evaluations, the first draw included.
///
/// ```
/// use shapegen_runtime::optimize::{
///     Budget, FnEvaluator, Optimizer, RandomSearch, RandomSearchSettings, Silent,
/// };
/// use shapegen_runtime::prelude::*;
///
/// generator! {
///     /// A chain of blocks.
///     pub Chain {
///         axiom Seg;
///         node Seg {
///             children { next: Seg = 0.8 }
///             derive(s) {
///                 s.emit(CUBE);
///                 if let Some(next) = next { s.translate(vec3(0.0, 1.0, 0.0)).derive(next); }
///             }
///         }
///     }
/// }
///
/// // Chains of 6 blocks are best; random chains get there by chance.
/// let settings = RandomSearchSettings { samples: 20, generations: 9 };
/// let mut search = RandomSearch::<Chain>::new(settings, Limits::new(1, 30, 30)?, 7)?;
/// let mut eval = FnEvaluator(|g: &Genome<Chain>| -(g.len() as f64 - 6.0).abs());
/// let result = search.run(&mut eval, &Budget::generations(9), &mut Silent)?;
/// assert_eq!(result.evaluations, 10 * 20);
/// assert_eq!(result.best.len(), 6);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct RandomSearch<G> {
    core: Core<RandomSearchSettings, Best<G>>,
    ops: Operators<G>,
    /// The models of the last draw and their fitness.
    samples: Vec<Genome<G>>,
    fitness: Vec<f64>,
}

impl<G: Grammar> RandomSearch<G> {
    /// Draws the models of generation `generation` and scores them.
    fn draw(
        &mut self,
        generation: u64,
        evaluator: &mut (dyn Evaluator<G> + '_),
    ) -> Result<(), OptimizeError> {
        let seed = self.core.progress.seed;
        let ops = &self.ops;
        self.samples.par_iter_mut().enumerate().for_each_init(
            || ops.clone(),
            |ops, (i, genome)| ops.sample_into(genome, &mut stream(seed, generation, i as u64)),
        );
        evaluator.evaluate(&self.samples, &mut self.fitness)?;
        self.core.progress.evaluations += self.samples.len() as u64;
        Ok(())
    }
}

impl<G: Grammar> Optimizer<G> for RandomSearch<G> {
    type Settings = RandomSearchSettings;
    type State = RandomSearchState<G>;
    type Record = Best<G>;

    /// The models of one draw; a checkpoint saves none of them.
    fn genomes_held(settings: &RandomSearchSettings) -> Vec<Held> {
        vec![Held::per("optimizer.samples", settings.samples, 1, 0)]
    }

    fn new(
        settings: RandomSearchSettings,
        limits: Limits,
        seed: u64,
    ) -> Result<Self, OptimizeError> {
        settings.validate()?;
        let n = settings.samples as usize;
        Ok(RandomSearch {
            core: Core::new(settings, limits, seed),
            ops: Operators::new(limits)?,
            samples: (0..n).map(|_| Genome::from_parts(Vec::new(), 0)).collect(),
            fitness: vec![f64::NAN; n],
        })
    }

    fn core(&self) -> &Core<RandomSearchSettings, Best<G>> {
        &self.core
    }

    fn parts(
        &mut self,
    ) -> (
        &mut Core<RandomSearchSettings, Best<G>>,
        &[Genome<G>],
        &[f64],
    ) {
        (&mut self.core, &self.samples, &self.fitness)
    }

    fn save_body(&self) {}

    fn restore_body(&mut self, (): ()) -> Result<(), OptimizeError> {
        Ok(())
    }

    fn step_cost(&self) -> u64 {
        self.core.settings.samples.into()
    }

    fn start(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        self.draw(0, evaluator)
    }

    fn step(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        self.draw(self.core.progress.generation + 1, evaluator)
    }
}
