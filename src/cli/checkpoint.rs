//! `checkpoint.json`: what a run folder holds to go on from, whatever the method.

use std::path::{Path, PathBuf};

use anyhow::Context;
use serde::{Deserialize, Serialize};
use shapegen::scene::Overrides;

use super::files::{Files, read};

/// What `checkpoint.json` holds: the scene and overrides a run started with, and the
/// state `S` of its optimizer.
#[derive(Serialize, Deserialize)]
pub struct Checkpoint<S> {
    /// The scene, as given on the command line of the run that started.
    pub scene: PathBuf,
    /// The overrides it started with.
    pub overrides: Overrides,
    /// The optimizer's state.
    pub search: S,
}

/// The part of a checkpoint that says which scene it belongs to.
#[derive(Deserialize)]
pub struct Head {
    /// The scene.
    pub scene: PathBuf,
    /// Its overrides.
    pub overrides: Overrides,
}

/// The path of the checkpoint in run folder `dir`.
fn path(dir: &Path) -> PathBuf {
    dir.join("checkpoint.json")
}

impl Head {
    /// Reads which scene the checkpoint in `dir` belongs to.
    pub fn load(dir: &Path) -> anyhow::Result<Head> {
        let path = path(dir);
        serde_json::from_str(&read(&path)?)
            .with_context(|| format!("`{}` is not a checkpoint", path.display()))
    }
}

impl<S: Serialize> Checkpoint<S> {
    /// Writes `checkpoint.json` into `dir` with `files`, landing when they are committed.
    pub fn write(&self, files: &mut Files, dir: &Path) -> anyhow::Result<()> {
        files.write(&path(dir), serde_json::to_string(self)?.as_bytes())
    }
}

impl<S: serde::de::DeserializeOwned> Checkpoint<S> {
    /// Reads `checkpoint.json` from `dir`; `what` says what kind of run it must be from.
    pub fn load(dir: &Path, what: &str) -> anyhow::Result<Checkpoint<S>> {
        let path = path(dir);
        serde_json::from_str(&read(&path)?)
            .with_context(|| format!("`{}` is not a checkpoint of {what}", path.display()))
    }
}
