//! The static generator graph: node types, their parameters and their child slots.
//!
//! The `generator!` macro writes one [`GeneratorGraph`] per grammar as a `static`; the
//! genome, the genetic operators and the serializer read it to know how large each gene
//! is, which children a node may have and how its parameters are distributed.

/// Number of header words at the start of every gene: the node kind and the relative
/// offset to the parent gene.
pub const HEADER_WORDS: u32 = 2;

/// A procedural generator's graph: its node types and the edges between them.
#[derive(Debug)]
pub struct GeneratorGraph {
    /// Name of the grammar as written in `generator!` (`ThreeBranchTree`).
    pub name: &'static str,
    /// The name in snake case (`three_branch_tree`): what genome files write as their
    /// `"generator"` and the name the command-line tool knows a published generator by.
    /// A file naming the generator either way reads ([`answers_to`](Self::answers_to)).
    pub key: &'static str,
    /// Index of the axiom in [`nodes`](Self::nodes).
    pub axiom: u32,
    /// Every node type, indexed by node kind.
    pub nodes: &'static [NodeDesc],
    /// Names of the meshes the grammar emits, indexed by [`MeshId`](crate::MeshId);
    /// index 0 is always the built-in unit cube, `"cube"`.
    pub meshes: &'static [&'static str],
}

impl GeneratorGraph {
    /// Whether `name` names this generator in a file: its [`key`](Self::key)
    /// (`spaceship`, what files are written with) or its [`name`](Self::name)
    /// (`Spaceship`), exactly.
    pub fn answers_to(&self, name: &str) -> bool {
        name == self.key || name == self.name
    }

    /// The node type of kind `kind`, if there is one.
    #[inline]
    pub fn node(&self, kind: u32) -> Option<&'static NodeDesc> {
        self.nodes.get(kind as usize)
    }

    /// The node type of kind `kind`, whose validity the caller already knows.
    #[inline]
    pub(crate) fn node_unchecked(&self, kind: u32) -> &'static NodeDesc {
        &self.nodes[kind as usize]
    }

    /// The node kind named `name`, if the grammar has one.
    pub fn kind_of(&self, name: &str) -> Option<u32> {
        self.nodes
            .iter()
            .position(|n| n.name == name)
            .map(|i| i as u32)
    }

    /// Whether the graph's layout numbers agree with each other and with this runtime:
    /// the axiom and every slot's child are node kinds; parameter offsets follow each
    /// other by [`Distribution::words`] and add up to `param_words`; slots' first links
    /// follow each other by their counts (at least 1) and add up to `links`;
    /// probabilities lie in `[0, 1]`; mesh 0 exists. The `generator!` macro asserts this
    /// at compile time.
    pub const fn layout_is_consistent(&self) -> bool {
        let kinds = self.nodes.len();
        if self.axiom as usize >= kinds || self.meshes.is_empty() {
            return false;
        }
        let mut k = 0;
        while k < kinds {
            let node = &self.nodes[k];
            let mut words = 0u32;
            let mut i = 0;
            while i < node.params.len() {
                let p = &node.params[i];
                if p.offset != words {
                    return false;
                }
                words += p.dist.words();
                i += 1;
            }
            let mut links = 0u32;
            i = 0;
            while i < node.slots.len() {
                let s = &node.slots[i];
                if s.first_link != links
                    || s.count == 0
                    || s.child as usize >= kinds
                    || !(s.probability >= 0.0 && s.probability <= 1.0)
                {
                    return false;
                }
                links += s.count;
                i += 1;
            }
            if words != node.param_words || links != node.links {
                return false;
            }
            k += 1;
        }
        true
    }
}

/// One node type of a generator graph.
#[derive(Debug)]
pub struct NodeDesc {
    /// Name of the node as written in `generator!`.
    pub name: &'static str,
    /// Parameters in gene order.
    pub params: &'static [ParamDesc],
    /// Child slots in gene order. An array slot `[Lot; 100]` is one entry with count 100.
    pub slots: &'static [SlotDesc],
    /// Number of child links in a gene of this type: the sum of the slots' counts.
    pub links: u32,
    /// Number of 32-bit words the parameters take.
    pub param_words: u32,
}

impl NodeDesc {
    /// Size of one gene of this type in 32-bit words: header, links, parameters.
    #[inline]
    pub const fn gene_words(&self) -> u32 {
        HEADER_WORDS + self.links + self.param_words
    }

    /// The slot that child link `link` belongs to.
    pub fn slot_of_link(&self, link: u32) -> Option<&'static SlotDesc> {
        self.slots
            .iter()
            .find(|s| link >= s.first_link && link < s.first_link + s.count)
    }
}

/// A child slot of a node type: an edge of the generator graph.
#[derive(Debug)]
pub struct SlotDesc {
    /// Name of the slot as written in `generator!`.
    pub name: &'static str,
    /// Node kind of the child.
    pub child: u32,
    /// Probability that the child appears in an uncontrolled derivation.
    pub probability: f32,
    /// Number of links: 1 for a single slot, N for an array slot `[Node; N]`.
    pub count: u32,
    /// Index of this slot's first link among the node's links.
    pub first_link: u32,
}

/// A parameter of a node type.
#[derive(Debug)]
pub struct ParamDesc {
    /// Name of the parameter as written in `generator!`.
    pub name: &'static str,
    /// Offset of its first word among the node's parameter words.
    pub offset: u32,
    /// How the parameter is sampled; this also fixes its Rust type.
    pub dist: Distribution,
}

/// The unit an angle parameter was written in. Angles are always stored and handed to
/// derivation bodies in radians; the unit only tells how to show them to people.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AngleUnit {
    /// Written in degrees.
    Degrees,
    /// Written in radians.
    Radians,
}

/// The distribution of a parameter, which also fixes its Rust type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Distribution {
    /// `f32`, uniform over `[lo, hi]`.
    Uniform {
        /// Lower bound, included.
        lo: f32,
        /// Upper bound, included.
        hi: f32,
    },
    /// `f32` angle in radians, uniform over `[lo, hi]` (both in radians).
    Angle {
        /// Lower bound in radians, included.
        lo: f32,
        /// Upper bound in radians, included.
        hi: f32,
        /// The unit the bounds were written in.
        unit: AngleUnit,
    },
    /// `Vec2`, each component uniform over its own `[lo, hi]`.
    UniformVec2 {
        /// Lower bounds, included.
        lo: [f32; 2],
        /// Upper bounds, included.
        hi: [f32; 2],
    },
    /// `Vec3`, each component uniform over its own `[lo, hi]`.
    UniformVec3 {
        /// Lower bounds, included.
        lo: [f32; 3],
        /// Upper bounds, included.
        hi: [f32; 3],
    },
    /// `i32`, uniform over the integers of `[lo, hi]`.
    Int {
        /// Lower bound, included.
        lo: i32,
        /// Upper bound, included.
        hi: i32,
    },
    /// `u32`, uniform over the integers of `[lo, hi]`.
    Index {
        /// Lower bound, included.
        lo: u32,
        /// Upper bound, included.
        hi: u32,
    },
    /// `u32` index `i` drawn with probability `weights[i] / sum(weights)`.
    Weighted {
        /// Non-negative weights, at least one positive.
        weights: &'static [f32],
    },
    /// `bool`, `true` with probability `p`.
    Bernoulli {
        /// Probability of `true`.
        p: f32,
    },
}

impl Distribution {
    /// Number of 32-bit words a value of this distribution takes in a gene.
    pub const fn words(&self) -> u32 {
        match self {
            Distribution::UniformVec2 { .. } => 2,
            Distribution::UniformVec3 { .. } => 3,
            _ => 1,
        }
    }

    /// Name of the Rust type of values of this distribution.
    pub const fn type_name(&self) -> &'static str {
        match self {
            Distribution::Uniform { .. } | Distribution::Angle { .. } => "f32",
            Distribution::UniformVec2 { .. } => "Vec2",
            Distribution::UniformVec3 { .. } => "Vec3",
            Distribution::Int { .. } => "i32",
            Distribution::Index { .. } | Distribution::Weighted { .. } => "u32",
            Distribution::Bernoulli { .. } => "bool",
        }
    }
}
