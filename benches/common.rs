//! Genomes of exact sizes for the benchmarks.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen::genome::Limits;
use shapegen::ops::Operators;
use shapegen::{Genome, Grammar};

/// Limits that let a genome of `genes` genes exist: the paper scene's depth where the
/// grammar fits that many genes within it (the spaceship holds at most 197 genes within
/// depth 15), else a depth of `genes`.
pub fn limits_for<G: Grammar>(genes: usize, paper: Limits) -> Limits {
    let mut limits = Limits {
        min_len: 1,
        max_len: genes.max(paper.max_len as usize) as u32,
        max_depth: paper.max_depth,
    };
    if genome_of::<G>(genes, limits, 0).len() < genes {
        limits.max_depth = limits.max_depth.max(genes as u32);
    }
    limits
}

/// A genome of `genes` genes, or as many as the grammar allows, grown by the grammar's
/// probabilities from `seed`.
pub fn genome_of<G: Grammar>(genes: usize, limits: Limits, seed: u64) -> Genome<G> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut ops = Operators::<G>::new(limits).expect("benchmark limits are valid");
    let mut genome = Genome::<G>::axiom(&mut rng);
    while genome.len() < genes && ops.grow(&mut genome, &mut rng) {}
    genome
}
