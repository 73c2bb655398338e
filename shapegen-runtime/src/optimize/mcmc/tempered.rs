//! The tempered variant ([`McmcVariant::Tempered`](super::McmcVariant::Tempered)):
//! RJMCMC after Talton et al. 2011 with parallel tempering on a calibrated ladder,
//! annealing and delayed rejection.

use rand::{Rng, RngExt};

use super::moves::TemperedMove as Move;
use super::sampler::{Mcmc, propose_each};
use crate::derive::Grammar;
use crate::evaluate::{Bred, Evaluator};
use crate::genome::{Genome, node_of};
use crate::graph::HEADER_WORDS;
use crate::ops::Operators;
use crate::optimize::error::OptimizeError;
use crate::optimize::fitness::mean_std;
use crate::optimize::grow::{jump_links, sample_subtree};
use crate::optimize::run::stream;

/// Per-thread scratch of a move.
#[derive(Default)]
pub(crate) struct Scratch {
    depth: Vec<u32>,
    links: Vec<(u32, u32)>,
    queue: Vec<(u32, u32)>,
    params: Vec<u32>,
}

impl<G: Grammar> Mcmc<G> {
    /// Sets the temperature ladder from the initial chains' fitness.
    pub(super) fn start_tempered(&mut self) {
        let (_, s) = mean_std(&self.fitness);
        let s = if s > 0.0 && s.is_finite() { s } else { 1.0 };
        let cold = -s / self.core.settings.cold_acceptance.ln();
        let hot = -s / self.core.settings.hot_acceptance.ln();
        let n = self.temperatures.len();
        for (k, t) in self.temperatures.iter_mut().enumerate() {
            let x = if n > 1 {
                k as f64 / (n - 1) as f64
            } else {
                0.0
            };
            *t = cold * (hot / cold).powf(x);
        }
    }

    /// One iteration: a move per chain, delayed rejection, swaps, annealing.
    pub(super) fn step_tempered<E: Evaluator<G> + ?Sized>(
        &mut self,
        evaluator: &mut E,
    ) -> Result<(), OptimizeError> {
        let generation = self.reseed();
        let (jump_probability, chains) = (self.core.settings.jump_probability, &self.chains);
        propose_each(
            &self.ops,
            &mut self.proposals,
            &mut self.moves,
            &mut self.rngs,
            |ops, s: &mut Scratch, i, p, rng| propose(jump_probability, ops, &chains[i], p, s, rng),
        );
        self.evaluate_proposals(evaluator)?;
        self.retry.clear();
        for i in 0..self.chains.len() {
            let (m, t) = (self.moves[i], self.temperatures[i]);
            let rng = &mut self.rngs[i];
            if accept(self.fitness[i], self.proposal_fitness[i], t, m.log_q, rng) {
                std::mem::swap(&mut self.chains[i], &mut self.proposals[i]);
                self.fitness[i] = self.proposal_fitness[i];
            } else if m.jump {
                self.retry.push(i as u32);
            }
        }
        for _ in 0..self.core.settings.delayed_rejection {
            if self.retry.is_empty() {
                break;
            }
            self.retry_rejected(evaluator)?;
        }
        self.swap_temperatures(&mut stream(self.core.progress.seed, generation, 1 << 31));
        if generation.is_multiple_of(self.core.settings.anneal_interval) {
            for t in &mut self.temperatures {
                *t /= self.core.settings.anneal_factor;
            }
        }
        Ok(())
    }

    /// One round of delayed rejection: the chains in `retry`, whose jump was rejected,
    /// propose again by an alter of the rejected proposal; those accepted leave `retry`.
    fn retry_rejected<E: Evaluator<G> + ?Sized>(
        &mut self,
        evaluator: &mut E,
    ) -> Result<(), OptimizeError> {
        let n = self.retry.len();
        while self.retry_genomes.len() < n {
            self.retry_genomes.push(Genome::from_parts(Vec::new(), 0));
        }
        self.retry_fitness.resize(n, f64::NAN);
        for (k, &i) in self.retry.iter().enumerate() {
            let i = i as usize;
            self.ops.alter(&mut self.proposals[i], &mut self.rngs[i]);
            self.retry_genomes[k].clone_from(&self.proposals[i]);
        }
        evaluator.evaluate_bred(
            Bred {
                children: &self.retry_genomes[..n],
                parents: &self.chains,
                from: &self.retry,
            },
            &mut self.retry_fitness[..n],
        )?;
        self.core.progress.evaluations += n as u64;
        let mut kept = 0;
        for k in 0..n {
            let i = self.retry[k] as usize;
            let (m, t) = (self.moves[i], self.temperatures[i]);
            if accept(
                self.fitness[i],
                self.retry_fitness[k],
                t,
                m.log_q,
                &mut self.rngs[i],
            ) {
                std::mem::swap(&mut self.chains[i], &mut self.proposals[i]);
                self.fitness[i] = self.retry_fitness[k];
            } else {
                self.retry[kept] = i as u32;
                kept += 1;
            }
        }
        self.retry.truncate(kept);
        Ok(())
    }

    /// Swaps neighbouring chains' states by the tempering test.
    fn swap_temperatures(&mut self, rng: &mut impl Rng) {
        for k in 1..self.chains.len() {
            let (i, j) = (k - 1, k);
            let (ti, tj) = (self.temperatures[i], self.temperatures[j]);
            let a = (self.fitness[j] - self.fitness[i]) * (1.0 / ti - 1.0 / tj);
            let u: f64 = rng.random();
            if a >= 0.0 || u.ln() < a {
                self.chains.swap(i, j);
                self.fitness.swap(i, j);
            }
        }
    }
}

/// Whether a proposal of fitness `new` replaces a state of fitness `old` at temperature
/// `t`, with log proposal ratio `log_q`.
fn accept(old: f64, new: f64, t: f64, log_q: f64, rng: &mut impl Rng) -> bool {
    if new.is_nan() {
        return false;
    }
    if old.is_nan() {
        return true;
    }
    let delta = if new == old { 0.0 } else { new - old };
    let a = delta / t + log_q;
    let u: f64 = rng.random();
    a >= 0.0 || u.ln() < a
}

/// Proposes a move from `chain` into `proposal`: with `jump_probability` a jump (a link
/// redrawn from the grammar), else a diffusion (one gene altered); see
/// [`McmcVariant::Tempered`](super::McmcVariant::Tempered).
pub(crate) fn propose<G: Grammar>(
    jump_probability: f64,
    ops: &mut Operators<G>,
    chain: &Genome<G>,
    proposal: &mut Genome<G>,
    s: &mut Scratch,
    rng: &mut impl Rng,
) -> Move {
    proposal.clone_from(chain);
    let limits = *ops.limits();
    if rng.random::<f64>() < jump_probability {
        jump_links(proposal, &limits, &mut s.depth, &mut s.links, &mut s.queue);
        if !s.links.is_empty() {
            let before = s.links.len() as f64;
            let (pos, link) = s.links[rng.random_range(0..s.links.len())];
            let child = proposal.words()[(pos + HEADER_WORDS + link) as usize];
            s.params.clear();
            let cut = if child == 0 {
                true
            } else {
                let child = pos + child;
                let node = node_of::<G>(proposal.words()[child as usize]);
                let at = (child + HEADER_WORDS + node.links) as usize;
                s.params
                    .extend_from_slice(&proposal.words()[at..at + node.param_words as usize]);
                ops.cut_at(proposal, child).is_ok()
            };
            if cut {
                if let Some(root) = sample_subtree(proposal, &limits, pos, link, &mut s.queue, rng)
                    && !s.params.is_empty()
                {
                    let node = node_of::<G>(proposal.words[root as usize]);
                    let at = (root + HEADER_WORDS + node.links) as usize;
                    proposal.words[at..at + s.params.len()].copy_from_slice(&s.params);
                }
                jump_links(proposal, &limits, &mut s.depth, &mut s.links, &mut s.queue);
                let after = (s.links.len() as f64).max(1.0);
                return Move {
                    jump: true,
                    log_q: before.ln() - after.ln(),
                };
            }
        }
    }
    ops.alter(proposal, rng);
    Move {
        jump: false,
        log_q: 0.0,
    }
}
