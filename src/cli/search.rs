//! From a scene's method to the optimizer type that runs it: the single-fitness methods
//! behind one generic call, so that the commands are written once for all of them.

use shapegen::Grammar;
use shapegen::optimize::islands::IslandGa;
use shapegen::optimize::{Best, Ga, Mcmc, Optimizer, Smc};
use shapegen::scene::{MethodSettings, OptimizerGoal};

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
    }
}
