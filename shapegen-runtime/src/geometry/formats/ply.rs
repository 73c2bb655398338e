//! PLY files, ASCII or binary, read with the `ply-rs-bw` crate: the `vertex` element's
//! `x`, `y`, `z` and the `face` element's index list.

use glam::Vec3;
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{DefaultElement, Encoding, Header, Ply, PropertyType, ScalarType};

use super::decode::{decode, fan};
use crate::geometry::mesh::{Mesh, MeshError};

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

/// The parsed file. A binary file's header is checked against the bytes that follow
/// it before the payload is read, so a declared count no file could hold is refused
/// instead of being read entry by entry.
fn read(name: &str, bytes: &[u8]) -> Result<Ply<DefaultElement>, MeshError> {
    let parser = Parser::<DefaultElement>::new();
    let mut reader = Reader::new(bytes);
    let header = parser
        .read_header(&mut reader)
        .map_err(|e| decode("PLY", name, e))?;
    let payload_bytes = reader.get_ref().len();
    if header.encoding != Encoding::Ascii {
        fits(name, &header, payload_bytes)?;
    }
    let payload = parser
        .read_payload(&mut reader, &header)
        .map_err(|e| decode("PLY", name, e))?;
    let mut ply = Ply::new();
    ply.header = header;
    ply.payload = payload;
    Ok(ply)
}

/// Checks that a binary payload of `payload_bytes` can hold every element the header
/// declares, each entry taking at least its scalars and its lists' lengths (and at
/// least one byte, so that an element without properties cannot declare more
/// entries than the file has bytes).
fn fits(name: &str, header: &Header, payload_bytes: usize) -> Result<(), MeshError> {
    let mut needed = 0usize;
    for element in header.elements.values() {
        let entry = element
            .properties
            .values()
            .map(|p| match &p.data_type {
                PropertyType::Scalar(t) | PropertyType::List(t, _) => scalar_size(t),
            })
            .sum::<usize>()
            .max(1);
        needed = element
            .count
            .checked_mul(entry)
            .and_then(|n| n.checked_add(needed))
            .filter(|&n| n <= payload_bytes)
            .ok_or_else(|| {
                decode(
                    "PLY",
                    name,
                    format!(
                        "element `{}` declares {} entries of at least {entry} byte{} each, \
                         but only {payload_bytes} bytes follow the header",
                        element.name,
                        element.count,
                        if entry == 1 { "" } else { "s" }
                    ),
                )
            })?;
    }
    Ok(())
}

/// The bytes one binary scalar of type `t` takes.
fn scalar_size(t: &ScalarType) -> usize {
    match t {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
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
