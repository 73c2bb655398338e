//! Code that works on every published generator.

use shapegen_runtime::Grammar;
use shapegen_runtime::genome::Limits;

/// Code that works on any grammar, run by [`Published::visit`](crate::Published::visit)
/// with the grammar chosen at run time.
pub trait GeneratorVisitor {
    /// What the visit returns.
    type Output;
    /// Runs with grammar `G`, whose published genome limits are `limits`.
    fn visit<G: Grammar>(self, limits: Limits) -> Self::Output;
}
