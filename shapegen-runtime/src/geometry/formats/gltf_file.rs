//! glTF 2.0 files, as JSON (`.gltf`) or binary (`.glb`), parsed and validated with the
//! `gltf` crate; the triangles of the default scene (or the first, or, without scenes,
//! of every mesh) placed by their nodes' transforms.

use std::path::Path;

use base64::Engine as _;
use glam::{Mat4, Vec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::{Mode, Semantic};
use gltf::{Accessor, Gltf};

use super::decode::decode;
use crate::geometry::mesh::{Mesh, MeshError};

impl Mesh {
    /// Reads a glTF file's bytes (JSON or binary), naming it `name` in errors. Buffers
    /// come from the binary chunk, from `data:` URIs, or from files beside the glTF
    /// file in `folder` (none: only embedded buffers are read).
    ///
    /// The triangles of the default scene are taken, or of the first scene, or without
    /// scenes of every mesh; each primitive placed by its node's world transform. Only
    /// triangle-list primitives with `f32` positions and non-sparse accessors are read;
    /// points, lines and strips are skipped. Normals are computed.
    ///
    /// ```
    /// use shapegen_runtime::geometry::Mesh;
    ///
    /// let err = Mesh::from_gltf_bytes("t.glb", b"glTF", None).unwrap_err();
    /// assert!(err.to_string().starts_with("cannot read glTF `t.glb`:"));
    /// ```
    pub fn from_gltf_bytes(
        name: &str,
        bytes: &[u8],
        folder: Option<&Path>,
    ) -> Result<Mesh, MeshError> {
        let fail = |what: String| decode("glTF", name, what);
        let (bytes, blob) = match bytes.strip_prefix(b"glTF") {
            Some(_) => glb_chunks(bytes).map_err(&fail)?,
            None => (bytes, None),
        };
        let unchecked =
            Gltf::from_slice_without_validation(bytes).map_err(|e| fail(e.to_string()))?;
        check_attributes(&unchecked).map_err(&fail)?;
        let gltf = Gltf::from_slice(bytes).map_err(|e| fail(e.to_string()))?;
        let buffers = read_buffers(&gltf, blob, folder).map_err(&fail)?;
        let placed = placed_meshes(&gltf).map_err(&fail)?;
        let (positions, indices) = triangles(placed, &buffers).map_err(&fail)?;
        Mesh::from_triangles(name, positions, indices)
    }
}

/// Checks that every attribute and index accessor a primitive names exists: gltf-json's
/// validation indexes a primitive's POSITION accessor before it checks that.
fn check_attributes(unchecked: &Gltf) -> Result<(), String> {
    let accessors = unchecked.document.as_json().accessors.len();
    for (m, mesh) in unchecked.document.as_json().meshes.iter().enumerate() {
        for primitive in &mesh.primitives {
            let named = primitive
                .attributes
                .values()
                .chain(primitive.indices.as_ref());
            if let Some(bad) = named.map(|a| a.value()).find(|&a| a >= accessors) {
                return Err(format!(
                    "mesh {m} names accessor {bad}, but the file has {accessors}"
                ));
            }
        }
    }
    Ok(())
}

/// The data of every buffer of `gltf`: from the binary chunk `blob`, a `data:` URI, or a
/// file in `folder`; each at least as long as it declares.
fn read_buffers(
    gltf: &Gltf,
    blob: Option<&[u8]>,
    folder: Option<&Path>,
) -> Result<Vec<Vec<u8>>, String> {
    gltf.buffers()
        .map(|buffer| {
            let data = match buffer.source() {
                gltf::buffer::Source::Bin => blob
                    .map(<[u8]>::to_vec)
                    .ok_or_else(|| "the binary chunk is missing".to_owned())?,
                gltf::buffer::Source::Uri(uri) => external(uri, folder)?,
            };
            if data.len() < buffer.length() {
                return Err(format!(
                    "buffer {} holds {} bytes of the {} it declares",
                    buffer.index(),
                    data.len(),
                    buffer.length()
                ));
            }
            Ok(data)
        })
        .collect()
}

/// The meshes to read with their world transforms: those of the default scene's node
/// tree (or the first scene's), or every mesh where there is no scene.
fn placed_meshes(gltf: &Gltf) -> Result<Vec<(gltf::Mesh<'_>, Mat4)>, String> {
    let mut placed = Vec::new();
    match gltf.default_scene().or_else(|| gltf.scenes().next()) {
        Some(scene) => {
            let mut stack: Vec<_> = scene.nodes().map(|n| (n, Mat4::IDENTITY)).collect();
            let mut visits = 0;
            while let Some((node, parent)) = stack.pop() {
                visits += 1;
                if visits > gltf.nodes().len() {
                    return Err("the scene's nodes do not form a tree".into());
                }
                let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
                if let Some(mesh) = node.mesh() {
                    placed.push((mesh, world));
                }
                stack.extend(node.children().map(|c| (c, world)));
            }
        }
        None => placed.extend(gltf.meshes().map(|m| (m, Mat4::IDENTITY))),
    }
    Ok(placed)
}

/// The world positions and triangle indices of the triangle-list primitives of
/// `placed`, read from `buffers`.
fn triangles(
    placed: Vec<(gltf::Mesh<'_>, Mat4)>,
    buffers: &[Vec<u8>],
) -> Result<(Vec<Vec3>, Vec<u32>), String> {
    let (mut positions, mut indices) = (Vec::new(), Vec::new());
    for (mesh, world) in placed {
        for primitive in mesh.primitives() {
            if primitive.mode() != Mode::Triangles {
                continue;
            }
            let at = format!("mesh {} primitive {}", mesh.index(), primitive.index());
            let accessor = primitive
                .get(&Semantic::Positions)
                .ok_or_else(|| format!("{at} has no POSITION"))?;
            let local = read_positions(&accessor, buffers)
                .map_err(|what| format!("{at}: POSITION {what}"))?;
            let base = positions.len() as u32;
            let corners = match primitive.indices() {
                Some(accessor) => read_indices(&accessor, buffers)
                    .map_err(|what| format!("{at}: indices {what}"))?,
                None => (0..local.len() as u32).collect(),
            };
            if let Some(&i) = corners.iter().find(|&&i| i as usize >= local.len()) {
                return Err(format!(
                    "{at}: index {i} is out of range for {} vertices",
                    local.len()
                ));
            }
            positions.extend(local.iter().map(|&p| world.transform_point3(p)));
            let whole = corners.len() - corners.len() % 3;
            indices.extend(corners[..whole].iter().map(|&i| base + i));
        }
    }
    Ok((positions, indices))
}

/// The JSON chunk and the binary chunk, if any, of a binary glTF (`.glb`): a 12-byte
/// header (`glTF`, version 2, total length), then chunks of a length, a type and the
/// data. Read here, every length checked, rather than by the `gltf` crate's reader.
fn glb_chunks(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), String> {
    let word = |at: usize| {
        bytes
            .get(at..at + 4)
            .map(|w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]) as usize)
    };
    if word(4) != Some(2) {
        return Err("the binary glTF header is not of version 2".into());
    }
    let total = word(8)
        .filter(|&n| n <= bytes.len())
        .ok_or_else(|| "the binary glTF is shorter than its header says".to_owned())?;
    // A chunk at `at`: its data, its type and where the next one starts.
    type Chunk<'a> = Option<(&'a [u8], u32, usize)>;
    let chunk = |at: usize| -> Result<Chunk<'_>, String> {
        if at >= total {
            return Ok(None);
        }
        let (Some(len), Some(kind)) = (word(at), word(at + 4)) else {
            return Err("a binary glTF chunk header is cut short".into());
        };
        let data = (at + 8)
            .checked_add(len)
            .filter(|&end| end <= total)
            .map(|end| &bytes[at + 8..end])
            .ok_or_else(|| "a binary glTF chunk runs past the end of the file".to_owned())?;
        Ok(Some((data, kind as u32, at + 8 + len)))
    };
    const JSON: u32 = 0x4E4F_534A;
    const BIN: u32 = 0x004E_4942;
    let Some((json, JSON, next)) = chunk(12)? else {
        return Err("the first chunk of a binary glTF is not its JSON".into());
    };
    let blob = match chunk(next)? {
        Some((data, BIN, _)) => Some(data),
        _ => None,
    };
    Ok((json, blob))
}

/// The bytes of a buffer's URI: a `data:` URI's base64 payload, or a file in `folder`.
fn external(uri: &str, folder: Option<&Path>) -> Result<Vec<u8>, String> {
    if let Some(data) = uri.strip_prefix("data:") {
        let (_, payload) = data
            .split_once(";base64,")
            .ok_or_else(|| "a data URI of a buffer is not base64".to_owned())?;
        return base64::engine::general_purpose::STANDARD
            .decode(payload)
            .map_err(|e| format!("a data URI of a buffer is not valid base64: {e}"));
    }
    let folder = folder.ok_or_else(|| format!("buffer `{uri}` is an external file"))?;
    let path = folder.join(uri);
    std::fs::read(&path).map_err(|e| format!("cannot read buffer `{}`: {e}", path.display()))
}

/// The bytes an accessor of `count` elements of `size` bytes reads, and its stride;
/// checked to lie within its buffer.
fn accessor_bytes<'a>(
    accessor: &Accessor,
    buffers: &'a [Vec<u8>],
    size: usize,
) -> Result<(&'a [u8], usize), String> {
    if accessor.sparse().is_some() {
        return Err("is sparse, which is not read".into());
    }
    let view = accessor
        .view()
        .ok_or_else(|| "has no buffer view".to_owned())?;
    let buffer = &buffers[view.buffer().index()];
    let data = view
        .offset()
        .checked_add(view.length())
        .and_then(|end| buffer.get(view.offset()..end))
        .ok_or_else(|| "reads past the end of its buffer".to_owned())?;
    let stride = view.stride().unwrap_or(size);
    if stride < size {
        return Err(format!(
            "has a stride of {stride} bytes for elements of {size}"
        ));
    }
    let count = accessor.count();
    let needed = match count {
        0 => Some(0),
        n => (n - 1)
            .checked_mul(stride)
            .and_then(|b| b.checked_add(size))
            .and_then(|b| b.checked_add(accessor.offset())),
    };
    match needed {
        Some(end) if end <= data.len() => Ok((&data[accessor.offset().min(end)..end], stride)),
        _ => Err("reads past the end of its buffer view".into()),
    }
}

/// A `VEC3` `f32` accessor's values.
fn read_positions(accessor: &Accessor, buffers: &[Vec<u8>]) -> Result<Vec<Vec3>, String> {
    if (accessor.data_type(), accessor.dimensions()) != (DataType::F32, Dimensions::Vec3) {
        return Err("is not a VEC3 of floats".into());
    }
    let (bytes, stride) = accessor_bytes(accessor, buffers, 12)?;
    Ok((0..accessor.count())
        .map(|i| {
            let at = &bytes[i * stride..i * stride + 12];
            let f = |k: usize| f32::from_le_bytes([at[k], at[k + 1], at[k + 2], at[k + 3]]);
            Vec3::new(f(0), f(4), f(8))
        })
        .collect())
}

/// A `SCALAR` unsigned-integer accessor's values.
fn read_indices(accessor: &Accessor, buffers: &[Vec<u8>]) -> Result<Vec<u32>, String> {
    let size = match (accessor.data_type(), accessor.dimensions()) {
        (DataType::U8, Dimensions::Scalar) => 1,
        (DataType::U16, Dimensions::Scalar) => 2,
        (DataType::U32, Dimensions::Scalar) => 4,
        _ => return Err("are not unsigned integer scalars".into()),
    };
    let (bytes, stride) = accessor_bytes(accessor, buffers, size)?;
    Ok((0..accessor.count())
        .map(|i| {
            let at = &bytes[i * stride..i * stride + size];
            match size {
                1 => u32::from(at[0]),
                2 => u32::from(u16::from_le_bytes([at[0], at[1]])),
                _ => u32::from_le_bytes([at[0], at[1], at[2], at[3]]),
            }
        })
        .collect())
}
