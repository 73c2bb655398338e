//! What the unit tests of several modules share: small grammars and seeded streams.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

crate::prelude::generator! {
    /// A chain: every gene has one link.
    pub Line {
        axiom Link;
        node Link { children { next: Link = 0.5 } }
    }
}

crate::prelude::generator! {
    /// A chain of blocks, each a cube.
    pub Chain {
        axiom Seg;
        node Seg {
            children { next: Seg = 0.5 }
            derive(s) { s.emit(crate::geometry::CUBE); if let Some(n) = next { s.derive(n); } }
        }
    }
}

/// The ChaCha8 stream of `seed`.
pub(crate) fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}
