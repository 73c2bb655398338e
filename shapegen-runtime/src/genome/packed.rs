//! [`Genome`] itself: its words, its derivation, and the helpers that walk its genes.

use std::marker::PhantomData;

use rand::Rng;

use crate::derive::{Derivation, GeneView, Grammar, Site};
use crate::geometry::Instance;
use crate::graph::{GeneratorGraph, HEADER_WORDS, NodeDesc};
use crate::param;

/// The deepest tree any genome may hold: bounds the recursion of derivation.
pub const DEPTH_CAP: u32 = 1024;

/// A derivation tree of grammar `G`, packed.
pub struct Genome<G> {
    pub(crate) words: Vec<u32>,
    pub(crate) len: u32,
    _g: PhantomData<fn() -> G>,
}

impl<G> Clone for Genome<G> {
    fn clone(&self) -> Self {
        Genome {
            words: self.words.clone(),
            len: self.len,
            _g: PhantomData,
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.words.clone_from(&source.words);
        self.len = source.len;
    }
}

impl<G> PartialEq for Genome<G> {
    fn eq(&self, other: &Self) -> bool {
        self.words == other.words
    }
}

impl<G> Eq for Genome<G> {}

impl<G: Grammar> Genome<G> {
    /// The grammar's graph.
    #[inline]
    pub fn graph() -> &'static GeneratorGraph {
        G::GRAPH
    }

    /// A genome holding only the axiom, its parameters drawn from `rng`.
    pub fn axiom(rng: &mut impl Rng) -> Self {
        let mut genome = Genome {
            words: Vec::new(),
            len: 0,
            _g: PhantomData,
        };
        genome.push_gene(G::GRAPH.axiom, None, rng);
        genome
    }

    /// Builds a genome from raw words and gene count without checking them.
    pub(crate) fn from_parts(words: Vec<u32>, len: u32) -> Self {
        Genome {
            words,
            len,
            _g: PhantomData,
        }
    }

    /// Replaces this genome by the axiom alone, its parameters drawn from `rng`, reusing
    /// the allocation.
    pub(crate) fn reset_to_axiom(&mut self, rng: &mut impl Rng) {
        self.words.clear();
        self.len = 0;
        self.push_gene(G::GRAPH.axiom, None, rng);
    }

    /// Number of genes: nodes of the derivation tree.
    #[inline]
    pub fn len(&self) -> usize {
        self.len as usize
    }

    /// Always `false`: a genome holds at least its axiom.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The packed words.
    #[inline]
    pub fn words(&self) -> &[u32] {
        &self.words
    }

    /// The root gene.
    #[inline]
    pub fn root(&self) -> GeneView<'_> {
        GeneView::new(&self.words, 0)
    }

    /// The gene at word position `pos`. `pos` must be the start of a gene.
    #[inline]
    pub fn gene(&self, pos: u32) -> GeneView<'_> {
        GeneView::new(&self.words, pos)
    }

    /// Every gene, in buffer order (every parent before its children).
    pub fn genes(&self) -> impl Iterator<Item = GeneView<'_>> + '_ {
        let words = &self.words[..];
        let mut pos = 0u32;
        std::iter::from_fn(move || {
            if pos as usize >= words.len() {
                return None;
            }
            let gene = GeneView::new(words, pos);
            pos += node_of::<G>(gene.kind()).gene_words();
            Some(gene)
        })
    }

    /// The node type of a gene of this genome.
    #[inline]
    pub fn node(&self, gene: GeneView<'_>) -> &'static NodeDesc {
        node_of::<G>(gene.kind())
    }

    /// Derives the model: runs the rules from the root in the axiom's unit scope and
    /// writes the emitted mesh instances into `out`, replacing what it held and reusing
    /// its allocation. The model grows on no site ([`Site::NONE`]); see
    /// [`derive_on`](Self::derive_on).
    pub fn derive_into(&self, out: &mut Vec<Instance>) {
        self.derive_on(&Site::NONE, out);
    }

    /// Derives the model like [`derive_into`](Self::derive_into), growing it on `site`
    /// (a lot for a building, say), which its rules read through
    /// [`Shape::site`](crate::Shape::site).
    pub fn derive_on(&self, site: &Site, out: &mut Vec<Instance>) {
        out.clear();
        Derivation::run::<G>(&self.words, site, out);
    }

    /// Derives the model like [`derive_into`](Self::derive_into), appending its
    /// instances to what `out` already holds (a population's models back to back).
    pub fn derive_append(&self, out: &mut Vec<Instance>) {
        self.derive_append_on(&Site::NONE, out);
    }

    /// Derives the model on `site` like [`derive_on`](Self::derive_on), appending its
    /// instances to what `out` already holds.
    pub fn derive_append_on(&self, site: &Site, out: &mut Vec<Instance>) {
        Derivation::run::<G>(&self.words, site, out);
    }

    /// Appends a gene of kind `kind` with parameters drawn from `rng`, linked from
    /// `parent` on link `link` when given; returns its word position. O(gene words).
    pub(crate) fn push_gene(
        &mut self,
        kind: u32,
        parent: Option<(u32, u32)>,
        rng: &mut impl Rng,
    ) -> u32 {
        let node = node_of::<G>(kind);
        let pos = self.words.len() as u32;
        let up = parent.map_or(0, |(parent, _)| (parent as i32 - pos as i32) as u32);
        self.words.extend([kind, up]);
        self.words.resize((pos + node.gene_words()) as usize, 0);
        if let Some((parent, link)) = parent {
            self.words[(parent + HEADER_WORDS + link) as usize] = pos - parent;
        }
        let params = &mut self.words[(pos + HEADER_WORDS + node.links) as usize..];
        for p in node.params {
            param::sample(&p.dist, rng, &mut params[p.offset as usize..]);
        }
        self.len += 1;
        pos
    }
}

/// Word position of the parent of the (non-root) gene at `pos`.
#[inline]
pub(crate) fn parent_pos(words: &[u32], pos: u32) -> u32 {
    pos.wrapping_add_signed(words[pos as usize + 1] as i32)
}

/// Fills `depth`, indexed by word position, with the depth of each gene of the valid
/// genome in `words` (entries between gene starts are left as they were); returns the
/// tree's depth. O(G).
pub(crate) fn depths<G: Grammar>(words: &[u32], depth: &mut Vec<u32>) -> u32 {
    if depth.len() < words.len() {
        depth.resize(words.len(), 0);
    }
    let mut max = 0;
    let mut pos = 0u32;
    while (pos as usize) < words.len() {
        let d = if pos == 0 {
            1
        } else {
            depth[parent_pos(words, pos) as usize] + 1
        };
        depth[pos as usize] = d;
        max = max.max(d);
        pos += node_of::<G>(words[pos as usize]).gene_words();
    }
    max
}

/// The node type of kind `kind` in `G`'s graph.
#[inline]
pub(crate) fn node_of<G: Grammar>(kind: u32) -> &'static NodeDesc {
    G::GRAPH.node_unchecked(kind)
}
