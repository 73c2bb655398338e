//! The genetic operators on packed genomes: grow, cut, alter (the original's
//! "permutate"), crossover, and the two ways to make a genome from nothing: a random
//! genome grown to a target length (the GA's initial population) and an uncontrolled
//! sample of the generator's own distribution.
//!
//! All of them live on [`Operators`], which holds the [`Limits`](crate::genome::Limits) they keep genomes within,
//! the grammar's link probabilities as exact fixed-point weights, and scratch buffers, so
//! that they allocate nothing once warmed up (crossover's children may be written into
//! existing genomes with [`Operators::crossover_into`]). Every choice is drawn from the
//! caller's RNG, with exact integer arithmetic under the weighted rules and the
//! original's own float draws under its rules: the same seed gives the same genomes.
//!
//! The operators follow one of two rule sets, an [`OperatorVariant`]:
//! [`Weighted`](OperatorVariant::Weighted) (the default) chooses with the grammar's
//! probabilities as the paper describes and keeps genomes within the limits;
//! [`Original`](OperatorVariant::Original) does what the original implementation's code
//! does, see [`OperatorVariant`] for the rules and the few places where it cannot.
//!
//! Array slots: the links of an array slot (`lots: [Lot; 100]`) are distinct edges for
//! crossover, one per index, as the original's one symbol per lot (`Lot_i_j`) are; a
//! subtree on index `i` is only ever exchanged with one on index `i`.
//! [`Operators::with_cross_array_index`] lets the indices mix.
//!
//! Costs, with G the genome's length in genes and W its length in words: grow, cut,
//! alter and crossover are O(W); [`Operators::random`] and [`Operators::grow_to`] are
//! O(G log G) with the weighted rules and O(W + G²) (a memmove of at most G words per
//! gene) with the original's; [`Operators::sample`] is O(W).
//!
//! ```
//! use rand::SeedableRng;
//! use rand_chacha::ChaCha8Rng;
//! use shapegen_runtime::prelude::*;
//!
//! generator! {
//!     /// A stack of segments with side branches.
//!     pub Chain {
//!         axiom Start;
//!         node Start { children { first: Seg = 0.9 } }
//!         node Seg {
//!             params { len: f32 ~ uniform(0.5, 1.5) }
//!             children { next: Seg = 0.5, side: Seg = 0.25 }
//!             derive(s) {
//!                 let s = s.resize(vec3(1.0, len, 1.0));
//!                 s.emit(CUBE);
//!                 if let Some(next) = next {
//!                     s.translate(vec3(0.0, s.size().y, 0.0)).derive(next);
//!                 }
//!                 if let Some(side) = side {
//!                     s.rotate_z(0.5).translate(vec3(0.0, s.size().y, 0.0)).derive(side);
//!                 }
//!             }
//!         }
//!     }
//! }
//!
//! // The examples of the operators below use this grammar.
//! let mut ops = Operators::<Chain>::new(Limits::new(2, 40, 10)?)?;
//! let mut rng = ChaCha8Rng::seed_from_u64(1);
//! let mut a = ops.random(20, &mut rng);
//! let b = ops.random(20, &mut rng);
//! ops.grow(&mut a, &mut rng);
//! ops.cut(&mut a, &mut rng);
//! ops.alter(&mut a, &mut rng);
//! if let Some((c, d)) = ops.crossover(&a, &b, &mut rng) {
//!     assert!(c.validate().is_ok() && d.validate_limits(ops.limits()).is_ok());
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod alter;
mod crossover;
mod cut;
pub(crate) mod draw;
mod edit;
mod grow;
mod kinds;
mod operators;
mod original;
pub(crate) use original::redraw;
mod random;
mod weight;

pub use operators::{CROSSOVER_RETRIES, ORIGINAL_CROSSOVER_ATTEMPTS, OperatorVariant, Operators};
