//! How a population is scored, on one fitness ([`Evaluator`], [`FnEvaluator`]) or on
//! several objectives ([`MultiEvaluator`], each objective with its [`Sense`]).
//!
//! This module sits below both the scorers ([`score`](crate::score)), which implement
//! these traits, and the optimizers ([`optimize`](crate::optimize)), which call them and
//! re-export every item here; neither depends on the other.

use serde::{Deserialize, Serialize};

use crate::derive::Grammar;
use crate::genome::Genome;

/// Why an [`Evaluator`] could not score a population.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("evaluation failed: {0}")]
pub struct EvaluateError(pub String);

/// Children bred from a scored population, with their lineage: `children[i]` was made from
/// `parents[from[i]]` ([`Evaluator::evaluate_bred`]).
pub struct Bred<'a, G> {
    /// The children.
    pub children: &'a [Genome<G>],
    /// The population they were bred from.
    pub parents: &'a [Genome<G>],
    /// Per child, the index of the parent it was made from; as long as `children`.
    pub from: &'a [u32],
}

impl<G> Clone for Bred<'_, G> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<G> Copy for Bred<'_, G> {}

/// Declares a trait scoring whole populations of genomes, `pub trait $name<G: Grammar>`,
/// with `evaluate(&mut self, genomes, out)`, `evaluate_bred(&mut self, bred, out)`, whose
/// default ignores the lineage and calls `evaluate` on the children, and the `&self`
/// methods of its own listed after them (declared first), each with the documentation
/// given; and implements the trait for `&mut E` by forwarding every method.
macro_rules! population_evaluator {
    (
        $(#[$doc:meta])*
        pub trait $name:ident {
            $(#[$evaluate_doc:meta])*
            fn evaluate;
            $(#[$bred_doc:meta])*
            fn evaluate_bred;
            $(
                $(#[$own_doc:meta])*
                fn $own:ident(&self) -> $own_out:ty;
            )*
        }
    ) => {
        $(#[$doc])*
        pub trait $name<G: Grammar> {
            $(
                $(#[$own_doc])*
                fn $own(&self) -> $own_out;
            )*

            $(#[$evaluate_doc])*
            fn evaluate(
                &mut self,
                genomes: &[Genome<G>],
                out: &mut [f64],
            ) -> Result<(), EvaluateError>;

            $(#[$bred_doc])*
            fn evaluate_bred(&mut self, bred: Bred<'_, G>, out: &mut [f64]) -> Result<(), EvaluateError> {
                self.evaluate(bred.children, out)
            }
        }

        impl<G: Grammar, E: $name<G> + ?Sized> $name<G> for &mut E {
            $(
                fn $own(&self) -> $own_out {
                    (**self).$own()
                }
            )*

            fn evaluate(
                &mut self,
                genomes: &[Genome<G>],
                out: &mut [f64],
            ) -> Result<(), EvaluateError> {
                (**self).evaluate(genomes, out)
            }

            fn evaluate_bred(&mut self, bred: Bred<'_, G>, out: &mut [f64]) -> Result<(), EvaluateError> {
                (**self).evaluate_bred(bred, out)
            }
        }
    };
}

population_evaluator! {
    /// Scores a whole population at once (the scene scorers batch it onto the CPU or the
    /// GPU).
    ///
    /// Fitness is higher-is-better. A NaN fitness is the worst of all values: it ranks
    /// last, has zero selection weight and is never accepted by a Metropolis test; `+inf`
    /// and `-inf` are ordinary extremes (see the module documentation of
    /// [`optimize`](crate::optimize) for each method's exact treatment).
    ///
    /// Optimizers that breed new genomes from a population they have scored (the GA, the
    /// multi-objective GA, RJMCMC) call [`evaluate_bred`](Self::evaluate_bred), which says
    /// which genome each child was bred from, so that an evaluator can score a child from
    /// what it kept of its parent (see [`score::retained`](crate::score::retained)).
    pub trait Evaluator {
        /// Writes the fitness of `genomes[i]` to `out[i]` (higher is better). `out` has the
        /// length of `genomes`.
        fn evaluate;

        /// As [`evaluate`](Self::evaluate) of `bred.children`, for children bred from
        /// `bred.parents`: `children[i]` was made from `parents[from[i]]` by a few
        /// operators (a mutation, or a crossover that put another parent's subtree into
        /// it), and `parents` is the population the optimizer breeds from, which it scored
        /// earlier. The fitness must be exactly what `evaluate` gives: lineage only lets an
        /// evaluator do less work. An evaluator that keeps state between calls may drop
        /// whatever is of neither `parents` nor `children`. The default ignores the
        /// lineage.
        ///
        /// `from` has the length of `children`, and each entry indexes `parents`.
        fn evaluate_bred;
    }
}

/// An [`Evaluator`] scoring each genome on its own with a closure, in order.
///
/// ```
/// use shapegen_runtime::evaluate::{Evaluator, FnEvaluator};
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

population_evaluator! {
    /// Scores a whole population on `k` objectives at once.
    pub trait MultiEvaluator {
        /// Writes the `k` raw objective values of `genomes[i]` to
        /// `out[i * k..(i + 1) * k]`. `out` holds `genomes.len() * k` values.
        fn evaluate;

        /// As [`evaluate`](Self::evaluate), for children bred from `parents`, with the
        /// lineage and the promises of [`Evaluator::evaluate_bred`]. The default ignores
        /// the lineage.
        fn evaluate_bred;

        /// The `k` objectives' senses (at least one).
        fn senses(&self) -> &[Sense];
    }
}

/// The direction of one objective of a multi-objective search.
///
/// ```
/// use shapegen_runtime::evaluate::Sense;
///
/// assert!(Sense::Minimize.better(1.0, 2.0));
/// assert_eq!(Sense::Minimize.oriented(2.0), -2.0);
/// assert!(Sense::Maximize.oriented(f64::NAN).is_nan());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Sense {
    /// Higher values are better.
    Maximize,
    /// Lower values are better.
    Minimize,
}

impl Sense {
    /// The value in the higher-is-better convention: itself, or its negation.
    pub fn oriented(self, value: f64) -> f64 {
        match self {
            Sense::Maximize => value,
            Sense::Minimize => -value,
        }
    }

    /// Whether `a` is strictly better than `b` (NaN is never better, and every number is
    /// better than NaN).
    pub fn better(self, a: f64, b: f64) -> bool {
        let (a, b) = (self.oriented(a), self.oriented(b));
        !a.is_nan() && (b.is_nan() || a > b)
    }
}
