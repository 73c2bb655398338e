//! [`ExportError`]: why an export failed.

use std::path::PathBuf;

/// Why a model could not be exported.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExportError {
    /// Writing failed.
    #[error("cannot write the export")]
    Io(#[from] std::io::Error),
    /// A file could not be created or written.
    #[error("cannot write `{}`", path.display())]
    File {
        /// The file.
        path: PathBuf,
        /// What the system said.
        #[source]
        source: std::io::Error,
    },
    /// An instance refers to a mesh id the bound meshes lack.
    #[error("instance {instance} uses mesh id {mesh}, but only {bound} meshes are bound")]
    UnknownMesh {
        /// Index of the instance.
        instance: usize,
        /// Its mesh id.
        mesh: u32,
        /// Number of bound meshes.
        bound: usize,
    },
    /// The model exceeds a limit of the format.
    #[error("{what} exceeds the format's limit of {limit}")]
    TooLarge {
        /// What is too large.
        what: String,
        /// The limit.
        limit: u64,
    },
}
