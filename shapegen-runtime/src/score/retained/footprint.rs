//! What each instance of a model covers, kept with the model's state so that taking the
//! instance away again replays it instead of rasterizing the instance a second time,
//! and the adding, removing and updating of states built on it ([`Footprinted`]).
//!
//! A footprint is kept only where replaying it is the cheaper way: when its instance's
//! rasterization goes through at least [`MIN_COST`] triangles (or hull points) and
//! through more of them than the footprint holds words. A tree's leaf, 574 small
//! triangles covering a few dozen words, keeps its footprint; a building's box (12
//! triangles over hundreds of words) or a window's quad (2 triangles) is rasterized again
//! instead, which costs about what keeping, finding and freeing its footprint would.
//! Words not kept are recorded in a buffer reused from instance to instance, so such an
//! instance allocates nothing.

use std::sync::Arc;

use super::cells::{CellCounts, Overflow};
use super::diff::{InstanceKey, instance_key};
use super::pixels::Hit;
use super::scorer::RetainedScorer;
use crate::geometry::Instance;
use crate::score::scorer::Scorer;

/// The fewest triangles (or hull points) whose rasterization a kept footprint saves.
pub(crate) const MIN_COST: usize = 32;

/// The most grids (images) one footprint covers: a silhouette scorer's targets.
pub(crate) const MAX_GRIDS: usize = 8;

/// The cells one instance covers in each grid of a scorer: the non-zero coverage words
/// it rasterizes to, as (word index, bits), grid after grid.
#[derive(Clone, Copy, Debug)]
pub struct Grids<'a> {
    words: &'a [(u32, u64)],
    /// Where each grid's words end in `words`.
    ends: &'a [u32; MAX_GRIDS],
}

impl<'a> Grids<'a> {
    /// The words of grid `g`.
    pub(crate) fn grid(self, g: usize) -> &'a [(u32, u64)] {
        let start = g.checked_sub(1).map_or(0, |p| self.ends[p] as usize);
        &self.words[start..self.ends[g] as usize]
    }
}

/// A buffer that one instance's words are recorded into, reused from instance to
/// instance.
#[derive(Clone, Debug, Default)]
pub struct Recorder {
    words: Vec<(u32, u64)>,
    ends: [u32; MAX_GRIDS],
}

impl Recorder {
    /// Records `grids` grids (at most [`MAX_GRIDS`]), grid `g`'s words appended to the
    /// buffer it is given by `fill(g, words)`.
    fn record(&mut self, grids: usize, mut fill: impl FnMut(usize, &mut Vec<(u32, u64)>)) {
        self.words.clear();
        for g in 0..grids {
            fill(g, &mut self.words);
            self.ends[g] = self.words.len() as u32;
        }
    }

    fn grids(&self) -> Grids<'_> {
        Grids {
            words: &self.words,
            ends: &self.ends,
        }
    }
}

/// The words one instance covers, kept: the instance's key and a copy of what a
/// [`Recorder`] recorded of it. Two instances with equal keys cover the same cells.
#[derive(Debug)]
struct Footprint {
    key: InstanceKey,
    words: Box<[(u32, u64)]>,
    ends: [u32; MAX_GRIDS],
}

impl Footprint {
    fn grids(&self) -> Grids<'_> {
        Grids {
            words: &self.words,
            ends: &self.ends,
        }
    }

    /// The bytes it holds.
    fn bytes(&self) -> usize {
        size_of::<Footprint>() + size_of_val(&*self.words)
    }
}

/// The footprints of a model's instances, sorted by instance key (an instance held
/// twice has two), shared with the states of related models: cloning copies the list,
/// not the footprints.
#[derive(Clone, Debug, Default)]
pub(crate) struct Footprints(Vec<Arc<Footprint>>);

impl Footprints {
    /// Room for `n` footprints.
    pub(crate) fn with_capacity(n: usize) -> Footprints {
        Footprints(Vec::with_capacity(n))
    }

    /// Keeps a copy of the words `recorded` of `instance` if `cost`, the triangles or
    /// points that rasterizing it goes through, is at least [`MIN_COST`] and more than
    /// the words (see the [module documentation](self)).
    fn keep(&mut self, instance: &Instance, recorded: &Recorder, cost: usize) {
        if cost >= MIN_COST && recorded.words.len() < cost {
            let footprint = Footprint {
                key: instance_key(instance),
                words: recorded.words.as_slice().into(),
                ends: recorded.ends,
            };
            let at = self.0.partition_point(|f| f.key <= footprint.key);
            self.0.insert(at, Arc::new(footprint));
        }
    }

    /// Takes out the footprint of `instance`, if one was kept: the rule of
    /// [`keep`](Self::keep) depends on the instance alone, so an instance of the model
    /// whose footprint was worth keeping finds it.
    fn take(&mut self, instance: &Instance) -> Option<Arc<Footprint>> {
        let key = instance_key(instance);
        let at = self.0.binary_search_by(|f| f.key.cmp(&key)).ok()?;
        Some(self.0.remove(at))
    }

    /// Hands the list and every footprint to `visit` as (address, bytes), to measure
    /// memory ([`RetainedScorer::visit_blocks`]).
    pub(crate) fn visit(&self, visit: &mut dyn FnMut(usize, usize)) {
        visit(self.0.as_ptr() as usize, size_of_val(self.0.as_slice()));
        for footprint in &self.0 {
            visit(Arc::as_ptr(footprint) as usize, footprint.bytes());
        }
    }
}

/// What a scorer that keeps footprints (the projection and silhouette scorers) keeps of
/// one model ([`RetainedScorer::State`]): its cells and counts, `C`, and the footprints of
/// its instances where worth keeping, shared with the states of related models (a
/// child's state holds its parent's, less those of the instances it lost, plus those of
/// the instances it gained), so that taking an instance away replays its footprint
/// instead of rasterizing it again.
#[derive(Clone, Debug)]
pub struct WithFootprints<C> {
    cells: C,
    footprints: Footprints,
}

/// A scorer whose kept states count, per cell, the instances covering it, and keep
/// [`Footprints`] beside them ([`WithFootprints`]): what it says about its cells,
/// rasterizing and counting, from which its [`RetainedScorer`] follows (adding an
/// instance to a state, counting a model from nothing, updating a state).
///
/// Declared `pub` in this private module, as are the types it names, so that the public
/// [`RetainedScorer`] can be implemented for every such scorer at once; nothing outside
/// the crate can name it.
pub trait Footprinted: Scorer {
    /// What is kept of one model beside its footprints: per-cell counts and the model's
    /// counts.
    type Cells: Clone + Send + Sync;

    /// The cells of a model of no instances.
    fn empty(&self) -> Self::Cells;

    /// The counts of the model whose cells are `cells`
    /// ([`RetainedScorer::state_counts`]).
    fn kept_counts(&self, cells: &Self::Cells) -> Self::Counts;

    /// Every cell grid of `cells` ([`RetainedScorer::visit_cells`]).
    fn kept_cells(&self, cells: &Self::Cells, visit: &mut dyn FnMut(&CellCounts));

    /// The grids (images) an instance is rasterized into, at most [`MAX_GRIDS`].
    fn grids(&self) -> usize;

    /// Appends the non-zero coverage words of `instance` in grid `g` to `words`.
    fn rasterize_words(
        &self,
        instance: &Instance,
        g: usize,
        scratch: &mut Self::Scratch,
        words: &mut Vec<(u32, u64)>,
    );

    /// The triangles or hull points that rasterizing `instance` goes through.
    fn raster_cost(&self, instance: &Instance) -> usize;

    /// Adds the cells of `grids` to `cells`, or takes them away.
    fn apply(&self, cells: &mut Self::Cells, grids: Grids<'_>, hit: Hit) -> Result<(), Overflow>;

    /// The buffer instances are recorded into.
    fn recorder(scratch: &mut Self::Scratch) -> &mut Recorder;

    /// Rasterizes `instance` into the scratch's recorder.
    fn record(&self, instance: &Instance, scratch: &mut Self::Scratch) -> Recorder {
        let mut recorder = std::mem::take(Self::recorder(scratch));
        recorder.record(self.grids(), |g, words| {
            self.rasterize_words(instance, g, scratch, words)
        });
        recorder
    }

    /// Rasterizes `instance` and adds its cells to `state` or takes them away (`hit`);
    /// an added instance's footprint is kept where that is worth it.
    fn rasterize_into(
        &self,
        state: &mut WithFootprints<Self::Cells>,
        instance: &Instance,
        hit: Hit,
        scratch: &mut Self::Scratch,
    ) -> Result<(), Overflow> {
        let recorded = self.record(instance, scratch);
        let applied = self.apply(&mut state.cells, recorded.grids(), hit);
        if applied.is_ok() && hit == Hit::Add {
            let cost = self.raster_cost(instance);
            state.footprints.keep(instance, &recorded, cost);
        }
        *Self::recorder(scratch) = recorded;
        applied
    }
}

impl<T: Footprinted> RetainedScorer for T {
    type State = WithFootprints<T::Cells>;

    /// Rasterizes every instance into empty cells.
    fn count_retained(
        &self,
        instances: &[Instance],
        scratch: &mut Self::Scratch,
    ) -> Result<Self::State, Overflow> {
        let mut state = WithFootprints {
            cells: self.empty(),
            footprints: Footprints::with_capacity(instances.len()),
        };
        for instance in instances {
            self.rasterize_into(&mut state, instance, Hit::Add, scratch)?;
        }
        Ok(state)
    }

    /// Takes each of `removed` out of `state` by replaying its kept footprint (or
    /// rasterizing it, where none was worth keeping), and adds each of `added`.
    fn update(
        &self,
        state: &mut Self::State,
        removed: &[Instance],
        added: &[Instance],
        scratch: &mut Self::Scratch,
    ) -> Result<(), Overflow> {
        for instance in removed {
            match state.footprints.take(instance) {
                Some(footprint) => self.apply(&mut state.cells, footprint.grids(), Hit::Remove)?,
                None => self.rasterize_into(state, instance, Hit::Remove, scratch)?,
            }
        }
        for instance in added {
            self.rasterize_into(state, instance, Hit::Add, scratch)?;
        }
        Ok(())
    }

    fn state_counts(&self, state: &Self::State) -> Self::Counts {
        self.kept_counts(&state.cells)
    }

    fn visit_cells(&self, state: &Self::State, visit: &mut dyn FnMut(&CellCounts)) {
        self.kept_cells(&state.cells, visit);
    }

    /// The footprints.
    fn visit_blocks(&self, state: &Self::State, visit: &mut dyn FnMut(usize, usize)) {
        state.footprints.visit(visit);
    }
}
