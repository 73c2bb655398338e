//! Why a scene could not be loaded.

use std::path::PathBuf;

/// Why a scene file could not be loaded: the file, the key at fault (a dotted path
/// such as `silhouette.target[0].camera.fov`) and what is wrong with it.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The file could not be read.
    #[error("cannot read scene `{}`", path.display())]
    Io {
        /// The scene file.
        path: PathBuf,
        /// What the system said.
        #[source]
        source: std::io::Error,
    },
    /// The file is not valid TOML, or has unknown keys or values of the wrong type.
    #[error("scene `{}`: {message}", path.display())]
    Syntax {
        /// The scene file.
        path: PathBuf,
        /// The parser's message, with the line and column.
        message: String,
    },
    /// A value is out of range, inconsistent with another, or names a file that cannot
    /// be used.
    #[error("scene `{}`: `{key}`: {reason}", path.display())]
    Invalid {
        /// The scene file.
        path: PathBuf,
        /// The key at fault.
        key: String,
        /// What is wrong and what would be valid.
        reason: String,
    },
    /// The backend asked for cannot count this scene.
    #[error("{0}")]
    Backend(String),
}
