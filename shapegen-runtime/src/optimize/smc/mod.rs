//! Sequential Monte Carlo: particles grown step by step from the axiom, scored as partial
//! models and resampled by fitness, in chromosome order (SMC) or with stochastic futures
//! (SOSMC).

use rand::{Rng, RngExt};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::fitness::{Roulette, bits_vec};
use super::grow::{depth_of, expand, link_facts, open_links};
use super::run::{Method, Progress, drive, grammar_struct_traits, stream};
use super::{Budget, Evaluator, Observer, OptimizeError, RunResult, SettingsError};
use crate::derive::Grammar;
use crate::genome::{Genome, Limits, node_of};
use crate::geometry::Instance;
use crate::graph::HEADER_WORDS;

/// Which unexpressed child a step grows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Order {
    /// SMC: links are decided in chromosome order (genes in buffer order, links in
    /// order); each is expressed with its generator probability or left empty for good.
    Chromosome,
    /// SOSMC: a link drawn uniformly among all the unexpressed ones that may grow (the
    /// "stochastic futures") is expressed.
    Stochastic,
}

/// Settings of [`Smc`]. Loads from scene files with serde; missing fields take the
/// [`Default`] values (the paper's spaceship SMC), unknown fields are errors.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SmcSettings {
    /// Number of particles; at least 1.
    pub particles: u32,
    /// Steps, the default generation budget.
    pub steps: u64,
    /// SMC or SOSMC.
    pub order: Order,
    /// Most genes a step adds while waiting for new geometry; at least 1.
    pub max_grows_per_step: u32,
}

impl Default for SmcSettings {
    fn default() -> Self {
        SmcSettings::paper_spaceship(Order::Chromosome)
    }
}

impl SmcSettings {
    /// The paper's spaceship scene: 500 particles, 40 steps.
    pub fn paper_spaceship(order: Order) -> Self {
        SmcSettings {
            particles: 500,
            steps: 40,
            order,
            max_grows_per_step: 64,
        }
    }

    /// The paper's tree-sketch scene: 1000 particles, 500 steps.
    pub fn paper_tree(order: Order) -> Self {
        SmcSettings {
            particles: 1000,
            steps: 500,
            ..SmcSettings::paper_spaceship(order)
        }
    }

    /// The paper's city-whale scene: 100 particles, 100 steps.
    pub fn paper_city(order: Order) -> Self {
        SmcSettings {
            particles: 100,
            steps: 100,
            ..SmcSettings::paper_spaceship(order)
        }
    }

    /// Checks every field; the error names the first one out of range.
    pub fn validate(&self) -> Result<(), SettingsError> {
        if self.particles == 0 {
            return Err(SettingsError::new("particles", 0, "at least 1"));
        }
        if self.max_grows_per_step == 0 {
            return Err(SettingsError::new("max_grows_per_step", 0, "at least 1"));
        }
        Ok(())
    }

    /// A budget of [`steps`](Self::steps) generations.
    pub fn budget(&self) -> Budget {
        Budget::generations(self.steps)
    }
}

/// One particle's growth bookkeeping.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Cursor {
    /// Chromosome order: word position of the gene whose links are being decided.
    pub pos: u32,
    /// Chromosome order: the next link of that gene to decide.
    pub link: u32,
    /// Instances the particle's model emitted when last derived.
    pub emitted: u32,
}

/// A checkpoint of an [`Smc`], resumed by [`Smc::resume`].
#[derive(Serialize, Deserialize)]
#[serde(
    deny_unknown_fields,
    bound(serialize = "G: Grammar", deserialize = "G: Grammar")
)]
pub struct SmcState<G> {
    /// The settings.
    pub settings: SmcSettings,
    /// The genome limits.
    pub limits: Limits,
    /// Generation, evaluations, best so far, history.
    pub progress: Progress<G>,
    /// The particles.
    pub particles: Vec<Genome<G>>,
    /// Their growth bookkeeping.
    pub cursors: Vec<Cursor>,
    /// Their fitness.
    #[serde(with = "bits_vec")]
    pub fitness: Vec<f64>,
}

grammar_struct_traits!(SmcState {
    settings,
    limits,
    progress,
    particles,
    cursors,
    fitness
});

/// Sequential Monte Carlo (ALGORITHMS.md, section 5), SMC or SOSMC by [`Order`].
///
/// Particles start as the axiom alone. A step first resamples the particles
/// multinomially by fitness (roulette weights as the GA's: `f - f_min`, NaN weighs 0),
/// then grows every particle until its model emits more instances than before (the
/// whole model is derived after each added gene to see it), at most
/// `max_grows_per_step` genes, or until nothing can grow (a finished particle stays as
/// it is), and scores all of them as partial models. Particles may be shorter than the
/// limits' minimum length while they grow.
///
/// Each particle's growth draws from the stream (seed, step, particle) and resampling
/// from (seed, step, 2^31 + particle): results never depend on the thread count.
///
/// ```
/// use shapegen_runtime::optimize::{Budget, FnEvaluator, Order, Silent, Smc, SmcSettings};
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
/// let settings = SmcSettings { particles: 20, ..SmcSettings::paper_city(Order::Stochastic) };
/// let mut smc = Smc::<Chain>::new(settings, Limits::new(1, 30, 30)?, 1)?;
/// let mut eval = FnEvaluator(|g: &Genome<Chain>| g.len().min(6) as f64);
/// let result = smc.run(&mut eval, &Budget::generations(10), &mut Silent)?;
/// assert_eq!(result.best_fitness, 6.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Smc<G> {
    settings: SmcSettings,
    limits: Limits,
    progress: Progress<G>,
    particles: Vec<Genome<G>>,
    cursors: Vec<Cursor>,
    fitness: Vec<f64>,
    next: Vec<Genome<G>>,
    next_cursors: Vec<Cursor>,
    roulette: Roulette,
}

impl<G: Grammar> std::fmt::Debug for Smc<G> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Smc")
            .field("settings", &self.settings)
            .field("progress", &self.progress)
            .finish_non_exhaustive()
    }
}

impl<G: Grammar> Smc<G> {
    /// An SMC run with these settings and limits, seeded with `seed`.
    pub fn new(settings: SmcSettings, limits: Limits, seed: u64) -> Result<Self, OptimizeError> {
        settings.validate()?;
        limits.check()?;
        let n = settings.particles as usize;
        let empty = || Genome::from_parts(Vec::new(), 0);
        Ok(Smc {
            settings,
            limits,
            progress: Progress::new(seed),
            particles: (0..n).map(|_| empty()).collect(),
            cursors: vec![Cursor::default(); n],
            fitness: vec![f64::NAN; n],
            next: (0..n).map(|_| empty()).collect(),
            next_cursors: vec![Cursor::default(); n],
            roulette: Roulette::default(),
        })
    }

    /// Resumes from a checkpoint; fails if it does not fit its own settings.
    pub fn resume(state: SmcState<G>) -> Result<Self, OptimizeError> {
        let mut smc = Smc::new(state.settings, state.limits, state.progress.seed)?;
        let n = state.settings.particles as usize;
        if !state.progress.history.is_empty() {
            if [
                state.particles.len(),
                state.cursors.len(),
                state.fitness.len(),
            ] != [n; 3]
            {
                return Err(OptimizeError::Checkpoint(format!(
                    "{} particles, {} cursors and {} fitness values for {n} particles",
                    state.particles.len(),
                    state.cursors.len(),
                    state.fitness.len()
                )));
            }
            smc.particles = state.particles;
            smc.cursors = state.cursors;
            smc.fitness = state.fitness;
        }
        smc.progress = state.progress;
        Ok(smc)
    }

    /// The state to resume from.
    pub fn checkpoint(&self) -> SmcState<G> {
        SmcState {
            settings: self.settings,
            limits: self.limits,
            progress: self.progress.clone(),
            particles: self.particles.clone(),
            cursors: self.cursors.clone(),
            fitness: self.fitness.clone(),
        }
    }

    /// Runs until `budget` or `observer` stops it; a later call goes on from there.
    pub fn run(
        &mut self,
        evaluator: &mut impl Evaluator<G>,
        budget: &Budget,
        observer: &mut impl Observer<G>,
    ) -> Result<RunResult<G>, OptimizeError> {
        drive(self, evaluator, budget, observer)
    }
}

/// Per-thread scratch of a step.
#[derive(Default)]
struct Scratch {
    instances: Vec<Instance>,
    depth: Vec<u32>,
    open: Vec<(u32, u32)>,
}

impl<G: Grammar> Method<G> for Smc<G> {
    fn step_cost(&self) -> u64 {
        u64::from(self.settings.particles)
    }

    fn start<E: Evaluator<G>>(&mut self, evaluator: &mut E) -> Result<(), OptimizeError> {
        let seed = self.progress.seed;
        let mut instances = Vec::new();
        for (i, (g, c)) in self.particles.iter_mut().zip(&mut self.cursors).enumerate() {
            g.reset_to_axiom(&mut stream(seed, 0, i as u64));
            g.derive_into(&mut instances);
            *c = Cursor {
                emitted: instances.len() as u32,
                ..Cursor::default()
            };
        }
        evaluator.evaluate(&self.particles, &mut self.fitness)?;
        self.progress.evaluations += self.step_cost();
        Ok(())
    }

    fn step<E: Evaluator<G>>(&mut self, evaluator: &mut E) -> Result<(), OptimizeError> {
        let (seed, generation) = (self.progress.seed, self.progress.generation + 1);
        self.roulette.build(&self.fitness);
        for (i, (g, c)) in self.next.iter_mut().zip(&mut self.next_cursors).enumerate() {
            let from = self
                .roulette
                .spin(&mut stream(seed, generation, (1 << 31) + i as u64));
            g.clone_from(&self.particles[from]);
            *c = self.cursors[from];
        }
        std::mem::swap(&mut self.particles, &mut self.next);
        std::mem::swap(&mut self.cursors, &mut self.next_cursors);
        let (settings, limits) = (&self.settings, &self.limits);
        self.particles
            .par_iter_mut()
            .zip(self.cursors.par_iter_mut())
            .enumerate()
            .for_each_init(Scratch::default, |s, (i, (g, c))| {
                let rng = &mut stream(seed, generation, i as u64);
                advance(settings, limits, g, c, s, rng);
            });
        evaluator.evaluate(&self.particles, &mut self.fitness)?;
        self.progress.evaluations += self.step_cost();
        Ok(())
    }

    fn parts(&mut self) -> (&mut Progress<G>, &[Genome<G>], &[f64]) {
        (&mut self.progress, &self.particles, &self.fitness)
    }
}

/// Grows one particle until it emits new geometry, `max_grows_per_step` genes were
/// added, or nothing can grow.
fn advance<G: Grammar>(
    settings: &SmcSettings,
    limits: &Limits,
    g: &mut Genome<G>,
    c: &mut Cursor,
    s: &mut Scratch,
    rng: &mut impl Rng,
) {
    for _ in 0..settings.max_grows_per_step {
        let grown = match settings.order {
            Order::Chromosome => next_in_order(limits, g, c, rng),
            Order::Stochastic => {
                open_links(g, limits, &mut s.depth, &mut s.open);
                if s.open.is_empty() {
                    false
                } else {
                    let (pos, link) = s.open[rng.random_range(0..s.open.len())];
                    expand(g, limits, pos, link, rng).is_some()
                }
            }
        };
        if !grown {
            return;
        }
        g.derive_into(&mut s.instances);
        let emitted = s.instances.len() as u32;
        if emitted > c.emitted {
            c.emitted = emitted;
            return;
        }
        c.emitted = emitted;
    }
}

/// Decides links in chromosome order from the cursor until one is expressed; returns
/// `false` when every link has been decided or the genome is at its maximum length.
fn next_in_order<G: Grammar>(
    limits: &Limits,
    g: &mut Genome<G>,
    c: &mut Cursor,
    rng: &mut impl Rng,
) -> bool {
    while (c.pos as usize) < g.words().len() {
        let kind = g.words()[c.pos as usize];
        let node = node_of::<G>(kind);
        if c.link >= node.links || depth_of(g.words(), c.pos) >= limits.max_depth {
            c.pos += node.gene_words();
            c.link = 0;
            continue;
        }
        let link = c.link;
        c.link += 1;
        if g.words()[(c.pos + HEADER_WORDS + link) as usize] != 0 {
            continue;
        }
        if rng.random::<f32>() < link_facts::<G>(kind, link).0 {
            return expand(g, limits, c.pos, link, rng).is_some();
        }
    }
    false
}
