//! Optimizers searching a grammar's derivation trees for models that score well:
//! the genetic algorithm ([`Ga`]) and sequential Monte Carlo in chromosome order or with
//! stochastic futures ([`Smc`], [`Order`]), and reversible-jump MCMC with parallel
//! tempering ([`Mcmc`]); and, in [`multi`], the multi-objective GA ([`multi::MultiGa`]) with
//! its selection on several objectives (Pareto fronts, summed rank, weighted sum).
//!
//! All are generic over the grammar and over an [`Evaluator`], which scores a whole
//! population at once. They share:
//! - [`Budget`]s of generations, evaluations and wall time (the first reached stops);
//! - an [`Observer`] called after every generation with a [`Snapshot`], which can stop
//!   the run;
//! - determinism: every random choice comes from a ChaCha8 stream fixed by the seed, the
//!   generation and the individual, so results never depend on the thread count;
//! - checkpoints ([`GaState`], [`SmcState`], [`McmcState`]; serde) from which a resumed
//!   run ends exactly as an uninterrupted one;
//! - a [`RunResult`] with the best genome and the per-generation history.
//!
//! Fitness is higher-is-better. NaN is the worst value everywhere: it ranks last, has
//! zero selection weight, is never accepted by a Metropolis test and never becomes the
//! best so far while any other value exists. `+inf` and `-inf` are ordinary extremes in
//! ranking; each method's documentation says how its weights treat them. Population
//! statistics (mean, std) are over the finite values.

mod error;
mod evaluate;
mod fitness;
mod ga;
mod grow;
mod mcmc;
pub mod multi;
mod run;
mod sense;
mod smc;

pub use error::{OptimizeError, SettingsError};
pub use evaluate::{EvaluateError, Evaluator, FnEvaluator};
pub use ga::{Ga, GaSettings, GaState};
pub use mcmc::{Mcmc, McmcSettings, McmcState, McmcVariant};
pub use run::{
    Budget, Control, HistoryEntry, Observer, Progress, RunResult, Silent, Snapshot, StopReason,
};
pub use sense::Sense;
pub use smc::{Cursor, Order, Smc, SmcSettings, SmcState, SmcVariant};
