//! The island model: several GA populations ("islands") evolving side by side, the best
//! few of each sent along a ring to the next every few generations ([`IslandGa`]), on
//! one process or spread over several ([`Exchange`]).
//!
//! # Design
//!
//! Island `k` of `K` is the paper's GA ([`Ga`](super::Ga)) with the run's settings,
//! drawing from its own random streams (the run's seed for island 0, a seed derived
//! from it and `k` for the others). All islands of a process breed their children, then
//! the children of all of them are evaluated in one call, so that incremental scoring
//! keeps every island's models and the threads share the work. After every `interval`
//! generations each island sends copies of its `migrants` best individuals, with their
//! fitness, to the next island on the ring (the last to the first), where they replace
//! the worst.
//!
//! Spread over `P` processes (`K` a multiple of `P`), process `r` holds islands
//! `r K / P ..` of them, and the processes exchange, through an [`Exchange`]:
//! - every generation, each island's fitness values and (when it beats the best so
//!   far) the process's best model, so that every process records the same history
//!   and best as one process holding all the islands would;
//! - at a migration, the migrants of each process's last island, to the next process;
//! - before every generation, the decisions to stop or save ([`Optimizer::agree`]): a
//!   stop flag set on any process stops all of them, and rank 0's clock decides saves
//!   and wall-time budgets;
//! - at a checkpoint, every island's population, gathered at rank 0.
//!
//! Every random choice depends only on the seed, the island and the generation, and
//! every record is computed over all islands in island order, so a run gives the same
//! result on any number of processes that divides `K`, and at any thread count.

pub(super) mod exchange;
mod wire;

use crate::optimize::settings::generations_field;
use std::fmt;

use serde::{Deserialize, Serialize};

pub use exchange::{Alone, Exchange, ExchangeError};

use super::best::Best;
use super::core::Core;
use super::driver::resume_with;
use super::driver::{Agreement, Held, Optimizer, Record};
use super::error::check_sizes;
use super::error::{OptimizeError, SettingsError, check_positive};
use super::fitness::{bits_vec, compare, rank};
use super::ga::GaSettings;
use super::ga::{Breeder, Generation, Parents, check_population};
use super::run::{StopReason, derived_seed, grammar_struct_traits};
use super::settings::Settings;
use crate::derive::Grammar;
use crate::evaluate::{Bred, Evaluator};
use crate::genome::{Genome, Limits};
use wire::{Reader, Writer};

/// How many islands, and how they migrate: the scene's `[islands]` table. Missing
/// fields take the [`Default`] values, unknown fields are errors.
///
/// ```
/// use shapegen_runtime::optimize::islands::IslandSettings;
///
/// let s: IslandSettings = serde_json::from_str(r#"{"count": 8, "migrants": 3}"#)?;
/// assert_eq!((s.count, s.migrants, s.interval), (8, 3, 10));
/// # Ok::<(), serde_json::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct IslandSettings {
    /// Islands, each a population of the GA's size; at least 1. One island is the GA.
    pub count: u32,
    /// Individuals each island sends to the next at each migration; less than the
    /// population. 0 keeps the islands apart.
    pub migrants: u32,
    /// Generations between migrations; at least 1.
    pub interval: u64,
}

impl Default for IslandSettings {
    fn default() -> Self {
        IslandSettings {
            count: 4,
            migrants: 2,
            interval: 10,
        }
    }
}

/// Settings of the [`IslandGa`]: every island's GA settings, and the islands'.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IslandGaSettings {
    /// Each island's GA.
    pub ga: GaSettings,
    /// How many islands, and how they migrate.
    pub islands: IslandSettings,
}

impl Settings for IslandGaSettings {
    generations_field!("generations", ga.generations);

    /// Its GA's.
    fn kept_limits(&self, limits: Limits) -> Limits {
        self.ga.kept_limits(limits)
    }

    /// Checks every field; the error names the first one out of range (the islands'
    /// under `islands.`).
    ///
    /// ```
    /// use shapegen_runtime::optimize::{GaSettings, Settings};
    /// use shapegen_runtime::optimize::islands::{IslandGaSettings, IslandSettings};
    ///
    /// let ga = GaSettings { population: 50, elitism: 10, ..GaSettings::default() };
    /// let islands = IslandSettings { migrants: 50, ..IslandSettings::default() };
    /// let err = IslandGaSettings { ga, islands }.validate().unwrap_err();
    /// assert_eq!(err.field, "islands.migrants");
    /// ```
    fn validate(&self) -> Result<(), SettingsError> {
        self.ga.validate()?;
        super::polish::refuse(
            self.ga.polish,
            "0 in the island model (run the GA or the hybrid on one island to polish)",
        )?;
        let islands = &self.islands;
        check_positive("islands.count", islands.count)?;
        if islands.migrants >= self.ga.population {
            return Err(SettingsError::new(
                "islands.migrants",
                islands.migrants,
                "less than the population",
            ));
        }
        check_positive("islands.interval", islands.interval)?;
        Ok(())
    }
}

/// One island's population and its fitness, as checkpoints hold it.
#[derive(Serialize, Deserialize)]
#[serde(
    deny_unknown_fields,
    bound(serialize = "G: Grammar", deserialize = "G: Grammar")
)]
pub struct Island<G> {
    /// The population, best first after the first generation.
    pub population: Vec<Genome<G>>,
    /// Its cached fitness.
    #[serde(with = "bits_vec")]
    pub fitness: Vec<f64>,
}

grammar_struct_traits!(Island {
    population,
    fitness
});

crate::checkpoint! {
    /// A checkpoint of an [`IslandGa`]: serialize it and give it to [`IslandGa::resume`]
    /// (or [`IslandGa::resume_on`], on any number of processes that divides the islands)
    /// to go on exactly as an uninterrupted run would. Its progress is over all islands.
    pub struct IslandGaState<G>: IslandGaSettings, Best<G> {
        /// Every island, in order; empty before the first generation. On processes other
        /// than rank 0 of a run spread over several, only this process's islands.
        pub islands: Vec<Island<G>>,
    }
}

/// The island model (see the [module documentation](self)): `K` GA populations on a
/// ring, migrating their best every few generations.
///
/// Evaluations count every island's, on every process: a generation costs
/// `K (population - elitism)` evaluations, the initial one `K population`. With one
/// island it is the [`Ga`](super::Ga), to the bit.
///
/// ```
/// use shapegen_runtime::optimize::islands::{IslandGa, IslandGaSettings, IslandSettings};
/// use shapegen_runtime::optimize::{Budget, FnEvaluator, GaSettings, Optimizer, Silent};
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
/// // Four islands of 20 chains, two migrants every 5 generations: look for 12 blocks.
/// let ga = GaSettings { population: 20, elitism: 4, initial_length: 4, ..GaSettings::default() };
/// let islands = IslandSettings { count: 4, migrants: 2, interval: 5 };
/// let mut run = IslandGa::<Chain>::new(IslandGaSettings { ga, islands }, Limits::new(1, 30, 30)?, 7)?;
/// let mut eval = FnEvaluator(|g: &Genome<Chain>| -(g.len() as f64 - 12.0).abs());
/// let result = run.run(&mut eval, &Budget::generations(30), &mut Silent)?;
/// assert_eq!(result.best.len(), 12);
/// assert_eq!(result.evaluations, 4 * 20 + 30 * 4 * 16);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct IslandGa<G> {
    core: Core<IslandGaSettings, Best<G>>,
    /// This process's islands, one after the other, with their fitness; its `from`
    /// indexes the whole population.
    breeder: Breeder<G>,
    exchange: Box<dyn Exchange>,
    /// The first island this process holds.
    first: usize,
    /// This process's children of a generation, island after island, and their fitness.
    children: Vec<Genome<G>>,
    child_fitness: Vec<f64>,
    /// What the last generation was over all islands, as every process records it.
    whole: Whole<G>,
}

/// The last generation over all islands: every island's fitness, in island order, and
/// the best model of it when it beats the best so far (the first of equals).
struct Whole<G> {
    fitness: Vec<f64>,
    best: Option<(Genome<G>, f64)>,
}

impl<G: Grammar> fmt::Debug for IslandGa<G> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.core
            .debug(f, "IslandGa")
            .field("rank", &self.exchange.rank())
            .field("processes", &self.exchange.size())
            .finish_non_exhaustive()
    }
}

impl<G: Grammar> IslandGa<G> {
    /// An island model whose islands are spread over the processes of `exchange`; fails
    /// if the settings are out of range, do not fit the limits, or the islands are not
    /// a multiple of the processes.
    pub fn new_on(
        settings: IslandGaSettings,
        limits: Limits,
        seed: u64,
        exchange: Box<dyn Exchange>,
    ) -> Result<Self, OptimizeError> {
        settings.validate()?;
        let (count, processes) = (settings.islands.count as usize, exchange.size());
        if processes == 0 || !count.is_multiple_of(processes) {
            return Err(SettingsError::new(
                "islands.count",
                count,
                "a multiple of the number of processes the run is spread over",
            )
            .into());
        }
        let local = count / processes;
        let children = local * settings.ga.children() as usize;
        Ok(IslandGa {
            breeder: Breeder::new(&settings.ga, limits, local, 1)?,
            core: Core::new(settings, limits, seed),
            first: exchange.rank() * local,
            exchange,
            children: (0..children)
                .map(|_| Genome::from_parts(Vec::new(), 0))
                .collect(),
            child_fitness: vec![f64::NAN; children],
            whole: Whole {
                fitness: Vec::new(),
                best: None,
            },
        })
    }

    /// Resumes from a checkpoint holding every island, on the processes of `exchange`
    /// (any number that divides the islands, whatever number saved it).
    pub fn resume_on(
        state: IslandGaState<G>,
        exchange: Box<dyn Exchange>,
    ) -> Result<Self, OptimizeError> {
        resume_with(state, |settings, limits, seed| {
            IslandGa::new_on(settings, limits, seed, exchange)
        })
    }

    /// The number of islands this process holds.
    fn islands(&self) -> usize {
        self.core.settings.islands.count as usize / self.exchange.size()
    }

    /// Island `k` of this process (from 0): its genomes and their fitness.
    fn island(&self, k: usize) -> Parents<'_, G> {
        let n = self.core.settings.ga.population as usize;
        let fitness = &self.breeder.scores[k * n..(k + 1) * n];
        Parents {
            population: &self.breeder.population[k * n..(k + 1) * n],
            fitness,
            scores: fitness,
        }
    }

    /// Sends every island's `migrants` best, with their fitness, to the next island on
    /// the ring, where they replace the worst; the last island of this process sends to
    /// the first of the next process.
    fn migrate(&mut self) -> Result<(), OptimizeError> {
        let (m, n) = (
            self.core.settings.islands.migrants as usize,
            self.core.settings.ga.population as usize,
        );
        let local = self.islands();
        // Each island's ranking, best first, before any migrant lands.
        let ranked: Vec<Vec<u32>> = (0..local)
            .map(|k| {
                let mut order = Vec::with_capacity(n);
                rank(self.island(k).fitness, &mut order);
                order
            })
            .collect();
        let emigrants = |k: usize| -> Vec<(Genome<G>, f64)> {
            let island = self.island(k);
            ranked[k][..m]
                .iter()
                .map(|&i| {
                    (
                        island.population[i as usize].clone(),
                        island.fitness[i as usize],
                    )
                })
                .collect()
        };
        let leaving = emigrants(local - 1);
        let mut message = Writer::default();
        message.genomes(leaving.iter().map(|(g, _)| g));
        message.f64s(&leaving.iter().map(|&(_, f)| f).collect::<Vec<_>>());
        let bytes = self.exchange.shift(message.finish())?;
        let mut reader = Reader::new(&bytes);
        let (genomes, fitness) = (reader.genomes::<G>()?, reader.f64s()?);
        reader.end()?;
        check_sizes(
            &[
                (genomes.len(), m, "migrants"),
                (fitness.len(), m, "fitness values"),
            ],
            "a migration",
        )?;
        let mut arriving: Vec<Vec<(Genome<G>, f64)>> = Vec::with_capacity(local);
        arriving.push(genomes.into_iter().zip(fitness).collect());
        arriving.extend((0..local - 1).map(emigrants));
        for (k, (migrants, order)) in arriving.into_iter().zip(&ranked).enumerate() {
            for ((genome, f), &i) in migrants.into_iter().zip(&order[n - m..]) {
                self.breeder.population[k * n + i as usize] = genome;
                self.breeder.scores[k * n + i as usize] = f;
            }
        }
        Ok(())
    }

    /// Gathers the generation over all islands from every process into `whole`.
    fn share(&mut self) -> Result<(), OptimizeError> {
        let record = &self.core.progress.record;
        let (population, fitness) = (&self.breeder.population, &self.breeder.scores);
        let local_best = super::fitness::best_index(fitness)
            .filter(|&i| record.best.is_none() || compare(fitness[i], record.best_fitness).is_gt());
        let mut message = Writer::default();
        message.f64s(fitness);
        message.genomes(local_best.map(|i| &population[i]).into_iter());
        let gathered = self.exchange.all_gather(message.finish())?;
        self.whole.fitness.clear();
        self.whole.best = None;
        for bytes in &gathered {
            let mut reader = Reader::new(bytes);
            let fitness = reader.f64s()?;
            let best = reader.genomes::<G>()?;
            reader.end()?;
            if let Some(genome) = best.into_iter().next() {
                let f = super::fitness::best_index(&fitness)
                    .map(|i| fitness[i])
                    .ok_or_else(|| ExchangeError("a best model without fitness values".into()))?;
                if self
                    .whole
                    .best
                    .as_ref()
                    .is_none_or(|(_, best)| compare(f, *best).is_gt())
                {
                    self.whole.best = Some((genome, f));
                }
            }
            self.whole.fitness.extend(fitness);
        }
        check_sizes(
            &[(
                self.whole.fitness.len(),
                self.core.settings.islands.count as usize
                    * self.core.settings.ga.population as usize,
                "fitness values",
            )],
            "all islands",
        )
    }

    /// This process's islands, as a checkpoint holds them.
    fn own_islands(&self) -> Vec<Island<G>> {
        (0..self.islands())
            .map(|k| {
                let island = self.island(k);
                Island {
                    population: island.population.to_vec(),
                    fitness: island.fitness.to_vec(),
                }
            })
            .collect()
    }

    /// Every island, gathered at rank 0 (only this process's elsewhere).
    fn gather_islands(&self) -> Result<Vec<Island<G>>, ExchangeError> {
        let own = self.own_islands();
        if self.exchange.size() == 1 {
            return Ok(own);
        }
        let mut message = Writer::default();
        for island in &own {
            message
                .genomes(island.population.iter())
                .f64s(&island.fitness);
        }
        let Some(all) = self.exchange.gather(message.finish())? else {
            return Ok(own);
        };
        let mut islands = Vec::with_capacity(self.core.settings.islands.count as usize);
        for bytes in &all {
            let mut reader = Reader::new(bytes);
            for _ in 0..self.islands() {
                islands.push(Island {
                    population: reader.genomes()?,
                    fitness: reader.f64s()?,
                });
            }
            reader.end()?;
        }
        Ok(islands)
    }
}

impl<G: Grammar> Optimizer<G> for IslandGa<G> {
    type Settings = IslandGaSettings;
    type State = IslandGaState<G>;
    type Record = Best<G>;

    /// Every island's GA (all of them, as one process runs them).
    fn genomes_held(settings: &IslandGaSettings) -> Vec<Held> {
        vec![settings.ga.held(settings.islands.count.into())]
    }

    /// An island model on one process.
    fn new(settings: IslandGaSettings, limits: Limits, seed: u64) -> Result<Self, OptimizeError> {
        IslandGa::new_on(settings, limits, seed, Box::new(Alone))
    }

    fn core(&self) -> &Core<IslandGaSettings, Best<G>> {
        &self.core
    }

    /// The core, with this process's islands and their fitness.
    fn parts(&mut self) -> (&mut Core<IslandGaSettings, Best<G>>, &[Genome<G>], &[f64]) {
        self.breeder.parts(&mut self.core)
    }

    /// Every island at rank 0 (see [`IslandGaState`]).
    ///
    /// On a run spread over several processes this gathers the islands, so every
    /// process must call it at the same point, as a [`Session`](super::Session) does.
    ///
    /// # Panics
    /// If the exchange fails while gathering (an MPI error ends the processes anyway).
    fn save_body(&self) -> (Vec<Island<G>>,) {
        if !self.core.progress.record.started() {
            return (Vec::new(),);
        }
        let islands = self
            .gather_islands()
            .unwrap_or_else(|err| panic!("gathering the islands for a checkpoint: {err}"));
        (islands,)
    }

    /// Counts the islands first, then each one's genomes and fitness values.
    fn check_body(state: &IslandGaState<G>) -> Result<(), OptimizeError> {
        let count = state.settings.islands.count as usize;
        check_sizes(
            &[(state.islands.len(), count, "islands")],
            format_args!("a run of {count} islands"),
        )?;
        state
            .islands
            .iter()
            .enumerate()
            .try_for_each(|(k, island)| {
                let ga = &state.settings.ga;
                check_population(ga, &island.population, &island.fitness, Some(k))
            })
    }

    /// Takes this process's islands.
    fn restore_body(&mut self, (islands,): (Vec<Island<G>>,)) -> Result<(), OptimizeError> {
        let mine = islands.into_iter().skip(self.first).take(self.islands());
        let (population, fitness) = (&mut self.breeder.population, &mut self.breeder.scores);
        population.clear();
        fitness.clear();
        for island in mine {
            population.extend(island.population);
            fitness.extend(island.fitness);
        }
        Ok(())
    }

    fn resume(state: IslandGaState<G>) -> Result<Self, OptimizeError> {
        IslandGa::resume_on(state, Box::new(Alone))
    }

    fn step_cost(&self) -> u64 {
        u64::from(self.core.settings.islands.count) * self.core.settings.ga.children()
    }

    /// Records the generation over all islands, as gathered after it.
    fn record(&mut self) {
        let best = self.whole.best.as_ref().map(|(g, f)| (g, *f));
        Best::record_generation(&mut self.core.progress, best, &self.whole.fitness);
    }

    /// Stops if any process stops (the first reason by rank); saves when rank 0 saves
    /// and the run goes on (a run that stops saves at its end).
    fn agree(&mut self, local: Agreement) -> Result<Agreement, OptimizeError> {
        if self.exchange.size() == 1 {
            return Ok(local);
        }
        let code = local.stop.map_or(0, |reason| {
            1 + StopReason::ALL
                .iter()
                .position(|&r| r == reason)
                .expect("listed") as u64
        });
        let gathered = self
            .exchange
            .all_gather(Writer::default().u64(code).u64(local.save.into()).finish())?;
        let mut agreed = Agreement::default();
        for (r, bytes) in gathered.iter().enumerate() {
            let mut reader = Reader::new(bytes);
            let (code, save) = (reader.u64()?, reader.u64()?);
            reader.end()?;
            if agreed.stop.is_none() && code > 0 {
                agreed.stop = Some(
                    *StopReason::ALL
                        .get(code as usize - 1)
                        .ok_or_else(|| ExchangeError(format!("stop code {code}")))?,
                );
            }
            if r == 0 {
                agreed.save = save == 1;
            }
        }
        // A run that stops saves at its end.
        agreed.save &= agreed.stop.is_none();
        Ok(agreed)
    }

    fn start(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        let (settings, progress) = (&self.core.settings, &mut self.core.progress);
        self.breeder
            .start(&settings.ga, progress.seed, self.first, evaluator)?;
        progress.evaluations +=
            u64::from(settings.islands.count) * u64::from(settings.ga.population);
        self.share()
    }

    fn step(&mut self, evaluator: &mut (dyn Evaluator<G> + '_)) -> Result<(), OptimizeError> {
        let ga = self.core.settings.ga;
        let (n, e) = (ga.population as usize, ga.elitism as usize);
        let c = n - e;
        let (seed, generation) = (self.core.progress.seed, self.core.progress.generation + 1);
        let local = self.islands();
        let b = &mut self.breeder;
        for k in 0..local {
            let seed = derived_seed(seed, (self.first + k) as u64);
            let (elites, _) = b.next[k * n..(k + 1) * n].split_at_mut(e);
            let from = &mut b.from[k * c..(k + 1) * c];
            let fitness = &b.scores[k * n..(k + 1) * n];
            Generation {
                settings: &ga,
                ops: &b.ops,
                seed,
                generation,
            }
            .breed(
                Parents {
                    population: &b.population[k * n..(k + 1) * n],
                    fitness,
                    scores: fitness,
                },
                &mut b.order,
                &mut b.roulette,
                (elites, &mut b.next_scores[k * n..k * n + e]),
                (&mut self.children[k * c..(k + 1) * c], from),
            )?;
            from.iter_mut().for_each(|f| *f += (k * n) as u32);
        }
        evaluator.evaluate_bred(
            Bred {
                children: &self.children,
                parents: &b.population,
                from: &b.from,
            },
            &mut self.child_fitness,
        )?;
        for (i, (child, f)) in self
            .children
            .iter_mut()
            .zip(&self.child_fitness)
            .enumerate()
        {
            let at = (i / c) * n + e + i % c;
            std::mem::swap(&mut b.next[at], child);
            b.next_scores[at] = *f;
        }
        self.core.progress.evaluations += self.step_cost();
        self.breeder.advance();
        let islands = &self.core.settings.islands;
        if islands.count > 1 && islands.migrants > 0 && generation.is_multiple_of(islands.interval)
        {
            self.migrate()?;
        }
        self.share()
    }
}
