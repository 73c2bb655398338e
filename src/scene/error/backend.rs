//! The backend that counts a scene's models: the GPU asked for, and what it can hold.

use shapegen_runtime::gpu::GpuError;

/// Why the backend asked for cannot count a scene's models.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum BackendError {
    /// The GPU was asked for (`--gpu`), and no adapter was found.
    #[error("--gpu asks for the GPU, but no GPU adapter was found")]
    NoAdapter,
    /// The GPU was asked for, and a scorer cannot count on it.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// The GPU cannot count as many models at once as a batch of the run holds.
    #[error(
        "{setting} has the GPU count {models} models at once, but the counts of at most \
         {max} fit the storage bindings of {backend}: lower it, or count on the CPU (--cpu)"
    )]
    Batch {
        /// The setting that sets the number, as `key = value`.
        setting: String,
        /// Models a batch holds.
        models: u64,
        /// The most models whose counts fit the device's storage bindings.
        max: usize,
        /// The backend, in words (`GPU: NVIDIA H200 (vulkan, discrete GPU)`).
        backend: String,
    },
}
