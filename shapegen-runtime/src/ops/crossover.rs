//! crossover: swap two subtrees hanging from the same edge of the generator graph (the
//! weighted rules; the original's are in `original.rs`).

use rand::Rng;

use super::edit::{Split, splice, split, survey_pair};
use super::operators::{CROSSOVER_RETRIES, OperatorVariant, Operators};
use super::weight::below;
use crate::derive::Grammar;
use crate::genome::{GeneAt, Genome, GenomeError, Limits, node_of, parent_pos, slot_at};
use crate::graph::HEADER_WORDS;

impl<G: Grammar> Operators<G> {
    /// Single-point crossover adapted to trees: picks uniformly an expressed link of `a`,
    /// collects the expressed links of `b` on the same edge of the generator graph (same
    /// parent node type and slot, and the same index within an array slot unless
    /// [`cross_array_index`](Self::cross_array_index)), picks one uniformly and swaps the
    /// two subtrees, giving two children. When `b` has no such link, or a child would
    /// break the limits, it draws again, up to [`CROSSOVER_RETRIES`] times, then gives up
    /// with `None`.
    ///
    /// The children are valid genomes within the limits. O(W_a + W_b) per attempt.
    ///
    /// With the [`Original`](super::OperatorVariant::Original) rules it follows the
    /// original's crossover instead (see [`OperatorVariant`]):
    /// the children's lengths are `len(a) - s_a + s_b` and `len(b) - s_b + s_a` for an
    /// exchange of subtrees of `s_a` and `s_b` genes, or `len(a) - s_a` and
    /// `len(b) + s_a` for a graft, whatever the limits.
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
    /// let mut ops = Operators::<Chain>::new(Limits::new(1, 60, 12)?)?;
    /// let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    /// let (a, b) = (ops.random(20, &mut rng), ops.random(20, &mut rng));
    /// let (c, d) = ops.crossover(&a, &b, &mut rng).expect("Chain's edges all match");
    /// assert_eq!(c.len() + d.len(), a.len() + b.len()); // genes are exchanged, not lost
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn crossover(
        &mut self,
        a: &Genome<G>,
        b: &Genome<G>,
        rng: &mut impl Rng,
    ) -> Option<(Genome<G>, Genome<G>)> {
        let mut c = Genome::from_parts(Vec::new(), 0);
        let mut d = Genome::from_parts(Vec::new(), 0);
        self.crossover_into(a, b, &mut c, &mut d, rng)
            .then_some((c, d))
    }

    /// As [`crossover`](Self::crossover), writing the children into `out_a` (from `a`,
    /// with `b`'s subtree) and `out_b`, reusing their allocations. Returns `false`, with
    /// the outputs unspecified, when no crossover was found.
    pub fn crossover_into(
        &mut self,
        a: &Genome<G>,
        b: &Genome<G>,
        out_a: &mut Genome<G>,
        out_b: &mut Genome<G>,
        rng: &mut impl Rng,
    ) -> bool {
        if self.variant == OperatorVariant::Original {
            return self.crossover_original(a, b, out_a, out_b, rng);
        }
        if a.len < 2 || b.len < 2 {
            return false; // no expressed link on one side
        }
        // A child's depth is at most its length, which is below a.len + b.len.
        let track_depth = self.limits.max_depth < a.len + b.len;
        self.survey_parents(a, b, track_depth);
        for _ in 0..=CROSSOVER_RETRIES {
            let s = &mut self.s;
            let ra = s.pa.starts[1 + below(rng, u64::from(a.len - 1)) as usize];
            let pa = parent_pos(&a.words, ra);
            let kind = a.words[pa as usize];
            let k = self.kinds[kind as usize];
            let link = (0..k.links)
                .find(|&l| pa + a.words[(pa + HEADER_WORDS + l) as usize] == ra)
                .expect("a valid genome's parent links to its child");
            // The links of `b`'s genes of that kind on the same edge: the whole slot, or
            // the drawn link alone.
            let (first, count) = if self.cross_array_index {
                let info = self.links[(k.first_link + link) as usize];
                let slot = &node_of::<G>(kind).slots[info.slot as usize];
                (slot.first_link, slot.count)
            } else {
                (link, 1)
            };
            s.cand.clear();
            for &pos in &s.pb.starts {
                if b.words[pos as usize] != kind {
                    continue;
                }
                let at = (pos + HEADER_WORDS + first) as usize;
                for &off in &b.words[at..at + count as usize] {
                    if off != 0 {
                        s.cand.push(pos + off);
                    }
                }
            }
            if s.cand.is_empty() {
                continue;
            }
            let rb = s.cand[below(rng, s.cand.len() as u64) as usize];
            if self.try_swap(a, ra, b, rb, track_depth, self.limits, out_a, out_b) {
                return true;
            }
        }
        false
    }

    /// Swaps the subtree of `a` at word `a_pos` with the subtree of `b` at word `b_pos`,
    /// which must hang from the same edge of the generator graph (same parent node type
    /// and slot, and the same index within an array slot unless
    /// [`cross_array_index`](Self::cross_array_index)). Fails if a position is the root
    /// or no gene start, the edges differ, or a child would break the limits (the error
    /// says which limit). The swap is the same with either [`OperatorVariant`]. O(W_a +
    /// W_b).
    pub fn crossover_at(
        &mut self,
        a: &Genome<G>,
        a_pos: u32,
        b: &Genome<G>,
        b_pos: u32,
    ) -> Result<(Genome<G>, Genome<G>), GenomeError> {
        let a_at = self.link_root(a, a_pos)?;
        let b_at = self.link_root(b, b_pos)?;
        let edge = |g: &Genome<G>, pos: u32| {
            let parent = parent_pos(&g.words, pos);
            let pnode = node_of::<G>(g.words[parent as usize]);
            let off = pos - parent;
            let link = (0..pnode.links)
                .find(|&l| g.words[(parent + HEADER_WORDS + l) as usize] == off)
                .expect("a valid genome's parent links to its child");
            (pnode, slot_at(pnode, link))
        };
        let ((an, aslot), (bn, bslot)) = (edge(a, a_pos), edge(b, b_pos));
        let index_differs = !self.cross_array_index && aslot.index != bslot.index;
        if !std::ptr::eq(an, bn) || aslot.slot != bslot.slot || index_differs {
            return Err(GenomeError::EdgeMismatch {
                a: a_at,
                a_edge: format!("{aslot} of `{}`", an.name),
                b: b_at,
                b_edge: format!("{bslot} of `{}`", bn.name),
            });
        }
        self.survey_parents(a, b, true);
        let mut c = Genome::from_parts(Vec::new(), 0);
        let mut d = Genome::from_parts(Vec::new(), 0);
        // No bound on the swap itself (a value beyond what `Limits::check` accepts): both
        // children are built, then checked against the operators' limits, so that the
        // error says which limit a child breaks.
        let any = Limits {
            min_len: 0,
            max_len: u32::MAX,
            max_depth: u32::MAX,
        };
        let built = self.try_swap(a, a_pos, b, b_pos, true, any, &mut c, &mut d);
        debug_assert!(built, "no limit refuses the swap");
        c.validate_limits(&self.limits)?;
        d.validate_limits(&self.limits)?;
        Ok((c, d))
    }

    /// Where the gene at `pos` of `g` is, if it hangs from a link.
    fn link_root(&mut self, g: &Genome<G>, pos: u32) -> Result<GeneAt, GenomeError> {
        let index = g.gene_index(pos)?;
        if pos == 0 {
            return Err(GenomeError::IsRoot);
        }
        Ok(GeneAt {
            index,
            pos,
            node: node_of::<G>(g.words[pos as usize]).name,
        })
    }

    /// Surveys the parents `a` and `b` of a crossover into the scratch buffers: their
    /// gene starts and, when `track_depth`, their depths ([`survey_pair`]).
    pub(super) fn survey_parents(&mut self, a: &Genome<G>, b: &Genome<G>, track_depth: bool) {
        let s = &mut self.s;
        survey_pair(
            &self.kinds,
            (&mut s.pa, &a.words),
            (&mut s.pb, &b.words),
            track_depth,
        );
    }

    /// Writes both children of a swap whose splits are done.
    fn build_children(
        &mut self,
        a: &Genome<G>,
        sa: &Split,
        b: &Genome<G>,
        sb: &Split,
        out_a: &mut Genome<G>,
        out_b: &mut Genome<G>,
    ) {
        let (da, db) = (
            self.s.pa.split_genome(&a.words, sa),
            self.s.pb.split_genome(&b.words, sb),
        );
        splice(&self.kinds, &mut out_a.words, da, Some(db));
        out_a.len = a.len - sa.sub_genes + sb.sub_genes;
        splice(&self.kinds, &mut out_b.words, db, Some(da));
        out_b.len = b.len - sb.sub_genes + sa.sub_genes;
    }

    /// Swaps the subtrees at `ra` and `rb` into the outputs if both children meet `lim`
    /// (their depths checked only when `track_depth`, with which the parents' surveys
    /// hold depths); `false` otherwise.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn try_swap(
        &mut self,
        a: &Genome<G>,
        ra: u32,
        b: &Genome<G>,
        rb: u32,
        track_depth: bool,
        lim: Limits,
        out_a: &mut Genome<G>,
        out_b: &mut Genome<G>,
    ) -> bool {
        let s = &mut self.s;
        let sa = split(&self.kinds, &a.words, &mut s.pa, ra, track_depth);
        let sb = split(&self.kinds, &b.words, &mut s.pb, rb, track_depth);
        let len_a = a.len - sa.sub_genes + sb.sub_genes;
        let len_b = b.len - sb.sub_genes + sa.sub_genes;
        let len_ok = |len: u32| len >= lim.min_len && len <= lim.max_len;
        if !len_ok(len_a) || !len_ok(len_b) {
            return false;
        }
        if track_depth && (sa.depth_with(&sb) > lim.max_depth || sb.depth_with(&sa) > lim.max_depth)
        {
            return false;
        }
        self.build_children(a, &sa, b, &sb, out_a, out_b);
        true
    }
}
