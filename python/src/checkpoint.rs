//! `checkpoint.json` in a run folder, as the tool writes it: the scene (its path as
//! given), the overrides the run started with, and the search's state. A search from
//! Python saves it as `shapegen run` does, so that either goes on from the other's.

use std::path::{Path, PathBuf};

use shapegen::scene::Overrides;

use crate::error::Error;

/// The checkpoint file of run folder `dir`.
fn path(dir: &Path) -> PathBuf {
    dir.join("checkpoint.json")
}

/// What a checkpoint holds.
pub struct Saved {
    /// The scene file.
    pub scene: PathBuf,
    /// The overrides the run started with.
    pub overrides: Overrides,
    /// The search's state, as JSON.
    pub state: String,
}

/// Reads the checkpoint in `dir`.
pub fn read(dir: &Path) -> Result<Saved, Error> {
    let file = path(dir);
    let bad =
        |why: String| Error::Search(format!("`{}` is not a checkpoint: {why}", file.display()));
    let text = std::fs::read_to_string(&file).map_err(|err| bad(err.to_string()))?;
    let mut value: serde_json::Value =
        serde_json::from_str(&text).map_err(|err| bad(err.to_string()))?;
    let mut take = |key: &str| {
        value
            .get_mut(key)
            .map(serde_json::Value::take)
            .ok_or_else(|| bad(format!("it has no `{key}`")))
    };
    let scene: PathBuf =
        serde_json::from_value(take("scene")?).map_err(|err| bad(err.to_string()))?;
    let overrides: Overrides =
        serde_json::from_value(take("overrides")?).map_err(|err| bad(err.to_string()))?;
    Ok(Saved {
        scene,
        overrides,
        state: take("search")?.to_string(),
    })
}

/// Writes the checkpoint of a run of `scene` with `overrides` into `dir`, whole or not
/// at all (a file beside it, renamed over it).
pub fn write(dir: &Path, scene: &Path, overrides: &Overrides, state: &str) -> Result<(), Error> {
    let failed = |err: &dyn std::fmt::Display| {
        Error::Search(format!(
            "cannot save the checkpoint in `{}`: {err}",
            dir.display()
        ))
    };
    let state: serde_json::Value = serde_json::from_str(state).map_err(|e| failed(&e))?;
    let text = serde_json::json!({ "scene": scene, "overrides": overrides, "search": state });
    std::fs::create_dir_all(dir).map_err(|e| failed(&e))?;
    let partial = dir.join("checkpoint.json.partial");
    std::fs::write(&partial, text.to_string()).map_err(|e| failed(&e))?;
    std::fs::rename(&partial, path(dir)).map_err(|e| failed(&e))
}
