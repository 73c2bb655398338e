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
    let words = genome.words();
    depths::<G>(words, depth);
    for gene in genome.genes() {
        let pos = gene.pos();
        if depth[pos as usize] >= limits.max_depth {
            continue;
        }
        let node = node_of::<G>(gene.kind());
        for link in 0..node.links {
            if words[(pos + HEADER_WORDS + link) as usize] == 0
                && link_facts::<G>(gene.kind(), link).0 > 0.0
            {
                open.push((pos, link));
            }
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
/// generator probability.
pub(crate) fn jump_links<G: Grammar>(
    genome: &Genome<G>,
    limits: &Limits,
    depth: &mut Vec<u32>,
    links: &mut Vec<(u32, u32)>,
) {
    links.clear();
    let words = genome.words();
    depths::<G>(words, depth);
    for gene in genome.genes() {
        let pos = gene.pos();
        if depth[pos as usize] >= limits.max_depth {
            continue;
        }
        for link in 0..node_of::<G>(gene.kind()).links {
            if words[(pos + HEADER_WORDS + link) as usize] != 0
                || link_facts::<G>(gene.kind(), link).0 > 0.0
            {
                links.push((pos, link));
            }
        }
    }
}
