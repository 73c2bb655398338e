//! The hybrid method: the paper's GA, its first population grown by a few steps of
//! SOSMC and its best individuals refined by short RJMCMC chains every generation
//! ([`Hybrid`]).

mod refine;

use crate::optimize::settings::generations_field;
use serde::{Deserialize, Serialize};

use super::SmcState;
use super::best::Best;
use super::core::Core;
use super::driver::{Held, Optimizer, Record};
use super::error::check_range;
use super::error::{OptimizeError, SettingsError};
use super::fitness::bits_vec;
use super::ga::GaSettings;
use super::ga::{Breeder, check_population};
use super::polish::{self, PolishState, Polisher};
use super::run::derived_seed;
use super::settings::Settings;
use super::smc::{Order, Smc, SmcSettings, SmcVariant};
use crate::derive::Grammar;
use crate::evaluate::Evaluator;
use crate::genome::{Genome, Limits};
use crate::ops::Operators;

/// Settings of the [`Hybrid`]: the GA's, and those of its seeding and its refinement.
/// Loads from scene files with serde; missing fields take the [`Default`] values,
/// unknown fields are errors.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HybridSettings {
    /// The GA that breeds every generation.
    pub ga: GaSettings,
    /// SOSMC steps that grow part of the first population from the axiom before the GA
    /// breeds it; 0 starts from random genomes, as the GA does.
    pub seed_steps: u32,
    /// The share of the first population that the seeding grows, in `[0, 1]`; the rest
    /// are random genomes of the GA's `initial_length`, as the GA starts from. 0 starts
    /// from random genomes alone, 1 from seeded ones alone.
    pub seed_share: f64,
    /// How many of the best individuals a short chain refines each generation; at most
    /// the population. 0 refines none.
    pub refine: u32,
    /// Moves each refined individual makes per generation; 0 refines none.
    pub refine_moves: u32,
    /// Chance that a refinement move is a jump (a subtree redrawn from the grammar)
    /// rather than a diffusion (one gene's parameters redrawn); in `[0, 1]`.
    pub jump_probability: f64,
}

impl Default for HybridSettings {
    /// [`over`](Self::over) the GA's defaults.
    fn default() -> Self {
        HybridSettings::over(GaSettings::default())
    }
}

impl Settings for HybridSettings {
    generations_field!("generations", ga.generations);

    /// Its GA's, but shorter than `min_len` while the seeding grows the first
    /// population from the axiom (and then while the GA breeds from what it grew).
    fn kept_limits(&self, limits: Limits) -> Limits {
        let ga = self.ga.kept_limits(limits);
        if self.seeded() > 0 {
            ga.without_min_len()
        } else {
            ga
        }
    }

    /// Checks every field; the error names the first one out of range.
    fn validate(&self) -> Result<(), SettingsError> {
        self.ga.validate()?;
        if self.refine > self.ga.population {
            return Err(SettingsError::new(
                "refine",
                self.refine,
                "at most the population",
            ));
        }
        check_range("seed_share", self.seed_share, 0.0, 1.0, "between 0 and 1")?;
        check_range(
            "jump_probability",
            self.jump_probability,
            0.0,
            1.0,
            "between 0 and 1",
        )?;
        Ok(())
    }
}

impl HybridSettings {
    /// The candidates a generation's polishing draws unless the settings say otherwise.
    pub const POLISH: u32 = 8;

    /// The hybrid's own defaults over the GA `ga` (a generator's published settings,
    /// say): three seeding steps growing half of the first population, the four best
    /// refined by two moves each generation, and the best polished by
    /// [`POLISH`](Self::POLISH) candidates a generation.
    ///
    /// ```
    /// use shapegen_runtime::optimize::{GaSettings, HybridSettings};
    ///
    /// let h = HybridSettings::over(GaSettings { population: 60, ..GaSettings::default() });
    /// assert_eq!((h.ga.population, h.ga.polish), (60, HybridSettings::POLISH));
    /// assert_eq!((h.seed_steps, h.seed_share), (3, 0.5));
    /// ```
    pub fn over(ga: GaSettings) -> Self {
        HybridSettings {
            ga: GaSettings {
                polish: Self::POLISH,
                ..ga
            },
            seed_steps: 3,
            seed_share: 0.5,
            refine: 4,
            refine_moves: 2,
            jump_probability: 0.5,
        }
    }

    /// How many of the first population the seeding grows: `seed_share` of it (rounded
    /// to the nearest), none without seeding steps.
    fn seeded(&self) -> u32 {
        if self.seed_steps == 0 {
            return 0;
        }
        (self.seed_share * f64::from(self.ga.population)).round() as u32
    }

    /// The SOSMC that seeds the first population.
    fn seeding(&self) -> SmcSettings {
        SmcSettings {
            particles: self.seeded(),
            steps: u64::from(self.seed_steps),
            order: Order::Stochastic,
            variant: SmcVariant::Generative,
            ..SmcSettings::default()
        }
    }
}

crate::checkpoint! {
    /// A checkpoint of a [`Hybrid`], resumed by [`Hybrid::resume`].
    pub struct HybridState<G>: HybridSettings, Best<G> {
        /// The population (empty while it is being seeded).
        pub population: Vec<Genome<G>>,
        /// Its fitness.
        #[serde(with = "bits_vec")]
        pub fitness: Vec<f64>,
        /// The SOSMC seeding the first population, while it runs.
        pub seeding: Option<SmcState<G>>,
        /// The polishing under way, if any.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub polish: Option<PolishState<G>>,
    }
}

/// The hybrid method: the paper's GA ([`Ga`](super::Ga)) with two additions, each of
/// which its settings can turn off (with both off it is the GA, to the bit). Each was
/// kept because it helped in the measurements of `benches/README.md` ("The hybrid
/// method"); annealed refinement, restarts on stagnation and adaptive operator rates
/// were tried there and dropped.
///
/// - **Seeding**: with [`seed_steps`](HybridSettings::seed_steps), a share of the first
///   population ([`seed_share`](HybridSettings::seed_share), half by default) is grown
///   by SOSMC (the generative variant, [`SmcVariant::Generative`]) from the axiom for
///   that many steps, one step per generation: small, well-formed models, cheap to
///   score. The rest are the GA's random genomes of its `initial_length`, drawn and
///   scored with the last seeding step. Seeded models lead where a goal wants small
///   models (volumes), random ones where it wants large ones (trees); with both in the
///   first population, selection takes whichever leads.
/// - **Refinement**: after each generation is bred and scored, its
///   [`refine`](HybridSettings::refine) best individuals each make
///   [`refine_moves`](HybridSettings::refine_moves) moves of a short RJMCMC chain, the
///   tempered variant's jumps and diffusions ([`McmcVariant::Tempered`](
///   super::McmcVariant::Tempered)); a move is kept when it loses nothing (a chain at
///   temperature 0). The refined individuals take the place of those they came from.
/// - **Polishing** ([`HybridSettings::POLISH`] candidates by default): with
///   [`polish`](GaSettings::polish), the
///   continuous parameters of the generation's best are then tuned by a separable
///   CMA-ES ([`SepCmaEs`](super::SepCmaEs)) that draws that many candidates; the
///   strategy goes on while the best keeps its structure and starts again when another
///   structure leads. The best candidate replaces the individual when it scores at least
///   as well. The strategy is part of the checkpoint.
///
/// Random streams: the GA breeds generation `g` from (seed, `g`, pair); refinement
/// chain `i` of generation `g` draws from (seed, `g`, 2^31 + `i`), its polishing from
/// (seed, `g`, 3 * 2^30); the random first
/// population comes from the run's seed, its seeding from the seed derived for `2^32`.
/// Results never depend on the thread count.
///
/// Evaluations: with seeding, the first seeded particles cost `k = seed_share *
/// population` (rounded), each seeding step as much, and the last one `population - k`
/// more for the random genomes; without, the first population costs `population`. A
/// generation costs `population - elitism + refine * refine_moves + polish`
/// (polishing makes none while the best has no continuous parameter).
///
/// ```
/// use shapegen_runtime::optimize::{Budget, FnEvaluator, GaSettings, Hybrid, HybridSettings};
/// use shapegen_runtime::optimize::{Optimizer, Silent};
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
/// let ga = GaSettings { population: 20, elitism: 4, initial_length: 4, ..GaSettings::default() };
/// let settings = HybridSettings { ga, seed_steps: 2, refine: 2, refine_moves: 2, ..HybridSettings::default() };
/// let mut hybrid = Hybrid::<Chain>::new(settings, Limits::new(1, 30, 30)?, 7)?;
/// let mut eval = FnEvaluator(|g: &Genome<Chain>| -(g.len() as f64 - 12.0).abs());
/// let result = hybrid.run(&mut eval, &Budget::generations(30), &mut Silent)?;
/// assert_eq!(result.best.len(), 12);
/// // Half of the first population seeded: the axiom's 10 particles, a step of 10, the
/// // last step's 10 with the 10 random genomes; then 28 generations, whose polishing
/// // draws nothing (a chain has no continuous parameter).
/// assert_eq!(result.evaluations, 10 + 10 + (10 + 10) + 28 * (16 + 2 * 2));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Hybrid<G> {
    core: Core<HybridSettings, Best<G>>,
    /// What the GA breeds with every generation.
    breeder: Breeder<G>,
    /// The refinement's operators (the tempered RJMCMC's, keeping to the limits).
    moves: Operators<G>,
    seeding: Option<Smc<G>>,
    chains: refine::Chains<G>,
    polisher: Polisher<G>,
}

impl<G: Grammar> std::fmt::Debug for Hybrid<G> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.core.debug(f, "Hybrid").finish_non_exhaustive()
    }
}

impl<G: Grammar> Hybrid<G> {
    /// One SOSMC step of the part of the population being seeded; the last puts it in
    /// place, beside the random genomes of the rest, drawn and scored then.
    fn seed_step(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        let last = self.last_seed_step();
        let (settings, progress) = (&self.core.settings, &mut self.core.progress);
        let smc = self.seeding.as_mut().expect("seeding");
        smc.step(evaluator)?;
        let (seeding, particles, particle_fitness) = smc.parts();
        seeding.progress.generation += 1;
        progress.evaluations += particles.len() as u64;
        if last {
            let b = &mut self.breeder;
            let k = particles.len();
            b.grow(&settings.ga, progress.seed, 0);
            b.population[..k].clone_from_slice(particles);
            b.scores[..k].copy_from_slice(particle_fitness);
            if k < b.population.len() {
                evaluator.evaluate(&b.population[k..], &mut b.scores[k..])?;
                progress.evaluations += (b.population.len() - k) as u64;
            }
            self.seeding = None;
        }
        Ok(())
    }

    /// Whether the next step is the seeding's last.
    fn last_seed_step(&self) -> bool {
        self.seeding.as_ref().is_some_and(|smc| {
            smc.core().progress.generation + 1 >= u64::from(self.core.settings.seed_steps)
        })
    }

    /// The evaluations of one refinement.
    fn refine_cost(&self) -> u64 {
        let s = &self.core.settings;
        u64::from(s.refine) * u64::from(s.refine_moves)
    }
}

impl<G: Grammar> Optimizer<G> for Hybrid<G> {
    type Settings = HybridSettings;
    type State = HybridState<G>;
    type Record = Best<G>;

    /// The GA's population, its next generation and their copies, and the refined
    /// elites' proposals. While the first population is seeded, the SOSMC holds as many
    /// particles (one per model, with their copies) and the GA's own are still empty, so
    /// the GA's count covers both.
    fn genomes_held(settings: &HybridSettings) -> Vec<Held> {
        vec![
            settings.ga.held(1),
            Held::per("optimizer.refine", settings.refine, 2, 0),
            polish::held(settings.ga.polish),
        ]
    }

    fn new(settings: HybridSettings, limits: Limits, seed: u64) -> Result<Self, OptimizeError> {
        settings.validate()?;
        Ok(Hybrid {
            breeder: Breeder::new(&settings.ga, limits, 1, 1)?,
            moves: Operators::new(limits)?,
            seeding: None,
            chains: refine::Chains::new(settings.refine as usize),
            polisher: Polisher::new(),
            core: Core::new(settings, limits, seed),
        })
    }

    fn core(&self) -> &Core<HybridSettings, Best<G>> {
        &self.core
    }

    /// The core, with the population, or the particles of the population being seeded.
    fn parts(&mut self) -> (&mut Core<HybridSettings, Best<G>>, &[Genome<G>], &[f64]) {
        match &mut self.seeding {
            Some(smc) => {
                let (_, particles, fitness) = smc.parts();
                (&mut self.core, particles, fitness)
            }
            None => self.breeder.parts(&mut self.core),
        }
    }

    /// The population and its fitness, or while it is seeded none and the SOSMC's
    /// checkpoint.
    #[allow(clippy::type_complexity)]
    fn save_body(
        &self,
    ) -> (
        Vec<Genome<G>>,
        Vec<f64>,
        Option<SmcState<G>>,
        Option<PolishState<G>>,
    ) {
        match &self.seeding {
            Some(smc) => (Vec::new(), Vec::new(), Some(smc.checkpoint()), None),
            None => {
                let (population, fitness) = self.breeder.save();
                (population, fitness, None, self.polisher.save())
            }
        }
    }

    fn check_body(state: &HybridState<G>) -> Result<(), OptimizeError> {
        Polisher::check(state.polish.as_ref())?;
        match &state.seeding {
            Some(smc) if smc.progress.record.started() => Smc::<G>::check_body(smc),
            Some(_) => Ok(()),
            None => check_population(&state.settings.ga, &state.population, &state.fitness, None),
        }
    }

    #[allow(clippy::type_complexity)]
    fn restore_body(
        &mut self,
        (population, fitness, seeding, polishing): (
            Vec<Genome<G>>,
            Vec<f64>,
            Option<SmcState<G>>,
            Option<PolishState<G>>,
        ),
    ) -> Result<(), OptimizeError> {
        self.polisher.restore(polishing);
        match seeding {
            // While the first population is seeded, the GA's own is not there yet.
            Some(smc) => self.seeding = Some(Smc::resume(smc)?),
            None => self.breeder.restore((population, fitness)),
        }
        Ok(())
    }

    fn step_cost(&self) -> u64 {
        let settings = &self.core.settings;
        let ga = &settings.ga;
        if self.last_seed_step() {
            u64::from(ga.population)
        } else if self.seeding.is_some() {
            u64::from(settings.seeded())
        } else {
            ga.children() + self.refine_cost() + u64::from(ga.polish)
        }
    }

    fn start(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        let (settings, progress) = (&self.core.settings, &mut self.core.progress);
        if settings.seeded() == 0 {
            self.breeder
                .start(&settings.ga, progress.seed, 0, evaluator)?;
            progress.evaluations += u64::from(settings.ga.population);
            return Ok(());
        }
        let mut smc = Smc::new(
            settings.seeding(),
            self.core.limits,
            derived_seed(progress.seed, 1 << 32),
        )?;
        smc.start(evaluator)?;
        // Marks its progress started, so that a checkpoint keeps its particles.
        smc.record();
        progress.evaluations += u64::from(settings.seeded());
        self.seeding = Some(smc);
        Ok(())
    }

    fn step(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        if self.seeding.is_some() {
            return self.seed_step(evaluator);
        }
        let cost = self.refine_cost();
        let (settings, progress) = (&self.core.settings, &mut self.core.progress);
        let b = &mut self.breeder;
        b.generation(&settings.ga, progress, evaluator)?;
        self.chains.refine(
            refine::Refinement {
                count: settings.refine as usize,
                moves: settings.refine_moves,
                jump_probability: settings.jump_probability,
                ops: &self.moves,
                seed: progress.seed,
                generation: progress.generation + 1,
            },
            evaluator,
            (&mut b.population, &mut b.scores),
        )?;
        progress.evaluations += cost;
        self.polisher.polish(
            (settings.ga.polish, settings.ga.polish_sigma),
            progress,
            evaluator,
            (&mut b.population, &mut b.scores),
        )
    }
}
