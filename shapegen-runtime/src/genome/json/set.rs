//! [`GenomeSet`]: many genomes of one grammar, as one file holds them.

use std::fmt;

use super::error::JsonError;
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

    /// The set of the genomes `read` makes of `entries`, in order; an entry that fails
    /// fails the set, with its index.
    pub(in crate::genome::json) fn read_entries<T>(
        entries: impl IntoIterator<Item = T>,
        mut read: impl FnMut(T) -> Result<Genome<G>, JsonError>,
    ) -> Result<Self, JsonError> {
        let genomes = entries
            .into_iter()
            .enumerate()
            .map(|(index, entry)| {
                read(entry).map_err(|e| JsonError::InSet {
                    index,
                    source: Box::new(e),
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(GenomeSet { genomes })
    }
}
