//! The search methods on the command line: one run of a method from the start to its
//! budget, as `compare` and `sweep` run each of theirs, and the help of the options that
//! name methods.

use std::sync::atomic::AtomicBool;

use shapegen::Grammar;
use shapegen::genome::Limits;
use shapegen::optimize::{Best, Budget, Optimizer, RunResult, Session};
use shapegen::scene::{Method, MethodJob, SceneEvaluator};

/// One run from the start to `budget` in a [`Session`] that `stop` can interrupt, with
/// no progress shown and nothing saved on the way: a run of `compare` or of a `sweep`.
pub struct SessionRun<'a, 'b> {
    /// The run's seed.
    pub seed: u64,
    /// Its genome limits.
    pub limits: Limits,
    /// Where it stops.
    pub budget: Budget,
    /// Set to interrupt it (the result then says [`StopReason::Observer`](
    /// shapegen::optimize::StopReason::Observer)).
    pub stop: &'a AtomicBool,
    /// What scores its models.
    pub evaluator: &'a mut SceneEvaluator<'b>,
}

impl<G: Grammar> MethodJob<G> for SessionRun<'_, '_> {
    type Output = anyhow::Result<RunResult<G>>;

    fn run<O: Optimizer<G, Record = Best<G>>>(self, settings: O::Settings) -> Self::Output {
        let session = Session::<G, O>::start(settings, self.limits, self.seed, self.budget)?;
        Ok(session.stop_flag(self.stop).run(self.evaluator)?)
    }
}

/// The help of an option naming methods: what it does, and every method it may name.
pub fn method_help(what: &str) -> String {
    format!("{what}; the methods are {}", Method::names())
}
