//! What the readers of the formats share: the error for a malformed file, and polygons
//! as triangles.

use crate::geometry::mesh::MeshError;

/// A polygon of `corners` vertex indices as a fan of triangles.
pub(super) fn fan(corners: &[u32], indices: &mut Vec<u32>) {
    if let [first, rest @ ..] = corners {
        for pair in rest.windows(2) {
            indices.extend([*first, pair[0], pair[1]]);
        }
    }
}

/// The error for a malformed file of `format`.
pub(super) fn decode(format: &str, name: &str, what: impl std::fmt::Display) -> MeshError {
    MeshError::Decode {
        format: format.to_owned(),
        name: name.to_owned(),
        what: what.to_string(),
    }
}
