//! cut: remove a subtree, chosen by the grammar's probabilities (the weighted rules; the
//! original's are in `original.rs`).

use rand::Rng;

use super::edit::cover;
use super::kinds::KindInfo;
use super::operators::{OperatorVariant, Operators};
use super::weight::{ONE, below};
use crate::derive::Grammar;
use crate::genome::{Genome, GenomeError};

impl<G: Grammar> Operators<G> {
    /// Cuts one subtree: picks an expressed link `(k, l)` with probability
    /// `(1 - p(k,l)) / sum of (1 - p)` over the expressed links whose removal keeps the
    /// genome at least `min_len` long, and removes the child there with its whole
    /// subtree. Links of probability 1 are never cut. Returns `false`, leaving the genome
    /// as it was, when nothing can be cut.
    ///
    /// One pass finds the candidates; the removal is one forward sweep from the cut
    /// gene that compacts the survivors and fixes their offsets. O(W); no allocation once
    /// the scratch buffers have grown.
    ///
    /// With the [`Original`](super::OperatorVariant::Original) rules it cuts as the
    /// original does instead: the subtree of a uniformly drawn non-root gene, `p = 1`
    /// links included and `min_len` ignored, then one grow if only the root is left;
    /// `false` only for a genome of the root alone.
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
    /// let mut ops = Operators::<Chain>::new(Limits::new(2, 50, 10)?)?;
    /// let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
    /// let mut g = ops.random(20, &mut rng);
    /// while ops.cut(&mut g, &mut rng) {}
    /// assert_eq!(g.len(), 2); // min_len
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn cut(&mut self, genome: &mut Genome<G>, rng: &mut impl Rng) -> bool {
        if self.variant == OperatorVariant::Original {
            return self.cut_original(genome, rng);
        }
        let len = genome.len;
        let min_len = self.limits.min_len.max(1);
        if len <= min_len {
            return false; // any cut removes at least one gene
        }
        // Subtrees of more than `len - min_len` genes may not be cut. Descendants follow
        // their root, so only a subtree rooted among the first `min_len` genes can be that
        // large: genes from `sure_from` on are always cuttable.
        let max_cut = len - min_len;
        let words = &genome.words[..];
        let (m, total, sure_from) = self.survey_cuts(words, len, min_len);
        if total == 0 {
            return false;
        }
        let s = &mut self.s;
        let (cand, cum) = (&s.cand[..m], &mut s.cum[..m]);
        let r = below(rng, total);
        let mut child = cand[cum.partition_point(|&c| c <= r)];
        if child < sure_from
            && subtree_len(
                &self.kinds,
                words,
                child,
                &s.genes.parent,
                &mut s.depth,
                max_cut,
            ) > max_cut
        {
            // Drawn too large: draw again among the cuttable links only. Accepting the
            // first draw when it fits and redrawing exactly otherwise gives each cuttable
            // link its weight over the cuttable links' total weight. The survey mapped
            // the genes' starts and parents.
            subtree_sizes(&s.genes.starts, &s.genes.parent, &mut s.depth);
            let total = cuttable_weights(cand, cum, &s.depth, max_cut);
            if total == 0 {
                return false;
            }
            let r = below(rng, total);
            child = cand[cum.partition_point(|&c| c <= r)];
        }
        genome.len -= s
            .genes
            .remove_subtree(&self.kinds, &mut genome.words, child);
        true
    }

    /// The cut candidates of the genome in `words` (`len` genes, at least `min_len + 1`):
    /// every expressed link of weight `1 - p > 0`, its child written to `s.cand` and
    /// the running total of the weights to `s.cum`, the genes mapped into `s.genes`.
    /// Returns the candidates' count, their total weight, and where the genes from index
    /// `min_len` on start (subtrees rooted there are never too large to cut; `u32::MAX`
    /// if none).
    fn survey_cuts(&mut self, words: &[u32], len: u32, min_len: u32) -> (usize, u64, u32) {
        let s = &mut self.s;
        // Every gene but the root hangs from one expressed link: `len - 1` candidates at
        // most, written by index.
        if s.cand.len() < len as usize {
            s.cand.resize(len as usize, 0);
        }
        if s.cum.len() < len as usize {
            s.cum.resize(len as usize, 0);
        }
        let (cand, cum) = (&mut s.cand[..], &mut s.cum[..]);
        let mut m = 0;
        let mut total = 0u64;
        s.genes
            .record(&self.kinds, &self.links, words, |child, info| {
                let w = ONE - info.grow;
                if w > 0 {
                    total += w;
                    cand[m] = child;
                    cum[m] = total;
                    m += 1;
                }
            });
        let sure_from = s
            .genes
            .starts
            .get(min_len as usize)
            .copied()
            .unwrap_or(u32::MAX);
        (m, total, sure_from)
    }

    /// Removes the gene at word `pos` and its subtree, whatever its link's probability;
    /// returns the number of genes removed. Fails, leaving the genome as it was, if `pos`
    /// is the root or not the start of a gene, or if the genome would become shorter than
    /// `min_len`. The same with either [`OperatorVariant`]. O(W).
    pub fn cut_at(&mut self, genome: &mut Genome<G>, pos: u32) -> Result<u32, GenomeError> {
        self.map_links(&genome.words);
        let s = &mut self.s;
        if s.genes.starts.binary_search(&pos).is_err() {
            return Err(GenomeError::NotAGene {
                pos,
                words: genome.words.len() as u32,
            });
        }
        if pos == 0 {
            return Err(GenomeError::IsRoot);
        }
        subtree_sizes(&s.genes.starts, &s.genes.parent, &mut s.depth);
        let left = genome.len - s.depth[pos as usize];
        if left < self.limits.min_len {
            return Err(GenomeError::TooShort {
                len: left,
                min_len: self.limits.min_len,
            });
        }
        let removed = s.genes.remove_subtree(&self.kinds, &mut genome.words, pos);
        genome.len -= removed;
        Ok(removed)
    }
}

/// Rewrites the running totals `cum` of the candidates `cand` to count only those whose
/// subtree (`size`, per word position) has at most `max_cut` genes; returns their total.
fn cuttable_weights(cand: &[u32], cum: &mut [u64], size: &[u32], max_cut: u32) -> u64 {
    let mut prev = 0;
    let mut total = 0;
    for (c, w) in cand.iter().zip(cum.iter_mut()) {
        let own = *w - prev;
        prev = *w;
        if size[*c as usize] <= max_cut {
            total += own;
        }
        *w = total;
    }
    total
}

/// Number of genes in the subtree of the gene at `root`, counted up to `limit + 1`, given
/// each gene's parent position; `mark` is scratch. O(W) from `root`.
fn subtree_len(
    kinds: &[KindInfo],
    words: &[u32],
    root: u32,
    parent: &[u32],
    mark: &mut Vec<u32>,
    limit: u32,
) -> u32 {
    cover(mark, words.len());
    let mut count = 0;
    let mut pos = root;
    while (pos as usize) < words.len() && count <= limit {
        let inside = pos == root || {
            let p = parent[pos as usize];
            p >= root && mark[p as usize] != 0
        };
        mark[pos as usize] = u32::from(inside);
        count += u32::from(inside);
        pos += kinds[words[pos as usize] as usize].gene_words;
    }
    count
}

/// Fills `size`, indexed by word position, with the number of genes in each gene's
/// subtree (itself included), given the gene starts and each gene's parent position.
/// O(G): children follow their parents, so a backward pass adds each finished subtree to
/// its parent.
fn subtree_sizes(starts: &[u32], parent: &[u32], size: &mut Vec<u32>) {
    if let Some(&last) = starts.last() {
        cover(size, last as usize + 1);
    }
    for &pos in starts {
        size[pos as usize] = 1;
    }
    for &pos in starts.iter().skip(1).rev() {
        size[parent[pos as usize] as usize] += size[pos as usize];
    }
}
