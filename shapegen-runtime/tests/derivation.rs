//! Derivation of genomes of the hand-expanded spaceship grammar.

mod support {
    pub mod spaceship_expanded;
}

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use shapegen_runtime::Genome;
use support::spaceship_expanded::Spaceship;

#[test]
fn axiom_alone_emits_nothing() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let g = Genome::<Spaceship>::axiom(&mut rng);
    assert_eq!(g.len(), 1);
    assert_eq!(g.words().len(), 3);
    let mut out = Vec::new();
    g.derive_into(&mut out);
    assert!(out.is_empty());
}
