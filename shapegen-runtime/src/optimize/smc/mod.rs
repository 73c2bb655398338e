//! Sequential Monte Carlo: particles grown step by step, scored as partial models and
//! resampled by fitness, in chromosome order (SMC) or with stochastic futures (SOSMC),
//! in two variants: the original implementation's ([`SmcVariant::Original`], in
//! `original.rs`) and this project's, which grows as the generator would
//! ([`SmcVariant::Generative`], in `generative.rs`). Both share the settings, the
//! checkpoints and the run loop here.

mod generative;
mod original;
mod sampler;
mod settings;

pub use sampler::{Smc, SmcState};
pub use settings::{Cursor, Order, SmcSettings, SmcVariant};
