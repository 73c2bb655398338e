//! [`GenomeSet`]: many genomes of one grammar, as one file holds them.

use std::fmt;

use crate::derive::Grammar;
use crate::genome::packed::Genome;

/// Many genomes of one grammar, as saved in one file (`genomes.json`):
/// `{"generator": "spaceship", "genomes": [{"genes": [...]}, ...]}` in the packed form
/// ([`Genome::to_json`]), `{"generator": "spaceship", "genomes": [{"tree": {...}}, ...]}`
/// in the nested form ([`Genome::to_nested_json`]).
pub struct GenomeSet<G> {
    /// The genomes, in file order.
    pub genomes: Vec<Genome<G>>,
}

impl<G> Clone for GenomeSet<G> {
    fn clone(&self) -> Self {
        GenomeSet {
            genomes: self.genomes.clone(),
        }
    }
}

impl<G> PartialEq for GenomeSet<G> {
    fn eq(&self, other: &Self) -> bool {
        self.genomes == other.genomes
    }
}

impl<G: Grammar> fmt::Debug for GenomeSet<G> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("GenomeSet")
            .field("generator", &G::GRAPH.name)
            .field("genomes", &self.genomes)
            .finish()
    }
}

impl<G: Grammar> GenomeSet<G> {
    /// A set of the given genomes.
    pub fn new(genomes: Vec<Genome<G>>) -> Self {
        GenomeSet { genomes }
    }
}
