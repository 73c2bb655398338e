//! The original's out-of-grid term: per instance, the voxels of its *span* that lie
//! outside the grid.
//!
//! The span of an instance is the box of voxel indices from the smallest to the largest
//! [`Grid::voxel_of`] of its transformed vertices, per axis. The original visits every
//! voxel of it and counts those outside the grid, whether or not the instance covers
//! their centres; here that number is the span's size less its intersection with the
//! grid. Vertices are transformed in `f32` as the original's source writes it: per row
//! `((m_r0 x + m_r1 y) + m_r2 z) + t_r`, each operation rounded. The original's CUDA
//! compiler may fuse those multiply-adds; for the unit cube, whose vertices at ±0.5 make
//! every product exact, fused or not gives the same sums, so a box's span is exactly
//! the original's, while for other meshes the last bit of a vertex may differ. For the
//! unit cube the span is found from two corners per axis: rounding is monotonic, so the
//! smallest coordinate is that of the corner taking every term at its smallest.

use glam::{Affine3A, Vec3};

use super::grid::Grid;
use super::parts::PartKind;
use crate::geometry::FACET_CORNERS;

/// The voxels outside `grid` of the span of the instance of `part` placed by `t`.
pub(crate) fn span_out_of_grid(grid: &Grid, part: &PartKind, t: &Affine3A) -> u64 {
    let (lo, hi) = match part {
        PartKind::Box => box_span(grid, t),
        PartKind::Solid { .. } | PartKind::Facet => {
            let vertices = match part {
                PartKind::Solid { vertices, .. } => vertices.as_slice(),
                _ => &FACET_CORNERS,
            };
            match mesh_span(grid, t, vertices) {
                Some(span) => span,
                None => return 0,
            }
        }
    };
    outside(grid, lo, hi)
}

/// Row `r` of `t` applied to `p` as the original computes it, in `f32`.
#[inline]
fn transformed(t: &Affine3A, p: Vec3, r: usize) -> f32 {
    let m = &t.matrix3;
    m.x_axis[r] * p.x + m.y_axis[r] * p.y + m.z_axis[r] * p.z + t.translation[r]
}

/// The span of the unit cube placed by `t`, as the lowest and highest voxel indices.
fn box_span(grid: &Grid, t: &Affine3A) -> ([i32; 3], [i32; 3]) {
    let m = &t.matrix3;
    let mut lo = Vec3::ZERO;
    let mut hi = Vec3::ZERO;
    for r in 0..3 {
        // The corner terms of row r are ±a, ±b, ±c (products with ±0.5 are exact).
        let (a, b, c) = (
            (m.x_axis[r] * 0.5).abs(),
            (m.y_axis[r] * 0.5).abs(),
            (m.z_axis[r] * 0.5).abs(),
        );
        lo[r] = -a + -b + -c + t.translation[r];
        hi[r] = a + b + c + t.translation[r];
    }
    (grid.voxel_of(lo), grid.voxel_of(hi))
}

/// The span of `vertices` placed by `t`; `None` without vertices.
fn mesh_span(grid: &Grid, t: &Affine3A, vertices: &[Vec3]) -> Option<([i32; 3], [i32; 3])> {
    let mut voxels = vertices.iter().map(|&p| {
        grid.voxel_of(Vec3::new(
            transformed(t, p, 0),
            transformed(t, p, 1),
            transformed(t, p, 2),
        ))
    });
    let first = voxels.next()?;
    Some(voxels.fold((first, first), |(lo, hi), v| {
        (
            std::array::from_fn(|a| lo[a].min(v[a])),
            std::array::from_fn(|a| hi[a].max(v[a])),
        )
    }))
}

/// The voxels of `lo ..= hi` (per axis) outside `grid`, saturated.
fn outside(grid: &Grid, lo: [i32; 3], hi: [i32; 3]) -> u64 {
    let (mut span, mut inside) = (1u128, 1u128);
    for (a, n) in grid.resolution().into_iter().enumerate() {
        let (l, h) = (i64::from(lo[a]), i64::from(hi[a]));
        span *= (h - l + 1) as u128;
        inside *= (h.min(i64::from(n) - 1) - l.max(0) + 1).max(0) as u128;
    }
    u64::try_from(span - inside).unwrap_or(u64::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{EulerRot, Quat};
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn the_box_closed_form_is_the_span_of_its_eight_corners() {
        let grid = Grid::spaceship();
        let corners: Vec<Vec3> = (0..8)
            .map(|c: u32| Vec3::new((c & 1) as f32, (c >> 1 & 1) as f32, (c >> 2) as f32) - 0.5)
            .collect();
        let mut rng = ChaCha8Rng::seed_from_u64(17);
        for n in 0..20_000 {
            // Sizes and places on coarse steps so that corners land on voxel boundaries
            // (exact ties of the rounding) as well as anywhere.
            let coarse = n % 2 == 0;
            let pick = |rng: &mut ChaCha8Rng, lo: f32, hi: f32| {
                let x = rng.random_range(lo..hi);
                if coarse { (x * 20.0).round() / 20.0 } else { x }
            };
            let size = Vec3::new(
                pick(&mut rng, 0.05, 4.0),
                pick(&mut rng, 0.05, 4.0),
                pick(&mut rng, 0.05, 4.0),
            );
            let rotation = if n % 3 == 0 {
                Quat::IDENTITY
            } else {
                let a = [0; 3].map(|_| rng.random_range(-3.2f32..3.2));
                Quat::from_euler(EulerRot::XYZ, a[0], a[1], a[2])
            };
            let centre = Vec3::new(
                pick(&mut rng, -7.0, 7.0),
                pick(&mut rng, -7.0, 7.0),
                pick(&mut rng, -4.0, 20.0),
            );
            let t = Affine3A::from_scale_rotation_translation(size, rotation, centre);
            assert_eq!(
                Some(box_span(&grid, &t)),
                mesh_span(&grid, &t, &corners),
                "{t:?}"
            );
        }
    }

    #[test]
    fn outside_is_the_span_less_its_part_in_the_grid() {
        let grid = Grid::new(Vec3::ZERO, Vec3::splat(10.0), [10, 10, 10]).unwrap();
        assert_eq!(outside(&grid, [0, 0, 0], [9, 9, 9]), 0);
        // 12 x 2 x 1 voxels, 10 x 2 x 1 of them inside.
        assert_eq!(outside(&grid, [-1, 3, 4], [10, 4, 4]), 4);
        // Wholly outside.
        assert_eq!(outside(&grid, [20, 20, 20], [22, 21, 20]), 6);
        assert_eq!(outside(&grid, [3, -5, 3], [4, -1, 4]), 20);
        // Saturating at the i32 range.
        let far = outside(&grid, [i32::MIN; 3], [i32::MAX; 3]);
        assert_eq!(far, u64::MAX);
    }
}
