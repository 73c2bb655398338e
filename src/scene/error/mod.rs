//! Why a scene could not be loaded, scored or searched: [`SceneError`], and the typed
//! causes it carries, each in a module of what it is about (those of the `[optimizer]`
//! table, [`SettingsKeyError`], beside the table of methods that reads it).
//!
//! A [`SceneError`]'s message is whole: the file, the key at fault and the cause with its
//! own chain of causes. So that printing the chain (`{:#}` of an `anyhow::Error`) does
//! not repeat the cause, only [`SceneError::Io`] exposes its cause as its
//! [`source()`](std::error::Error::source), and [`SceneError::Backend`] is the
//! backend's error itself; the others keep their cause as a typed field. The causes
//! follow the runtime's convention: a message never repeats what its `source()` gives.

mod backend;
mod image;
mod set;
mod value;

use std::path::PathBuf;

use shapegen_runtime::error_chain;

use super::method::SettingsKeyError;

pub use backend::BackendError;
pub use image::{DecodeError, ImageError};
pub use set::SetError;
pub use value::ValueError;

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

#[cfg(test)]
mod tests {
    use std::error::Error;

    use crate::scene::Scene;

    /// A silhouette scene whose target image is `bytes`, in a folder of its own.
    fn with_image(bytes: &[u8]) -> (tempfile::TempDir, super::SceneError) {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("target.png"), bytes).unwrap();
        let text = r#"
generator = "city"
[limits]
min_len = 1
max_len = 201
max_depth = 8
[[silhouette.target]]
image = "target.png"
camera = { phi = 0, theta = 0, radius = 5, lookat = [0, 0, 0], fov = 60, near = 0.1, far = 100, width = 8, height = 6 }
"#;
        let err = Scene::parse(text, &dir.path().join("scene.toml")).unwrap_err();
        (dir, err)
    }

    #[test]
    fn a_cause_is_printed_once_and_not_chained() {
        let (dir, err) = with_image(b"\x89PNG\r\n\x1a\n");
        let super::SceneError::Value { key, cause, .. } = &err else {
            panic!("{err}");
        };
        assert_eq!(key, "silhouette.target[0].image");
        assert!(matches!(**cause, super::ValueError::Image(_)), "{cause:?}");
        let image = dir.path().join("target.png");
        let message = err.to_string();
        let want = format!(
            "scene `{}`: `silhouette.target[0].image`: `{}`: ",
            dir.path().join("scene.toml").display(),
            image.display()
        );
        assert!(message.starts_with(&want), "{message}");
        assert!(
            err.source().is_none(),
            "the cause is in the message: {message}"
        );
    }
}
