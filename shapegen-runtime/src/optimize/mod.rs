//! Optimizers searching a grammar's derivation trees for models that score well:
//! the genetic algorithm ([`Ga`]) and sequential Monte Carlo in chromosome order or with
//! stochastic futures ([`Smc`], [`Order`]), and reversible-jump MCMC with parallel
//! tempering ([`Mcmc`]); and, in [`multi`], the multi-objective GA ([`multi::MultiGa`]) with
//! its selection on several objectives (Pareto fronts, summed rank, weighted sum).
//!
//! Every method implements one public trait, [`Optimizer`] (settings as a serde type;
//! start, step, step cost; its settings, limits and progress in one [`Core`]; the fields
//! of its own that a checkpoint saves), and one loop, [`drive`], runs them all; see the
//! `driver` module's design notes on [`Optimizer`] and [`Record`]. A method's
//! [`Record`] says what a run keeps: one fitness per individual
//! ([`Best`]: best genome, best / mean / std history, [`RunResult`]) or an objective
//! vector ([`multi::Front`]: per-objective best and archive front,
//! [`multi::MultiResult`]). They share:
//! - the evaluator kinds, [`Evaluator`] (one fitness) and [`MultiEvaluator`] (objective
//!   vectors, with their [`Sense`]s), defined below this module in
//!   [`evaluate`](crate::evaluate) and re-exported here;
//! - [`Budget`]s of generations, evaluations and wall time (the first reached stops);
//! - an [`Observer`] (or [`multi::MultiObserver`]) called after every generation with a
//!   [`Snapshot`], which can stop the run;
//! - determinism: every random choice comes from a ChaCha8 [`stream`] fixed by the seed,
//!   the generation and the individual, so results never depend on the thread count;
//! - checkpoints ([`GaState`], [`SmcState`], [`McmcState`], [`HybridState`],
//!   [`multi::MultiGaState`], [`islands::IslandGaState`]; serde) from which a resumed
//!   run ends exactly as an uninterrupted one: each a [`Checkpoint`], the method's
//!   [`Core`] (settings, limits, and the shared counters in [`Progress`]) and its own
//!   fields, declared with [`checkpoint!`](crate::checkpoint);
//! - the island model ([`islands::IslandGa`]): GA populations on a ring, on one
//!   process or spread over several;
//! - a [`Session`] running one optimizer to its budget with a stop flag, a progress hook
//!   and checkpoints saved every few seconds and at the end, ending with a
//!   [`StopReason`].
//!
//! Fitness is higher-is-better. NaN is the worst value everywhere: it ranks last, has
//! zero selection weight, is never accepted by a Metropolis test and never becomes the
//! best so far while any other value exists. `+inf` and `-inf` are ordinary extremes in
//! ranking; each method's documentation says how its weights treat them. Population
//! statistics (mean, std) are over the finite values.

mod best;
mod core;
mod driver;
mod error;
mod fitness;
mod ga;
mod grow;
mod hybrid;
pub mod islands;
mod mcmc;
pub mod multi;
mod polish;
mod random;
mod run;
mod session;
mod settings;
mod smc;

pub use self::core::{Checkpoint, Core};
pub use crate::evaluate::{Bred, EvaluateError, Evaluator, FnEvaluator, MultiEvaluator, Sense};
pub use best::Best;
pub use driver::{Agreement, CoreOf, Held, Optimizer, Record, drive};
pub use error::{BufferSize, CheckpointError, OptimizeError, SettingsError};
pub use ga::{Ga, GaSettings, GaState, ParentSelection};
pub use hybrid::{Hybrid, HybridSettings, HybridState};
pub use mcmc::{Mcmc, McmcSettings, McmcState, McmcVariant};
pub use polish::{Coordinate, PolishState, SepCmaEs, polish_coordinates};
pub use random::{RandomSearch, RandomSearchSettings, RandomSearchState};
pub use run::{
    Budget, Control, HistoryEntry, Observer, Progress, RunResult, Silent, Snapshot, StopReason,
    stream,
};
pub use session::{SAVE_SPACING, Save, Session, SessionError};
pub use settings::Settings;
pub use smc::{Cursor, Order, Smc, SmcSettings, SmcState, SmcVariant};
