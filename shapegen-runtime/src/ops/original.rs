//! The original implementation's rules for grow, cut, alter and crossover
//! ([`OperatorVariant::Original`](super::OperatorVariant::Original), whose documentation
//! gives them and says where they come from).

use rand::Rng;

use super::draw::{int_value, pick};
use super::edit::{cover, graft, splice, split};
use super::kinds::{KindInfo, gene_starts};
use super::operators::{ORIGINAL_CROSSOVER_ATTEMPTS, Operators};
use crate::derive::Grammar;
use crate::genome::{DEPTH_CAP, Genome, depths, node_of, parent_pos};
use crate::graph::HEADER_WORDS;
use crate::param;

/// A gene's symbol in the original's sense: its node kind and its index within the
/// array slot it hangs from (0 for a single slot).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Symbol {
    kind: u32,
    index: u32,
}

impl<G: Grammar> Operators<G> {
    /// Whether link `link` of a gene of kind `k` takes a child of symbol `sym`: the
    /// link's child kind is the symbol's, and so is its index within its slot unless
    /// array indices may cross.
    #[inline]
    fn takes(&self, k: &KindInfo, link: u32, sym: Symbol) -> bool {
        let l = self.link(k, link);
        l.child == sym.kind && (self.cross_array_index || l.index == sym.index)
    }

    /// Up to `steps` of the original's grow (`do_symbol_grow`): each takes one of the
    /// genes with an empty link (never one at [`DEPTH_CAP`]), then one of its empty links
    /// in link order, both by the original's [`pick`], and appends a child there with
    /// parameters drawn from their distributions. Returns the number of genes added,
    /// fewer than `steps` only when nothing can grow.
    ///
    /// The candidate genes stay in packed order, which for the genes appended here is
    /// their creation order: a random genome's candidates are ordered as the original
    /// orders them. O(W) to list them, then per step O(links) plus a memmove of the
    /// candidate list when a gene fills up.
    pub(super) fn grow_original(
        &mut self,
        genome: &mut Genome<G>,
        steps: u32,
        rng: &mut impl Rng,
    ) -> u32 {
        // A gene lies at most as deep as the genome is long: only track depths if the
        // genome can get longer than the cap.
        let track = genome.len.saturating_add(steps) > DEPTH_CAP;
        if track {
            depths::<G>(&genome.words, &mut self.s.depth);
        }
        let s = &mut self.s;
        s.cand.clear();
        let mut pos = 0u32;
        while (pos as usize) < genome.words.len() {
            let k = self.kinds[genome.words[pos as usize] as usize];
            let open = !track || s.depth[pos as usize] < DEPTH_CAP;
            if open && has_empty_link(&genome.words, pos, &k) {
                s.cand.push(pos);
            }
            pos += k.gene_words;
        }
        let mut added = 0;
        while added < steps && !self.s.cand.is_empty() {
            let i = pick(rng, self.s.cand.len());
            let pos = self.s.cand[i];
            let (child, empty) = self.add_child_original(genome, pos, rng);
            added += 1;
            if empty == 1 {
                self.s.cand.remove(i);
            }
            let ck = self.kind_at(&genome.words, child);
            let open = if track {
                cover(&mut self.s.depth, genome.words.len());
                let d = self.s.depth[pos as usize] + 1;
                self.s.depth[child as usize] = d;
                d < DEPTH_CAP
            } else {
                true
            };
            if open && ck.links > 0 {
                // The new gene is the last in packed order: the list stays ordered.
                self.s.cand.push(child);
            }
        }
        added
    }

    /// The original's addition of one child to the gene at `pos`, which must have an
    /// empty link: one of its empty links, in link order, drawn by [`pick`] whatever its
    /// probability, and there a child with parameters drawn from their distributions.
    /// Returns the child's position and how many empty links the gene had. O(links).
    pub(crate) fn add_child_original(
        &self,
        genome: &mut Genome<G>,
        pos: u32,
        rng: &mut impl Rng,
    ) -> (u32, usize) {
        let k = self.kind_at(&genome.words, pos);
        let at = (pos + HEADER_WORDS) as usize;
        let links = &genome.words[at..at + k.links as usize];
        let (link, empty) = if links.len() == 1 {
            (0, 1) // the one link, empty: a pick among one draws nothing
        } else {
            let empty = links.iter().filter(|&&w| w == 0).count();
            let j = pick(rng, empty);
            let link = (0..k.links)
                .filter(|&l| links[l as usize] == 0)
                .nth(j)
                .expect("the drawn index lies among the empty links");
            (link, empty)
        };
        let child_kind = self.link(&k, link).child;
        (
            self.fresh.push(genome, child_kind, Some((pos, link)), rng),
            empty,
        )
    }

    /// The original's cut (`do_symbol_cut`): removes the subtree of a uniformly drawn
    /// non-root gene, whatever its link's probability, then grows once if only the root
    /// is left. `false` only for a genome of the root alone. O(W).
    pub(super) fn cut_original(&mut self, genome: &mut Genome<G>, rng: &mut impl Rng) -> bool {
        if genome.len <= 1 {
            return false;
        }
        self.map_links(&genome.words);
        let s = &mut self.s;
        let pos = s.genes.starts[random_gene(genome.len, rng)];
        genome.len -= s.genes.remove_subtree(&self.kinds, &mut genome.words, pos);
        if genome.len == 1 {
            self.grow_original(genome, 1, rng);
        }
        true
    }

    /// The original's alter (`do_parameter_mutation`): redraws all parameters of a
    /// uniformly drawn non-root gene. `false`, the genome unchanged, when that gene has
    /// no parameters or the genome is the root alone. O(G).
    pub(super) fn alter_original(&mut self, genome: &mut Genome<G>, rng: &mut impl Rng) -> bool {
        if genome.len <= 1 {
            return false;
        }
        gene_starts(&self.kinds, &genome.words, &mut self.s.genes.starts);
        let pos = self.s.genes.starts[random_gene(genome.len, rng)];
        if !self.kind_at(&genome.words, pos).has_params {
            return false;
        }
        redraw::<G>(genome, pos, rng);
        true
    }

    /// The original's crossover (`Crossover_CPU::recombine`), see
    /// [`OperatorVariant::Original`](super::OperatorVariant::Original). Returns `false`,
    /// the outputs unspecified, when all [`ORIGINAL_CROSSOVER_ATTEMPTS`] attempts fail.
    /// O(W_a + W_b) per attempt.
    pub(super) fn crossover_original(
        &mut self,
        a: &Genome<G>,
        b: &Genome<G>,
        out_a: &mut Genome<G>,
        out_b: &mut Genome<G>,
        rng: &mut impl Rng,
    ) -> bool {
        if a.len < 2 {
            return false; // no non-root gene to draw
        }
        // A child is shorter than a.len + b.len, and no deeper than long.
        let track = a.len + b.len > DEPTH_CAP;
        self.survey_parents(a, b, track);
        for _ in 0..ORIGINAL_CROSSOVER_ATTEMPTS {
            let ra = self.s.pa.starts[random_gene(a.len, rng)];
            let pa = parent_pos(&a.words, ra);
            let ka = self.kind_at(&a.words, pa);
            let link_a = (0..ka.links)
                .find(|&l| pa + a.words[(pa + HEADER_WORDS + l) as usize] == ra)
                .expect("a valid genome's parent links to its child");
            let sym = Symbol {
                kind: a.words[ra as usize],
                index: self.link(&ka, link_a).index,
            };
            let mut cand = std::mem::take(&mut self.s.cand);
            cand.clear();
            for &pos in &self.s.pb.starts {
                let k = self.kind_at(&b.words, pos);
                if (0..k.links).any(|l| self.takes(&k, l, sym)) {
                    cand.push(pos);
                }
            }
            let pb = (!cand.is_empty()).then(|| cand[pick(rng, cand.len())]);
            self.s.cand = cand;
            let Some(pb) = pb else {
                continue; // no gene of b may have such a child
            };
            // b's first child of the symbol, else its first empty link taking it.
            let kb = self.kind_at(&b.words, pb);
            let (mut child, mut empty) = (None, None);
            for l in (0..kb.links).filter(|&l| self.takes(&kb, l, sym)) {
                match b.words[(pb + HEADER_WORDS + l) as usize] {
                    0 => {
                        empty = empty.or(Some(l));
                    }
                    off => {
                        child = Some(pb + off);
                        break;
                    }
                }
            }
            let done = match child {
                Some(rb) => {
                    // Any length, and a depth checked against the cap alone.
                    let lim = self.limits.without_length().without_depth();
                    self.try_swap(a, ra, b, rb, track, lim, out_a, out_b)
                }
                None => {
                    let link = empty.expect("a gene taking the symbol has a link for it");
                    self.graft_into(a, ra, b, pb, link, track, out_a, out_b)
                }
            };
            if done {
                return true;
            }
        }
        false
    }

    /// Writes `a` without its subtree at `ra` into `out_a`, and `b` with that subtree
    /// grafted onto the empty link `link` of its gene `pb` into `out_b`, unless that
    /// child would be deeper than [`DEPTH_CAP`] (checked when `track`, with both parents'
    /// depths surveyed into the scratch).
    #[allow(clippy::too_many_arguments)]
    fn graft_into(
        &mut self,
        a: &Genome<G>,
        ra: u32,
        b: &Genome<G>,
        pb: u32,
        link: u32,
        track: bool,
        out_a: &mut Genome<G>,
        out_b: &mut Genome<G>,
    ) -> bool {
        let s = &mut self.s;
        let sa = split(&self.kinds, &a.words, &mut s.pa, ra, track);
        if track {
            let hung = s.pb.depth[pb as usize] + 1 + sa.sub_max_depth - sa.root_depth;
            if s.pb.max_depth.max(hung) > DEPTH_CAP {
                return false;
            }
        }
        let donor = s.pa.split_genome(&a.words, &sa);
        splice(&self.kinds, &mut out_a.words, donor, None);
        out_a.len = a.len - sa.sub_genes;
        graft(&self.kinds, &mut out_b.words, &b.words, pb, link, donor);
        out_b.len = b.len + sa.sub_genes;
        true
    }
}

/// The original's `getRandomGene` on a genome of `len > 1` genes: the index, in gene
/// order, of a gene drawn by stepping `getRandomValue(1, len)` genes past the first (the
/// root), so uniform over the genes but the root.
#[inline]
fn random_gene(len: u32, rng: &mut impl Rng) -> usize {
    int_value(rng, 1, len as i32) as usize
}

/// Whether the gene at `pos`, of kind `k`, has an empty link.
#[inline]
fn has_empty_link(words: &[u32], pos: u32, k: &KindInfo) -> bool {
    let at = (pos + HEADER_WORDS) as usize;
    words[at..at + k.links as usize].contains(&0)
}

/// Redraws all parameters of the gene at `pos` from their distributions.
pub(crate) fn redraw<G: Grammar>(genome: &mut Genome<G>, pos: u32, rng: &mut impl Rng) {
    let node = node_of::<G>(genome.words[pos as usize]);
    let at = (pos + HEADER_WORDS + node.links) as usize;
    for p in node.params {
        param::sample(&p.dist, rng, &mut genome.words[at + p.offset as usize..]);
    }
}
