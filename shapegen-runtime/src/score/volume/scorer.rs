//! The volume scorer: its grid, classes and form, and the fitness of counts.

use std::sync::Arc;

use super::classes::VoxelClasses;
use super::counts::VolumeCounts;
use super::grid::Grid;
use super::parts::PartKind;
use super::scratch::VolumeScratch;
use super::surface::SurfaceBand;
use super::target::{VolumeError, VolumeTarget};
use crate::geometry::{BoundMeshes, Instance, MeshId};
use crate::score::form::{Form, f_score, share, smoothstep};
use crate::score::scorer::Scorer;

/// Scores models by the voxels they cover on a grid against weighted target volumes.
/// See the [module documentation](super).
#[derive(Clone, Debug)]
pub struct VolumeScorer {
    pub(super) grid: Grid,
    pub(super) classes: VoxelClasses,
    /// Per grid word, a bit mask of the voxels of each class but the last:
    /// `class_bits[w * class_stride + c]`.
    pub(super) class_bits: Vec<u64>,
    /// Number of classes minus one.
    pub(super) class_stride: usize,
    pub(super) parts: Vec<PartKind>,
    pub(super) meshes: BoundMeshes,
    pub(super) form: Form,
    pub(super) outside_sum: f64,
    /// With [`Form::FScore`], what its counts need of the grid and the targets.
    pub(super) surface: Option<Arc<SurfaceBand>>,
}

impl VolumeScorer {
    /// A scorer of models made of `meshes` (a grammar's meshes, indexed by [`MeshId`])
    /// against `targets` on `grid`, giving fitness in `form`.
    ///
    /// Fails as [`VoxelClasses::new`] does: a malformed target mesh, a weight that is not
    /// finite, more than [`MAX_CLASSES`](super::MAX_CLASSES) distinct combined weights;
    /// and with [`Form::FScore`], on a threshold that is not a distance above 0 or that
    /// spans more than [`MAX_HALF_WIDTH`](super::MAX_HALF_WIDTH) voxels along x. A target
    /// mesh that is not closed is no error: parity does what it does with it.
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
                good * share(counts.inside, union)
            }
            Form::FScore { good, .. } => {
                let model = counts.surface.saturating_add(counts.out_of_grid_hits);
                let target = self.target_surface_voxels().unwrap_or(0);
                good * f_score(
                    share(counts.surface_near, model),
                    share(counts.target_surface_near, target),
                )
            }
        }
    }
}
