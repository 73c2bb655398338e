//! The genetic operators on packed genomes, with the paper's probabilities: grow, cut,
//! alter (the original's "permutate"), crossover, and the two ways to make a genome from
//! nothing: a random genome grown to a target length (the GA's initial population) and
//! an uncontrolled sample of the generator's own distribution.
//!
//! All of them live on [`Operators`], which holds the [`Limits`] they keep genomes within,
//! the grammar's link probabilities as exact fixed-point weights, and scratch buffers, so
//! that they allocate nothing once warmed up (crossover's children may be written into
//! existing genomes with [`Operators::crossover_into`]). Every choice is made with exact
//! integer arithmetic from the caller's RNG: the same seed gives the same genomes.
//!
//! Costs, with G the genome's length in genes and W its length in words: grow, cut,
//! alter and crossover are O(W); [`Operators::random`] and [`Operators::grow_to`] are
//! O(G log G); [`Operators::sample`] is O(W).
//!
//! ```
//! use rand::SeedableRng;
//! use rand_chacha::ChaCha8Rng;
//! use shapegen_runtime::prelude::*;
//!
//! generator! {
//!     /// A stack of segments with side branches.
//!     pub Chain {
//!         axiom Start;
//!         node Start { children { first: Seg = 0.9 } }
//!         node Seg {
//!             params { len: f32 ~ uniform(0.5, 1.5) }
//!             children { next: Seg = 0.5, side: Seg = 0.25 }
//!             derive(s) {
//!                 let s = s.resize(vec3(1.0, len, 1.0));
//!                 s.emit(CUBE);
//!                 if let Some(next) = next {
//!                     s.translate(vec3(0.0, s.size().y, 0.0)).derive(next);
//!                 }
//!                 if let Some(side) = side {
//!                     s.rotate_z(0.5).translate(vec3(0.0, s.size().y, 0.0)).derive(side);
//!                 }
//!             }
//!         }
//!     }
//! }
//!
//! // The examples of the operators below use this grammar.
//! let mut ops = Operators::<Chain>::new(Limits::new(2, 40, 10)?)?;
//! let mut rng = ChaCha8Rng::seed_from_u64(1);
//! let mut a = ops.random(20, &mut rng);
//! let b = ops.random(20, &mut rng);
//! ops.grow(&mut a, &mut rng);
//! ops.cut(&mut a, &mut rng);
//! ops.alter(&mut a, &mut rng);
//! if let Some((c, d)) = ops.crossover(&a, &b, &mut rng) {
//!     assert!(c.validate().is_ok() && d.validate_limits(ops.limits()).is_ok());
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod alter;
mod crossover;
mod cut;
mod edit;
mod grow;
mod random;
mod weight;

use std::fmt;
use std::marker::PhantomData;

use crate::derive::Grammar;
use crate::genome::{Limits, LimitsError};
use weight::{Fenwick, weight};

/// How many times crossover draws a new link in the first parent when the second has no
/// link on the same edge, or the children would break the limits (as the original did).
pub const CROSSOVER_RETRIES: u32 = 3;

/// The genetic operators for genomes of grammar `G`, keeping them within [`Limits`].
///
/// Holds scratch buffers; keep one per thread and reuse it.
pub struct Operators<G> {
    limits: Limits,
    kinds: Vec<KindInfo>,
    links: Vec<LinkInfo>,
    s: Scratch,
    _g: PhantomData<fn() -> G>,
}

impl<G> fmt::Debug for Operators<G> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Operators")
            .field("limits", &self.limits)
            .finish_non_exhaustive()
    }
}

impl<G> Clone for Operators<G> {
    /// A copy with the same limits and fresh scratch buffers.
    fn clone(&self) -> Self {
        Operators {
            limits: self.limits,
            kinds: self.kinds.clone(),
            links: self.links.clone(),
            s: Scratch::default(),
            _g: PhantomData,
        }
    }
}

/// What the operators need to know of a node type, by kind.
#[derive(Clone, Copy, Debug)]
struct KindInfo {
    /// Index of the node's first link in [`Operators::links`].
    first_link: u32,
    /// Number of links.
    links: u32,
    /// Gene size in words.
    gene_words: u32,
    /// Whether the node has parameters.
    has_params: bool,
}

/// What the operators need to know of one link of a node type.
#[derive(Clone, Copy, Debug)]
struct LinkInfo {
    /// Fixed-point probability of the child: the grow weight; `ONE - grow` is the cut
    /// weight.
    grow: u64,
    /// Node kind of the child.
    child: u32,
    /// Index of the link's slot among the node's slots.
    slot: u32,
}

/// Reusable buffers. Word-indexed ones hold meaningful values at gene starts only.
#[derive(Default)]
struct Scratch {
    starts: Vec<u32>,
    starts_b: Vec<u32>,
    cand: Vec<u32>,
    cum: Vec<u64>,
    depth: Vec<u32>,
    depth_b: Vec<u32>,
    map: Vec<u32>,
    map_b: Vec<u32>,
    link_of: Vec<u32>,
    fenwick: Fenwick,
    /// Open links of [`Self::fenwick`] or the sampling queue: (gene, link, depth).
    owners: Vec<(u32, u32, u32)>,
}

impl<G: Grammar> Operators<G> {
    /// Operators keeping genomes within `limits`; fails if the limits cannot be met
    /// together (see [`Limits::check`]).
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
                });
            }
        }
        Ok(Operators {
            limits,
            kinds,
            links,
            s: Scratch::default(),
            _g: PhantomData,
        })
    }

    /// The limits the operators keep genomes within.
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
    fn kind_at(&self, words: &[u32], pos: u32) -> KindInfo {
        self.kinds[words[pos as usize] as usize]
    }

    /// The link facts of link `link` of a gene of kind `k`.
    #[inline]
    fn link(&self, k: &KindInfo, link: u32) -> LinkInfo {
        self.links[(k.first_link + link) as usize]
    }
}

/// Fills `starts` with the word position of every gene of `words`, in order.
fn gene_starts(kinds: &[KindInfo], words: &[u32], starts: &mut Vec<u32>) {
    starts.clear();
    let mut pos = 0u32;
    while (pos as usize) < words.len() {
        starts.push(pos);
        pos += kinds[words[pos as usize] as usize].gene_words;
    }
}
