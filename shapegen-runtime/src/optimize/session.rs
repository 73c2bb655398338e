//! A run session: one optimizer run to its budget, with what a long-running command
//! needs around the loop: a stop flag (set by a Ctrl-C handler), a progress hook, and
//! checkpoints saved every few seconds and at the end.

use std::marker::PhantomData;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use super::driver::{Agreement, Optimizer, Record, drive};
use super::error::OptimizeError;
use super::run::{Budget, Control, Progress, StopReason};
use crate::derive::Grammar;
use crate::genome::Limits;

/// Why a [`Session`] failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SessionError {
    /// The optimizer could not start or go on.
    #[error(transparent)]
    Optimize(#[from] OptimizeError),
    /// The save hook failed.
    #[error("saving the run failed: {0}")]
    Save(Box<dyn std::error::Error + Send + Sync>),
}

/// What the save hook of a [`Session`] receives.
pub struct Save<'a, G: Grammar, O: Optimizer<G>> {
    /// The checkpoint to write, from which [`Session::resume`] goes on.
    pub state: O::State,
    /// The counters and the record (best so far or front, history), for the files a
    /// caller writes beside the checkpoint; the outcome so far is
    /// [`result`](Self::result).
    pub progress: &'a Progress<O::Record>,
    /// `None` for a save during the run; why the run stopped for the save at its end.
    pub stopped: Option<StopReason>,
}

impl<G: Grammar, O: Optimizer<G>> Save<'_, G, O> {
    /// The run's outcome as of this save (for a save during the run, as if it stopped
    /// here, its stop reason [`StopReason::Observer`]).
    pub fn result(&self) -> <O::Record as Record<G>>::Result {
        O::Record::result(self.progress, self.stopped.unwrap_or(StopReason::Observer))
    }
}

/// The save hook: the checkpoint and what else the caller writes.
type SaveHook<'s, G, O> =
    Box<dyn FnMut(Save<'_, G, O>) -> Result<(), Box<dyn std::error::Error + Send + Sync>> + 's>;

/// One optimizer run to its budget: checks a stop flag after every generation, calls a
/// progress hook after every generation, saves a checkpoint every
/// [`save_every`](Self::save_every) (1 s by default) and once at the end, whatever
/// stopped the run. Where saving is slow (large models written each time), saves space
/// out so that they take at most 5 % of the run: the next waits at least
/// [`SAVE_SPACING`] times as long as the last took. A session built with [`resume`](Self::resume) from a saved state
/// goes on and ends exactly as an uninterrupted run: the same best genome, fitness,
/// evaluations and history, wall times apart.
///
/// The run ends at the first of: the budget's generations, evaluations or wall time
/// (counted from the start of the optimization, across resumes), the stop flag, or the
/// progress hook returning [`Control::Stop`] (both [`StopReason::Observer`], named
/// `"interrupted"`).
///
/// ```
/// use std::sync::atomic::AtomicBool;
/// use shapegen_runtime::optimize::{
///     Budget, Control, FnEvaluator, Ga, GaSettings, GaState, Session, Snapshot, StopReason,
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
/// let settings = GaSettings { population: 20, elitism: 4, initial_length: 4, ..GaSettings::default() };
/// let limits = Limits::new(1, 30, 30)?;
/// let mut eval = FnEvaluator(|g: &Genome<Chain>| -(g.len() as f64 - 12.0).abs());
/// let stop = AtomicBool::new(false); // a Ctrl-C handler would set it
/// let mut saved: Option<GaState<Chain>> = None;
/// let mut generations = 0;
/// let mut count = |_: &Snapshot<'_, Chain>| {
///     generations += 1;
///     Control::Continue
/// };
/// let result = Session::<Chain, Ga<Chain>>::start(settings, limits, 7, Budget::generations(10))?
///     .stop_flag(&stop)
///     .on_progress(&mut count)
///     .on_save(|save| {
///         saved = Some(save.state);
///         Ok::<(), std::io::Error>(())
///     })
///     .run(&mut eval)?;
/// assert_eq!((result.stopped, result.stopped.name()), (StopReason::Generations, "generations"));
/// assert_eq!(generations, 11);
/// assert_eq!(saved.unwrap().progress.generation, 10);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Session<'s, G: Grammar, O: Optimizer<G>> {
    optimizer: O,
    budget: Budget,
    stop: Option<&'s AtomicBool>,
    save_every: Duration,
    save: Option<SaveHook<'s, G, O>>,
    observer: Option<&'s mut <O::Record as Record<G>>::Observer<'s>>,
    grammar: PhantomData<G>,
}

impl<G: Grammar, O: Optimizer<G>> std::fmt::Debug for Session<'_, G, O> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Session")
            .field("budget", &self.budget)
            .field("stop", &self.stop)
            .field("save_every", &self.save_every)
            .finish_non_exhaustive()
    }
}

impl<'s, G: Grammar, O: Optimizer<G>> Session<'s, G, O> {
    /// A session running `optimizer` (new or resumed) until `budget` stops it.
    pub fn new(optimizer: O, budget: Budget) -> Self {
        Session {
            optimizer,
            budget,
            stop: None,
            save_every: Duration::from_secs(1),
            save: None,
            observer: None,
            grammar: PhantomData,
        }
    }

    /// A session of a new optimizer ([`Optimizer::new`]).
    pub fn start(
        settings: O::Settings,
        limits: Limits,
        seed: u64,
        budget: Budget,
    ) -> Result<Self, OptimizeError> {
        Ok(Session::new(O::new(settings, limits, seed)?, budget))
    }

    /// A session going on from a checkpoint ([`Optimizer::resume`]).
    pub fn resume(state: O::State, budget: Budget) -> Result<Self, OptimizeError> {
        Ok(Session::new(O::resume(state)?, budget))
    }

    /// Stops the run after the generation during which `flag` is set.
    pub fn stop_flag(self, flag: &'s AtomicBool) -> Self {
        Session {
            stop: Some(flag),
            ..self
        }
    }

    /// Saves at most this often during the run (after the first generation that ends
    /// this long after the last save, or [`SAVE_SPACING`] times as long as the last save
    /// took, whichever is longer); 1 s by default. Zero saves after every generation,
    /// however long saving takes.
    pub fn save_every(self, interval: Duration) -> Self {
        Session {
            save_every: interval,
            ..self
        }
    }

    /// Saves through `save` during the run and at its end; an error stops the run and
    /// is returned as [`SessionError::Save`].
    pub fn on_save<E>(self, mut save: impl FnMut(Save<'_, G, O>) -> Result<(), E> + 's) -> Self
    where
        E: Into<Box<dyn std::error::Error + Send + Sync>>,
    {
        Session {
            save: Some(Box::new(move |s: Save<'_, G, O>| {
                save(s).map_err(Into::into)
            })),
            ..self
        }
    }

    /// Calls `observer` after every generation (the initial population's included); it
    /// may stop the run.
    pub fn on_progress(self, observer: &'s mut <O::Record as Record<G>>::Observer<'s>) -> Self {
        Session {
            observer: Some(observer),
            ..self
        }
    }

    /// The optimizer.
    pub fn optimizer(&self) -> &O {
        &self.optimizer
    }

    /// Runs to the end (see [`Session`]) and returns the outcome, whose `stopped` says
    /// why it ended; the last save has been made by then.
    pub fn run(
        mut self,
        evaluator: &mut <O::Record as Record<G>>::Evaluator<'_>,
    ) -> Result<<O::Record as Record<G>>::Result, SessionError> {
        let mut last_save = Instant::now();
        let (stop, base) = (self.stop, self.save_every);
        let mut every = base;
        let (save, observer, budget) = (&mut self.save, &mut self.observer, &self.budget);
        let stopped = drive(&mut self.optimizer, evaluator, budget, |o: &mut O| {
            let mut control = match observer {
                Some(observer) => O::Record::observe(o.progress(), observer),
                None => Control::Continue,
            };
            if stop.is_some_and(|s| s.load(Ordering::SeqCst)) {
                control = Control::Stop;
            }
            // When the run ends here, the save at the end follows at once.
            let p = o.progress();
            let ends = budget
                .stop(p.generation, p.evaluations, o.step_cost(), p.elapsed_s)
                .is_some();
            let agreed = o.agree(Agreement {
                stop: (control == Control::Stop).then_some(StopReason::Observer),
                save: control == Control::Continue && !ends && last_save.elapsed() >= every,
            })?;
            if agreed.save {
                let start = Instant::now();
                store(save, o, None)?;
                last_save = Instant::now();
                if !base.is_zero() {
                    every = base.max((last_save - start) * SAVE_SPACING);
                }
            }
            Ok::<_, SessionError>(match agreed.stop {
                Some(_) => Control::Stop,
                None => Control::Continue,
            })
        })?;
        store(&mut self.save, &self.optimizer, Some(stopped))?;
        Ok(O::Record::result(self.optimizer.progress(), stopped))
    }
}

/// How many times as long as the last save took a [`Session`] waits, at least, before
/// the next save during the run: saving then takes at most `1 / (1 + 19)`, 5 %, of it.
pub const SAVE_SPACING: u32 = 19;

/// Saves `optimizer` through `save`, if there is a hook.
fn store<G: Grammar, O: Optimizer<G>>(
    save: &mut Option<SaveHook<'_, G, O>>,
    optimizer: &O,
    stopped: Option<StopReason>,
) -> Result<(), SessionError> {
    match save {
        Some(save) => save(Save {
            state: optimizer.checkpoint(),
            progress: optimizer.progress(),
            stopped,
        })
        .map_err(SessionError::Save),
        None => Ok(()),
    }
}
