//! Mesh files of every format the toolkit reads, chosen by the file's extension: one
//! table ([`MeshFormat::ALL`]) names each format, its extensions and its reader.

mod decode;
mod gltf_file;
mod ply;
mod points;
mod stl;

use std::path::Path;

use glam::Vec3;

pub use points::PointCloud;

use super::mesh::{Mesh, MeshError};

/// A mesh file format.
///
/// ```
/// use shapegen_runtime::geometry::MeshFormat;
///
/// assert_eq!(MeshFormat::of_path("scan.STL".as_ref()), Some(MeshFormat::Stl));
/// assert_eq!(MeshFormat::of_path("model.glb".as_ref()), Some(MeshFormat::Gltf));
/// assert_eq!(MeshFormat::of_path("notes.txt".as_ref()), None);
/// assert_eq!(MeshFormat::extensions(), ".obj, .stl, .ply, .gltf, .glb");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ text ([`Mesh::from_obj_str`]).
    Obj,
    /// STL, ASCII or binary ([`Mesh::from_stl_bytes`]).
    Stl,
    /// PLY, ASCII or binary ([`Mesh::from_ply_bytes`]).
    Ply,
    /// glTF 2.0, as JSON (`.gltf`) or binary (`.glb`) ([`Mesh::from_gltf_bytes`]).
    Gltf,
}

impl MeshFormat {
    /// Every format with its lower-case file extensions, in the order errors list them.
    pub const ALL: [(MeshFormat, &'static [&'static str]); 4] = [
        (MeshFormat::Obj, &["obj"]),
        (MeshFormat::Stl, &["stl"]),
        (MeshFormat::Ply, &["ply"]),
        (MeshFormat::Gltf, &["gltf", "glb"]),
    ];

    /// The format of a file by its extension, in any case; `None` for another one.
    pub fn of_path(path: &Path) -> Option<MeshFormat> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        Self::ALL
            .iter()
            .find(|(_, extensions)| extensions.contains(&extension.as_str()))
            .map(|&(format, _)| format)
    }

    /// The extensions read, as `.obj, .stl, ...`, for error messages.
    pub fn extensions() -> String {
        Self::ALL
            .iter()
            .flat_map(|(_, extensions)| extensions.iter())
            .map(|e| format!(".{e}"))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Reads a mesh in this format from `bytes`, naming it `name` in errors. `folder`
    /// is where a glTF file's external buffers are looked for (none: only embedded
    /// buffers are read).
    pub fn read(self, name: &str, bytes: &[u8], folder: Option<&Path>) -> Result<Mesh, MeshError> {
        match self {
            MeshFormat::Obj => {
                let text = std::str::from_utf8(bytes).map_err(|e| MeshError::Parse {
                    name: name.to_owned(),
                    line: None,
                    what: format!("the file is not UTF-8 text: {e}"),
                })?;
                Mesh::from_obj_str(name, text)
            }
            MeshFormat::Stl => Mesh::from_stl_bytes(name, bytes),
            MeshFormat::Ply => Mesh::from_ply_bytes(name, bytes),
            MeshFormat::Gltf => Mesh::from_gltf_bytes(name, bytes, folder),
        }
    }
}

impl Mesh {
    /// Loads a mesh from a file of any format of [`MeshFormat::ALL`], chosen by its
    /// extension: all its triangles merged into one mesh, normals computed where the
    /// file has none. Errors name the file and, for an unknown extension, the valid
    /// ones.
    ///
    /// ```
    /// use shapegen_runtime::geometry::Mesh;
    ///
    /// let err = Mesh::load("target.fbx").unwrap_err();
    /// assert_eq!(
    ///     err.to_string(),
    ///     "cannot read mesh file `target.fbx`: its extension is not one of \
    ///      .obj, .stl, .ply, .gltf, .glb"
    /// );
    /// ```
    pub fn load(path: impl AsRef<Path>) -> Result<Mesh, MeshError> {
        let path = path.as_ref();
        let format = MeshFormat::of_path(path).ok_or_else(|| MeshError::Format {
            path: path.to_owned(),
            valid: MeshFormat::extensions(),
        })?;
        let bytes = std::fs::read(path).map_err(|source| MeshError::Io {
            path: path.to_owned(),
            source,
        })?;
        format.read(&path.display().to_string(), &bytes, path.parent())
    }

    /// A mesh from triangles read from a file: checks the indices and coordinates,
    /// computes the normals (see [`compute_normals`](Self::compute_normals) with
    /// [`DEFAULT_CREASE_ANGLE`](Self::DEFAULT_CREASE_ANGLE)) and validates it.
    fn from_triangles(
        name: &str,
        positions: Vec<Vec3>,
        indices: Vec<u32>,
    ) -> Result<Mesh, MeshError> {
        if let Some(vertex) = positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinite {
                name: name.to_owned(),
                vertex,
            });
        }
        let mut mesh = Mesh {
            normals: vec![Vec3::ZERO; positions.len()],
            positions,
            indices,
        };
        mesh.validate(name)?;
        mesh.compute_normals(Mesh::DEFAULT_CREASE_ANGLE);
        mesh.validate(name)?;
        Ok(mesh)
    }
}
