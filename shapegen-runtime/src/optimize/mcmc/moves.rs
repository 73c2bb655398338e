//! What a chain proposed in an iteration, in each variant: kept by the [`Mcmc`](super::Mcmc)
//! between its proposal and its acceptance.

/// What a chain proposed this iteration.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct OriginalMove {
    /// The log prior change in the acceptance: a jump's selection log probability after
    /// minus before; 0 for a diffusion.
    pub(super) accept_prior: f32,
    /// The log prior the proposal keeps if accepted (the original's `setLogPrior`).
    pub(super) log_prior: f32,
}

/// What a chain proposed this iteration.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct TemperedMove {
    /// Whether it is a jump (delayed rejection applies).
    pub(super) jump: bool,
    /// Log of the proposal ratio.
    pub(super) log_q: f64,
}
