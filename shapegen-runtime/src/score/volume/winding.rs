//! Voxelization of open or messy meshes by their generalized winding number.
//!
//! The winding number of a closed, outward-oriented surface about a point is 1 inside
//! and 0 outside; for any triangle soup it is the sum of the triangles' signed solid
//! angles seen from the point over `4 pi` (Jacobson et al. 2013), which degrades
//! gracefully where the surface has holes, cracks, overlaps or stray faces. A lattice
//! point is inside when the winding number's magnitude is at least 1/2, so inverted
//! meshes fill as well. Points outside the mesh's bounding box see the surface within
//! less than a hemisphere and are never inside; the others are evaluated exactly, every
//! triangle for every point, in `f64`: `O(points x triangles)`, done once per target.

use glam::DVec3;
use rayon::prelude::*;

use super::grid::Grid;
use crate::geometry::Mesh;

/// The grid's lattice points inside `mesh` by winding number, as indices
/// `i + nx (j + ny k)` in ascending order.
pub(crate) fn inside_points(mesh: &Mesh, grid: &Grid) -> Vec<usize> {
    let points: Vec<DVec3> = mesh
        .positions
        .iter()
        .map(|p| grid.to_lattice(p.as_dvec3()))
        .collect();
    if points.is_empty() || points.iter().any(|p| !p.is_finite()) {
        return Vec::new();
    }
    let triangles: Vec<[DVec3; 3]> = mesh
        .triangles()
        .map(|t| t.map(|i| points[i as usize]))
        .collect();
    let (lo, hi) = points.iter().fold((points[0], points[0]), |(lo, hi), &p| {
        (lo.min(p), hi.max(p))
    });
    let res = grid.resolution().map(i64::from);
    let span = |axis: usize| {
        let first = (lo[axis].ceil() as i64).max(0);
        let last = (hi[axis].floor() as i64).min(res[axis] - 1);
        first..=last
    };
    let (xs, ys, zs) = (span(0), span(1), span(2));
    let rows: Vec<(i64, i64)> = zs.flat_map(|k| ys.clone().map(move |j| (j, k))).collect();
    rows.par_iter()
        .flat_map_iter(|&(j, k)| {
            let triangles = &triangles;
            xs.clone()
                .filter(move |&i| {
                    let p = DVec3::new(i as f64, j as f64, k as f64);
                    winding_number(triangles, p).abs() >= 0.5
                })
                .map(move |i| (i + res[0] * (j + res[1] * k)) as usize)
        })
        .collect()
}

/// The generalized winding number of `triangles` about `p`: the sum of their signed
/// solid angles (Van Oosterom and Strackee's formula) over `4 pi`.
pub(crate) fn winding_number(triangles: &[[DVec3; 3]], p: DVec3) -> f64 {
    let total: f64 = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| v - p);
            let (la, lb, lc) = (a.length(), b.length(), c.length());
            let det = a.dot(b.cross(c));
            let div = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
            2.0 * det.atan2(div)
        })
        .sum();
    total / (4.0 * std::f64::consts::PI)
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    fn cube_triangles(mesh: &Mesh) -> Vec<[DVec3; 3]> {
        mesh.triangles()
            .map(|t| t.map(|i| mesh.positions[i as usize].as_dvec3()))
            .collect()
    }

    #[test]
    fn a_closed_surface_winds_once_around_inside_points_and_never_around_outside_ones() {
        let cube = cube_triangles(&Mesh::unit_cube());
        for p in [DVec3::ZERO, DVec3::new(0.3, -0.2, 0.4)] {
            assert!((winding_number(&cube, p) - 1.0).abs() < 1e-12);
        }
        for p in [DVec3::new(0.7, 0.0, 0.0), DVec3::splat(3.0)] {
            assert!(winding_number(&cube, p).abs() < 1e-12);
        }
    }

    #[test]
    fn a_missing_face_leaves_the_middle_inside_and_an_inverted_mesh_fills_as_well() {
        let mut open = Mesh::unit_cube();
        open.indices.drain(..6); // the +x face
        let tris = cube_triangles(&open);
        // The missing face subtends 1/6 of the sphere from the centre.
        assert!((winding_number(&tris, DVec3::ZERO) - 5.0 / 6.0).abs() < 1e-12);
        let mut inverted = Mesh::unit_cube();
        for t in inverted.indices.chunks_exact_mut(3) {
            t.swap(1, 2);
        }
        let grid = Grid::new(Vec3::splat(-1.0), Vec3::splat(1.0), [4, 4, 4]).unwrap();
        assert_eq!(
            inside_points(&inverted, &grid),
            inside_points(&Mesh::unit_cube(), &grid)
        );
        assert_eq!(inside_points(&Mesh::unit_cube(), &grid).len(), 8);
    }
}
