//! [`RetainedScorer`]: a scorer that keeps what it counted and counts again only what
//! changed.

use super::cells::{CellCounts, Overflow};
use crate::geometry::Instance;
use crate::score::scorer::Scorer;

/// A [`Scorer`] that can keep what it counted of a model and count a related model
/// from it (see the [module documentation](super)).
///
/// The promise: for any instances `a`, `b`, updating `count_retained(a)` with the
/// [`InstanceDiff`](super::InstanceDiff) from `a` to `b` gives a state whose
/// [`state_counts`](Self::state_counts) equal `count(b)`, and so does
/// `count_retained(b)`.
pub trait RetainedScorer: Scorer {
    /// What is kept of one model: per-cell hit counts and the model's counts. Cloning
    /// shares the cells until one clone writes to them.
    type State: Clone + Send + Sync;

    /// Counts the model made of `instances` from nothing and returns its state; fails
    /// when a cell would be hit more than 65 535 times (count it with
    /// [`Scorer::count`] then).
    fn count_retained(
        &self,
        instances: &[Instance],
        scratch: &mut Self::Scratch,
    ) -> Result<Self::State, Overflow>;

    /// Turns the state of a model into that of the model without the instances
    /// `removed` (which it must hold) and with the instances `added`. Fails as
    /// [`count_retained`](Self::count_retained) does, leaving `state` unusable.
    fn update(
        &self,
        state: &mut Self::State,
        removed: &[Instance],
        added: &[Instance],
        scratch: &mut Self::Scratch,
    ) -> Result<(), Overflow>;

    /// The counts of the model `state` describes.
    fn state_counts(&self, state: &Self::State) -> Self::Counts;

    /// Hands every cell grid of `state` to `visit`, to measure memory.
    fn visit_cells(&self, state: &Self::State, visit: &mut dyn FnMut(&CellCounts));

    /// Hands every other block of memory `state` holds to `visit`, as its address (to
    /// count a block that states share once) and its bytes, to measure memory. A state
    /// that holds only cell grids has none.
    fn visit_blocks(&self, state: &Self::State, visit: &mut dyn FnMut(usize, usize));
}
