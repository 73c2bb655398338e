//! Subtree surgery on packed genomes: removing a subtree in one compacting pass,
//! splicing one genome's subtree into another's place (or nowhere), and grafting one onto
//! an empty link of another genome.
//!
//! All rely on the layout's order: a gene lies after its parent, so one forward sweep
//! from a subtree's root meets every gene of the subtree after its parent, and can tell
//! subtree members by their parent's mark. Word positions are remapped through a
//! word-indexed table and every offset is rewritten once: O(W).

use super::kinds::{KindInfo, LinkInfo};
use crate::genome::parent_pos;
use crate::graph::HEADER_WORDS;

/// Marks a gene as removed in a position map.
const GONE: u32 = u32::MAX;
/// Marks a gene as part of the split-off subtree in a position map; the other bits hold
/// its position relative to the subtree's new start.
const SUB: u32 = 1 << 31;

/// Grows a word-indexed scratch table to cover `n` words.
#[inline]
pub(super) fn cover(table: &mut Vec<u32>, n: usize) {
    if table.len() < n {
        table.resize(n, 0);
    }
}

/// Where the genes of a genome start, and each child's parent and link, as
/// [`record`](Self::record) fills them.
#[derive(Debug, Default)]
pub(super) struct GeneMap {
    /// Every gene's start, in order.
    pub starts: Vec<u32>,
    /// Word-indexed: each child's parent position.
    pub parent: Vec<u32>,
    /// Word-indexed: the index of the link each child hangs from.
    pub link: Vec<u32>,
}

impl GeneMap {
    /// One forward pass over the valid genome in `words`: records each gene's start,
    /// each child's parent position and link index, and calls `each_link` with every
    /// expressed link's child position and [`LinkInfo`].
    #[inline]
    pub(super) fn record(
        &mut self,
        kinds: &[KindInfo],
        links: &[LinkInfo],
        words: &[u32],
        mut each_link: impl FnMut(u32, &LinkInfo),
    ) {
        cover(&mut self.parent, words.len());
        cover(&mut self.link, words.len());
        self.starts.clear();
        let mut pos = 0u32;
        while (pos as usize) < words.len() {
            let k = kinds[words[pos as usize] as usize];
            self.starts.push(pos);
            let at = (pos + HEADER_WORDS) as usize;
            let infos = &links[k.first_link as usize..][..k.links as usize];
            for (l, (&off, info)) in words[at..at + k.links as usize]
                .iter()
                .zip(infos)
                .enumerate()
            {
                if off != 0 {
                    let child = pos + off;
                    self.parent[child as usize] = pos;
                    self.link[child as usize] = l as u32;
                    each_link(child, info);
                }
            }
            pos += k.gene_words;
        }
    }

    /// Removes the gene at `root` (not the genome's root) and its whole subtree from the
    /// valid genome in `words`, compacting the survivors and fixing all offsets in one
    /// forward sweep from `root`; the parent's link becomes 0. Returns the number of genes
    /// removed.
    ///
    /// The map must hold the genome as [`record`](Self::record) filled it; its parents
    /// are overwritten. The sweep meets parents before children, so when it moves a gene
    /// it knows its parent's new place and the link there to patch, and it tells removed
    /// genes by their parent's mark.
    pub(super) fn remove_subtree(
        &mut self,
        kinds: &[KindInfo],
        words: &mut Vec<u32>,
        root: u32,
    ) -> u32 {
        debug_assert!(root != 0);
        let n = words.len() as u32;
        let mut cursor = root;
        let mut removed = 0;
        let mut pos = root;
        while pos < n {
            let k = kinds[words[pos as usize] as usize];
            let p = pos as usize;
            let par = self.parent[p];
            if pos == root || par == GONE {
                if pos == root {
                    words[(par + HEADER_WORDS + self.link[p]) as usize] = 0;
                }
                for &off in &words[p + HEADER_WORDS as usize..][..k.links as usize] {
                    if off != 0 {
                        self.parent[(pos + off) as usize] = GONE;
                    }
                }
                removed += 1;
            } else {
                // Moving down never reaches the words of a gene not yet swept.
                let np = cursor;
                words.copy_within(p..p + k.gene_words as usize, np as usize);
                words[np as usize + 1] = par.wrapping_sub(np);
                words[(par + HEADER_WORDS + self.link[p]) as usize] = np - par;
                for &off in &words[(np + HEADER_WORDS) as usize..][..k.links as usize] {
                    if off != 0 {
                        self.parent[(pos + off) as usize] = np;
                    }
                }
                cursor += k.gene_words;
            }
            pos += k.gene_words;
        }
        words.truncate(cursor as usize);
        removed
    }
}

/// What crossover learns of a parent genome in one forward pass ([`survey_pair`]), and
/// the position map its [`split`] fills.
#[derive(Debug, Default)]
pub(super) struct Survey {
    /// Every gene's start, in order.
    pub starts: Vec<u32>,
    /// Word-indexed: each gene's depth, when tracked.
    pub depth: Vec<u32>,
    /// Word-indexed: the deepest gene before each gene (0 for the root), when tracked.
    pub above: Vec<u32>,
    /// The genome's depth, when tracked; 0 otherwise.
    pub max_depth: u32,
    /// Word-indexed, from a split's root on: what [`split`] maps each gene to.
    pub map: Vec<u32>,
}

impl Survey {
    /// Empties the survey for a genome of `words`.
    fn begin(&mut self, words: &[u32], track_depth: bool) {
        self.starts.clear();
        self.max_depth = 0;
        if track_depth {
            cover(&mut self.depth, words.len());
            cover(&mut self.above, words.len());
        }
    }

    /// Records the gene at `pos` of the genome in `words`, whose earlier genes are
    /// recorded; returns the next gene's position.
    #[inline(always)]
    fn visit(&mut self, kinds: &[KindInfo], words: &[u32], pos: u32, track_depth: bool) -> u32 {
        self.starts.push(pos);
        if track_depth {
            let d = if pos == 0 {
                1
            } else {
                self.depth[parent_pos(words, pos) as usize] + 1
            };
            self.depth[pos as usize] = d;
            self.above[pos as usize] = self.max_depth;
            self.max_depth = self.max_depth.max(d);
        }
        pos + kinds[words[pos as usize] as usize].gene_words
    }
}

/// Surveys the valid genomes in `a.1` and `b.1` into `a.0` and `b.0`: their gene starts
/// and, when `track_depth`, their depths. Both walks advance in one loop, so that the
/// processor overlaps their chains of dependent loads. O(G_a + G_b).
pub(super) fn survey_pair(
    kinds: &[KindInfo],
    a: (&mut Survey, &[u32]),
    b: (&mut Survey, &[u32]),
    track_depth: bool,
) {
    let ((sa, wa), (sb, wb)) = (a, b);
    sa.begin(wa, track_depth);
    sb.begin(wb, track_depth);
    let (mut pa, mut pb) = (0u32, 0u32);
    while (pa as usize) < wa.len() && (pb as usize) < wb.len() {
        pa = sa.visit(kinds, wa, pa, track_depth);
        pb = sb.visit(kinds, wb, pb, track_depth);
    }
    while (pa as usize) < wa.len() {
        pa = sa.visit(kinds, wa, pa, track_depth);
    }
    while (pb as usize) < wb.len() {
        pb = sb.visit(kinds, wb, pb, track_depth);
    }
}

/// How a genome splits at a link: the subtree below it and the rest.
#[derive(Clone, Copy, Debug)]
pub(super) struct Split {
    /// Position of the subtree's root.
    pub root: u32,
    /// Index of the subtree's root among the genome's genes.
    pub first: usize,
    /// Position of its parent.
    pub parent: u32,
    /// Genes in the subtree.
    pub sub_genes: u32,
    /// Words in the subtree.
    pub sub_words: u32,
    /// Depth of the subtree's root.
    pub root_depth: u32,
    /// Deepest gene of the subtree.
    pub sub_max_depth: u32,
    /// Deepest gene outside the subtree.
    pub rest_max_depth: u32,
}

impl Split {
    /// The depth of the genome this split is of once `other`'s subtree replaces its own:
    /// the donated subtree keeps its own height, hung at the taken subtree's depth.
    #[inline]
    pub(super) fn depth_with(&self, other: &Split) -> u32 {
        self.rest_max_depth
            .max(self.root_depth + other.sub_max_depth - other.root_depth)
    }
}

/// Splits the valid genome in `words`, surveyed into `sv` (with depths when
/// `track_depth`), at the gene `root`: fills `sv.map`, from `root` on, with each gene's
/// position in the rest (compacted) or, marked [`SUB`], relative to the subtree's start.
/// Genes before `root` keep their positions and are not mapped. O(W from `root`).
pub(super) fn split(
    kinds: &[KindInfo],
    words: &[u32],
    sv: &mut Survey,
    root: u32,
    track_depth: bool,
) -> Split {
    cover(&mut sv.map, words.len());
    let (map, depth) = (&mut sv.map[..], &sv.depth[..]);
    let depth_at = |pos: u32| if track_depth { depth[pos as usize] } else { 0 };
    let first = sv.starts.partition_point(|&p| p < root);
    let mut s = Split {
        root,
        first,
        parent: parent_pos(words, root),
        sub_genes: 0,
        sub_words: 0,
        root_depth: depth_at(root),
        sub_max_depth: 0,
        rest_max_depth: if track_depth {
            sv.above[root as usize]
        } else {
            0
        },
    };
    let mut kept = root;
    for &pos in &sv.starts[first..] {
        let size = kinds[words[pos as usize] as usize].gene_words;
        let parent = parent_pos(words, pos);
        let d = depth_at(pos);
        if pos == root || (parent >= root && map[parent as usize] & SUB != 0) {
            map[pos as usize] = SUB | s.sub_words;
            s.sub_words += size;
            s.sub_genes += 1;
            s.sub_max_depth = s.sub_max_depth.max(d);
        } else {
            map[pos as usize] = kept;
            kept += size;
            s.rest_max_depth = s.rest_max_depth.max(d);
        }
    }
    s
}

/// A genome split by [`split`]: its words and gene starts, the map [`split`] filled for
/// it, and the split. The side that keeps its rest, or the donor of the subtree.
#[derive(Clone, Copy)]
pub(super) struct SplitGenome<'a> {
    pub words: &'a [u32],
    pub starts: &'a [u32],
    pub map: &'a [u32],
    pub split: &'a Split,
}

impl Survey {
    /// The genome in `words`, surveyed here and split by `split` (which filled the map).
    #[inline]
    pub(super) fn split_genome<'a>(
        &'a self,
        words: &'a [u32],
        split: &'a Split,
    ) -> SplitGenome<'a> {
        SplitGenome {
            words,
            starts: &self.starts,
            map: &self.map,
            split,
        }
    }
}

/// Writes into `out` the split genome `kept` without its subtree and, when given, the
/// `donor`'s subtree hung in its place (else the link that held it becomes empty). The
/// genes before the subtree's root are copied as one block; the donor's subtree goes
/// after all kept genes, in its own order.
pub(super) fn splice(
    kinds: &[KindInfo],
    out: &mut Vec<u32>,
    kept: SplitGenome<'_>,
    donor: Option<SplitGenome<'_>>,
) {
    let (keep, keep_starts, keep_map, ks) = (kept.words, kept.starts, kept.map, kept.split);
    out.clear();
    let base = keep.len() as u32 - ks.sub_words;
    out.reserve((base + donor.map_or(0, |d| d.split.sub_words)) as usize);
    let root = ks.root;
    // The genes before the root stay in place; of their links, only those to kept genes
    // from the root on change, which the sweep below patches from the child's side.
    out.extend_from_slice(&keep[..root as usize]);
    let root_link = link_of(kinds, keep, ks.parent, root - ks.parent);
    for &pos in &keep_starts[ks.first..] {
        let np = keep_map[pos as usize];
        if np & SUB != 0 {
            continue;
        }
        let k = kinds[keep[pos as usize] as usize];
        debug_assert_eq!(np as usize, out.len());
        out.extend_from_slice(&keep[pos as usize..(pos + k.gene_words) as usize]);
        let n = np as usize;
        let parent = parent_pos(keep, pos);
        let new_parent = if parent < root {
            // Links patched so far point below `pos - parent`, and the root's still
            // holds `root - parent`: only this child's link holds `pos - parent`.
            let at = link_of(kinds, out, parent, pos - parent);
            out[at] = np - parent;
            parent
        } else {
            keep_map[parent as usize]
        };
        out[n + 1] = new_parent.wrapping_sub(np);
        for w in &mut out[n + HEADER_WORDS as usize..][..k.links as usize] {
            if *w != 0 {
                *w = keep_map[(pos + *w) as usize] - np;
            }
        }
    }
    out[root_link] = if donor.is_some() { base - ks.parent } else { 0 };
    if let Some(donor) = donor {
        // The root's parent lies before it, so it did not move.
        append_subtree(kinds, out, ks.parent, donor);
    }
}

/// The word index of the link of the gene at `parent` of `words` that holds the offset
/// `off`.
#[inline]
fn link_of(kinds: &[KindInfo], words: &[u32], parent: u32, off: u32) -> usize {
    let at = (parent + HEADER_WORDS) as usize;
    let k = kinds[words[parent as usize] as usize];
    at + words[at..at + k.links as usize]
        .iter()
        .position(|&w| w == off)
        .expect("a valid genome's parent links to its child")
}

/// Writes into `out` the genome `keep` unchanged but for the `donor`'s subtree hung on
/// the empty link `link` of its gene at `at`: nothing of `keep` moves, the subtree is
/// appended after it. O(W_keep + W_donor).
pub(super) fn graft(
    kinds: &[KindInfo],
    out: &mut Vec<u32>,
    keep: &[u32],
    at: u32,
    link: u32,
    donor: SplitGenome<'_>,
) {
    out.clear();
    out.reserve(keep.len() + donor.split.sub_words as usize);
    out.extend_from_slice(keep);
    let slot = (at + HEADER_WORDS + link) as usize;
    debug_assert_eq!(out[slot], 0, "grafting onto an empty link");
    out[slot] = keep.len() as u32 - at;
    append_subtree(kinds, out, at, donor);
}

/// Appends the donor's split-off subtree to `out` in its own order, its root hanging from
/// the gene at `parent` of `out` (whose link the caller sets), recomputing the offsets:
/// the subtree's genes were not contiguous in the donor. O(W_donor from the subtree's
/// root).
fn append_subtree(kinds: &[KindInfo], out: &mut Vec<u32>, parent: u32, donor: SplitGenome<'_>) {
    let base = out.len() as u32;
    let ds = donor.split;
    for &pos in &donor.starts[ds.first..] {
        let m = donor.map[pos as usize];
        if m & SUB != 0 {
            let k = kinds[donor.words[pos as usize] as usize];
            let np = base + (m & !SUB);
            debug_assert_eq!(np as usize, out.len());
            out.extend_from_slice(&donor.words[pos as usize..(pos + k.gene_words) as usize]);
            let n = np as usize;
            let parent_np = if pos == ds.root {
                parent
            } else {
                base + (donor.map[parent_pos(donor.words, pos) as usize] & !SUB)
            };
            out[n + 1] = parent_np.wrapping_sub(np);
            for w in &mut out[n + HEADER_WORDS as usize..][..k.links as usize] {
                if *w != 0 {
                    *w = base + (donor.map[(pos + *w) as usize] & !SUB) - np;
                }
            }
        }
    }
}
