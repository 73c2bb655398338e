//! The original variant ([`McmcVariant::Original`](super::McmcVariant::Original)): the
//! original implementation's Metropolis-Hastings (`MetropolisHastings.h`), with its
//! moves (`MHOperators.cpp`), its random genomes (`Genome_Factory::createRandomGenome`
//! with `GrowMutation::grow`), its gene selection (`Genome_CPU::selectSemiRandomGene`,
//! `getSelectionLogProb`) and its random draws (`RandomValues.cpp`), on packed genomes.
//!
//! The original's genes keep their children in the order they were added, and a new
//! genome numbers its genes in creation order. A packed genome appends new genes and
//! keeps the order of the others when it removes some, so buffer order is that order:
//! a gene's children sorted by position are its children in the original's order, and
//! the genes of a new genome in buffer order are the original's genes in map order.
//! Each link of a node type plays the part of one of the original's possible children
//! of at most one instance, which is what every published grammar declares (the city's
//! array of lots is the original's hundred lot symbols). As the original, the moves
//! ignore the links' probabilities.

use rand::Rng;

use super::moves::OriginalMove as Move;
use super::sampler::{Mcmc, propose_each};
use crate::derive::Grammar;
use crate::evaluate::Evaluator;
use crate::genome::{DEPTH_CAP, Genome, depths, node_of};
use crate::graph::HEADER_WORDS;
use crate::ops::draw::{int_value, pick, value, value01};
use crate::ops::{Operators, redraw};
use crate::optimize::error::OptimizeError;
use crate::optimize::run::stream;

/// Chain `i` starts at the exponent `1 / (i + 1)^TEMPERATURE_EXPONENT`.
const TEMPERATURE_EXPONENT: f32 = 1.03;
/// Every move multiplies its chain's exponent by this.
const ANNEALING: f32 = 1.1;
/// A jump stops adding genes after one when a draw falls below this.
const STOP_PROBABILITY: f32 = 0.02;
/// A jump stops adding genes once the tree reaches this level (the root is level 0).
const LEVEL_CAP: u32 = 25;
/// Non-positive fitness values are shifted to lie this far above 0 (the lower of the
/// two values being compared lands on it).
const SHIFT: f32 = 0.01;

/// Per-thread scratch.
#[derive(Default)]
struct Scratch {
    /// Depth of each gene, by word position (the root is at depth 1, level 0).
    depth: Vec<u32>,
    /// Candidate genes with their depths.
    genes: Vec<(u32, u32)>,
    /// Breadth-first queue, with depths.
    queue: Vec<(u32, u32)>,
    /// The children of one gene.
    list: Vec<u32>,
}

impl<G: Grammar> Mcmc<G> {
    /// Sets the initial chains' exponents and log priors (the chains themselves grow as
    /// the original's `createRandomGenome` grows them: the operators follow its rules).
    pub(super) fn start_original(&mut self) {
        for (i, t) in self.temperatures.iter_mut().enumerate() {
            *t = f64::from(initial_temperature(i));
        }
        self.log_priors.fill(1.0);
    }

    /// One iteration: a move per chain, each followed by its annealing, then one swap.
    pub(super) fn step_original<E: Evaluator<G> + ?Sized>(
        &mut self,
        evaluator: &mut E,
    ) -> Result<(), OptimizeError> {
        let generation = self.reseed();
        // The original's `basic_prob`, in percent.
        let basic_prob = (self.core.settings.jump_probability * 100.0) as f32;
        let (chains, priors) = (&self.chains, &self.log_priors);
        propose_each(
            &self.ops,
            &mut self.proposals,
            &mut self.original_moves,
            &mut self.rngs,
            |ops, s: &mut Scratch, i, p, rng| {
                propose(basic_prob, ops, &chains[i], priors[i] as f32, p, s, rng)
            },
        );
        self.evaluate_proposals(evaluator)?;
        for i in 0..self.chains.len() {
            let (m, t) = (self.original_moves[i], self.temperatures[i] as f32);
            let (old, new) = (self.fitness[i], self.proposal_fitness[i]);
            if accepts(old, new, t, m.accept_prior, &mut self.rngs[i]) {
                std::mem::swap(&mut self.chains[i], &mut self.proposals[i]);
                self.fitness[i] = new;
                self.log_priors[i] = f64::from(m.log_prior);
            }
            self.temperatures[i] = f64::from(t * ANNEALING);
        }
        self.swap_chains(&mut stream(self.core.progress.seed, generation, 1 << 31));
        Ok(())
    }

    /// The original's one tempering swap per iteration: two chains drawn at random
    /// exchange genomes, fitness and log priors, each position keeping its exponent.
    fn swap_chains(&mut self, rng: &mut impl Rng) {
        let n = self.chains.len() as i32;
        let mut a = int_value(rng, 0, n);
        let b = int_value(rng, 0, n);
        if a == b {
            a = int_value(rng, 0, n);
        }
        if a == b {
            return;
        }
        let (a, b) = (a as usize, b as usize);
        let p = swap_probability(
            [self.fitness[a] as f32, self.fitness[b] as f32],
            [self.temperatures[a] as f32, self.temperatures[b] as f32],
            [self.log_priors[a] as f32, self.log_priors[b] as f32],
        );
        if p >= value01(rng) {
            self.chains.swap(a, b);
            self.fitness.swap(a, b);
            self.log_priors.swap(a, b);
        }
    }
}

/// Chain `i`'s initial exponent, `1 / (i + 1)^1.03`.
fn initial_temperature(i: usize) -> f32 {
    1.0 / ((i + 1) as f32).powf(TEMPERATURE_EXPONENT)
}

/// The original's shift of two fitness values when either is `<= 0`: both are raised by
/// `0.01 - min(a, b)`.
fn shifted(a: f32, b: f32) -> (f32, f32) {
    if a <= 0.0 || b <= 0.0 {
        // std::min(a, b)
        let m = -(if b < a { b } else { a });
        (a + (m + SHIFT), b + (m + SHIFT))
    } else {
        (a, b)
    }
}

/// The original's acceptance probability of a move from fitness `old` to `new` by a
/// chain at exponent `t`, with log prior change `prior` (0 for a diffusion):
/// `exp(t (prior + ln new - ln old))` on the shifted values. NaN when a value is NaN
/// or the exponent has overflowed on an unchanged fitness; may exceed 1.
fn acceptance(old: f32, new: f32, t: f32, prior: f32) -> f32 {
    let (old, new) = shifted(old, new);
    (t * (prior + (new.ln() - old.ln()))).exp()
}

/// Whether a chain at fitness `old` and exponent `t` moves to a proposal at `new`: as
/// the original, when [`acceptance`] is at least a uniform draw, which NaN never is;
/// beyond it, a chain at NaN takes any non-NaN proposal and one at `-inf` any better
/// one, where the original's arithmetic would keep them there forever.
fn accepts(old: f64, new: f64, t: f32, prior: f32, rng: &mut impl Rng) -> bool {
    let (old, new) = (old as f32, new as f32);
    if new.is_nan() {
        false
    } else if old.is_nan() {
        true
    } else if old == f32::NEG_INFINITY {
        new > old
    } else {
        acceptance(old, new, t, prior) >= value01(rng)
    }
}

/// The original's swap probability of two chains with fitness `f`, exponents `t` and
/// log priors `prior`: `(p01 p10) / (p00 p11)`, `pab = exp(t_a (ln f_b + prior_b))` on
/// the shifted fitness values.
fn swap_probability(f: [f32; 2], t: [f32; 2], prior: [f32; 2]) -> f32 {
    let (f0, f1) = shifted(f[0], f[1]);
    let p = |a: usize, f: f32, b: usize| (t[a] * (f.ln() + prior[b])).exp();
    (p(0, f1, 1) * p(1, f0, 0)) / (p(0, f0, 0) * p(1, f1, 1))
}

/// Proposes a move from `chain` (stored log prior `chain_prior`) into `proposal`, as an
/// iteration of the original's `createNewGeneration` does for one chain: a jump when
/// `getRandomValue(0, 100) <= basic_prob`, else a diffusion, on a gene picked by
/// [`select_gene`].
fn propose<G: Grammar>(
    basic_prob: f32,
    ops: &mut Operators<G>,
    chain: &Genome<G>,
    chain_prior: f32,
    proposal: &mut Genome<G>,
    s: &mut Scratch,
    rng: &mut impl Rng,
) -> Move {
    proposal.clone_from(chain);
    // A clone's `_max_level` is its deepest level.
    let max_level = depths::<G>(proposal.words(), &mut s.depth) - 1;
    let jump = value(rng, 0.0, 100.0) <= basic_prob;
    let (gene, level) = select_gene(proposal, max_level, s, rng);
    let before = selection_log_prob(level_count(proposal, &s.depth, level), level, max_level);
    if jump {
        delete_children(ops, proposal, gene, s);
        let deepest = add_random_symbols(ops, proposal, gene, level + 1, s, rng);
        // `_max_level` only grows: deletions leave it as it was.
        let max_level = max_level.max(deepest);
        depths::<G>(proposal.words(), &mut s.depth);
        let after = selection_log_prob(level_count(proposal, &s.depth, level), level, max_level);
        Move {
            accept_prior: after - before,
            log_prior: after - before,
        }
    } else {
        redraw(proposal, gene, rng);
        Move {
            accept_prior: 0.0,
            log_prior: before - chain_prior,
        }
    }
}

/// The original's `selectSemiRandomGene` on a tree whose deepest level is `max_level`,
/// `s.depth` holding its depths: a level drawn by `getRandomValue(1, max_level)` (so
/// `1..max_level - 1`, or 1 when `max_level` is 1, or mostly 0, the root, when it is 0),
/// then a gene of that level uniformly by `getRandomValue(0, n)`. A level without genes
/// (only drawn for the root alone, with `U = 0`) gives the root. Returns the gene's
/// position and level.
fn select_gene<G: Grammar>(
    genome: &Genome<G>,
    max_level: u32,
    s: &mut Scratch,
    rng: &mut impl Rng,
) -> (u32, u32) {
    let level = int_value(rng, 1, max_level as i32) as u32;
    s.genes.clear();
    s.genes.extend(
        genome
            .genes()
            .map(|g| (g.pos(), s.depth[g.pos() as usize]))
            .filter(|&(_, d)| d - 1 == level),
    );
    match s.genes.len() {
        0 => (0, 0),
        1 => (s.genes[0].0, level),
        n => (s.genes[int_value(rng, 0, n as i32) as usize].0, level),
    }
}

/// Number of genes at `level`, given the genome's depths.
fn level_count<G: Grammar>(genome: &Genome<G>, depth: &[u32], level: u32) -> usize {
    genome
        .genes()
        .filter(|g| depth[g.pos() as usize] - 1 == level)
        .count()
}

/// The original's `getSelectionLogProb(level)` with `n` genes at that level:
/// `ln(level / max_level) + ln(1 / n)`, the second term left out when `n` is 0.
fn selection_log_prob(n: usize, level: u32, max_level: u32) -> f32 {
    let p = (level as f32 / max_level as f32).ln();
    if n == 0 { p } else { p + (1.0 / n as f32).ln() }
}

/// Fills `out` with the positions of the children of the gene at `pos`, in the
/// original's order (the order they were added in).
fn children<G: Grammar>(words: &[u32], pos: u32, out: &mut Vec<u32>) {
    out.clear();
    let links = node_of::<G>(words[pos as usize]).links;
    let at = (pos + HEADER_WORDS) as usize;
    out.extend(
        words[at..at + links as usize]
            .iter()
            .filter(|&&off| off != 0)
            .map(|&off| pos + off),
    );
    out.sort_unstable();
}

/// Whether the gene at `pos` (depth `depth`) can have another child: the original's
/// `can_have_children`.
fn can_grow<G: Grammar>(words: &[u32], pos: u32, depth: u32) -> bool {
    let at = (pos + HEADER_WORDS) as usize;
    let links = node_of::<G>(words[pos as usize]).links as usize;
    depth < DEPTH_CAP && words[at..at + links].contains(&0)
}

/// The original's `deleteChildGenes` on the gene at `pos`: it deletes child `i` while
/// counting `i` up over a list that shrinks with each deletion, so it deletes the first,
/// third, fifth, ... child (in the order they were added) with their subtrees, and keeps
/// the others. Nothing when the genome is the root alone.
fn delete_children<G: Grammar>(
    ops: &mut Operators<G>,
    genome: &mut Genome<G>,
    pos: u32,
    s: &mut Scratch,
) {
    if genome.len() <= 1 {
        return;
    }
    children::<G>(genome.words(), pos, &mut s.list);
    // From the last, so that the positions of the earlier ones stay.
    for &child in s.list.iter().step_by(2).rev() {
        ops.cut_at(genome, child)
            .expect("a child is a gene other than the root, and no length limit applies");
    }
}

/// The original's `addRandomSymbols` below the gene at `root` (depth `root_depth`):
/// adds a child ([`Operators::add_child_original`]) to a gene drawn by [`pick`] among the genes of `root`'s
/// subtree that can grow, in breadth-first order, again and again, until the whole tree
/// reaches level [`LEVEL_CAP`] or a uniform draw after an addition falls below
/// [`STOP_PROBABILITY`], or until no gene of the subtree can grow. No length limit.
/// Returns the tree's deepest level.
fn add_random_symbols<G: Grammar>(
    ops: &Operators<G>,
    genome: &mut Genome<G>,
    root: u32,
    root_depth: u32,
    s: &mut Scratch,
    rng: &mut impl Rng,
) -> u32 {
    let mut max_level = depths::<G>(genome.words(), &mut s.depth) - 1;
    while let Some((gene, d)) = valid_sub_gene(genome, root, root_depth, s, rng) {
        ops.add_child_original(genome, gene, rng);
        let stop = value01(rng);
        // The child lies at depth d + 1, level d.
        max_level = max_level.max(d);
        if max_level >= LEVEL_CAP || stop < STOP_PROBABILITY {
            break;
        }
    }
    max_level
}

/// The original's `selectRandomValidSubGene`: a gene drawn by [`pick`] among the genes of
/// `root`'s subtree that can grow, in breadth-first order (children in the order they
/// were added); `root` itself when the genome is the root alone and it can grow. Returns
/// the gene's position and depth.
fn valid_sub_gene<G: Grammar>(
    genome: &Genome<G>,
    root: u32,
    root_depth: u32,
    s: &mut Scratch,
    rng: &mut impl Rng,
) -> Option<(u32, u32)> {
    let words = genome.words();
    if genome.len() == 1 {
        return can_grow::<G>(words, root, root_depth).then_some((root, root_depth));
    }
    s.genes.clear();
    s.queue.clear();
    s.queue.push((root, root_depth));
    let mut head = 0;
    while head < s.queue.len() {
        let (pos, d) = s.queue[head];
        head += 1;
        if can_grow::<G>(words, pos, d) {
            s.genes.push((pos, d));
        }
        children::<G>(words, pos, &mut s.list);
        s.queue.extend(s.list.iter().map(|&c| (c, d + 1)));
    }
    match s.genes.len() {
        0 => None,
        n => Some(s.genes[pick(rng, n)]),
    }
}

#[cfg(test)]
mod tests {
    use rand_chacha::ChaCha8Rng;

    use super::*;
    use crate::genome::Limits;
    use crate::testing::{Line, rng};

    crate::prelude::generator! {
        /// Branches of three kinds; `C` is a leaf.
        pub Branchy {
            axiom Root;
            node Root { children { a: A = 1.0 } }
            node A {
                params { x: f32 ~ uniform(0.0, 1.0) }
                children { a: A = 0.3, b: B = 0.3, c: C = 0.3 }
            }
            node B {
                params { x: f32 ~ uniform(0.0, 1.0) }
                children { a: A = 0.5 }
            }
            node C { params { y: f32 ~ uniform(0.0, 1.0) } }
        }
    }

    fn kind(name: &str) -> u32 {
        Branchy::GRAPH.kind_of(name).unwrap()
    }

    fn close(a: f32, b: f32) -> bool {
        (a - b).abs() <= 1e-4 * b.abs().max(1.0)
    }

    /// Whether `count` of `n` draws fits probability `p` within five standard deviations.
    fn fits(count: u32, n: u32, p: f64) -> bool {
        let (n, count) = (f64::from(n), f64::from(count));
        (count - n * p).abs() <= 5.0 * (n * p * (1.0 - p)).sqrt()
    }

    /// Root (level 0) - A1 (1); A1's children added as C1, A2, B1 (links 2, 0, 1; level
    /// 2); A2 - A3, C2 (3); A3 - C3 (4). Returns the genome and the positions
    /// `[root, a1, c1, a2, b1, a3, c2, c3]`.
    fn sample_tree(r: &mut ChaCha8Rng) -> (Genome<Branchy>, [u32; 8]) {
        let mut g = Genome::<Branchy>::axiom(r);
        let a1 = g.push_gene(kind("A"), Some((0, 0)), r);
        let c1 = g.push_gene(kind("C"), Some((a1, 2)), r);
        let a2 = g.push_gene(kind("A"), Some((a1, 0)), r);
        let b1 = g.push_gene(kind("B"), Some((a1, 1)), r);
        let a3 = g.push_gene(kind("A"), Some((a2, 0)), r);
        let c2 = g.push_gene(kind("C"), Some((a2, 2)), r);
        let c3 = g.push_gene(kind("C"), Some((a3, 2)), r);
        g.validate().unwrap();
        (g, [0, a1, c1, a2, b1, a3, c2, c3])
    }

    #[test]
    fn acceptance_by_hand() {
        // exp(T (dp + ln f' - ln f)), no shift when both are positive.
        assert!(close(acceptance(2.0, 4.0, 1.0, 0.0), 2.0));
        assert!(close(
            acceptance(4.0, 2.0, 0.5, 0.0),
            std::f32::consts::FRAC_1_SQRT_2
        ));
        assert!(close(acceptance(1.0, 1.0, 2.0, -0.5), 0.367_879_4));
        // Either <= 0: both shifted by 0.01 - min.
        assert!(close(acceptance(-1.0, 1.0, 1.0, 0.0), 2.01 / 0.01));
        assert!(close(acceptance(0.0, -0.5, 1.0, 0.0), 0.01 / 0.51));
        assert!(close(
            acceptance(-3.0, -2.0, 0.5, 0.0),
            (1.01f32 / 0.01).sqrt()
        ));
        assert!(close(acceptance(0.0, 0.0, 1.0, 0.0), 1.0));
        // Grown exponents: a loss is never accepted, a gain always, and an unchanged
        // fitness at an infinite exponent gives NaN, which no draw is below.
        assert_eq!(acceptance(2.0, 1.0, 1e30, 0.0), 0.0);
        assert_eq!(acceptance(1.0, 2.0, 1e30, 0.0), f32::INFINITY);
        assert!(acceptance(1.0, 1.0, f32::INFINITY, 0.0).is_nan());
        assert!(acceptance(1.0, f32::NAN, 1.0, 0.0).is_nan());
        // The selection log probabilities that make dp.
        assert!(close(selection_log_prob(2, 1, 4), (1.0f32 / 8.0).ln()));
        assert!(close(selection_log_prob(0, 3, 4), 0.75f32.ln()));
    }

    #[test]
    fn acceptance_test_and_its_nan_rules() {
        let mut r = rng(1);
        for _ in 0..100 {
            assert!(accepts(1.0, 2.0, 0.3, 0.0, &mut r));
            assert!(!accepts(1.0, f64::NAN, 0.3, 0.0, &mut r));
            assert!(accepts(f64::NAN, -5.0, 0.3, 0.0, &mut r));
            assert!(accepts(f64::NEG_INFINITY, -1e9, 0.3, 0.0, &mut r));
            assert!(!accepts(
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
                0.3,
                0.0,
                &mut r
            ));
            assert!(!accepts(1.0, 1.0, f32::INFINITY, 0.0, &mut r));
        }
        // A loss to half the fitness at exponent 1 is accepted half the time.
        let n = 20_000;
        let hits = (0..n)
            .filter(|_| accepts(2.0, 1.0, 1.0, 0.0, &mut r))
            .count();
        assert!(fits(hits as u32, n, 0.5), "{hits}");
    }

    #[test]
    fn swap_probability_by_hand() {
        // (p01 p10) / (p00 p11) = exp((t0 - t1) ((ln f1 + prior1) - (ln f0 + prior0))).
        let p = swap_probability([2.0, 4.0], [1.0, 0.5], [0.0, 0.0]);
        assert!(close(p, 2f32.sqrt()), "{p}");
        let p = swap_probability([2.0, 4.0], [1.0, 0.5], [1.0, 0.0]);
        assert!(close(p, (0.5 * (4f32.ln() - 2f32.ln() - 1.0)).exp()), "{p}");
        let p = swap_probability([-1.0, 1.0], [1.0, 0.5], [0.0, 0.0]);
        assert!(close(p, (2.01f32 / 0.01).sqrt()), "{p}");
        // Grown exponents overflow: inf / inf.
        assert!(swap_probability([2.0, 4.0], [1e30, 1e29], [0.0, 0.0]).is_nan());
    }

    #[test]
    fn chains_start_at_their_exponents() {
        // Chain 0 the coldest.
        assert_eq!(initial_temperature(0), 1.0);
        assert!(close(initial_temperature(1), 0.489_730_6));
    }

    #[test]
    fn semi_random_selection_draws_a_level_then_a_gene() {
        let mut r = rng(3);
        let (g, [root, a1, c1, a2, b1, a3, c2, c3]) = sample_tree(&mut r);
        let mut s = Scratch::default();
        let max_level = depths::<Branchy>(g.words(), &mut s.depth) - 1;
        assert_eq!(max_level, 4);
        let n = 90_000;
        let mut counts = std::collections::HashMap::new();
        for _ in 0..n {
            let (pos, level) = select_gene(&g, max_level, &mut s, &mut r);
            assert_eq!(level, s.depth[pos as usize] - 1);
            *counts.entry(pos).or_insert(0u32) += 1;
        }
        // Levels 1, 2, 3 alike (never 4, the deepest, nor the root); genes alike within.
        for (pos, p) in [
            (a1, 1.0 / 3.0),
            (c1, 1.0 / 9.0),
            (a2, 1.0 / 9.0),
            (b1, 1.0 / 9.0),
        ]
        .into_iter()
        .chain([(a3, 1.0 / 6.0), (c2, 1.0 / 6.0)])
        {
            let c = counts.get(&pos).copied().unwrap_or(0);
            assert!(fits(c, n, p), "gene at {pos}: {c} of {n}");
        }
        assert!(!counts.contains_key(&c3) && !counts.contains_key(&root));
        // A tree of two levels: level 1 always; the root alone: the root.
        let mut line = Genome::<Line>::axiom(&mut r);
        let seg = line.push_gene(0, Some((0, 0)), &mut r);
        depths::<Line>(line.words(), &mut s.depth);
        assert!((0..100).all(|_| select_gene(&line, 1, &mut s, &mut r) == (seg, 1)));
        let line = Genome::<Line>::axiom(&mut r);
        depths::<Line>(line.words(), &mut s.depth);
        assert!((0..100).all(|_| select_gene(&line, 0, &mut s, &mut r) == (0, 0)));
    }

    #[test]
    fn jumps_delete_every_other_child_in_the_order_they_were_added() {
        let mut r = rng(4);
        let (mut g, [_, a1, ..]) = sample_tree(&mut r);
        let mut ops = Operators::<Branchy>::new(Limits::new(0, 100, 50).unwrap()).unwrap();
        let mut s = Scratch::default();
        // A1's children were added C1, A2, B1: C1 and B1 go, A2 stays with its subtree,
        // though A2 comes first in link order.
        delete_children(&mut ops, &mut g, a1, &mut s);
        g.validate().unwrap();
        assert_eq!(g.len(), 6);
        let a1 = g.gene(a1);
        assert!(a1.link(0).is_some() && a1.link(1).is_none() && a1.link(2).is_none());
        // The root alone keeps itself.
        let mut ops = Operators::<Line>::new(Limits::new(0, 100, 50).unwrap()).unwrap();
        let mut line = Genome::<Line>::axiom(&mut r);
        delete_children(&mut ops, &mut line, 0, &mut s);
        assert_eq!(line.len(), 1);
    }

    #[test]
    fn children_are_drawn_uniformly_but_never_the_last_free_link() {
        let mut r = rng(5);
        let mut g = Genome::<Branchy>::axiom(&mut r);
        let a1 = g.push_gene(kind("A"), Some((0, 0)), &mut r);
        let ops = original_ops::<Branchy>();
        let n = 10_000;
        let mut counts = [0u32; 4];
        for _ in 0..n {
            let mut h = g.clone();
            let (child, _) = ops.add_child_original(&mut h, a1, &mut r);
            counts[h.words()[child as usize] as usize] += 1;
        }
        // Links a, b, c free: a or b alike (whatever their probabilities), never c.
        assert!(fits(counts[kind("A") as usize], n, 0.5), "{counts:?}");
        assert_eq!(counts[kind("C") as usize], 0);
        // Links b and c free: always b.
        g.push_gene(kind("A"), Some((a1, 0)), &mut r);
        for _ in 0..100 {
            let mut h = g.clone();
            let (child, _) = ops.add_child_original(&mut h, a1, &mut r);
            assert_eq!(h.words()[child as usize], kind("B"));
        }
    }

    #[test]
    fn jumps_add_a_geometric_number_of_genes_whatever_the_length() {
        let mut r = rng(6);
        let mut g = Genome::<Branchy>::axiom(&mut r);
        let a1 = g.push_gene(kind("A"), Some((0, 0)), &mut r);
        let (ops, mut s) = (original_ops::<Branchy>(), Scratch::default());
        let n = 2000;
        let mut added = Vec::with_capacity(n);
        for _ in 0..n {
            let mut h = g.clone();
            let deepest = add_random_symbols(&ops, &mut h, a1, 2, &mut s, &mut r);
            h.validate().unwrap();
            assert_eq!(deepest, h.depth() - 1);
            added.push(h.len() - 2);
        }
        // At least one gene, then stop with 2% after each: 50 on average, and no length
        // limit (the original has none).
        let mean = added.iter().sum::<usize>() as f64 / n as f64;
        assert!((46.0..54.0).contains(&mean), "{mean}");
        assert!(added.iter().all(|&a| a >= 1));
        assert!(added.iter().any(|&a| a > 150));
    }

    #[test]
    fn jumps_stop_at_level_25() {
        let mut r = rng(7);
        let (ops, mut s) = (original_ops::<Line>(), Scratch::default());
        // A line of levels 0..=2, grown from its end: one gene per addition.
        let mut g = Genome::<Line>::axiom(&mut r);
        let mut end = 0;
        for _ in 0..2 {
            end = g.push_gene(0, Some((end, 0)), &mut r);
        }
        let mut at_cap = 0;
        for _ in 0..500 {
            let mut h = g.clone();
            let deepest = add_random_symbols(&ops, &mut h, end, 3, &mut s, &mut r);
            assert!(deepest <= 25 && deepest == h.depth() - 1);
            at_cap += u32::from(deepest == 25);
        }
        // 23 more genes without a stop: 0.98^22 of the time.
        assert!(fits(at_cap, 500, 0.98f64.powi(22)), "{at_cap}");
        // Already past the cap: exactly one gene.
        for _ in 0..28 {
            end = g.push_gene(0, Some((end, 0)), &mut r);
        }
        for _ in 0..50 {
            let mut h = g.clone();
            assert_eq!(
                add_random_symbols(&ops, &mut h, end, 31, &mut s, &mut r),
                31
            );
            assert_eq!(h.len(), g.len() + 1);
        }
    }

    #[test]
    fn random_genomes_have_exactly_the_length_and_grow_the_oldest_first() {
        let mut ops = original_ops::<Branchy>();
        let mut g = Genome::<Branchy>::axiom(&mut rng(0));
        for len in 1..=60 {
            ops.random_into(len, &mut g, &mut rng(u64::from(len)));
            g.validate().unwrap();
            assert_eq!(g.len(), len as usize);
        }
        // Four genes: the root, A1 and two children of A1 on links a and b, never a
        // grandchild (A1 is the older of the two genes that can grow) nor link c (the
        // last free one).
        for seed in 0..100 {
            ops.random_into(4, &mut g, &mut rng(seed));
            let a1 = g.gene(g.root().link(0).unwrap());
            assert!(a1.link(0).is_some() && a1.link(1).is_some() && a1.link(2).is_none());
        }
    }

    /// Operators with the original's rules, as the original variant's chains use them.
    fn original_ops<G: Grammar>() -> Operators<G> {
        Operators::new(Limits::new(0, 100, 50).unwrap())
            .unwrap()
            .with_variant(crate::ops::OperatorVariant::Original)
    }
}
