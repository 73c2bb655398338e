//! From a scene's method to the optimizer type that runs it: the single-fitness methods
//! behind one generic call, so that the commands are written once for all of them.

use std::sync::atomic::AtomicBool;

use shapegen::Grammar;
use shapegen::genome::Limits;
use shapegen::optimize::islands::IslandGa;
use shapegen::optimize::{Best, Budget, Ga, Hybrid, Mcmc, Optimizer, RunResult, Session, Smc};
use shapegen::scene::{MethodSettings, OptimizerGoal, SceneEvaluator};

/// Work generic over the optimizer that searches one fitness.
pub trait MethodJob<G: Grammar> {
    /// What the work returns.
    type Output;
    /// Does the work with optimizer `O`, whose settings the scene gives as `settings`.
    fn run<O: Optimizer<G, Record = Best<G>>>(self, settings: O::Settings) -> Self::Output;
}

/// Runs `job` with the optimizer of `goal`'s method: one arm per optimizer type.
pub fn with_method<G: Grammar, J: MethodJob<G>>(goal: &OptimizerGoal, job: J) -> J::Output {
    match goal.settings {
        MethodSettings::Ga(s) => job.run::<Ga<G>>(s),
        MethodSettings::Islands(s) => job.run::<IslandGa<G>>(s),
        MethodSettings::Smc(s) => job.run::<Smc<G>>(s),
        MethodSettings::Mcmc(s) => job.run::<Mcmc<G>>(s),
        MethodSettings::Hybrid(s) => job.run::<Hybrid<G>>(s),
    }
}

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
