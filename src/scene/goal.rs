//! The goals a scene's tables resolve to, which its scorers and its multi-objective
//! search are made from: [`VolumeGoal`], [`SilhouetteGoal`] and [`ObjectiveGoal`].

use shapegen_runtime::optimize::multi::Selection;
use shapegen_runtime::score::Form;
use shapegen_runtime::score::objective::ObjectiveSet;
use shapegen_runtime::score::silhouette::ImageTarget;
use shapegen_runtime::score::volume::{Grid, VolumeTarget};

/// The `[[objective]]` tables and the `[selection]` table, resolved.
#[derive(Clone, Debug)]
pub struct ObjectiveGoal {
    /// The objectives, under their names, in the file's order.
    pub set: ObjectiveSet,
    /// How their values are ranked for selection.
    pub selection: Selection,
    /// Most models kept in the non-dominated archive (`optimizer.archive`).
    pub archive: u32,
}

/// The `[volume]` table, resolved: the grid, the targets loaded, and the fitness form.
#[derive(Clone, Debug)]
pub struct VolumeGoal {
    /// The voxel grid.
    pub grid: Grid,
    /// The target meshes and their weights.
    pub targets: Vec<VolumeTarget>,
    /// How counts become fitness.
    pub form: Form,
    /// Opt-in distance shaping ([`VolumeScorer::shaped`](shapegen_runtime::score::volume::VolumeScorer::shaped)):
    /// the distance in voxels over which an off-target voxel's cost rises to its full
    /// weight; `None` scores as published.
    pub shaping_radius: Option<f64>,
}

/// The `[silhouette]` table, resolved: the target images with their cameras, and the
/// fitness form.
#[derive(Clone, Debug)]
pub struct SilhouetteGoal {
    /// The target images.
    pub targets: Vec<ImageTarget>,
    /// How counts become fitness.
    pub form: Form,
}
