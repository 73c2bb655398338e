//! Reversible-jump MCMC over derivation trees (the paper's section 7), in two variants:
//! the original implementation's Metropolis-Hastings ([`McmcVariant::Original`], in
//! `original.rs`) and this project's tempered RJMCMC after Talton et al. 2011
//! ([`McmcVariant::Tempered`], in `tempered.rs`). Both share the chains, the
//! checkpoints and the run loop here.

mod moves;
mod original;
mod sampler;
mod tempered;

pub use sampler::{Mcmc, McmcSettings, McmcState, McmcVariant};
pub(crate) use tempered::{Scratch as MoveScratch, propose};
