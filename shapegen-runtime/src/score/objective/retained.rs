//! Projection objectives counted incrementally: per-pixel instance counts of one model.

use super::projection::ProjectionMatch;
use super::surface::Surface;
use crate::geometry::{BoundMeshes, Instance};
use crate::score::retained::{
    CellCounts, Footprinted, Grids, Hit, Overflow, PixelCounts, Recorder,
};
use crate::score::scorer::Scorer;
use crate::score::silhouette::raster::Coverage;

/// A [`ProjectionMatch`] measured on models made of a grammar's meshes: a [`Scorer`]
/// whose counts are the pixels a model's projection gets wrong and whose fitness is the
/// match, and a [`RetainedScorer`](crate::score::retained::RetainedScorer), so that a
/// bred child's projection is counted from its parent's (see
/// [`score::retained`](crate::score::retained)).
///
/// Whether a pixel is covered depends on each triangle alone, and each instance's
/// triangles on the instance alone, so the pixels a model covers are the union of those
/// its instances cover, each rasterized on its own. The kept state counts, per pixel,
/// the instances covering it; a pixel is covered while its count is above 0.
///
/// ```
/// use glam::{Affine3A, Vec2, Vec3};
/// use shapegen_runtime::score::objective::{ProjectionMatch, ProjectionScorer, Surface, View};
/// use shapegen_runtime::score::retained::{InstanceDiff, RetainedScorer};
/// use shapegen_runtime::score::Scorer;
/// use shapegen_runtime::{CUBE, Instance, MeshLibrary};
///
/// // The top view of [-2, 2]^2 in 8 x 8 pixels; the target is the middle 4 x 2, where
/// // two unit cubes side by side stand.
/// let mask: Vec<bool> = (0..64).map(|i| (2..6).contains(&(i % 8)) && (3..5).contains(&(i / 8))).collect();
/// let top = ProjectionMatch::new(View::Top, Vec2::splat(-2.0), Vec2::splat(2.0), 8, 8, &mask)?;
/// let meshes = MeshLibrary::new().bind_names("Boxes", &["cube"])?;
/// let scorer = ProjectionScorer::new(top.clone(), meshes.clone());
/// let at = |x: f32| Instance { transform: Affine3A::from_translation(Vec3::X * x), mesh: CUBE };
/// let mut scratch = scorer.scratch();
///
/// let parent = [at(-0.5), at(0.5)];
/// let child = [at(-0.5)];
/// let mut state = scorer.count_retained(&parent, &mut scratch).unwrap();
/// assert_eq!(scorer.fitness(&scorer.state_counts(&state)), 1.0);
/// let mut diff = InstanceDiff::default();
/// diff.between(&parent, &child);
/// scorer.update(&mut state, diff.removed(), diff.added(), &mut scratch).unwrap();
/// let counts = scorer.state_counts(&state);
/// assert_eq!(counts, scorer.count(&child, &mut scratch));
/// assert_eq!(counts.mismatched, 4); // the right half of the target, uncovered
/// assert_eq!(scorer.fitness(&counts), top.score(&Surface::from_instances(&child, &meshes)));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct ProjectionScorer {
    projection: ProjectionMatch,
    meshes: BoundMeshes,
}

/// What a [`ProjectionScorer`] counts of one model.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ProjectionCounts {
    /// Pixels whose coverage differs from the mask: covered outside it or uncovered
    /// inside it.
    pub mismatched: u64,
}

/// Working memory of a [`ProjectionScorer`]: the surface of a model or of one instance,
/// and its coverage.
#[derive(Clone, Debug, Default)]
pub struct ProjectionScratch {
    surface: Surface,
    coverage: Coverage,
    recorder: Recorder,
}

/// What a [`ProjectionScorer`] keeps of one model beside its instances' footprints
/// ([`WithFootprints`](crate::score::retained::WithFootprints)): how many of its
/// instances cover each pixel, and its counts.
#[derive(Clone, Debug)]
pub struct ProjectionState {
    pixels: PixelCounts,
    counts: ProjectionCounts,
}

impl ProjectionScorer {
    /// Measures `projection` on models whose mesh ids index `meshes`.
    pub fn new(projection: ProjectionMatch, meshes: BoundMeshes) -> ProjectionScorer {
        ProjectionScorer { projection, meshes }
    }

    /// The projection measured.
    pub fn projection(&self) -> &ProjectionMatch {
        &self.projection
    }
}

impl Footprinted for ProjectionScorer {
    type Cells = ProjectionState;

    /// Every pixel of the mask mismatched.
    fn empty(&self) -> ProjectionState {
        let p = &self.projection;
        ProjectionState {
            pixels: PixelCounts::new(p.width(), p.height()),
            counts: ProjectionCounts {
                mismatched: p.mask_pixels(),
            },
        }
    }

    fn kept_counts(&self, state: &ProjectionState) -> ProjectionCounts {
        state.counts
    }

    fn kept_cells(&self, state: &ProjectionState, visit: &mut dyn FnMut(&CellCounts)) {
        visit(state.pixels.cells());
    }

    fn grids(&self) -> usize {
        1
    }

    fn rasterize_words(
        &self,
        instance: &Instance,
        _: usize,
        scratch: &mut ProjectionScratch,
        words: &mut Vec<(u32, u64)>,
    ) {
        let p = &self.projection;
        scratch
            .surface
            .fill(std::slice::from_ref(instance), &self.meshes);
        scratch.coverage.shape(p.width(), p.height());
        p.rasterize(&scratch.surface, &mut scratch.coverage);
        scratch
            .coverage
            .drain(|w, bits| words.push((w as u32, bits)));
    }

    /// Its mesh's triangles.
    fn raster_cost(&self, instance: &Instance) -> usize {
        self.meshes
            .get(instance.mesh)
            .map_or(0, |m| m.triangle_count())
    }

    fn apply(
        &self,
        state: &mut ProjectionState,
        grids: Grids<'_>,
        hit: Hit,
    ) -> Result<(), Overflow> {
        let ProjectionState { pixels, counts } = state;
        for &(w, bits) in grids.grid(0) {
            let flipped = pixels.apply(hit, w as usize, bits)?;
            let (before, after) = match hit {
                Hit::Add => (0, flipped),
                Hit::Remove => (flipped, 0),
            };
            counts.mismatched =
                self.projection
                    .remismatched(counts.mismatched, w as usize, before, after);
        }
        Ok(())
    }

    fn recorder(scratch: &mut ProjectionScratch) -> &mut Recorder {
        &mut scratch.recorder
    }
}

impl Scorer for ProjectionScorer {
    type Counts = ProjectionCounts;
    type Scratch = ProjectionScratch;

    fn scratch(&self) -> ProjectionScratch {
        ProjectionScratch::default()
    }

    /// Rasterizes the whole model at once, as [`ProjectionMatch::score`] does.
    fn count(&self, instances: &[Instance], scratch: &mut ProjectionScratch) -> ProjectionCounts {
        scratch.surface.fill(instances, &self.meshes);
        ProjectionCounts {
            mismatched: self
                .projection
                .mismatched(&scratch.surface, &mut scratch.coverage),
        }
    }

    /// The objective's value: the fraction of pixels whose coverage equals the mask.
    fn fitness(&self, counts: &ProjectionCounts) -> f64 {
        self.projection.value(counts.mismatched)
    }
}
