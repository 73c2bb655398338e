//! Incremental silhouette counting: per-pixel instance counts of one model, and what
//! each of its instances covers.

use super::counts::{MAX_TARGETS, SilhouetteCounts, TargetCounts};
use super::scorer::{SilhouetteScorer, SilhouetteScratch};
use super::target::ImageTarget;
use crate::geometry::Instance;
use crate::score::retained::{
    CellCounts, Footprinted, Grids, Hit, MAX_GRIDS, Overflow, PixelCounts, Recorder,
};

const _: () = assert!(MAX_TARGETS <= MAX_GRIDS, "a footprint holds every target");

/// What a [`SilhouetteScorer`] keeps of one model beside its instances' footprints
/// ([`WithFootprints`](crate::score::retained::WithFootprints)): per target, how many of
/// the model's instances cover each pixel, and the model's counts.
///
/// A pixel's count is the number of instances whose own silhouette covers it (each
/// instance counts a pixel once, however many of its triangles cover it), so a pixel is
/// covered by the model exactly when its count is above 0. Tiles are 8 rows of one
/// 64-pixel word of the target's coverage rows.
#[derive(Clone, Debug)]
pub struct SilhouetteState {
    targets: Vec<TargetState>,
}

/// One target's part of a [`SilhouetteState`].
#[derive(Clone, Debug)]
struct TargetState {
    pixels: PixelCounts,
    counts: TargetCounts,
}

impl TargetState {
    fn new(target: &ImageTarget) -> TargetState {
        TargetState {
            pixels: PixelCounts::new(target.width(), target.height()),
            counts: TargetCounts::default(),
        }
    }
}

impl Footprinted for SilhouetteScorer {
    type Cells = SilhouetteState;

    fn empty(&self) -> SilhouetteState {
        SilhouetteState {
            targets: self.targets().iter().map(TargetState::new).collect(),
        }
    }

    fn kept_counts(&self, state: &SilhouetteState) -> SilhouetteCounts {
        let mut counts = SilhouetteCounts::zeroed(state.targets.len());
        for (out, part) in counts.targets_mut().iter_mut().zip(&state.targets) {
            *out = TargetCounts {
                off_target: part.counts.covered - part.counts.on_target,
                ..part.counts
            };
        }
        counts
    }

    fn kept_cells(&self, state: &SilhouetteState, visit: &mut dyn FnMut(&CellCounts)) {
        for part in &state.targets {
            visit(part.pixels.cells());
        }
    }

    fn grids(&self) -> usize {
        self.targets().len()
    }

    fn rasterize_words(
        &self,
        instance: &Instance,
        k: usize,
        scratch: &mut SilhouetteScratch,
        words: &mut Vec<(u32, u64)>,
    ) {
        let t = &self.targets()[k];
        scratch.coverage.shape(t.width(), t.height());
        self.rasterize_instance(t, t.view_projection(), instance, scratch);
        scratch
            .coverage
            .drain(|w, bits| words.push((w as u32, bits)));
    }

    /// Its mesh's hull points, or triangles.
    fn raster_cost(&self, instance: &Instance) -> usize {
        self.meshes
            .get(instance.mesh.0 as usize)
            .map_or(0, |m| m.hull.as_ref().map_or(m.triangles.len(), Vec::len))
    }

    fn apply(
        &self,
        state: &mut SilhouetteState,
        grids: Grids<'_>,
        hit: Hit,
    ) -> Result<(), Overflow> {
        for (k, (t, part)) in self.targets().iter().zip(&mut state.targets).enumerate() {
            let TargetState { pixels, counts } = part;
            for &(w, bits) in grids.grid(k) {
                let first = pixels.apply(hit, w as usize, bits)?;
                if first == 0 {
                    continue;
                }
                let (on, levels) = t.count_word(w as usize, first);
                let n = first.count_ones();
                match hit {
                    Hit::Add => {
                        counts.covered += n;
                        counts.on_target += on;
                        counts.level_sum += levels;
                    }
                    Hit::Remove => {
                        counts.covered -= n;
                        counts.on_target -= on;
                        counts.level_sum -= levels;
                    }
                }
            }
        }
        Ok(())
    }

    fn recorder(scratch: &mut SilhouetteScratch) -> &mut Recorder {
        &mut scratch.recorder
    }
}
