//! The scene file as written: TOML tables deserialized strictly (unknown keys are
//! errors), before paths are resolved and values checked.

use serde::Deserialize;
use shapegen_runtime::score::volume::Fill;

/// A whole scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SceneFile {
    pub generator: String,
    #[serde(default)]
    pub meshes: std::collections::BTreeMap<String, MeshFile>,
    pub limits: LimitsFile,
    /// `[lot]`: the footprint a building generator builds on.
    pub lot: Option<LotFile>,
    #[serde(default)]
    pub fitness: FitnessFile,
    pub volume: Option<VolumeFile>,
    pub silhouette: Option<SilhouetteFile>,
    /// `[[objective]]`: the objectives of a multi-objective scene, each read as the
    /// runtime's [`ObjectiveFile`](shapegen_runtime::score::objective::ObjectiveFile) by
    /// the resolver, which names the table at fault.
    #[serde(default)]
    pub objective: Vec<toml::Table>,
    /// `[selection]`: how a multi-objective scene's objective vectors are ranked.
    pub selection: Option<shapegen_runtime::optimize::multi::Selection>,
    /// `[optimizer]`: kept as a table, checked against the optimizer's own settings.
    #[serde(default)]
    pub optimizer: toml::Table,
    /// `[islands]`: the GA as an island model.
    pub islands: Option<shapegen_runtime::optimize::islands::IslandSettings>,
}

/// An entry of `[meshes]`: a path, or a path with whether to normalize the part.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(super) enum MeshFile {
    /// `name = "path.obj"`: normalized as the original does.
    Path(String),
    /// `name = { path = "path.obj", normalize = false }`.
    Table {
        path: String,
        #[serde(default = "yes")]
        normalize: bool,
    },
}

fn yes() -> bool {
    true
}

/// `[limits]`
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LimitsFile {
    pub min_len: u32,
    pub optimal_len: Option<u32>,
    pub max_len: u32,
    pub max_depth: u32,
}

/// `[fitness]`
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FitnessFile {
    #[serde(default)]
    pub form: FormName,
    #[serde(default)]
    pub length: f64,
    #[serde(default)]
    pub length_from: LengthFrom,
    pub optimum: Option<f64>,
}

/// `fitness.length_from`: the genome length where the length penalty starts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub(super) enum LengthFrom {
    /// `limits.min_len`, as the original implementation's fitness does.
    #[default]
    MinLen,
    /// `limits.optimal_len`, which the scene must then give.
    OptimalLen,
}

/// `fitness.form`
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum FormName {
    /// The original implementation's smoothstep form.
    #[default]
    Smooth,
    /// The paper's weighted sum.
    Weighted,
    /// The intersection over union that runs report, times `good`.
    Iou,
    /// Volumes only: the surface F-score at `volume.fscore_threshold`, times `good`.
    FScore,
}

fn one() -> f64 {
    1.0
}

fn minus_one() -> f64 {
    -1.0
}

/// `[volume]`
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct VolumeFile {
    pub grid: GridFile,
    #[serde(default = "one")]
    pub good: f64,
    #[serde(default = "one")]
    pub bad: f64,
    #[serde(default)]
    pub overlap: f64,
    /// Opt-in distance shaping: the distance in voxels over which an off-target voxel's
    /// cost rises to its full weight.
    pub shaping_radius: Option<f64>,
    /// The `fscore` form's threshold, in world units.
    pub fscore_threshold: Option<f64>,
    #[serde(default)]
    pub target: Vec<VolumeTargetFile>,
}

/// `volume.grid`
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct GridFile {
    pub min: [f32; 3],
    pub max: [f32; 3],
    pub resolution: [u32; 3],
}

/// `[[volume.target]]`
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct VolumeTargetFile {
    pub mesh: String,
    #[serde(default = "one")]
    pub inside: f64,
    #[serde(default = "minus_one")]
    pub outside: f64,
    #[serde(default)]
    pub fill: Fill,
}

/// `[silhouette]`
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SilhouetteFile {
    #[serde(default = "one")]
    pub good: f64,
    #[serde(default = "one")]
    pub bad: f64,
    /// Opt-in distance shaping of every mask target: the distance in pixels over which
    /// an off-target pixel's cost rises to its full weight.
    pub shaping_radius: Option<f32>,
    #[serde(default)]
    pub target: Vec<ImageTargetFile>,
}

/// `[[silhouette.target]]`
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ImageTargetFile {
    pub image: String,
    #[serde(default)]
    pub kind: ImageKind,
    /// Mask images: pixels darker than this grey level are the target, instead of the
    /// original's rule (red channel 0).
    pub threshold: Option<u16>,
    /// Mask images: pixels at least this opaque (alpha 1 to 255) are the target.
    pub alpha: Option<u16>,
    /// Mask images: pixels farther than `tolerance` from this RGB colour are the target.
    pub background: Option<[u16; 3]>,
    /// Mask images with a `background`: the largest RGB distance of a backdrop pixel.
    pub tolerance: Option<u16>,
    /// Mask images: weight of dark pixels. Weight maps: weight of black.
    pub on: Option<f32>,
    /// Mask images: weight of light pixels. Weight maps: weight of white.
    pub off: Option<f32>,
    pub camera: CameraFile,
}

/// `silhouette.target.kind`
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(super) enum ImageKind {
    /// Black and white: black pixels (red channel 0) are the target, or those darker
    /// than a threshold.
    #[default]
    Mask,
    /// Grey levels mapped linearly from `on` (black) to `off` (white).
    Weights,
}

/// `silhouette.target.camera`: an orbit camera or explicit matrices.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CameraFile {
    pub width: u32,
    pub height: u32,
    pub phi: Option<f32>,
    pub theta: Option<f32>,
    pub radius: Option<f32>,
    pub lookat: Option<[f32; 3]>,
    pub fov: Option<f32>,
    pub near: Option<f32>,
    pub far: Option<f32>,
    /// Row-major 4 x 4 view matrix.
    pub view: Option<[[f32; 4]; 4]>,
    /// Row-major 4 x 4 projection matrix.
    pub projection: Option<[[f32; 4]; 4]>,
}

/// `[lot]`: exactly one of `points` and `geojson`, how their numbers are read, and
/// whether the lot is moved to the origin.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LotFile {
    /// The outline's points, `[x, y]` with `y` north, in either orientation.
    pub points: Option<Vec<Vec<f64>>>,
    /// A GeoJSON file, relative to the scene's folder, holding one polygon.
    pub geojson: Option<String>,
    /// How the outline's numbers are read.
    #[serde(default)]
    pub coordinates: Coordinates,
    /// Whether a lot in metres is moved so that the middle of its bounding box is the
    /// origin (one in degrees always is).
    #[serde(default)]
    pub centre: bool,
}

/// How a lot's numbers are read (`[lot] coordinates`).
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq)]
#[serde(rename_all = "lowercase")]
pub(super) enum Coordinates {
    /// Metres (the scene's units) of a local or projected system, `[x, y]` with `y`
    /// north, used as they are.
    #[default]
    Metres,
    /// Longitude and latitude in degrees on WGS 84, as GeoJSON (RFC 7946) writes them:
    /// projected to metres on the plane touching the ellipsoid at the middle of the
    /// lot's bounding box, `x` east and `y` north, that middle at the origin.
    Degrees,
}
