//! How a population is scored: the [`Evaluator`] trait and a closure-backed evaluator.

use crate::derive::Grammar;
use crate::genome::Genome;

/// Why an [`Evaluator`] could not score a population.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("evaluation failed: {0}")]
pub struct EvaluateError(pub String);

/// Scores a whole population at once (the scene scorers batch it onto the CPU or the GPU).
///
/// Fitness is higher-is-better. A NaN fitness is the worst of all values: it ranks last,
/// has zero selection weight and is never accepted by a Metropolis test; `+inf` and
/// `-inf` are ordinary extremes (see the module documentation of
/// [`optimize`](crate::optimize) for each method's exact treatment).
pub trait Evaluator<G: Grammar> {
    /// Writes the fitness of `genomes[i]` to `out[i]` (higher is better). `out` has the
    /// length of `genomes`.
    fn evaluate(&mut self, genomes: &[Genome<G>], out: &mut [f64]) -> Result<(), EvaluateError>;
}

impl<G: Grammar, E: Evaluator<G> + ?Sized> Evaluator<G> for &mut E {
    fn evaluate(&mut self, genomes: &[Genome<G>], out: &mut [f64]) -> Result<(), EvaluateError> {
        (**self).evaluate(genomes, out)
    }
}

/// An [`Evaluator`] scoring each genome on its own with a closure, in order.
///
/// ```
/// use shapegen_runtime::optimize::{Evaluator, FnEvaluator};
/// use shapegen_runtime::prelude::*;
///
/// generator! {
///     /// A single block.
///     pub Block { axiom B; node B { derive(s) { s.emit(CUBE); } } }
/// }
///
/// let mut by_len = FnEvaluator(|g: &Genome<Block>| g.len() as f64);
/// let genomes = [Genome::<Block>::axiom(&mut rand::rng())];
/// let mut out = [0.0];
/// by_len.evaluate(&genomes, &mut out)?;
/// assert_eq!(out, [1.0]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct FnEvaluator<F>(pub F);

impl<G: Grammar, F: FnMut(&Genome<G>) -> f64> Evaluator<G> for FnEvaluator<F> {
    fn evaluate(&mut self, genomes: &[Genome<G>], out: &mut [f64]) -> Result<(), EvaluateError> {
        for (g, o) in genomes.iter().zip(out.iter_mut()) {
            *o = (self.0)(g);
        }
        Ok(())
    }
}
