//! Incremental volume counting: per-voxel hit counts of one model.

use super::count::{Lattice, word_masks};
use super::counts::VolumeCounts;
use super::scorer::VolumeScorer;
use super::scratch::VolumeScratch;
use crate::geometry::Instance;
use crate::score::retained::{CellCounts, Changed, Overflow, RetainedScorer, TILE_WORDS};

/// What a [`VolumeScorer`] keeps of one model: how many times its instances hit each
/// in-grid voxel (every hit of every instance, as the overlap counts need), and the
/// model's counts. Tiles are 8 consecutive words of 64 voxels in [`Grid::index`]
/// order.
///
/// [`Grid::index`]: super::Grid::index
#[derive(Clone, Debug)]
pub struct VolumeState {
    cells: CellCounts,
    counts: VolumeCounts,
    /// The model's facet instances, which cover together: when one changes, what they
    /// covered is taken away and what the new set covers is added.
    facets: Vec<Instance>,
}

/// One instance's hits going into, or out of, a [`VolumeState`].
struct Apply<'a> {
    scorer: &'a VolumeScorer,
    state: &'a mut VolumeState,
    remove: bool,
    overflow: bool,
}

impl Apply<'_> {
    /// `total + n`, or `total - n` when removing; marks an overflow.
    fn sum(total: &mut u64, n: u64, remove: bool, overflow: &mut bool) {
        if remove {
            *total -= n;
        } else {
            match total.checked_add(n) {
                Some(t) => *total = t,
                None => *overflow = true,
            }
        }
    }
}

impl Lattice for Apply<'_> {
    fn span(&mut self, n: u64) {
        let c = &mut self.state.counts;
        Apply::sum(&mut c.span_out_of_grid, n, self.remove, &mut self.overflow);
    }

    fn outside(&mut self, n: u64) {
        let c = &mut self.state.counts;
        Apply::sum(&mut c.out_of_grid_hits, n, self.remove, &mut self.overflow);
    }

    #[inline]
    fn voxels(&mut self, first: usize, last: usize) {
        let per = self.scorer.class_stride;
        let VolumeState { cells, counts, .. } = &mut *self.state;
        for (w, mask) in word_masks(first, last) {
            let (tile, word) = (w / TILE_WORDS, w % TILE_WORDS);
            let Changed { first, second } = if self.remove {
                cells.remove(tile, word, mask)
            } else {
                match cells.add(tile, word, mask) {
                    Ok(changed) => changed,
                    Err(Overflow) => {
                        self.overflow = true;
                        return;
                    }
                }
            };
            let again = u64::from(mask.count_ones() - first.count_ones());
            let twice = u64::from(second.count_ones());
            let masks = &self.scorer.class_bits[w * per..(w + 1) * per];
            let mut rest = u64::from(first.count_ones());
            if self.remove {
                counts.overlap_hits -= again;
                counts.overlap_voxels -= twice;
                for (count, &m) in counts.classes.iter_mut().zip(masks) {
                    let n = u64::from((first & m).count_ones());
                    *count -= n;
                    rest -= n;
                }
                counts.classes[per] -= rest;
            } else {
                counts.overlap_hits += again;
                counts.overlap_voxels += twice;
                for (count, &m) in counts.classes.iter_mut().zip(masks) {
                    let n = u64::from((first & m).count_ones());
                    *count += n;
                    rest -= n;
                }
                counts.classes[per] += rest;
            }
        }
    }
}

impl VolumeScorer {
    /// Adds the hits of `instances` to `state`, or takes them away.
    fn apply(
        &self,
        state: &mut VolumeState,
        instances: &[Instance],
        remove: bool,
        scratch: &mut VolumeScratch,
    ) -> Result<(), Overflow> {
        let mut apply = Apply {
            scorer: self,
            state,
            remove,
            overflow: false,
        };
        for instance in instances {
            self.walk(instance, &mut scratch.voxelizer, &mut apply);
            if apply.overflow {
                return Err(Overflow);
            }
        }
        Ok(())
    }

    /// Adds what the state's facets cover together, or takes it away.
    fn apply_facets(
        &self,
        state: &mut VolumeState,
        remove: bool,
        scratch: &mut VolumeScratch,
    ) -> Result<(), Overflow> {
        let facets = std::mem::take(&mut state.facets);
        let mut apply = Apply {
            scorer: self,
            state,
            remove,
            overflow: false,
        };
        self.walk_facets(&facets, &mut scratch.voxelizer, &mut apply);
        let overflow = apply.overflow;
        state.facets = facets;
        if overflow { Err(Overflow) } else { Ok(()) }
    }

    /// With the F-score form, counts the state's surface from its cells (in `scratch`'s
    /// bitset, cleared again after).
    fn count_surface(&self, state: &mut VolumeState, scratch: &mut VolumeScratch) {
        if self.surface.is_none() {
            return;
        }
        let VolumeScratch {
            covered,
            touched,
            dilated,
            ..
        } = scratch;
        state.cells.visit_words(|tile, word, bits| {
            let w = tile * TILE_WORDS + word;
            covered[w] = bits;
            touched.push(w as u32);
        });
        state.counts = self.add_surface(
            state.counts,
            covered,
            touched.iter().map(|&w| w as usize),
            dilated,
        );
        for &w in touched.iter() {
            covered[w as usize] = 0;
        }
        touched.clear();
    }
}

impl RetainedScorer for VolumeScorer {
    type State = VolumeState;

    fn count_retained(
        &self,
        instances: &[Instance],
        scratch: &mut VolumeScratch,
    ) -> Result<VolumeState, Overflow> {
        let words = self.grid.voxel_count().div_ceil(64) as usize;
        let mut state = VolumeState {
            cells: CellCounts::new(words.div_ceil(TILE_WORDS)),
            counts: VolumeCounts::default(),
            facets: instances
                .iter()
                .filter(|i| self.is_facet(i))
                .copied()
                .collect(),
        };
        self.apply(&mut state, instances, false, scratch)?;
        self.apply_facets(&mut state, false, scratch)?;
        self.count_surface(&mut state, scratch);
        Ok(state)
    }

    fn update(
        &self,
        state: &mut VolumeState,
        removed: &[Instance],
        added: &[Instance],
        scratch: &mut VolumeScratch,
    ) -> Result<(), Overflow> {
        let facets_change = removed.iter().chain(added).any(|i| self.is_facet(i));
        if facets_change {
            self.apply_facets(state, true, scratch)?;
            for gone in removed.iter().filter(|i| self.is_facet(i)) {
                if let Some(k) = state.facets.iter().position(|f| f == gone) {
                    state.facets.swap_remove(k);
                }
            }
            state
                .facets
                .extend(added.iter().filter(|i| self.is_facet(i)).copied());
        }
        self.apply(state, removed, true, scratch)?;
        self.apply(state, added, false, scratch)?;
        if facets_change {
            self.apply_facets(state, false, scratch)?;
        }
        self.count_surface(state, scratch);
        Ok(())
    }

    fn state_counts(&self, state: &VolumeState) -> VolumeCounts {
        self.with_totals(state.counts)
    }

    fn visit_cells(&self, state: &VolumeState, visit: &mut dyn FnMut(&CellCounts)) {
        visit(&state.cells);
    }

    /// The facet instances, beside the cells.
    fn visit_blocks(&self, state: &VolumeState, visit: &mut dyn FnMut(usize, usize)) {
        visit(
            state.facets.as_ptr() as usize,
            size_of_val(state.facets.as_slice()),
        );
    }
}
