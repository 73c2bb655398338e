//! The runtime of shapegen: packed derivation-tree genomes of procedural generators,
//! derivation of genomes into mesh instances, and the building blocks the `generator!`
//! macro expands to.
//!
//! Most users depend on the `shapegen` crate, which re-exports this one.
//!
//! # Errors
//!
//! An error's message never repeats its cause when the cause is exposed as its
//! [`source()`](std::error::Error::source): the message says what failed, and the cause
//! is reached through the chain — `{:#}` of an `anyhow::Error`, or walking `source()`
//! as [`error_chain`] does. Errors that only wrap another are `#[error(transparent)]`.

pub mod derive;
mod error;
pub mod evaluate;
pub mod export;
pub mod genome;
pub mod geometry;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod graph;
pub mod ops;
pub mod optimize;
pub mod param;
pub mod score;
#[cfg(test)]
mod testing;

pub use derive::{Child, GeneView, Grammar, NodeParams, NodeRule, Shape, Site, Slots};
pub use error::error_chain;
pub use genome::{Genome, GenomeError, Limits};
pub use geometry::{Axis, CUBE, Face, Instance, MeshId, Part, Scope};
pub use geometry::{BoundMeshes, Mesh, MeshError, MeshLibrary};
pub use graph::GeneratorGraph;
pub use ops::Operators;

/// The names most generator code needs: `use shapegen_runtime::prelude::*;`.
pub mod prelude {
    pub use crate::derive::{Child, Grammar, Shape, Slots};
    pub use crate::generator;
    pub use crate::genome::{Genome, Limits};
    pub use crate::geometry::{Axis, CUBE, Face, Instance, MeshId, Part, Scope};
    pub use crate::ops::Operators;
    pub use glam::{Affine3A, Quat, Vec2, Vec3, vec2, vec3};
}

/// Declares a procedural generator: its node types, their parameters and distributions,
/// their child slots with probabilities, and the rules that derive them into geometry.
///
/// ```
/// use shapegen_runtime::prelude::*;
///
/// generator! {
///     /// A tower of boxes with optional balconies.
///     pub Tower {
///         axiom Ground;
///         meshes { BALCONY = "balcony" }
///
///         node Ground {
///             children { floor: Floor = 1.0 }
///             derive(s) {
///                 if let Some(floor) = floor {
///                     s.resize(floor.size).derive(floor);
///                 }
///             }
///         }
///         /// One storey.
///         node Floor {
///             params {
///                 /// Size of the storey relative to the one below.
///                 size: Vec3 ~ uniform([0.8, 0.5, 0.8], [1.0, 1.0, 1.0]),
///                 twist: f32 ~ degrees(-10, 10),
///             }
///             children { up: Floor = 0.8, balconies: [Balcony; 4] = 0.25 }
///             derive(s) {
///                 let s = s.translate(vec3(0.0, s.size().y / 2.0, 0.0));
///                 s.emit(CUBE);
///                 for (side, balcony) in balconies.iter() {
///                     let angle = side as f32 * std::f32::consts::FRAC_PI_2;
///                     s.rotate_y(angle).translate(vec3(s.size().x / 2.0, 0.0, 0.0)).derive(balcony);
///                 }
///                 if let Some(up) = up {
///                     s.translate(vec3(0.0, s.size().y / 2.0, 0.0))
///                         .rotate_y(twist)
///                         .resize(up.size)
///                         .derive(up);
///                 }
///             }
///         }
///         node Balcony {
///             params { depth: f32 ~ uniform(0.1, 0.3), railing: bool ~ bernoulli(0.5) }
///             derive(s) {
///                 s.with_size(vec3(depth, 0.1, 0.5)).emit(BALCONY);
///                 if railing {
///                     s.translate(vec3(0.0, 0.1, 0.0)).with_size(vec3(depth, 0.1, 0.02)).emit(CUBE);
///                 }
///             }
///         }
///     }
/// }
///
/// let graph = Tower::GRAPH;
/// assert_eq!(graph.nodes[graph.axiom as usize].name, "Ground");
/// assert_eq!(graph.meshes, ["cube", "balcony"]);
/// assert_eq!(graph.nodes[1].links, 1 + 4);
/// let floor = Floor { size: Vec3::ONE, twist: 0.0 };
/// assert_eq!(floor.size, Vec3::ONE);
///
/// let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(7);
/// let genome = Genome::<Tower>::axiom(&mut rng);
/// let mut instances = Vec::new();
/// genome.derive_into(&mut instances);
/// assert!(instances.is_empty()); // the axiom alone has no floor yet
/// ```
///
/// # Syntax
///
/// ```text
/// generator! {
///     #[attributes] /// docs        // on the grammar struct
///     Visibility Name {
///         axiom NodeName;                                   // exactly once
///         meshes { CONST = "mesh name", .. }                // optional, at most once
///         #[attributes] /// docs    // on the node's parameter struct
///         node NodeName {
///             params { #[attrs] /// docs
///                      name: Type ~ distribution(..), .. }  // optional
///             children { /// docs
///                        name: Node = p, name: [Node; N] = p, .. }  // optional
///             derive(scope) { Rust statements }             // optional
///         }
///         ..
///     }
/// }
/// ```
///
/// Items of the body come in any order; so do the three sections of a node, each at most
/// once. Lists take commas between entries and allow a trailing one.
///
/// ## What it declares
///
/// In the scope of the invocation, with the grammar's visibility:
/// - `struct Name;`, the grammar, implementing [`Grammar`]: use it as `Genome<Name>`.
///   Its `GRAPH` is a [`GeneratorGraph`] whose node kinds are the nodes in declaration
///   order.
/// - For each node, a `#[repr(C)]` struct named after it whose public fields are its
///   parameters, in order, implementing [`NodeParams`], `Clone`, `Copy`, `Debug` and
///   `PartialEq`. Rules see a present child as a [`Child`] of this struct, so
///   `child.size` reads the child's parameter `size`.
/// - For each mesh `CONST = "name"`, `const CONST: MeshId`. [`CUBE`] is always mesh 0
///   (named `"cube"`, not declared); declared meshes follow in order, so
///   `GRAPH.meshes` is `["cube", ..]`.
///
/// Doc comments and attributes on the grammar, nodes, parameters and meshes go on the
/// generated items, followed by a generated paragraph describing the item (its slots and
/// probabilities, a parameter's distribution); `#[derive(..)]` on a node adds to its
/// parameter struct. Child slots take doc comments only. `cfg` attributes are refused:
/// the graph always lists every part.
///
/// ## Parameters
///
/// A parameter's value is drawn from its distribution when a gene is created and stored
/// in the gene; rules read it under the parameter's name.
///
/// | type | distributions |
/// |---|---|
/// | `f32` | `uniform(lo, hi)`; `degrees(lo, hi)` and `radians(lo, hi)`: an angle, uniform over the bounds written in that unit, always stored and handed to rules in radians |
/// | `Vec2`, `Vec3` | `uniform(lo, hi)`, each bound `[x, y]` / `[x, y, z]` or `[v; 2]` / `[v; 3]`, each component uniform over its own range |
/// | `i32` | `uniform(lo..=hi)` or `uniform(lo..hi)`: uniform over the integers in the range |
/// | `u32` | as `i32`, or `weighted([w0, w1, ..])`: index `i` with probability `w_i / sum(w)` |
/// | `bool` | `bernoulli(p)`: `true` with probability `p` |
///
/// Ranges are closed: `uniform(lo, hi)` may draw `hi`; `lo == hi` makes a constant.
///
/// ## Constants
///
/// Bounds, probabilities, weights and array lengths are evaluated when the macro expands,
/// so that they can be checked and stored as plain numbers. They are written with number
/// literals (any numeric suffix), unary `-`, `+ - * /`, parentheses and the `f32`
/// constants (`PI`, `TAU`, `E`, `FRAC_PI_2`, `SQRT_2`, ...), bare or as
/// `std::f32::consts::PI` / `core::f32::consts::PI`. Float values are computed in `f64`
/// and rounded once to the nearest `f32` (so `1.0 / 3.0` is the `f32` nearest a third);
/// integer literals count as floats where a float is expected. Integer positions (ranges,
/// array lengths) take integers only, with truncating division. Other names, such as
/// your own `const`s, cannot be evaluated: write the value.
///
/// ## Children
///
/// `name: Node = p` is a slot for one optional child of type `Node`, present with
/// probability `p` (in `[0, 1]`) when a derivation grows uncontrolled; children with
/// `p = 1.0` are never cut. `name: [Node; N] = p` is `N` such slots, `N >= 1` (the
/// city's `lots: [Lot; 100] = 0.33`). A node may be its own child.
///
/// ## Rules
///
/// `derive(s) { .. }` is ordinary Rust run when a gene of this node is derived. In it:
/// - `s` (any name; `derive(mut s)` to reassign it) is the node's scope, a [`Shape`]:
///   `s.translate(v)`, `s.resize(v)`, `s.rotate_y(a)`, `s.emit(mesh)`, `s.derive(child)`;
/// - each parameter is a local of its declared type;
/// - each single slot is an `Option<Child<'_, Node>>`, each array slot a
///   [`Slots<'_, Node, N>`](Slots) (`get(i)`, `iter()` over the present children with
///   their indices);
/// - `Self` is the grammar.
///
/// The body sees the names in scope where `generator!` is invoked (your imports), the
/// parameter structs and mesh constants included; unused parameters are fine. A node
/// without `derive` derives each present child, in slot order, in its own scope.
///
/// ## Checks
///
/// Every mistake is reported at once, each pointing at the tokens at fault: unknown node
/// names (with the declared ones listed), a missing, unknown or repeated `axiom`,
/// duplicate node, parameter, slot or mesh names, a parameter and a slot (or either and
/// the scope) sharing a name, unknown or repeated sections, unsupported types,
/// distributions that do not fit the type, vector bounds of the wrong length, empty
/// ranges (per component for vectors), probabilities outside `[0, 1]`, weights that are
/// negative or all zero, array slots of length 0, and anything that is not a constant.
///
/// A node that cannot be reached from the axiom through child slots is an error too:
/// genomes grow from the axiom along slots only, so such a node could never appear in a
/// genome, and declaring it is almost always a forgotten child slot.
///
/// After a mistake the macro still declares the grammar (with an empty graph), the
/// parameter structs and the mesh constants, so the rest of your crate reports nothing
/// but the mistake.
#[macro_export]
macro_rules! generator {
    ($($grammar:tt)*) => {
        $crate::__private::generator_impl! { $crate; $($grammar)* }
    };
}

/// What the expansions of the `generator!` and `checkpoint!` macros refer to. Not a
/// public API: it may change in any release.
#[doc(hidden)]
pub mod __private {
    pub use crate::derive::Child;
    pub use crate::derive::{
        GeneView, Grammar, NodeParams, NodeRule, Shape, Slots, read_param, write_param,
    };
    pub use crate::geometry::MeshId;
    pub use crate::graph::{
        AngleUnit, Distribution, GeneratorGraph, NodeDesc, ParamDesc, SlotDesc,
    };
    pub use crate::optimize::Progress;
    pub use glam::{Vec2, Vec3};
    pub use shapegen_macros::generator_impl;
}
