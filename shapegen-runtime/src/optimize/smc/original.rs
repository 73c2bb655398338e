//! The original variant ([`SmcVariant::Original`](super::SmcVariant::Original), whose
//! documentation gives the rules): the original's grows (`SMCGrowMutation`,
//! `SoSmcGrowMutation`) and its resampling wheel (`SMCSelection`, `SoSmcSelection`).

use rand::Rng;

use super::super::fitness::rank;
use super::super::grow::link_facts;
use super::settings::Order;
use crate::derive::Grammar;
use crate::genome::{DEPTH_CAP, Genome, node_of};
use crate::graph::HEADER_WORDS;
use crate::ops::draw::{pick, value01};

/// Per-thread scratch of the grows.
#[derive(Default)]
pub(super) struct Scratch {
    /// Genes to visit, with their levels.
    stack: Vec<(u32, u32)>,
    /// The children of one gene.
    children: Vec<u32>,
    /// The genes that may take a child, in the original's order.
    candidates: Vec<u32>,
}

/// Fills `s.candidates` with the genes of `genome` that have an empty link and lie above
/// level `bound` (the root is level 0), in the original's gene order: pre-order, each
/// gene's children in the order they were added, which is their packed order. O(G log G)
/// at worst.
fn candidates<G: Grammar>(genome: &Genome<G>, bound: u32, s: &mut Scratch) {
    let words = genome.words();
    s.candidates.clear();
    s.stack.clear();
    s.stack.push((0, 0));
    while let Some((pos, level)) = s.stack.pop() {
        if level >= bound {
            // Neither this gene nor anything below it may take a child.
            continue;
        }
        let at = (pos + HEADER_WORDS) as usize;
        let links = node_of::<G>(words[pos as usize]).links as usize;
        s.children.clear();
        s.children.extend(
            words[at..at + links]
                .iter()
                .filter(|&&o| o != 0)
                .map(|&o| pos + o),
        );
        if s.children.len() < links {
            s.candidates.push(pos);
        }
        // The stack pops the earliest child first.
        s.children.sort_unstable_by(|a, b| b.cmp(a));
        s.stack.extend(s.children.iter().map(|&c| (c, level + 1)));
    }
}

/// One grow of the original's, in `order`: returns whether a gene was added (`false`
/// when no gene may take a child). `step_back` is the chance, in percent, that the
/// chromosome-order walk steps back one gene; `max_depth` bounds the levels it grows
/// from.
pub(super) fn grow<G: Grammar>(
    order: Order,
    step_back: f32,
    max_depth: u32,
    genome: &mut Genome<G>,
    s: &mut Scratch,
    rng: &mut impl Rng,
) -> bool {
    // A gene at level `DEPTH_CAP - 1` is at depth `DEPTH_CAP`, the deepest allowed.
    let bound = match order {
        Order::Chromosome => max_depth.min(DEPTH_CAP - 1),
        Order::Stochastic => DEPTH_CAP - 1,
    };
    candidates(genome, bound, s);
    let n = s.candidates.len();
    if n == 0 {
        return false;
    }
    let i = match order {
        Order::Chromosome => {
            let mut i = n - 1;
            while i > 0 && 100.0 * value01(rng) < step_back {
                i -= 1;
            }
            i
        }
        Order::Stochastic => pick(rng, n),
    };
    let pos = s.candidates[i];
    let kind = genome.words()[pos as usize];
    let at = (pos + HEADER_WORDS) as usize;
    let links = node_of::<G>(kind).links;
    let free = || (0..links).filter(|&l| genome.words()[at + l as usize] == 0);
    let link = free()
        .nth(pick(rng, free().count()))
        .expect("a candidate has an empty link");
    genome.push_gene(link_facts::<G>(kind, link).1, Some((pos, link)), rng);
    true
}

/// The original's resampling wheel over one generation's fitness, see
/// [`SmcVariant::Original`](super::SmcVariant::Original).
#[derive(Clone, Debug, Default)]
pub(super) struct Wheel {
    /// Particle indices, best first.
    rank: Vec<u32>,
    /// Leading particles at `+inf`.
    infinite: usize,
    /// Over the finite particles, in rank order: the running maximum of the cumulative
    /// relative fitness, NaN values left out (`-inf` while all are NaN).
    top: Vec<f32>,
}

impl Wheel {
    /// Builds the wheel for `fitness`, reusing its buffers.
    pub(super) fn build(&mut self, fitness: &[f64]) {
        rank(fitness, &mut self.rank);
        let at = |k: usize| fitness[self.rank[k] as usize];
        self.infinite = (0..self.rank.len())
            .take_while(|&k| at(k) == f64::INFINITY)
            .count();
        self.top.clear();
        if self.infinite > 0 {
            return;
        }
        let finite = (0..self.rank.len())
            .take_while(|&k| at(k).is_finite())
            .count();
        if finite == 0 {
            return;
        }
        let f = |k: usize| at(k) as f32;
        // The offset lifts the worst to 0 if it is positive, and is 0 otherwise.
        let mut offset = -f(finite - 1);
        if offset > 0.0 {
            offset = 0.0;
        }
        let sum: f32 = (0..finite).map(|k| offset + f(k)).sum();
        let (mut cumulative, mut top) = (0.0f32, f32::NEG_INFINITY);
        for k in 0..finite {
            cumulative += (offset + f(k)) / sum;
            top = top.max(cumulative);
            self.top.push(top);
        }
    }

    /// Draws a rank position (0: the best particle); [`particle`](Self::particle) names
    /// the particle there.
    pub(super) fn spin(&self, rng: &mut impl Rng) -> usize {
        let u = value01(rng);
        if self.infinite > 0 {
            return ((self.infinite as f32 * u) as usize).min(self.infinite - 1);
        }
        if self.top.is_empty() {
            return self.rank.len() - 1;
        }
        // The first position whose cumulative value reaches `u` is the first whose
        // running maximum (never NaN) does; none: the last finite particle.
        self.top.partition_point(|&t| t < u).min(self.top.len() - 1)
    }

    /// The particle at rank position `k`.
    pub(super) fn particle(&self, k: usize) -> usize {
        self.rank[k] as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::genome::parent_pos;
    use crate::testing::{Line, rng};

    crate::prelude::generator! {
        /// Every gene may take two children.
        pub Two {
            axiom N;
            node N { children { a: N = 0.5, b: N = 0.5 } }
        }
    }

    crate::prelude::generator! {
        /// A root with four leaf links of very different probabilities.
        pub Fan {
            axiom R;
            node R { children { a: L = 0.9, z: L = 0.0, b: L = 0.05, c: L = 0.05 } }
            node L { params { x: f32 ~ uniform(0.0, 1.0) } }
        }
    }

    /// R with, in the order added: Z on link b, X on link a, Y below X, W below Z. The
    /// original's order of the genes that may grow is Z, W, X, Y (packed order: Z, X, Y,
    /// W; link order: X, Y, Z, W). Returns the genome and [Z, W, X, Y].
    fn tree() -> (Genome<Two>, [u32; 4]) {
        let mut r = rng(0);
        let mut g = Genome::<Two>::axiom(&mut r);
        let z = g.push_gene(0, Some((0, 1)), &mut r);
        let x = g.push_gene(0, Some((0, 0)), &mut r);
        let y = g.push_gene(0, Some((x, 0)), &mut r);
        let w = g.push_gene(0, Some((z, 0)), &mut r);
        (g, [z, w, x, y])
    }

    /// How often each of `genes` is the parent of the gene one grow adds to `genome`.
    fn parent_shares<G: Grammar>(
        genome: &Genome<G>,
        genes: &[u32],
        order: Order,
        step_back: f32,
        max_depth: u32,
        draws: u32,
    ) -> Vec<f64> {
        let (mut s, mut r, mut g) = (Scratch::default(), rng(7), genome.clone());
        let mut counts = vec![0u32; genes.len()];
        for _ in 0..draws {
            g.clone_from(genome);
            assert!(grow(order, step_back, max_depth, &mut g, &mut s, &mut r));
            let new = g.genes().last().unwrap().pos();
            let parent = parent_pos(g.words(), new);
            counts[genes.iter().position(|&p| p == parent).unwrap()] += 1;
        }
        counts
            .iter()
            .map(|&c| f64::from(c) / f64::from(draws))
            .collect()
    }

    fn close(shares: &[f64], expected: &[f64]) {
        for (s, e) in shares.iter().zip(expected) {
            assert!((s - e).abs() < 0.01, "{shares:?} against {expected:?}");
        }
    }

    #[test]
    fn chromosome_grow_steps_back_from_the_last_growable_gene() {
        let (g, genes) = tree();
        // Z, W, X, Y with p = 1/2: Y 1/2, X 1/4, W 1/8, Z 1/8.
        let shares = parent_shares(&g, &genes, Order::Chromosome, 50.0, 15, 40_000);
        close(&shares, &[0.125, 0.125, 0.25, 0.5]);
        let shares = parent_shares(&g, &genes, Order::Chromosome, 0.0, 15, 1000);
        assert_eq!(shares, [0.0, 0.0, 0.0, 1.0]);
        let shares = parent_shares(&g, &genes, Order::Chromosome, 100.0, 15, 1000);
        assert_eq!(shares, [1.0, 0.0, 0.0, 0.0]);
    }

    #[test]
    fn chromosome_grow_skips_genes_at_the_maximum_level() {
        let (g, genes) = tree();
        // W and Y lie at level 2: with max_depth 2 the walk starts at X.
        let shares = parent_shares(&g, &genes, Order::Chromosome, 50.0, 2, 20_000);
        close(&shares, &[0.5, 0.0, 0.5, 0.0]);
        // Levels 0 to max_depth, one more than the limits' depth counts (root at 1).
        let (mut s, mut r) = (Scratch::default(), rng(1));
        let mut line = Genome::<Line>::axiom(&mut r);
        while grow(Order::Chromosome, 0.0, 3, &mut line, &mut s, &mut r) {}
        assert_eq!(line.len(), 4);
        // The stochastic order has no such bound.
        for _ in 0..20 {
            assert!(grow(Order::Stochastic, 0.0, 3, &mut line, &mut s, &mut r));
        }
        assert_eq!(line.len(), 24);
    }

    #[test]
    fn stochastic_grow_draws_all_but_the_last_growable_gene() {
        let (g, genes) = tree();
        let shares = parent_shares(&g, &genes, Order::Stochastic, 0.0, 1, 30_000);
        close(&shares, &[1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 0.0]);
    }

    #[test]
    fn child_links_are_drawn_ignoring_probabilities() {
        for order in [Order::Chromosome, Order::Stochastic] {
            let (mut s, mut r) = (Scratch::default(), rng(3));
            let root = Genome::<Fan>::axiom(&mut r);
            let mut counts = [0u32; 4];
            let mut g = root.clone();
            for _ in 0..30_000 {
                g.clone_from(&root);
                assert!(grow(order, 0.0, 15, &mut g, &mut s, &mut r));
                let link = (0..4)
                    .position(|l| g.words()[(HEADER_WORDS + l) as usize] != 0)
                    .unwrap();
                counts[link] += 1;
            }
            let shares: Vec<f64> = counts.iter().map(|&c| f64::from(c) / 30_000.0).collect();
            // a, z, b each a third whatever their probabilities; c, the last, never.
            close(&shares, &[1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 0.0]);
            // A lone empty link is taken, the last one included.
            for _ in 0..3 {
                assert!(grow(order, 0.0, 15, &mut g, &mut s, &mut r));
            }
            assert!(!grow(order, 0.0, 15, &mut g, &mut s, &mut r));
            assert_eq!(g.len(), 5);
        }
    }

    /// How often each particle is drawn from a wheel on `fitness`.
    fn drawn(fitness: &[f64], draws: u32) -> Vec<f64> {
        let mut wheel = Wheel::default();
        wheel.build(fitness);
        let mut r = rng(11);
        let mut counts = vec![0u32; fitness.len()];
        for _ in 0..draws {
            counts[wheel.particle(wheel.spin(&mut r))] += 1;
        }
        counts
            .iter()
            .map(|&c| f64::from(c) / f64::from(draws))
            .collect()
    }

    #[test]
    fn the_wheel_shifts_a_positive_worst_to_zero() {
        // Weights 3, 2, 1, 0 after the offset -1.
        close(
            &drawn(&[1.0, 4.0, 2.0, 3.0], 60_000),
            &[0.0, 0.5, 1.0 / 6.0, 1.0 / 3.0],
        );
        // All equal: every relative value is 0 / 0, no draw reaches one, and the last
        // particle is taken.
        assert_eq!(drawn(&[5.0, 5.0, 5.0], 100), [0.0, 0.0, 1.0]);
    }

    #[test]
    fn the_wheel_keeps_negative_fitness_unshifted() {
        // Sum 3.5, from the best: 3/3.5, then past 1: the third and fourth are never drawn.
        close(
            &drawn(&[1.0, 3.0, 0.5, -1.0], 60_000),
            &[1.0 - 3.0 / 3.5, 3.0 / 3.5, 0.0, 0.0],
        );
        // A negative sum turns the wheel around: only the worst reaches the draw.
        assert_eq!(drawn(&[2.0, -3.0, 1.0, -2.0], 100), [0.0, 1.0, 0.0, 0.0]);
        // All equal and negative: no offset, a fair wheel.
        close(&drawn(&[-1.0, -1.0], 20_000), &[0.5, 0.5]);
    }

    #[test]
    fn the_wheel_leaves_out_nan_and_infinities() {
        assert_eq!(
            drawn(&[f64::NAN, 2.0, 1.0, f64::NEG_INFINITY], 100),
            [0.0, 1.0, 0.0, 0.0]
        );
        close(
            &drawn(&[f64::INFINITY, 1.0, f64::INFINITY], 20_000),
            &[0.5, 0.0, 0.5],
        );
        let all_nan = drawn(&[f64::NAN, f64::NAN], 100);
        assert_eq!(all_nan.iter().sum::<f64>(), 1.0);
    }
}
