//! Random lot buildings: walls, roofs and windows generated as facets, on the L-shaped
//! lot.

use generators::lot_building::{L_LOT, LIMITS, LotBuilding};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::score::InstanceBatch;
use shapegen_runtime::{Operators, Site};

/// `models` random lot buildings (initial length 30) on [`L_LOT`], drawn from `seed`.
pub fn lot_buildings(models: usize, seed: u64) -> InstanceBatch {
    let mut ops = Operators::<LotBuilding>::new(LIMITS).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut batch = InstanceBatch::new().on_site(Site::with_lot(L_LOT.clone()));
    for _ in 0..models {
        batch.push_genome(&ops.random(30, &mut rng));
    }
    batch
}
