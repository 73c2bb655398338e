//! The world-space triangles of one model, each with its unit face normal and mesh.

use glam::Vec3;

use crate::geometry::{BoundMeshes, Instance, MeshId};

/// The world-space triangles of one model, each with its unit face normal and the mesh
/// of the instance it comes from, and their bounding box: what the
/// [objectives](super::Objective) measure.
///
/// Each instance's mesh vertices are transformed by the instance's transform and every
/// triangle of the mesh is kept with the normal of the transformed triangle,
/// `(b - a) x (c - a)` normalised, negated when the transform mirrors (negative
/// determinant) so that it keeps pointing out of a mesh modelled counter-clockwise seen
/// from outside. Rotated, scaled, sheared and mirrored instances therefore get the normals
/// of the shape they really place.
///
/// A triangle is *degenerate*, and skipped, when a vertex is not finite or when
/// `|(b - a) x (c - a)| <= f32::EPSILON * |b - a| * |c - a|` (its corner at `a` is flat
/// to within rounding, or an edge has length 0). Instances whose mesh id has no mesh in
/// the [`BoundMeshes`] are skipped, as the scorers do. The [bounds](Self::bounds) are those
/// of the kept triangles' vertices.
///
/// The buffers are kept between [`fill`](Self::fill)s, so one surface per worker measures
/// a whole population without allocating once it has grown to the largest model.
///
/// ```
/// use glam::{Affine3A, Vec3};
/// use shapegen_runtime::score::objective::Surface;
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let model = [Instance { transform: Affine3A::from_translation(Vec3::Y), mesh: CUBE }];
/// let surface = Surface::from_instances(&model, &meshes);
/// assert_eq!(surface.triangles().len(), 12);
/// assert_eq!(surface.normals().len(), 12);
/// assert!(surface.mesh_ids().iter().all(|&id| id == CUBE));
/// assert_eq!(surface.bounds(), Some((Vec3::new(-0.5, 0.5, -0.5), Vec3::new(0.5, 1.5, 0.5))));
/// # Ok::<(), shapegen_runtime::MeshError>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct Surface {
    triangles: Vec<[Vec3; 3]>,
    normals: Vec<Vec3>,
    /// The mesh of each triangle's instance.
    mesh_ids: Vec<MeshId>,
    bounds: Option<(Vec3, Vec3)>,
    /// One instance's transformed vertices.
    world: Vec<Vec3>,
}

impl Surface {
    /// An empty surface.
    pub fn new() -> Self {
        Surface::default()
    }

    /// The surface of the model made of `instances`.
    pub fn from_instances(instances: &[Instance], meshes: &BoundMeshes) -> Self {
        let mut surface = Surface::new();
        surface.fill(instances, meshes);
        surface
    }

    /// Empties the surface, keeping its memory.
    pub fn clear(&mut self) {
        self.triangles.clear();
        self.normals.clear();
        self.mesh_ids.clear();
        self.bounds = None;
    }

    /// Replaces the surface with that of the model made of `instances`, whose mesh ids
    /// index `meshes`.
    pub fn fill(&mut self, instances: &[Instance], meshes: &BoundMeshes) {
        self.clear();
        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for instance in instances {
            let Some(mesh) = meshes.get(instance.mesh) else {
                continue;
            };
            let t = instance.transform;
            let flip = if t.matrix3.determinant() < 0.0 {
                -1.0
            } else {
                1.0
            };
            self.world.clear();
            self.world
                .extend(mesh.positions.iter().map(|&p| t.transform_point3(p)));
            for tri in mesh.indices.chunks_exact(3) {
                let (Some(&a), Some(&b), Some(&c)) = (
                    self.world.get(tri[0] as usize),
                    self.world.get(tri[1] as usize),
                    self.world.get(tri[2] as usize),
                ) else {
                    continue;
                };
                let Some(normal) = face_normal(a, b, c) else {
                    continue;
                };
                self.triangles.push([a, b, c]);
                self.normals.push(flip * normal);
                self.mesh_ids.push(instance.mesh);
                lo = lo.min(a.min(b).min(c));
                hi = hi.max(a.max(b).max(c));
            }
        }
        if !self.triangles.is_empty() {
            self.bounds = Some((lo, hi));
        }
    }

    /// The kept triangles, in instance order and then mesh order.
    pub fn triangles(&self) -> &[[Vec3; 3]] {
        &self.triangles
    }

    /// The unit face normal of each of [`triangles`](Self::triangles).
    pub fn normals(&self) -> &[Vec3] {
        &self.normals
    }

    /// The mesh of the instance each of [`triangles`](Self::triangles) comes from: which
    /// part of the model it is.
    pub fn mesh_ids(&self) -> &[MeshId] {
        &self.mesh_ids
    }

    /// The smallest and largest coordinates of the triangles' vertices, or `None` when
    /// the surface has no triangle.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        self.bounds
    }

    /// Whether the surface has no triangle.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }
}

/// The unit normal of the counter-clockwise triangle `a b c`, or `None` when it is
/// degenerate (see [`Surface`]).
fn face_normal(a: Vec3, b: Vec3, c: Vec3) -> Option<Vec3> {
    if !(a.is_finite() && b.is_finite() && c.is_finite()) {
        return None;
    }
    let (e1, e2) = (b - a, c - a);
    let cross = e1.cross(e2);
    let len = cross.length();
    if !len.is_finite() || len <= f32::EPSILON * e1.length() * e2.length() {
        return None;
    }
    Some(cross / len)
}
