//! alter (the original's "permutate"): redraw all parameters of one gene.

use rand::Rng;

use super::operators::{OperatorVariant, Operators};
use super::original::redraw;
use super::weight::below;
use crate::derive::Grammar;
use crate::genome::Genome;

impl<G: Grammar> Operators<G> {
    /// Picks uniformly one gene whose node type has parameters and redraws all its
    /// parameters from their distributions. Returns `false` when no gene has parameters.
    /// The tree's shape is unchanged, so the limits stay met. O(G).
    ///
    /// With the [`Original`](super::OperatorVariant::Original) rules it alters as the
    /// original does instead: it draws uniformly one of the non-root genes, parameters or
    /// not, and returns `false`, changing nothing, when that gene has none.
    ///
    /// ```
    /// # use rand::SeedableRng;
    /// # use shapegen_runtime::genome::{Genome, Limits};
    /// # use shapegen_runtime::ops::Operators;
    /// # shapegen_runtime::generator! {
    /// #     pub Chain {
    /// #         axiom Start;
    /// #         node Start { children { first: Seg = 0.9 } }
    /// #         node Seg {
    /// #             params { len: f32 ~ uniform(0.5, 1.5) }
    /// #             children { next: Seg = 0.5, side: Seg = 0.25 }
    /// #             derive(s) {
    /// #                 use shapegen_runtime::prelude::{CUBE, vec3};
    /// #                 let s = s.resize(vec3(1.0, len, 1.0));
    /// #                 s.emit(CUBE);
    /// #                 if let Some(next) = next {
    /// #                     s.translate(vec3(0.0, s.size().y, 0.0)).derive(next);
    /// #                 }
    /// #                 if let Some(side) = side {
    /// #                     s.rotate_z(0.5).translate(vec3(0.0, s.size().y, 0.0)).derive(side);
    /// #                 }
    /// #             }
    /// #         }
    /// #     }
    /// # }
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
        if self.variant == OperatorVariant::Original {
            return self.alter_original(genome, rng);
        }
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
        redraw(genome, pos, rng);
        true
    }
}
