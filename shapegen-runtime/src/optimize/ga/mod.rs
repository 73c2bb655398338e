//! The genetic algorithm, the paper's Algorithm 1: its settings (`settings.rs`), the
//! breeding of one generation (`breed.rs`) and what the GA breeds with (`breeder.rs`),
//! which the hybrid, the multi-objective GA and the island model share.

mod breed;
mod breeder;
mod settings;

pub(crate) use breed::{Generation, Parents};
pub(crate) use breeder::{Breeder, check_population};
pub use settings::{GaSettings, ParentSelection};

use super::best::Best;
use super::core::Core;
use super::driver::{Held, Optimizer};
use super::error::OptimizeError;
use super::fitness::bits_vec;
use super::polish::{self, PolishState, Polisher};
use super::settings::Settings;
use crate::derive::Grammar;
use crate::evaluate::Evaluator;
use crate::genome::{Genome, Limits};

crate::checkpoint! {
    /// A checkpoint of a [`Ga`]: serialize it (e.g. with `serde_json`) and give it to
    /// [`Ga::resume`] to go on exactly as an uninterrupted run would.
    ///
    /// The random streams are fixed by the seed and the generation number, so the state
    /// holds no generator positions beyond those.
    pub struct GaState<G>: GaSettings, Best<G> {
        /// The current population, best first after the first generation.
        pub population: Vec<Genome<G>>,
        /// Its cached fitness.
        #[serde(with = "bits_vec")]
        pub fitness: Vec<f64>,
        /// The polishing under way, if any.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub polish: Option<PolishState<G>>,
    }
}

/// The genetic algorithm (the paper's Algorithm 1): each generation keeps the
/// `elitism` best unchanged, with their cached fitness, and fills the rest in pairs:
/// parent 1 by k-tournament, parent 2 by roulette on shifted fitness (see below), or as
/// another [`ParentSelection`] says; with
/// the mutation probability both are copied and mutated once each (grow, cut or alter
/// by their weights), otherwise they are crossed over. Only the new children are
/// evaluated.
///
/// How a pair is bred depends on [`GaSettings::operators`]:
/// - `weighted`: the operators keep genomes within the limits (a mutation the limits
///   forbid leaves the copy as it is), a failed crossover gives copies of the parents,
///   and every pair of slots takes the first two children it breeds.
/// - `original`, as the original's `createNewGeneration`: the original's operators,
///   which ignore the limits; a child is kept only if `min_len <= len < max_len` (max
///   excluded) and a failed crossover gives no children; breeding goes on until the
///   generation is full. The tournament never draws the worst-ranked individual (the
///   original draws its entrants among all but the last of the population sorted best
///   first). Initial genomes have exactly `initial_length` genes, unfiltered.
///
/// Fitness: NaN loses every tournament and has roulette weight 0; roulette weights are
/// `f - f_min` over finite values, or uniform over the `+inf` individuals if any. When
/// all weights are 0 (equal fitness) the wheel is uniform; the original's then always
/// gives the best individual.
///
/// Breeding runs in parallel with rayon; every pair of slots draws from its own stream
/// (seed, generation, pair), so results never depend on the thread count. With the
/// original's breeding a pair breeds again from its stream until both its slots hold
/// accepted children. Every child is then, as in the original, an accepted child of a
/// breeding event drawn as the original draws one, independently of all other events;
/// only the grouping of siblings differs: where a pair needs one more child and an event
/// gives two acceptable ones, the second is dropped, while the original's sequential
/// fill keeps both children of every event, and so may end a generation one individual
/// over the population size, which never happens here. A pair that 10 000 events do not
/// fill stops the run with a settings error (the original would loop forever).
///
/// Polishing (off by default): with [`polish`](GaSettings::polish), each generation
/// ends with a separable CMA-ES ([`SepCmaEs`](super::SepCmaEs)) drawing that many
/// candidates over the continuous parameters of the population's best, its structure
/// kept; the best candidate replaces it when it scores at least as well. The strategy
/// goes on while the best keeps its structure and starts again when another structure
/// leads; it draws from its own stream (seed, generation, 3 * 2^30) and is kept in
/// checkpoints.
///
/// Evaluations: elites keep their cached fitness and are not evaluated again, so every
/// generation after the first costs `population - elitism` evaluations (and `polish`
/// more while the best has a continuous parameter), with either operators; the original evaluates the whole population every generation, elites
/// included, so its evaluation counts are higher by `elitism` per generation.
///
/// ```
/// use shapegen_runtime::optimize::{Budget, FnEvaluator, Ga, GaSettings, Optimizer, Silent};
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
/// // Look for chains of 12 blocks.
/// let settings = GaSettings { population: 20, elitism: 4, initial_length: 4, ..GaSettings::default() };
/// let mut ga = Ga::<Chain>::new(settings, Limits::new(1, 30, 30)?, 7)?;
/// let mut eval = FnEvaluator(|g: &Genome<Chain>| -(g.len() as f64 - 12.0).abs());
/// let result = ga.run(&mut eval, &Budget::generations(30), &mut Silent)?;
/// assert_eq!(result.best.len(), 12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Ga<G> {
    core: Core<GaSettings, Best<G>>,
    breeder: Breeder<G>,
    polisher: Polisher<G>,
}

impl<G: Grammar> std::fmt::Debug for Ga<G> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.core.debug(f, "Ga").finish_non_exhaustive()
    }
}

impl<G: Grammar> Optimizer<G> for Ga<G> {
    type Settings = GaSettings;
    type State = GaState<G>;
    type Record = Best<G>;

    /// The population, the next generation bred beside it, and the checkpoint's copy;
    /// polishing's candidates and origin.
    fn genomes_held(settings: &GaSettings) -> Vec<Held> {
        vec![settings.held(1), polish::held(settings.polish)]
    }

    /// A GA with these settings, keeping genomes within `limits` (the weighted operators)
    /// or its children within `[min_len, max_len)` (the original's), seeded with `seed`.
    fn new(settings: GaSettings, limits: Limits, seed: u64) -> Result<Self, OptimizeError> {
        settings.validate()?;
        Ok(Ga {
            breeder: Breeder::new(&settings, limits, 1, 1)?,
            polisher: Polisher::new(),
            core: Core::new(settings, limits, seed),
        })
    }

    fn core(&self) -> &Core<GaSettings, Best<G>> {
        &self.core
    }

    fn parts(&mut self) -> (&mut Core<GaSettings, Best<G>>, &[Genome<G>], &[f64]) {
        self.breeder.parts(&mut self.core)
    }

    #[allow(clippy::type_complexity)]
    fn save_body(&self) -> (Vec<Genome<G>>, Vec<f64>, Option<PolishState<G>>) {
        let (population, fitness) = self.breeder.save();
        (population, fitness, self.polisher.save())
    }

    fn check_body(state: &GaState<G>) -> Result<(), OptimizeError> {
        Polisher::check(state.polish.as_ref())?;
        check_population(&state.settings, &state.population, &state.fitness, None)
    }

    #[allow(clippy::type_complexity)]
    fn restore_body(
        &mut self,
        (population, fitness, polish): (Vec<Genome<G>>, Vec<f64>, Option<PolishState<G>>),
    ) -> Result<(), OptimizeError> {
        self.breeder.restore((population, fitness));
        self.polisher.restore(polish);
        Ok(())
    }

    fn step_cost(&self) -> u64 {
        self.core.settings.children() + u64::from(self.core.settings.polish)
    }

    fn start(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        let core = &mut self.core;
        self.breeder
            .start(&core.settings, core.progress.seed, 0, evaluator)?;
        core.progress.evaluations += u64::from(core.settings.population);
        Ok(())
    }

    fn step(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        let (settings, progress) = (&self.core.settings, &mut self.core.progress);
        let b = &mut self.breeder;
        b.generation(settings, progress, evaluator)?;
        self.polisher.polish(
            (settings.polish, settings.polish_sigma),
            progress,
            evaluator,
            (&mut b.population, &mut b.scores),
        )
    }
}
