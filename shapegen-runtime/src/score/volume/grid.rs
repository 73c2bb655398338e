//! The voxel grid and the lattice of voxel centres around it.

use glam::{DVec3, Vec3};

/// The most voxels a grid may hold: 2^28.
pub const MAX_VOXELS: u64 = 1 << 28;

/// An axis-aligned box split into `resolution` voxels along each axis.
///
/// Voxel `(i, j, k)` has its centre at `min + (idx + 0.5) * cell` with
/// `cell = (max - min) / resolution`, computed in `f64`. The lattice of centres
/// continues beyond the grid (indices below 0 or from `resolution` on), which is how
/// models poking out of the grid are counted. Voxels are numbered `i + nx * (j + ny * k)`
/// (x fastest).
///
/// The spans of instances ([`VolumeCounts::span_out_of_grid`](super::VolumeCounts))
/// take each vertex to the voxel holding it as the original does, in `f32`: per axis
/// `floor((s p + o) + 0.5)` with `size = (max - min) / resolution`, `s = 1 / size` and
/// `o = s (-min - size / 2)`, every operation rounded to `f32`. A position on the
/// boundary between two voxels belongs to the upper one: a box whose face lies on the
/// grid's upper bound reaches one voxel beyond it.
///
/// ```
/// use glam::Vec3;
/// use shapegen_runtime::score::volume::Grid;
///
/// let grid = Grid::new(Vec3::splat(-1.0), Vec3::splat(1.0), [4, 2, 2])?;
/// assert_eq!(grid.voxel_count(), 16);
/// assert_eq!(grid.cell().x, 0.5);
/// assert_eq!(grid.centre([0, 0, 0]).x, -0.75);
/// assert_eq!(grid.index([3, 1, 1]), Some(15));
/// assert_eq!(grid.index([4, 0, 0]), None);
///
/// let err = Grid::new(Vec3::ZERO, Vec3::new(1.0, 0.0, 1.0), [1, 1, 1]).unwrap_err();
/// assert_eq!(
///     err.to_string(),
///     "grid axis y: min 0 is not below max 0 (min < max on every axis)"
/// );
/// # Ok::<(), shapegen_runtime::score::volume::GridError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    min: Vec3,
    max: Vec3,
    resolution: [u32; 3],
    origin: DVec3,
    cell: DVec3,
    /// `1 / voxel size` in `f32`: the diagonal of the original's world-to-voxel matrix.
    voxel_scale: Vec3,
    /// `voxel_scale * (-min - voxel size / 2)` in `f32`: that matrix's translation.
    voxel_offset: Vec3,
}

/// Why a [`Grid`] cannot be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GridError {
    /// A bound is infinite or NaN.
    #[error("grid axis {axis}: bounds {min} .. {max} are not finite (finite numbers only)")]
    NonFinite {
        /// `x`, `y` or `z`.
        axis: char,
        /// The lower bound given.
        min: f32,
        /// The upper bound given.
        max: f32,
    },
    /// A lower bound is not below its upper bound.
    #[error("grid axis {axis}: min {min} is not below max {max} (min < max on every axis)")]
    Empty {
        /// `x`, `y` or `z`.
        axis: char,
        /// The lower bound given.
        min: f32,
        /// The upper bound given.
        max: f32,
    },
    /// A resolution of zero.
    #[error("grid axis {axis}: resolution 0 (at least 1 voxel per axis)")]
    ZeroResolution {
        /// `x`, `y` or `z`.
        axis: char,
    },
    /// The grid would hold too many voxels.
    #[error(
        "grid resolution {resolution:?} makes {voxels} voxels (at most 2^28 = {} in all)",
        MAX_VOXELS
    )]
    TooManyVoxels {
        /// The resolution given.
        resolution: [u32; 3],
        /// Its product.
        voxels: u64,
    },
}

const AXES: [char; 3] = ['x', 'y', 'z'];

impl Grid {
    /// The grid spanning `min .. max` with `resolution` voxels along x, y and z.
    ///
    /// Fails unless the bounds are finite with `min < max` on every axis, every
    /// resolution is at least 1 and there are at most [`MAX_VOXELS`] voxels in all.
    pub fn new(min: Vec3, max: Vec3, resolution: [u32; 3]) -> Result<Grid, GridError> {
        for a in 0..3 {
            let (lo, hi, axis) = (min[a], max[a], AXES[a]);
            if !lo.is_finite() || !hi.is_finite() {
                return Err(GridError::NonFinite {
                    axis,
                    min: lo,
                    max: hi,
                });
            }
            if lo >= hi {
                return Err(GridError::Empty {
                    axis,
                    min: lo,
                    max: hi,
                });
            }
            if resolution[a] == 0 {
                return Err(GridError::ZeroResolution { axis });
            }
        }
        let voxels = resolution.iter().map(|&r| u64::from(r)).product::<u64>();
        if voxels > MAX_VOXELS {
            return Err(GridError::TooManyVoxels { resolution, voxels });
        }
        let origin = min.as_dvec3();
        let res = DVec3::new(
            f64::from(resolution[0]),
            f64::from(resolution[1]),
            f64::from(resolution[2]),
        );
        // The original's `VoxelCoords::init`, in f32: the world-to-voxel matrix is
        // `scale(1 / size) * translation(-min - size / 2)`.
        let [rx, ry, rz] = resolution.map(|r| r as f32);
        let size = (max - min) / Vec3::new(rx, ry, rz);
        let translation = min * -1.0 - size / 2.0;
        let voxel_scale = Vec3::ONE / size;
        Ok(Grid {
            min,
            max,
            resolution,
            origin,
            cell: (max.as_dvec3() - origin) / res,
            voxel_scale,
            voxel_offset: voxel_scale * translation,
        })
    }

    /// The lower corner.
    #[inline]
    pub fn min(&self) -> Vec3 {
        self.min
    }

    /// The upper corner.
    #[inline]
    pub fn max(&self) -> Vec3 {
        self.max
    }

    /// Voxels along x, y and z.
    #[inline]
    pub fn resolution(&self) -> [u32; 3] {
        self.resolution
    }

    /// The size of one voxel, `(max - min) / resolution`.
    #[inline]
    pub fn cell(&self) -> DVec3 {
        self.cell
    }

    /// Number of voxels.
    #[inline]
    pub fn voxel_count(&self) -> u64 {
        self.resolution.iter().map(|&r| u64::from(r)).product()
    }

    /// The centre of lattice point `idx`, which may lie outside the grid.
    #[inline]
    pub fn centre(&self, idx: [i64; 3]) -> DVec3 {
        let i = DVec3::new(idx[0] as f64, idx[1] as f64, idx[2] as f64);
        self.origin + (i + 0.5) * self.cell
    }

    /// The position `p` in lattice coordinates: lattice point `idx` sits at `idx`.
    #[inline]
    pub fn to_lattice(&self, p: DVec3) -> DVec3 {
        (p - self.origin) / self.cell - 0.5
    }

    /// The index of the voxel containing world position `p`, computed as the original's
    /// `VoxelCoords::toVoxel` computes it, in `f32`: per axis `floor((s p + o) + 0.5)`
    /// with `s = 1 / size` and `o = s (-min - size / 2)`, `size = (max - min) /
    /// resolution`, each operation rounded to `f32` (the matrix's other terms are exact
    /// zeros and its `w` is 1). Not bounded by the grid; indices saturate at the `i32`
    /// range and a NaN gives 0, as CUDA's float-to-int conversion does. Exact for finite
    /// `p`.
    #[inline]
    pub(crate) fn voxel_of(&self, p: Vec3) -> [i32; 3] {
        let v = (self.voxel_scale * p + self.voxel_offset) + 0.5;
        [floor_i32(v.x), floor_i32(v.y), floor_i32(v.z)]
    }

    /// The voxel number of lattice point `idx`, or `None` outside the grid.
    #[inline]
    pub fn index(&self, idx: [i64; 3]) -> Option<usize> {
        let [nx, ny, nz] = self.resolution.map(i64::from);
        let [i, j, k] = idx;
        let inside = (0..nx).contains(&i) && (0..ny).contains(&j) && (0..nz).contains(&k);
        inside.then(|| (i + nx * (j + ny * k)) as usize)
    }

    /// The lattice point of voxel number `index` (`index < voxel_count()`).
    #[inline]
    pub fn voxel(&self, index: usize) -> [i64; 3] {
        let [nx, ny, _] = self.resolution.map(|r| r as usize);
        [
            (index % nx) as i64,
            (index / nx % ny) as i64,
            (index / (nx * ny)) as i64,
        ]
    }
}

/// `floor(x) as i32`, saturating and 0 for NaN, without the library call `floor` is on
/// targets lacking a rounding instruction.
#[inline]
fn floor_i32(x: f32) -> i32 {
    let t = x as i32; // towards zero, saturating
    if (t as f32) > x {
        t.saturating_sub(1)
    } else {
        t
    }
}

#[cfg(test)]
impl Grid {
    /// The spaceship scene's grid, for tests: 100 x 200 x 100 voxels from (-5, -5, -2)
    /// to (5, 5, 18), of 0.1 x 0.05 x 0.2.
    pub(crate) fn spaceship() -> Grid {
        Grid::new(
            Vec3::new(-5.0, -5.0, -2.0),
            Vec3::new(5.0, 5.0, 18.0),
            [100, 200, 100],
        )
        .unwrap()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(min: Vec3, max: Vec3, res: [u32; 3]) -> String {
        Grid::new(min, max, res).unwrap_err().to_string()
    }

    #[test]
    fn new_names_what_is_wrong() {
        let one = Vec3::ONE;
        assert_eq!(
            err(Vec3::new(0.0, 0.0, f32::NAN), one, [1, 1, 1]),
            "grid axis z: bounds NaN .. 1 are not finite (finite numbers only)"
        );
        assert_eq!(
            err(Vec3::ZERO, Vec3::new(f32::INFINITY, 1.0, 1.0), [1, 1, 1]),
            "grid axis x: bounds 0 .. inf are not finite (finite numbers only)"
        );
        assert_eq!(
            err(Vec3::new(2.0, 0.0, 0.0), one, [1, 1, 1]),
            "grid axis x: min 2 is not below max 1 (min < max on every axis)"
        );
        assert_eq!(
            err(Vec3::ZERO, one, [1, 0, 1]),
            "grid axis y: resolution 0 (at least 1 voxel per axis)"
        );
        assert_eq!(
            err(Vec3::ZERO, one, [1024, 1024, 257]),
            "grid resolution [1024, 1024, 257] makes 269484032 voxels (at most 2^28 = 268435456 in all)"
        );
        assert!(Grid::new(Vec3::ZERO, one, [1024, 1024, 256]).is_ok());
    }

    #[test]
    fn floor_is_the_library_floor_saturated() {
        let mut xs = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            2147483520.0,
            -2147483648.0,
            3e9,
            -3e9,
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
        ];
        let mut x = 1e-3f32;
        while x < 1e10 {
            xs.extend([x, -x, x.next_up(), -x.next_up(), x.round(), -x.round()]);
            x *= 1.37;
        }
        for x in xs {
            assert_eq!(floor_i32(x), x.floor() as i32, "{x}");
        }
    }

    #[test]
    fn positions_round_to_the_voxel_holding_them() {
        let grid = Grid::spaceship();
        assert_eq!(grid.voxel_of(Vec3::new(-5.0, -5.0, -2.0)), [0, 0, 0]);
        assert_eq!(grid.voxel_of(Vec3::new(-5.01, 4.99, 17.9)), [-1, 199, 99]);
        // The upper bound lies in the voxel beyond the grid.
        assert_eq!(grid.voxel_of(Vec3::new(5.0, 5.0, 18.0)), [100, 200, 100]);
        assert_eq!(
            grid.voxel_of(Vec3::new(f32::NAN, f32::INFINITY, -1e30)),
            [0, i32::MAX, i32::MIN]
        );
    }

    #[test]
    fn lattice_round_trips() {
        let grid = Grid::spaceship();
        assert_eq!(grid.cell(), DVec3::new(0.1, 0.05, 0.2));
        for idx in [[0, 0, 0], [99, 199, 99], [-3, 250, 7]] {
            let back = grid.to_lattice(grid.centre(idx));
            for a in 0..3 {
                assert!(
                    (back[a] - idx[a] as f64).abs() < 1e-9,
                    "{idx:?} -> {back:?}"
                );
            }
        }
        let n = grid.index([99, 199, 99]).unwrap();
        assert_eq!(n as u64, grid.voxel_count() - 1);
        assert_eq!(grid.voxel(n), [99, 199, 99]);
        assert_eq!(grid.voxel(grid.index([5, 6, 7]).unwrap()), [5, 6, 7]);
        assert_eq!(grid.index([0, -1, 0]), None);
    }
}
