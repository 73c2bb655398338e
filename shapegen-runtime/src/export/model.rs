//! What every exporter takes: a model's instances, their meshes and their colours.

use super::palette::Palette;
use crate::geometry::{BoundMeshes, Instance};

/// A model to export: its instances, the meshes they place and the palette that colours
/// each mesh.
///
/// ```
/// use glam::Affine3A;
/// use shapegen_runtime::{CUBE, Instance, export::{Model, Palette, glb_bytes}, geometry::MeshLibrary};
///
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let boxes = [Instance { transform: Affine3A::IDENTITY, mesh: CUBE }];
/// let palette = Palette::new().with("cube", [0.8, 0.1, 0.1]);
/// let glb = glb_bytes(Model::new(&boxes, &meshes, &palette))?;
/// assert_eq!(&glb[..4], b"glTF");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Model<'a> {
    /// The mesh instances, in world space.
    pub instances: &'a [Instance],
    /// The meshes they place, by id.
    pub meshes: &'a BoundMeshes,
    /// The colour of each mesh.
    pub palette: &'a Palette,
}

impl<'a> Model<'a> {
    /// The model of `instances`, placing `meshes` coloured from `palette`.
    pub fn new(instances: &'a [Instance], meshes: &'a BoundMeshes, palette: &'a Palette) -> Self {
        Model {
            instances,
            meshes,
            palette,
        }
    }
}
