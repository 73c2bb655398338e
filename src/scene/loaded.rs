//! The loaded and checked scene: [`Scene`], what a run aims at, with the goals of its
//! tables resolved. Reading and checking a scene file is `resolve.rs`'s.

use std::path::PathBuf;

use shapegen_runtime::genome::Limits;
use shapegen_runtime::geometry::MeshLibrary;
use shapegen_runtime::optimize::islands::IslandSettings;
use shapegen_runtime::optimize::multi::{MultiGa, MultiGaSettings};
use shapegen_runtime::score::LengthPenalty;
use shapegen_runtime::{Grammar, Site};

use super::error::{SceneError, ValueError};
use super::goal::ObjectiveGoal;
use super::method::{Method, MethodSettings, SearchJob};
use super::optimizer::{self, OptimizerGoal, Overrides};
use super::scorer::ScorerGoal;
use crate::registry::Presets;

/// A loaded and checked scene.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The scene file.
    pub path: PathBuf,
    /// The name of the generator whose models are scored, as registered.
    pub generator: String,
    /// The generator's default meshes with the scene's replacements and additions.
    pub meshes: MeshLibrary,
    /// Genome limits of the search.
    pub limits: Limits,
    /// The site models grow on (`[lot]`): the lot a building generator builds on, or
    /// [`Site::NONE`] when the scene gives none. Derive a scene's genomes on it
    /// ([`Genome::derive_on`](shapegen_runtime::Genome::derive_on)); its evaluators do.
    pub site: Site,
    /// The optimal genome length, when the scene gives one (`limits.optimal_len`); the
    /// length penalty starts there if `fitness.length_from = "optimal_len"`.
    pub optimal_len: Option<u32>,
    /// The genome-length term of the fitness.
    pub length: LengthPenalty,
    /// The best fitness the scene can reach, when it says (`fitness.optimum`): the score
    /// of a reachable target's own genome. `compare` and `sweep` then measure the gap to
    /// it and the time to fractions of it.
    pub optimum: Option<f64>,
    /// The scorers' settings, at most one of each [kind](crate::scene::ScorerKind), in
    /// the order of [`ScorerKind::ALL`](crate::scene::ScorerKind::ALL); read them with
    /// [`scorers`](Self::scorers).
    pub(super) scorers: Vec<ScorerGoal>,
    /// The objectives of a multi-objective scene (`[[objective]]` tables), which has no
    /// scorers.
    pub objectives: Option<ObjectiveGoal>,
    /// The optimizer, its settings, seed and budget. A multi-objective scene's method
    /// is the GA, whose settings breed for [`multi_settings`](Self::multi_settings).
    pub optimizer: OptimizerGoal,
    /// The `[optimizer]` table as written and overridden, for the goals of other methods.
    pub(super) optimizer_table: toml::Table,
    /// The `[islands]` table as written and overridden, likewise.
    pub(super) islands: Option<IslandSettings>,
    /// The generator's presets.
    pub(super) presets: Presets,
    /// The overrides the scene was read with.
    pub(super) overrides: Overrides,
}

impl Scene {
    /// The scene's scorers' settings, at most one of each kind, in the order of
    /// [`ScorerKind::ALL`](crate::scene::ScorerKind::ALL); empty for a scene with
    /// [`objectives`](Scene::objectives).
    pub fn scorers(&self) -> &[ScorerGoal] {
        &self.scorers
    }

    /// The scene's optimizer goal had it named `method`: the `[optimizer]` keys and the
    /// overrides read as that method's (`shapegen compare` runs each method so).
    ///
    /// # Errors
    /// [`SceneError::Optimizer`] when a key of the table is not one of the method's
    /// settings, or out of range.
    pub fn optimizer_for(&self, method: Method) -> Result<OptimizerGoal, SceneError> {
        let overrides = Overrides {
            method: Some(method),
            ..self.overrides.clone()
        };
        optimizer::resolve(
            &self.presets,
            self.optimizer_table.clone(),
            self.islands,
            &overrides,
        )
        .map_err(|error| SceneError::Optimizer {
            path: self.path.clone(),
            error: Box::new(error),
        })
    }

    /// The multi-objective GA's settings of a scene with objectives: the `[optimizer]`
    /// table's GA settings with the `[selection]` and the archive size; `None` for a
    /// scene without objectives.
    pub fn multi_settings(&self) -> Option<MultiGaSettings> {
        self.front_settings(&self.optimizer)
    }

    /// Runs `job` with the optimizer that searches `goal` on this scene: for a scene with
    /// objectives, the multi-objective GA of [`multi_settings`](Self::multi_settings),
    /// whose record is a front ([`SearchJob::run_front`]); otherwise as
    /// [`OptimizerGoal::run`] (the method's optimizer, or the GA's island model).
    pub fn search<G: Grammar, J: SearchJob<G>>(&self, goal: &OptimizerGoal, job: J) -> J::Output {
        match self.front_settings(goal) {
            Some(multi) => job.run_front::<MultiGa<G>>(multi),
            None => goal.run(job),
        }
    }

    /// The multi-objective GA's settings of `goal`, a goal of this scene, if the scene
    /// has objectives.
    fn front_settings(&self, goal: &OptimizerGoal) -> Option<MultiGaSettings> {
        let objectives = self.objectives.as_ref()?;
        let MethodSettings::Ga(ga) = goal.settings else {
            return None;
        };
        Some(MultiGaSettings {
            ga,
            selection: objectives.selection.clone(),
            archive: objectives.archive,
        })
    }

    /// An error about `key` of this scene.
    pub(crate) fn invalid(&self, key: &str, reason: String) -> SceneError {
        SceneError::Invalid {
            path: self.path.clone(),
            key: key.to_owned(),
            reason,
        }
    }

    /// An error about `key` of this scene, whose value cannot be used for `cause`.
    pub(crate) fn refused(&self, key: &str, cause: impl Into<ValueError>) -> SceneError {
        SceneError::Value {
            path: self.path.clone(),
            key: key.to_owned(),
            cause: Box::new(cause.into()),
        }
    }
}
