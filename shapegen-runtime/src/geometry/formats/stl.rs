//! STL files, ASCII or binary, read with the `stl_io` crate.

use std::io::Cursor;

use glam::Vec3;

use super::decode::decode;
use crate::geometry::mesh::{Mesh, MeshError};

impl Mesh {
    /// Reads an STL file's bytes, ASCII or binary, naming it `name` in errors. Triangles
    /// keep the file's vertex order (counter-clockwise seen from outside, as STL
    /// requires); the facet normals are ignored and vertex normals computed.
    ///
    /// ```
    /// use shapegen_runtime::geometry::Mesh;
    ///
    /// let stl = "solid t\nfacet normal 0 0 1\nouter loop\n\
    ///            vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
    /// let mesh = Mesh::from_stl_bytes("t.stl", stl.as_bytes())?;
    /// assert_eq!(mesh.triangle_count(), 1);
    /// assert!(Mesh::from_stl_bytes("bad.stl", b"solid t\nfacet oops").is_err());
    /// # Ok::<(), shapegen_runtime::geometry::MeshError>(())
    /// ```
    pub fn from_stl_bytes(name: &str, bytes: &[u8]) -> Result<Mesh, MeshError> {
        let stl = stl_io::read_stl(&mut Cursor::new(bytes)).map_err(|e| decode("STL", name, e))?;
        let positions: Vec<Vec3> = stl.vertices.iter().map(|v| Vec3::from(v.0)).collect();
        let mut indices = Vec::with_capacity(stl.faces.len() * 3);
        for face in &stl.faces {
            for &v in &face.vertices {
                let index = u32::try_from(v)
                    .ok()
                    .filter(|&i| (i as usize) < positions.len())
                    .ok_or_else(|| {
                        decode("STL", name, format!("vertex index {v} is out of range"))
                    })?;
                indices.push(index);
            }
        }
        Mesh::from_triangles(name, positions, indices)
    }
}
