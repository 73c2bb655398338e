//! How each of a grammar's meshes is counted: boxes exactly in integers, facets
//! together by winding number, anything else by parity.

use glam::Vec3;

use crate::geometry::{Mesh, is_facet};

/// How instances of one mesh are counted.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum PartKind {
    /// The unit cube `[-0.5, 0.5]^3`: the exact integer path.
    Box,
    /// The unit [facet](crate::geometry::Mesh::facet), one triangle of a generated
    /// surface: a model's facets are voxelized together, by winding number.
    Facet,
    /// Any other mesh: parity voxelization of its transformed triangles. `volume` (the
    /// magnitude of its signed volume) sizes instances too large to rasterise.
    Solid {
        /// Volume in mesh units.
        volume: f64,
        /// The distinct positions its triangles use, which bound its span.
        vertices: Vec<Vec3>,
    },
}

impl PartKind {
    /// The kind of `mesh`.
    pub(crate) fn of(mesh: &Mesh) -> PartKind {
        if is_unit_cube(mesh) {
            PartKind::Box
        } else if is_facet(mesh) {
            PartKind::Facet
        } else {
            PartKind::Solid {
                volume: signed_volume(mesh).abs(),
                vertices: used_positions(mesh),
            }
        }
    }
}

/// The distinct positions of `mesh` that its triangles use, in first use.
fn used_positions(mesh: &Mesh) -> Vec<Vec3> {
    let mut seen = std::collections::HashSet::new();
    mesh.indices
        .iter()
        .map(|&i| mesh.positions[i as usize])
        .filter(|p| seen.insert(p.to_array().map(f32::to_bits)))
        .collect()
}

/// The signed volume enclosed by the triangles (divergence theorem), in `f64`.
fn signed_volume(mesh: &Mesh) -> f64 {
    mesh.triangles()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize].as_dvec3());
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

/// Whether `mesh`'s geometry is exactly the unit cube: every vertex is a corner of
/// `[-0.5, 0.5]^3`, every triangle with three distinct corners lies in a face, and each
/// face holds exactly two such triangles with different corners (two distinct
/// triangles on the four corners of a square always tile it). Triangles repeating a
/// corner have no area and are ignored.
pub(crate) fn is_unit_cube(mesh: &Mesh) -> bool {
    let corner = |i: u32| -> Option<u8> {
        let p = mesh.positions.get(i as usize)?;
        let mut bits = 0u8;
        for a in 0..3 {
            match p[a] {
                0.5 => bits |= 1 << a,
                -0.5 => {}
                _ => return None,
            }
        }
        Some(bits)
    };
    // Per face (axis * 2 + side): the corner sets of its triangles.
    let mut faces: [Vec<u8>; 6] = Default::default();
    for [a, b, c] in mesh.triangles() {
        let (Some(a), Some(b), Some(c)) = (corner(a), corner(b), corner(c)) else {
            return false;
        };
        if a == b || b == c || a == c {
            continue;
        }
        // The axes along which all three corners agree: the face they lie in.
        let same = !(a ^ b) & !(a ^ c) & 0b111;
        let Some(axis) = (0..3).find(|&x| same & (1 << x) != 0) else {
            return false; // cuts through the inside
        };
        let side = usize::from(a & (1 << axis) != 0);
        faces[axis * 2 + side].push(corner_set(a, b, c));
    }
    faces.iter().all(|f| f.len() == 2 && f[0] != f[1])
}

/// The three corners `a, b, c` (each 0..8) as a bit set.
fn corner_set(a: u8, b: u8, c: u8) -> u8 {
    (1 << a) | (1 << b) | (1 << c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn recognises_unit_cubes_only() {
        let cube = Mesh::unit_cube();
        assert_eq!(PartKind::of(&cube), PartKind::Box);
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../generators/meshes");
        let trunk = Mesh::from_obj(dir.join("trunk.obj")).unwrap();
        let PartKind::Solid { volume, vertices } = PartKind::of(&trunk) else {
            panic!("the trunk is a prism");
        };
        assert!(volume > 0.5 && volume < 1.0, "{volume}");
        let mut distinct = trunk.positions.clone();
        distinct.sort_by(|a, b| a.to_array().partial_cmp(&b.to_array()).unwrap());
        distinct.dedup();
        assert_eq!(vertices.len(), distinct.len(), "each used position once");
        let mut unused = trunk.clone();
        unused.positions.push(Vec3::splat(100.0));
        unused.normals.push(Vec3::X);
        assert_eq!(
            PartKind::of(&unused),
            PartKind::of(&trunk),
            "unused vertices are left out"
        );

        let mut doubled = cube.clone();
        doubled.indices.extend_from_slice(&cube.indices[..3]);
        assert!(!is_unit_cube(&doubled), "a face covered twice");
        let mut open = cube.clone();
        open.indices.truncate(33);
        assert!(!is_unit_cube(&open), "a face half covered");
        let mut bigger = cube.clone();
        bigger.positions.iter_mut().for_each(|p| *p *= 1.5);
        assert!(!is_unit_cube(&bigger));
        let mut degenerate = cube.clone();
        degenerate.indices.extend([0, 0, 1]);
        assert!(
            is_unit_cube(&degenerate),
            "zero-area triangles change nothing"
        );
        let mut diagonal = cube.clone();
        diagonal.positions.push(Vec3::splat(-0.5));
        diagonal.positions.push(Vec3::splat(0.5));
        diagonal.normals.extend([Vec3::X, Vec3::X]);
        diagonal.indices.extend([24, 25, 1]);
        assert!(!is_unit_cube(&diagonal), "a triangle through the inside");
        assert!((signed_volume(&cube) - 1.0).abs() < 1e-12);
    }
}
