//! grow: append one child at an empty link, chosen by the grammar's probabilities (the
//! weighted rules; the original's are in `original.rs`).

use rand::Rng;

use super::edit::cover;
use super::operators::{OperatorVariant, Operators};
use super::weight::below;
use crate::derive::Grammar;
use crate::genome::{Genome, parent_pos};
use crate::graph::HEADER_WORDS;

impl<G: Grammar> Operators<G> {
    /// Grows the genome by one gene: picks a gene `i` that lies above the maximum depth
    /// and one of its empty links `j` with probability `p(i,j) / sum of p(k,l)` over all
    /// such genes `k` and their empty links `l`, and appends a child there with
    /// parameters drawn from their distributions. Returns `false`, leaving the genome as
    /// it was, when it is at the maximum length or no link can grow.
    ///
    /// Probabilities are compared as exact 32-bit fixed-point weights. O(W), plus O(1)
    /// for the append; no allocation once the scratch buffers have grown.
    ///
    /// With the [`Original`](super::OperatorVariant::Original) rules it grows as the
    /// original does instead, ignoring the probabilities and the limits: one of the genes
    /// with an empty link, then one of its empty links (see
    /// [`OperatorVariant`]); `false` only when no gene has an
    /// empty link.
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
    /// let mut ops = Operators::<Chain>::new(Limits::new(1, 3, 10)?)?;
    /// let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    /// let mut g = Genome::<Chain>::axiom(&mut rng);
    /// assert!(ops.grow(&mut g, &mut rng));
    /// assert!(ops.grow(&mut g, &mut rng));
    /// assert!(!ops.grow(&mut g, &mut rng)); // at max_len
    /// assert_eq!(g.len(), 3);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn grow(&mut self, genome: &mut Genome<G>, rng: &mut impl Rng) -> bool {
        if self.variant == OperatorVariant::Original {
            return self.grow_original(genome, 1, rng) == 1;
        }
        if genome.len >= self.limits.max_len {
            return false;
        }
        let max_depth = self.limits.max_depth;
        // A gene of a G-gene tree lies at most G deep: only track depth if it can matter.
        let track_depth = max_depth <= genome.len;
        let words = &genome.words;
        let s = &mut self.s;
        if track_depth {
            cover(&mut s.depth, words.len());
        }
        s.cand.clear();
        s.cum.clear();
        let mut total = 0u64;
        let mut pos = 0u32;
        while (pos as usize) < words.len() {
            let k = self.kinds[words[pos as usize] as usize];
            let open = if track_depth {
                let d = if pos == 0 {
                    1
                } else {
                    s.depth[parent_pos(words, pos) as usize] + 1
                };
                s.depth[pos as usize] = d;
                d < max_depth
            } else {
                true
            };
            if open && k.links > 0 {
                let at = (pos + HEADER_WORDS) as usize;
                let links = &self.links[k.first_link as usize..][..k.links as usize];
                let w: u64 = words[at..at + k.links as usize]
                    .iter()
                    .zip(links)
                    .filter(|(w, _)| **w == 0)
                    .map(|(_, l)| l.grow)
                    .sum();
                if w > 0 {
                    total += w;
                    s.cand.push(pos);
                    s.cum.push(total);
                }
            }
            pos += k.gene_words;
        }
        if total == 0 {
            return false;
        }
        let r = below(rng, total);
        let i = s.cum.partition_point(|&c| c <= r);
        let pos = s.cand[i];
        let mut r = r - if i > 0 { s.cum[i - 1] } else { 0 };
        let k = self.kind_at(words, pos);
        for link in 0..k.links {
            if words[(pos + HEADER_WORDS + link) as usize] != 0 {
                continue;
            }
            let l = self.link(&k, link);
            if r < l.grow {
                self.fresh.push(genome, l.child, Some((pos, link)), rng);
                return true;
            }
            r -= l.grow;
        }
        unreachable!("the drawn weight lies within the chosen gene's empty links")
    }
}
