//! Meshes by name, and bound to a grammar's mesh ids.

use std::collections::BTreeMap;
use std::ops::Index;
use std::path::Path;
use std::sync::Arc;

use super::instance::MeshId;
use super::mesh::{Mesh, MeshError};
use crate::graph::GeneratorGraph;

/// Meshes registered by name, to be [bound](Self::bind) to the mesh names a grammar
/// uses. It always has `"cube"`, the [unit cube](Mesh::unit_cube), unless that is
/// replaced.
///
/// ```
/// use shapegen_runtime::geometry::{Mesh, MeshLibrary};
///
/// let mut library = MeshLibrary::new();
/// library.register("box", Mesh::unit_cube())?;
/// let bound = library.bind_names("Demo", &["cube", "box"])?;
/// assert_eq!(bound.len(), 2);
///
/// let missing = library.bind_names("Tree", &["cube", "leaf"]).unwrap_err();
/// assert_eq!(
///     missing.to_string(),
///     "generator `Tree` uses mesh `leaf`, which is not registered; \
///      register it with MeshLibrary::register_obj(\"leaf\", path)"
/// );
/// # Ok::<(), shapegen_runtime::geometry::MeshError>(())
/// ```
#[derive(Clone, Debug)]
pub struct MeshLibrary {
    meshes: BTreeMap<String, Arc<Mesh>>,
}

impl Default for MeshLibrary {
    fn default() -> Self {
        Self::new()
    }
}

impl MeshLibrary {
    /// A library holding only `"cube"`.
    pub fn new() -> Self {
        let mut meshes = BTreeMap::new();
        meshes.insert("cube".to_owned(), Arc::new(Mesh::unit_cube()));
        MeshLibrary { meshes }
    }

    /// Registers `mesh` as `name`, replacing any mesh of that name, after checking it
    /// with [`Mesh::validate`].
    pub fn register(
        &mut self,
        name: impl Into<String>,
        mesh: Mesh,
    ) -> Result<&mut Self, MeshError> {
        let name = name.into();
        mesh.validate(&name)?;
        self.meshes.insert(name, Arc::new(mesh));
        Ok(self)
    }

    /// Loads a generator part from an OBJ file with [`Mesh::from_obj_normalized`] (fitted
    /// to unit extent as the original implementation does with every generator mesh)
    /// and registers it as `name`.
    pub fn register_obj(
        &mut self,
        name: impl Into<String>,
        path: impl AsRef<Path>,
    ) -> Result<&mut Self, MeshError> {
        let mesh = Mesh::from_obj_normalized(path)?;
        self.register(name, mesh)
    }

    /// Loads an OBJ file with [`Mesh::from_obj`], keeping its coordinates as written,
    /// and registers it as `name`: for parts modelled at the size they are meant to
    /// have.
    pub fn register_obj_as_written(
        &mut self,
        name: impl Into<String>,
        path: impl AsRef<Path>,
    ) -> Result<&mut Self, MeshError> {
        let mesh = Mesh::from_obj(path)?;
        self.register(name, mesh)
    }

    /// The mesh registered as `name`.
    pub fn get(&self, name: &str) -> Option<&Mesh> {
        self.meshes.get(name).map(|m| &**m)
    }

    /// The registered names, in sorted order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.meshes.keys().map(String::as_str)
    }

    /// Resolves every mesh name of `graph` (its [`meshes`](GeneratorGraph::meshes)),
    /// giving the meshes indexed by [`MeshId`]. Fails on the first name that is not
    /// registered.
    pub fn bind(&self, graph: &GeneratorGraph) -> Result<BoundMeshes, MeshError> {
        self.bind_names(graph.name, graph.meshes)
    }

    /// Resolves `names` for the generator called `generator` (named in errors): mesh
    /// `i` of the result is the one registered as `names[i]`.
    pub fn bind_names<S: AsRef<str>>(
        &self,
        generator: &str,
        names: &[S],
    ) -> Result<BoundMeshes, MeshError> {
        let entries = names
            .iter()
            .map(|name| {
                let name = name.as_ref();
                match self.meshes.get(name) {
                    Some(mesh) => Ok((name.to_owned(), Arc::clone(mesh))),
                    None => Err(MeshError::Unregistered {
                        generator: generator.to_owned(),
                        mesh: name.to_owned(),
                    }),
                }
            })
            .collect::<Result<_, _>>()?;
        Ok(BoundMeshes { entries })
    }
}

/// A grammar's meshes, indexed by [`MeshId`]: what exporters and scorers read instances
/// against. Made by [`MeshLibrary::bind`]; cheap to clone (the meshes are shared).
///
/// ```
/// use shapegen_runtime::{CUBE, geometry::MeshLibrary};
///
/// let bound = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// assert_eq!(bound.name(CUBE), Some("cube"));
/// assert_eq!(bound[CUBE].triangle_count(), 12);
/// # Ok::<(), shapegen_runtime::geometry::MeshError>(())
/// ```
#[derive(Clone, Debug)]
pub struct BoundMeshes {
    entries: Vec<(String, Arc<Mesh>)>,
}

impl BoundMeshes {
    /// Number of meshes.
    #[inline]
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether there are no meshes.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The mesh with id `id`, if there is one.
    #[inline]
    pub fn get(&self, id: MeshId) -> Option<&Mesh> {
        self.entries.get(id.0 as usize).map(|(_, m)| &**m)
    }

    /// The name of the mesh with id `id`, if there is one.
    #[inline]
    pub fn name(&self, id: MeshId) -> Option<&str> {
        self.entries.get(id.0 as usize).map(|(n, _)| n.as_str())
    }

    /// Every mesh with its id and name, in id order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = (MeshId, &str, &Mesh)> {
        self.entries
            .iter()
            .enumerate()
            .map(|(i, (n, m))| (MeshId(i as u32), n.as_str(), &**m))
    }
}

impl Index<MeshId> for BoundMeshes {
    type Output = Mesh;

    /// The mesh with id `id`; panics when there is none.
    #[inline]
    fn index(&self, id: MeshId) -> &Mesh {
        &self.entries[id.0 as usize].1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    static TREE: GeneratorGraph = GeneratorGraph {
        name: "Tree",
        key: "tree",
        axiom: 0,
        nodes: &[],
        meshes: &["cube", "trunk", "leaf"],
    };

    fn meshes_dir() -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../generators/meshes")
    }

    #[test]
    fn bind_resolves_every_grammar_mesh_by_id() {
        let mut library = MeshLibrary::new();
        let err = library.bind(&TREE).unwrap_err().to_string();
        assert_eq!(
            err,
            "generator `Tree` uses mesh `trunk`, which is not registered; \
             register it with MeshLibrary::register_obj(\"trunk\", path)"
        );
        library
            .register_obj("trunk", meshes_dir().join("trunk.obj"))
            .unwrap()
            .register_obj("leaf", meshes_dir().join("leaf.obj"))
            .unwrap();
        let bound = library.bind(&TREE).unwrap();
        assert_eq!(bound.len(), 3);
        let names: Vec<_> = bound.iter().map(|(id, name, _)| (id.0, name)).collect();
        assert_eq!(names, [(0, "cube"), (1, "trunk"), (2, "leaf")]);
        assert_eq!(bound[MeshId(0)], Mesh::unit_cube());
        assert_eq!(bound.get(MeshId(2)), library.get("leaf"));
        assert_eq!(bound.get(MeshId(3)), None);
        assert_eq!(
            library.names().collect::<Vec<_>>(),
            ["cube", "leaf", "trunk"]
        );
    }

    #[test]
    fn register_checks_the_mesh() {
        let mut bad = Mesh::unit_cube();
        bad.indices[0] = 100;
        let err = MeshLibrary::new().register("odd", bad).unwrap_err();
        assert!(err.to_string().starts_with("mesh `odd` is malformed"));
    }

    /// The tree generator's own meshes: closed, centred, with the documented extents.
    #[test]
    fn default_tree_meshes_load_closed_and_centred() {
        for (file, size) in [
            ("trunk.obj", [1.0, 1.0, 1.0]),
            ("leaf.obj", [0.48, 0.98, 0.15]),
        ] {
            let mesh = Mesh::from_obj(meshes_dir().join(file)).unwrap();
            assert!(mesh.is_closed(), "{file} is closed");
            let (lo, hi) = mesh.bounds().unwrap();
            assert!((lo + hi).abs().max_element() < 1e-3, "{file} is centred");
            let extent = hi - lo;
            for k in 0..3 {
                assert!((extent[k] - size[k]).abs() < 2e-3, "{file} extent {extent}");
            }
            for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
                assert!((n.length() - 1.0).abs() < 1e-3);
                // Both solids are star-shaped about the origin: normals face outward.
                assert!(p.dot(*n) > 0.0, "{file}: normal {n} at {p}");
            }
        }
    }
}
