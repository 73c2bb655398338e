//! `--cpu` / `--gpu`: which backend counts, and opening the GPU when it may be used.

use clap::Args;
use serde::{Deserialize, Serialize};
use shapegen::gpu::GpuContext;
use shapegen::optimize::Held;
use shapegen::scene::{Backend, BackendChoice};
use shapegen::score::retained::RetentionStats;

/// The backend flags of the scoring commands; a sweep's plan saves them.
#[derive(Clone, Debug, Default, PartialEq, Eq, Args, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BackendArgs {
    /// Count on the CPU (all worker threads).
    #[arg(long, conflicts_with = "gpu")]
    cpu: bool,
    /// Count on the GPU, any adapter including a software one; fails when there is none.
    #[arg(long)]
    gpu: bool,
    /// Count every bred child from nothing, not from what was kept of its parent (the
    /// reference: the same results, more slowly).
    #[arg(long)]
    no_incremental: bool,
}

impl BackendArgs {
    /// The choice the flags make: neither flag lets the scene pick (a hardware GPU when
    /// there is one, else the CPU).
    pub fn choice(&self) -> BackendChoice {
        match (self.cpu, self.gpu) {
            (true, _) => BackendChoice::Cpu,
            (_, true) => BackendChoice::Gpu,
            _ => BackendChoice::Auto,
        }
    }

    /// Whether models may be counted on a GPU: unless `--cpu` is given.
    pub fn may_use_gpu(&self) -> bool {
        self.choice() != BackendChoice::Cpu
    }

    /// Whether bred children may be counted from their parents' kept state.
    pub fn incremental(&self) -> bool {
        !self.no_incremental
    }

    /// Opens the GPU unless the CPU was asked for. `None` when there is no adapter (the
    /// reason is printed when `--gpu` is not given: the scorer then says it counts on the
    /// CPU).
    pub fn open(&self) -> Option<GpuContext> {
        if !self.may_use_gpu() {
            return None;
        }
        match GpuContext::new() {
            Ok(gpu) => Some(gpu),
            Err(err) => {
                eprintln!("{err}");
                None
            }
        }
    }
}

/// Refuses a run whose batches `backend` cannot count: on a GPU, the most models the
/// method scores at once (`held`) must fit its storage bindings
/// ([`Backend::check_batch`]).
pub fn check_batches(backend: &Backend<'_>, held: &[Held]) -> anyhow::Result<()> {
    Ok(backend.check_held(held)?)
}

/// How a run's bred children were counted, for its summary.
#[derive(Debug, Serialize)]
pub struct Incremental {
    /// Children counted from their parent's kept state.
    pub children_incremental: u64,
    /// Children counted from nothing.
    pub children_full: u64,
    /// Parents whose state was counted because none was kept (the first generation, a
    /// resume).
    pub parents_counted: u64,
    /// Of the incrementally counted children's instances, the share that changed
    /// (removed and added, over the children's instances).
    pub changed_share: f64,
    /// Bytes of state kept at the end.
    pub kept_bytes: usize,
}

impl From<(RetentionStats, usize)> for Incremental {
    fn from((stats, kept_bytes): (RetentionStats, usize)) -> Self {
        Incremental {
            children_incremental: stats.incremental,
            children_full: stats.full,
            parents_counted: stats.parents_counted,
            changed_share: stats.changed_instances as f64 / stats.child_instances.max(1) as f64,
            kept_bytes,
        }
    }
}

impl std::fmt::Display for Incremental {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "incremental scoring: {} children counted from their parents ({:.1} % of their \
             instances changed), {} from nothing; {:.1} MiB of state kept",
            self.children_incremental,
            100.0 * self.changed_share,
            self.children_full,
            self.kept_bytes as f64 / f64::from(1 << 20)
        )
    }
}
