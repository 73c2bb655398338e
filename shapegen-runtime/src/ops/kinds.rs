//! What the operators know of a grammar's node types and links, by kind, and the gene
//! starts of a genome.

/// What the operators need to know of a node type, by kind.
#[derive(Clone, Copy, Debug)]
pub(super) struct KindInfo {
    /// Index of the node's first link in [`Operators::links`].
    pub(super) first_link: u32,
    /// Number of links.
    pub(super) links: u32,
    /// Gene size in words.
    pub(super) gene_words: u32,
    /// Whether the node has parameters.
    pub(super) has_params: bool,
}

/// What the operators need to know of one link of a node type.
#[derive(Clone, Copy, Debug)]
pub(super) struct LinkInfo {
    /// Fixed-point probability of the child: the grow weight; `ONE - grow` is the cut
    /// weight.
    pub(super) grow: u64,
    /// Node kind of the child.
    pub(super) child: u32,
    /// Index of the link's slot among the node's slots.
    pub(super) slot: u32,
    /// Index of the link within its slot: 0 for a single slot.
    pub(super) index: u32,
}

/// Fills `starts` with the word position of every gene of `words`, in order.
pub(super) fn gene_starts(kinds: &[KindInfo], words: &[u32], starts: &mut Vec<u32>) {
    starts.clear();
    let mut pos = 0u32;
    while (pos as usize) < words.len() {
        starts.push(pos);
        pos += kinds[words[pos as usize] as usize].gene_words;
    }
}
