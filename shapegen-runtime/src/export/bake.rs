//! Placing mesh vertices in world space, shared by the exporters.

use glam::{Affine3A, Mat3A, Vec3};

use super::error::ExportError;
use crate::geometry::{BoundMeshes, Instance, MeshId};

/// One instance's transform, ready to place positions, normals and triangles.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Placement {
    transform: Affine3A,
    /// The inverse transpose of the linear part, up to a positive factor: the cofactor
    /// matrix times the determinant's sign, defined even for singular transforms.
    normal_matrix: Mat3A,
    /// Whether the transform mirrors, so that triangle winding must be reversed.
    flip: bool,
}

impl Placement {
    pub(crate) fn new(transform: Affine3A) -> Self {
        let m = transform.matrix3;
        let cofactor = Mat3A::from_cols(
            m.y_axis.cross(m.z_axis),
            m.z_axis.cross(m.x_axis),
            m.x_axis.cross(m.y_axis),
        );
        let flip = m.determinant() < 0.0;
        Placement {
            transform,
            normal_matrix: if flip { -cofactor } else { cofactor },
            flip,
        }
    }

    #[inline]
    pub(crate) fn position(&self, p: Vec3) -> Vec3 {
        // +0.0 folds -0.0 into 0.0, for tidy text.
        self.transform.transform_point3(p) + 0.0
    }

    /// The unit normal; `+y` where the transform flattens the surface to nothing.
    #[inline]
    pub(crate) fn normal(&self, n: Vec3) -> Vec3 {
        (self.normal_matrix * n).normalize_or(Vec3::Y) + 0.0
    }

    /// The triangle's indices, offset by `base` and reversed for mirroring transforms.
    #[inline]
    pub(crate) fn triangle(&self, [a, b, c]: [u32; 3], base: u32) -> [u32; 3] {
        if self.flip {
            [a + base, c + base, b + base]
        } else {
            [a + base, b + base, c + base]
        }
    }
}

/// The distinct meshes the instances use, in id order, after checking that all are
/// bound.
pub(crate) fn used_meshes(
    instances: &[Instance],
    meshes: &BoundMeshes,
) -> Result<Vec<MeshId>, ExportError> {
    let mut used = vec![false; meshes.len()];
    for (i, inst) in instances.iter().enumerate() {
        match used.get_mut(inst.mesh.0 as usize) {
            Some(u) => *u = true,
            None => {
                return Err(ExportError::UnknownMesh {
                    instance: i,
                    mesh: inst.mesh.0,
                    bound: meshes.len(),
                });
            }
        }
    }
    Ok((0..meshes.len() as u32)
        .filter(|&i| used[i as usize])
        .map(MeshId)
        .collect())
}

/// The transforms of the instances of `mesh`, in input order.
pub(crate) fn placements(
    instances: &[Instance],
    mesh: MeshId,
) -> impl Iterator<Item = Placement> + '_ {
    instances
        .iter()
        .filter(move |i| i.mesh == mesh)
        .map(|i| Placement::new(i.transform))
}

#[cfg(test)]
mod tests {
    use glam::vec3;

    use super::*;

    #[test]
    fn normals_follow_the_inverse_transpose() {
        // Non-uniform scale and a shear: a face normal must stay perpendicular to the
        // transformed face.
        let t = Affine3A::from_cols_array(&[
            2.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 3.0, 5.0, 0.0, 0.0,
        ]);
        let p = Placement::new(t);
        let (u, v) = (Vec3::X, Vec3::Y); // a face in the xy plane, normal +z
        let n = p.normal(Vec3::Z);
        assert!((n.length() - 1.0).abs() < 1e-6);
        assert!(n.dot(t.transform_vector3(u)).abs() < 1e-6);
        assert!(n.dot(t.transform_vector3(v)).abs() < 1e-6);
        assert!(n.z > 0.0);
        // Mirroring keeps normals outward and reverses winding.
        let m = Placement::new(Affine3A::from_scale(vec3(-1.0, 1.0, 1.0)));
        assert_eq!(m.normal(Vec3::X), Vec3::NEG_X);
        assert_eq!(m.triangle([0, 1, 2], 10), [10, 12, 11]);
        // Flattening: the flat side keeps its normal, the vanishing sides get +y.
        let f = Placement::new(Affine3A::from_scale(vec3(2.0, 2.0, 0.0)));
        assert_eq!(f.normal(Vec3::NEG_Z), Vec3::NEG_Z);
        assert_eq!(f.normal(Vec3::X), Vec3::Y);
        assert_eq!(f.triangle([0, 1, 2], 0), [0, 1, 2]);
    }
}
