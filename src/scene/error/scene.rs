//! [`SceneError`]: why a scene could not be loaded, scored or searched, naming the file and
//! the key at fault.

use std::path::PathBuf;

use shapegen_runtime::error_chain;

use super::backend::BackendError;
use super::set::SetError;
use super::value::ValueError;
use crate::scene::method::SettingsKeyError;

/// Why a scene file could not be loaded: the file, the key at fault (a dotted path
/// such as `silhouette.target[0].camera.fov`) and what is wrong with it.
///
/// ```
/// use shapegen::registry::Registry;
/// use shapegen::scene::{Overrides, Scene, SceneError, SettingsCause};
///
/// let sets = vec!["optimizer.population=0".to_owned()];
/// let overrides = Overrides { sets, ..Overrides::default() };
/// let path = "scenes/paper/spaceship_volume.toml";
/// let err = Scene::open(path, &Registry::published(), &overrides).unwrap_err();
/// let SceneError::Optimizer { error, .. } = &err else { panic!("{err}") };
/// assert_eq!(error.key, "optimizer.population");
/// let SettingsCause::Settings(cause) = &error.cause else { panic!("{err}") };
/// assert_eq!((cause.field, cause.valid), ("population", "at least 2"));
/// assert_eq!(
///     err.to_string(),
///     format!("scene `{path}`: `optimizer.population`: population = 0 is invalid: it must be at least 2")
/// );
/// ```
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
    /// A `--set` override is not `key=value` over the file's tables.
    #[error("scene `{}`: {error}", path.display())]
    Set {
        /// The scene file.
        path: PathBuf,
        /// What is wrong with the override.
        error: SetError,
    },
    /// A value is out of range or inconsistent with another, as the scene's own checks
    /// find where they read it.
    #[error("scene `{}`: `{key}`: {reason}", path.display())]
    Invalid {
        /// The scene file.
        path: PathBuf,
        /// The key at fault.
        key: String,
        /// What is wrong and what would be valid.
        reason: String,
    },
    /// A value that the runtime refuses, or a file it names that cannot be used.
    #[error("scene `{}`: `{key}`: {}", path.display(), error_chain(cause))]
    Value {
        /// The scene file.
        path: PathBuf,
        /// The key at fault.
        key: String,
        /// Why its value cannot be used.
        cause: Box<ValueError>,
    },
    /// A key of the `[optimizer]` or `[islands]` table, or the command-line flag in its
    /// place, cannot be used.
    #[error("scene `{}`: {}", path.display(), error_chain(error))]
    Optimizer {
        /// The scene file.
        path: PathBuf,
        /// The key and why.
        error: Box<SettingsKeyError>,
    },
    /// The backend asked for cannot count this scene.
    #[error(transparent)]
    Backend(#[from] BackendError),
}
