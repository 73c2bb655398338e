//! PLY files, ASCII or binary, read with the `ply-rs-bw` crate: the `vertex` element's
//! `x`, `y`, `z` and the `face` element's index list.

use glam::Vec3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, Ply};

use super::{Mesh, MeshError, decode, fan};

impl Mesh {
    /// Reads a PLY file's bytes, ASCII or binary, naming it `name` in errors: the
    /// `vertex` element's `x`, `y` and `z` (of any numeric type) and the `face`
    /// element's `vertex_indices` (or `vertex_index`) lists, polygons cut into fans.
    /// Other elements and properties are ignored; normals are computed.
    ///
    /// ```
    /// use shapegen_runtime::geometry::Mesh;
    ///
    /// let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n\
    ///            property float y\nproperty float z\nelement face 1\n\
    ///            property list uchar int vertex_indices\nend_header\n\
    ///            0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    /// let mesh = Mesh::from_ply_bytes("t.ply", ply.as_bytes())?;
    /// assert_eq!(mesh.triangle_count(), 1);
    /// # Ok::<(), shapegen_runtime::geometry::MeshError>(())
    /// ```
    pub fn from_ply_bytes(name: &str, bytes: &[u8]) -> Result<Mesh, MeshError> {
        let ply = read(name, bytes)?;
        let positions = vertices(name, &ply)?;
        let faces = ply
            .payload
            .get("face")
            .map(Vec::as_slice)
            .unwrap_or_default();
        let mut indices = Vec::with_capacity(faces.len() * 3);
        for (f, face) in faces.iter().enumerate() {
            let corners = face
                .get("vertex_indices")
                .or_else(|| face.get("vertex_index"))
                .and_then(|p| p.to_u32_list())
                .ok_or_else(|| {
                    decode(
                        "PLY",
                        name,
                        format!("face {f} has no `vertex_indices` list of non-negative integers"),
                    )
                })?;
            if let Some(&v) = corners.iter().find(|&&v| v as usize >= positions.len()) {
                return Err(decode(
                    "PLY",
                    name,
                    format!("face {f} names vertex {v} of {}", positions.len()),
                ));
            }
            fan(&corners, &mut indices);
        }
        if indices.is_empty() {
            return Err(decode(
                "PLY",
                name,
                "it has no faces: a mesh target needs a `face` element (a point cloud \
                 is read as points, not as a mesh)",
            ));
        }
        Mesh::from_triangles(name, positions, indices)
    }
}

/// The parsed file.
fn read(name: &str, bytes: &[u8]) -> Result<Ply<DefaultElement>, MeshError> {
    Parser::<DefaultElement>::new()
        .read_ply(&mut &bytes[..])
        .map_err(|e| decode("PLY", name, e))
}

/// The positions of the `vertex` element, checked finite.
fn vertices(name: &str, ply: &Ply<DefaultElement>) -> Result<Vec<Vec3>, MeshError> {
    let Some(elements) = ply.payload.get("vertex") else {
        return Err(decode("PLY", name, "it has no `vertex` element"));
    };
    elements
        .iter()
        .enumerate()
        .map(|(v, vertex)| {
            let coordinate = |axis: &str| {
                vertex
                    .get(axis)
                    .and_then(|p| p.to_f32_lossy())
                    .ok_or_else(|| {
                        decode(
                            "PLY",
                            name,
                            format!("vertex {v} has no numeric `{axis}` property"),
                        )
                    })
            };
            let p = Vec3::new(coordinate("x")?, coordinate("y")?, coordinate("z")?);
            if p.is_finite() {
                Ok(p)
            } else {
                Err(MeshError::NonFinite {
                    name: name.to_owned(),
                    vertex: v,
                })
            }
        })
        .collect()
}

/// The `vertex` element's positions of a PLY file's bytes (a point cloud), naming it
/// `name` in errors.
pub(crate) fn ply_points(name: &str, bytes: &[u8]) -> Result<Vec<Vec3>, MeshError> {
    vertices(name, &read(name, bytes)?)
}
