//! [`Scorer`]: what every scorer offers.

use crate::geometry::Instance;

/// Counts what models cover and turns the counts into fitness.
///
/// Implementors keep no state between calls apart from `Scratch`, so that one scorer is
/// shared by every worker thread, each with its own scratch.
pub trait Scorer: Sync {
    /// What one model covers, in exact integers.
    type Counts: Copy + Send + Sync + std::fmt::Debug + PartialEq;
    /// Reusable working memory of one worker.
    type Scratch: Send;

    /// Fresh working memory for [`count`](Self::count).
    fn scratch(&self) -> Self::Scratch;

    /// Counts what the model made of `instances` covers. Leaves `scratch` ready for the
    /// next model; allocates nothing once `scratch` has grown to the largest model.
    fn count(&self, instances: &[Instance], scratch: &mut Self::Scratch) -> Self::Counts;

    /// The scorer's part of the fitness of a model with these counts (higher is better),
    /// without any genome-length term.
    fn fitness(&self, counts: &Self::Counts) -> f64;
}
