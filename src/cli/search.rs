//! One run of a method from the start to its budget, as `compare` and `sweep` run each of
//! theirs.

use std::sync::atomic::AtomicBool;

use shapegen::Grammar;
use shapegen::genome::Limits;
use shapegen::optimize::{Best, Budget, Optimizer, RunResult, Session};
use shapegen::scene::{MethodJob, SceneEvaluator};

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
