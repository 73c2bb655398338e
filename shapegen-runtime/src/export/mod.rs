//! Writing derived models to files: Wavefront OBJ with its MTL materials, binary glTF
//! (`.glb`), and shaded [`Preview`] pictures, alone or side by side ([`ContactSheet`]).
//!
//! Both exporters bake every [`Instance`] into world space: positions through the
//! instance's transform, normals through its inverse transpose (renormalized), and
//! triangle winding reversed for mirroring transforms (negative determinant), so that
//! faces stay counter-clockwise and normals outward. Instances are grouped by mesh, in
//! [`MeshId`] order, each group coloured from a [`Palette`]. The output is a function
//! of the input alone: identical input gives identical bytes. glTF holds finite numbers
//! only, so [`glb_bytes`] leaves out an instance that places a vertex at NaN or
//! infinity.

mod bake;
mod glb;
mod obj;
mod palette;
mod render;
mod sheet;

use std::path::PathBuf;

pub use glb::{glb_bytes, save_glb, write_glb};
pub use obj::{save_obj, write_mtl, write_obj};
pub use palette::Palette;
pub use render::Preview;
pub use sheet::ContactSheet;

#[cfg(doc)]
use crate::geometry::{Instance, MeshId};

/// Why a model could not be exported.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExportError {
    /// Writing failed.
    #[error("cannot write the export")]
    Io(#[from] std::io::Error),
    /// A file could not be created or written.
    #[error("cannot write `{}`", path.display())]
    File {
        /// The file.
        path: PathBuf,
        /// What the system said.
        #[source]
        source: std::io::Error,
    },
    /// An instance refers to a mesh id the bound meshes lack.
    #[error("instance {instance} uses mesh id {mesh}, but only {bound} meshes are bound")]
    UnknownMesh {
        /// Index of the instance.
        instance: usize,
        /// Its mesh id.
        mesh: u32,
        /// Number of bound meshes.
        bound: usize,
    },
    /// The model exceeds a limit of the format.
    #[error("{what} exceeds the format's limit of {limit}")]
    TooLarge {
        /// What is too large.
        what: String,
        /// The limit.
        limit: u64,
    },
}

#[cfg(test)]
mod tests;
