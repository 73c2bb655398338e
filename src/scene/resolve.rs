//! From the scene file as written to a checked [`Scene`]: paths resolved against the
//! scene's folder, files loaded, values checked, every error naming its key. Each kind
//! of scorer resolves its own table (`scorer/`), with the [`Resolver`] of `resolver.rs`.

use std::collections::BTreeMap;
use std::path::Path;

use shapegen_runtime::Site;
use shapegen_runtime::genome::Limits;
use shapegen_runtime::geometry::MeshLibrary;
use shapegen_runtime::optimize::multi::Selection;
use shapegen_runtime::score::LengthPenalty;

use super::error::SceneError;
use super::file::{FitnessFile, LengthFrom, LimitsFile, MeshFile, SceneFile};
use super::goal::ObjectiveGoal;
use super::loaded::Scene;
use super::method::{Method, SettingsKeyError};
use super::optimizer::{self, OptimizerGoal, Overrides};
pub(super) use super::resolver::Resolver;
use super::scorer::ScorerGoal;
use super::sources::Sources;
use crate::registry::Registry;

impl Scene {
    /// Loads and checks the scene file at `path`, which names a published generator.
    pub fn load(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        Scene::open(path, &Registry::published(), &Overrides::default())
    }

    /// Loads the scene file at `path`, naming one of `registry`'s generators, with
    /// `overrides` applied.
    pub fn open(
        path: impl AsRef<Path>,
        registry: &Registry,
        overrides: &Overrides,
    ) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
            path: path.to_owned(),
            source,
        })?;
        Scene::parse_in(&text, path, registry, overrides)
    }

    /// Checks the scene written in `text`, as if read from `path` (paths in it are
    /// relative to `path`'s folder), naming a published generator.
    pub fn parse(text: &str, path: &Path) -> Result<Scene, SceneError> {
        Scene::parse_in(text, path, &Registry::published(), &Overrides::default())
    }

    /// Checks the scene written in `text`, as if read from `path`, naming one of
    /// `registry`'s generators, with `overrides` applied.
    pub fn parse_in(
        text: &str,
        path: &Path,
        registry: &Registry,
        overrides: &Overrides,
    ) -> Result<Scene, SceneError> {
        Scene::parse_with(text, path, registry, overrides, &Sources::new())
    }

    /// Checks the scene written in `text`, as if read from `path`, naming one of
    /// `registry`'s generators, with `overrides` applied, its targets taken from
    /// `sources` where it names one they hold (see [`Sources`]).
    pub fn parse_with(
        text: &str,
        path: &Path,
        registry: &Registry,
        overrides: &Overrides,
        sources: &Sources,
    ) -> Result<Scene, SceneError> {
        let syntax = |message: String| SceneError::Syntax {
            path: path.to_owned(),
            message: message.trim_end().to_owned(),
        };
        let file: SceneFile = if overrides.sets.is_empty() {
            toml::from_str(text).map_err(|err| syntax(err.to_string()))?
        } else {
            let mut table: toml::Table =
                toml::from_str(text).map_err(|err| syntax(err.to_string()))?;
            optimizer::apply_overrides(&mut table, &overrides.sets).map_err(|error| {
                SceneError::Set {
                    path: path.to_owned(),
                    error,
                }
            })?;
            toml::Value::Table(table)
                .try_into()
                .map_err(|err: toml::de::Error| syntax(format!("after --set: {}", err.message())))?
        };
        Resolver::new(path, sources).scene(file, registry, overrides)
    }
}

impl Resolver<'_> {
    /// An error about a key of the `[optimizer]` or `[islands]` table.
    fn optimizer(&self, error: SettingsKeyError) -> SceneError {
        SceneError::Optimizer {
            path: self.path().to_owned(),
            error: Box::new(error),
        }
    }

    pub(super) fn scene(
        &self,
        file: SceneFile,
        registry: &Registry,
        overrides: &Overrides,
    ) -> Result<Scene, SceneError> {
        let entry = registry.get(&file.generator).ok_or_else(|| {
            self.invalid(
                "generator",
                format!(
                    "`{}` is not a registered generator; the generators are {}",
                    file.generator,
                    registry.names()
                ),
            )
        })?;
        let presets = entry.defaults.presets;
        let meshes = self.meshes(&entry.defaults.meshes, &file.meshes)?;
        let (limits, optimal_len) = self.limits(&file.limits)?;
        let site = match &file.lot {
            Some(lot) => self.lot(lot)?,
            None => Site::NONE,
        };
        let length = self.length_penalty(&file.fitness, &limits, optimal_len)?;
        let optimum = self.optimum(file.fitness.optimum)?;
        let scorers = file.scorer_goals(self)?;
        let mut table = file.optimizer;
        let objectives = self.objective_goal(
            file.objective,
            file.selection,
            &scorers,
            entry.mesh_names,
            &mut table,
        )?;
        let optimizer = optimizer::resolve(&presets, table.clone(), file.islands, overrides)
            .map_err(|err| self.optimizer(err))?;
        if objectives.is_some() {
            self.check_front_search(&optimizer)?;
        }

        Ok(Scene {
            optimizer,
            optimizer_table: table,
            islands: file.islands,
            presets,
            overrides: overrides.clone(),
            path: self.path().to_owned(),
            generator: entry.name.clone(),
            meshes,
            limits,
            site,
            optimal_len,
            length,
            optimum,
            scorers,
            objectives,
        })
    }

    /// The generator's meshes `base` with the scene's `[meshes]` registered over them.
    fn meshes(
        &self,
        base: &MeshLibrary,
        files: &BTreeMap<String, MeshFile>,
    ) -> Result<MeshLibrary, SceneError> {
        let mut meshes = base.clone();
        for (name, entry) in files {
            let key = format!("meshes.{name}");
            let (written, normalize) = match entry {
                MeshFile::Path(path) => (path, true),
                MeshFile::Table { path, normalize } => (path, *normalize),
            };
            let path = self.file(&key, written)?;
            let registered = if normalize {
                meshes.register_obj(name.clone(), &path)
            } else {
                meshes.register_obj_as_written(name.clone(), &path)
            };
            registered.map_err(|err| self.refused(key, err))?;
        }
        Ok(meshes)
    }

    /// The length penalty of `[fitness]`, from `min_len` or `optimal_len` to `max_len`.
    fn length_penalty(
        &self,
        fitness: &FitnessFile,
        limits: &Limits,
        optimal_len: Option<u32>,
    ) -> Result<LengthPenalty, SceneError> {
        let from = match (fitness.length_from, optimal_len) {
            (LengthFrom::MinLen, _) => limits.min_len,
            (LengthFrom::OptimalLen, Some(optimal)) => optimal,
            (LengthFrom::OptimalLen, None) => {
                return Err(self.invalid(
                    "fitness.length_from",
                    "\"optimal_len\" starts the length penalty at limits.optimal_len, \
                     which the scene does not give; add it to [limits]",
                ));
            }
        };
        Ok(LengthPenalty {
            weight: self.non_negative("fitness.length", fitness.length)?,
            from: f64::from(from),
            to: f64::from(limits.max_len),
        })
    }

    /// `fitness.optimum`, which must be a finite number above 0 when given.
    fn optimum(&self, optimum: Option<f64>) -> Result<Option<f64>, SceneError> {
        match optimum {
            Some(v) if !(v.is_finite() && v > 0.0) => Err(self.invalid(
                "fitness.optimum",
                format!(
                    "{v} must be a finite number > 0: the best fitness the scene can \
                     reach, whose fractions compare and sweep time"
                ),
            )),
            v => Ok(v),
        }
    }

    /// The `[[objective]]` tables' goal, if the scene has any: then its `[selection]`
    /// and the archive taken from the `[optimizer]` `table`, whose method defaults to the
    /// GA. A scene scores by `scorers` or by objectives, not both, and by something.
    fn objective_goal(
        &self,
        objective: Vec<toml::Table>,
        selection: Option<Selection>,
        scorers: &[ScorerGoal],
        mesh_names: &[&str],
        table: &mut toml::Table,
    ) -> Result<Option<ObjectiveGoal>, SceneError> {
        if objective.is_empty() {
            if scorers.is_empty() {
                return Err(self.invalid(
                    "volume",
                    "the scene has nothing to score: add a [volume] or [silhouette] table, \
                     or [[objective]] tables",
                ));
            }
            if selection.is_some() {
                return Err(self.invalid(
                    "selection",
                    "ranks the objectives of [[objective]] tables, and the scene has none",
                ));
            }
            return Ok(None);
        }
        if !scorers.is_empty() {
            return Err(self.invalid(
                "objective",
                "a scene scores either by [volume] / [silhouette] or by [[objective]] \
                 tables, not both",
            ));
        }
        let set = self.objectives(objective, mesh_names)?;
        let selection = selection.unwrap_or_default();
        selection
            .validate()
            .and_then(|()| selection.check_objectives(set.len()))
            .map_err(|err| self.refused(err.field, err))?;
        let archive = optimizer::take_archive(table).map_err(|err| self.optimizer(err))?;
        // The multi-objective GA searches it, whatever the default method.
        table
            .entry("method")
            .or_insert_with(|| toml::Value::String(Method::Ga.name().to_owned()));
        Ok(Some(ObjectiveGoal {
            set,
            selection,
            archive,
        }))
    }

    /// A scene with objectives is searched by the multi-objective GA: the method must be
    /// the GA, without islands.
    fn check_front_search(&self, optimizer: &OptimizerGoal) -> Result<(), SceneError> {
        if optimizer.islands.is_some() {
            return Err(self.invalid(
                "islands",
                "scenes with [[objective]] tables are searched by the multi-objective GA, \
                 which has no island model; leave out [islands] and --islands",
            ));
        }
        if optimizer.method() != Method::Ga {
            return Err(self.invalid(
                "optimizer.method",
                format!(
                    "\"{}\": scenes with [[objective]] tables are searched by the \
                     multi-objective GA; the method must be \"ga\"",
                    optimizer.method().name()
                ),
            ));
        }
        Ok(())
    }

    fn limits(&self, l: &LimitsFile) -> Result<(Limits, Option<u32>), SceneError> {
        if l.min_len == 0 {
            return Err(self.invalid("limits.min_len", "must be at least 1 (the root gene)"));
        }
        if l.max_len < l.min_len {
            return Err(self.invalid(
                "limits.max_len",
                format!("{} is below limits.min_len = {}", l.max_len, l.min_len),
            ));
        }
        if let Some(optimal) = l
            .optimal_len
            .filter(|o| !(l.min_len..=l.max_len).contains(o))
        {
            return Err(self.invalid(
                "limits.optimal_len",
                format!(
                    "{optimal} must lie between limits.min_len = {} and limits.max_len = {}",
                    l.min_len, l.max_len
                ),
            ));
        }
        if l.max_depth == 0 {
            return Err(self.invalid("limits.max_depth", "must be at least 1 (the root)"));
        }
        let limits = Limits {
            min_len: l.min_len,
            max_len: l.max_len,
            max_depth: l.max_depth,
        };
        Ok((limits, l.optimal_len))
    }
}

#[cfg(test)]
mod tests {
    use std::error::Error;

    use super::Scene;

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
        assert!(
            matches!(**cause, crate::scene::error::ValueError::Image(_)),
            "{cause:?}"
        );
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
