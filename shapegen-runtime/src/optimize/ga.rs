//! The genetic algorithm, the paper's Algorithm 1.

use rand::{Rng, RngExt};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::best::Best;
use super::error::{check_range, check_sizes};
use super::fitness::{Roulette, bits_vec, compare, rank};
use super::run::{Progress, grammar_struct_traits, stream};
use super::{Evaluator, Held, OptimizeError, Optimizer, Record, Settings, SettingsError};
use crate::derive::Grammar;
use crate::genome::{Genome, Limits};
use crate::ops::{OperatorVariant, Operators};

/// With the original's breeding, how many breeding events a pair of slots may take to
/// fill with children within the length window before the GA gives up with an error
/// (the original would loop forever).
const ORIGINAL_BREEDS_PER_PAIR: u32 = 10_000;

/// Settings of the [`Ga`]. Loads from scene files with serde; missing fields take the
/// [`Default`] values, unknown fields are errors.
///
/// The default is the good setting of the CESCG study (ALGORITHMS.md, section 4):
/// population 200, elitism 30, initial length 20, 50 generations, mutation 30% with
/// uniform grow / cut / alter, tournament of 10, with the weighted operators. The
/// published generators carry the original's settings for their paper scenes
/// (`generators::spaceship::paper_ga`, ...), with the original's operators and breeding.
///
/// ```
/// use shapegen_runtime::ops::OperatorVariant;
/// use shapegen_runtime::optimize::GaSettings;
///
/// let s: GaSettings = serde_json::from_str(r#"{"operators": "original", "population": 50}"#)?;
/// assert_eq!(s.operators, OperatorVariant::Original);
/// assert!(!s.cross_array_index);
/// # Ok::<(), serde_json::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GaSettings {
    /// Individuals per generation; at least 2.
    pub population: u32,
    /// Best individuals copied unchanged into the next generation (their fitness is
    /// kept, not recomputed); less than `population`.
    pub elitism: u32,
    /// Initial genomes are grown from the axiom: with the weighted operators to a length
    /// drawn uniformly from `[L/2, 3L/2]` around this `L` (within the limits), with the
    /// original's to exactly `L` genes, as the original does; at least 1.
    pub initial_length: u32,
    /// Generations after the initial one, the default generation budget.
    pub generations: u64,
    /// Chance that a pair of parents is mutated instead of crossed over; in `[0, 1]`.
    pub mutation_probability: f64,
    /// Relative weight of grow among mutations; finite and not negative.
    pub grow_weight: f64,
    /// Relative weight of cut among mutations; finite and not negative.
    pub cut_weight: f64,
    /// Relative weight of alter among mutations; finite and not negative. The three
    /// weights must not all be 0.
    pub alter_weight: f64,
    /// Size of the tournaments that choose parents (see
    /// [`selection`](Self::selection)); at least 1.
    pub tournament: u32,
    /// How the two parents of a pair are chosen (scene key `selection`:
    /// `"tournament_roulette"`, the default and the paper's, `"tournament"`,
    /// `"roulette"` or `"random"`); see [`ParentSelection`].
    pub selection: ParentSelection,
    /// The rules of the operators and of the breeding around them (scene key
    /// `operators`: `"weighted"`, the default, or `"original"`); see
    /// [`OperatorVariant`] and [`Ga`].
    pub operators: OperatorVariant,
    /// Whether crossover may exchange subtrees hanging from different indices of an array
    /// slot, which moves, say, a city lot's building to another lot (scene key
    /// `cross_array_index`). `false`, the default: `lots[i]` meets only `lots[i]`, as
    /// the original's one symbol per lot does.
    pub cross_array_index: bool,
}

impl Default for GaSettings {
    fn default() -> Self {
        GaSettings {
            population: 200,
            elitism: 30,
            initial_length: 20,
            generations: 50,
            mutation_probability: 0.3,
            grow_weight: 1.0,
            cut_weight: 1.0,
            alter_weight: 1.0,
            tournament: 10,
            selection: ParentSelection::TournamentRoulette,
            operators: OperatorVariant::Weighted,
            cross_array_index: false,
        }
    }
}

/// How the [`Ga`] chooses the two parents of each pair it breeds. Tournaments are of
/// [`GaSettings::tournament`] entrants; the roulette wheel weighs each individual by its
/// fitness above the population's worst (see [`Ga`] for NaN and infinities).
///
/// The CESCG study compared these schemes (ALGORITHMS.md, section 4); the paper's GA and
/// the original implementation use the first.
///
/// ```
/// use shapegen_runtime::optimize::{GaSettings, ParentSelection};
///
/// let s: GaSettings = serde_json::from_str(r#"{"selection": "roulette"}"#)?;
/// assert_eq!(s.selection, ParentSelection::Roulette);
/// assert_eq!(GaSettings::default().selection, ParentSelection::TournamentRoulette);
/// # Ok::<(), serde_json::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ParentSelection {
    /// Parent 1 by tournament, parent 2 by roulette (`"tournament_roulette"`): the
    /// paper's Algorithm 1 and the original's `createNewGeneration`.
    #[default]
    TournamentRoulette,
    /// Both parents by tournament (`"tournament"`).
    Tournament,
    /// Both parents by roulette (`"roulette"`).
    Roulette,
    /// Both parents drawn uniformly from the population, ignoring fitness (`"random"`).
    Random,
}

impl Settings for GaSettings {
    const GENERATIONS: &'static str = "generations";

    fn generations(&self) -> u64 {
        self.generations
    }

    fn set_generations(&mut self, generations: u64) {
        self.generations = generations;
    }

    /// Checks every field; the error names the first one out of range.
    ///
    /// ```
    /// use shapegen_runtime::optimize::{GaSettings, Settings};
    ///
    /// let bad = GaSettings { elitism: 200, ..GaSettings::default() };
    /// assert_eq!(bad.validate().unwrap_err().field, "elitism");
    /// ```
    fn validate(&self) -> Result<(), SettingsError> {
        if self.population < 2 {
            return Err(SettingsError::new(
                "population",
                self.population,
                "at least 2",
            ));
        }
        if self.elitism >= self.population {
            return Err(SettingsError::new(
                "elitism",
                self.elitism,
                "less than the population",
            ));
        }
        if self.initial_length == 0 {
            return Err(SettingsError::new("initial_length", 0, "at least 1"));
        }
        check_range(
            "mutation_probability",
            self.mutation_probability,
            0.0,
            1.0,
            "between 0 and 1",
        )?;
        let valid = "finite and not negative";
        check_range("grow_weight", self.grow_weight, 0.0, f64::MAX, valid)?;
        check_range("cut_weight", self.cut_weight, 0.0, f64::MAX, valid)?;
        check_range("alter_weight", self.alter_weight, 0.0, f64::MAX, valid)?;
        let total = self.grow_weight + self.cut_weight + self.alter_weight;
        if !(total > 0.0 && total.is_finite()) {
            return Err(SettingsError::new(
                "alter_weight",
                self.alter_weight,
                "positive when grow_weight and cut_weight are 0 (the weights' sum must be finite and positive)",
            ));
        }
        if self.tournament == 0 {
            return Err(SettingsError::new("tournament", 0, "at least 1"));
        }
        Ok(())
    }
}

impl GaSettings {
    /// The genomes `populations` GAs of these settings hold: each its population, the
    /// next generation and a checkpoint's copy.
    pub(crate) fn held(&self, populations: u64) -> Held {
        Held {
            genomes: 3 * u64::from(self.population) * populations,
            saved: u64::from(self.population) * populations,
            setting: "optimizer.population",
            value: self.population.into(),
        }
    }

    /// Checks the settings against the genome limits: the original's breeding keeps only
    /// children within `[min_len, max_len)`, which must not be empty.
    pub(crate) fn check_limits(&self, limits: &Limits) -> Result<(), SettingsError> {
        if self.operators == OperatorVariant::Original && limits.min_len.max(1) >= limits.max_len {
            return Err(SettingsError::new(
                "limits.max_len",
                limits.max_len,
                "above limits.min_len with operators = \"original\", whose GA keeps only \
                 children shorter than max_len",
            ));
        }
        Ok(())
    }

    /// The operators these settings breed with, keeping to `limits`.
    pub(crate) fn build_operators<G: Grammar>(
        &self,
        limits: Limits,
    ) -> Result<Operators<G>, OptimizeError> {
        self.check_limits(&limits)?;
        Ok(Operators::new(limits)?
            .with_variant(self.operators)
            .with_cross_array_index(self.cross_array_index))
    }
}

/// A checkpoint of a [`Ga`]: serialize it (e.g. with `serde_json`) and give it to
/// [`Ga::resume`] to go on exactly as an uninterrupted run would.
///
/// The random streams are fixed by the seed and the generation number, so the state
/// holds no generator positions beyond those.
#[derive(Serialize, Deserialize)]
#[serde(
    deny_unknown_fields,
    bound(serialize = "G: Grammar", deserialize = "G: Grammar")
)]
pub struct GaState<G> {
    /// The settings.
    pub settings: GaSettings,
    /// The genome limits.
    pub limits: Limits,
    /// Generation, evaluations, best so far, history.
    pub progress: Progress<Best<G>>,
    /// The current population, best first after the first generation.
    pub population: Vec<Genome<G>>,
    /// Its cached fitness.
    #[serde(with = "bits_vec")]
    pub fitness: Vec<f64>,
}

grammar_struct_traits!(GaState {
    settings,
    limits,
    progress,
    population,
    fitness
});

/// The genetic algorithm (ALGORITHMS.md, section 4): each generation keeps the
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
/// Evaluations: elites keep their cached fitness and are not evaluated again, so every
/// generation after the first costs `population - elitism` evaluations, with either
/// operators; the original evaluates the whole population every generation, elites
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
    settings: GaSettings,
    ops: Operators<G>,
    progress: Progress<Best<G>>,
    population: Vec<Genome<G>>,
    fitness: Vec<f64>,
    next: Vec<Genome<G>>,
    next_fitness: Vec<f64>,
    /// The parent each child of `next` was bred from, by index into `population`.
    from: Vec<u32>,
    order: Vec<u32>,
    roulette: Roulette,
}

impl<G: Grammar> std::fmt::Debug for Ga<G> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Ga")
            .field("settings", &self.settings)
            .field("progress", &self.progress)
            .finish_non_exhaustive()
    }
}

impl<G: Grammar> Ga<G> {
    /// The progress, the population and its fitness, for a method that changes
    /// individuals between the GA's generations (the hybrid's seeding and refinement).
    pub(super) fn parts_mut(&mut self) -> (&mut Progress<Best<G>>, &mut [Genome<G>], &mut [f64]) {
        (&mut self.progress, &mut self.population, &mut self.fitness)
    }
}

impl<G: Grammar> Optimizer<G> for Ga<G> {
    type Settings = GaSettings;
    type State = GaState<G>;
    type Record = Best<G>;

    /// The population, the next generation bred beside it, and the checkpoint's copy.
    fn genomes_held(settings: &GaSettings) -> Vec<Held> {
        vec![settings.held(1)]
    }

    /// A GA with these settings, keeping genomes within `limits` (the weighted operators)
    /// or its children within `[min_len, max_len)` (the original's), seeded with `seed`.
    fn new(settings: GaSettings, limits: Limits, seed: u64) -> Result<Self, OptimizeError> {
        settings.validate()?;
        let n = settings.population as usize;
        let empty = || Genome::from_parts(Vec::new(), 0);
        Ok(Ga {
            settings,
            ops: settings.build_operators(limits)?,
            progress: Progress::new(seed),
            population: (0..n).map(|_| empty()).collect(),
            fitness: vec![f64::NAN; n],
            next: (0..n).map(|_| empty()).collect(),
            next_fitness: vec![f64::NAN; n],
            from: vec![0; n - settings.elitism as usize],
            order: Vec::with_capacity(n),
            roulette: Roulette::default(),
        })
    }

    fn resume(state: GaState<G>) -> Result<Self, OptimizeError> {
        // The sizes are checked before the GA is made, so that settings disagreeing with
        // the checkpoint's population cannot make it allocate more than that holds.
        if state.progress.record.started() {
            let n = state.settings.population as usize;
            check_sizes(
                &[
                    (state.population.len(), n, "genomes"),
                    (state.fitness.len(), n, "fitness values"),
                ],
                format_args!("a population of {n}"),
            )?;
        }
        let mut ga = Ga::new(state.settings, state.limits, state.progress.seed)?;
        if state.progress.record.started() {
            ga.population = state.population;
            ga.fitness = state.fitness;
        }
        ga.progress = state.progress;
        Ok(ga)
    }

    fn checkpoint(&self) -> GaState<G> {
        GaState {
            settings: self.settings,
            limits: *self.ops.limits(),
            progress: self.progress.clone(),
            population: self.population.clone(),
            fitness: self.fitness.clone(),
        }
    }

    fn settings(&self) -> &GaSettings {
        &self.settings
    }

    fn state_settings(state: &GaState<G>) -> &GaSettings {
        &state.settings
    }

    fn state_limits(state: &GaState<G>) -> &Limits {
        &state.limits
    }

    fn progress(&self) -> &Progress<Best<G>> {
        &self.progress
    }

    fn parts(&mut self) -> (&mut Progress<Best<G>>, &[Genome<G>], &[f64]) {
        (&mut self.progress, &self.population, &self.fitness)
    }

    fn step_cost(&self) -> u64 {
        u64::from(self.settings.population - self.settings.elitism)
    }

    fn start(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        let seed = self.progress.seed;
        random_population(&self.ops, &self.settings, seed, &mut self.population);
        evaluator.evaluate(&self.population, &mut self.fitness)?;
        self.progress.evaluations += self.population.len() as u64;
        Ok(())
    }

    fn step(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        let elite = self.settings.elitism as usize;
        let (elites, children) = self.next.split_at_mut(elite);
        Generation {
            settings: &self.settings,
            ops: &self.ops,
            seed: self.progress.seed,
            generation: self.progress.generation + 1,
        }
        .breed(
            Parents {
                population: &self.population,
                fitness: &self.fitness,
            },
            &mut self.order,
            &mut self.roulette,
            (elites, &mut self.next_fitness[..elite]),
            (children, &mut self.from),
        )?;
        evaluator.evaluate_bred(
            &self.next[elite..],
            &self.population,
            &self.from,
            &mut self.next_fitness[elite..],
        )?;
        self.progress.evaluations += self.step_cost();
        std::mem::swap(&mut self.population, &mut self.next);
        std::mem::swap(&mut self.fitness, &mut self.next_fitness);
        Ok(())
    }
}

/// One population and its fitness, as a generation is bred from them.
pub(crate) struct Parents<'a, G> {
    /// The population.
    pub(crate) population: &'a [Genome<G>],
    /// Its fitness, one value per genome.
    pub(crate) fitness: &'a [f64],
}

/// What breeding one generation of a GA population needs besides the population: the
/// settings and operators, and the seed and number of the generation being bred. The
/// [`Ga`] breeds its one population with it, the island model each of its islands.
pub(crate) struct Generation<'a, G> {
    /// The GA's settings.
    pub(crate) settings: &'a GaSettings,
    /// The operators, keeping to the limits.
    pub(crate) ops: &'a Operators<G>,
    /// The seed of the population's random streams.
    pub(crate) seed: u64,
    /// The number of the generation being bred (the first bred is 1).
    pub(crate) generation: u64,
}

impl<G: Grammar> Generation<'_, G> {
    /// Breeds the next generation of `parents`: copies its `elitism` best, with their
    /// fitness, into `elites`, and breeds `children` (see [`Breed::children`]), each
    /// child's parent index into `from`. `order` and `roulette` are scratch.
    pub(crate) fn breed(
        &self,
        parents: Parents<'_, G>,
        order: &mut Vec<u32>,
        roulette: &mut Roulette,
        (elites, elite_fitness): (&mut [Genome<G>], &mut [f64]),
        (children, from): (&mut [Genome<G>], &mut [u32]),
    ) -> Result<(), OptimizeError> {
        rank(parents.fitness, order);
        roulette.build(parents.fitness);
        for ((elite, f), &i) in elites.iter_mut().zip(elite_fitness).zip(order.iter()) {
            elite.clone_from(&parents.population[i as usize]);
            *f = parents.fitness[i as usize];
        }
        Breed {
            settings: self.settings,
            population: parents.population,
            fitness: parents.fitness,
            roulette,
            worst: *order.last().expect("a population of at least 2"),
        }
        .children(self.ops, self.seed, self.generation, children, from)
    }
}

/// Grows the initial population in parallel: genome `i` from stream (seed, 0, `i`), to a
/// length around the settings' initial length (exactly that length with the original's
/// operators).
pub(crate) fn random_population<G: Grammar>(
    ops: &Operators<G>,
    settings: &GaSettings,
    seed: u64,
    population: &mut [Genome<G>],
) {
    let len = settings.initial_length;
    population.par_iter_mut().enumerate().for_each_init(
        || ops.clone(),
        |ops, (i, g)| ops.random_into(len, g, &mut stream(seed, 0, i as u64)),
    );
}

/// What breeding reads: the current generation, the higher-is-better fitness it is
/// selected on (the GA's own fitness, or a multi-objective selection fitness) and the
/// roulette wheel built on that fitness.
pub(crate) struct Breed<'a, G> {
    /// Mutation probability and weights, tournament size, operator rules.
    pub(crate) settings: &'a GaSettings,
    /// The parents to choose from.
    pub(crate) population: &'a [Genome<G>],
    /// Their selection fitness, one per genome.
    pub(crate) fitness: &'a [f64],
    /// The roulette wheel built on `fitness`.
    pub(crate) roulette: &'a Roulette,
    /// The index of the worst-ranked individual, which the original's tournament never
    /// draws.
    pub(crate) worst: u32,
}

impl<G: Grammar> Breed<'_, G> {
    /// Breeds `children` in parallel, in pairs: pair `p` (children `2p` and `2p + 1`; the
    /// last pair may hold one) draws from stream (seed, `generation`, `p`), so the
    /// children never depend on the thread count. `from[i]` is set to the index of the
    /// parent child `i` was made from (the one it is a mutated copy of, or whose tree
    /// received the other parent's subtree). Fails only with the original's breeding,
    /// when [`ORIGINAL_BREEDS_PER_PAIR`] breeding events do not fill a pair with children
    /// within the length window.
    pub(crate) fn children(
        &self,
        ops: &Operators<G>,
        seed: u64,
        generation: u64,
        children: &mut [Genome<G>],
        from: &mut [u32],
    ) -> Result<(), OptimizeError> {
        debug_assert_eq!(children.len(), from.len());
        let empty = || Genome::from_parts(Vec::new(), 0);
        children
            .par_chunks_mut(2)
            .zip(from.par_chunks_mut(2))
            .enumerate()
            .try_for_each_init(
                || (ops.clone(), [empty(), empty()]),
                |(ops, spare), (pair, (children, from))| {
                    let rng = &mut stream(seed, generation, pair as u64);
                    if self.settings.operators == OperatorVariant::Original {
                        return self.original_pair(ops, children, from, spare, rng);
                    }
                    let (a, b) = match children {
                        [a, b] => (a, b),
                        [a] => (a, &mut spare[0]),
                        _ => unreachable!("chunks hold one or two children"),
                    };
                    let parents = self.pair(ops, a, b, rng);
                    from.copy_from_slice(&parents[..from.len()]);
                    Ok(())
                },
            )
    }

    /// Breeds two children into `a` and `b`, and returns the parents they were made
    /// from, in that order.
    fn pair(
        &self,
        ops: &mut Operators<G>,
        a: &mut Genome<G>,
        b: &mut Genome<G>,
        rng: &mut impl Rng,
    ) -> [u32; 2] {
        let (i1, i2) = self.parents(rng);
        let (p1, p2) = (&self.population[i1], &self.population[i2]);
        if self.mutates(rng) {
            a.clone_from(p1);
            self.mutate(ops, a, rng);
            b.clone_from(p2);
            self.mutate(ops, b, rng);
        } else if !ops.crossover_into(p1, p2, a, b, rng) {
            a.clone_from(p1);
            b.clone_from(p2);
        }
        [i1 as u32, i2 as u32]
    }

    /// Fills `slots` (one or two) as the original's `createNewGeneration` fills the
    /// generation: breeds a pair of children into `kids` (none when the crossover
    /// fails), keeps each child with `min_len <= len < max_len` in the next empty slot
    /// (swapping buffers, so nothing is allocated once warmed up), and breeds again until
    /// the slots are full. `from` gets the parent of each slot's child.
    fn original_pair(
        &self,
        ops: &mut Operators<G>,
        slots: &mut [Genome<G>],
        from: &mut [u32],
        kids: &mut [Genome<G>; 2],
        rng: &mut impl Rng,
    ) -> Result<(), OptimizeError> {
        let limits = *ops.limits();
        let fits = |g: &Genome<G>| (limits.min_len..limits.max_len).contains(&(g.len() as u32));
        let mut filled = 0;
        for _ in 0..ORIGINAL_BREEDS_PER_PAIR {
            let (i1, i2) = self.parents(rng);
            let (p1, p2) = (&self.population[i1], &self.population[i2]);
            let [c, d] = kids;
            let bred = if self.mutates(rng) {
                c.clone_from(p1);
                self.mutate(ops, c, rng);
                d.clone_from(p2);
                self.mutate(ops, d, rng);
                true
            } else {
                ops.crossover_into(p1, p2, c, d, rng)
            };
            if !bred {
                continue;
            }
            for (kid, parent) in kids.iter_mut().zip([i1, i2]) {
                if !fits(kid) {
                    continue;
                }
                std::mem::swap(kid, &mut slots[filled]);
                from[filled] = parent as u32;
                filled += 1;
                if filled == slots.len() {
                    return Ok(());
                }
            }
        }
        Err(SettingsError::new(
            "limits",
            format!("min_len {} and max_len {}", limits.min_len, limits.max_len),
            "a length window [min_len, max_len) that bred children fall in: 10 000 \
             breedings did not fill one pair of slots",
        )
        .into())
    }

    /// The two parents of a pair, chosen as [`GaSettings::selection`] says.
    fn parents(&self, rng: &mut impl Rng) -> (usize, usize) {
        match self.settings.selection {
            ParentSelection::TournamentRoulette => (self.tournament(rng), self.roulette.spin(rng)),
            ParentSelection::Tournament => (self.tournament(rng), self.tournament(rng)),
            ParentSelection::Roulette => (self.roulette.spin(rng), self.roulette.spin(rng)),
            ParentSelection::Random => {
                let n = self.population.len();
                (rng.random_range(0..n), rng.random_range(0..n))
            }
        }
    }

    /// Best of `tournament` individuals drawn uniformly with replacement (the first drawn
    /// wins ties); with the original's rules, drawn among all but the worst-ranked.
    fn tournament(&self, rng: &mut impl Rng) -> usize {
        let mut best = self.entrant(rng);
        for _ in 1..self.settings.tournament {
            let i = self.entrant(rng);
            if compare(self.fitness[i], self.fitness[best]).is_gt() {
                best = i;
            }
        }
        best
    }

    /// One tournament entrant, drawn uniformly; with the original's rules, among all but
    /// the worst-ranked individual.
    fn entrant(&self, rng: &mut impl Rng) -> usize {
        let n = self.population.len();
        match self.settings.operators {
            OperatorVariant::Weighted => rng.random_range(0..n),
            OperatorVariant::Original => {
                let i = rng.random_range(0..n - 1);
                i + usize::from(i >= self.worst as usize)
            }
        }
    }

    /// Whether a pair is mutated (rather than crossed over), with the mutation
    /// probability.
    fn mutates(&self, rng: &mut impl Rng) -> bool {
        rng.random::<f64>() < self.settings.mutation_probability
    }

    /// Which mutation to apply, grow / cut / alter by their weights.
    fn mutation(&self, rng: &mut impl Rng) -> Mutation {
        let s = self.settings;
        let r = rng.random::<f64>() * (s.grow_weight + s.cut_weight + s.alter_weight);
        if r < s.grow_weight {
            Mutation::Grow
        } else if r < s.grow_weight + s.cut_weight {
            Mutation::Cut
        } else {
            Mutation::Alter
        }
    }

    /// One mutation, grow / cut / alter by their weights.
    fn mutate(&self, ops: &mut Operators<G>, g: &mut Genome<G>, rng: &mut impl Rng) {
        match self.mutation(rng) {
            Mutation::Grow => ops.grow(g, rng),
            Mutation::Cut => ops.cut(g, rng),
            Mutation::Alter => ops.alter(g, rng),
        };
    }
}

/// The three mutations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mutation {
    Grow,
    Cut,
    Alter,
}

/// Selection and mutation rates, each on its own: statistical tests with fixed seeds,
/// tolerances stated with each (about 5 standard deviations of the estimate or more).
#[cfg(test)]
mod tests {
    use super::*;

    crate::generator! {
        /// A chain of blocks.
        pub Chain {
            axiom Seg;
            node Seg {
                children { next: Seg = 0.5 }
                derive(s) { s.emit(crate::CUBE); if let Some(n) = next { s.derive(n); } }
            }
        }
    }

    const DRAWS: usize = 100_000;

    /// A breeding context over `fitness`, with everything else from `settings`.
    fn check<R>(
        settings: GaSettings,
        fitness: &[f64],
        f: impl FnOnce(&Breed<'_, Chain>) -> R,
    ) -> R {
        let population: Vec<Genome<Chain>> = (0..fitness.len())
            .map(|i| Genome::axiom(&mut stream(1, 0, i as u64)))
            .collect();
        let mut roulette = Roulette::default();
        roulette.build(fitness);
        let mut order = Vec::new();
        rank(fitness, &mut order);
        let breed = Breed {
            settings: &settings,
            population: &population,
            fitness,
            roulette: &roulette,
            worst: *order.last().unwrap(),
        };
        f(&breed)
    }

    /// Counts of `draw` over [`DRAWS`] draws from one stream, as frequencies.
    fn frequencies(
        n: usize,
        mut draw: impl FnMut(&mut rand_chacha::ChaCha8Rng) -> usize,
    ) -> Vec<f64> {
        let rng = &mut stream(42, 1, 0);
        let mut counts = vec![0usize; n];
        for _ in 0..DRAWS {
            counts[draw(rng)] += 1;
        }
        counts.iter().map(|&c| c as f64 / DRAWS as f64).collect()
    }

    #[test]
    fn a_tournament_returns_the_best_of_its_entrants() {
        let fitness = [
            3.0,
            f64::NAN,
            7.0,
            -1.0,
            7.0,
            0.5,
            2.0,
            f64::INFINITY,
            4.0,
            1.0,
        ];
        for operators in OperatorVariant::ALL {
            for k in [1, 2, 3, 10] {
                let settings = GaSettings {
                    tournament: k,
                    operators,
                    ..GaSettings::default()
                };
                check(settings, &fitness, |breed| {
                    let rng = &mut stream(5, 2, u64::from(k));
                    for _ in 0..2_000 {
                        // The same draws, replayed: the entrants, then the winner.
                        let mut replay = rng.clone();
                        let entrants: Vec<usize> =
                            (0..k).map(|_| breed.entrant(&mut replay)).collect();
                        let winner = breed.tournament(rng);
                        let best = entrants.iter().copied().fold(entrants[0], |b, i| {
                            if compare(fitness[i], fitness[b]).is_gt() {
                                i
                            } else {
                                b
                            }
                        });
                        assert_eq!(winner, best, "{operators:?}, k = {k}: {entrants:?}");
                        // The original's never draws the worst-ranked (the NaN, index 1).
                        if operators == OperatorVariant::Original {
                            assert!(!entrants.contains(&1));
                        }
                    }
                });
            }
        }
    }

    #[test]
    fn a_tournament_of_k_picks_rank_r_as_often_as_order_statistics_say() {
        // Ten distinct values, k = 3 with replacement: the best of three uniform draws
        // has rank r (0: best) with probability ((10 - r)^3 - (9 - r)^3) / 1000.
        let fitness: Vec<f64> = (0..10).map(|i| f64::from(i) * 1.5).collect();
        let settings = GaSettings {
            tournament: 3,
            ..GaSettings::default()
        };
        let freq = check(settings, &fitness, |breed| {
            frequencies(10, |rng| breed.tournament(rng))
        });
        for (i, &got) in freq.iter().enumerate() {
            let r = 9 - i as i32;
            let want = f64::from((10 - r).pow(3) - (9 - r).pow(3)) / 1000.0;
            // The standard deviation of an estimate is at most 0.0016.
            assert!((got - want).abs() < 0.008, "index {i}: {got} vs {want}");
        }
    }

    #[test]
    fn roulette_frequencies_follow_fitness_above_the_minimum() {
        let fitness = [1.0, 2.0, 4.0, 8.0, f64::NAN, 3.0];
        // Weights f - f_min: 0, 1, 3, 7, NaN 0, 2; sum 13.
        let want = [0.0, 1.0, 3.0, 7.0, 0.0, 2.0].map(|w| w / 13.0);
        let freq = check(GaSettings::default(), &fitness, |breed| {
            frequencies(6, |rng| breed.roulette.spin(rng))
        });
        for (i, (&got, &want)) in freq.iter().zip(&want).enumerate() {
            // At most 0.0016 of standard deviation; the zero weights are never drawn.
            assert!((got - want).abs() < 0.008, "index {i}: {got} vs {want}");
            if want == 0.0 {
                assert_eq!(got, 0.0, "index {i}");
            }
        }
    }

    #[test]
    fn each_selection_scheme_draws_both_parents_at_its_rates() {
        // Five distinct values; rank r (0: best) wins a 2-tournament with probability
        // ((5 - r)^2 - (4 - r)^2) / 25; roulette weights f - f_min are 0, 4, 1, 3, 2 of 10.
        let fitness = [1.0, 5.0, 2.0, 4.0, 3.0];
        let rank_of = [4, 0, 3, 1, 2];
        let tournament = rank_of.map(|r: i32| f64::from((5 - r).pow(2) - (4 - r).pow(2)) / 25.0);
        let roulette = [0.0, 0.4, 0.1, 0.3, 0.2];
        let uniform = [0.2; 5];
        for (selection, want) in [
            (ParentSelection::TournamentRoulette, [tournament, roulette]),
            (ParentSelection::Tournament, [tournament, tournament]),
            (ParentSelection::Roulette, [roulette, roulette]),
            (ParentSelection::Random, [uniform, uniform]),
        ] {
            let settings = GaSettings {
                tournament: 2,
                selection,
                ..GaSettings::default()
            };
            check(settings, &fitness, |breed| {
                for (parent, want) in want.iter().enumerate() {
                    let freq = frequencies(5, |rng| {
                        let (a, b) = breed.parents(rng);
                        [a, b][parent]
                    });
                    for (i, (&got, &want)) in freq.iter().zip(want).enumerate() {
                        // The standard deviation of an estimate is at most 0.0016.
                        assert!(
                            (got - want).abs() < 0.008,
                            "{selection:?}, parent {parent}, index {i}: {got} vs {want}"
                        );
                    }
                }
            });
        }
        // The default draws exactly as the paper's breeding always has: a tournament,
        // then a spin of the wheel, from the same stream.
        check(GaSettings::default(), &fitness, |breed| {
            let rng = &mut stream(9, 3, 0);
            for _ in 0..1_000 {
                let mut replay = rng.clone();
                let want = (
                    breed.tournament(&mut replay),
                    breed.roulette.spin(&mut replay),
                );
                assert_eq!(breed.parents(rng), want);
            }
        });
    }

    #[test]
    fn mutation_probability_and_weights_show_at_their_rates() {
        let settings = GaSettings {
            mutation_probability: 0.3,
            grow_weight: 45.0,
            cut_weight: 35.0,
            alter_weight: 20.0,
            ..GaSettings::default()
        };
        check(settings, &[1.0, 2.0], |breed| {
            let mutated = frequencies(2, |rng| usize::from(breed.mutates(rng)));
            // Standard deviation about 0.0015.
            assert!((mutated[1] - 0.3).abs() < 0.008, "{mutated:?}");
            let kinds = frequencies(3, |rng| breed.mutation(rng) as usize);
            for (got, want) in kinds.iter().zip([0.45, 0.35, 0.20]) {
                assert!((got - want).abs() < 0.008, "{kinds:?}");
            }
        });
    }

    #[test]
    fn children_are_mutated_copies_at_the_mutation_rate() {
        // Parents of different lengths, so that a child's origin shows: with mutation
        // probability 0 every pair is crossed over (lengths add up to the parents'), with
        // 1 and only grow every child is its parent grown by at least one gene.
        let limits = Limits::new(1, 60, 60).unwrap();
        let mut ops = Operators::<Chain>::new(limits).unwrap();
        let population: Vec<Genome<Chain>> = [3, 9]
            .iter()
            .map(|&n| {
                let mut g = Genome::axiom(&mut stream(1, 0, 0));
                ops.grow_to(&mut g, n, &mut stream(1, 0, 1));
                g
            })
            .collect();
        assert_eq!([population[0].len(), population[1].len()], [3, 9]);
        let fitness = [1.0, 2.0];
        let mut roulette = Roulette::default();
        roulette.build(&fitness);
        for (p, grow) in [(0.0, 1.0), (1.0, 1.0)] {
            let settings = GaSettings {
                mutation_probability: p,
                grow_weight: grow,
                cut_weight: 0.0,
                alter_weight: 0.0,
                tournament: 2,
                ..GaSettings::default()
            };
            let breed = Breed {
                settings: &settings,
                population: &population,
                fitness: &fitness,
                roulette: &roulette,
                worst: 0,
            };
            let mut children: Vec<Genome<Chain>> =
                (0..200).map(|_| population[0].clone()).collect();
            let mut from = vec![u32::MAX; children.len()];
            breed
                .children(&ops, 3, 1, &mut children, &mut from)
                .unwrap();
            assert!(
                from.iter().all(|&f| (f as usize) < population.len()),
                "{from:?}"
            );
            for pair in children.chunks(2) {
                let lens = (pair[0].len(), pair[1].len());
                if p == 0.0 {
                    assert!([6, 12, 18].contains(&(lens.0 + lens.1)), "{lens:?}");
                } else {
                    assert!(lens.0 > 3 && lens.1 > 3, "{lens:?}");
                }
            }
        }
    }
}
