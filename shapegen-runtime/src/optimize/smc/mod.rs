//! Sequential Monte Carlo: particles grown step by step, scored as partial models and
//! resampled by fitness, in chromosome order (SMC) or with stochastic futures (SOSMC),
//! in two variants: the original implementation's ([`SmcVariant::Original`], in
//! `original.rs`) and this project's, which grows as the generator would
//! ([`SmcVariant::Generative`], in `generative.rs`). Both share the settings, the
//! checkpoints and the run loop here.

mod generative;
mod original;

use crate::optimize::settings::generations_field;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::best::Best;
use super::core::Core;
use super::error::{check_range, check_sizes};
use super::fitness::{Roulette, bits_vec};
use super::polish::{self, PolishState, Polisher};
use super::run::stream;
use super::{Evaluator, Held, OptimizeError, Optimizer, Settings, SettingsError};
use crate::derive::Grammar;
use crate::genome::{Genome, Limits};

/// Which unexpressed child a step grows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Order {
    /// SMC. Generative variant: links are decided in chromosome order (genes in buffer
    /// order, links in order); each is expressed with its generator probability or left
    /// empty for good. Original variant: the newest gene that can still take a child,
    /// or with [`step_back_probability`](SmcSettings::step_back_probability) one before
    /// it, and so on.
    Chromosome,
    /// SOSMC: a link among the unexpressed ones (the "stochastic futures") is expressed.
    /// Generative variant: drawn uniformly among those that may grow. Original variant:
    /// a gene drawn among those that can still take a child, then one of its free links.
    Stochastic,
}

/// Which SMC an [`Smc`] runs.
///
/// In scene files and JSON: `"original"` or `"generative"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SmcVariant {
    /// The original implementation's SMC and SOSMC (`SMC.h`, `SOSMC.h`, with the grows of
    /// `SMCOperators.cpp` and `SOSMCOperators.cpp` and their `SMCSelection` and
    /// `SoSmcSelection`, which are the same), reproduced with their oddities.
    ///
    /// A node's *possible children* are its links in link order, each taking at most one
    /// child, as every possible child of the published grammars has `max_num` 1. A gene
    /// *can take a child* when it has an empty link. The original's gene order is
    /// pre-order, each gene's children in the order they were added: it renumbers a
    /// genome so whenever it copies one, and it copies every particle before growing it.
    ///
    /// - Particles start as the axiom and one grow (the original's
    ///   `createRandomGenome(grammar, 2)`), and are evaluated.
    /// - Each step, every particle grows by exactly one gene and is evaluated: one
    ///   evaluation per particle per step. Nothing else happens to a particle that cannot
    ///   grow; it is evaluated all the same.
    /// - A grow in chromosome order ([`Order::Chromosome`], `SMCGrowMutation`) lists the
    ///   genes that can take a child and lie above level `max_depth` (the root is level
    ///   0, so the original's trees reach level `max_depth`, one deeper than
    ///   [`Limits::max_depth`] allows elsewhere, the root counting as depth 1), in gene
    ///   order, starts from the last one and steps back one gene at a time with
    ///   probability [`step_back_probability`](SmcSettings::step_back_probability) (the
    ///   original's `basic_prob`, 0 in all published configurations: always the last),
    ///   never past the first.
    /// - A grow with stochastic futures ([`Order::Stochastic`], `SoSmcGrowMutation`)
    ///   draws among all genes that can take a child, with no depth bound.
    /// - Either then draws one of the gene's empty links uniformly, ignoring the
    ///   generator's probabilities (the original's "TODO: pay attention to percentage
    ///   values"), and appends a child there with parameters drawn from their
    ///   distributions.
    /// - From the second step on, before growing, the particles are resampled from the
    ///   previous step's grown particles: ranked best first, each of the `n` new
    ///   particles is drawn by its own `U` in `[0, 1)` as the first particle in rank
    ///   order whose cumulative relative fitness `sum_{j <= k} (f_j + offset) / S`
    ///   reaches `U`, or the last one if none does, where `offset = -f_worst` when the
    ///   worst fitness is not negative and 0 otherwise, and `S = sum_j (f_j + offset)`;
    ///   the new particles are ordered best first. The first step grows the initial
    ///   particles themselves. (The original resamples at the end of each step instead,
    ///   the last one included; the particles evaluated are the same, and checkpoints
    ///   hold them as grown and scored.)
    ///
    /// Oddities of the original, reproduced:
    /// - its integer draw `getRandomValue(0, n - 1)` truncates `(n - 1) U`, so the last of
    ///   `n >= 2` candidates is never taken: the stochastic grow never grows from the last
    ///   gene in gene order, and neither order takes a gene's last empty link unless it is
    ///   the only one;
    /// - the offset is the opposite of what its comment says: a non-negative worst is
    ///   lifted to 0 (the worst then weighs nothing), a negative one is left as it is, so
    ///   negative fitness weighs negatively. The cumulative values then rise above 1 and
    ///   come back, and the weaker particles whose range lies past 1 are never drawn;
    ///   when `S` is negative the wheel turns around and only the worst particles are
    ///   drawn; when all particles have the same non-negative fitness every relative
    ///   value is `0 / 0`, no draw reaches one, and all new particles are copies of the
    ///   last one in rank order;
    /// - nothing bounds a genome's length: particles grow past [`Limits::max_len`] (one
    ///   gene per step), and [`Limits::min_len`] is not enforced (the limits this
    ///   variant keeps, [`Settings::kept_limits`], bound neither length nor depth).
    ///
    /// As the original, the resampling works in `f32` (fitness values are converted);
    /// ties in rank keep their index order (the original's sort leaves it unspecified).
    /// Beyond the original: only finite fitness values enter the wheel: NaN and `-inf`
    /// particles are drawn only when every particle is NaN or `-inf` (then the last in
    /// rank order is), and if some particles are at `+inf` the draws are uniform among
    /// them. Genomes stay within [`DEPTH_CAP`](crate::genome::DEPTH_CAP): no gene at that
    /// depth takes a child. Not reproduced: the original redraws the axiom's parameters
    /// whenever it copies a genome (none of the published grammars' axioms has any).
    Original,
    /// This project's SMC: particles grow as the generator would, from the axiom, each
    /// step until the model shows new geometry.
    ///
    /// Particles start as the axiom alone. A step first resamples the particles
    /// multinomially by fitness (roulette weights as the GA's: `f - f_min`, NaN weighs
    /// 0), then grows every particle until its model emits more instances than before
    /// (the whole model is derived after each added gene to see it), at most
    /// [`max_grows_per_step`](SmcSettings::max_grows_per_step) genes, or until nothing
    /// can grow (a finished particle stays as it is), and scores all of them as partial
    /// models. A grow in chromosome order decides the links in chromosome order, each
    /// expressed with its generator probability; one with stochastic futures expresses a
    /// link drawn uniformly among the empty ones of genes above the maximum depth with a
    /// non-zero probability. Genomes stay within [`Limits::max_len`] and
    /// [`Limits::max_depth`]; particles may be shorter than [`Limits::min_len`] while
    /// they grow, and one that can grow no more while shorter gets a NaN fitness, so
    /// that it is never drawn again.
    Generative,
}

impl SmcVariant {
    /// Every variant.
    pub const ALL: [SmcVariant; 2] = [SmcVariant::Original, SmcVariant::Generative];

    /// Its name in scene files and settings.
    pub const fn name(self) -> &'static str {
        match self {
            SmcVariant::Original => "original",
            SmcVariant::Generative => "generative",
        }
    }
}

/// Settings of [`Smc`]. Loads from scene files with serde; missing fields take the
/// [`Default`] values, unknown fields are errors.
///
/// The default is the [generative](SmcVariant::Generative) variant with the spaceship
/// scene's sizes; the published generators carry the original's configuration files with
/// the [original](SmcVariant::Original) variant (`generators::spaceship::paper_smc`, ...).
///
/// ```
/// use shapegen_runtime::optimize::{Order, SmcSettings, SmcVariant};
///
/// let s: SmcSettings = serde_json::from_str(r#"{"variant": "original", "particles": 50}"#)?;
/// assert_eq!((s.variant, s.particles), (SmcVariant::Original, 50));
/// assert_eq!(SmcSettings::default().variant, SmcVariant::Generative);
/// # Ok::<(), serde_json::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SmcSettings {
    /// Number of particles; at least 1.
    pub particles: u32,
    /// Steps, the default generation budget.
    pub steps: u64,
    /// SMC or SOSMC.
    pub order: Order,
    /// Which SMC runs.
    pub variant: SmcVariant,
    /// Original variant only, chromosome order: the chance that a grow steps back from a
    /// gene to the one before it; in `[0, 1]`.
    pub step_back_probability: f64,
    /// Generative variant only: most genes a step adds while waiting for new geometry;
    /// at least 1.
    pub max_grows_per_step: u32,
    /// Candidates a separable CMA-ES draws each step to tune the continuous parameters
    /// of the best particle (see [`Smc`]); 0, the default, polishes nothing, otherwise at
    /// least 2.
    pub polish: u32,
    /// The step size a new polishing strategy starts with, as a share of each
    /// parameter's range; in `(0, 1]`.
    pub polish_sigma: f64,
}

impl Default for SmcSettings {
    fn default() -> Self {
        SmcSettings {
            particles: 500,
            steps: 40,
            order: Order::Chromosome,
            variant: SmcVariant::Generative,
            step_back_probability: 0.0,
            max_grows_per_step: 64,
            polish: 0,
            polish_sigma: 0.1,
        }
    }
}

impl Settings for SmcSettings {
    generations_field!("steps", steps);

    /// The original's particles grow one gene a step from the axiom, bounded by neither
    /// length nor depth; the generative variant's keep the given limits but may be
    /// shorter than `min_len` while they grow.
    fn kept_limits(&self, limits: Limits) -> Limits {
        match self.variant {
            SmcVariant::Original => limits.without_length().without_depth(),
            SmcVariant::Generative => limits.without_min_len(),
        }
    }

    /// Checks every field the variant reads; the error names the first one out of range.
    fn validate(&self) -> Result<(), SettingsError> {
        if self.particles == 0 {
            return Err(SettingsError::new("particles", 0, "at least 1"));
        }
        match self.variant {
            SmcVariant::Original => check_range(
                "step_back_probability",
                self.step_back_probability,
                0.0,
                1.0,
                "between 0 and 1",
            )?,
            SmcVariant::Generative => {
                if self.max_grows_per_step == 0 {
                    return Err(SettingsError::new("max_grows_per_step", 0, "at least 1"));
                }
            }
        }
        polish::check_settings(self.polish, self.polish_sigma)
    }
}

/// One particle's growth bookkeeping in the [generative](SmcVariant::Generative) variant.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Cursor {
    /// Chromosome order: word position of the gene whose links are being decided.
    pub pos: u32,
    /// Chromosome order: the next link of that gene to decide.
    pub link: u32,
    /// Instances the particle's model emitted when last derived.
    pub emitted: u32,
}

crate::checkpoint! {
    /// A checkpoint of an [`Smc`], resumed by [`Smc::resume`].
    pub struct SmcState<G>: SmcSettings, Best<G> {
        /// The particles as last grown and evaluated.
        pub particles: Vec<Genome<G>>,
        /// Their growth bookkeeping: one per particle in the generative variant, none in
        /// the original one.
        pub cursors: Vec<Cursor>,
        /// Their fitness.
        #[serde(with = "bits_vec")]
        pub fitness: Vec<f64>,
        /// The polishing under way, if any.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub polish: Option<PolishState<G>>,
    }
}

/// Sequential Monte Carlo (the paper's section 7), SMC or SOSMC by [`Order`], in the
/// [`SmcVariant`] its settings name (see there for the rules).
///
/// Each particle's growth draws from the stream (seed, step, particle) and resampling
/// from (seed, step, 2^31 + particle): results never depend on the thread count. Each
/// step costs one evaluation per particle, as does the initial population.
///
/// Polishing (off by default): with [`polish`](SmcSettings::polish), each step ends
/// with a separable CMA-ES ([`SepCmaEs`](super::SepCmaEs)) drawing that many candidates
/// over the continuous parameters of the best particle, its structure kept; the best
/// candidate replaces it when it scores at least as well, before the next resampling.
/// It draws from (seed, step, 3 * 2^30) and costs `polish` evaluations a step while the
/// best particle has a continuous parameter.
///
/// ```
/// use shapegen_runtime::optimize::{
///     Budget, FnEvaluator, Optimizer, Order, Silent, Smc, SmcSettings,
/// };
/// use shapegen_runtime::prelude::*;
///
/// generator! {
///     /// A chain of blocks.
///     pub Chain {
///         axiom Seg;
///         node Seg {
///             children { next: Seg = 0.7 }
///             derive(s) {
///                 s.emit(CUBE);
///                 if let Some(next) = next { s.translate(vec3(0.0, 1.0, 0.0)).derive(next); }
///             }
///         }
///     }
/// }
///
/// let settings = SmcSettings { particles: 20, ..SmcSettings::default() };
/// let mut smc = Smc::<Chain>::new(settings, Limits::new(1, 30, 30)?, 1)?;
/// let mut eval = FnEvaluator(|g: &Genome<Chain>| g.len().min(6) as f64);
/// let result = smc.run(&mut eval, &Budget::generations(10), &mut Silent)?;
/// assert_eq!(result.best_fitness, 6.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Smc<G> {
    core: Core<SmcSettings, Best<G>>,
    particles: Vec<Genome<G>>,
    cursors: Vec<Cursor>,
    fitness: Vec<f64>,
    next: Vec<Genome<G>>,
    next_cursors: Vec<Cursor>,
    roulette: Roulette,
    wheel: original::Wheel,
    picks: Vec<usize>,
    /// Which particles of the generative variant's last step can grow no more while
    /// shorter than the limits' `min_len`.
    stuck: Vec<bool>,
    polisher: Polisher<G>,
}

impl<G: Grammar> std::fmt::Debug for Smc<G> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.core.debug(f, "Smc").finish_non_exhaustive()
    }
}

impl<G: Grammar> Smc<G> {
    /// How many cursors the variant keeps.
    fn cursors(settings: &SmcSettings) -> usize {
        match settings.variant {
            SmcVariant::Original => 0,
            SmcVariant::Generative => settings.particles as usize,
        }
    }

    /// Grows every particle once as the original does, particle `i` from the stream
    /// (seed, `generation`, `i`), first replacing it by the axiom if `from_axiom`.
    fn grow_original(&mut self, generation: u64, from_axiom: bool) {
        let seed = self.core.progress.seed;
        let s = &self.core.settings;
        let (order, max_depth) = (s.order, self.core.limits.max_depth);
        let step_back = (100.0 * s.step_back_probability) as f32;
        self.particles.par_iter_mut().enumerate().for_each_init(
            original::Scratch::default,
            |scratch, (i, g)| {
                let rng = &mut stream(seed, generation, i as u64);
                if from_axiom {
                    g.reset_to_axiom(rng);
                }
                original::grow(order, step_back, max_depth, g, scratch, rng);
            },
        );
    }

    /// Resamples the particles as the original does, draw `j` from the stream (seed,
    /// `generation`, 2^31 + `j`), best first.
    fn resample_original(&mut self, generation: u64) {
        let seed = self.core.progress.seed;
        self.wheel.build(&self.fitness);
        let wheel = &self.wheel;
        self.picks.clear();
        self.picks.extend(
            (0..self.particles.len())
                .map(|j| wheel.spin(&mut stream(seed, generation, (1 << 31) + j as u64))),
        );
        self.picks.sort_unstable();
        for (g, &k) in self.next.iter_mut().zip(&self.picks) {
            g.clone_from(&self.particles[wheel.particle(k)]);
        }
        std::mem::swap(&mut self.particles, &mut self.next);
    }
}

impl<G: Grammar> Optimizer<G> for Smc<G> {
    type Settings = SmcSettings;
    type State = SmcState<G>;
    type Record = Best<G>;

    /// The particles, the next generation resampled beside them, and the checkpoint's
    /// copy; polishing's candidates and origin.
    fn genomes_held(settings: &SmcSettings) -> Vec<Held> {
        vec![
            Held {
                genomes: 3 * u64::from(settings.particles),
                saved: settings.particles.into(),
                setting: "optimizer.particles",
                value: settings.particles.into(),
            },
            polish::held(settings.polish),
        ]
    }

    /// An SMC run with these settings and limits, seeded with `seed`.
    fn new(settings: SmcSettings, limits: Limits, seed: u64) -> Result<Self, OptimizeError> {
        settings.validate()?;
        limits.check()?;
        let n = settings.particles as usize;
        let empty = || Genome::from_parts(Vec::new(), 0);
        let cursors = Smc::<G>::cursors(&settings);
        Ok(Smc {
            core: Core::new(settings, limits, seed),
            particles: (0..n).map(|_| empty()).collect(),
            cursors: vec![Cursor::default(); cursors],
            fitness: vec![f64::NAN; n],
            next: (0..n).map(|_| empty()).collect(),
            next_cursors: vec![Cursor::default(); cursors],
            roulette: Roulette::default(),
            wheel: original::Wheel::default(),
            picks: Vec::new(),
            stuck: vec![false; cursors],
            polisher: Polisher::new(),
        })
    }

    fn core(&self) -> &Core<SmcSettings, Best<G>> {
        &self.core
    }

    fn parts(&mut self) -> (&mut Core<SmcSettings, Best<G>>, &[Genome<G>], &[f64]) {
        (&mut self.core, &self.particles, &self.fitness)
    }

    #[allow(clippy::type_complexity)]
    fn save_body(
        &self,
    ) -> (
        Vec<Genome<G>>,
        Vec<Cursor>,
        Vec<f64>,
        Option<PolishState<G>>,
    ) {
        (
            self.particles.clone(),
            self.cursors.clone(),
            self.fitness.clone(),
            self.polisher.save(),
        )
    }

    /// Counts the particles first, then, as many as the settings', their cursors and
    /// fitness values.
    fn check_body(state: &SmcState<G>) -> Result<(), OptimizeError> {
        Polisher::check(state.polish.as_ref())?;
        let s = &state.settings;
        let (n, cursors) = (s.particles as usize, Smc::<G>::cursors(s));
        let particles = (state.particles.len(), n, "particles");
        check_sizes(&[particles], format_args!("{n} particles"))?;
        check_sizes(
            &[
                particles,
                (state.cursors.len(), cursors, "cursors"),
                (state.fitness.len(), n, "fitness values"),
            ],
            format_args!("{n} particles of the {} variant", s.variant.name()),
        )
    }

    fn restore_body(
        &mut self,
        (particles, cursors, fitness, polish): (
            Vec<Genome<G>>,
            Vec<Cursor>,
            Vec<f64>,
            Option<PolishState<G>>,
        ),
    ) -> Result<(), OptimizeError> {
        self.particles = particles;
        self.cursors = cursors;
        self.fitness = fitness;
        self.polisher.restore(polish);
        Ok(())
    }

    fn step_cost(&self) -> u64 {
        u64::from(self.core.settings.particles) + u64::from(self.core.settings.polish)
    }

    fn start(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        match self.core.settings.variant {
            SmcVariant::Original => self.grow_original(0, true),
            SmcVariant::Generative => {
                let seed = self.core.progress.seed;
                let mut instances = Vec::new();
                for (i, (g, c)) in self.particles.iter_mut().zip(&mut self.cursors).enumerate() {
                    g.reset_to_axiom(&mut stream(seed, 0, i as u64));
                    g.derive_into(&mut instances);
                    *c = Cursor {
                        emitted: instances.len() as u32,
                        ..Cursor::default()
                    };
                }
            }
        }
        evaluator.evaluate(&self.particles, &mut self.fitness)?;
        self.core.progress.evaluations += u64::from(self.core.settings.particles);
        Ok(())
    }

    fn step(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        let (seed, generation) = (self.core.progress.seed, self.core.progress.generation + 1);
        match self.core.settings.variant {
            SmcVariant::Original => {
                if generation > 1 {
                    self.resample_original(generation);
                }
                self.grow_original(generation, false);
            }
            SmcVariant::Generative => {
                self.roulette.build(&self.fitness);
                for (i, (g, c)) in self.next.iter_mut().zip(&mut self.next_cursors).enumerate() {
                    let from =
                        self.roulette
                            .spin(&mut stream(seed, generation, (1 << 31) + i as u64));
                    g.clone_from(&self.particles[from]);
                    *c = self.cursors[from];
                }
                std::mem::swap(&mut self.particles, &mut self.next);
                std::mem::swap(&mut self.cursors, &mut self.next_cursors);
                let (settings, limits) = (&self.core.settings, &self.core.limits);
                self.particles
                    .par_iter_mut()
                    .zip(self.cursors.par_iter_mut())
                    .zip(self.stuck.par_iter_mut())
                    .enumerate()
                    .for_each_init(generative::Scratch::default, |s, (i, ((g, c), stuck))| {
                        let rng = &mut stream(seed, generation, i as u64);
                        let grows = generative::advance(settings, limits, g, c, s, rng);
                        *stuck = !grows && g.len() < limits.min_len as usize;
                    });
            }
        }
        evaluator.evaluate(&self.particles, &mut self.fitness)?;
        // A generative particle that can grow no more while shorter than `min_len` is
        // never drawn again (the original variant leaves `stuck` empty).
        for (f, &stuck) in self.fitness.iter_mut().zip(&self.stuck) {
            if stuck {
                *f = f64::NAN;
            }
        }
        let (settings, progress) = (&self.core.settings, &mut self.core.progress);
        progress.evaluations += u64::from(settings.particles);
        self.polisher.polish(
            (settings.polish, settings.polish_sigma),
            progress,
            evaluator,
            (&mut self.particles, &mut self.fitness),
        )?;
        Ok(())
    }
}
