//! [`Mcmc`]: the chains, their settings and checkpoints, and the run loop both variants share.

use crate::optimize::settings::generations_field;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::moves::{OriginalMove, TemperedMove};
use crate::derive::Grammar;
use crate::evaluate::{Bred, Evaluator};
use crate::genome::{Genome, Limits};
use crate::ops::{OperatorVariant, Operators};
use crate::optimize::best::Best;
use crate::optimize::core::Core;
use crate::optimize::driver::{Held, Optimizer};
use crate::optimize::error::{OptimizeError, SettingsError};
use crate::optimize::error::{check_positive, check_range, check_sizes};
use crate::optimize::fitness::bits_vec;
use crate::optimize::polish::{self, PolishState, Polisher};
use crate::optimize::run::stream;
use crate::optimize::settings::Settings;

/// Which RJMCMC an [`Mcmc`] runs.
///
/// In scene files and JSON: `"original"` or `"tempered"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum McmcVariant {
    /// The original implementation's Metropolis-Hastings (`MetropolisHastings.h` with
    /// the jump and diffusion moves of `MHOperators.cpp`), reproduced with its oddities.
    ///
    /// - Chain `i` (from 0) starts from a random genome of exactly
    ///   [`initial_length`](McmcSettings::initial_length) genes (the axiom, then
    ///   `initial_length - 1` uniform grows, as the original's `createRandomGenome`), with
    ///   the exponent `T_i = 1 / (i + 1)^1.03`, which the original calls the chain's
    ///   temperature: it multiplies log densities, so chain 0 is the coldest. Its log
    ///   prior starts at 1.
    /// - Each iteration every chain proposes a *jump* (with
    ///   [`jump_probability`](McmcSettings::jump_probability)) or a *diffusion* on one gene
    ///   picked by the original's `selectSemiRandomGene`: a level drawn by its
    ///   `getRandomValue(1, max_level)`, then a gene of that level uniformly.
    ///   - jump: delete the gene's children, then add random genes below it
    ///     (`addRandomSymbols`); the log prior change `dp` is the difference of
    ///     `getSelectionLogProb(level)` after and before;
    ///   - diffusion: redraw all parameters of the gene; `dp = 0`.
    /// - The proposal is accepted when `exp(T * (dp + ln f' - ln f)) >= U[0, 1)`, after
    ///   shifting both fitness values by `0.01 - min(f, f')` when either is `<= 0`.
    /// - After every move, accepted or not, the chain's exponent is multiplied by 1.1.
    /// - Then one tempering swap is tried between two chains drawn at random; the chains
    ///   exchange genomes (with their fitness and log priors), each position keeping its
    ///   exponent, with the probability as the original codes it (see below).
    ///
    /// As the original, this works in `f32` (fitness values are converted), and it
    /// ignores the genome [`Limits`]: genomes may grow past `max_len` and `max_depth`
    /// and shrink below `min_len` (jumps stop adding genes once the tree reaches level
    /// 25, the original's only bound; [`DEPTH_CAP`](crate::genome::DEPTH_CAP) is kept).
    /// [`Settings::kept_limits`] says so.
    ///
    /// Oddities of the original, reproduced:
    /// - its integer draw `getRandomValue(min, max)` truncates `min + (max - min) * U`,
    ///   `U` in `[0, 1)`, so it never returns `max` (unless `min == max`). Hence moves
    ///   pick genes of levels 1 to `max_level - 1` only: never the root (level 0) nor the
    ///   deepest level, unless that is level 1 (or the tree is the root alone); and
    ///   wherever the original draws
    ///   `getRandomValue(0, n - 1)` among `n >= 2` candidates (the gene to grow from, the
    ///   child to add, in grows and jumps alike) the last candidate is never taken: the
    ///   newest gene that can still grow, the last free child link in the node's order;
    /// - child types are drawn uniformly among the free links, ignoring the generator's
    ///   probabilities (the original's own "TODO: pay attention to percentage values");
    /// - a jump's `deleteChildGenes` deletes the gene's children while iterating over the
    ///   list it shrinks, so only every other child goes (the first, third, ... in the
    ///   order they were added); then `addRandomSymbols` adds genes below the gene, each
    ///   below a gene of its subtree that can still grow, drawn from the subtree in
    ///   breadth-first order, until a draw `U < 0.02` (at least one gene, 50 on average)
    ///   or until the whole tree reaches level 25;
    /// - `getSelectionLogProb(level)` is `ln(level / max_level) - ln(n_level)`, with
    ///   `max_level` never lowered by a jump's deletions; the log prior stored with a
    ///   diffusion's proposal is its selection log probability minus the chain's stored
    ///   log prior (the original's diffusion leaves the prior out of its acceptance);
    /// - the swap ("TODO: i don't think this works properly at all" in the original)
    ///   draws two chain indices with `getRandomValue(0, chains)`, which lies in
    ///   `[0, chains)`, redraws the first once if they are equal and gives up if they
    ///   still are; it swaps when `(p12 p21) / (p11 p22) >= U`, with
    ///   `pab = exp(T_a (ln f_b + prior_b))` on the shifted fitness and the stored log
    ///   priors, in `f32`, where infinities make it NaN (no swap) once the exponents
    ///   have grown;
    /// - the exponents overflow to infinity after about 930 iterations (the hotter
    ///   chains up to 50 later); from then on a move that keeps the fitness is rejected
    ///   (`inf * 0` is NaN), as in the original.
    ///
    /// Beyond the original: NaN fitness is never accepted, and a chain at NaN (or `-inf`,
    /// where the original's shift gives NaN as well) accepts any better proposal
    /// instead of being stuck forever. The original's `getRandomValue(1, max_level)` on a
    /// tree of the root alone lands on level 1 when `U` is exactly 0, a level with no
    /// gene (its code then reads past an empty list); here the root is taken.
    Original,
    /// This project's RJMCMC after Talton et al. 2011 (Metropolis procedural modeling)
    /// with parallel tempering on a calibrated temperature ladder, annealing and delayed
    /// rejection; it keeps genomes within their [`Limits`].
    ///
    /// Each chain samples the density `prior(x) * exp(f(x) / T)`, the prior being the
    /// grammar's own distribution, so that moves drawing from the prior need only the
    /// fitness in their acceptance:
    /// - *diffusion*: alter one gene (resample its parameters from their distributions);
    ///   accepted with `min(1, exp((f' - f) / T))`;
    /// - *jump*: pick a link uniformly among the links a jump may redraw (non-terminal
    ///   selection: only genes above the maximum depth; links that are expressed or have
    ///   a non-zero probability, except those whose redraw must give the same subtree
    ///   back), cut the subtree below it and redraw it from the grammar, keeping the old
    ///   subtree root's parameter values if the link is expressed again (the random
    ///   values reused); accepted with `min(1, exp((f' - f) / T) * n / n')`, `n` and `n'`
    ///   the numbers of selectable links before and after (the proposal ratio of uniform
    ///   link selection). Limits truncate redrawn subtrees, which the ratio ignores. A
    ///   jump whose cut would go below the minimum length becomes a diffusion;
    /// - *delayed rejection*: a rejected jump gets
    ///   [`delayed_rejection`](McmcSettings::delayed_rejection) more chances, each
    ///   altering the proposal once more and testing it again with the same acceptance
    ///   (a simplified scheme, without the second-stage correction of Tierney and Mira);
    /// - *parallel tempering*: after every iteration, neighbouring temperatures (coldest
    ///   first) swap states with probability `min(1, exp((f_j - f_i) (1/T_i - 1/T_j)))`.
    ///   Temperatures form a geometric ladder from `T_cold` to `T_hot`, set from the
    ///   initial chains' fitness standard deviation `s` (1 when it is 0 or not finite) so
    ///   that a move losing `s` is accepted with
    ///   [`cold_acceptance`](McmcSettings::cold_acceptance) by the coldest chain and
    ///   [`hot_acceptance`](McmcSettings::hot_acceptance) by the hottest:
    ///   `T = -s / ln(acceptance)`;
    /// - *annealing*: every [`anneal_interval`](McmcSettings::anneal_interval) iterations
    ///   all temperatures are divided by [`anneal_factor`](McmcSettings::anneal_factor).
    ///
    /// Chains start from random genomes as the GA's initial population. NaN fitness is
    /// never accepted (a chain at NaN accepts any non-NaN proposal) and never swapped;
    /// `+inf` to `+inf` counts as no change.
    Tempered,
}

impl McmcVariant {
    /// Every variant.
    pub const ALL: [McmcVariant; 2] = [McmcVariant::Original, McmcVariant::Tempered];

    /// Its name in scene files and settings.
    pub const fn name(self) -> &'static str {
        match self {
            McmcVariant::Original => "original",
            McmcVariant::Tempered => "tempered",
        }
    }
}

/// Settings of [`Mcmc`]. Loads from scene files with serde; missing fields take the
/// [`Default`] values (the paper's spaceship scene, [`McmcVariant::Original`]), unknown
/// fields are errors.
///
/// The last five fields are read by the [tempered](McmcVariant::Tempered) variant only;
/// the [original](McmcVariant::Original) one has its constants built in (exponents
/// `1/(i+1)^1.03`, annealing 1.1 after every move, no delayed rejection).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct McmcSettings {
    /// Which RJMCMC runs.
    pub variant: McmcVariant,
    /// Number of chains; at least 1.
    pub chains: u32,
    /// Iterations (one move per chain each), the default generation budget.
    pub iterations: u64,
    /// Length of the chains' random initial genomes; at least 1. The original variant
    /// grows exactly this many genes (fewer only if the grammar's trees cannot be that
    /// large); the tempered one draws a target length around it, as the GA's initial
    /// population.
    pub initial_length: u32,
    /// Chance that a move is a jump rather than a diffusion; in `[0, 1]`.
    pub jump_probability: f64,
    /// Tempered variant only: extra alter steps tried on a rejected jump before giving it
    /// up; at most 16.
    pub delayed_rejection: u32,
    /// Tempered variant only: every `anneal_interval` iterations all temperatures are
    /// divided by this; at least 1 (1: no annealing), finite.
    pub anneal_factor: f64,
    /// Tempered variant only: iterations between annealing steps; at least 1.
    pub anneal_interval: u64,
    /// Tempered variant only: acceptance chance, in the hottest chain, of a move losing
    /// one initial standard deviation of fitness; in `(0, 1)`.
    pub hot_acceptance: f64,
    /// Tempered variant only: acceptance chance of the same move in the coldest chain;
    /// in `(0, hot_acceptance)`.
    pub cold_acceptance: f64,
    /// Tempered variant only: candidates a separable CMA-ES draws each iteration to tune
    /// the continuous parameters of the best chain's state (see [`Mcmc`]); 0, the
    /// default, polishes nothing, otherwise at least 2.
    pub polish: u32,
    /// The step size a new polishing strategy starts with, as a share of each
    /// parameter's range; in `(0, 1]`.
    pub polish_sigma: f64,
}

impl Default for McmcSettings {
    /// The original variant with the original's settings for the paper's spaceship
    /// scene (70 chains, 250 iterations, initial length 50, jumps half the moves); the
    /// tempered variant's fields hold its own defaults: delayed rejection 1, annealing
    /// by 1.1 every 10 iterations, acceptance 70% hot and 1% cold.
    fn default() -> Self {
        McmcSettings {
            variant: McmcVariant::Original,
            chains: 70,
            iterations: 250,
            initial_length: 50,
            jump_probability: 0.5,
            delayed_rejection: 1,
            anneal_factor: 1.1,
            anneal_interval: 10,
            hot_acceptance: 0.7,
            cold_acceptance: 0.01,
            polish: 0,
            polish_sigma: 0.1,
        }
    }
}

impl Settings for McmcSettings {
    generations_field!("iterations", iterations);

    /// The original's chains are bounded by neither length nor depth; the tempered
    /// variant's keep the given limits.
    fn kept_limits(&self, limits: Limits) -> Limits {
        match self.variant {
            McmcVariant::Original => limits.without_length().without_depth(),
            McmcVariant::Tempered => limits,
        }
    }

    /// Checks every field the variant reads; the error names the first one out of
    /// range.
    fn validate(&self) -> Result<(), SettingsError> {
        check_positive("chains", self.chains)?;
        check_positive("initial_length", self.initial_length)?;
        check_range(
            "jump_probability",
            self.jump_probability,
            0.0,
            1.0,
            "between 0 and 1",
        )?;
        match self.variant {
            McmcVariant::Tempered => self.validate_tempered()?,
            McmcVariant::Original => polish::refuse(
                self.polish,
                "0 with variant = \"original\", whose chains keep the prior of their last \
                 move (polishing runs with variant = \"tempered\")",
            )?,
        }
        polish::check_settings(self.polish, self.polish_sigma)
    }
}

impl McmcSettings {
    /// Checks the fields only the tempered variant reads.
    fn validate_tempered(&self) -> Result<(), SettingsError> {
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
        check_positive("anneal_interval", self.anneal_interval)?;
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
}

crate::checkpoint! {
    /// A checkpoint of an [`Mcmc`], resumed by [`Mcmc::resume`].
    pub struct McmcState<G>: McmcSettings, Best<G> {
        /// The chains' current states, by position.
        pub chains: Vec<Genome<G>>,
        /// Their fitness.
        #[serde(with = "bits_vec")]
        pub fitness: Vec<f64>,
        /// Each position's temperature: see [`Mcmc::temperatures`].
        #[serde(with = "bits_vec")]
        pub temperatures: Vec<f64>,
        /// Original variant: each chain's stored log prior, read by its tempering swaps
        /// (`f32` values); empty for the tempered variant.
        #[serde(default, with = "bits_vec")]
        pub log_priors: Vec<f64>,
        /// The polishing under way, if any.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        pub polish: Option<PolishState<G>>,
    }
}

/// Reversible-jump MCMC over derivation trees, in the [`McmcVariant`] its settings
/// name.
///
/// Every chain draws from the stream (seed, iteration, chain), tempering swaps from
/// (seed, iteration, 2^31), initial genomes from (seed, 0, chain): results never depend
/// on the thread count. An iteration costs one evaluation per chain, plus, in the
/// tempered variant, one per delayed-rejection try.
///
/// Polishing (tempered variant, off by default): with [`polish`](McmcSettings::polish),
/// each iteration ends with a separable CMA-ES ([`SepCmaEs`](crate::optimize::SepCmaEs)) drawing
/// that many candidates over the continuous parameters of the best chain's state, its
/// structure kept; the best candidate replaces the state when it scores at least as
/// well. It draws from (seed, iteration, 3 * 2^30) and costs `polish` evaluations an
/// iteration while the best state has a continuous parameter.
///
/// ```
/// use shapegen_runtime::optimize::{
///     Budget, FnEvaluator, Mcmc, McmcSettings, McmcVariant, Optimizer, Silent,
/// };
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
/// let mut eval = FnEvaluator(|g: &Genome<Chain>| -(g.len() as f64 - 8.0).abs());
/// for variant in [McmcVariant::Original, McmcVariant::Tempered] {
///     let settings =
///         McmcSettings { variant, chains: 8, initial_length: 2, ..McmcSettings::default() };
///     let mut mcmc = Mcmc::<Chain>::new(settings, Limits::new(1, 30, 30)?, 3)?;
///     let result = mcmc.run(&mut eval, &Budget::generations(60), &mut Silent)?;
///     assert_eq!(result.best.len(), 8);
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Mcmc<G> {
    pub(super) core: Core<McmcSettings, Best<G>>,
    pub(super) ops: Operators<G>,
    pub(super) chains: Vec<Genome<G>>,
    pub(super) fitness: Vec<f64>,
    pub(super) temperatures: Vec<f64>,
    /// Original variant: the chains' stored log priors.
    pub(super) log_priors: Vec<f64>,
    pub(super) proposals: Vec<Genome<G>>,
    pub(super) proposal_fitness: Vec<f64>,
    /// `0..chains`: proposal `i` is bred from chain `i`.
    pub(super) own_chain: Vec<u32>,
    pub(super) rngs: Vec<ChaCha8Rng>,
    /// Tempered variant: what each chain proposed this iteration.
    pub(super) moves: Vec<TemperedMove>,
    /// Original variant: what each chain proposed this iteration.
    pub(super) original_moves: Vec<OriginalMove>,
    /// Tempered variant: chains whose jump awaits another delayed-rejection try.
    pub(super) retry: Vec<u32>,
    /// Tempered variant: copies of their proposals, evaluated together.
    pub(super) retry_genomes: Vec<Genome<G>>,
    /// Tempered variant: their fitness.
    pub(super) retry_fitness: Vec<f64>,
    pub(super) polisher: Polisher<G>,
}

impl<G: Grammar> std::fmt::Debug for Mcmc<G> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.core
            .debug(f, "Mcmc")
            .field("temperatures", &self.temperatures)
            .finish_non_exhaustive()
    }
}

impl<G: Grammar> Mcmc<G> {
    /// Each chain position's current temperature. Tempered variant: the temperatures,
    /// ascending (coldest first). Original variant: the original's "temperature", an
    /// exponent on the fitness ratio (an inverse temperature, `f32` values): it starts at
    /// `1 / (i + 1)^1.03` for position `i`, descending (coldest first), and is multiplied
    /// by 1.1 after every move.
    pub fn temperatures(&self) -> &[f64] {
        &self.temperatures
    }

    /// Grows every chain's initial genome, chain `i` from stream (seed, 0, `i`), with the
    /// variant's operators, and evaluates them.
    pub(super) fn start_chains<E: Evaluator<G> + ?Sized>(
        &mut self,
        evaluator: &mut E,
    ) -> Result<(), OptimizeError> {
        let (seed, len) = (self.core.progress.seed, self.core.settings.initial_length);
        let ops = &self.ops;
        self.chains.par_iter_mut().enumerate().for_each_init(
            || ops.clone(),
            |ops, (i, g)| ops.random_into(len, g, &mut stream(seed, 0, i as u64)),
        );
        evaluator.evaluate(&self.chains, &mut self.fitness)?;
        self.core.progress.evaluations += self.chains.len() as u64;
        Ok(())
    }

    /// Starts an iteration: chain `i` draws from stream (seed, generation, `i`) for the
    /// next generation. Returns that generation.
    pub(super) fn reseed(&mut self) -> u64 {
        let (seed, generation) = (self.core.progress.seed, self.core.progress.generation + 1);
        for (i, r) in self.rngs.iter_mut().enumerate() {
            *r = stream(seed, generation, i as u64);
        }
        generation
    }

    /// Evaluates every chain's proposal into `proposal_fitness`, proposal `i` bred from
    /// chain `i`.
    pub(super) fn evaluate_proposals<E: Evaluator<G> + ?Sized>(
        &mut self,
        evaluator: &mut E,
    ) -> Result<(), OptimizeError> {
        evaluator.evaluate_bred(
            Bred {
                children: &self.proposals,
                parents: &self.chains,
                from: &self.own_chain,
            },
            &mut self.proposal_fitness,
        )?;
        self.core.progress.evaluations += self.chains.len() as u64;
        Ok(())
    }
}

/// Writes every chain's proposal in parallel: `propose(ops, scratch, i, proposal, rng)`
/// writes proposal `i` with chain `i`'s stream and returns its move, which lands in
/// `moves[i]`. Each thread works with its own copy of the operators and its own scratch.
pub(super) fn propose_each<G: Grammar, M: Send, S: Default>(
    ops: &Operators<G>,
    proposals: &mut [Genome<G>],
    moves: &mut [M],
    rngs: &mut [ChaCha8Rng],
    propose: impl Fn(&mut Operators<G>, &mut S, usize, &mut Genome<G>, &mut ChaCha8Rng) -> M + Sync,
) {
    proposals
        .par_iter_mut()
        .zip(moves.par_iter_mut())
        .zip(rngs.par_iter_mut())
        .enumerate()
        .for_each_init(
            || (ops.clone(), S::default()),
            |(ops, s), (i, ((p, m), rng))| *m = propose(ops, s, i, p, rng),
        );
}

impl<G: Grammar> Optimizer<G> for Mcmc<G> {
    type Settings = McmcSettings;
    type State = McmcState<G>;
    type Record = Best<G>;

    /// The chains, their proposals, delayed-rejection retries and the checkpoint's
    /// copy; polishing's candidates and origin.
    fn genomes_held(settings: &McmcSettings) -> Vec<Held> {
        vec![
            Held::per("optimizer.chains", settings.chains, 4, 1),
            polish::held(settings.polish),
        ]
    }

    /// An MCMC run with these settings and limits, seeded with `seed`.
    fn new(settings: McmcSettings, limits: Limits, seed: u64) -> Result<Self, OptimizeError> {
        settings.validate()?;
        let n = settings.chains as usize;
        let empty = || Genome::from_parts(Vec::new(), 0);
        let original = settings.variant == McmcVariant::Original;
        // The original's jumps delete children whatever the length left.
        let op_limits = if original {
            Limits {
                min_len: 0,
                ..limits
            }
        } else {
            limits
        };
        Ok(Mcmc {
            core: Core::new(settings, limits, seed),
            ops: Operators::new(op_limits)?.with_variant(if original {
                OperatorVariant::Original
            } else {
                OperatorVariant::Weighted
            }),
            chains: (0..n).map(|_| empty()).collect(),
            fitness: vec![f64::NAN; n],
            temperatures: vec![1.0; n],
            log_priors: if original { vec![1.0; n] } else { Vec::new() },
            proposals: (0..n).map(|_| empty()).collect(),
            proposal_fitness: vec![f64::NAN; n],
            own_chain: (0..n as u32).collect(),
            rngs: (0..n).map(|i| stream(seed, 0, i as u64)).collect(),
            moves: if original {
                Vec::new()
            } else {
                vec![TemperedMove::default(); n]
            },
            original_moves: if original {
                vec![OriginalMove::default(); n]
            } else {
                Vec::new()
            },
            retry: Vec::new(),
            retry_genomes: Vec::new(),
            retry_fitness: Vec::new(),
            polisher: Polisher::new(),
        })
    }

    fn core(&self) -> &Core<McmcSettings, Best<G>> {
        &self.core
    }

    fn parts(&mut self) -> (&mut Core<McmcSettings, Best<G>>, &[Genome<G>], &[f64]) {
        (&mut self.core, &self.chains, &self.fitness)
    }

    #[allow(clippy::type_complexity)]
    fn save_body(
        &self,
    ) -> (
        Vec<Genome<G>>,
        Vec<f64>,
        Vec<f64>,
        Vec<f64>,
        Option<PolishState<G>>,
    ) {
        (
            self.chains.clone(),
            self.fitness.clone(),
            self.temperatures.clone(),
            self.log_priors.clone(),
            self.polisher.save(),
        )
    }

    /// Counts the chains first, then, as many as the settings', their fitness values,
    /// temperatures and (original variant) log priors.
    fn check_body(state: &McmcState<G>) -> Result<(), OptimizeError> {
        Polisher::check(state.polish.as_ref())?;
        let s = &state.settings;
        let n = s.chains as usize;
        let priors = if s.variant == McmcVariant::Original {
            n
        } else {
            0
        };
        let chains = (state.chains.len(), n, "chains");
        check_sizes(&[chains], format_args!("{n} chains"))?;
        check_sizes(
            &[
                chains,
                (state.fitness.len(), n, "fitness values"),
                (state.temperatures.len(), n, "temperatures"),
                (state.log_priors.len(), priors, "log priors"),
            ],
            format_args!("{n} chains of the {} variant", s.variant.name()),
        )
    }

    #[allow(clippy::type_complexity)]
    fn restore_body(
        &mut self,
        (chains, fitness, temperatures, log_priors, polish): (
            Vec<Genome<G>>,
            Vec<f64>,
            Vec<f64>,
            Vec<f64>,
            Option<PolishState<G>>,
        ),
    ) -> Result<(), OptimizeError> {
        self.chains = chains;
        self.fitness = fitness;
        self.temperatures = temperatures;
        self.log_priors = log_priors;
        self.polisher.restore(polish);
        Ok(())
    }

    fn step_cost(&self) -> u64 {
        let tries = match self.core.settings.variant {
            McmcVariant::Original => 1,
            McmcVariant::Tempered => 1 + u64::from(self.core.settings.delayed_rejection),
        };
        u64::from(self.core.settings.chains) * tries + u64::from(self.core.settings.polish)
    }

    fn start(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        self.start_chains(evaluator)?;
        match self.core.settings.variant {
            McmcVariant::Original => self.start_original(),
            McmcVariant::Tempered => self.start_tempered(),
        }
        Ok(())
    }

    fn step(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        match self.core.settings.variant {
            McmcVariant::Original => self.step_original(evaluator),
            McmcVariant::Tempered => {
                self.step_tempered(evaluator)?;
                let (settings, progress) = (&self.core.settings, &mut self.core.progress);
                self.polisher.polish(
                    (settings.polish, settings.polish_sigma),
                    progress,
                    evaluator,
                    (&mut self.chains, &mut self.fitness),
                )
            }
        }
    }
}
