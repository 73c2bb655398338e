//! What can be wrong with a genome, or with a request to build or change one.

use std::fmt;

/// Where a gene is: its index in buffer order, its word position and its node type.
///
/// Shown as ``gene 3 (`Body` @12)``.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GeneAt {
    /// Index of the gene in buffer order (the root is gene 0).
    pub index: u32,
    /// Word position of the gene's first word.
    pub pos: u32,
    /// Name of the gene's node type.
    pub node: &'static str,
}

impl fmt::Display for GeneAt {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "gene {} (`{}` @{})", self.index, self.node, self.pos)
    }
}

/// One child link of a node type: its slot's name and, for an array slot, the index.
///
/// Shown as ``slot `next` `` or ``slot `lots[3]` ``.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SlotAt {
    /// Name of the slot.
    pub slot: &'static str,
    /// Index within an array slot; `None` for a single slot.
    pub index: Option<u32>,
}

impl fmt::Display for SlotAt {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.index {
            Some(i) => write!(f, "slot `{}[{i}]`", self.slot),
            None => write!(f, "slot `{}`", self.slot),
        }
    }
}

/// Why a genome is not valid, or why a requested change to it cannot be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GenomeError {
    /// The buffer holds no gene.
    #[error("the genome holds no gene; it needs at least its root, of the axiom `{axiom}`")]
    Empty {
        /// Name of the axiom node.
        axiom: &'static str,
    },
    /// A gene's kind is not a node of the grammar.
    #[error(
        "gene {index} @{pos} has node kind {kind}, but `{generator}` only has kinds 0..{kinds}"
    )]
    UnknownKind {
        /// Index of the gene.
        index: u32,
        /// Word position of the gene.
        pos: u32,
        /// The kind found.
        kind: u32,
        /// Name of the grammar.
        generator: &'static str,
        /// Number of node kinds of the grammar.
        kinds: u32,
    },
    /// A gene runs past the end of the buffer.
    #[error("{at} needs {need} words, but the buffer ends {left} words after its start")]
    Truncated {
        /// The gene.
        at: GeneAt,
        /// Words the gene's node type takes.
        need: u32,
        /// Words left from the gene's start.
        left: u32,
    },
    /// The gene at word 0 is not of the axiom's kind.
    #[error("the root gene is `{node}`, but the axiom of `{generator}` is `{axiom}`")]
    RootNotAxiom {
        /// Node of the root gene found.
        node: &'static str,
        /// Name of the grammar.
        generator: &'static str,
        /// Name of the axiom node.
        axiom: &'static str,
    },
    /// The root gene has a parent offset.
    #[error("the root gene has parent offset {offset}; the root's parent offset must be 0")]
    RootHasParent {
        /// The offset found.
        offset: i32,
    },
    /// A gene other than the root does not point back to an earlier gene.
    #[error(
        "{at} has parent offset {offset}; every gene but the root lies after its parent, so \
         its parent offset must be negative"
    )]
    ParentNotBefore {
        /// The gene.
        at: GeneAt,
        /// The offset found.
        offset: i32,
    },
    /// A gene's parent offset does not land on the start of a gene.
    #[error(
        "{at} has parent offset {offset}, which lands on word {target}: not the start of a gene"
    )]
    ParentNotGene {
        /// The gene.
        at: GeneAt,
        /// The offset found.
        offset: i32,
        /// The word it lands on.
        target: i64,
    },
    /// A gene's parent does not link to it on exactly one link.
    #[error(
        "{at} names {parent} as its parent, which links to it on {links} links instead of exactly one"
    )]
    NotLinkedBack {
        /// The child gene.
        at: GeneAt,
        /// Its parent.
        parent: GeneAt,
        /// Number of the parent's links that point to the child.
        links: u32,
    },
    /// A link does not point forward.
    #[error(
        "{at}: {slot} has offset {offset}; a child lies after its parent, so a link's offset \
         is positive (or 0 when the child is absent)"
    )]
    LinkNotForward {
        /// The parent gene.
        at: GeneAt,
        /// The link.
        slot: SlotAt,
        /// The offset found.
        offset: i32,
    },
    /// A link does not land on the start of a gene.
    #[error(
        "{at}: {slot} has offset {offset}, which lands on word {target}: not the start of a gene"
    )]
    LinkNotGene {
        /// The parent gene.
        at: GeneAt,
        /// The link.
        slot: SlotAt,
        /// The offset found.
        offset: i32,
        /// The word it lands on.
        target: i64,
    },
    /// A link points to a gene of a node type its slot does not hold.
    #[error("{at}: {slot} links to {child}, but that slot holds `{expected}` genes")]
    WrongChildKind {
        /// The parent gene.
        at: GeneAt,
        /// The link.
        slot: SlotAt,
        /// The gene linked to.
        child: GeneAt,
        /// Node type the slot holds.
        expected: &'static str,
    },
    /// A link points to a gene whose parent is another gene: that gene is linked twice.
    #[error(
        "{at}: {slot} links to {child}, whose parent offset names word {child_parent} instead; \
         a gene is linked from its own parent only"
    )]
    ForeignChild {
        /// The gene holding the link.
        at: GeneAt,
        /// The link.
        slot: SlotAt,
        /// The gene linked to.
        child: GeneAt,
        /// Word its parent offset lands on.
        child_parent: i64,
    },
    /// The recorded gene count differs from the genes in the buffer.
    #[error("the genome records {recorded} genes, but its buffer holds {actual}")]
    CountMismatch {
        /// Count recorded.
        recorded: u32,
        /// Genes found in the buffer.
        actual: u32,
    },
    /// A parameter value lies outside its distribution.
    #[error("{at}: parameter `{param}`: {reason}")]
    Param {
        /// The gene.
        at: GeneAt,
        /// Name of the parameter.
        param: &'static str,
        /// What is wrong, and the valid range.
        reason: String,
    },
    /// A gene lies deeper than any genome may.
    #[error("{at} lies at depth {depth}; no genome may be deeper than {cap}")]
    TooDeep {
        /// The gene.
        at: GeneAt,
        /// Its depth.
        depth: u32,
        /// [`DEPTH_CAP`](super::DEPTH_CAP).
        cap: u32,
    },
    /// The genome is shorter than the limits allow.
    #[error("the genome has {len} genes, fewer than the minimum length {min_len}")]
    TooShort {
        /// Genes in the genome.
        len: u32,
        /// The limit.
        min_len: u32,
    },
    /// The genome is longer than the limits allow.
    #[error("the genome has {len} genes, more than the maximum length {max_len}")]
    TooLong {
        /// Genes in the genome.
        len: u32,
        /// The limit.
        max_len: u32,
    },
    /// A gene lies deeper than the limits allow.
    #[error("{at} lies at depth {depth}, deeper than the maximum depth {max_depth}")]
    DeeperThanLimit {
        /// The first gene found that deep.
        at: GeneAt,
        /// Its depth.
        depth: u32,
        /// The limit.
        max_depth: u32,
    },
    /// A word position given to a builder is not the start of a gene.
    #[error("word {pos} is not the start of a gene of this genome ({words} words)")]
    NotAGene {
        /// The position given.
        pos: u32,
        /// Words in the genome.
        words: u32,
    },
    /// The node type has no slot of that name.
    #[error("`{node}` has no child slot `{slot}`; its slots are: {valid}")]
    UnknownSlot {
        /// The parent's node type.
        node: &'static str,
        /// The slot name given.
        slot: String,
        /// The node's slots, or "none".
        valid: String,
    },
    /// An array slot was named without an index.
    #[error("slot `{slot}` of `{node}` is an array of {count}; name the index with `attach_at`")]
    NeedsIndex {
        /// The parent's node type.
        node: &'static str,
        /// The slot.
        slot: &'static str,
        /// Links in the array.
        count: u32,
    },
    /// An index was given for a single slot, or is beyond an array slot's end.
    #[error("slot `{slot}` of `{node}` has indices 0..{count}; {index} is not one of them")]
    SlotIndex {
        /// The parent's node type.
        node: &'static str,
        /// The slot.
        slot: &'static str,
        /// The index given.
        index: u32,
        /// Links in the slot.
        count: u32,
    },
    /// The parameters given are of another node type than the slot (or axiom) holds.
    #[error("{place} holds `{expected}` genes, but the parameters given are of `{given}`")]
    WrongNode {
        /// What was being filled: a slot, or the root.
        place: String,
        /// Node type expected.
        expected: &'static str,
        /// Node type of the parameters given.
        given: &'static str,
    },
    /// The parameter type given belongs to no node of this grammar.
    #[error(
        "the parameters given (node kind {kind}, {links} links, {words} words) are of no node \
         of `{generator}`; were they declared by another grammar?"
    )]
    ForeignParams {
        /// `NodeParams::KIND` of the type given.
        kind: u32,
        /// `NodeParams::LINKS` of the type given.
        links: u32,
        /// `NodeParams::WORDS` of the type given.
        words: u32,
        /// Name of the grammar.
        generator: &'static str,
    },
    /// The link to fill already holds a child.
    #[error("{at}: {slot} already holds the gene @{child}")]
    Occupied {
        /// The parent gene.
        at: GeneAt,
        /// The link.
        slot: SlotAt,
        /// Word position of the child there.
        child: u32,
    },
    /// The root was named where a gene hanging from a parent link is needed.
    #[error("word 0 is the root gene, which hangs from no link; name a gene below it")]
    IsRoot,
    /// Two subtrees to swap hang from different edges of the generator graph.
    #[error(
        "{a} hangs from {a_edge} but {b} from {b_edge}; only subtrees on the same edge of \
         the generator graph can be swapped"
    )]
    EdgeMismatch {
        /// Root of the first subtree.
        a: GeneAt,
        /// The edge it hangs from, as ``slot `next` of `Body` ``.
        a_edge: String,
        /// Root of the second subtree.
        b: GeneAt,
        /// The edge it hangs from.
        b_edge: String,
    },
}
