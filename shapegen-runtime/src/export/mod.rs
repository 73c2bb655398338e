//! Writing derived models to files: Wavefront OBJ with its MTL materials, binary glTF
//! (`.glb`), and shaded [`Preview`] pictures, alone or side by side ([`ContactSheet`]).
//! The file writers take a [`Model`]: its instances, their meshes and a palette.
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
mod error;
mod glb;
mod model;
mod obj;
mod palette;
mod render;
mod sheet;

pub use error::ExportError;
pub use glb::{glb_bytes, save_glb, write_glb};
pub use model::Model;
pub use obj::{save_obj, write_mtl, write_obj};
pub use palette::Palette;
pub use render::Preview;
pub use sheet::ContactSheet;

#[cfg(doc)]
use crate::geometry::{Instance, MeshId};

#[cfg(test)]
mod tests;
