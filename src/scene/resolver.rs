//! The resolver of one scene file: where it is, the targets given in memory, and the
//! errors that name its keys ([`Resolver`]). Each part of the scene resolves its own
//! tables with it (`resolve.rs`, `lot.rs`, `objective.rs`, each kind of `scorer/`).

use std::path::{Path, PathBuf};

use super::error::{SceneError, ValueError};
use super::sources::Sources;

/// Resolves the tables of the scene file at its path: paths relative to its folder,
/// targets taken from [`Sources`] first, errors naming the scene and the key.
pub struct Resolver<'a> {
    path: &'a Path,
    dir: PathBuf,
    /// Targets given in memory, looked up before files.
    sources: &'a Sources,
}

impl<'a> Resolver<'a> {
    /// A resolver of the scene at `path` that takes the targets `sources` holds from
    /// there.
    pub fn new(path: &'a Path, sources: &'a Sources) -> Self {
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Resolver { path, dir, sources }
    }

    /// An error about `key`, whose value is refused for `reason`.
    pub fn invalid(&self, key: impl Into<String>, reason: impl Into<String>) -> SceneError {
        SceneError::Invalid {
            path: self.path.to_owned(),
            key: key.into(),
            reason: reason.into(),
        }
    }

    /// An error about `key`, whose value cannot be used for `cause`.
    pub fn refused(&self, key: impl Into<String>, cause: impl Into<ValueError>) -> SceneError {
        SceneError::Value {
            path: self.path.to_owned(),
            key: key.into(),
            cause: Box::new(cause.into()),
        }
    }

    /// A path written in the scene, relative to the scene's folder, which must name an
    /// existing file.
    pub fn file(&self, key: &str, written: &str) -> Result<PathBuf, SceneError> {
        if written.is_empty() {
            return Err(self.invalid(key, "the path is empty"));
        }
        let path = self.dir.join(written);
        if !path.is_file() {
            return Err(self.invalid(
                key,
                format!(
                    "`{}` is not a file (paths are relative to the scene file's folder)",
                    path.display()
                ),
            ));
        }
        Ok(path)
    }

    /// `value` of `key`, which must be finite.
    pub fn finite(&self, key: &str, value: f64) -> Result<f64, SceneError> {
        if value.is_finite() {
            Ok(value)
        } else {
            Err(self.invalid(key, format!("{value} is not a finite number")))
        }
    }

    /// `value` of `key`, which must be finite and at least 0.
    pub fn non_negative(&self, key: &str, value: f64) -> Result<f64, SceneError> {
        if value.is_finite() && value >= 0.0 {
            Ok(value)
        } else {
            Err(self.invalid(key, format!("{value} must be a finite number >= 0")))
        }
    }

    /// The scene file.
    pub fn path(&self) -> &Path {
        self.path
    }

    /// The targets given in memory, looked up before files.
    pub fn sources(&self) -> &Sources {
        self.sources
    }
}
