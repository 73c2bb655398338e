//! Reversible-jump MCMC (Metropolis procedural modeling, Talton et al. 2011) with
//! parallel tempering, annealing and delayed rejection.

use rand::{Rng, RngExt};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::error::check_range;
use super::fitness::{bits_vec, mean_std};
use super::grow::{jump_links, sample_subtree};
use super::run::{Method, Progress, drive, grammar_struct_traits, stream};
use super::{Budget, Evaluator, Observer, OptimizeError, RunResult, SettingsError};
use crate::derive::Grammar;
use crate::genome::{Genome, Limits, node_of};
use crate::graph::HEADER_WORDS;
use crate::ops::Operators;

/// Settings of [`Mcmc`]. Loads from scene files with serde; missing fields take the
/// [`Default`] values (the paper's spaceship scene), unknown fields are errors.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct McmcSettings {
    /// Number of chains; at least 1.
    pub chains: u32,
    /// Iterations (one move per chain each), the default generation budget.
    pub iterations: u64,
    /// Chains start from random genomes grown to about this length, as the GA's initial
    /// population; at least 1.
    pub initial_length: u32,
    /// Chance that a move is a jump rather than a diffusion; in `[0, 1]`.
    pub jump_probability: f64,
    /// Extra alter steps tried on a rejected jump before giving it up; at most 16.
    pub delayed_rejection: u32,
    /// Every `anneal_interval` iterations all temperatures are divided by this; at least
    /// 1 (1: no annealing), finite.
    pub anneal_factor: f64,
    /// Iterations between annealing steps; at least 1.
    pub anneal_interval: u64,
    /// Acceptance chance, in the hottest chain, of a move losing one initial standard
    /// deviation of fitness; in `(0, 1)`.
    pub hot_acceptance: f64,
    /// Acceptance chance of the same move in the coldest chain; in `(0, hot_acceptance)`.
    pub cold_acceptance: f64,
}

impl Default for McmcSettings {
    fn default() -> Self {
        McmcSettings::paper_spaceship()
    }
}

impl McmcSettings {
    /// The paper's spaceship scene: 70 chains, 250 iterations.
    pub fn paper_spaceship() -> Self {
        McmcSettings {
            chains: 70,
            iterations: 250,
            initial_length: 50,
            jump_probability: 0.5,
            delayed_rejection: 1,
            anneal_factor: 1.1,
            anneal_interval: 10,
            hot_acceptance: 0.7,
            cold_acceptance: 0.01,
        }
    }

    /// The paper's tree-sketch scene: 100 chains, 3000 iterations, initial length 250.
    pub fn paper_tree() -> Self {
        McmcSettings {
            chains: 100,
            iterations: 3000,
            initial_length: 250,
            ..McmcSettings::paper_spaceship()
        }
    }

    /// The paper's city-whale scene: 50 chains, 200 iterations, jump and diffusion
    /// 50 / 50.
    pub fn paper_city() -> Self {
        McmcSettings {
            chains: 50,
            iterations: 200,
            ..McmcSettings::paper_spaceship()
        }
    }

    /// Checks every field; the error names the first one out of range.
    pub fn validate(&self) -> Result<(), SettingsError> {
        if self.chains == 0 {
            return Err(SettingsError::new("chains", 0, "at least 1"));
        }
        if self.initial_length == 0 {
            return Err(SettingsError::new("initial_length", 0, "at least 1"));
        }
        check_range(
            "jump_probability",
            self.jump_probability,
            0.0,
            1.0,
            "between 0 and 1",
        )?;
        if self.delayed_rejection > 16 {
            return Err(SettingsError::new(
                "delayed_rejection",
                self.delayed_rejection,
                "at most 16",
            ));
        }
        check_range(
            "anneal_factor",
            self.anneal_factor,
            1.0,
            f64::MAX,
            "at least 1 and finite",
        )?;
        if self.anneal_interval == 0 {
            return Err(SettingsError::new("anneal_interval", 0, "at least 1"));
        }
        let open = "strictly between 0 and 1";
        if !(self.hot_acceptance > 0.0 && self.hot_acceptance < 1.0) {
            return Err(SettingsError::new(
                "hot_acceptance",
                self.hot_acceptance,
                open,
            ));
        }
        if !(self.cold_acceptance > 0.0 && self.cold_acceptance < self.hot_acceptance) {
            return Err(SettingsError::new(
                "cold_acceptance",
                self.cold_acceptance,
                "above 0 and below hot_acceptance",
            ));
        }
        Ok(())
    }

    /// A budget of [`iterations`](Self::iterations) generations.
    pub fn budget(&self) -> Budget {
        Budget::generations(self.iterations)
    }
}

/// A checkpoint of an [`Mcmc`], resumed by [`Mcmc::resume`].
#[derive(Serialize, Deserialize)]
#[serde(
    deny_unknown_fields,
    bound(serialize = "G: Grammar", deserialize = "G: Grammar")
)]
pub struct McmcState<G> {
    /// The settings.
    pub settings: McmcSettings,
    /// The genome limits.
    pub limits: Limits,
    /// Generation, evaluations, best so far, history.
    pub progress: Progress<G>,
    /// The chains' current states, coldest first.
    pub chains: Vec<Genome<G>>,
    /// Their fitness.
    #[serde(with = "bits_vec")]
    pub fitness: Vec<f64>,
    /// The chains' temperatures, ascending.
    #[serde(with = "bits_vec")]
    pub temperatures: Vec<f64>,
}

grammar_struct_traits!(McmcState {
    settings,
    limits,
    progress,
    chains,
    fitness,
    temperatures
});

/// Reversible-jump MCMC over derivation trees (ALGORITHMS.md, section 5).
///
/// Each chain samples the density `prior(x) * exp(f(x) / T)`, the prior being the
/// grammar's own distribution, so that moves drawing from the prior need only the
/// fitness in their acceptance:
/// - *diffusion*: alter one gene (resample its parameters from their distributions);
///   accepted with `min(1, exp((f' - f) / T))`;
/// - *jump*: pick a link uniformly among the links a jump may redraw (non-terminal
///   selection: only genes with children, above the maximum depth), cut the subtree
///   below it and redraw it from the grammar, keeping the old subtree root's parameter
///   values if the link is expressed again (the random values reused); accepted with
///   `min(1, exp((f' - f) / T) * n / n')`, `n` and `n'` the numbers of selectable links
///   before and after (the proposal ratio of uniform link selection). Limits truncate
///   redrawn subtrees, which the ratio ignores. A jump whose cut would go below the
///   minimum length becomes a diffusion;
/// - *delayed rejection*: a rejected jump gets `delayed_rejection` more chances, each
///   altering the proposal once more and testing it again with the same acceptance
///   (a simplified scheme, without the second-stage correction of Tierney and Mira);
/// - *parallel tempering*: after every iteration, neighbouring temperatures (coldest
///   first) swap states with probability `min(1, exp((f_j - f_i) (1/T_i - 1/T_j)))`.
///   Temperatures form a geometric ladder from `T_cold` to `T_hot`, set from the
///   initial chains' fitness standard deviation `s` (1 when it is 0 or not finite) so
///   that a move losing `s` is accepted with `cold_acceptance` (1%) by the coldest
///   chain and `hot_acceptance` (70%) by the hottest: `T = -s / ln(acceptance)`;
/// - *annealing*: every `anneal_interval` iterations all temperatures are divided by
///   `anneal_factor` (1.1).
///
/// NaN fitness is never accepted (a chain at NaN accepts any non-NaN proposal) and
/// never swapped; `+inf` to `+inf` counts as no change.
///
/// Every chain draws from the stream (seed, iteration, chain), swaps from (seed,
/// iteration, 2^31): results never depend on the thread count. An iteration costs one
/// evaluation per chain plus one per delayed-rejection try.
///
/// ```
/// use shapegen_runtime::optimize::{Budget, FnEvaluator, Mcmc, McmcSettings, Silent};
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
/// let settings = McmcSettings { chains: 8, initial_length: 2, ..McmcSettings::paper_city() };
/// let mut mcmc = Mcmc::<Chain>::new(settings, Limits::new(1, 30, 30)?, 3)?;
/// let mut eval = FnEvaluator(|g: &Genome<Chain>| -(g.len() as f64 - 8.0).abs());
/// let result = mcmc.run(&mut eval, &Budget::generations(60), &mut Silent)?;
/// assert_eq!(result.best.len(), 8);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Mcmc<G> {
    settings: McmcSettings,
    ops: Operators<G>,
    progress: Progress<G>,
    chains: Vec<Genome<G>>,
    fitness: Vec<f64>,
    temperatures: Vec<f64>,
    proposals: Vec<Genome<G>>,
    proposal_fitness: Vec<f64>,
    moves: Vec<Move>,
    rngs: Vec<ChaCha8Rng>,
    retry: Vec<u32>,
    retry_genomes: Vec<Genome<G>>,
    retry_fitness: Vec<f64>,
}

impl<G: Grammar> std::fmt::Debug for Mcmc<G> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Mcmc")
            .field("settings", &self.settings)
            .field("progress", &self.progress)
            .field("temperatures", &self.temperatures)
            .finish_non_exhaustive()
    }
}

/// What a chain proposed this iteration.
#[derive(Clone, Copy, Debug, Default)]
struct Move {
    /// Whether it is a jump (delayed rejection applies).
    jump: bool,
    /// Log of the proposal ratio.
    log_q: f64,
}

/// Per-thread scratch of a move.
#[derive(Default)]
struct Scratch {
    depth: Vec<u32>,
    links: Vec<(u32, u32)>,
    queue: Vec<(u32, u32)>,
    params: Vec<u32>,
}

impl<G: Grammar> Mcmc<G> {
    /// An MCMC run with these settings and limits, seeded with `seed`.
    pub fn new(settings: McmcSettings, limits: Limits, seed: u64) -> Result<Self, OptimizeError> {
        settings.validate()?;
        let n = settings.chains as usize;
        let empty = || Genome::from_parts(Vec::new(), 0);
        Ok(Mcmc {
            settings,
            ops: Operators::new(limits)?,
            progress: Progress::new(seed),
            chains: (0..n).map(|_| empty()).collect(),
            fitness: vec![f64::NAN; n],
            temperatures: vec![1.0; n],
            proposals: (0..n).map(|_| empty()).collect(),
            proposal_fitness: vec![f64::NAN; n],
            moves: vec![Move::default(); n],
            rngs: (0..n).map(|i| stream(seed, 0, i as u64)).collect(),
            retry: Vec::with_capacity(n),
            retry_genomes: Vec::with_capacity(n),
            retry_fitness: Vec::with_capacity(n),
        })
    }

    /// Resumes from a checkpoint; fails if it does not fit its own settings.
    pub fn resume(state: McmcState<G>) -> Result<Self, OptimizeError> {
        let mut mcmc = Mcmc::new(state.settings, state.limits, state.progress.seed)?;
        let n = state.settings.chains as usize;
        if !state.progress.history.is_empty() {
            let lens = [
                state.chains.len(),
                state.fitness.len(),
                state.temperatures.len(),
            ];
            if lens != [n; 3] {
                return Err(OptimizeError::Checkpoint(format!(
                    "{} chains, {} fitness values and {} temperatures for {n} chains",
                    lens[0], lens[1], lens[2]
                )));
            }
            mcmc.chains = state.chains;
            mcmc.fitness = state.fitness;
            mcmc.temperatures = state.temperatures;
        }
        mcmc.progress = state.progress;
        Ok(mcmc)
    }

    /// The state to resume from.
    pub fn checkpoint(&self) -> McmcState<G> {
        McmcState {
            settings: self.settings,
            limits: *self.ops.limits(),
            progress: self.progress.clone(),
            chains: self.chains.clone(),
            fitness: self.fitness.clone(),
            temperatures: self.temperatures.clone(),
        }
    }

    /// The chains' current temperatures, coldest first.
    pub fn temperatures(&self) -> &[f64] {
        &self.temperatures
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

    /// Swaps neighbouring chains' states by the tempering test.
    fn swap_temperatures(&mut self, rng: &mut impl Rng) {
        for k in 1..self.chains.len() {
            let (i, j) = (k - 1, k);
            let (ti, tj) = (self.temperatures[i], self.temperatures[j]);
            let a = (self.fitness[j] - self.fitness[i]) * (1.0 / ti - 1.0 / tj);
            let u: f64 = rng.random();
            if a >= 0.0 || u.ln() < a {
                self.chains.swap(i, j);
                self.fitness.swap(i, j);
            }
        }
    }
}

/// Whether a proposal of fitness `new` replaces a state of fitness `old` at temperature
/// `t`, with log proposal ratio `log_q`.
fn accept(old: f64, new: f64, t: f64, log_q: f64, rng: &mut impl Rng) -> bool {
    if new.is_nan() {
        return false;
    }
    if old.is_nan() {
        return true;
    }
    let delta = if new == old { 0.0 } else { new - old };
    let a = delta / t + log_q;
    let u: f64 = rng.random();
    a >= 0.0 || u.ln() < a
}

/// Proposes a move from `chain` into `proposal`.
fn propose<G: Grammar>(
    settings: &McmcSettings,
    ops: &mut Operators<G>,
    chain: &Genome<G>,
    proposal: &mut Genome<G>,
    s: &mut Scratch,
    rng: &mut impl Rng,
) -> Move {
    proposal.clone_from(chain);
    let limits = *ops.limits();
    if rng.random::<f64>() < settings.jump_probability {
        jump_links(proposal, &limits, &mut s.depth, &mut s.links);
        if !s.links.is_empty() {
            let before = s.links.len() as f64;
            let (pos, link) = s.links[rng.random_range(0..s.links.len())];
            let child = proposal.words()[(pos + HEADER_WORDS + link) as usize];
            s.params.clear();
            let cut = if child == 0 {
                true
            } else {
                let child = pos + child;
                let node = node_of::<G>(proposal.words()[child as usize]);
                let at = (child + HEADER_WORDS + node.links) as usize;
                s.params
                    .extend_from_slice(&proposal.words()[at..at + node.param_words as usize]);
                ops.cut_at(proposal, child).is_ok()
            };
            if cut {
                if let Some(root) = sample_subtree(proposal, &limits, pos, link, &mut s.queue, rng)
                    && !s.params.is_empty()
                {
                    let node = node_of::<G>(proposal.words[root as usize]);
                    let at = (root + HEADER_WORDS + node.links) as usize;
                    proposal.words[at..at + s.params.len()].copy_from_slice(&s.params);
                }
                jump_links(proposal, &limits, &mut s.depth, &mut s.links);
                let after = (s.links.len() as f64).max(1.0);
                return Move {
                    jump: true,
                    log_q: before.ln() - after.ln(),
                };
            }
        }
    }
    ops.alter(proposal, rng);
    Move {
        jump: false,
        log_q: 0.0,
    }
}

impl<G: Grammar> Method<G> for Mcmc<G> {
    fn step_cost(&self) -> u64 {
        u64::from(self.settings.chains) * (1 + u64::from(self.settings.delayed_rejection))
    }

    fn start<E: Evaluator<G>>(&mut self, evaluator: &mut E) -> Result<(), OptimizeError> {
        let (seed, len) = (self.progress.seed, self.settings.initial_length);
        let ops = &self.ops;
        self.chains.par_iter_mut().enumerate().for_each_init(
            || ops.clone(),
            |ops, (i, g)| ops.random_into(len, g, &mut stream(seed, 0, i as u64)),
        );
        evaluator.evaluate(&self.chains, &mut self.fitness)?;
        self.progress.evaluations += self.chains.len() as u64;
        let (_, s) = mean_std(&self.fitness);
        let s = if s > 0.0 && s.is_finite() { s } else { 1.0 };
        let cold = -s / self.settings.cold_acceptance.ln();
        let hot = -s / self.settings.hot_acceptance.ln();
        let n = self.temperatures.len();
        for (k, t) in self.temperatures.iter_mut().enumerate() {
            let x = if n > 1 {
                k as f64 / (n - 1) as f64
            } else {
                0.0
            };
            *t = cold * (hot / cold).powf(x);
        }
        Ok(())
    }

    fn step<E: Evaluator<G>>(&mut self, evaluator: &mut E) -> Result<(), OptimizeError> {
        let (seed, generation) = (self.progress.seed, self.progress.generation + 1);
        for (i, r) in self.rngs.iter_mut().enumerate() {
            *r = stream(seed, generation, i as u64);
        }
        let (settings, ops, chains) = (&self.settings, &self.ops, &self.chains);
        self.proposals
            .par_iter_mut()
            .zip(self.moves.par_iter_mut())
            .zip(self.rngs.par_iter_mut())
            .enumerate()
            .for_each_init(
                || (ops.clone(), Scratch::default()),
                |(ops, s), (i, ((p, m), rng))| *m = propose(settings, ops, &chains[i], p, s, rng),
            );
        evaluator.evaluate(&self.proposals, &mut self.proposal_fitness)?;
        self.progress.evaluations += self.chains.len() as u64;
        self.retry.clear();
        for i in 0..self.chains.len() {
            let (m, t) = (self.moves[i], self.temperatures[i]);
            let rng = &mut self.rngs[i];
            if accept(self.fitness[i], self.proposal_fitness[i], t, m.log_q, rng) {
                std::mem::swap(&mut self.chains[i], &mut self.proposals[i]);
                self.fitness[i] = self.proposal_fitness[i];
            } else if m.jump {
                self.retry.push(i as u32);
            }
        }
        for _ in 0..self.settings.delayed_rejection {
            if self.retry.is_empty() {
                break;
            }
            let n = self.retry.len();
            while self.retry_genomes.len() < n {
                self.retry_genomes.push(Genome::from_parts(Vec::new(), 0));
            }
            self.retry_fitness.resize(n, f64::NAN);
            for (k, &i) in self.retry.iter().enumerate() {
                let i = i as usize;
                self.ops.alter(&mut self.proposals[i], &mut self.rngs[i]);
                self.retry_genomes[k].clone_from(&self.proposals[i]);
            }
            evaluator.evaluate(&self.retry_genomes[..n], &mut self.retry_fitness[..n])?;
            self.progress.evaluations += n as u64;
            let mut kept = 0;
            for k in 0..n {
                let i = self.retry[k] as usize;
                let (m, t) = (self.moves[i], self.temperatures[i]);
                if accept(
                    self.fitness[i],
                    self.retry_fitness[k],
                    t,
                    m.log_q,
                    &mut self.rngs[i],
                ) {
                    std::mem::swap(&mut self.chains[i], &mut self.proposals[i]);
                    self.fitness[i] = self.retry_fitness[k];
                } else {
                    self.retry[kept] = i as u32;
                    kept += 1;
                }
            }
            self.retry.truncate(kept);
        }
        self.swap_temperatures(&mut stream(seed, generation, 1 << 31));
        if generation.is_multiple_of(self.settings.anneal_interval) {
            for t in &mut self.temperatures {
                *t /= self.settings.anneal_factor;
            }
        }
        Ok(())
    }

    fn parts(&mut self) -> (&mut Progress<G>, &[Genome<G>], &[f64]) {
        (&mut self.progress, &self.chains, &self.fitness)
    }
}
