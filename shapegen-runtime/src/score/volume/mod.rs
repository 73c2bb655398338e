//! The volume scorer: how well a model fills target volumes, counted on a voxel grid.
//!
//! Targets are voxelized once by ray parity ([`VoxelClasses`]); each voxel gets the
//! combined weight `sum_i (inside target i ? inside_i : outside_i)`, and the distinct
//! weights are the voxel *classes*. A model is the union of its instances: instances of
//! the unit cube (or any mesh whose geometry is exactly the unit cube) are rasterised
//! with exact integer arithmetic from a quantised form of the instance, which the GPU
//! evaluates identically; other meshes are voxelized by parity on their transformed
//! triangles. A model's [facets](crate::geometry::Mesh::facet), the triangles of the
//! surfaces its rules generate, are voxelized together by winding number: a lattice
//! point is covered by them once for each closed, outward-wound facet surface holding
//! it (corners snapped to 1/4096 of a voxel, so that a corner two facets share is one
//! point), and each facet's span is that of its triangle. A lattice point counts as
//! covered when its voxel centre is.
//!
//! [`VolumeCounts`] holds what a model covers: distinct covered voxels per class,
//! `inside` (target voxels: class weight above 0) and `outside` (the rest); repeated
//! coverage twice over, as `overlap_hits` (every hit of a voxel beyond its first) and
//! `overlap_voxels` (distinct voxels covered more than once); and what lies beyond the
//! grid twice over, as `out_of_grid_hits` (covered lattice points outside the grid, one
//! per instance and point) and `span_out_of_grid` (per instance, the voxels of its
//! *span* outside the grid, covered or not: see below). The fitness is, with
//! [`Form::Weighted`] (the paper's text), `sum_c count_c weight_c + out_of_grid_hits
//! sum_i outside_i - w_self overlap_hits` and, with [`Form::Smooth`] (the original's
//! code), `good S(0, T, inside) - bad S(0, 2T, outside + overlap_voxels +
//! span_out_of_grid)` where `T` is the number of target voxels; with [`Form::Iou`],
//! `good inside / (T + outside + out_of_grid_hits)`: the voxel IoU that runs report
//! ([`voxel_iou`](crate::score::metrics::voxel_iou)) for a model within the grid, and
//! below it by what the model covers beyond the grid, so that a search gains nothing by
//! growing out of it.
//!
//! # The F-score form
//! With [`Form::FScore`], the scorer also counts the model's surface voxels (those it
//! covers with a face neighbour it does not cover), `surface`, those within the
//! threshold of the target's surface voxels, `surface_near`, and the target's surface
//! voxels within the threshold of the model's, `target_surface_near`; the fitness is
//! `good` times the harmonic mean of the precision `surface_near / (surface +
//! out_of_grid_hits)` and the recall `target_surface_near / T_s`, `T_s` the target's
//! surface voxels ([`VolumeScorer::target_surface_voxels`]). These counts are made on
//! the CPU only ([`GpuVolumeScorer::new`] refuses the form); the other forms leave them
//! 0.
//!
//! # As the original counts
//! The original voxelizes each instance on its own over its span, the box of voxel
//! indices between the rounded positions of its transformed vertices (each rounded to
//! the voxel containing it, in `f32`: [`Grid`] documents the expression); every span
//! voxel outside the grid adds 1 to its out-of-grid count, and every span voxel inside
//! the grid whose centre the instance covers adds 1 to that voxel's count. Its
//! `overlap` is the number of voxels whose count exceeds 1, and its smooth fitness
//! penalises `bad + overlap + out-of-grid`: `outside`, `overlap_voxels` and
//! `span_out_of_grid` here. With `inside`, they equal the original's for every model
//! whose voxel centres it decides as we do (the volume tests check them against a
//! transcription of the original's kernels on random spaceships).
//!
//! Which centres an instance covers is decided differently, with the same result
//! except on ties of measure zero. The original casts a ray from each centre along +y
//! and counts crossings with the instance's transformed triangles (Möller–Trumbore in
//! `f32`, a crossing at the centre itself included, triangles whose projection onto
//! the x-z plane has less than `5e-8` of area ignored). For a box that makes the faces
//! met by the ray half-open: an axis-aligned box covers the centres with `y` in
//! `(y_min, y_max]`, `x` and `z` in the closed ranges, and a centre whose ray passes
//! exactly through the diagonal shared by a face's two triangles meets that face twice,
//! so is left out; where `f32` rounding puts a centre on a face is decided by that
//! rounding. Here a box covers a centre whose local coordinates lie in the closed
//! `[-0.5, 0.5]^3`, decided exactly on its quantised form (within about 1e-6 of a voxel
//! of the exact box, see `quant.rs`); other meshes by parity along +x with ties broken
//! by symbolic perturbation, so that shared edges and vertices count once.
//!
//! [`count_batch`](super::count_batch) counts a population on the CPU threads;
//! [`GpuVolumeScorer`] counts it on the GPU in one submission, with the same counts:
//! box instances are rasterised there, other meshes and facets on the CPU threads
//! (their covered runs are then counted on the GPU with the boxes).
//!
//! ```
//! use glam::{Affine3A, Quat, Vec3};
//! use shapegen_runtime::{CUBE, Instance, Mesh, MeshLibrary};
//! use shapegen_runtime::score::{Form, Scorer};
//! use shapegen_runtime::score::volume::{Fill, Grid, VolumeScorer, VolumeTarget};
//!
//! // A 2 x 2 x 2 block of target voxels in the middle of a 4^3 grid of voxels of 0.5.
//! let grid = Grid::new(Vec3::splat(-1.0), Vec3::splat(1.0), [4, 4, 4])?;
//! let target = VolumeTarget {
//!     name: "block".into(),
//!     mesh: Mesh::unit_cube(),
//!     inside: 1.0,
//!     outside: -1.0,
//!     fill: Fill::Parity,
//! };
//! let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
//! let form = Form::Smooth { good: 2.0, bad: 15.0 };
//! let scorer = VolumeScorer::new(grid, &[target], &meshes, form)?;
//! assert_eq!(scorer.target_voxels(), 8);
//!
//! // A box reaching one layer further up: the 8 target voxels and 4 others.
//! let taller = Instance {
//!     transform: Affine3A::from_scale_rotation_translation(
//!         Vec3::new(1.0, 1.0, 1.5),
//!         Quat::IDENTITY,
//!         Vec3::new(0.0, 0.0, 0.25),
//!     ),
//!     mesh: CUBE,
//! };
//! let mut scratch = scorer.scratch();
//! let counts = scorer.count(&[taller], &mut scratch);
//! let summary = (counts.inside, counts.outside, counts.overlap_voxels, counts.out_of_grid_hits);
//! assert_eq!(summary, (8, 4, 0, 0));
//! // Its top face lies on the grid's top, z = 1, which is rounded to voxel index 4 (the
//! // voxel that would hold it), beyond the grid: of its span of 3 x 3 x 4 voxels, 9 lie
//! // outside the grid although it covers none of their centres.
//! assert_eq!(counts.span_out_of_grid, 9);
//!
//! // Two of them: the 12 voxels are covered twice, once more each.
//! let twice = scorer.count(&[taller, taller], &mut scratch);
//! assert_eq!((twice.overlap_hits, twice.overlap_voxels), (12, 12));
//! // Three: 24 hits beyond the first, still 12 voxels.
//! let thrice = scorer.count(&[taller, taller, taller], &mut scratch);
//! assert_eq!((thrice.overlap_hits, thrice.overlap_voxels), (24, 12));
//!
//! // The target exactly: the optimum, `good`.
//! let exact = Instance { transform: Affine3A::IDENTITY, mesh: CUBE };
//! assert_eq!(scorer.fitness(&scorer.count(&[exact], &mut scratch)), 2.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod classes;
mod count;
#[cfg(feature = "gpu")]
mod gpu;
mod grid;
mod parity;
mod parts;
mod quant;
mod retained;
mod span;
mod surface;
mod winding;

pub use classes::{MAX_CLASSES, VoxelClasses};
pub use count::VolumeScratch;
#[cfg(feature = "gpu")]
pub use gpu::GpuVolumeScorer;
pub use grid::{Grid, GridError, MAX_VOXELS};
pub use retained::VolumeState;
pub use surface::{MAX_HALF_WIDTH, fscore_half_width};

use std::sync::Arc;

use super::form::{Form, smoothstep};
use super::metrics;
use super::scorer::Scorer;
use crate::geometry::{BoundMeshes, Instance, Mesh, MeshError, MeshId};
use parts::PartKind;
use surface::{SurfaceBand, SurfaceCounts};

/// A volume to fill (or avoid): a mesh in world space, voxelized by its [`Fill`] rule, and the
/// weights a model's voxel scores inside and outside it.
#[derive(Clone, Debug, PartialEq)]
pub struct VolumeTarget {
    /// Names the target in errors.
    pub name: String,
    /// The target's surface, in world space.
    pub mesh: Mesh,
    /// Weight of a voxel inside the mesh.
    pub inside: f64,
    /// Weight of a voxel outside the mesh (also of each out-of-grid hit).
    pub outside: f64,
    /// How the mesh's inside is found.
    pub fill: Fill,
}

/// How a [`VolumeTarget`]'s inside is found on the grid's lattice points; scene files
/// name it in lower case (`fill = "winding"`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Fill {
    /// A point is inside when the ray from it along +x crosses the mesh an odd number of
    /// times: exact for closed meshes, and the original implementation's rule.
    #[default]
    Parity,
    /// A point is inside when the mesh's generalized winding number about it has a
    /// magnitude of at least 1/2: for open or messy meshes (holes, cracks, overlapping
    /// or inverted parts), where parity streaks. Slower: every triangle is measured from
    /// every lattice point within the mesh's bounding box, once per target.
    Winding,
}

/// Why a [`VolumeScorer`] cannot be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum VolumeError {
    /// A weight is infinite or NaN.
    #[error("volume target `{target}`: {which} weight {value} is not finite (finite numbers only)")]
    Weight {
        /// The target's name.
        target: String,
        /// `inside` or `outside`.
        which: &'static str,
        /// The weight given.
        value: f64,
    },
    /// A target's mesh is malformed.
    #[error("volume target `{target}`")]
    Mesh {
        /// The target's name.
        target: String,
        /// What is wrong with it.
        #[source]
        source: MeshError,
    },
    /// The targets' weights combine into too many distinct voxel weights.
    #[error(
        "volume targets {targets} combine into {classes} distinct voxel weights; at most {} \
         are supported (give targets fewer distinct inside/outside weights, or fewer targets)",
        MAX_CLASSES
    )]
    TooManyClasses {
        /// The targets, named and quoted.
        targets: String,
        /// How many distinct weights there are.
        classes: usize,
    },
    /// The F-score form's threshold cannot be used.
    #[error("volume F-score: {reason}")]
    Threshold {
        /// What is wrong, and what would be valid.
        reason: String,
    },
    /// [Distance shaping](VoxelClasses::shaped) cannot be done.
    #[error("volume distance shaping: {reason}")]
    Shaping {
        /// What is wrong, and what would be valid.
        reason: String,
    },
}

/// What one model covers on the grid. Equal counts give equal fitness, whichever
/// backend counted them. The [module documentation](self) says which fitness form uses
/// which count.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct VolumeCounts {
    /// Distinct covered target voxels (class weight above 0).
    pub inside: u64,
    /// Distinct covered voxels that are not target voxels.
    pub outside: u64,
    /// Hits of in-grid voxels beyond each voxel's first: a voxel covered by three
    /// instances counts 2.
    pub overlap_hits: u64,
    /// Distinct in-grid voxels covered more than once: a voxel covered by three
    /// instances counts 1.
    pub overlap_voxels: u64,
    /// Covered lattice points outside the grid, one per instance and point.
    pub out_of_grid_hits: u64,
    /// Per instance, the voxels of its span (the box of voxel indices of its rounded
    /// vertices) outside the grid, whether it covers them or not; summed over
    /// instances.
    pub span_out_of_grid: u64,
    /// Distinct covered voxels of each class ([`VoxelClasses::weights`]); classes the
    /// scene lacks stay 0. Not serialized: `inside` and `outside` sum them up.
    #[serde(skip)]
    pub classes: [u64; MAX_CLASSES],
    /// With [`Form::FScore`], the model's surface voxels in the grid (0 in other forms).
    #[serde(skip)]
    pub surface: u64,
    /// With [`Form::FScore`], those within the threshold of the target's surface.
    #[serde(skip)]
    pub surface_near: u64,
    /// With [`Form::FScore`], the target's surface voxels within the threshold of the
    /// model's surface.
    #[serde(skip)]
    pub target_surface_near: u64,
}

impl VolumeCounts {
    /// `self` with the F-score counts `c`.
    fn with_surface(self, c: SurfaceCounts) -> VolumeCounts {
        VolumeCounts {
            surface: c.surface,
            surface_near: c.near,
            target_surface_near: c.target_near,
            ..self
        }
    }
}

/// Scores models by the voxels they cover on a grid against weighted target volumes.
/// See the [module documentation](self).
#[derive(Clone, Debug)]
pub struct VolumeScorer {
    grid: Grid,
    classes: VoxelClasses,
    /// Per grid word, a bit mask of the voxels of each class but the last:
    /// `class_bits[w * class_stride + c]`.
    class_bits: Vec<u64>,
    /// Number of classes minus one.
    class_stride: usize,
    parts: Vec<PartKind>,
    meshes: BoundMeshes,
    form: Form,
    outside_sum: f64,
    /// With [`Form::FScore`], what its counts need of the grid and the targets.
    surface: Option<Arc<SurfaceBand>>,
}

impl VolumeScorer {
    /// A scorer of models made of `meshes` (a grammar's meshes, indexed by [`MeshId`])
    /// against `targets` on `grid`, giving fitness in `form`.
    ///
    /// Fails as [`VoxelClasses::new`] does: a malformed target mesh, a weight that is
    /// not finite, more than [`MAX_CLASSES`] distinct combined weights; and with
    /// [`Form::FScore`], on a threshold that is not a distance above 0 or that spans
    /// more than [`MAX_HALF_WIDTH`] voxels along x. A target mesh that is not closed is
    /// no error: parity does what it does with it.
    pub fn new(
        grid: Grid,
        targets: &[VolumeTarget],
        meshes: &BoundMeshes,
        form: Form,
    ) -> Result<VolumeScorer, VolumeError> {
        let classes = VoxelClasses::new(&grid, targets)?;
        let surface = match form {
            Form::FScore { threshold, .. } => Some(Arc::new(
                SurfaceBand::new(&classes, threshold)
                    .map_err(|reason| VolumeError::Threshold { reason })?,
            )),
            _ => None,
        };
        let mut scorer = VolumeScorer {
            grid,
            classes,
            class_bits: Vec::new(),
            class_stride: 0,
            parts: meshes.iter().map(|(_, _, m)| PartKind::of(m)).collect(),
            meshes: meshes.clone(),
            form,
            outside_sum: targets.iter().map(|t| t.outside).sum(),
            surface,
        };
        scorer.build_class_bits();
        Ok(scorer)
    }

    /// The scorer with its classes [shaped by distance](VoxelClasses::shaped): an
    /// opt-in slope for targets a generator cannot reach, off-target voxels costing in
    /// proportion to their distance from the target up to `radius` voxels. Out-of-grid
    /// hits keep their full cost.
    pub fn shaped(mut self, radius: f64) -> Result<VolumeScorer, VolumeError> {
        self.classes = self.classes.shaped(radius)?;
        self.build_class_bits();
        Ok(self)
    }

    /// Fills `class_bits` and `class_stride` from the classes.
    fn build_class_bits(&mut self) {
        let class_stride = self.classes.weights().len() - 1;
        let words = self.classes.voxels().len().div_ceil(64);
        let mut class_bits = vec![0u64; words * class_stride];
        for (v, &c) in self.classes.voxels().iter().enumerate() {
            let c = usize::from(c);
            if c < class_stride {
                class_bits[v / 64 * class_stride + c] |= 1 << (v % 64);
            }
        }
        self.class_bits = class_bits;
        self.class_stride = class_stride;
    }

    /// The grid.
    #[inline]
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The voxel classes: every voxel's combined target weight.
    #[inline]
    pub fn classes(&self) -> &VoxelClasses {
        &self.classes
    }

    /// `T`, the number of target voxels (class weight above 0).
    #[inline]
    pub fn target_voxels(&self) -> u64 {
        self.classes.target_voxels()
    }

    /// The fitness form.
    #[inline]
    pub fn form(&self) -> Form {
        self.form
    }

    /// With [`Form::FScore`], the number of the target's surface voxels (target voxels
    /// with a face neighbour that is not one, or outside the grid); `None` in other
    /// forms.
    pub fn target_surface_voxels(&self) -> Option<u64> {
        self.surface.as_ref().map(|s| s.target_count())
    }

    /// The F-score counts of the model covering `covered` (a bitset over the grid whose
    /// words not in `touched` are zero), added to `counts`; `counts` unchanged in other
    /// forms.
    pub(crate) fn add_surface(
        &self,
        counts: VolumeCounts,
        covered: &[u64],
        touched: impl Iterator<Item = usize>,
        dilated: &mut Vec<Vec<u64>>,
    ) -> VolumeCounts {
        match &self.surface {
            Some(band) => counts.with_surface(band.count(covered, touched, dilated)),
            None => counts,
        }
    }

    /// The grammar's meshes.
    #[inline]
    pub fn meshes(&self) -> &BoundMeshes {
        &self.meshes
    }

    /// Counts the model made of `instances` as [`Scorer::count`] does, and writes the
    /// in-grid voxels it covers to `covered` as a bitset: voxel `v` (numbered as
    /// [`Grid::index`] numbers them) is bit `v % 64` of word `v / 64`.
    ///
    /// ```
    /// # use glam::Vec3;
    /// # use shapegen_runtime::{CUBE, Instance, Mesh, MeshLibrary};
    /// # use shapegen_runtime::score::{Form, Scorer};
    /// # use shapegen_runtime::score::volume::{Fill, Grid, VolumeScorer, VolumeTarget};
    /// let grid = Grid::new(Vec3::splat(-1.0), Vec3::splat(1.0), [4, 4, 4])?;
    /// let target = VolumeTarget { name: "t".into(), mesh: Mesh::unit_cube(), inside: 1.0, outside: -1.0, fill: Fill::Parity };
    /// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
    /// let scorer = VolumeScorer::new(grid, &[target], &meshes, Form::Weighted { overlap: 0.0 })?;
    /// let cube = [Instance { transform: glam::Affine3A::IDENTITY, mesh: CUBE }];
    /// let mut covered = Vec::new();
    /// let counts = scorer.coverage(&cube, &mut scorer.scratch(), &mut covered);
    /// let n: u32 = covered.iter().map(|w| w.count_ones()).sum();
    /// assert_eq!((counts.inside, n), (8, 8));
    /// assert!(covered[0] & 1 << grid.index([1, 1, 1]).unwrap() != 0);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn coverage(
        &self,
        instances: &[Instance],
        scratch: &mut VolumeScratch,
        covered: &mut Vec<u64>,
    ) -> VolumeCounts {
        self.count_model(instances, scratch, Some(covered))
    }

    /// Whether instances of mesh `id` take the exact integer path (the mesh is the
    /// unit cube); `None` for an id the grammar lacks, whose instances cover nothing.
    #[inline]
    pub fn is_box(&self, id: MeshId) -> Option<bool> {
        self.part(id).map(|p| *p == PartKind::Box)
    }

    /// How instances of mesh `id` are counted; `None` for an id the grammar lacks.
    #[inline]
    pub(crate) fn part(&self, id: MeshId) -> Option<&PartKind> {
        self.parts.get(id.0 as usize)
    }
}

impl Scorer for VolumeScorer {
    type Counts = VolumeCounts;
    type Scratch = VolumeScratch;

    fn scratch(&self) -> VolumeScratch {
        VolumeScratch::new(self.grid.voxel_count())
    }

    fn count(&self, instances: &[Instance], scratch: &mut VolumeScratch) -> VolumeCounts {
        self.count_model(instances, scratch, None)
    }

    fn fitness(&self, counts: &VolumeCounts) -> f64 {
        match self.form {
            Form::Weighted { overlap } => {
                let covered: f64 = self
                    .classes
                    .weights()
                    .iter()
                    .zip(&counts.classes)
                    .map(|(&w, &n)| w * n as f64)
                    .sum();
                covered + counts.out_of_grid_hits as f64 * self.outside_sum
                    - overlap * counts.overlap_hits as f64
            }
            Form::Smooth { good, bad } => {
                let t = self.target_voxels() as f64;
                let outside = match self.classes.shares() {
                    None => counts.outside as f64,
                    Some(shares) => (0..shares.len())
                        .filter(|&c| !self.classes.is_target(c))
                        .map(|c| shares[c] * counts.classes[c] as f64)
                        .sum(),
                };
                let off = outside
                    + counts
                        .overlap_voxels
                        .saturating_add(counts.span_out_of_grid) as f64;
                good * smoothstep(0.0, t, counts.inside as f64)
                    - bad * smoothstep(0.0, 2.0 * t, off)
            }
            Form::Iou { good } => {
                let union = self.target_voxels() + counts.outside + counts.out_of_grid_hits;
                good * metrics::share(counts.inside, union)
            }
            Form::FScore { good, .. } => {
                let model = counts.surface.saturating_add(counts.out_of_grid_hits);
                let target = self.target_surface_voxels().unwrap_or(0);
                good * metrics::f_score(
                    metrics::share(counts.surface_near, model),
                    metrics::share(counts.target_surface_near, target),
                )
            }
        }
    }
}

#[cfg(test)]
mod tests;
