//! The silhouette scorer: rasterize a model through each target's camera, count.

use glam::{Mat4, Vec2, Vec4};

use super::counts::{MAX_TARGETS, SilhouetteCounts, TargetCounts};
use super::mesh_fill::{MeshScratch, ProjectedMesh};
use super::meshes::{RasterMesh, prepare};
use super::raster::{
    Coverage, MAX_POLYGON, clip_triangle, convex_hull, in_front, in_reach, to_fixed, to_pixels,
};
use super::target::ImageTarget;
use crate::geometry::{BoundMeshes, Instance};
use crate::score::form::{Form, smoothstep};
use crate::score::metrics::silhouette_iou;
use crate::score::retained::Recorder;
use crate::score::scorer::Scorer;

/// Why a silhouette scorer cannot be built or asked.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SilhouetteError {
    /// No target was given.
    #[error("a silhouette scorer needs at least one target image")]
    NoTargets,
    /// More targets than [`MAX_TARGETS`].
    #[error("{count} target images given; a silhouette scorer takes at most {max}")]
    TooManyTargets {
        /// Targets given.
        count: usize,
        /// [`MAX_TARGETS`].
        max: usize,
    },
    /// The weighted form was given a self-overlap weight, which images do not have.
    #[error(
        "the weighted form's `overlap` is {0} for a silhouette scorer; images have no \
         self-overlap term, use 0"
    )]
    Overlap(f64),
    /// The F-score form, which is for volumes.
    #[error(
        "the fscore form is for volume goals; a silhouette scorer takes the smooth, \
         weighted or iou form"
    )]
    FScore,
    /// A target index is out of range.
    #[error("target {index} asked for; the scorer has {count} targets (0..{count})")]
    NoSuchTarget {
        /// The index asked for.
        index: usize,
        /// Number of targets.
        count: usize,
    },
    /// A caller's mask has the wrong size.
    #[error("a coverage mask of {len} pixels given for target `{name}`, which has {expected}")]
    MaskSize {
        /// The target's name.
        name: String,
        /// The mask's length.
        len: usize,
        /// Width times height of the target.
        expected: usize,
    },
}

/// Scores models by the silhouettes they cast through the cameras of target images
/// (the paper's image score).
///
/// A pixel is covered by a model when its centre lies inside the projection of any
/// triangle of any instance (top-left rule on edges, triangles clipped at the near plane
/// before the perspective divide, no depth test); each pixel counts once per model. The
/// [`Form::Weighted`] fitness is the sum over targets of the weights of the covered
/// pixels; [`Form::Smooth`] is the sum over targets of
/// `good * S(0, T, on_target) - bad * S(0, T, off_target)`, `T` the target's
/// [target pixels](ImageTarget::target_pixels) (for a [shaped](ImageTarget::shaped)
/// target, `off_target` is the sum of the covered off-target pixels' shares of the full
/// cost); [`Form::Iou`] is the sum over targets of `good` times the silhouette IoU
/// ([`silhouette_iou`](crate::score::metrics::silhouette_iou)), the measure runs
/// report.
///
/// ```
/// use glam::{Affine3A, Vec3};
/// use image::{DynamicImage, GrayImage, Luma};
/// use shapegen_runtime::score::silhouette::{Camera, ImageTarget, OrbitCamera, SilhouetteScorer, Weighting};
/// use shapegen_runtime::score::{Form, Scorer};
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// // A 20 x 20 target whose left half is black, seen head-on from +z.
/// let image = GrayImage::from_fn(20, 20, |x, _| Luma([if x < 10 { 0 } else { 255 }]));
/// let camera = Camera::Orbit(OrbitCamera {
///     phi: -std::f32::consts::FRAC_PI_2, theta: 0.0, radius: 5.0, lookat: Vec3::ZERO,
///     fov_degrees: 90.0, near: 0.1, far: 100.0,
/// });
/// let target = ImageTarget::new("half".into(), &DynamicImage::ImageLuma8(image), camera, Weighting::mask(1.0, -1.0))?;
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let scorer = SilhouetteScorer::new(vec![target], &meshes, Form::Weighted { overlap: 0.0 })?;
///
/// let model = [Instance { transform: Affine3A::IDENTITY, mesh: CUBE }];
/// let counts = scorer.count(&model, &mut scorer.scratch());
/// let t = counts.targets()[0];
/// assert_eq!(t.covered, t.on_target + t.off_target);
/// assert!(t.covered > 0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct SilhouetteScorer {
    targets: Vec<ImageTarget>,
    /// The meshes prepared for rasterization, indexed by mesh id.
    pub(super) meshes: Vec<RasterMesh>,
    form: Form,
}

/// Working memory of one worker of a [`SilhouetteScorer`].
#[derive(Clone, Debug, Default)]
pub struct SilhouetteScratch {
    pub(super) coverage: Coverage,
    /// One instance's mesh positions in clip space.
    clip: Vec<Vec4>,
    /// The same in pixels (or a convex mesh's projected hull points).
    points: Vec<Vec2>,
    /// The same in `1/256` pixel, when every one is within the exact range.
    fixed: Vec<[i32; 2]>,
    /// Working memory of [`Coverage::fill_mesh`].
    mesh: MeshScratch,
    /// One instance's coverage words, as incremental counting records them.
    pub(super) recorder: Recorder,
}

impl SilhouetteScorer {
    /// A scorer of `targets` (1 to [`MAX_TARGETS`]) for models made of `meshes` (a
    /// grammar's meshes, indexed by mesh id), with fitness `form`.
    pub fn new(
        targets: Vec<ImageTarget>,
        meshes: &BoundMeshes,
        form: Form,
    ) -> Result<SilhouetteScorer, SilhouetteError> {
        if targets.is_empty() {
            return Err(SilhouetteError::NoTargets);
        }
        if targets.len() > MAX_TARGETS {
            return Err(SilhouetteError::TooManyTargets {
                count: targets.len(),
                max: MAX_TARGETS,
            });
        }
        if let Form::Weighted { overlap } = form
            && overlap != 0.0
        {
            return Err(SilhouetteError::Overlap(overlap));
        }
        if let Form::FScore { .. } = form {
            return Err(SilhouetteError::FScore);
        }
        Ok(SilhouetteScorer {
            targets,
            meshes: prepare(meshes),
            form,
        })
    }

    /// The targets, in order.
    pub fn targets(&self) -> &[ImageTarget] {
        &self.targets
    }

    /// The fitness form.
    pub fn form(&self) -> Form {
        self.form
    }

    /// Writes which pixels of target `target` the model made of `instances` covers into
    /// `mask` (row by row from the top, `width * height` entries).
    ///
    /// ```
    /// # use glam::{Affine3A, Vec3};
    /// # use image::{DynamicImage, GrayImage, Luma};
    /// # use shapegen_runtime::score::silhouette::{Camera, ImageTarget, OrbitCamera, SilhouetteScorer, Weighting};
    /// # use shapegen_runtime::score::Form;
    /// # use shapegen_runtime::{CUBE, Instance, MeshLibrary};
    /// # let image = DynamicImage::ImageLuma8(GrayImage::from_pixel(8, 6, Luma([0])));
    /// # let camera = Camera::Orbit(OrbitCamera { phi: 0.0, theta: 0.0, radius: 5.0,
    /// #     lookat: Vec3::ZERO, fov_degrees: 60.0, near: 0.1, far: 100.0 });
    /// # let target = ImageTarget::new("t".into(), &image, camera, Weighting::mask(1.0, -1.0))?;
    /// # let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
    /// let scorer = SilhouetteScorer::new(vec![target], &meshes, Form::Smooth { good: 1.0, bad: 1.0 })?;
    /// let model = [Instance { transform: Affine3A::IDENTITY, mesh: CUBE }];
    /// let mut mask = vec![false; 8 * 6];
    /// scorer.coverage_mask(0, &model, &mut mask)?;
    /// assert!(mask[3 * 8 + 4]); // the centre
    /// assert!(scorer.coverage_mask(1, &model, &mut mask).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn coverage_mask(
        &self,
        target: usize,
        instances: &[Instance],
        mask: &mut [bool],
    ) -> Result<(), SilhouetteError> {
        let t = self
            .targets
            .get(target)
            .ok_or(SilhouetteError::NoSuchTarget {
                index: target,
                count: self.targets.len(),
            })?;
        let expected = t.width() as usize * t.height() as usize;
        if mask.len() != expected {
            return Err(SilhouetteError::MaskSize {
                name: t.name().to_owned(),
                len: mask.len(),
                expected,
            });
        }
        let mut scratch = self.scratch();
        scratch.coverage.shape(t.width(), t.height());
        self.rasterize(t, instances, &mut scratch);
        for y in 0..t.height() {
            for x in 0..t.width() {
                mask[(y * t.width() + x) as usize] = scratch.coverage.get(x, y);
            }
        }
        scratch.coverage.drain(|_, _| {});
        Ok(())
    }

    /// Rasterizes every instance into `scratch.coverage` (already shaped for `target`).
    fn rasterize(
        &self,
        target: &ImageTarget,
        instances: &[Instance],
        scratch: &mut SilhouetteScratch,
    ) {
        let vp = target.view_projection();
        for instance in instances {
            self.rasterize_instance(target, vp, instance, scratch);
        }
    }

    /// Rasterizes one instance into `scratch.coverage` (already shaped for `target`,
    /// whose view-projection matrix is `vp`). What an instance covers depends on the
    /// instance alone, never on what else the coverage holds.
    pub(super) fn rasterize_instance(
        &self,
        target: &ImageTarget,
        vp: Mat4,
        instance: &Instance,
        scratch: &mut SilhouetteScratch,
    ) {
        let (w, h) = (target.width() as f32, target.height() as f32);
        let Some(mesh) = self.meshes.get(instance.mesh.0 as usize) else {
            return;
        };
        let m = vp * Mat4::from(instance.transform);
        if let Some(hull) = &mesh.hull {
            scratch.points.clear();
            let mut front = true;
            for &p in hull {
                let c = m * p.extend(1.0);
                front &= in_front(c);
                scratch.points.push(to_pixels(c, w, h));
            }
            if front {
                let mut poly = [Vec2::ZERO; MAX_POLYGON + 1];
                let n = convex_hull(&mut scratch.points, &mut poly);
                scratch.coverage.fill_convex(&poly[..n]);
                return;
            }
        }
        // Each distinct position projected once. When every position is in front of the
        // near plane and within the exact range, every triangle is filled from its
        // corners' pixels in `1/256` pixel; otherwise each triangle wholly in front is
        // filled from its corners' pixels, and one crossing the near plane is clipped
        // first.
        scratch.clip.clear();
        scratch
            .clip
            .extend(mesh.positions.iter().map(|&p| m * p.extend(1.0)));
        scratch.points.clear();
        scratch
            .points
            .extend(scratch.clip.iter().map(|&c| to_pixels(c, w, h)));
        let near = scratch.clip.iter().all(|&c| in_front(c));
        if near && scratch.points.iter().all(|&p| in_reach(p)) {
            scratch.fixed.clear();
            scratch
                .fixed
                .extend(scratch.points.iter().map(|&p| to_fixed(p)));
            let projected = ProjectedMesh {
                mesh,
                points: &scratch.points,
                fixed: &scratch.fixed,
            };
            scratch.coverage.fill_mesh(&projected, &mut scratch.mesh);
            return;
        }
        for tri in &mesh.triangles {
            let c = tri.map(|i| scratch.clip[i as usize]);
            if c.iter().all(|&v| in_front(v)) {
                let corners = tri.map(|i| scratch.points[i as usize]);
                scratch.coverage.fill_triangle(corners);
            } else {
                let mut clipped = [Vec4::ZERO; 5];
                let n = clip_triangle(c, &mut clipped);
                let mut poly = [Vec2::ZERO; 5];
                for k in 0..n {
                    poly[k] = to_pixels(clipped[k], w, h);
                }
                scratch.coverage.fill_convex(&poly[..n]);
            }
        }
    }
}

impl Scorer for SilhouetteScorer {
    type Counts = SilhouetteCounts;
    type Scratch = SilhouetteScratch;

    fn scratch(&self) -> SilhouetteScratch {
        SilhouetteScratch::default()
    }

    fn count(&self, instances: &[Instance], scratch: &mut SilhouetteScratch) -> SilhouetteCounts {
        let mut counts = SilhouetteCounts::zeroed(self.targets.len());
        for (target, out) in self.targets.iter().zip(counts.targets_mut()) {
            scratch.coverage.shape(target.width(), target.height());
            self.rasterize(target, instances, scratch);
            let mut c = TargetCounts::default();
            scratch.coverage.drain(|w, bits| {
                let (on, levels) = target.count_word(w, bits);
                c.covered += bits.count_ones();
                c.on_target += on;
                c.level_sum += levels;
            });
            c.off_target = c.covered - c.on_target;
            *out = c;
        }
        counts
    }

    fn fitness(&self, counts: &SilhouetteCounts) -> f64 {
        fitness(self.form, &self.targets, counts)
    }
}

/// The fitness of `counts` against `targets` under `form` (see [`SilhouetteScorer`]).
pub(super) fn fitness(form: Form, targets: &[ImageTarget], counts: &SilhouetteCounts) -> f64 {
    targets
        .iter()
        .zip(counts.targets())
        .map(|(t, c)| match form {
            Form::Weighted { .. } => t.weighted_sum(u64::from(c.covered), c.level_sum),
            Form::Smooth { good, bad } => {
                let total = t.target_pixels() as f64;
                good * smoothstep(0.0, total, f64::from(c.on_target))
                    - bad * smoothstep(0.0, total, t.off_target_cost(c))
            }
            Form::Iou { good } => good * silhouette_iou(t, c),
            Form::FScore { .. } => unreachable!("SilhouetteScorer::new refuses the form"),
        })
        .sum()
}
