//! The scene file as written: TOML tables deserialized strictly (unknown keys are
//! errors), before paths are resolved and values checked.

use serde::Deserialize;

use super::scorer::scene_file;
use super::scorer_kind::FormName;

scene_file! {
    /// A whole scene file.
    #[derive(Debug, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub(super) struct SceneFile {
        {
            pub generator: String,
            #[serde(default)]
            pub meshes: std::collections::BTreeMap<String, MeshFile>,
            pub limits: LimitsFile,
            /// `[lot]`: the footprint a building generator builds on.
            pub lot: Option<LotFile>,
            #[serde(default)]
            pub fitness: FitnessFile,
        }
        scorers
        {
            /// `[[objective]]`: the objectives of a multi-objective scene, each read as the
            /// runtime's [`ObjectiveFile`](shapegen_runtime::score::objective::ObjectiveFile)
            /// by the resolver, which names the table at fault.
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
    }
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
