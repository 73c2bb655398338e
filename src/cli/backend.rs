//! `--cpu` / `--gpu`: which backend counts, and opening the GPU when it may be used.

use clap::Args;
use shapegen::gpu::GpuContext;
use shapegen::scene::BackendChoice;

/// The backend flags of the scoring commands.
#[derive(Debug, Args)]
pub struct BackendArgs {
    /// Count on the CPU (all worker threads).
    #[arg(long, conflicts_with = "gpu")]
    cpu: bool,
    /// Count on the GPU, any adapter including a software one; fails when there is none.
    #[arg(long)]
    gpu: bool,
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

    /// Opens the GPU unless the CPU was asked for. `None` when there is no adapter (the
    /// reason is printed when `--gpu` is not given: the scorer then says it counts on the
    /// CPU).
    pub fn open(&self) -> Option<GpuContext> {
        if self.choice() == BackendChoice::Cpu {
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
