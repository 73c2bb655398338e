//! The one search driver: the [`Optimizer`] trait every method implements, the
//! [`Record`] trait telling a run on one fitness from a run on objective vectors, and the
//! loop ([`drive`]) that runs any optimizer under a [`Budget`].
//!
//! # Design
//!
//! A method is one type implementing [`Optimizer`]: it builds and evaluates its initial
//! population ([`start`](Optimizer::start)), runs one generation
//! ([`step`](Optimizer::step)) and says how many evaluations the next generation may use
//! at most ([`step_cost`](Optimizer::step_cost)). What every method has, its settings,
//! the genome limits and its [`Progress`], is one [`Core`] that the method holds and
//! hands out ([`core`](Optimizer::core), [`parts`](Optimizer::parts)); a checkpoint is
//! that core and the method's own fields, its body, in a struct declared with
//! [`checkpoint!`](crate::checkpoint) ([`Checkpoint`]). The method only saves, checks and
//! restores its body ([`save_body`](Optimizer::save_body),
//! [`check_body`](Optimizer::check_body), [`restore_body`](Optimizer::restore_body)):
//! the provided [`checkpoint`](Optimizer::checkpoint) and [`resume`](Optimizer::resume)
//! do the rest, and the settings and progress accessors are provided too.
//! Everything else (budgets, generation counting, wall time across resumes, the history,
//! the best so far, the observer, the stop reasons) lives once, in [`drive`] and in the
//! method's [`Record`]. Adding a method is one file with one `impl Optimizer` and one
//! `checkpoint!`, plus its registration where the command-line tool lists the methods;
//! nothing in the trait is private to this crate, so other crates can add methods too
//! (see `tests/toy_optimizer.rs`).
//!
//! What a run records is the associated type [`Optimizer::Record`]: [`Best`] for one
//! fitness per individual (best genome, best / mean / std history, [`RunResult`](super::RunResult)) or
//! [`Front`](super::multi::Front) for `k` objective values per individual (per-objective
//! best, archive front, [`MultiResult`](super::multi::MultiResult)). The record also
//! names the evaluator and observer kinds, as trait objects (`dyn Evaluator<G>`,
//! `dyn MultiEvaluator<G>`; `dyn Observer<G>`, `dyn MultiObserver<G>`): the evaluator
//! kind is then fixed by the method (a GA cannot be handed a multi-objective evaluator
//! by mistake), the trait stays free of generic methods (so a session can own any
//! optimizer behind one type parameter), and the cost is one dynamic call per
//! generation, next to a whole population's evaluation. Callers pass `&mut evaluator`;
//! it coerces to the trait object.

use std::time::Instant;

use super::core::{Checkpoint, Core};
use super::error::OptimizeError;
use super::run::{Budget, Control, Progress, StopReason};
use super::settings::Settings;
use crate::derive::Grammar;
use crate::genome::{Genome, Limits};

/// What a kind of run records after every generation, and how it reports: one fitness
/// per individual ([`Best`](super::Best)) or an objective vector
/// ([`Front`](super::multi::Front)).
///
/// The record is the part of an optimizer's [`Progress`] that is not a counter; it holds
/// the per-generation history, and serializes inline with the counters.
pub trait Record<G: Grammar>: Clone + Default {
    /// The evaluator kind of this record's runs (a trait object).
    type Evaluator<'e>: ?Sized;
    /// The observer kind of this record's runs (a trait object), called after every
    /// generation.
    type Observer<'o>: ?Sized;
    /// The outcome of a run.
    type Result;

    /// Whether the initial population has been recorded.
    fn started(&self) -> bool;

    /// Called by the driver after every generation, the initial population's included,
    /// with the counters (generation, evaluations, elapsed time) already updated: takes
    /// in the current population and its scores (one value per individual, or `k`), and
    /// appends the generation's history entry.
    fn record(progress: &mut Progress<Self>, population: &[Genome<G>], scores: &[f64]);

    /// Shows the last recorded generation to `observer`; returns whether to go on.
    fn observe(progress: &Progress<Self>, observer: &mut Self::Observer<'_>) -> Control;

    /// The outcome of a run that stopped for `stopped`.
    fn result(progress: &Progress<Self>, stopped: StopReason) -> Self::Result;
}

/// Genomes a run holds at once, and the setting whose value makes their number
/// ([`Optimizer::genomes_held`]).
///
/// ```
/// use shapegen_runtime::optimize::{Ga, GaSettings, Held, Optimizer};
/// use shapegen_runtime::prelude::*;
///
/// generator! {
///     /// One block.
///     pub Chain { axiom Seg; node Seg { derive(s) { s.emit(CUBE); } } }
/// }
///
/// let settings = GaSettings { population: 100, ..GaSettings::default() };
/// let held = Ga::<Chain>::genomes_held(&settings);
/// assert_eq!(held[0].genomes, 300); // the population, the next generation, a checkpoint's copy
/// assert_eq!((held[0].saved, held[0].setting), (100, "optimizer.population"));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Held {
    /// How many genomes.
    pub genomes: u64,
    /// How many of them a checkpoint saves.
    pub saved: u64,
    /// The scene key that sets their number, e.g. `optimizer.population`.
    pub setting: &'static str,
    /// Its value.
    pub value: u64,
}

impl Held {
    /// `copies` genomes for each unit of `value`, the value of `setting`, of which a
    /// checkpoint saves `saved` for each unit.
    ///
    /// ```
    /// use shapegen_runtime::optimize::Held;
    ///
    /// // Each of 8 chains with its proposal and two more copies; checkpoints save the chains.
    /// let held = Held::per("optimizer.chains", 8, 4, 1);
    /// assert_eq!((held.genomes, held.saved, held.value), (32, 8, 8));
    /// ```
    pub fn per(setting: &'static str, value: u32, copies: u64, saved: u64) -> Held {
        let value = u64::from(value);
        Held {
            genomes: copies * value,
            saved: saved * value,
            setting,
            value,
        }
    }
}

/// A search method, as the driver ([`drive`], [`Session`](super::Session)) runs it.
///
/// Implementations keep a [`Core`] holding the [`Progress`] of their [`Record`]: the
/// driver advances the generation counter and the wall time and records each
/// generation; the method counts its evaluations in [`start`](Self::start) and
/// [`step`](Self::step). Random choices
/// should come from [`stream`](super::stream) (seed, generation, index), so that a
/// resumed run ends exactly as an uninterrupted one.
///
/// ```
/// use shapegen_runtime::optimize::{
///     Best, Budget, FnEvaluator, Ga, GaSettings, Optimizer, Silent, StopReason,
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
/// /// Any optimizer, on the same evaluator and budget.
/// fn search<O: Optimizer<Chain, Record = Best<Chain>>>(
///     settings: O::Settings,
/// ) -> Result<f64, Box<dyn std::error::Error>> {
///     let mut eval = FnEvaluator(|g: &Genome<Chain>| -(g.len() as f64 - 6.0).abs());
///     let mut optimizer = O::new(settings, Limits::new(1, 30, 30)?, 7)?;
///     let result = optimizer.run(&mut eval, &Budget::evaluations(400), &mut Silent)?;
///     assert_eq!(result.stopped, StopReason::Evaluations);
///     Ok(result.best_fitness)
/// }
///
/// let ga = GaSettings { population: 20, elitism: 4, initial_length: 3, ..GaSettings::default() };
/// assert_eq!(search::<Ga<Chain>>(ga)?, 0.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub trait Optimizer<G: Grammar>: Sized {
    /// The settings, as scene files give them.
    type Settings: Settings;
    /// A checkpoint, from which [`resume`](Self::resume) goes on exactly as an
    /// uninterrupted run would: the [`Core`] and the method's own fields, its body
    /// (declare it with [`checkpoint!`](crate::checkpoint)).
    type State: Checkpoint<Settings = Self::Settings, Record = Self::Record>;
    /// What the run records: [`Best`](super::Best) or [`Front`](super::multi::Front).
    type Record: Record<G>;

    /// The genomes a run with `settings` holds at once, at most, by the setting that
    /// sets their number: populations and their next generations, chains and their
    /// proposals, archives, and the copies a checkpoint takes. With the genome limits
    /// they bound the run's memory before it allocates anything (see
    /// `shapegen::scene::MemoryEstimate`); for a checkpoint, with the settings of
    /// [`Checkpoint::settings`].
    fn genomes_held(settings: &Self::Settings) -> Vec<Held>;

    /// An optimizer with these settings, keeping genomes within `limits`, seeded with
    /// `seed`; fails if the settings are out of range or do not fit the limits.
    fn new(settings: Self::Settings, limits: Limits, seed: u64) -> Result<Self, OptimizeError>;

    /// The settings, the genome limits and the progress.
    fn core(&self) -> &CoreOf<G, Self>;

    /// The core, mutably, with the current population and its scores (one value per
    /// individual for one fitness, `k` for objective vectors), as the driver records a
    /// generation.
    fn parts(&mut self) -> (&mut CoreOf<G, Self>, &[Genome<G>], &[f64]);

    /// The method's own fields of a checkpoint: copies of what [`restore_body`](
    /// Self::restore_body) puts back.
    fn save_body(&self) -> <Self::State as Checkpoint>::Body;

    /// Puts back the fields [`save_body`](Self::save_body) gave, into an optimizer just
    /// made by [`new`](Self::new) with the checkpoint's settings, limits and seed; called
    /// only for checkpoints of started runs, after [`check_body`](Self::check_body).
    fn restore_body(
        &mut self,
        body: <Self::State as Checkpoint>::Body,
    ) -> Result<(), OptimizeError>;

    /// Checks the body of a checkpoint of a started run against its settings (the sizes
    /// of its populations, say) before [`new`](Self::new) allocates anything for them,
    /// so that settings disagreeing with the checkpoint cannot make a resumed run
    /// allocate more than the checkpoint holds, nor restore buffers of the wrong size. By
    /// default there is nothing to check.
    fn check_body(state: &Self::State) -> Result<(), OptimizeError> {
        let _ = state;
        Ok(())
    }

    /// Resumes from a checkpoint; fails if it does not fit its own settings. By default:
    /// [`check_body`](Self::check_body) if the run had started, [`new`](Self::new),
    /// [`restore_body`](Self::restore_body) if it had started, and the progress put back.
    fn resume(state: Self::State) -> Result<Self, OptimizeError> {
        resume_with(state, Self::new)
    }

    /// The state to resume from: a copy of the core, and [`save_body`](Self::save_body).
    fn checkpoint(&self) -> Self::State {
        Self::State::from_parts(self.core().clone(), self.save_body())
    }

    /// The settings.
    fn settings(&self) -> &Self::Settings {
        &self.core().settings
    }

    /// The counters and the record.
    fn progress(&self) -> &Progress<Self::Record> {
        &self.core().progress
    }

    /// Evaluations the next [`step`](Self::step) may use at most.
    fn step_cost(&self) -> u64;

    /// Records the generation just run (the initial population's included) in the
    /// progress, whose counters and elapsed time the driver has updated. By default the
    /// record takes in the population and scores of [`parts`](Self::parts); an optimizer
    /// spread over several processes records what they hold together.
    ///
    /// A debug build checks that every genome recorded keeps the limits the method
    /// keeps ([`Settings::kept_limits`]): the record takes the best of them, whatever it
    /// is.
    fn record(&mut self) {
        let (core, population, scores) = self.parts();
        if cfg!(debug_assertions) {
            let kept = core.settings.kept_limits(core.limits);
            for (i, genome) in population.iter().enumerate() {
                if let Err(e) = genome.validate_limits(&kept) {
                    panic!("genome {i} is outside the limits its method keeps ({kept:?}): {e}");
                }
            }
        }
        Self::Record::record(&mut core.progress, population, scores);
    }

    /// Agrees with the other processes of a run spread over several on what happens
    /// before the next generation: whether the run stops, and why, and whether it saves
    /// a checkpoint. Every process calls it at the same points with what it would decide
    /// alone (`local`) and gets the decision all of them take. By default a run is one
    /// process, and the decision its own.
    fn agree(&mut self, local: Agreement) -> Result<Agreement, OptimizeError> {
        Ok(local)
    }

    /// Checks that `evaluator` fits this run, before every run (e.g. the objectives of
    /// a resumed multi-objective run); by default, any does.
    fn check(
        &self,
        evaluator: &mut <Self::Record as Record<G>>::Evaluator<'_>,
    ) -> Result<(), OptimizeError> {
        let _ = evaluator;
        Ok(())
    }

    /// Builds and evaluates the initial population, counting its evaluations in the
    /// progress.
    fn start(
        &mut self,
        evaluator: &mut <Self::Record as Record<G>>::Evaluator<'_>,
    ) -> Result<(), OptimizeError>;

    /// Runs one generation, counting its evaluations (the driver then advances the
    /// generation counter).
    fn step(
        &mut self,
        evaluator: &mut <Self::Record as Record<G>>::Evaluator<'_>,
    ) -> Result<(), OptimizeError>;

    /// Runs until `budget` or `observer` stops it; a later call goes on from there. For
    /// checkpoints between generations, a stop flag and saving, see
    /// [`Session`](super::Session).
    fn run(
        &mut self,
        evaluator: &mut <Self::Record as Record<G>>::Evaluator<'_>,
        budget: &Budget,
        observer: &mut <Self::Record as Record<G>>::Observer<'_>,
    ) -> Result<<Self::Record as Record<G>>::Result, OptimizeError> {
        let stopped = drive(self, evaluator, budget, |o: &mut Self| {
            let control = Self::Record::observe(o.progress(), observer);
            let agreed = o.agree(Agreement {
                stop: (control == Control::Stop).then_some(StopReason::Observer),
                save: false,
            })?;
            Ok::<_, OptimizeError>(match agreed.stop {
                Some(_) => Control::Stop,
                None => Control::Continue,
            })
        })?;
        Ok(Self::Record::result(self.progress(), stopped))
    }
}

/// The [`Core`] of an optimizer `O` searching grammar `G`: its settings, the genome
/// limits and its progress.
pub type CoreOf<G, O> = Core<<O as Optimizer<G>>::Settings, <O as Optimizer<G>>::Record>;

/// A decision the processes of a run take together between generations
/// ([`Optimizer::agree`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Agreement {
    /// Whether the run stops before the next generation, and why.
    pub stop: Option<StopReason>,
    /// Whether a checkpoint is saved now.
    pub save: bool,
}

/// The run loop every optimizer shares: checks the evaluator, starts the optimizer if it
/// has not started (recording the initial population), then, while `budget` allows the
/// next generation, steps it, advances the generation counter and records it; after
/// every recorded generation `after` sees the optimizer and may stop the run
/// ([`StopReason::Observer`]) or fail it. Wall time adds to the progress's, so it counts
/// across resumed runs. Returns why the run stopped.
///
/// Before each generation the budget is checked with the optimizer's
/// [`step_cost`](Optimizer::step_cost): a generation that could take the evaluation
/// count past the budget is not run. That decision goes through
/// [`Optimizer::agree`], so that the processes of a run spread over several stop
/// together.
pub fn drive<G, O, E>(
    optimizer: &mut O,
    evaluator: &mut <O::Record as Record<G>>::Evaluator<'_>,
    budget: &Budget,
    mut after: impl FnMut(&mut O) -> Result<Control, E>,
) -> Result<StopReason, E>
where
    G: Grammar,
    O: Optimizer<G>,
    E: From<OptimizeError>,
{
    optimizer.check(evaluator)?;
    let t0 = Instant::now();
    let base = optimizer.progress().elapsed_s;
    let elapsed = || base + t0.elapsed().as_secs_f64();
    let mut record = |optimizer: &mut O| {
        optimizer.parts().0.progress.elapsed_s = elapsed();
        optimizer.record();
        after(optimizer)
    };
    if !optimizer.progress().record.started() {
        optimizer.start(evaluator)?;
        if record(optimizer)? == Control::Stop {
            return Ok(StopReason::Observer);
        }
    }
    loop {
        let cost = optimizer.step_cost();
        let p = optimizer.progress();
        let local = Agreement {
            stop: budget.stop(p.generation, p.evaluations, cost, elapsed()),
            save: false,
        };
        if let Some(reason) = optimizer.agree(local)?.stop {
            optimizer.parts().0.progress.elapsed_s = elapsed();
            return Ok(reason);
        }
        optimizer.step(evaluator)?;
        optimizer.parts().0.progress.generation += 1;
        if record(optimizer)? == Control::Stop {
            return Ok(StopReason::Observer);
        }
    }
}

/// Resumes `state` as [`Optimizer::resume`] does, with the optimizer `new` makes from
/// the checkpoint's settings, limits and seed: for a method whose `new` takes more (the
/// processes an island model is spread over).
pub(crate) fn resume_with<G, O>(
    state: O::State,
    new: impl FnOnce(O::Settings, Limits, u64) -> Result<O, OptimizeError>,
) -> Result<O, OptimizeError>
where
    G: Grammar,
    O: Optimizer<G>,
{
    let started = state.progress().record.started();
    if started {
        O::check_body(&state)?;
    }
    let (core, body) = state.into_parts();
    let mut optimizer = new(core.settings, core.limits, core.progress.seed)?;
    if started {
        optimizer.restore_body(body)?;
    }
    optimizer.parts().0.progress = core.progress;
    Ok(optimizer)
}
