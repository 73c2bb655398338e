//! Growing a genome at one chosen link, for the step-by-step optimizers: the open links
//! of a genome, and expansion of a link or a whole subtree as the generator would.

use rand::{Rng, RngExt};

use crate::derive::Grammar;
use crate::genome::{Genome, Limits, depths, node_of, parent_pos};
use crate::graph::HEADER_WORDS;

/// The generator probability of link `link` of a gene of kind `kind`, and the child kind.
pub(crate) fn link_facts<G: Grammar>(kind: u32, link: u32) -> (f32, u32) {
    let slot = node_of::<G>(kind)
        .slot_of_link(link)
        .expect("links lie within their node's slots");
    (slot.probability, slot.child)
}

/// Depth of the gene at `pos` (the root is 1). O(depth).
pub(crate) fn depth_of(words: &[u32], mut pos: u32) -> u32 {
    let mut d = 1;
    while pos != 0 {
        pos = parent_pos(words, pos);
        d += 1;
    }
    d
}

/// Fills `open` with every empty link (gene position, link) that may grow under
/// `limits` (its gene above the maximum depth, a non-zero generator probability).
pub(crate) fn open_links<G: Grammar>(
    genome: &Genome<G>,
    limits: &Limits,
    depth: &mut Vec<u32>,
    open: &mut Vec<(u32, u32)>,
) {
    open.clear();
    for_each_link(genome, limits, depth, |pos, _, link, child, p| {
        if child == 0 && p > 0.0 {
            open.push((pos, link));
        }
    });
}

/// Calls `visit(pos, depth, link, child, p)` for every link of every gene above the
/// maximum depth: the gene's position and depth (filling `depth` by position), the
/// link, its word (the child's offset, 0 when empty) and its generator probability.
#[inline]
fn for_each_link<G: Grammar>(
    genome: &Genome<G>,
    limits: &Limits,
    depth: &mut Vec<u32>,
    mut visit: impl FnMut(u32, u32, u32, u32, f32),
) {
    let words = genome.words();
    depths::<G>(words, depth);
    for gene in genome.genes() {
        let pos = gene.pos();
        let d = depth[pos as usize];
        if d >= limits.max_depth {
            continue;
        }
        for link in 0..node_of::<G>(gene.kind()).links {
            let child = words[(pos + HEADER_WORDS + link) as usize];
            visit(pos, d, link, child, link_facts::<G>(gene.kind(), link).0);
        }
    }
}

/// Expresses the empty link `link` of the gene at `pos` with a child drawn from its
/// distributions; returns its position, or `None` at the maximum length.
pub(crate) fn expand<G: Grammar>(
    genome: &mut Genome<G>,
    limits: &Limits,
    pos: u32,
    link: u32,
    rng: &mut impl Rng,
) -> Option<u32> {
    if genome.len() as u32 >= limits.max_len {
        return None;
    }
    let kind = genome.words()[pos as usize];
    let child = link_facts::<G>(kind, link).1;
    Some(genome.push_gene(child, Some((pos, link)), rng))
}
/// Draws the subtree below the empty link `link` of the gene at `pos` as the generator
/// would: the link is expressed with its probability, then every link of every new gene
/// with its own, breadth first, within the limits. `queue` is scratch. Returns the
/// position of the new subtree's root, if any.
pub(crate) fn sample_subtree<G: Grammar>(
    genome: &mut Genome<G>,
    limits: &Limits,
    pos: u32,
    link: u32,
    queue: &mut Vec<(u32, u32)>,
    rng: &mut impl Rng,
) -> Option<u32> {
    queue.clear();
    queue.push((pos, depth_of(genome.words(), pos)));
    let mut root = None;
    let mut head = 0;
    while head < queue.len() {
        let (at, depth) = queue[head];
        head += 1;
        if depth >= limits.max_depth {
            continue;
        }
        let kind = genome.words()[at as usize];
        let links = if head == 1 {
            link..link + 1
        } else {
            0..node_of::<G>(kind).links
        };
        for l in links {
            let (p, _) = link_facts::<G>(kind, l);
            if rng.random::<f32>() < p {
                let Some(child) = expand(genome, limits, at, l, rng) else {
                    return root;
                };
                root.get_or_insert(child);
                queue.push((child, depth + 1));
            }
        }
    }
    root
}

/// Fills `links` with every link (gene position, link), empty or not, that a jump may
/// redraw: links of genes above the maximum depth that are expressed or have a non-zero
/// generator probability, except those whose redraw must give the genome back unchanged
/// (see [`regrows_identically`]): such a jump would only cost an evaluation. `stack` is
/// scratch.
pub(crate) fn jump_links<G: Grammar>(
    genome: &Genome<G>,
    limits: &Limits,
    depth: &mut Vec<u32>,
    links: &mut Vec<(u32, u32)>,
    stack: &mut Vec<(u32, u32)>,
) {
    links.clear();
    let words = genome.words();
    for_each_link(genome, limits, depth, |pos, d, link, child, p| {
        let redrawn = if child == 0 {
            p > 0.0
        } else {
            p < 1.0 || !regrows_identically::<G>(words, pos + child, d + 1, limits, stack)
        };
        if redrawn {
            links.push((pos, link));
        }
    });
}

/// Whether a jump's redraw of the subtree at `root` (depth `root_depth`), the child of a
/// probability-1 link, must give it back unchanged: the link is expressed again, the
/// root keeps its parameter values, and [`sample_subtree`] redraws the rest. That is so
/// when every gene below the root has no parameters and every link of the subtree's
/// genes above the maximum depth is expressed exactly when its probability is 1, the
/// others having probability 0 (genes at the maximum depth have no children). The
/// redraw adds as many genes as the cut removed, so the maximum length never truncates
/// it. `stack` is scratch. O(size of the subtree), stopping at the first difference.
fn regrows_identically<G: Grammar>(
    words: &[u32],
    root: u32,
    root_depth: u32,
    limits: &Limits,
    stack: &mut Vec<(u32, u32)>,
) -> bool {
    stack.clear();
    stack.push((root, root_depth));
    while let Some((pos, d)) = stack.pop() {
        let kind = words[pos as usize];
        let node = node_of::<G>(kind);
        if pos != root && node.param_words > 0 {
            return false;
        }
        for link in 0..node.links {
            let child = words[(pos + HEADER_WORDS + link) as usize];
            if d >= limits.max_depth {
                if child != 0 {
                    return false;
                }
                continue;
            }
            let p = link_facts::<G>(kind, link).0;
            if p == 1.0 && child != 0 {
                stack.push((pos + child, d + 1));
            } else if p != 0.0 || child != 0 {
                return false;
            }
        }
    }
    true
}
