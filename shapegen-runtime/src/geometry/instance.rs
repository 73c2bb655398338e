//! Mesh instances: the output of a derivation.

use glam::Affine3A;

/// Identifies a mesh within a grammar: an index into
/// [`GeneratorGraph::meshes`](crate::graph::GeneratorGraph::meshes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct MeshId(pub u32);

/// The built-in unit cube, centred at the origin and spanning `[-0.5, 0.5]` on each axis.
/// Every grammar has it as mesh 0.
pub const CUBE: MeshId = MeshId(0);

/// One placed mesh: which mesh, and the affine transform from mesh space to world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instance {
    /// Mesh space to world space.
    pub transform: Affine3A,
    /// The mesh placed.
    pub mesh: MeshId,
}
