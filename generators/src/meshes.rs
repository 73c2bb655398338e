//! The project's own part meshes for the published generators, built into the crate.

use shapegen_runtime::{Mesh, MeshLibrary};

/// The tree's branch mesh: a closed eight-sided prism spanning `[-0.5, 0.5]`.
pub const TRUNK_OBJ: &str = include_str!("../meshes/trunk.obj");

/// The tree's leaf mesh: a closed lens-shaped leaf about 0.48 x 0.98 x 0.15, centred,
/// its tip towards +y. The tree emits it unscaled.
pub const LEAF_OBJ: &str = include_str!("../meshes/leaf.obj");

/// A mesh library holding every mesh the published generators use: the built-in `cube`,
/// `trunk` and `leaf`.
///
/// ```
/// let library = generators::default_meshes();
/// let bound = library.bind(<generators::Tree as shapegen_runtime::Grammar>::GRAPH).unwrap();
/// assert_eq!(bound.len(), 3);
/// ```
pub fn default_meshes() -> MeshLibrary {
    let mut library = MeshLibrary::new();
    for (name, file, text) in [
        ("trunk", "trunk.obj", TRUNK_OBJ),
        ("leaf", "leaf.obj", LEAF_OBJ),
    ] {
        let mesh = Mesh::from_obj_str(file, text)
            .unwrap_or_else(|e| panic!("the built-in mesh {file} is broken: {e}"));
        library
            .register(name, mesh)
            .unwrap_or_else(|e| panic!("the built-in mesh {file} is broken: {e}"));
    }
    library
}
