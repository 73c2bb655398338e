//! Incremental silhouette counting: per-pixel instance counts of one model, and what
//! each of its instances covers.

use std::sync::Arc;

use super::counts::{SilhouetteCounts, TargetCounts};
use super::scorer::{SilhouetteScorer, SilhouetteScratch};
use super::target::ImageTarget;
use crate::geometry::Instance;
use crate::score::retained::{
    CellCounts, Hit, InstanceKey, Overflow, PixelCounts, RetainedScorer, instance_key,
};

/// What a [`SilhouetteScorer`] keeps of one model: per target, how many of the model's
/// instances cover each pixel, and the model's counts; and per instance, the pixels it
/// covers, so that taking it away again replays them instead of rasterizing it.
///
/// A pixel's count is the number of instances whose own silhouette covers it (each
/// instance counts a pixel once, however many of its triangles cover it), so a pixel is
/// covered by the model exactly when its count is above 0. Tiles are 8 rows of one
/// 64-pixel word of the target's coverage rows. The footprints are shared between the
/// states of related models: a child's state holds its parent's, less those of the
/// instances it lost, plus those of the instances it gained.
#[derive(Clone, Debug)]
pub struct SilhouetteState {
    targets: Vec<TargetState>,
    /// The footprint of every instance of the model, sorted by instance key (an
    /// instance held twice has two entries).
    footprints: Vec<Arc<Footprint>>,
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

/// The pixels one instance covers in every target: the non-zero coverage words it
/// rasterizes to, as (word index, bits).
#[derive(Debug)]
struct Footprint {
    key: InstanceKey,
    /// Every target's words, target after target.
    words: Box<[(u32, u64)]>,
    /// Where each target's words end in `words`.
    ends: Box<[u32]>,
}

impl Footprint {
    /// The words of target `t`.
    fn target(&self, t: usize) -> &[(u32, u64)] {
        let start = t.checked_sub(1).map_or(0, |p| self.ends[p] as usize);
        &self.words[start..self.ends[t] as usize]
    }
}

impl SilhouetteScorer {
    /// Rasterizes `instance` into every target and returns what it covers.
    fn footprint(&self, instance: &Instance, scratch: &mut SilhouetteScratch) -> Footprint {
        let mut words = Vec::new();
        let mut ends = Vec::with_capacity(self.targets().len());
        for t in self.targets() {
            scratch.coverage.shape(t.width(), t.height());
            self.rasterize_instance(t, t.view_projection(), instance, scratch);
            scratch
                .coverage
                .drain(|w, bits| words.push((w as u32, bits)));
            ends.push(words.len() as u32);
        }
        Footprint {
            key: instance_key(instance),
            words: words.into(),
            ends: ends.into(),
        }
    }

    /// Adds the pixels of `footprint` to `state`, or takes them away.
    fn apply(
        &self,
        state: &mut SilhouetteState,
        footprint: &Footprint,
        hit: Hit,
    ) -> Result<(), Overflow> {
        for (k, (t, part)) in self.targets().iter().zip(&mut state.targets).enumerate() {
            let TargetState { pixels, counts } = part;
            for &(w, bits) in footprint.target(k) {
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

    /// Adds `instance` to `state`: rasterizes it, adds its pixels and keeps its
    /// footprint.
    fn add(
        &self,
        state: &mut SilhouetteState,
        instance: &Instance,
        scratch: &mut SilhouetteScratch,
    ) -> Result<(), Overflow> {
        let footprint = self.footprint(instance, scratch);
        self.apply(state, &footprint, Hit::Add)?;
        let at = state.footprints.partition_point(|f| f.key <= footprint.key);
        state.footprints.insert(at, Arc::new(footprint));
        Ok(())
    }

    /// Takes `instance` out of `state` by replaying its kept footprint.
    ///
    /// # Panics
    /// If the model lacks `instance`.
    fn remove(&self, state: &mut SilhouetteState, instance: &Instance) -> Result<(), Overflow> {
        let key = instance_key(instance);
        let at = state
            .footprints
            .binary_search_by(|f| f.key.cmp(&key))
            .expect("an instance taken away is one of the model's");
        let footprint = state.footprints.remove(at);
        self.apply(state, &footprint, Hit::Remove)
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
            footprints: Vec::with_capacity(instances.len()),
        };
        for instance in instances {
            let footprint = self.footprint(instance, scratch);
            self.apply(&mut state, &footprint, Hit::Add)?;
            state.footprints.push(Arc::new(footprint));
        }
        state.footprints.sort_by(|a, b| a.key.cmp(&b.key));
        Ok(state)
    }

    fn update(
        &self,
        state: &mut SilhouetteState,
        removed: &[Instance],
        added: &[Instance],
        scratch: &mut SilhouetteScratch,
    ) -> Result<(), Overflow> {
        for instance in removed {
            self.remove(state, instance)?;
        }
        for instance in added {
            self.add(state, instance, scratch)?;
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

    fn visit_blocks(&self, state: &SilhouetteState, visit: &mut dyn FnMut(usize, usize)) {
        let list = &state.footprints;
        visit(list.as_ptr() as usize, size_of_val(list.as_slice()));
        for footprint in &state.footprints {
            let bytes = size_of::<Footprint>()
                + size_of_val(&*footprint.words)
                + size_of_val(&*footprint.ends);
            visit(Arc::as_ptr(footprint) as usize, bytes);
        }
    }
}
