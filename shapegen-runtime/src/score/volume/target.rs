//! The targets a volume scorer is made from, how their inside is found, and why one
//! cannot be made.

use crate::geometry::{Mesh, MeshError};

/// The most distinct voxel weights (classes) a scene may have.
pub const MAX_CLASSES: usize = 16;

/// A volume to fill (or avoid): a mesh in world space, voxelized by its [`Fill`] rule,
/// and the weights a model's voxel scores inside and outside it.
#[derive(Clone, Debug, PartialEq)]
pub struct VolumeTarget {
    /// Names the target in errors.
    pub name: String,
    /// The target's surface, in world space.
    pub mesh: Mesh,
    /// Weight of a voxel inside the mesh.
    pub inside: f64,
    /// Weight of a voxel outside the mesh (also of each out-of-grid hit).
    pub outside: f64,
    /// How the mesh's inside is found.
    pub fill: Fill,
}

/// How a [`VolumeTarget`]'s inside is found on the grid's lattice points; scene files
/// name it in lower case (`fill = "winding"`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Fill {
    /// A point is inside when the ray from it along +x crosses the mesh an odd number of
    /// times: exact for closed meshes, and the original implementation's rule.
    #[default]
    Parity,
    /// A point is inside when the mesh's generalized winding number about it has a
    /// magnitude of at least 1/2: for open or messy meshes (holes, cracks, overlapping
    /// or inverted parts), where parity streaks. Slower: every triangle is measured from
    /// every lattice point within the mesh's bounding box, once per target.
    Winding,
}

/// Why a [`VolumeScorer`](super::VolumeScorer) cannot be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum VolumeError {
    /// A weight is infinite or NaN.
    #[error("volume target `{target}`: {which} weight {value} is not finite (finite numbers only)")]
    Weight {
        /// The target's name.
        target: String,
        /// `inside` or `outside`.
        which: &'static str,
        /// The weight given.
        value: f64,
    },
    /// A target's mesh is malformed.
    #[error("volume target `{target}`")]
    Mesh {
        /// The target's name.
        target: String,
        /// What is wrong with it.
        #[source]
        source: MeshError,
    },
    /// The targets' weights combine into too many distinct voxel weights.
    #[error(
        "volume targets {targets} combine into {classes} distinct voxel weights; at most {} \
         are supported (give targets fewer distinct inside/outside weights, or fewer targets)",
        MAX_CLASSES
    )]
    TooManyClasses {
        /// The targets, named and quoted.
        targets: String,
        /// How many distinct weights there are.
        classes: usize,
    },
    /// The F-score form's threshold cannot be used.
    #[error("volume F-score: {reason}")]
    Threshold {
        /// What is wrong, and what would be valid.
        reason: String,
    },
    /// [Distance shaping](super::VoxelClasses::shaped) cannot be done.
    #[error("volume distance shaping: {reason}")]
    Shaping {
        /// What is wrong, and what would be valid.
        reason: String,
    },
}
