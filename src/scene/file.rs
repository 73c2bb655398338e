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
            /// `[[objective]]`: the objectives of a multi-objective scene, each read as an
            /// [`ObjectiveFile`] by the resolver, which names the table at fault.
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

/// One `[[objective]]` table as written, less its optional `name`: `kind` picks the
/// variant, whose fields are exactly the keys that kind takes (any other is refused, and
/// the message lists the valid ones). The kinds' names are the runtime's
/// [`Objective::name`](shapegen_runtime::score::objective::Objective::name)s.
#[derive(Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub(super) enum ObjectiveFile {
    /// `|top - target|`.
    Height { target: f32 },
    /// Distinct face normals.
    UniqueNormals {
        #[serde(default = "one_degree")]
        tolerance_deg: f32,
    },
    /// How far apart the distinct face normals are.
    NormalSpread {
        #[serde(default = "one_degree")]
        tolerance_deg: f32,
    },
    /// How far the x/z extent leaves `[min, max]`.
    FootprintExcess { min: [f32; 2], max: [f32; 2] },
    /// An image matched by the view from above.
    TopMatch(ProjectionFile),
    /// An image matched by the view from the front.
    FrontMatch(ProjectionFile),
    /// A point cloud approached by the model's surface.
    Chamfer {
        /// The cloud's file (`.xyz`, `.txt` or `.ply`).
        points: String,
        #[serde(default = "chamfer_samples")]
        samples: usize,
    },
    /// The share of the area of the meshes `of` (all when absent) that the meshes
    /// `parts` take, toward `target`.
    AreaShare {
        parts: Vec<String>,
        #[serde(default)]
        of: Option<Vec<String>>,
        target: f32,
    },
    /// The mean pitch of the upward-facing triangles of the meshes `parts`, toward
    /// `target_deg`.
    RoofPitch {
        #[serde(default = "roof_parts")]
        parts: Vec<String>,
        target_deg: f32,
    },
}

/// Default parts of a `roof_pitch` objective: the mesh a building names its roofs.
fn roof_parts() -> Vec<String> {
    vec!["roof".to_owned()]
}

/// Default samples a side of a `chamfer` objective.
fn chamfer_samples() -> usize {
    512
}

/// Default tolerance between normals counted as one, in degrees.
fn one_degree() -> f32 {
    1.0
}

/// The keys of a `top_match` or `front_match` objective.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ProjectionFile {
    /// The target image; black = covered.
    pub image: String,
    /// The view plane's area the image covers: (x, z) from above, (x, y) from the front.
    pub min: [f32; 2],
    pub max: [f32; 2],
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
