//! Scene files: what a run aims at.
//!
//! A scene is a TOML file naming a published generator, the meshes it uses, the genome
//! limits, and one or both scorers with their targets: a volume to fill or avoid, and
//! silhouettes seen through cameras. Paths in it are relative to the scene file.
//!
//! ```toml
//! generator = "spaceship"            # a registered generator: spaceship, tree, city,
//!                                    # building, roofed_building, lot_building, or one
//!                                    # of your own (shapegen::registry)
//!
//! [lot]                              # optional: the site a building generator builds on
//! points = [[-8, -6], [8, -6], [8, 0], [0, 0], [0, 6], [-8, 6]]   # [x, y], y north
//! # geojson = "lots/l_lot.geojson"   # or: a GeoJSON file holding one Polygon (no holes)
//!                                    # any simple polygon, either orientation; laid on
//!                                    # the ground as x = x, z = -y (see Site)
//! # coordinates = "degrees"          # optional: "metres" (the default, used as they
//!                                    # are) or "degrees": [longitude, latitude] on WGS 84,
//!                                    # as GeoJSON files hold them, laid out in metres
//!                                    # east and north of the lot's middle
//! # centre = true                    # optional: move the lot's middle to the origin
//!
//! [meshes]                           # optional: replace or add meshes by name
//! cube = "meshes/cube.obj"           # normalized to unit extent, as the original does
//! leaf = { path = "leaf.obj", normalize = false }   # or kept as written
//!
//! [limits]
//! min_len = 4                        # genes
//! max_len = 100
//! max_depth = 15
//! optimal_len = 10                   # optional: see fitness.length_from
//!
//! [fitness]
//! form = "smooth"                    # "smooth" (original implementation), "weighted" (paper)
//!                                    # or "iou": good * the voxel or silhouette IoU runs report
//! length = 0.1                       # weight * S(min_len, max_len, genes), as the original
//! length_from = "min_len"            # or "optimal_len": weight * S(optimal_len, max_len, genes)
//! optimum = 1.0                      # optional, > 0: the best fitness there is (a reachable
//!                                    # target's own score); compare and sweep time fractions of it
//!
//! [volume]
//! grid = { min = [-5, -5, -2], max = [5, 5, 18], resolution = [100, 200, 100] }
//! good = 2.0                         # smooth form weights
//! bad = 15.0
//! overlap = 0.0                      # weighted form: subtracted per repeated voxel hit
//! shaping_radius = 4                 # optional, opt-in: voxels off the target cost by their
//!                                    # distance to it, in full from 4 voxels away
//!                                    # (VolumeScorer::shaped)
//! [[volume.target]]
//! mesh = "target.obj"                # .obj, .stl (ASCII or binary), .ply, .gltf or .glb
//! inside = 1.0                       # weight of voxels inside (negative avoids)
//! outside = -1.0                     # weight of voxels outside
//! fill = "parity"                    # closed meshes (the original's rule); "winding":
//!                                    # open or messy meshes, by generalized winding number
//!
//! [silhouette]
//! good = 1.0
//! bad = 1.0
//! shaping_radius = 40                # optional, opt-in: masks shaped by distance, an
//!                                    # off-target pixel costing from ~0 beside the target
//!                                    # to its full weight 40 px away (ImageTarget::shaped)
//! [[silhouette.target]]
//! image = "skyline.png"              # its size must be the camera's
//! kind = "mask"                      # black pixels (red channel 0, the original's rule)
//!                                    # weigh `on` (1), the others `off` (-1); "weights": grey
//!                                    # levels from `on` (black) to `off` (white)
//! threshold = 128                    # optional, masks: pixels darker than this are the target
//! # alpha = 128                      # or: pixels at least this opaque are the target
//! # background = [255, 255, 255]     # or: pixels farther than `tolerance` (RGB distance,
//! # tolerance = 32                   #   default 32) from this colour are the target
//! camera = { phi = -3.05, theta = 0.05, radius = 12.4, lookat = [1.8, 4.7, -0.6],
//!            fov = 60, near = 0.1, far = 100, width = 800, height = 600 }
//! # or: camera = { view = [[..], [..], [..], [..]], projection = [..], width = .., height = .. }
//!
//! [optimizer]                        # optional: the generator's presets for the method
//! method = "ga"                      # a method's name (`Method`); hybrid by default,
//!                                    # but the GA with [islands] or [[objective]] tables
//! seed = 1
//! seconds = 60                       # budgets: time, evaluations, generations
//! generations = 100
//! population = 100                   # and any other field of the GA's settings
//!
//! [islands]                          # optional, the GA only: an island model
//! count = 4                          # populations of the [optimizer] settings
//! migrants = 2                       # best sent to the next island on the ring,
//! interval = 10                      #   every this many generations
//! ```
//!
//! A scene may instead aim at several objectives at once, measured on the derived
//! triangles ([`shapegen_runtime::score::objective`]); it is then searched by the
//! multi-objective GA ([`shapegen_runtime::optimize::multi`]) and has no `[volume]` or
//! `[silhouette]`:
//!
//! ```toml
//! [[objective]]
//! name = "top"                       # optional, default the kind
//! kind = "top_match"                 # or front_match: image matched by an orthographic view
//! image = "top.png"                  # black = covered
//! min = [-8, -8]                     # the view plane's area the image covers:
//! max = [8, 8]                       #   (x, z) from above, (x, y) from the front
//! [[objective]]
//! kind = "unique_normals"            # or normal_spread; tolerance_deg = 1 (default)
//! [[objective]]
//! kind = "height"                    # |top - target|, minimized
//! target = 30
//! [[objective]]
//! kind = "footprint_excess"          # how far the x/z extent leaves [min, max], minimized
//! min = [-5, -5]
//! max = [5, 5]
//! [[objective]]
//! kind = "chamfer"                   # Chamfer distance to a point cloud, minimized
//! points = "scan.xyz"                # .xyz or .txt (x y z per line) or .ply (its vertices)
//! samples = 512                      # points a side (default 512)
//! [[objective]]
//! kind = "area_share"                # |share - target|, minimized: the share of the area
//! parts = ["window", "door"]         #   of the meshes `of` (all when left out) that the
//! of = ["wall", "window", "door"]    #   meshes `parts` take (a window-to-wall ratio)
//! target = 0.4                       # from 0 to 1
//! [[objective]]
//! kind = "roof_pitch"                # |mean pitch - target_deg|, minimized: the area-weighted
//! parts = ["roof"]                   #   pitch of the upward-facing triangles of `parts`
//! target_deg = 35                    #   (default ["roof"]); from 0 to 90 degrees
//!
//! [selection]
//! ranking = "pareto"                 # or summed_rank, normalized_summed_rank, weighted_sum
//! diversity_penalty = 20.0           # subtracted from clones of an earlier objective vector
//! # weights = [1, 0.5, ...]          # weighted_sum only: one per objective
//!
//! [optimizer]                        # the GA's settings (the thesis's by default) and
//! archive = 300                      # the most non-dominated models kept
//! ```
//!
//! The `parts` and `of` of `area_share` and `roof_pitch` name the generator's meshes: a
//! triangle belongs to the part its instance's mesh is (a building's generator names its
//! facet meshes `wall`, `roof`, `window` and `door`). The names are looked up when the
//! scene is loaded; one the generator does not have is refused, with the names it has.
//!
//! Unknown keys, missing files, values out of range and images whose size differs from
//! their camera's are all refused with the file, the key and the reason.
//! [`Scene::open`] reads a scene naming any generator of a [`Registry`], with the
//! command line's [`Overrides`]: typed flags, and `key=value` overrides (`--set`) applied
//! before checking.

mod error;
mod evaluate;
mod file;
mod image;
mod lot;
mod memory;
mod method;
mod metrics;
mod objective;
mod optimizer;
mod resolve;
mod sources;

use std::path::{Path, PathBuf};

use crate::registry::{Presets, Registry};
use shapegen_runtime::Site;
use shapegen_runtime::genome::Limits;
use shapegen_runtime::geometry::MeshLibrary;
use shapegen_runtime::optimize::islands::IslandSettings;
use shapegen_runtime::optimize::multi::{MultiGaSettings, Selection};
use shapegen_runtime::score::objective::ObjectiveSet;
use shapegen_runtime::score::silhouette::ImageTarget;
use shapegen_runtime::score::volume::{Grid, VolumeTarget};
use shapegen_runtime::score::{Form, LengthPenalty};

pub use error::{BackendError, DecodeError, ImageError, SceneError, SetError, ValueError};
pub use evaluate::{
    AnyCounts, AnyScorer, Backend, BackendChoice, SceneCounts, SceneEvaluator, SceneScorer,
    ScorerGoal, ScorerKind,
};
pub use image::{decode_image, read_image};
pub use lot::{LotError, geojson_outline};
pub use memory::{JSON_BYTES_PER_WORD, MemoryError, MemoryEstimate, MemoryPart, RunShape};
pub use method::{
    Method, MethodJob, MethodSettings, SettingsCause, SettingsKeyError, UnknownMethod,
};
pub use metrics::{
    CloudDistance, F_SCORE_THRESHOLD, METRIC_COLUMNS, Metrics, SURFACE_SAMPLES, ViewIou,
};
pub use objective::ObjectiveEvaluator;
pub use optimizer::{OptimizerGoal, Overrides};
pub use sources::Sources;

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
    /// The scorers' settings, at most one of each [kind](ScorerKind), in the order of
    /// [`ScorerKind::ALL`]; read them with [`scorers`](Self::scorers).
    scorers: Vec<ScorerGoal>,
    /// The objectives of a multi-objective scene (`[[objective]]` tables), which has no
    /// scorers.
    pub objectives: Option<ObjectiveGoal>,
    /// The optimizer, its settings, seed and budget. A multi-objective scene's method
    /// is the GA, whose settings breed for [`multi_settings`](Self::multi_settings).
    pub optimizer: OptimizerGoal,
    /// The `[optimizer]` table as written and overridden, for the goals of other methods.
    optimizer_table: toml::Table,
    /// The `[islands]` table as written and overridden, likewise.
    islands: Option<IslandSettings>,
    /// The generator's presets.
    presets: Presets,
    /// The overrides the scene was read with.
    overrides: Overrides,
}

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
        let file: file::SceneFile = if overrides.sets.is_empty() {
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
        resolve::Resolver::new(path, sources).scene(file, registry, overrides)
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
        let goal = self.objectives.as_ref()?;
        let MethodSettings::Ga(ga) = self.optimizer.settings else {
            return None;
        };
        Some(MultiGaSettings {
            ga,
            selection: goal.selection.clone(),
            archive: goal.archive,
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
