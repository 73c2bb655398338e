//! The checked model of a generator: nodes, parameters, child slots and meshes, borrowing
//! names, attributes and rule bodies from the syntax tree.
//!
//! [`check`](crate::check) builds it and reports every mistake it meets. Where a part is
//! wrong it is left out or marked unknown (`None`), so that the fallback expansion can
//! still emit everything that is right; when no error was reported every part is known.

use proc_macro2::{Group, Ident};
use syn::{Attribute, Token, Visibility};

/// Header words at the start of every gene: node kind and parent offset. The runtime's
/// `graph::HEADER_WORDS`.
pub const HEADER_WORDS: u32 = 2;

/// A generator.
pub struct Generator<'a> {
    pub attrs: &'a [Attribute],
    pub vis: &'a Visibility,
    pub name: &'a Ident,
    /// Kind of the axiom node, when it names a declared node.
    pub axiom: Option<u32>,
    /// The declared meshes; mesh 0, the built-in cube, is not among them.
    pub meshes: Vec<Mesh<'a>>,
    /// The nodes, indexed by kind.
    pub nodes: Vec<Node<'a>>,
}

/// A mesh of a `meshes` block.
pub struct Mesh<'a> {
    pub attrs: &'a [Attribute],
    /// The constant's name.
    pub name: &'a Ident,
    /// The mesh's name, as stored in the generator graph.
    pub file: String,
    /// The mesh's id: its index in the graph's meshes, counting the cube as 0.
    pub id: u32,
}

/// A node type.
pub struct Node<'a> {
    pub attrs: &'a [Attribute],
    pub name: &'a Ident,
    /// Index of the node among the generator's nodes.
    pub kind: u32,
    /// Name of the rule function, unique within the generator.
    pub rule_fn: Ident,
    pub params: Vec<Param<'a>>,
    pub slots: Vec<Slot<'a>>,
    pub rule: Rule<'a>,
    /// Whether the parameter struct is whole: the node's body parsed and every
    /// parameter's type is known. Only whole structs get their rule body emitted by the
    /// fallback, and only rules whose children are whole, so that no body reads a field
    /// that is missing.
    pub whole: bool,
    /// Whether the node's bindings are sound: every slot's node and length is known and
    /// no two bindings share a name.
    pub bindings_ok: bool,
}

/// A parameter.
pub struct Param<'a> {
    pub attrs: &'a [Attribute],
    pub name: &'a Ident,
    /// Its type; `None` when unsupported.
    pub ty: Option<ParamType>,
    /// Its distribution; `None` when wrong.
    pub dist: Option<Dist>,
}

/// The supported parameter types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamType {
    F32,
    Vec2,
    Vec3,
    I32,
    U32,
    Bool,
}

impl ParamType {
    /// The type's name as the user writes it.
    pub fn name(self) -> &'static str {
        match self {
            ParamType::F32 => "f32",
            ParamType::Vec2 => "Vec2",
            ParamType::Vec3 => "Vec3",
            ParamType::I32 => "i32",
            ParamType::U32 => "u32",
            ParamType::Bool => "bool",
        }
    }

    /// The type named `name`, if supported.
    pub fn from_name(name: &str) -> Option<Self> {
        Some(match name {
            "f32" => ParamType::F32,
            "Vec2" => ParamType::Vec2,
            "Vec3" => ParamType::Vec3,
            "i32" => ParamType::I32,
            "u32" => ParamType::U32,
            "bool" => ParamType::Bool,
            _ => return None,
        })
    }

    /// Number of 32-bit gene words a value takes.
    pub fn words(self) -> u32 {
        match self {
            ParamType::Vec2 => 2,
            ParamType::Vec3 => 3,
            _ => 1,
        }
    }
}

/// Unit an angle's bounds were written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AngleUnit {
    Degrees,
    Radians,
}

/// A parameter's distribution, its bounds already evaluated and rounded to `f32`.
#[derive(Clone, Debug, PartialEq)]
pub enum Dist {
    Uniform {
        lo: f32,
        hi: f32,
    },
    /// Bounds in radians; `written` holds them as written, for documentation.
    Angle {
        lo: f32,
        hi: f32,
        unit: AngleUnit,
        written: (f64, f64),
    },
    UniformVec2 {
        lo: [f32; 2],
        hi: [f32; 2],
    },
    UniformVec3 {
        lo: [f32; 3],
        hi: [f32; 3],
    },
    Int {
        lo: i32,
        hi: i32,
    },
    Index {
        lo: u32,
        hi: u32,
    },
    Weighted {
        weights: Vec<f32>,
    },
    Bernoulli {
        p: f32,
    },
}

/// A child slot.
pub struct Slot<'a> {
    pub name: &'a Ident,
    /// Name of the child's node as written.
    pub node: &'a Ident,
    /// Kind of the child's node; `None` when no node has that name.
    pub child: Option<u32>,
    /// `Some(n)` for an array slot `[Node; n]`, with `n` as evaluated (`None` inside when
    /// wrong); `None` for a single slot.
    pub array: Option<Option<u32>>,
    /// Probability that the child appears; `None` when wrong.
    pub probability: Option<f32>,
}

impl Slot<'_> {
    /// Number of links the slot takes, when known.
    pub fn count(&self) -> Option<u32> {
        match self.array {
            None => Some(1),
            Some(n) => n,
        }
    }
}

/// How a node derives.
pub enum Rule<'a> {
    /// No `derive` section: every present child is derived in the node's scope.
    Default,
    /// `derive(scope) { body }`.
    Body {
        mutability: Option<&'a Token![mut]>,
        scope: &'a Ident,
        body: &'a Group,
    },
}
