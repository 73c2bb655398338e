//! Random operator sequences for the incremental-scoring property tests: one random
//! operator at a time, and how many sequences a test runs.

use rand::{Rng, RngExt};
use shapegen_runtime::ops::Operators;
use shapegen_runtime::{Genome, Grammar};

/// How many sequences a case runs: `release` in a release build, a fifth in debug,
/// times `SHAPEGEN_PROPERTY_SCALE` (default 1).
pub fn sequences(release: usize) -> usize {
    let scale: usize = std::env::var("SHAPEGEN_PROPERTY_SCALE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let base = if cfg!(debug_assertions) {
        release.div_ceil(5)
    } else {
        release
    };
    base * scale
}

/// One random operator on `g` (grow, cut, alter, or a crossover with a fresh random
/// genome of `initial` genes), with the rules `ops` has.
pub fn bred<G: Grammar>(
    ops: &mut Operators<G>,
    g: &Genome<G>,
    initial: u32,
    rng: &mut impl Rng,
) -> Genome<G> {
    let mut child = g.clone();
    match rng.random_range(0..4) {
        0 => {
            ops.grow(&mut child, rng);
        }
        1 => {
            ops.cut(&mut child, rng);
        }
        2 => {
            ops.alter(&mut child, rng);
        }
        _ => {
            let other = ops.random(initial, rng);
            if let Some((a, b)) = ops.crossover(g, &other, rng) {
                child = if rng.random::<bool>() { a } else { b };
            }
        }
    }
    child
}
