//! The four search methods behind one face, for `shapegen run`: start, resume, run a
//! stretch of generations, save.

use serde::{Deserialize, Serialize};
use shapegen::Grammar;
use shapegen::genome::Limits;
use shapegen::optimize::Optimizer;
use shapegen::optimize::{
    Budget, Evaluator, Ga, GaState, Mcmc, McmcState, Observer, OptimizeError, RunResult, Smc,
    SmcState,
};
use shapegen::scene::{MethodSettings, OptimizerGoal};

/// A running search.
pub enum Search<G: Grammar> {
    /// The genetic algorithm.
    Ga(Ga<G>),
    /// SMC or SOSMC.
    Smc(Smc<G>),
    /// Reversible-jump MCMC.
    Mcmc(Mcmc<G>),
}

/// A saved search.
#[derive(Serialize, Deserialize)]
#[serde(bound(serialize = "G: Grammar", deserialize = "G: Grammar"))]
#[serde(rename_all = "snake_case")]
pub enum SearchState<G: Grammar> {
    /// The genetic algorithm.
    Ga(GaState<G>),
    /// SMC or SOSMC.
    Smc(SmcState<G>),
    /// Reversible-jump MCMC.
    Mcmc(McmcState<G>),
}

impl<G: Grammar> Search<G> {
    /// A new search as `goal` says, within `limits`.
    pub fn start(goal: &OptimizerGoal, limits: Limits) -> Result<Search<G>, OptimizeError> {
        Ok(match goal.settings {
            MethodSettings::Ga(s) => Search::Ga(Ga::new(s, limits, goal.seed)?),
            MethodSettings::Smc(s) => Search::Smc(Smc::new(s, limits, goal.seed)?),
            MethodSettings::Mcmc(s) => Search::Mcmc(Mcmc::new(s, limits, goal.seed)?),
        })
    }

    /// The search saved in `state`.
    pub fn resume(state: SearchState<G>) -> Result<Search<G>, OptimizeError> {
        Ok(match state {
            SearchState::Ga(s) => Search::Ga(Ga::resume(s)?),
            SearchState::Smc(s) => Search::Smc(Smc::resume(s)?),
            SearchState::Mcmc(s) => Search::Mcmc(Mcmc::resume(s)?),
        })
    }

    /// The search's state, to resume from.
    pub fn checkpoint(&self) -> SearchState<G> {
        match self {
            Search::Ga(m) => SearchState::Ga(m.checkpoint()),
            Search::Smc(m) => SearchState::Smc(m.checkpoint()),
            Search::Mcmc(m) => SearchState::Mcmc(m.checkpoint()),
        }
    }

    /// Runs until `budget` or `observer` stops it.
    pub fn run(
        &mut self,
        evaluator: &mut impl Evaluator<G>,
        budget: &Budget,
        observer: &mut impl Observer<G>,
    ) -> Result<RunResult<G>, OptimizeError> {
        match self {
            Search::Ga(m) => m.run(evaluator, budget, observer),
            Search::Smc(m) => m.run(evaluator, budget, observer),
            Search::Mcmc(m) => m.run(evaluator, budget, observer),
        }
    }
}

impl<G: Grammar> SearchState<G> {
    /// Generations done when it was saved.
    pub fn generation(&self) -> u64 {
        match self {
            SearchState::Ga(s) => s.progress.generation,
            SearchState::Smc(s) => s.progress.generation,
            SearchState::Mcmc(s) => s.progress.generation,
        }
    }
}
