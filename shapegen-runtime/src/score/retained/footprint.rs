//! What each instance of a model covers, kept with the model's state so that taking the
//! instance away again replays it instead of rasterizing the instance a second time.
//!
//! A footprint is kept only where replaying it is the cheaper way: when its instance's
//! rasterization goes through at least [`MIN_COST`] triangles (or hull points) and
//! through more of them than the footprint holds words. A tree's leaf, 574 small
//! triangles covering a few dozen words, keeps its footprint; a building's box (12
//! triangles over hundreds of words) or a window's quad (2 triangles) is rasterized again
//! instead, which costs about what keeping, finding and freeing its footprint would.

use std::sync::Arc;

use super::diff::{InstanceKey, instance_key};
use crate::geometry::Instance;

/// The fewest triangles (or hull points) whose rasterization a kept footprint saves.
pub(crate) const MIN_COST: usize = 32;

/// The most grids (images) one footprint covers: a silhouette scorer's targets.
pub(crate) const MAX_GRIDS: usize = 8;

/// The cells one instance covers in each grid of a scorer: the non-zero coverage words
/// it rasterizes to, as (word index, bits), grid after grid. What an instance covers
/// depends on the instance alone, so two instances with equal keys share a footprint.
#[derive(Debug)]
pub(crate) struct Footprint {
    key: InstanceKey,
    words: Box<[(u32, u64)]>,
    /// Where each grid's words end in `words`.
    ends: [u32; MAX_GRIDS],
}

impl Footprint {
    /// The footprint of `instance` in `grids` grids, grid `g`'s words written by
    /// `fill(g, words)` (appended to `words`).
    ///
    /// # Panics
    /// If `grids > MAX_GRIDS`.
    pub(crate) fn of(
        instance: &Instance,
        grids: usize,
        mut fill: impl FnMut(usize, &mut Vec<(u32, u64)>),
    ) -> Footprint {
        let mut words = Vec::new();
        let mut ends = [0; MAX_GRIDS];
        for (g, end) in ends[..grids].iter_mut().enumerate() {
            fill(g, &mut words);
            *end = words.len() as u32;
        }
        Footprint {
            key: instance_key(instance),
            words: words.into(),
            ends,
        }
    }

    /// The words of grid `g`.
    pub(crate) fn grid(&self, g: usize) -> &[(u32, u64)] {
        let start = g.checked_sub(1).map_or(0, |p| self.ends[p] as usize);
        &self.words[start..self.ends[g] as usize]
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

    /// Keeps `footprint` if `cost`, the triangles or points that rasterizing its
    /// instance goes through, is at least [`MIN_COST`] and more than the words it holds
    /// (see the [module documentation](self)).
    pub(crate) fn keep(&mut self, footprint: Footprint, cost: usize) {
        if cost >= MIN_COST && footprint.words.len() < cost {
            let at = self.0.partition_point(|f| f.key <= footprint.key);
            self.0.insert(at, Arc::new(footprint));
        }
    }

    /// Takes out the footprint of `instance`, if one was kept: the rule of
    /// [`keep`](Self::keep) depends on the instance alone, so an instance of the model
    /// whose footprint was worth keeping finds it.
    pub(crate) fn take(&mut self, instance: &Instance) -> Option<Arc<Footprint>> {
        let key = instance_key(instance);
        let at = self.0.binary_search_by(|f| f.key.cmp(&key)).ok()?;
        Some(self.0.remove(at))
    }

    /// Hands the list and every footprint to `visit` as (address, bytes), to measure
    /// memory ([`RetainedScorer::visit_blocks`](super::RetainedScorer::visit_blocks)).
    pub(crate) fn visit(&self, visit: &mut dyn FnMut(usize, usize)) {
        visit(self.0.as_ptr() as usize, size_of_val(self.0.as_slice()));
        for footprint in &self.0 {
            visit(Arc::as_ptr(footprint) as usize, footprint.bytes());
        }
    }
}
