//! Refinement: short RJMCMC chains from a population's best individuals, the moves of
//! the tempered variant, each kept when it loses nothing.

use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use super::super::fitness::{compare, rank};
use super::super::mcmc::{MoveScratch, propose};
use super::super::run::stream;
use crate::derive::Grammar;
use crate::evaluate::{Bred, Evaluator};
use crate::genome::Genome;
use crate::ops::Operators;
use crate::optimize::error::OptimizeError;

/// One generation's refinement: how many of the best individuals, and how many moves
/// each.
pub(super) struct Refinement<'a, G> {
    /// How many of the best individuals are refined.
    pub(super) count: usize,
    /// Moves each makes.
    pub(super) moves: u32,
    /// Chance that a move is a jump.
    pub(super) jump_probability: f64,
    /// The operators of the moves.
    pub(super) ops: &'a Operators<G>,
    /// The run's seed.
    pub(super) seed: u64,
    /// The generation refined.
    pub(super) generation: u64,
}

/// The chains' buffers, reused from generation to generation.
pub(super) struct Chains<G> {
    /// The index of each chain's individual in the population.
    chosen: Vec<u32>,
    proposals: Vec<Genome<G>>,
    proposal_fitness: Vec<f64>,
    rngs: Vec<ChaCha8Rng>,
    /// The population's ranks, best first.
    order: Vec<u32>,
}

impl<G: Grammar> Chains<G> {
    /// Buffers for `count` chains.
    pub(super) fn new(count: usize) -> Self {
        Chains {
            chosen: Vec::with_capacity(count),
            proposals: (0..count)
                .map(|_| Genome::from_parts(Vec::new(), 0))
                .collect(),
            proposal_fitness: vec![f64::NAN; count],
            rngs: Vec::with_capacity(count),
            order: Vec::new(),
        }
    }

    /// Refines the `count` best of `population` (ranked by `fitness`, the first of
    /// equals first) in place: each makes `moves` moves, chain `i`
    /// drawing from stream (seed, generation, 2^31 + `i`), and keeps a proposal that
    /// scores at least as well as its individual (not NaN). All chains' proposals of a
    /// move are scored together, bred from the population.
    pub(super) fn refine(
        &mut self,
        r: Refinement<'_, G>,
        evaluator: &mut (dyn Evaluator<G> + '_),
        (population, fitness): (&mut [Genome<G>], &mut [f64]),
    ) -> Result<(), OptimizeError> {
        let n = r.count.min(population.len());
        if n == 0 || r.moves == 0 {
            return Ok(());
        }
        rank(fitness, &mut self.order);
        self.chosen.clear();
        self.chosen.extend_from_slice(&self.order[..n]);
        self.rngs.clear();
        self.rngs
            .extend((0..n).map(|i| stream(r.seed, r.generation, (1 << 31) + i as u64)));
        for _ in 0..r.moves {
            let (chosen, current) = (&self.chosen, &*population);
            self.proposals[..n]
                .par_iter_mut()
                .zip(&mut self.rngs[..])
                .enumerate()
                .for_each_init(
                    || (r.ops.clone(), MoveScratch::default()),
                    |(ops, scratch), (i, (p, rng))| {
                        let from = &current[chosen[i] as usize];
                        propose(r.jump_probability, ops, from, p, scratch, rng);
                    },
                );
            evaluator.evaluate_bred(
                Bred {
                    children: &self.proposals[..n],
                    parents: population,
                    from: &self.chosen,
                },
                &mut self.proposal_fitness[..n],
            )?;
            for i in 0..n {
                let at = self.chosen[i] as usize;
                let (old, new) = (fitness[at], self.proposal_fitness[i]);
                if !new.is_nan() && compare(new, old).is_ge() {
                    std::mem::swap(&mut population[at], &mut self.proposals[i]);
                    fitness[at] = new;
                }
            }
        }
        Ok(())
    }
}
