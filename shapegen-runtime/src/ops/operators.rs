//! [`Operators`] and the rules they follow ([`OperatorVariant`]).

use std::fmt;
use std::marker::PhantomData;

use serde::{Deserialize, Serialize};

use super::edit::{GeneMap, Survey};
use super::kinds::{KindInfo, LinkInfo};
use super::weight::{Fenwick, weight};
use crate::derive::Grammar;
use crate::genome::{FreshGenes, Limits, LimitsError};

/// How many times the weighted crossover draws again after a failed attempt (no link of
/// the second parent on the drawn edge, or a child breaking the limits): 4 attempts in
/// all. The original makes [`ORIGINAL_CROSSOVER_ATTEMPTS`] attempts in all.
pub const CROSSOVER_RETRIES: u32 = 3;

/// How many attempts the original's crossover makes in all before it gives up
/// (`tries <= 3` in its `Crossover_CPU::recombine`).
pub const ORIGINAL_CROSSOVER_ATTEMPTS: u32 = 3;

/// The rules the genetic operators follow.
///
/// In scene files and settings it is written `"weighted"` or `"original"`.
///
/// **`Weighted`**, the default, is the paper's description: grow picks an empty link
/// with probability proportional to its slot's probability `p`, cut an expressed link
/// proportionally to `1 - p` (never a link of `p = 1`), alter a gene with parameters
/// uniformly; crossover swaps two subtrees on the same edge of the generator graph (same
/// parent node type, slot and array index); random genomes grow to a length drawn
/// around the initial length. All of them keep genomes within the [`Limits`].
///
/// **`Original`** does what the original implementation's operators do
/// (`MutationOperator.cpp`, `CrossoverCPU.h`, `GenomeCPU.h`), read in terms of this
/// crate's graphs. The original compares genes by *symbol*; a gene's symbol here is its
/// node kind together with its index within the array slot it hangs from (0 for a
/// single slot), so that the city's `lots[k]` are the original's distinct `Lot_i_j`
/// symbols. A node's *possible children* are its links in link order, each taking at
/// most one child, as every possible child of the published grammars has `max_num` 1.
/// Where a grammar gives a node several links taking one symbol (two single slots of
/// one child kind, or a single slot and index 0 of an array slot of that kind; none of
/// the published grammars does), grow still counts each link as a possible child, and
/// crossover takes the first of them holding a child, else the first empty one, in
/// link order, as the original takes a gene's first child of the symbol.
/// - grow: draws one of the genes with an empty link, then one of that gene's empty
///   links, ignoring the probabilities (both draws as described below);
/// - cut: removes the subtree of a uniformly drawn non-root gene, `p = 1` links included;
///   if only the root is left, grows once;
/// - alter: redraws all parameters of a uniformly drawn non-root gene, which does
///   nothing if the gene has none (a city `Lot`);
/// - crossover: up to [`ORIGINAL_CROSSOVER_ATTEMPTS`] attempts; an attempt draws a
///   uniformly random non-root gene of the first parent, then one of the genes of the
///   second parent having a link that takes the drawn gene's symbol, whatever the node
///   types of the two parents; the second parent's first child of that symbol (in link
///   order) is exchanged with the drawn subtree, or, if it has none, the drawn subtree
///   is grafted onto its first empty link that takes the symbol (the first child only
///   loses its subtree). An attempt fails when the second parent has no such gene;
/// - random genomes: the root, then exactly `L - 1` grows (fewer only if nothing can
///   grow).
///
/// The original's integer draw `getRandomValue(min, max)` is `int(min + (max - min) u)`
/// for a float `u` in `[0, 1)`, and `Original` draws exactly so: `max` itself is never
/// drawn (and `min == max` gives `min` without a draw). Its uniform non-root gene is `1 + int((len - 1) u)` genes past
/// the first, which is always the root. Its draws among `n` listed candidates use
/// `max = n - 1`, so the last candidate is never taken when `n >= 2`, and `Original`
/// keeps that:
/// - grow's link: the last empty link of the gene, in link order (the original's
///   possible-children order, which the published grammars' slots follow), is taken
///   only when it is the only one: a spaceship body grows its top only once it holds a
///   next body and a wing;
/// - grow's gene and crossover's gene of the second parent: the last candidate in gene
///   order is never taken when there are several. The original's gene order is its
///   creation order, renumbered in pre-order (children in insertion order) whenever it
///   copies a genome. Packed genomes keep the creation order of what grows and crossover
///   append, which for a random genome is exactly the original's order, but no
///   insertion order of children: elsewhere `Original` leaves out the last candidate in
///   packed order, which is the original's one wherever the two orders agree.
///
/// Besides that, `Original` does not reproduce: the original redraws the axiom's
/// parameters whenever it copies a genome (none of the published grammars' axioms has
/// any); its undefined behaviour on a genome of the root alone (here alter and crossover
/// do nothing there); and its freedom from any depth bound: `Original` keeps every genome
/// within [`DEPTH_CAP`](crate::genome::DEPTH_CAP), growing no gene at that depth and
/// counting a crossover attempt that would go deeper as failed.
///
/// Nothing in the original's operators checks the genome limits, and `Original` does not
/// apply [`Limits`] either: genomes may grow longer than `max_len`, deeper than
/// `max_depth` and be cut below `min_len`. The original's GA drops children outside
/// `[min_len, max_len)` instead, and so does this crate's [`Ga`](crate::optimize::Ga)
/// with this variant.
///
/// ```
/// use shapegen_runtime::ops::OperatorVariant;
///
/// let v: OperatorVariant = serde_json::from_str("\"original\"")?;
/// assert_eq!(v, OperatorVariant::Original);
/// assert_eq!(v.name(), "original");
/// assert_eq!(OperatorVariant::default(), OperatorVariant::Weighted);
/// # Ok::<(), serde_json::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum OperatorVariant {
    /// The paper's operators, weighted by the grammar's probabilities, within the limits.
    #[default]
    Weighted,
    /// The original implementation's operators.
    Original,
}

impl OperatorVariant {
    /// Every variant.
    pub const ALL: [OperatorVariant; 2] = [OperatorVariant::Weighted, OperatorVariant::Original];

    /// Its name in scene files and settings.
    pub const fn name(self) -> &'static str {
        match self {
            OperatorVariant::Weighted => "weighted",
            OperatorVariant::Original => "original",
        }
    }
}

/// The genetic operators for genomes of grammar `G`, following an [`OperatorVariant`]'s
/// rules; the weighted ones keep genomes within [`Limits`].
///
/// Holds scratch buffers; keep one per thread and reuse it.
///
/// ```
/// use shapegen_runtime::genome::Limits;
/// use shapegen_runtime::ops::{OperatorVariant, Operators};
/// # shapegen_runtime::generator! {
/// #     pub Chain {
/// #         axiom Seg;
/// #         node Seg {
/// #             children { next: Seg = 0.5 }
/// #             derive(s) {
/// #                 use shapegen_runtime::prelude::CUBE;
/// #                 s.emit(CUBE);
/// #                 if let Some(next) = next { s.derive(next); }
/// #             }
/// #         }
/// #     }
/// # }
///
/// let ops = Operators::<Chain>::new(Limits::new(4, 100, 12)?)?
///     .with_variant(OperatorVariant::Original)
///     .with_cross_array_index(false);
/// assert_eq!(ops.variant(), OperatorVariant::Original);
/// assert!(!ops.cross_array_index());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Operators<G> {
    pub(super) limits: Limits,
    pub(super) variant: OperatorVariant,
    pub(super) cross_array_index: bool,
    pub(super) kinds: Vec<KindInfo>,
    pub(super) links: Vec<LinkInfo>,
    /// Words of the largest gene any link takes: what one grow appends at most.
    pub(super) child_words: u32,
    /// How new genes are written.
    pub(super) fresh: FreshGenes<G>,
    pub(super) s: Scratch,
    _g: PhantomData<fn() -> G>,
}

impl<G> fmt::Debug for Operators<G> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Operators")
            .field("limits", &self.limits)
            .field("variant", &self.variant)
            .field("cross_array_index", &self.cross_array_index)
            .finish_non_exhaustive()
    }
}

impl<G> Clone for Operators<G> {
    /// A copy with the same limits and rules and fresh scratch buffers.
    fn clone(&self) -> Self {
        Operators {
            limits: self.limits,
            variant: self.variant,
            cross_array_index: self.cross_array_index,
            kinds: self.kinds.clone(),
            links: self.links.clone(),
            child_words: self.child_words,
            fresh: self.fresh.clone(),
            s: Scratch::default(),
            _g: PhantomData,
        }
    }
}

/// Reusable buffers. Word-indexed ones hold meaningful values at gene starts only.
#[derive(Default)]
pub(super) struct Scratch {
    pub(super) genes: GeneMap,
    pub(super) cand: Vec<u32>,
    pub(super) cum: Vec<u64>,
    pub(super) depth: Vec<u32>,
    /// Crossover's surveys of its first and second parent.
    pub(super) pa: Survey,
    pub(super) pb: Survey,
    pub(super) fenwick: Fenwick,
    /// Open links of [`Self::fenwick`] or the sampling queue: (gene, link, depth).
    pub(super) owners: Vec<(u32, u32, u32)>,
}

impl<G: Grammar> Operators<G> {
    /// Weighted operators keeping genomes within `limits`, array-slot links matching
    /// only on the same index; fails if the limits cannot be met together (see
    /// [`Limits::check`]).
    pub fn new(limits: Limits) -> Result<Self, LimitsError> {
        limits.check()?;
        let mut kinds = Vec::with_capacity(G::GRAPH.nodes.len());
        let mut links = Vec::new();
        for node in G::GRAPH.nodes {
            kinds.push(KindInfo {
                first_link: links.len() as u32,
                links: node.links,
                gene_words: node.gene_words(),
                has_params: !node.params.is_empty(),
            });
            for link in 0..node.links {
                let slot = node
                    .slots
                    .iter()
                    .position(|s| link >= s.first_link && link < s.first_link + s.count)
                    .expect("the grammar's slots cover every link");
                let sdesc = &node.slots[slot];
                links.push(LinkInfo {
                    grow: weight(sdesc.probability),
                    child: sdesc.child,
                    slot: slot as u32,
                    index: link - sdesc.first_link,
                });
            }
        }
        let child_words = links
            .iter()
            .map(|l| kinds[l.child as usize].gene_words)
            .max()
            .unwrap_or(0);
        Ok(Operators {
            limits,
            variant: OperatorVariant::Weighted,
            cross_array_index: false,
            kinds,
            links,
            child_words,
            fresh: FreshGenes::new(),
            s: Scratch::default(),
            _g: PhantomData,
        })
    }

    /// These operators following `variant`'s rules.
    pub fn with_variant(mut self, variant: OperatorVariant) -> Self {
        self.variant = variant;
        self
    }

    /// These operators with array-slot links matching across indices in crossover
    /// (`true`: a subtree on `lots[i]` may be exchanged with one on `lots[j]`, moving it
    /// to another index) or only on the same index (`false`, the default).
    pub fn with_cross_array_index(mut self, cross: bool) -> Self {
        self.cross_array_index = cross;
        self
    }

    /// The rules the operators follow.
    pub fn variant(&self) -> OperatorVariant {
        self.variant
    }

    /// Whether crossover matches array-slot links across indices.
    pub fn cross_array_index(&self) -> bool {
        self.cross_array_index
    }

    /// The limits the weighted operators keep genomes within.
    pub fn limits(&self) -> &Limits {
        &self.limits
    }

    /// Changes the limits; fails, leaving them as they were, if they cannot be met.
    pub fn set_limits(&mut self, limits: Limits) -> Result<(), LimitsError> {
        limits.check()?;
        self.limits = limits;
        Ok(())
    }

    /// The node facts of the gene starting at `pos`.
    #[inline]
    pub(super) fn kind_at(&self, words: &[u32], pos: u32) -> KindInfo {
        self.kinds[words[pos as usize] as usize]
    }

    /// The link facts of link `link` of a gene of kind `k`.
    #[inline]
    pub(super) fn link(&self, k: &KindInfo, link: u32) -> LinkInfo {
        self.links[(k.first_link + link) as usize]
    }
}

impl<G: Grammar> Operators<G> {
    /// [`GeneMap::record`] of the genome in `words` into the scratch: each gene's start,
    /// parent and link.
    pub(super) fn map_links(&mut self, words: &[u32]) {
        self.s
            .genes
            .record(&self.kinds, &self.links, words, |_, _| {});
    }
}
