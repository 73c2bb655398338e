//! Binary glTF 2.0 (`.glb`) export.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;

use glam::Vec3;
use gltf_json as json;
use json::validation::{Checked::Valid, USize64};

use super::bake::{placements, used_meshes};
use super::error::ExportError;
use super::model::Model;
use super::obj::write_file;
use crate::geometry::{Instance, Mesh};

const GLB_MAGIC: &[u8; 4] = b"glTF";
const GLB_VERSION: u32 = 2;
const CHUNK_JSON: &[u8; 4] = b"JSON";
const CHUNK_BIN: &[u8; 4] = b"BIN\0";

/// The model as a binary glTF 2.0 file.
///
/// One glTF mesh per mesh used, in [`MeshId`] order, holding all its instances baked
/// into world space: one triangle primitive with `POSITION` (with the exact `min` and
/// `max` the specification requires) and `NORMAL` as `f32` vectors and `u32` indices,
/// each accessor in its own buffer view of the single binary buffer. One
/// metallic-roughness material per mesh (`baseColorFactor` from the palette, metallic
/// 0, roughness 0.8), one node per mesh, one scene holding the nodes; meshes,
/// materials and nodes are named after the mesh. With no instances the file holds no
/// scene and no buffer.
///
/// glTF allows finite numbers only: an instance that places a vertex at NaN or infinity
/// (a non-finite transform, or one whose result overflows `f32`) is left out, and a
/// mesh with no instance left, or with no triangle, gets no glTF mesh, material or
/// node. So every file passes the Khronos glTF validator, as `tests/gltf_validator.rs`
/// checks.
///
/// [`MeshId`]: crate::MeshId
///
/// ```
/// use glam::Affine3A;
/// use shapegen_runtime::{CUBE, Instance, export::{Model, Palette, glb_bytes}, geometry::MeshLibrary};
///
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let boxes = [Instance { transform: Affine3A::IDENTITY, mesh: CUBE }];
/// let glb = glb_bytes(Model::new(&boxes, &meshes, &Palette::new()))?;
/// assert_eq!(&glb[..4], b"glTF");
/// assert_eq!(glb.len() % 4, 0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn glb_bytes(model: Model<'_>) -> Result<Vec<u8>, ExportError> {
    let Model {
        instances,
        meshes,
        palette,
    } = model;
    let mut file = GlbFile::default();
    for id in used_meshes(instances, meshes)? {
        let name = meshes.name(id).unwrap_or_default();
        let baked = bake(instances, id, &meshes[id], name)?;
        if baked.indices.is_empty() {
            // No finite instance, or no triangle: an accessor must hold an element.
            continue;
        }
        file.add_mesh(&baked, name, palette.color(id, name));
    }
    file.finish()
}

/// A glTF document and its binary buffer as [`glb_bytes`] builds them, one mesh (with
/// its material and node) at a time.
struct GlbFile {
    root: json::Root,
    bin: Vec<u8>,
    nodes: Vec<json::Index<json::Node>>,
}

impl Default for GlbFile {
    fn default() -> Self {
        GlbFile {
            root: json::Root {
                asset: json::Asset {
                    generator: Some("shapegen".to_owned()),
                    ..Default::default()
                },
                ..Default::default()
            },
            bin: Vec::new(),
            nodes: Vec::new(),
        }
    }
}

impl GlbFile {
    /// Adds `baked` (with at least one triangle) as the glTF mesh `name`, with a node and
    /// a material of colour `rgb`.
    fn add_mesh(&mut self, baked: &Baked, name: &str, rgb: [f32; 3]) {
        let views = [
            (
                as_bytes(&baked.positions),
                json::buffer::Target::ArrayBuffer,
            ),
            (as_bytes(&baked.normals), json::buffer::Target::ArrayBuffer),
            (
                as_bytes(&baked.indices),
                json::buffer::Target::ElementArrayBuffer,
            ),
        ]
        .map(|(bytes, target)| self.push_view(&bytes, target));
        let root = &mut self.root;
        let (lo, hi) = bounds(&baked.positions);
        let vec3 = |view, min_max: Option<(Vec3, Vec3)>| json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(baked.positions.len()),
            component_type: Valid(json::accessor::GenericComponentType(
                json::accessor::ComponentType::F32,
            )),
            extensions: None,
            extras: Default::default(),
            type_: Valid(json::accessor::Type::Vec3),
            min: min_max.map(|(lo, _)| json::Value::from(lo.to_array().to_vec())),
            max: min_max.map(|(_, hi)| json::Value::from(hi.to_array().to_vec())),
            name: None,
            normalized: false,
            sparse: None,
        };
        let position = root.push(vec3(views[0], Some((lo, hi))));
        let normal = root.push(vec3(views[1], None));
        let indices = root.push(json::Accessor {
            count: USize64::from(baked.indices.len()),
            component_type: Valid(json::accessor::GenericComponentType(
                json::accessor::ComponentType::U32,
            )),
            type_: Valid(json::accessor::Type::Scalar),
            min: None,
            max: None,
            ..vec3(views[2], None)
        });
        let primitive = json::mesh::Primitive {
            attributes: BTreeMap::from([
                (Valid(json::mesh::Semantic::Positions), position),
                (Valid(json::mesh::Semantic::Normals), normal),
            ]),
            extensions: None,
            extras: Default::default(),
            indices: Some(indices),
            material: Some(self.push_material(name, rgb)),
            mode: Valid(json::mesh::Mode::Triangles),
            targets: None,
        };
        self.push_node(name, primitive);
    }

    /// Appends `bytes` to the binary buffer as a view for `target`.
    fn push_view(
        &mut self,
        bytes: &[u8],
        target: json::buffer::Target,
    ) -> json::Index<json::buffer::View> {
        let view = json::buffer::View {
            buffer: json::Index::new(0),
            byte_length: USize64::from(bytes.len()),
            byte_offset: Some(USize64::from(self.bin.len())),
            byte_stride: None,
            name: None,
            target: Some(Valid(target)),
            extensions: None,
            extras: Default::default(),
        };
        self.bin.extend_from_slice(bytes);
        self.root.push(view)
    }

    /// A metallic-roughness material `name` of colour `rgb`.
    fn push_material(&mut self, name: &str, [r, g, b]: [f32; 3]) -> json::Index<json::Material> {
        self.root.push(json::Material {
            name: Some(name.to_owned()),
            pbr_metallic_roughness: json::material::PbrMetallicRoughness {
                base_color_factor: json::material::PbrBaseColorFactor([r, g, b, 1.0]),
                metallic_factor: json::material::StrengthFactor(0.0),
                roughness_factor: json::material::StrengthFactor(0.8),
                ..Default::default()
            },
            ..Default::default()
        })
    }

    /// The mesh `name` of one primitive, and a node holding it.
    fn push_node(&mut self, name: &str, primitive: json::mesh::Primitive) {
        let mesh = self.root.push(json::Mesh {
            extensions: None,
            extras: Default::default(),
            name: Some(name.to_owned()),
            primitives: vec![primitive],
            weights: None,
        });
        self.nodes.push(self.root.push(json::Node {
            mesh: Some(mesh),
            name: Some(name.to_owned()),
            ..Default::default()
        }));
    }

    /// The file's bytes: the buffer and the scene, where there is anything to hold.
    fn finish(mut self) -> Result<Vec<u8>, ExportError> {
        if !self.bin.is_empty() {
            self.root.push(json::Buffer {
                byte_length: USize64::from(self.bin.len()),
                name: None,
                uri: None,
                extensions: None,
                extras: Default::default(),
            });
        }
        if !self.nodes.is_empty() {
            let scene = self.root.push(json::Scene {
                extensions: None,
                extras: Default::default(),
                name: None,
                nodes: self.nodes,
            });
            self.root.scene = Some(scene);
        }
        let json = self.root.to_vec().map_err(std::io::Error::from)?;
        pack(json, self.bin)
    }
}

/// Writes [`glb_bytes`] to `writer`.
pub fn write_glb<W: Write>(mut writer: W, model: Model<'_>) -> Result<(), ExportError> {
    writer.write_all(&glb_bytes(model)?)?;
    writer.flush()?;
    Ok(())
}

/// Writes [`glb_bytes`] to the file `path`, as given (conventionally `*.glb`).
pub fn save_glb(path: impl AsRef<Path>, model: Model<'_>) -> Result<(), ExportError> {
    let bytes = glb_bytes(model)?;
    write_file(path.as_ref(), |f| Ok(f.write_all(&bytes)?))
}

/// All instances of one mesh in world space.
struct Baked {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    indices: Vec<u32>,
}

fn bake(
    instances: &[Instance],
    id: crate::geometry::MeshId,
    mesh: &Mesh,
    name: &str,
) -> Result<Baked, ExportError> {
    let count = instances.iter().filter(|i| i.mesh == id).count();
    let vertices = (count as u64) * mesh.positions.len() as u64;
    if vertices > u64::from(u32::MAX) {
        return Err(ExportError::TooLarge {
            what: format!("mesh `{name}`: {vertices} vertices over {count} instances"),
            limit: u64::from(u32::MAX),
        });
    }
    let mut baked = Baked {
        positions: Vec::with_capacity(vertices as usize),
        normals: Vec::with_capacity(vertices as usize),
        indices: Vec::with_capacity(count * mesh.indices.len()),
    };
    for place in placements(instances, id) {
        let base = baked.positions.len() as u32;
        baked
            .positions
            .extend(mesh.positions.iter().map(|&p| place.position(p)));
        // glTF allows finite floats only: an instance placed at NaN or infinity (a
        // non-finite transform, or one that overflows) is left out.
        if !baked.positions[base as usize..]
            .iter()
            .all(|p| p.is_finite())
        {
            baked.positions.truncate(base as usize);
            continue;
        }
        baked
            .normals
            .extend(mesh.normals.iter().map(|&n| place.normal(n)));
        for t in mesh.triangles() {
            baked.indices.extend(place.triangle(t, base));
        }
    }
    Ok(baked)
}

fn bounds(points: &[Vec3]) -> (Vec3, Vec3) {
    points.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    )
}

/// Little-endian bytes of `f32` vectors or `u32` indices.
fn as_bytes<T: ToLeBytes>(items: &[T]) -> Vec<u8> {
    let mut bytes = Vec::with_capacity(items.len() * T::SIZE);
    for item in items {
        item.append_le(&mut bytes);
    }
    bytes
}

trait ToLeBytes {
    const SIZE: usize;
    fn append_le(&self, out: &mut Vec<u8>);
}

impl ToLeBytes for Vec3 {
    const SIZE: usize = 12;
    fn append_le(&self, out: &mut Vec<u8>) {
        for c in self.to_array() {
            out.extend_from_slice(&c.to_le_bytes());
        }
    }
}

impl ToLeBytes for u32 {
    const SIZE: usize = 4;
    fn append_le(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
}

/// The GLB container: a 12-byte header, the JSON chunk padded with spaces and, when
/// there is binary data, the BIN chunk padded with zeros, all 4-byte aligned.
fn pack(mut json: Vec<u8>, mut bin: Vec<u8>) -> Result<Vec<u8>, ExportError> {
    json.resize(json.len().next_multiple_of(4), b' ');
    bin.resize(bin.len().next_multiple_of(4), 0);
    let bin_chunk = if bin.is_empty() { 0 } else { 8 + bin.len() };
    let total = 12 + 8 + json.len() + bin_chunk;
    let total = u32::try_from(total).map_err(|_| ExportError::TooLarge {
        what: format!("the GLB file ({total} bytes)"),
        limit: u64::from(u32::MAX),
    })?;
    let mut out = Vec::with_capacity(total as usize);
    out.extend_from_slice(GLB_MAGIC);
    out.extend_from_slice(&GLB_VERSION.to_le_bytes());
    out.extend_from_slice(&total.to_le_bytes());
    for (kind, data) in [(CHUNK_JSON, &json), (CHUNK_BIN, &bin)] {
        if data.is_empty() && kind == CHUNK_BIN {
            continue;
        }
        out.extend_from_slice(&(data.len() as u32).to_le_bytes());
        out.extend_from_slice(kind);
        out.extend_from_slice(data);
    }
    Ok(out)
}
