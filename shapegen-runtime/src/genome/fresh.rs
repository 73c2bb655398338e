//! New genes written from a plan made once per grammar.
//!
//! [`Genome::push_gene`] reads a node's parameter list and draws each parameter through
//! [`param::sample`], which is right for any gene but pays, for every gene, for walking
//! the graph's descriptions, matching each distribution and zeroing the gene word by
//! word. The operators add genes by the hundred per genome, so they keep a [`FreshGenes`]
//! instead: per node kind, the gene's words as they are before any draw (kind, links,
//! parameters whose range is a single value), and the list of its draws, each a uniform
//! `f32` component with its bounds ready, or any other distribution left to
//! [`param::sample`]. [`FreshGenes::push`] copies the first and makes the second,
//! drawing exactly what `push_gene` draws, in the same order, to the same bits: a test
//! holds the two equal for every kind of distribution.

use std::marker::PhantomData;

use rand::Rng;

use super::packed::Genome;
use crate::derive::Grammar;
use crate::graph::{Distribution, HEADER_WORDS};
use crate::param;

/// One draw of a new gene, at word `word` of the gene.
#[derive(Clone, Copy, Debug)]
enum Draw {
    /// One uniform `f32` in `[lo, lo + scale]`, exactly as [`param::sample`] draws it.
    Uniform { word: u32, lo: f32, scale: f32 },
    /// A whole parameter drawn by [`param::sample`].
    Param {
        word: u32,
        dist: &'static Distribution,
    },
}

/// Where a node kind's template gene and draws lie in [`FreshGenes`]' buffers.
#[derive(Clone, Copy, Debug)]
struct FreshKind {
    first_word: u32,
    words: u32,
    first_draw: u32,
    draws: u32,
}

/// The plan for writing new genes of grammar `G`: see the [module](self).
#[derive(Debug)]
pub(crate) struct FreshGenes<G> {
    kinds: Vec<FreshKind>,
    words: Vec<u32>,
    draws: Vec<Draw>,
    _g: PhantomData<fn() -> G>,
}

impl<G> Clone for FreshGenes<G> {
    fn clone(&self) -> Self {
        FreshGenes {
            kinds: self.kinds.clone(),
            words: self.words.clone(),
            draws: self.draws.clone(),
            _g: PhantomData,
        }
    }
}

/// The bounds of the uniform `f32` components of a parameter drawn from `dist`, lower
/// and upper, one of each per word; `None` for any other distribution.
fn uniform_bounds(dist: &Distribution) -> Option<(&[f32], &[f32])> {
    match dist {
        Distribution::Uniform { lo, hi } | Distribution::Angle { lo, hi, .. } => {
            Some((std::slice::from_ref(lo), std::slice::from_ref(hi)))
        }
        Distribution::UniformVec2 { lo, hi } => Some((&lo[..], &hi[..])),
        Distribution::UniformVec3 { lo, hi } => Some((&lo[..], &hi[..])),
        _ => None,
    }
}

impl<G: Grammar> FreshGenes<G> {
    /// The plan for every node kind of `G`.
    pub(crate) fn new() -> Self {
        let mut plan = FreshGenes {
            kinds: Vec::with_capacity(G::GRAPH.nodes.len()),
            words: Vec::new(),
            draws: Vec::new(),
            _g: PhantomData,
        };
        for (kind, node) in G::GRAPH.nodes.iter().enumerate() {
            let first_word = plan.words.len();
            let first_draw = plan.draws.len() as u32;
            plan.words.push(kind as u32);
            plan.words
                .resize(first_word + node.gene_words() as usize, 0);
            let params_at = HEADER_WORDS + node.links;
            for p in node.params {
                let word = params_at + p.offset;
                plan.add_param(first_word, word, &p.dist);
            }
            plan.kinds.push(FreshKind {
                first_word: first_word as u32,
                words: node.gene_words(),
                first_draw,
                draws: plan.draws.len() as u32 - first_draw,
            });
        }
        plan
    }

    /// Plans parameter `dist` at word `word` of the template gene at `first_word`.
    fn add_param(&mut self, first_word: usize, word: u32, dist: &'static Distribution) {
        let planned = uniform_bounds(dist)
            .filter(|(lo, hi)| lo.iter().zip(*hi).all(|(&lo, &hi)| (hi - lo).is_finite()));
        let Some((lo, hi)) = planned else {
            self.draws.push(Draw::Param { word, dist });
            return;
        };
        for (i, (&lo, &hi)) in lo.iter().zip(hi).enumerate() {
            let word = word + i as u32;
            if lo < hi {
                self.draws.push(Draw::Uniform {
                    word,
                    lo,
                    scale: hi - lo,
                });
            } else {
                // A single value: drawn without using the stream.
                self.words[first_word + word as usize] = lo.to_bits();
            }
        }
    }

    /// Appends a gene of kind `kind` to `genome`, linked from `parent` on link `link`
    /// when given, with parameters drawn from `rng`: exactly what
    /// [`Genome::push_gene`] does. Returns its word position. O(gene words).
    #[inline]
    pub(crate) fn push(
        &self,
        genome: &mut Genome<G>,
        kind: u32,
        parent: Option<(u32, u32)>,
        rng: &mut impl Rng,
    ) -> u32 {
        let k = self.kinds[kind as usize];
        let pos = genome.words.len() as u32;
        let template = &self.words[k.first_word as usize..][..k.words as usize];
        genome.words.extend_from_slice(template);
        if let Some((parent, link)) = parent {
            genome.words[pos as usize + 1] = (parent as i32 - pos as i32) as u32;
            genome.words[(parent + HEADER_WORDS + link) as usize] = pos - parent;
        }
        let gene = &mut genome.words[pos as usize..];
        for d in &self.draws[k.first_draw as usize..][..k.draws as usize] {
            match *d {
                Draw::Uniform { word, lo, scale } => {
                    gene[word as usize] = param::uniform_in(rng, lo, scale).to_bits();
                }
                Draw::Param { word, dist } => param::sample(dist, rng, &mut gene[word as usize..]),
            }
        }
        genome.len += 1;
        pos
    }
}

#[cfg(test)]
mod tests {
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    use super::*;
    use crate::derive::{GeneView, Shape};
    use crate::graph::{AngleUnit, GeneratorGraph, NodeDesc, ParamDesc, SlotDesc};

    /// Every kind of distribution, and bounds of a single value, on a chain of nodes.
    struct AllDists;

    const fn param(name: &'static str, offset: u32, dist: Distribution) -> ParamDesc {
        ParamDesc { name, offset, dist }
    }

    static PARAMS: &[ParamDesc] = &[
        param("f", 0, Distribution::Uniform { lo: -0.5, hi: 0.5 }),
        param(
            "v",
            1,
            Distribution::UniformVec3 {
                lo: [0.6, 2.0, 0.3],
                hi: [1.5, 2.0, 0.8],
            },
        ),
        param("i", 4, Distribution::Int { lo: -3, hi: 7 }),
        param(
            "w",
            5,
            Distribution::Weighted {
                weights: &[1.0, 0.0, 2.5],
            },
        ),
        param("b", 6, Distribution::Bernoulli { p: 0.3 }),
        param(
            "a",
            7,
            Distribution::Angle {
                lo: 0.1,
                hi: 2.0,
                unit: AngleUnit::Degrees,
            },
        ),
        param("u", 8, Distribution::Index { lo: 2, hi: 9 }),
        param(
            "p",
            9,
            Distribution::UniformVec2 {
                lo: [-1.0, 4.0],
                hi: [1.0, 4.5],
            },
        ),
        param("c", 11, Distribution::Uniform { lo: 3.0, hi: 3.0 }),
    ];

    static GRAPH: GeneratorGraph = GeneratorGraph {
        name: "AllDists",
        key: "all_dists",
        axiom: 0,
        nodes: &[
            NodeDesc {
                name: "Start",
                params: &[],
                slots: &[SlotDesc {
                    name: "first",
                    child: 1,
                    probability: 1.0,
                    count: 2,
                    first_link: 0,
                }],
                links: 2,
                param_words: 0,
            },
            NodeDesc {
                name: "Node",
                params: PARAMS,
                slots: &[SlotDesc {
                    name: "next",
                    child: 1,
                    probability: 0.5,
                    count: 1,
                    first_link: 0,
                }],
                links: 1,
                param_words: 12,
            },
        ],
        meshes: &["cube"],
    };

    impl Grammar for AllDists {
        const GRAPH: &'static GeneratorGraph = &GRAPH;

        fn derive_gene<'a>(_: Shape<'a, Self>, _: GeneView<'a>) {}
    }

    #[test]
    fn planned_genes_are_push_genes_word_for_word_and_draw_for_draw() {
        let plan = FreshGenes::<AllDists>::new();
        for seed in 0..200 {
            let (mut r1, mut r2) = (
                ChaCha8Rng::seed_from_u64(seed),
                ChaCha8Rng::seed_from_u64(seed),
            );
            let mut by_graph = Genome::<AllDists>::from_parts(Vec::new(), 0);
            let mut planned = Genome::<AllDists>::from_parts(Vec::new(), 0);
            by_graph.push_gene(0, None, &mut r1);
            plan.push(&mut planned, 0, None, &mut r2);
            let mut parent = (0, 1);
            for _ in 0..5 {
                let a = by_graph.push_gene(1, Some(parent), &mut r1);
                let b = plan.push(&mut planned, 1, Some(parent), &mut r2);
                assert_eq!(a, b);
                parent = (a, 0);
            }
            assert_eq!(by_graph.words, planned.words, "seed {seed}");
            assert_eq!(by_graph.len, planned.len);
            assert_eq!(r1.next_u64(), r2.next_u64(), "the same draws, seed {seed}");
            by_graph.validate().unwrap();
        }
    }
}
