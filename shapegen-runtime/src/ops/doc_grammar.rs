//! A two-node grammar for this crate's documentation examples, written out as the
//! `generator!` macro expands it. Not part of the API: it may change in any release.
//!
//! ```text
//! generator! {
//!     pub Chain {
//!         axiom Start;
//!         node Start { children { first: Seg = 0.9 } derive(s) { .. } }
//!         node Seg {
//!             params { len: f32 ~ uniform(0.5, 1.5) }
//!             children { next: Seg = 0.5, side: Seg = 0.25 }
//!             derive(s) { .. }
//!         }
//!     }
//! }
//! ```

use glam::vec3;

use crate::derive::{Child, GeneView, Grammar, NodeParams, Shape, read_param, write_param};
use crate::geometry::CUBE;
use crate::graph::{Distribution, GeneratorGraph, NodeDesc, ParamDesc, SlotDesc};

/// Generator `Chain`.
#[derive(Debug)]
pub struct Chain;

/// Parameters of node `Start` of generator `Chain`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Start {}

/// Parameters of node `Seg` of generator `Chain`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Seg {
    /// Parameter `len`.
    pub len: f32,
}

impl NodeParams for Start {
    const KIND: u32 = 0;
    const LINKS: u32 = 1;
    const WORDS: u32 = 0;
    fn read(_params: &[u32]) -> Self {
        Start {}
    }
    fn write(&self, _params: &mut [u32]) {}
}

impl NodeParams for Seg {
    const KIND: u32 = 1;
    const LINKS: u32 = 2;
    const WORDS: u32 = 1;
    fn read(params: &[u32]) -> Self {
        Seg {
            len: read_param(params, 0),
        }
    }
    fn write(&self, params: &mut [u32]) {
        write_param(params, 0, self.len);
    }
}

static GRAPH: GeneratorGraph = GeneratorGraph {
    name: "Chain",
    axiom: 0,
    meshes: &["cube"],
    nodes: &[
        NodeDesc {
            name: "Start",
            params: &[],
            slots: &[SlotDesc {
                name: "first",
                child: 1,
                probability: 0.9,
                count: 1,
                first_link: 0,
            }],
            links: 1,
            param_words: 0,
        },
        NodeDesc {
            name: "Seg",
            params: &[ParamDesc {
                name: "len",
                offset: 0,
                dist: Distribution::Uniform { lo: 0.5, hi: 1.5 },
            }],
            slots: &[
                SlotDesc {
                    name: "next",
                    child: 1,
                    probability: 0.5,
                    count: 1,
                    first_link: 0,
                },
                SlotDesc {
                    name: "side",
                    child: 1,
                    probability: 0.25,
                    count: 1,
                    first_link: 1,
                },
            ],
            links: 2,
            param_words: 1,
        },
    ],
};

impl Grammar for Chain {
    const GRAPH: &'static GeneratorGraph = &GRAPH;

    fn derive_gene<'a>(s: Shape<'a, Self>, gene: GeneView<'a>) {
        match gene.kind() {
            0 => {
                if let Some(first) = gene.child::<Seg>(0) {
                    s.derive(first);
                }
            }
            1 => {
                let Seg { len } = Seg::read(gene.params(Seg::LINKS));
                let s = s.resize(vec3(1.0, len, 1.0));
                s.emit(CUBE);
                let next: Option<Child<'a, Seg>> = gene.child(0);
                let side: Option<Child<'a, Seg>> = gene.child(1);
                if let Some(next) = next {
                    s.translate(vec3(0.0, s.size().y, 0.0)).derive(next);
                }
                if let Some(side) = side {
                    s.rotate_z(0.5)
                        .translate(vec3(0.0, s.size().y, 0.0))
                        .derive(side);
                }
            }
            _ => {}
        }
    }
}
