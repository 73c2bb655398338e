//! Scene files: what a run aims at.
//!
//! A scene is a TOML file naming a published generator, the meshes it uses, the genome
//! limits, and one or both scorers with their targets: a volume to fill or avoid, and
//! silhouettes seen through cameras. Paths in it are relative to the scene file.
//!
//! ```toml
//! generator = "spaceship"            # a registered generator: a published one
//!                                    # (spaceship, tree, city, building, ...) or one
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
//! [bounds]                           # optional: a penalty for the model outside a box
//! min = [-8, 0, -6]                  # the box's corners, in world units
//! max = [8, 30, 6]
//! weight = 1.0                       # fitness lost per cubic unit of the instances'
//!                                    # bounding boxes outside the box (default 1)
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
//! [`Scene::open`] reads a scene naming any generator of a [`Registry`](crate::registry::Registry), with the
//! command line's [`Overrides`]: typed flags, and `key=value` overrides (`--set`) applied
//! before checking.

mod error;
mod evaluate;
mod file;
mod goal;
mod image;
mod loaded;
mod lot;
mod memory;
mod method;
mod metrics;
mod objective;
mod optimizer;
mod resolve;
mod resolver;
mod scorer;
mod scorer_kind;
mod sources;

pub use error::{
    BackendError, DecodeError, ImageError, LotError, SceneError, SetError, ValueError,
};
pub use evaluate::{Backend, BackendChoice, SceneEvaluator};
pub use goal::ObjectiveGoal;
pub use image::{decode_image, read_image};
pub use loaded::Scene;
pub use lot::geojson_outline;
pub use memory::{JSON_BYTES_PER_WORD, MemoryError, MemoryEstimate, MemoryPart, RunShape};
pub use method::{
    Method, MethodJob, MethodSettings, SearchJob, SettingsCause, SettingsKeyError, UnknownMethod,
};
pub use metrics::{CloudDistance, METRIC_COLUMNS, Metrics, SURFACE_SAMPLES, ViewIou};
pub use objective::ObjectiveEvaluator;
pub use optimizer::{OptimizerGoal, Overrides};
pub use scorer::silhouette::SilhouetteGoal;
pub use scorer::volume::{F_SCORE_THRESHOLD, VolumeGoal};
pub use scorer::{AnyCounts, AnyScorer, SceneCounts, SceneScorer, ScorerGoal, ScorerKind};
pub use sources::Sources;
