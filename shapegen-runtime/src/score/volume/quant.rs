//! The exact integer path for box instances, shared bit for bit by the CPU and the GPU.
//!
//! A box instance covers lattice point `(I, J, K)` when its centre lies in the box
//! `[-0.5, 0.5]^3` of the instance's local frame. On the CPU, in `f64`, the instance's
//! linear part is inverted and the local coordinate along each box axis `a` of lattice
//! point `(I0 + i, J0 + j, K0 + k)` is written as `u_a = alpha_a i + beta_a j +
//! gamma_a k + delta_a`, relative to the corner `(I0, J0, K0)` of the instance's lattice
//! bounding box. Each axis is scaled by its own power of two `2^s_a` and rounded to
//! `i32` coefficients `A_a, B_a, C_a, D_a` and half-width `H_a` (`0.5 * 2^s_a`); the
//! coefficient of an index that takes one value only (the bounding box is one lattice
//! point thick along its axis) is 0. From then on coverage is integer arithmetic only: a lattice point of the bounding box is
//! covered iff `-H_a <= A_a i + B_a j + C_a k + D_a <= H_a` for all three axes, and in
//! row `(j, k)` the covered `i` form one interval found by exact floor and ceiling
//! divisions ([`QuantBox::row`], mirrored by `row_interval` in [`shapegen_shaders::VOLUME`]).
//!
//! # Scale and precision
//! `s_a` is the largest integer with `M_a 2^s_a <= 2^29`, where
//! `M_a = |alpha_a| (ni-1) + |beta_a| (nj-1) + |gamma_a| (nk-1) + |delta_a| + 0.5`
//! bounds `|u_a| + 0.5` over the bounding box of `ni x nj x nk` points. Each rounded
//! value is within 1/2 of the scaled one, so with extents of at most 2^24 every partial
//! sum stays below `2^29 + 2^25 < 2^30`: half the `i32` range is spare. The quantised
//! `u_a` at `(i, j, k)` is off by at most `(i + j + k + 2) / 2^(s_a + 1)` box widths, so
//! quantisation moves a face by at most `(ni + nj + nk) / 2^(s_a + 1)` of the box's
//! width along that axis: about `2^-s_a` of its size per lattice point spanned. For a
//! box spanning 100 voxels with `M_a` around 2 that is about 6e-7 of its width, 6e-5 of
//! a voxel.
//!
//! # Degenerate and oversized instances
//! An instance whose linear part is not finite, or whose `|det|` is at most 1e-9 times
//! the product of its column lengths (flatter than a billionth of its size), covers
//! nothing. An instance whose lattice bounding box spans more than 2^24 points along an
//! axis, more than 2^26 rows, or reaches beyond index ±2^30 is not rasterised: it counts
//! its volume in voxels, rounded, as out-of-grid hits.

use glam::{DMat3, DVec3, Vec3};

use super::grid::Grid;

/// Most lattice points along one axis of an instance's bounding box.
pub(crate) const MAX_SPAN: i64 = 1 << 24;
/// Most rows `(j, k)` of an instance's bounding box.
pub(crate) const MAX_ROWS: i64 = 1 << 26;
/// Largest lattice index magnitude an instance may reach.
pub(crate) const MAX_INDEX: f64 = (1u64 << 30) as f64;
/// Target bound of the scaled terms of one axis.
const TERM_BUDGET: f64 = (1u64 << 29) as f64;

/// One box instance, quantised. Mirrors `struct QuantBox` in [`shapegen_shaders::VOLUME`]
/// (six `vec4<i32>`, 96 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct QuantBox {
    /// `I0, J0, K0`: the lattice bounding box's lowest corner; the fourth entry is free
    /// for the GPU batch (the model's index).
    pub corner: [i32; 4],
    /// `ni, nj, nk`: lattice points of the bounding box per axis (each >= 1); the fourth
    /// entry is free for the GPU batch (the instance's first row in the dispatch).
    pub extent: [i32; 4],
    /// For each local box axis `a`: `[A_a, B_a, C_a, D_a]`.
    pub axes: [[i32; 4]; 3],
    /// `[H_x, H_y, H_z, 0]`: the scaled half-widths.
    pub half: [i32; 4],
}

const _: () = assert!(size_of::<QuantBox>() == 96);

/// What a box instance covers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Placement {
    /// No lattice point.
    Nothing,
    /// Too large to rasterise: this many out-of-grid hits.
    Oversize(u64),
    /// The lattice points of the quantised box.
    Box(QuantBox),
}

/// `floor(n / d)` for `d > 0`.
#[inline]
fn floor_div(n: i32, d: i32) -> i32 {
    let q = n / d;
    if n % d != 0 && n < 0 { q - 1 } else { q }
}

/// `ceil(n / d)` for `d > 0`.
#[inline]
fn ceil_div(n: i32, d: i32) -> i32 {
    let q = n / d;
    if n % d != 0 && n > 0 { q + 1 } else { q }
}

impl QuantBox {
    /// The covered `i` of row `(j, k)` (relative to the corner, `0 <= j < nj`,
    /// `0 <= k < nk`) as an inclusive range within `0..ni`, or `None` when the row
    /// covers nothing.
    #[inline]
    pub fn row(&self, j: i32, k: i32) -> Option<(i32, i32)> {
        let mut lo = 0;
        let mut hi = self.extent[0] - 1;
        for (&[a, b, c, d], &h) in self.axes.iter().zip(&self.half) {
            let r = b * j + c * k + d;
            if a > 0 {
                lo = lo.max(ceil_div(-h - r, a));
                hi = hi.min(floor_div(h - r, a));
            } else if a < 0 {
                lo = lo.max(ceil_div(r - h, -a));
                hi = hi.min(floor_div(r + h, -a));
            } else if r < -h || r > h {
                return None;
            }
        }
        (lo <= hi).then_some((lo, hi))
    }
}

/// The lattice volume, in voxels, of something of world volume `volume`, rounded and
/// saturated.
pub(crate) fn voxels_of_volume(grid: &Grid, volume: f64) -> u64 {
    let cell = grid.cell();
    (volume / (cell.x * cell.y * cell.z)).round() as u64
}

/// The linear part of `m` in `f64`, with its translation, when it is usable: finite and
/// not flat. `None` when it covers nothing.
pub(crate) fn usable_linear(m: glam::Mat3A, t: Vec3) -> Option<(DMat3, DVec3)> {
    let m = DMat3::from_cols(
        Vec3::from(m.x_axis).as_dvec3(),
        Vec3::from(m.y_axis).as_dvec3(),
        Vec3::from(m.z_axis).as_dvec3(),
    );
    let t = t.as_dvec3();
    let det = m.determinant();
    let size = m.x_axis.length() * m.y_axis.length() * m.z_axis.length();
    let usable = det.is_finite() && t.is_finite() && det.abs() > 1e-9 * size;
    usable.then_some((m, t))
}

/// The lattice points whose positions lie in `lo ..= hi` (lattice coordinates), as the
/// first point and the count per axis; `Ok(None)` when it holds no lattice point.
/// `Err(())` when it is not finite, reaches beyond [`MAX_INDEX`] or, when `limited`,
/// exceeds [`MAX_SPAN`] or [`MAX_ROWS`].
#[allow(clippy::type_complexity, clippy::result_unit_err)]
pub(crate) fn lattice_box(
    lo: DVec3,
    hi: DVec3,
    limited: bool,
) -> Result<Option<([i64; 3], [i64; 3])>, ()> {
    let (first, last) = (lo.ceil(), hi.floor());
    if !(first.is_finite() && last.is_finite())
        || first.abs().max_element() > MAX_INDEX
        || last.abs().max_element() > MAX_INDEX
    {
        return Err(());
    }
    let first = [first.x as i64, first.y as i64, first.z as i64];
    let count = [
        last.x as i64 - first[0] + 1,
        last.y as i64 - first[1] + 1,
        last.z as i64 - first[2] + 1,
    ];
    if count.iter().any(|&n| n <= 0) {
        return Ok(None);
    }
    if limited && (count.iter().any(|&n| n > MAX_SPAN) || count[1] * count[2] > MAX_ROWS) {
        return Err(());
    }
    Ok(Some((first, count)))
}

/// Quantises the unit-cube instance `transform` against `grid`.
pub(crate) fn quantize(grid: &Grid, transform: &glam::Affine3A) -> Placement {
    let Some((m, t)) = usable_linear(transform.matrix3, transform.translation.into()) else {
        return Placement::Nothing;
    };
    let reach = 0.5 * (m.x_axis.abs() + m.y_axis.abs() + m.z_axis.abs());
    let (first, count) =
        match lattice_box(grid.to_lattice(t - reach), grid.to_lattice(t + reach), true) {
            Ok(Some(b)) => b,
            Ok(None) => return Placement::Nothing,
            Err(()) => {
                return Placement::Oversize(voxels_of_volume(grid, m.determinant().abs()));
            }
        };
    let inv = m.inverse();
    let cell = grid.cell();
    let step = [
        inv.x_axis * cell.x,
        inv.y_axis * cell.y,
        inv.z_axis * cell.z,
    ];
    let offset = inv * (grid.centre(first) - t);
    let span = count.map(|n| (n - 1) as f64);
    let mut q = QuantBox {
        corner: [first[0] as i32, first[1] as i32, first[2] as i32, 0],
        extent: [count[0] as i32, count[1] as i32, count[2] as i32, 0],
        ..QuantBox::default()
    };
    for a in 0..3 {
        // An index that takes only the value 0 (one lattice point along its axis) needs
        // no coefficient, and its term, unbounded by the budget, could overflow i32.
        let mut terms = [step[0][a], step[1][a], step[2][a], offset[a]];
        for (term, &s) in terms.iter_mut().zip(&span) {
            if s == 0.0 {
                *term = 0.0;
            }
        }
        let bound = terms[0].abs() * span[0]
            + terms[1].abs() * span[1]
            + terms[2].abs() * span[2]
            + terms[3].abs()
            + 0.5;
        let scale = power_of_two_scale(bound);
        q.axes[a] = terms.map(|x| (x * scale).round() as i32);
        q.half[a] = (0.5 * scale).round() as i32;
    }
    Placement::Box(q)
}

/// The largest power of two `p` with `bound * p <= 2^29`.
fn power_of_two_scale(bound: f64) -> f64 {
    let mut e = (TERM_BUDGET / bound).log2().floor() as i32;
    while bound * 2f64.powi(e) > TERM_BUDGET {
        e -= 1;
    }
    while bound * 2f64.powi(e + 1) <= TERM_BUDGET {
        e += 1;
    }
    2f64.powi(e)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Affine3A, Quat};

    #[test]
    fn integer_division_rounds_the_right_way() {
        for n in -20..=20 {
            for d in 1..=7 {
                let exact = f64::from(n) / f64::from(d);
                assert_eq!(floor_div(n, d), exact.floor() as i32, "{n}/{d}");
                assert_eq!(ceil_div(n, d), exact.ceil() as i32, "{n}/{d}");
            }
        }
    }

    #[test]
    fn scale_is_the_largest_power_of_two_within_budget() {
        for bound in [0.5, 1.0, 1.5, 3.0, 1e-3, 7e5] {
            let s = power_of_two_scale(bound);
            assert!(bound * s <= TERM_BUDGET && bound * s * 2.0 > TERM_BUDGET);
            assert_eq!(s.log2().fract(), 0.0);
        }
    }

    #[test]
    fn terms_stay_within_half_the_i32_range() {
        let grid = Grid::new(Vec3::splat(-4.0), Vec3::splat(4.0), [64, 64, 64]).unwrap();
        let t = Affine3A::from_scale_rotation_translation(
            Vec3::new(3.0, 0.02, 5.0),
            Quat::from_euler(glam::EulerRot::XYZ, 0.3, 1.1, -0.4),
            Vec3::new(0.5, -0.2, 0.1),
        );
        let Placement::Box(q) = quantize(&grid, &t) else {
            panic!("a box inside the grid");
        };
        for a in 0..3 {
            let [ca, cb, cc, cd] = q.axes[a].map(i64::from);
            let worst = ca.abs() * i64::from(q.extent[0] - 1)
                + cb.abs() * i64::from(q.extent[1] - 1)
                + cc.abs() * i64::from(q.extent[2] - 1)
                + cd.abs()
                + i64::from(q.half[a]);
            assert!(worst < 1 << 30, "axis {a}: {worst}");
            assert!(worst > 1 << 28, "axis {a} uses its budget: {worst}");
        }
    }

    #[test]
    fn rows_are_exactly_the_points_meeting_every_inequality() {
        let grid = Grid::new(Vec3::splat(-3.0), Vec3::splat(3.0), [23, 29, 31]).unwrap();
        let mut checked = 0;
        for n in 0..40 {
            let f = n as f32;
            let t = Affine3A::from_scale_rotation_translation(
                Vec3::new(
                    0.3 + (f * 0.37) % 3.0,
                    0.2 + (f * 0.71) % 2.0,
                    0.5 + (f * 0.13) % 4.0,
                ),
                Quat::from_euler(glam::EulerRot::ZXY, f * 0.7, f * 1.3, f * 0.4),
                Vec3::new((f * 0.29) % 2.0 - 1.0, (f * 0.53) % 2.0 - 1.0, 0.1),
            );
            let Placement::Box(q) = quantize(&grid, &t) else {
                panic!("box {n} covers lattice points");
            };
            for k in 0..q.extent[2] {
                for j in 0..q.extent[1] {
                    let inside = |i: i32| {
                        (0..3).all(|a| {
                            let [ca, cb, cc, cd] = q.axes[a].map(i64::from);
                            let u = ca * i64::from(i) + cb * i64::from(j) + cc * i64::from(k) + cd;
                            u.abs() <= i64::from(q.half[a])
                        })
                    };
                    let all: Vec<i32> = (0..q.extent[0]).filter(|&i| inside(i)).collect();
                    let expected = all.first().map(|&lo| (lo, *all.last().unwrap()));
                    assert_eq!(q.row(j, k), expected, "box {n} row {j} {k}");
                    checked += all.len();
                }
            }
        }
        assert!(checked > 10_000, "{checked}");
    }

    #[test]
    fn boxes_one_lattice_point_thick_have_no_coefficient_there() {
        // A wing box of the spaceship, 0.02 wide on a grid of 0.1 voxels: one lattice
        // point along x, whose coefficient (about 5 per point) scaled to the budget of
        // the other terms would not fit an i32.
        let grid = Grid::spaceship();
        let t = Affine3A::from_cols_array(&[
            -0.021694506,
            -1.896594e-9,
            0.0,
            2.9626166e-8,
            -0.33888385,
            0.0,
            0.0,
            0.0,
            0.4443658,
            -1.0441633,
            -9.1283674e-8,
            1.3668362,
        ]);
        let Placement::Box(q) = quantize(&grid, &t) else {
            panic!("the box holds lattice points");
        };
        assert_eq!(q.extent[0], 1);
        assert_eq!([q.axes[0][0], q.axes[1][0], q.axes[2][0]], [0, 0, 0]);
        // Every row covers the one point: its centre x = -1.05 lies in the box.
        for k in 0..q.extent[2] {
            for j in 0..q.extent[1] {
                assert_eq!(q.row(j, k), Some((0, 0)), "row {j} {k}");
            }
        }
        assert_eq!(q.corner[0], 39);
    }

    #[test]
    fn flat_far_and_huge_boxes() {
        let grid = Grid::new(Vec3::ZERO, Vec3::ONE, [10, 10, 10]).unwrap();
        let flat = Affine3A::from_scale(Vec3::new(1.0, 1.0, 0.0));
        assert_eq!(quantize(&grid, &flat), Placement::Nothing);
        let nan = Affine3A::from_translation(Vec3::NAN);
        assert_eq!(quantize(&grid, &nan), Placement::Nothing);
        // Between two lattice planes: no lattice point.
        let thin = Affine3A::from_scale_rotation_translation(
            Vec3::new(1.0, 1.0, 0.01),
            Quat::IDENTITY,
            Vec3::new(0.5, 0.5, 0.5),
        );
        assert_eq!(quantize(&grid, &thin), Placement::Nothing);
        // 10^5 rows of 10^5 points: counted from its volume, 10^12 / 10^-3 voxels.
        let huge = Affine3A::from_scale(Vec3::splat(1e4));
        assert_eq!(
            quantize(&grid, &huge),
            Placement::Oversize(1_000_000_000_000_000)
        );
        let immense = Affine3A::from_scale(Vec3::splat(1e12));
        assert_eq!(quantize(&grid, &immense), Placement::Oversize(u64::MAX));
    }
}
