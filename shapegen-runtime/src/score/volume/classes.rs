//! The targets combined into one grid of voxel classes.

use super::grid::Grid;
use super::parity::{Bounds, Voxelizer};
use super::target::{Fill, MAX_CLASSES, VolumeError, VolumeTarget};
use super::winding;
use crate::score::distance::squared_distances;

/// Every voxel's class: the distinct combined weights `sum_i (inside target i ?
/// inside_i : outside_i)` in ascending order, and one class index per voxel.
///
/// ```
/// use glam::Vec3;
/// use shapegen_runtime::Mesh;
/// use shapegen_runtime::score::volume::{Fill, Grid, VolumeTarget, VoxelClasses};
///
/// let grid = Grid::new(Vec3::splat(-1.0), Vec3::splat(1.0), [4, 4, 4])?;
/// let target = VolumeTarget { name: "cube".into(), mesh: Mesh::unit_cube(), inside: 1.0, outside: -0.5, fill: Fill::Parity };
/// let classes = VoxelClasses::new(&grid, &[target])?;
/// assert_eq!(classes.weights(), [-0.5, 1.0]);
/// assert_eq!(classes.target_voxels(), 8); // the middle 2 x 2 x 2
/// assert_eq!(classes.weight_at([1, 1, 1]), Some(1.0));
/// assert_eq!(classes.weight_at([0, 1, 1]), Some(-0.5));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct VoxelClasses {
    grid: Grid,
    weights: Vec<f64>,
    /// Per class, the share of the full cost a voxel of it carries (see
    /// [`shaped`](VoxelClasses::shaped)); `None` when not shaped: every share is 1.
    shares: Option<Vec<f64>>,
    voxels: Vec<u8>,
    sizes: Vec<u64>,
}

impl VoxelClasses {
    /// Voxelizes `targets` on `grid`, each by its [`Fill`] rule, and combines their
    /// weights.
    ///
    /// Fails when a target's mesh is malformed or a weight is not finite (naming the
    /// target), or when the combined weights take more than [`MAX_CLASSES`] values.
    pub fn new(grid: &Grid, targets: &[VolumeTarget]) -> Result<VoxelClasses, VolumeError> {
        let voxels = grid.voxel_count() as usize;
        let words = voxels.div_ceil(64);
        let mut inside = vec![0u64; words * targets.len()];
        let mut voxelizer = Voxelizer::default();
        let [nx, ny, _] = grid.resolution().map(i64::from);
        for (t, target) in targets.iter().enumerate() {
            for (which, value) in [("inside", target.inside), ("outside", target.outside)] {
                if !value.is_finite() {
                    return Err(VolumeError::Weight {
                        target: target.name.clone(),
                        which,
                        value,
                    });
                }
            }
            target
                .mesh
                .validate(&target.name)
                .map_err(|source| VolumeError::Mesh {
                    target: target.name.clone(),
                    source,
                })?;
            let bits = &mut inside[t * words..(t + 1) * words];
            let mut set = |v: usize| bits[v / 64] |= 1 << (v % 64);
            match target.fill {
                Fill::Parity => {
                    let place = |p: glam::Vec3| grid.to_lattice(p.as_dvec3());
                    let run = voxelizer.run(
                        &target.mesh,
                        place,
                        Bounds::Grid(grid.resolution()),
                        |j, k, a, b| {
                            let base = (j + ny * k) * nx;
                            ((base + a) as usize..=(base + b) as usize).for_each(&mut set);
                        },
                    );
                    debug_assert!(run.is_ok(), "grid bounds have no size limit");
                }
                Fill::Winding => winding::inside_points(&target.mesh, grid)
                    .into_iter()
                    .for_each(set),
            }
        }

        let weight_of = |v: usize| -> f64 {
            let mut w = 0.0;
            for (t, target) in targets.iter().enumerate() {
                let bit = inside[t * words + v / 64] >> (v % 64) & 1 != 0;
                w += if bit { target.inside } else { target.outside };
            }
            w + 0.0 // -0 is 0
        };
        let (weights, classes, sizes) = classify(voxels, weight_of, f64::total_cmp);
        if weights.len() > MAX_CLASSES {
            return Err(VolumeError::TooManyClasses {
                classes: weights.len(),
                targets: targets
                    .iter()
                    .map(|t| format!("`{}`", t.name))
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        }
        Ok(VoxelClasses {
            grid: *grid,
            weights,
            shares: None,
            voxels: classes,
            sizes,
        })
    }

    /// The classes shaped by distance: an opt-in slope for targets a generator cannot
    /// reach exactly. A voxel of negative weight `w` at distance `d` (in voxel steps,
    /// Euclidean, as if voxels were cubes) from the nearest target voxel carries the share
    /// `s = min(1, d / radius)` of its cost, rounded up to one of `B` bands
    /// (`s = ceil(B s) / B`), and weighs `w s`; target voxels and voxels of weight 0 are
    /// unchanged. `B` is as many bands as the class limit leaves: `(MAX_CLASSES - P) / N`
    /// for `P` classes of weight 0 or more and `N` of negative weight, at least 2. The
    /// smoothstep form counts each such voxel as its share instead of 1
    /// ([`shares`](Self::shares)).
    ///
    /// Fails when `radius` is not a positive number, when there are no target voxels to
    /// measure from, or when the class limit leaves fewer than 2 bands.
    ///
    /// ```
    /// use glam::Vec3;
    /// use shapegen_runtime::Mesh;
    /// use shapegen_runtime::score::volume::{Fill, Grid, VolumeTarget, VoxelClasses};
    ///
    /// let grid = Grid::new(Vec3::splat(-1.0), Vec3::splat(1.0), [8, 8, 8])?;
    /// let target = VolumeTarget { name: "cube".into(), mesh: Mesh::unit_cube(), inside: 1.0, outside: -1.0, fill: Fill::Parity };
    /// let shaped = VoxelClasses::new(&grid, &[target])?.shaped(2.0)?;
    /// // Up to 15 bands of -1/15 .. -1 outside, of which the distances 1, √2, √3 and 2
    /// // or more take 4, and the target's 1.
    /// assert_eq!(shaped.weights().len(), 5);
    /// assert_eq!(shaped.weight_at([2, 3, 3]), Some(1.0));
    /// // 1 voxel away: the share 1/2, rounded up to 8 of the 15 bands.
    /// assert_eq!(shaped.weight_at([1, 3, 3]), Some(-(8.0 / 15.0)));
    /// assert_eq!(shaped.weight_at([0, 3, 3]), Some(-1.0)); // 2 voxels away
    /// assert_eq!(shaped.target_voxels(), 64);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn shaped(&self, radius: f64) -> Result<VoxelClasses, VolumeError> {
        let refuse = |reason: String| Err(VolumeError::Shaping { reason });
        if !(radius.is_finite() && radius > 0.0) {
            return refuse(format!(
                "radius is {radius}; it must be a positive number of voxels"
            ));
        }
        if self.target_voxels() == 0 {
            return refuse(
                "no voxel is a target voxel, so there is nothing to measure from".into(),
            );
        }
        let negative = self.weights.iter().filter(|&&w| w < 0.0).count();
        let kept = self.weights.len() - negative;
        let bands = (MAX_CLASSES - kept) / negative.max(1);
        if bands < 2 {
            return refuse(format!(
                "needs at least 2 bands of distance per negative weight, and the targets' \
                 {} distinct weights leave {bands} of the {MAX_CLASSES} classes; give the \
                 targets fewer distinct weights",
                self.weights.len()
            ));
        }
        let [nx, ny, nz] = self.grid.resolution().map(|n| n as usize);
        let distances = squared_distances(&[nz, ny, nx], |v| {
            self.weights[usize::from(self.voxels[v])] > 0.0
        });
        // Classes as (weight, share), ascending; equal weights of different shares stay
        // apart.
        let class_of = |v: usize| -> (f64, f64) {
            let w = self.weights[usize::from(self.voxels[v])];
            if w >= 0.0 {
                return (w, 1.0);
            }
            let share = (distances[v].sqrt() / radius).min(1.0);
            let band = ((share * bands as f64).ceil() as usize).clamp(1, bands);
            let share = band as f64 / bands as f64;
            (w * share, share)
        };
        let order = |a: &(f64, f64), b: &(f64, f64)| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1));
        let (classes, voxels, sizes) = classify(self.voxels.len(), class_of, order);
        Ok(VoxelClasses {
            grid: self.grid,
            weights: classes.iter().map(|c| c.0).collect(),
            shares: Some(classes.iter().map(|c| c.1).collect()),
            voxels,
            sizes,
        })
    }

    /// Per class, the share of its full cost that a voxel of it carries in the smoothstep
    /// form: 1 for every class unless [shaped](Self::shaped).
    pub fn shares(&self) -> Option<&[f64]> {
        self.shares.as_deref()
    }

    /// The grid.
    #[inline]
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The weight of each class, ascending (at least one class, at most
    /// [`MAX_CLASSES`]).
    #[inline]
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Every voxel's class index, by voxel number ([`Grid::index`]).
    #[inline]
    pub fn voxels(&self) -> &[u8] {
        &self.voxels
    }

    /// Number of voxels of each class.
    #[inline]
    pub fn sizes(&self) -> &[u64] {
        &self.sizes
    }

    /// Whether class `class` is a target class: its weight is above 0.
    #[inline]
    pub fn is_target(&self, class: usize) -> bool {
        self.weights.get(class).is_some_and(|&w| w > 0.0)
    }

    /// The class of lattice point `idx`, `None` outside the grid.
    #[inline]
    pub fn class_at(&self, idx: [i64; 3]) -> Option<u8> {
        self.grid.index(idx).map(|v| self.voxels[v])
    }

    /// The combined weight at lattice point `idx`, `None` outside the grid.
    #[inline]
    pub fn weight_at(&self, idx: [i64; 3]) -> Option<f64> {
        self.class_at(idx).map(|c| self.weights[usize::from(c)])
    }

    /// Number of target voxels: those whose weight is above 0.
    pub fn target_voxels(&self) -> u64 {
        (0..self.weights.len())
            .filter(|&c| self.is_target(c))
            .map(|c| self.sizes[c])
            .sum()
    }
}

/// The distinct keys of `count` voxels (`key_of(v)`), ascending by `order`, each voxel's
/// index among them, and the number of voxels of each.
fn classify<K: Copy>(
    count: usize,
    key_of: impl Fn(usize) -> K,
    order: impl Fn(&K, &K) -> std::cmp::Ordering,
) -> (Vec<K>, Vec<u8>, Vec<u64>) {
    let mut keys: Vec<K> = Vec::new();
    for v in 0..count {
        let k = key_of(v);
        if let Err(at) = keys.binary_search_by(|x| order(x, &k)) {
            keys.insert(at, k);
        }
    }
    let mut sizes = vec![0u64; keys.len()];
    let classes = (0..count)
        .map(|v| {
            let k = key_of(v);
            let c = keys.partition_point(|x| order(x, &k).is_lt());
            sizes[c] += 1;
            c as u8
        })
        .collect();
    (keys, classes, sizes)
}
