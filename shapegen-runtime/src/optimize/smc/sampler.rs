//! [`Smc`]: the particles, their checkpoints, and the run loop both variants share.

use rayon::prelude::*;

use super::settings::{Cursor, SmcSettings, SmcVariant};
use crate::derive::Grammar;
use crate::evaluate::Evaluator;
use crate::genome::{Genome, Limits};
use crate::optimize::best::Best;
use crate::optimize::core::Core;
use crate::optimize::driver::{Held, Optimizer};
use crate::optimize::error::{OptimizeError, check_sizes};
use crate::optimize::fitness::{Roulette, bits_vec};
use crate::optimize::polish::{self, PolishState, Polisher};
use crate::optimize::run::stream;
use crate::optimize::settings::Settings;

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

/// Sequential Monte Carlo (the paper's section 7), SMC or SOSMC by [`Order`](super::Order), in the
/// [`SmcVariant`] its settings name (see there for the rules).
///
/// Each particle's growth draws from the stream (seed, step, particle) and resampling
/// from (seed, step, 2^31 + particle): results never depend on the thread count. Each
/// step costs one evaluation per particle, as does the initial population.
///
/// Polishing (off by default): with [`polish`](SmcSettings::polish), each step ends
/// with a separable CMA-ES ([`SepCmaEs`](crate::optimize::SepCmaEs)) drawing that many candidates
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
    wheel: super::original::Wheel,
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
            super::original::Scratch::default,
            |scratch, (i, g)| {
                let rng = &mut stream(seed, generation, i as u64);
                if from_axiom {
                    g.reset_to_axiom(rng);
                }
                super::original::grow(order, step_back, max_depth, g, scratch, rng);
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
            Held::per("optimizer.particles", settings.particles, 3, 1),
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
            wheel: super::original::Wheel::default(),
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
                    .for_each_init(
                        super::generative::Scratch::default,
                        |s, (i, ((g, c), stuck))| {
                            let rng = &mut stream(seed, generation, i as u64);
                            let grows = super::generative::advance(settings, limits, g, c, s, rng);
                            *stuck = !grows && g.len() < limits.min_len as usize;
                        },
                    );
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
        )
    }
}
