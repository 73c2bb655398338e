//! Incremental silhouette counting: per-pixel instance counts of one model.

use super::counts::{SilhouetteCounts, TargetCounts};
use super::scorer::{SilhouetteScorer, SilhouetteScratch};
use super::target::ImageTarget;
use crate::geometry::Instance;
use crate::score::retained::{CellCounts, Hit, Overflow, PixelCounts, RetainedScorer};

/// What a [`SilhouetteScorer`] keeps of one model: per target, how many of the model's
/// instances cover each pixel, and the model's counts.
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

impl SilhouetteScorer {
    /// Adds the pixels of `instances` to, or removes them from, `state`'s part for
    /// target `t`.
    fn apply(
        &self,
        t: &ImageTarget,
        state: &mut TargetState,
        instances: &[Instance],
        hit: Hit,
        scratch: &mut SilhouetteScratch,
    ) -> Result<(), Overflow> {
        let vp = t.view_projection();
        let mut result = Ok(());
        for instance in instances {
            scratch.coverage.shape(t.width(), t.height());
            self.rasterize_instance(t, vp, instance, scratch);
            let TargetState { pixels, counts } = state;
            scratch.coverage.drain(|w, bits| {
                let first = pixels.apply(hit, w, bits).unwrap_or_else(|overflow| {
                    result = Err(overflow);
                    0
                });
                if first == 0 {
                    return;
                }
                let (on, levels) = t.count_word(w, first);
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
            });
            result?;
        }
        Ok(())
    }
}

impl RetainedScorer for SilhouetteScorer {
    type State = SilhouetteState;

    fn count_retained(
        &self,
        instances: &[Instance],
        scratch: &mut SilhouetteScratch,
    ) -> Result<SilhouetteState, Overflow> {
        let mut state = SilhouetteState {
            targets: self.targets().iter().map(TargetState::new).collect(),
        };
        for (t, part) in self.targets().iter().zip(&mut state.targets) {
            self.apply(t, part, instances, Hit::Add, scratch)?;
        }
        Ok(state)
    }

    fn update(
        &self,
        state: &mut SilhouetteState,
        removed: &[Instance],
        added: &[Instance],
        scratch: &mut SilhouetteScratch,
    ) -> Result<(), Overflow> {
        for (t, part) in self.targets().iter().zip(&mut state.targets) {
            self.apply(t, part, removed, Hit::Remove, scratch)?;
            self.apply(t, part, added, Hit::Add, scratch)?;
        }
        Ok(())
    }

    fn state_counts(&self, state: &SilhouetteState) -> SilhouetteCounts {
        let mut counts = SilhouetteCounts::zeroed(state.targets.len());
        for (out, part) in counts.targets_mut().iter_mut().zip(&state.targets) {
            *out = TargetCounts {
                off_target: part.counts.covered - part.counts.on_target,
                ..part.counts
            };
        }
        counts
    }

    fn visit_cells(&self, state: &SilhouetteState, visit: &mut dyn FnMut(&CellCounts)) {
        for part in &state.targets {
            visit(part.pixels.cells());
        }
    }
}
