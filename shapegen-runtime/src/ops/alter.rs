//! alter (the original's "permutate"): redraw all parameters of one gene.

use rand::Rng;

use super::Operators;
use super::weight::below;
use crate::derive::Grammar;
use crate::genome::{Genome, node_of};
use crate::graph::HEADER_WORDS;
use crate::param;

impl<G: Grammar> Operators<G> {
    /// Picks uniformly one gene whose node type has parameters and redraws all its
    /// parameters from their distributions. Returns `false` when no gene has parameters.
    /// The tree's shape is unchanged, so the limits stay met. O(G).
    ///
    /// ```
    /// # use rand::SeedableRng;
    /// # use shapegen_runtime::genome::{Genome, Limits};
    /// # use shapegen_runtime::ops::Operators;
    /// # use shapegen_runtime::ops::doc_grammar::Chain;
    /// let mut ops = Operators::<Chain>::new(Limits::new(1, 50, 10)?)?;
    /// let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    /// let mut g = Genome::<Chain>::axiom(&mut rng);
    /// assert!(!ops.alter(&mut g, &mut rng)); // the axiom `Start` has no parameters
    /// ops.grow(&mut g, &mut rng);
    /// let before = g.clone();
    /// assert!(ops.alter(&mut g, &mut rng));
    /// assert_ne!(g, before);
    /// assert_eq!(g.len(), before.len());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn alter(&mut self, genome: &mut Genome<G>, rng: &mut impl Rng) -> bool {
        let words = &genome.words;
        let cand = &mut self.s.cand;
        cand.clear();
        let mut pos = 0u32;
        while (pos as usize) < words.len() {
            let k = self.kinds[words[pos as usize] as usize];
            if k.has_params {
                cand.push(pos);
            }
            pos += k.gene_words;
        }
        if cand.is_empty() {
            return false;
        }
        let pos = cand[below(rng, cand.len() as u64) as usize];
        let node = node_of::<G>(words[pos as usize]);
        let at = (pos + HEADER_WORDS + node.links) as usize;
        for p in node.params {
            param::sample(&p.dist, rng, &mut genome.words[at + p.offset as usize..]);
        }
        true
    }
}
