//! Coverage checked point by point against direct `f64` geometry.

use glam::{Affine3A, DVec3, EulerRot, Quat, Vec3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::Grid;
use super::parity::{Bounds, Voxelizer};
use super::quant::{Placement, quantize, usable_linear};
use crate::geometry::Mesh;

/// The lattice points the integer path covers for box `t`.
fn quantised_points(grid: &Grid, t: &Affine3A) -> Vec<[i64; 3]> {
    let Placement::Box(q) = quantize(grid, t) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for k in 0..q.extent[2] {
        for j in 0..q.extent[1] {
            if let Some((a, b)) = q.row(j, k) {
                for i in a..=b {
                    out.push([
                        i64::from(q.corner[0] + i),
                        i64::from(q.corner[1] + j),
                        i64::from(q.corner[2] + k),
                    ]);
                }
            }
        }
    }
    out
}

/// The local coordinates of lattice point `idx` in box `t`, and the world distance
/// from it to each face plane pair.
fn local(grid: &Grid, t: &Affine3A, idx: [i64; 3]) -> (DVec3, DVec3) {
    let (m, shift) = usable_linear(t.matrix3, Vec3::from(t.translation)).unwrap();
    let inv = m.inverse();
    let u = inv * (grid.centre(idx) - shift);
    let rows = inv.transpose();
    let dist = DVec3::new(
        ((u.x.abs() - 0.5) / rows.x_axis.length()).abs(),
        ((u.y.abs() - 0.5) / rows.y_axis.length()).abs(),
        ((u.z.abs() - 0.5) / rows.z_axis.length()).abs(),
    );
    (u, dist)
}

fn random_box(rng: &mut ChaCha8Rng) -> Affine3A {
    let size = Vec3::new(
        rng.random_range(0.05..2.5),
        rng.random_range(0.05..2.5),
        rng.random_range(0.05..2.5),
    );
    let angles = [0; 3].map(|_| rng.random_range(-3.2f32..3.2));
    let rotation = Quat::from_euler(EulerRot::XYZ, angles[0], angles[1], angles[2]);
    let centre = Vec3::new(
        rng.random_range(-2.5..2.5),
        rng.random_range(-2.5..2.5),
        rng.random_range(-2.5..2.5),
    );
    Affine3A::from_scale_rotation_translation(size, rotation, centre)
}

#[test]
fn rotated_boxes_match_point_in_box_except_at_faces() {
    let grid = Grid::new(Vec3::splat(-2.0), Vec3::new(2.0, 2.0, 3.0), [40, 36, 44]).unwrap();
    let tolerance = 1e-4 * grid.cell().min_element();
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let (mut points, mut disagreements) = (0usize, 0usize);
    for _ in 0..200 {
        let t = random_box(&mut rng);
        let mut covered = quantised_points(&grid, &t);
        covered.sort_unstable();
        // Brute force over a generous box around the instance.
        let reach = Vec3::from(t.matrix3.x_axis).abs()
            + Vec3::from(t.matrix3.y_axis).abs()
            + Vec3::from(t.matrix3.z_axis).abs();
        let c = Vec3::from(t.translation).as_dvec3();
        let lo = grid.to_lattice(c - reach.as_dvec3()).floor();
        let hi = grid.to_lattice(c + reach.as_dvec3()).ceil();
        let mut brute = Vec::new();
        for k in lo.z as i64..=hi.z as i64 {
            for j in lo.y as i64..=hi.y as i64 {
                for i in lo.x as i64..=hi.x as i64 {
                    let (u, _) = local(&grid, &t, [i, j, k]);
                    if u.abs().max_element() <= 0.5 {
                        brute.push([i, j, k]);
                    }
                }
            }
        }
        brute.sort_unstable();
        points += brute.len();
        for p in &covered {
            assert!(
                p[0] >= lo.x as i64 && p[0] <= hi.x as i64,
                "inside the search box"
            );
        }
        let mismatch = covered
            .iter()
            .filter(|p| brute.binary_search(p).is_err())
            .chain(brute.iter().filter(|p| covered.binary_search(p).is_err()));
        for &p in mismatch {
            let (_, dist) = local(&grid, &t, p);
            assert!(
                dist.min_element() <= tolerance,
                "point {p:?} of {t:?} is {} cells from a face",
                dist.min_element() / grid.cell().min_element()
            );
            disagreements += 1;
        }
    }
    assert!(points > 100_000, "the boxes cover enough to test: {points}");
    assert!(
        disagreements * 10_000 < points,
        "{disagreements} of {points}"
    );
}

#[test]
fn parity_of_transformed_meshes_matches_point_in_box() {
    // The unit cube voxelized by parity as a mesh, under random transforms, against the
    // same f64 point-in-box test.
    let grid = Grid::new(Vec3::splat(-2.0), Vec3::splat(2.0), [30, 34, 38]).unwrap();
    let tolerance = 1e-6 * grid.cell().min_element();
    let cube = Mesh::unit_cube();
    let mut voxelizer = Voxelizer::default();
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut total = 0;
    for _ in 0..100 {
        let t = random_box(&mut rng);
        let (m, shift) = usable_linear(t.matrix3, Vec3::from(t.translation)).unwrap();
        let mut covered = Vec::new();
        voxelizer
            .run(
                &cube,
                |p| grid.to_lattice(m * p.as_dvec3() + shift),
                Bounds::Lattice,
                |j, k, a, b| {
                    covered.extend((a..=b).map(|i| [i, j, k]));
                },
            )
            .unwrap();
        for &p in &covered {
            let (u, dist) = local(&grid, &t, p);
            assert!(
                u.abs().max_element() <= 0.5 || dist.min_element() <= tolerance,
                "{p:?}"
            );
        }
        covered.sort_unstable();
        let before = covered.len();
        covered.dedup();
        assert_eq!(before, covered.len(), "each point once");
        let all = quantised_points(&grid, &t);
        for p in &all {
            let (_, dist) = local(&grid, &t, *p);
            assert!(
                covered.binary_search(p).is_ok()
                    || dist.min_element() <= 1e-4 * grid.cell().min_element()
            );
        }
        total += covered.len();
    }
    assert!(total > 10_000, "{total}");
}
