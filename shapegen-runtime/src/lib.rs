//! The runtime of shapegen: packed derivation-tree genomes of procedural generators,
//! derivation of genomes into mesh instances, and the building blocks the `generator!`
//! macro expands to.
//!
//! Most users depend on the `shapegen` crate, which re-exports this one.

pub mod derive;
pub mod genome;
pub mod geometry;
pub mod graph;
pub mod ops;
pub mod param;

pub use derive::{Child, GeneView, Grammar, NodeParams, Shape, Slots};
pub use genome::{Genome, GenomeError, Limits};
pub use geometry::{CUBE, Instance, MeshId, Scope};
pub use graph::GeneratorGraph;
pub use ops::Operators;

/// The names most generator code needs: `use shapegen_runtime::prelude::*;`.
pub mod prelude {
    pub use crate::derive::{Child, Grammar, Shape, Slots};
    pub use crate::generator;
    pub use crate::genome::{Genome, Limits};
    pub use crate::geometry::{CUBE, Instance, MeshId, Scope};
    pub use crate::ops::Operators;
    pub use glam::{Affine3A, Quat, Vec2, Vec3, vec2, vec3};
}

/// Declares a procedural generator; see the `shapegen` crate's documentation for the
/// syntax.
#[macro_export]
macro_rules! generator {
    ($($grammar:tt)*) => {
        $crate::__private::generator_impl! { $crate; $($grammar)* }
    };
}

/// What the `generator!` macro's expansion refers to. Not a public API: it may change in
/// any release.
#[doc(hidden)]
pub mod __private {
    pub use crate::derive::Child;
    pub use crate::derive::{GeneView, Grammar, NodeParams, Shape, Slots, read_param, write_param};
    pub use crate::geometry::MeshId;
    pub use crate::graph::{
        AngleUnit, Distribution, GeneratorGraph, NodeDesc, ParamDesc, SlotDesc,
    };
    pub use glam::{Vec2, Vec3};
    pub use shapegen_macros::generator_impl;
}
