//! The published scenes' folder and random populations, shared by the volume and
//! silhouette tests on the CPU and on the GPU.

use std::path::{Path, PathBuf};

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::score::InstanceBatch;
use shapegen_runtime::{Grammar, Limits, Operators};

/// The folder of the paper's scenes (`scenes/paper/` of the repository).
pub fn scenes() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/paper")
}

/// The instances of `n` random genomes of `G` of length `initial`, drawn from `seed`.
pub fn population<G: Grammar>(n: usize, limits: Limits, initial: u32, seed: u64) -> InstanceBatch {
    let mut ops = Operators::<G>::new(limits).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut batch = InstanceBatch::new();
    for _ in 0..n {
        batch.push_genome(&ops.random(initial, &mut rng));
    }
    batch
}
